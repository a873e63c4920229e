//! Scene validation: every value checked against its allowed range, and the
//! physical parameters resolved (ρA, EI, EA) as MODEL §1–§3 define them.

use super::{ContactSpec, EndTime, IntegratorSpec, Scene, Scheme, Side, SpeedProfile, Support};
use std::collections::HashMap;

use super::Discretization;
use super::Grading;
use super::Motion;
use super::manufactured::{Declared, ReferenceKind};
use crate::error::{Error, Result};

/// Largest mesh accepted: beyond this the run would not fit a sane budget
/// (10⁶ elements is 2·10⁶ unknowns; banded storage ≈ 0.2 GB).
pub const MAX_ELEMENTS: usize = 1_000_000;

/// Largest number of steps accepted (10⁹ steps would take hours even at N = 4).
pub const MAX_STEPS: usize = 1_000_000_000;

/// Relative slack of the step count: a run has floor(t_end/Δt · (1 + slack))
/// steps, so an end time that is a whole number of steps up to the round-off
/// of the division (0.15 / 1e-4 = 1499.9999999999998) gets all its steps.
/// A few ulps: any more would add a step to an end time that is really short
/// of it.
pub const STEP_COUNT_SLACK: f64 = 4.0 * f64::EPSILON;

/// The beam's resolved properties (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct BeamProps {
    /// Span L, m.
    pub length: f64,
    /// Mass per length ρA, kg/m.
    pub rho_a: f64,
    /// Bending stiffness EI, N·m² (0 = taut string, MODEL §6).
    pub ei: f64,
    /// Axial stiffness EA, N, when `youngs_modulus` and `area` are given.
    pub ea: Option<f64>,
    /// Tension T, N.
    pub tension: f64,
    /// Support at x = 0.
    pub left: Support,
    /// Support at x = L.
    pub right: Support,
    /// Distributed load p, N/m (self-weight −ρA g when asked for, else 0).
    pub distributed_load: f64,
}

impl BeamProps {
    /// String wave speed c = sqrt(T/ρA), m/s (MODEL §1).
    pub fn wave_speed(&self) -> f64 {
        (self.tension / self.rho_a).sqrt()
    }

    /// Beam mass M = ρA L, kg.
    pub fn total_mass(&self) -> f64 {
        self.rho_a * self.length
    }

    /// True when EI = 0: C0 string elements, one dof per node (MODEL §6).
    pub fn is_string(&self) -> bool {
        self.ei == 0.0
    }
}

/// What a carrier is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CarrierKind {
    /// A mass on a spring (k = 0: a riding mass), MODEL §2.
    MassSpring {
        /// m, kg.
        mass: f64,
        /// k, N/m.
        stiffness: f64,
        /// c_s, N·s/m.
        damping: f64,
        /// δ0, m.
        preload: f64,
    },
    /// A constant force F, N, pressing into the beam; no mass dof.
    Force {
        /// F, N.
        force: f64,
    },
}

/// A carrier's resolved properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CarrierProps {
    /// Mass–spring or force.
    pub kind: CarrierKind,
    /// Side sign s (+1 below, −1 above).
    pub side: Side,
    /// Its motion along the beam.
    pub motion: Motion,
}

/// A validated scene: physical parameters ready to build a model from.
#[derive(Debug, Clone)]
pub struct Resolved {
    /// The scene as given (after overrides).
    pub scene: Scene,
    /// Beam properties.
    pub beam: BeamProps,
    /// Carriers, in scene order.
    pub carriers: Vec<CarrierProps>,
    /// Number of elements N (`mesh.elements`).
    pub elements: usize,
    /// The space discretization (`mesh.kind`, MODEL §9.2).
    pub discretization: Discretization,
    /// The mesh grading (`mesh.grading`).
    pub grading: Grading,
    /// Contact settings.
    pub contact: ContactSpec,
    /// `[integrator]` as given.
    pub integrator: IntegratorSpec,
    /// The time integrator with its parameters resolved (MODEL §9.1).
    pub scheme: Scheme,
    /// Gravity on carrier masses, m/s².
    pub g: f64,
    /// Time step Δt, s.
    pub dt: f64,
    /// Number of steps.
    pub steps: usize,
    /// The run's end time `time.end`, s: as given, or when the first moving
    /// carrier leaves the beam (the run stops at the last whole step before it).
    pub t_end: f64,
    /// Probes: (name, x in m).
    pub probes: Vec<(String, f64)>,
    /// The history records row 0, every `record_every`-th step and the last
    /// step (`output.record_every`, ≥ 1); statistics use every step.
    pub record_every: usize,
    /// The manufactured solution of a scene with `[manufactured]` (MODEL §11).
    pub manufactured: Option<crate::manufactured::Manufactured>,
    /// The reference the scene declares (`[reference]`, or the manufactured
    /// solution), its assumptions checked.
    pub reference: Declared,
}

impl Resolved {
    /// The length the space discretization resolves, m: h = L/N on a
    /// uniform mesh, the longest element of a graded one (the coarsest
    /// place), L/J for a `galerkin` basis of J modes (the half-wavelength
    /// of its last mode), and the larger of the mesh's and L/J for `modal`.
    /// Resolution checks and the contact-loss support zone use it.
    pub fn resolution(&self) -> f64 {
        let l = self.beam.length;
        let mesh = || match self.grading {
            Grading::Uniform => l / self.elements as f64,
            g => crate::model::mesh::Mesh::new(l, self.elements, g)
                .map_or(l / self.elements as f64, |m| m.h_max()),
        };
        match self.discretization {
            Discretization::Hermite => mesh(),
            Discretization::Galerkin { modes } => l / modes as f64,
            Discretization::Modal { modes } => mesh().max(l / modes as f64),
        }
    }

    /// The unknowns of the space discretization's FE mesh (before a modal
    /// truncation): the most modes a `modal` basis can take.
    pub fn beam_unknowns(&self) -> usize {
        super::discretization::fe_unknowns(&self.beam, self.elements)
    }

    /// The memory the run is estimated to need (history, model, a modal
    /// basis's eigenproblem) and the size of its `history.csv`: what
    /// validation checks against the budgets and what a run reserves from
    /// the process's budget while it runs ([`crate::budget`]).
    pub fn memory_estimate(&self) -> super::memory::MemoryEstimate {
        let (per_node, half_band) = if self.beam.is_string() {
            (1, 1)
        } else {
            (2, 3)
        };
        let masses = self
            .carriers
            .iter()
            .filter(|c| matches!(c.kind, CarrierKind::MassSpring { .. }))
            .count();
        let mut need = super::memory::estimate(
            self.steps,
            self.record_every,
            self.elements,
            per_node,
            half_band,
            self.carriers.len(),
            masses,
            self.probes.len(),
        );
        if let Discretization::Modal { modes } = self.discretization {
            need.model = need.model.saturating_add(super::memory::modal_bytes(
                super::discretization::fe_unknowns(&self.beam, self.elements),
                modes,
            ));
        }
        need
    }

    /// Rows the run's history will hold.
    pub fn history_rows(&self) -> usize {
        super::memory::history_rows(self.steps, self.record_every)
    }

    /// Refuse a scene that records only every K-th step (K > 1), for a study
    /// (`what`) that reads the history step by step.
    pub fn require_every_step(&self, what: &str) -> Result<()> {
        if self.record_every == 1 {
            Ok(())
        } else {
            Err(Error::invalid(
                "output.record_every",
                self.record_every,
                format!(
                    "{what} reads the history at every step: must be 1 (leave out [output] record_every)"
                ),
            ))
        }
    }
}

fn positive(field: &str, v: f64, unit: &str) -> Result<f64> {
    if !v.is_finite() {
        Err(Error::invalid(
            field,
            v,
            format!("must be a finite number > 0 ({unit})"),
        ))
    } else if v > 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(field, v, format!("must be > 0 ({unit})")))
    }
}

fn non_negative(field: &str, v: f64, unit: &str) -> Result<f64> {
    if !v.is_finite() {
        Err(Error::invalid(
            field,
            v,
            format!("must be a finite number ≥ 0 ({unit})"),
        ))
    } else if v >= 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(field, v, format!("must be ≥ 0 ({unit})")))
    }
}

impl Scene {
    /// Check every value and resolve the physical parameters.
    pub fn validate(&self) -> Result<Resolved> {
        let beam = self.resolve_beam()?;
        let l = beam.length;

        let elements = self.mesh.elements;
        if elements == 0 || elements > MAX_ELEMENTS {
            return Err(Error::invalid(
                "mesh.elements",
                elements,
                format!("must be in 1 ..= {MAX_ELEMENTS}"),
            ));
        }
        let (discretization, grading) = super::discretization::resolve(&self.mesh, &beam)?;

        if self.carriers.is_empty() {
            return Err(Error::invalid(
                "carrier",
                "[]",
                "at least one [[carrier]] is required",
            ));
        }
        let carriers = self
            .carriers
            .iter()
            .enumerate()
            .map(|(i, c)| resolve_carrier(i, c, l))
            .collect::<Result<Vec<_>>>()?;

        let scheme = self.integrator.scheme()?;
        let g = non_negative("gravity.g", self.gravity.g, "m/s²")?;
        validate_contact(&self.contact)?;
        // the method's own check of the contact settings and basis
        self.integrator
            .method_info()?
            .accepts(&self.contact, discretization)?;

        let dt = positive("time.step", self.time.step, "s")?;
        let t_end = match self.time.end {
            EndTime::Seconds(t) => positive("time.end", t, "s")?,
            EndTime::CarrierLeaves => carriers
                .iter()
                .filter_map(|c| c.motion.time_to_leave(l))
                .fold(None, |acc: Option<f64>, t| {
                    Some(acc.map_or(t, |a| a.min(t)))
                })
                .ok_or_else(|| {
                    Error::invalid(
                        "time.end",
                        "\"carrier_leaves\"",
                        "no carrier moves, so none leaves the beam: give an end time in seconds",
                    )
                })?,
        };
        // floor, with a little slack so that an end time that is a whole number
        // of steps up to round-off (0.15 / 1e-4) gets all its steps.
        let steps_f = (t_end / dt * (1.0 + STEP_COUNT_SLACK)).floor();
        if steps_f < 1.0 {
            return Err(match self.time.end {
                EndTime::Seconds(_) => Error::invalid(
                    "time.end",
                    format!("{t_end} s"),
                    format!("gives no step with time.step = {dt} s: must be ≥ time.step"),
                ),
                EndTime::CarrierLeaves => Error::invalid(
                    "time.end",
                    "\"carrier_leaves\"",
                    format!(
                        "a carrier leaves the beam after {t_end:e} s, before the first step (time.step = {dt} s): start it further from the end it moves to, or give an end time in seconds"
                    ),
                ),
            });
        }
        if let EndTime::Seconds(t) = self.time.end {
            // a carrier past the end of the beam is outside the model: refuse
            // rather than hold its contact point at the support
            let leaves = carriers
                .iter()
                .enumerate()
                .filter_map(|(i, c)| c.motion.time_to_leave(l).map(|tl| (i, tl)))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((i, tl)) = leaves
                && t > tl * (1.0 + 4.0 * f64::EPSILON)
            {
                return Err(Error::invalid(
                    "time.end",
                    format!("{t} s"),
                    format!(
                        "carrier {i} leaves the beam at t = {tl:.6} s: must be ≤ that, or \"carrier_leaves\""
                    ),
                ));
            }
        }
        if steps_f > MAX_STEPS as f64 {
            return Err(Error::invalid(
                "time.end",
                format!("{t_end} s"),
                format!("gives {steps_f:e} steps with time.step = {dt} s: at most {MAX_STEPS:e}"),
            ));
        }

        let mut probes = Vec::with_capacity(self.probes.len());
        let mut seen: HashMap<&str, usize> = HashMap::with_capacity(self.probes.len());
        for (i, p) in self.probes.iter().enumerate() {
            let field = format!("probe.{i}.x");
            let x = p.x;
            if !(0.0..=l).contains(&x) {
                return Err(Error::invalid(
                    field,
                    x,
                    format!("must be on the beam, in [0, {l}] m"),
                ));
            }
            let ok = !p.name.is_empty()
                && p.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            if !ok {
                return Err(Error::invalid(
                    format!("probe.{i}.name"),
                    format!("{:?}", p.name),
                    "must be non-empty and use only letters, digits, `_` and `-`",
                ));
            }
            let column = |n: &str| {
                ["t", "x_m", "beam_w", "mass_q", "gap", "force", "in_contact"]
                    .iter()
                    .any(|c| {
                        n == *c
                            || n.strip_prefix(c).is_some_and(|r| {
                                r.starts_with('_') && r[1..].parse::<usize>().is_ok()
                            })
                    })
            };
            if column(&p.name) {
                return Err(Error::invalid(
                    format!("probe.{i}.name"),
                    format!("{:?}", p.name),
                    "must differ from the history.csv columns (t, x_m, beam_w, mass_q, gap, force, in_contact and their _0, _1, … forms)",
                ));
            }
            // a set, not a scan of the probes so far: 10⁵ probes are 10⁵
            // look-ups, not 10¹⁰ comparisons
            if let Some(first) = seen.insert(p.name.as_str(), i) {
                return Err(Error::invalid(
                    format!("probe.{i}.name"),
                    format!("{:?}", p.name),
                    format!("must be unique among probes: probe.{first}.name has it too"),
                ));
            }
            probes.push((p.name.clone(), x));
        }

        if self.output.record_every == 0 {
            return Err(Error::invalid(
                "output.record_every",
                0,
                "must be an integer ≥ 1 (record every K-th step; 1 = every step)",
            ));
        }
        let record_every = usize::try_from(self.output.record_every).unwrap_or(usize::MAX);
        let steps = steps_f as usize;
        let manufactured = match &self.manufactured {
            None => None,
            Some(spec) => Some(crate::manufactured::Manufactured::new(
                spec,
                crate::manufactured::Setting {
                    beam: &beam,
                    carriers: &carriers,
                    contact: self.contact.kind,
                    g,
                    t_end,
                    steps,
                },
            )?),
        };
        let reference = self.declared_reference(&beam, &carriers)?;

        let resolved = Resolved {
            manufactured,
            reference,
            scene: self.clone(),
            beam,
            carriers,
            elements,
            discretization,
            grading,
            contact: self.contact.clone(),
            integrator: self.integrator.clone(),
            scheme,
            g,
            dt,
            steps,
            t_end,
            probes,
            record_every,
        };
        super::memory::check_budget(
            &resolved.memory_estimate(),
            steps,
            record_every,
            elements,
            resolved.carriers.len(),
            resolved.probes.len(),
        )?;
        Ok(resolved)
    }

    /// The reference the scene declares, its assumptions checked (MODEL §8;
    /// `docs/scene.md`, `[reference]`): a declaration that does not fit the
    /// scene is refused naming `reference.kind` and the key that breaks it.
    fn declared_reference(&self, beam: &BeamProps, carriers: &[CarrierProps]) -> Result<Declared> {
        if self.manufactured.is_some() {
            if let Some(r) = &self.reference {
                return Err(Error::invalid(
                    "reference.kind",
                    format!("\"{}\"", r.kind.name()),
                    "must be left out with [manufactured]: the manufactured solution is the scene's reference",
                ));
            }
            return Ok(Declared::Manufactured);
        }
        let Some(spec) = &self.reference else {
            return Ok(Declared::Richardson);
        };
        let kind = spec.kind;
        let refuse = |key: &str, value: String, why: &str| {
            Err(Error::invalid(
                "reference.kind",
                format!("\"{}\"", kind.name()),
                format!("needs {why}, but {key} = {value}"),
            ))
        };
        if spec.modes.is_some() && kind != ReferenceKind::RidingMassGalerkin {
            return Err(Error::invalid(
                "reference.modes",
                spec.modes.unwrap_or(0),
                "is read only by kind = \"riding_mass_galerkin\": leave it out",
            ));
        }
        let pinned = beam.left == Support::Pinned && beam.right == Support::Pinned;
        let supports = || format!("{:?}–{:?}", beam.left, beam.right).to_lowercase();
        match kind {
            ReferenceKind::Richardson => Ok(Declared::Richardson),
            ReferenceKind::MovingForceSeries | ReferenceKind::RidingMassGalerkin => {
                if carriers.len() != 1 {
                    return refuse(
                        "carrier",
                        format!("{} carriers", carriers.len()),
                        "exactly one carrier",
                    );
                }
                let c = &carriers[0];
                let SpeedProfile::Constant { value: speed } = c.motion.profile else {
                    return refuse(
                        "carrier.speed.profile",
                        "\"smooth_ramp\"".into(),
                        "a constant speed",
                    );
                };
                if !pinned {
                    return refuse("beam.left/right", supports(), "pinned–pinned supports");
                }
                if beam.distributed_load != 0.0 {
                    return refuse(
                        "gravity.beam_self_weight",
                        "true".into(),
                        "no distributed load",
                    );
                }
                if kind == ReferenceKind::MovingForceSeries {
                    if !matches!(c.kind, CarrierKind::Force { .. }) {
                        return refuse(
                            "carrier.mass",
                            "given".into(),
                            "a moving force (carrier.force)",
                        );
                    }
                    if speed <= 0.0 {
                        return refuse("carrier.speed.value", speed.to_string(), "a speed > 0");
                    }
                    if c.motion.start != 0.0 {
                        return refuse("carrier.start", c.motion.start.to_string(), "start = 0");
                    }
                    return Ok(Declared::MovingForceSeries);
                }
                let CarrierKind::MassSpring {
                    stiffness, damping, ..
                } = c.kind
                else {
                    return refuse("carrier.force", "given".into(), "a mass carrier");
                };
                if stiffness != 0.0 {
                    return refuse(
                        "carrier.stiffness",
                        stiffness.to_string(),
                        "a riding mass (stiffness = 0)",
                    );
                }
                if damping != 0.0 {
                    return refuse("carrier.damping", damping.to_string(), "no dashpot");
                }
                if self.contact.kind != super::ContactKind::Bilateral {
                    return refuse(
                        "contact.kind",
                        "\"unilateral\"".into(),
                        "a bilateral contact",
                    );
                }
                if beam.is_string() {
                    return refuse(
                        "beam.bending_stiffness",
                        "0".into(),
                        "EI > 0 (a string's curvature under a mass has no limit)",
                    );
                }
                if let Some(j) = spec.modes
                    && !(1..=crate::analytic::MAX_MODES * 4).contains(&j)
                {
                    return Err(Error::invalid(
                        "reference.modes",
                        j,
                        format!("must be in 1 ..= {}", crate::analytic::MAX_MODES * 4),
                    ));
                }
                Ok(Declared::RidingMassGalerkin { modes: spec.modes })
            }
            ReferenceKind::StandingForceModes => {
                for (i, c) in carriers.iter().enumerate() {
                    if !matches!(c.kind, CarrierKind::Force { .. }) {
                        return refuse(
                            &format!("carrier.{i}.mass"),
                            "given".into(),
                            "standing forces only (carrier.force)",
                        );
                    }
                    if !c.motion.is_stationary() {
                        return refuse(
                            &format!("carrier.{i}.speed"),
                            c.motion.profile.cruise_speed().to_string(),
                            "standing forces (speed 0)",
                        );
                    }
                }
                Ok(Declared::StandingForceModes)
            }
        }
    }

    fn resolve_beam(&self) -> Result<BeamProps> {
        let b = &self.beam;
        let length = positive("beam.length", b.length, "m")?;
        let tension = non_negative("beam.tension", b.tension, "N")?;
        let opt = |name: &str, v: Option<f64>, strict: bool| -> Result<Option<f64>> {
            let field = format!("beam.{name}");
            match v {
                None => Ok(None),
                Some(x) if strict => positive(&field, x, unit_of(name)).map(Some),
                Some(x) => non_negative(&field, x, unit_of(name)).map(Some),
            }
        };
        let density = opt("density", b.density, true)?;
        let area = opt("area", b.area, true)?;
        let youngs = opt("youngs_modulus", b.youngs_modulus, false)?;
        let second = opt("second_moment", b.second_moment, false)?;
        let mpl = opt("mass_per_length", b.mass_per_length, true)?;
        let bend = opt("bending_stiffness", b.bending_stiffness, false)?;

        let rho_a = match (mpl, density, area) {
            (Some(m), None, _) => m,
            (None, Some(rho), Some(a)) => rho * a,
            (Some(m), Some(_), _) => {
                return Err(Error::invalid(
                    "beam.mass_per_length",
                    m,
                    "give either mass_per_length or density and area, not both",
                ));
            }
            (None, Some(rho), None) => {
                return Err(Error::invalid(
                    "beam.density",
                    rho,
                    "needs beam.area too (or give mass_per_length)",
                ));
            }
            (None, None, _) => {
                return Err(Error::invalid(
                    "beam.mass_per_length",
                    "(missing)",
                    "give mass_per_length (kg/m) or density (kg/m³) and area (m²)",
                ));
            }
        };
        let ei = match (bend, youngs, second) {
            (Some(ei), None, None) => ei,
            (None, Some(e), Some(i)) => e * i,
            (Some(ei), _, _) => {
                return Err(Error::invalid(
                    "beam.bending_stiffness",
                    ei,
                    "give either bending_stiffness or youngs_modulus and second_moment, not both",
                ));
            }
            (None, Some(e), None) => {
                return Err(Error::invalid(
                    "beam.youngs_modulus",
                    e,
                    "needs beam.second_moment too (or give bending_stiffness)",
                ));
            }
            (None, None, _) => {
                return Err(Error::invalid(
                    "beam.bending_stiffness",
                    "(missing)",
                    "give bending_stiffness (N·m², 0 for a string) or youngs_modulus (Pa) and second_moment (m⁴)",
                ));
            }
        };
        let ea = match (youngs, area) {
            (Some(e), Some(a)) => Some(e * a),
            _ => None,
        };
        if ei == 0.0 {
            for (field, s) in [("beam.left", b.left), ("beam.right", b.right)] {
                if s != Support::Pinned {
                    return Err(Error::invalid(
                        field,
                        format!("{s:?}").to_lowercase(),
                        "a string (EI = 0) allows only `pinned` supports (v = 0); clamped and free need bending stiffness",
                    ));
                }
            }
            if tension == 0.0 {
                return Err(Error::invalid(
                    "beam.tension",
                    tension,
                    "a string (EI = 0) needs tension > 0 (N), else it has no stiffness",
                ));
            }
        }
        let g = non_negative("gravity.g", self.gravity.g, "m/s²")?;
        Ok(BeamProps {
            length,
            rho_a,
            ei,
            ea,
            tension,
            left: b.left,
            right: b.right,
            distributed_load: if self.gravity.beam_self_weight {
                -rho_a * g
            } else {
                0.0
            },
        })
    }
}

fn unit_of(name: &str) -> &'static str {
    match name {
        "density" => "kg/m³",
        "area" => "m²",
        "youngs_modulus" => "Pa",
        "second_moment" => "m⁴",
        "mass_per_length" => "kg/m",
        "bending_stiffness" => "N·m²",
        _ => "",
    }
}

fn resolve_carrier(i: usize, c: &super::CarrierSpec, l: f64) -> Result<CarrierProps> {
    let f = |name: &str| format!("carrier.{i}.{name}");
    let start = c.start;
    if !(0.0..=l).contains(&start) {
        return Err(Error::invalid(
            f("start"),
            start,
            format!("must be on the beam, in [0, {l}] m"),
        ));
    }
    match c.speed {
        SpeedProfile::Constant { value } => {
            non_negative(&f("speed.value"), value, "m/s")?;
        }
        SpeedProfile::SmoothRamp { cruise } => {
            positive(&f("speed.cruise"), cruise, "m/s")?;
        }
    }
    let kind = if let Some(force) = c.force {
        for (name, v) in [
            ("mass", c.mass),
            ("stiffness", c.stiffness),
            ("damping", c.damping),
            ("preload", c.preload),
        ] {
            if let Some(v) = v {
                return Err(Error::invalid(
                    f(name),
                    v,
                    "a moving force (`force` given) has no mass, spring, damping or preload: remove it or remove `force`",
                ));
            }
        }
        CarrierKind::Force {
            force: non_negative(&f("force"), force, "N")?,
        }
    } else {
        let mass = c.mass.ok_or_else(|| {
            Error::invalid(
                f("mass"),
                "(missing)",
                "a mass–spring carrier needs mass > 0 (kg); for a massless load give `force`",
            )
        })?;
        let mass = positive(&f("mass"), mass, "kg; for a massless load give `force`")?;
        let stiffness = c.stiffness.ok_or_else(|| {
            Error::invalid(
                f("stiffness"),
                "(missing)",
                "must be ≥ 0 (N/m); 0 makes a riding mass",
            )
        })?;
        CarrierKind::MassSpring {
            mass,
            stiffness: non_negative(&f("stiffness"), stiffness, "N/m")?,
            damping: non_negative(&f("damping"), c.damping.unwrap_or(0.0), "N·s/m")?,
            preload: non_negative(&f("preload"), c.preload.unwrap_or(0.0), "m")?,
        }
    };
    Ok(CarrierProps {
        kind,
        side: c.side,
        motion: Motion::new(start, c.speed, l),
    })
}

/// Default penalty stiffness relative to the step's contact stiffness 1/W:
/// the penalty force is then 1000/1001 of the Lagrange force per step.
pub const DEFAULT_PENALTY_RELATIVE: f64 = 1e3;

/// Check `[contact]`: penalty stiffness, QP tolerances, restitution.
pub(crate) fn validate_contact(c: &super::ContactSpec) -> Result<()> {
    let p = &c.penalty;
    if let (Some(k), Some(_)) = (p.stiffness, p.relative) {
        return Err(Error::invalid(
            "contact.penalty.stiffness",
            k,
            "give either stiffness (N/m) or relative (× 1/W), not both",
        ));
    }
    if let Some(k) = p.stiffness {
        positive("contact.penalty.stiffness", k, "N/m")?;
    }
    if let Some(r) = p.relative {
        positive("contact.penalty.relative", r, "dimensionless, × 1/W")?;
    }
    let q = &c.complementarity;
    for (name, v) in [
        ("tol_gap_abs", q.tol_gap_abs),
        ("tol_gap_rel", q.tol_gap_rel),
        ("tol_feas", q.tol_feas),
    ] {
        let field = format!("contact.complementarity.{name}");
        positive(&field, v, "dimensionless")?;
        if v >= 1e-2 {
            return Err(Error::invalid(
                field,
                v,
                "must be in (0, 1e-2): a looser QP is not a contact solve",
            ));
        }
    }
    if q.max_iter == 0 {
        return Err(Error::invalid(
            "contact.complementarity.max_iter",
            0,
            "must be ≥ 1",
        ));
    }
    let e = c.impact.restitution;
    if !(0.0..=1.0).contains(&e) {
        return Err(Error::invalid(
            "contact.impact.restitution",
            e,
            "must be in [0, 1]",
        ));
    }
    Ok(())
}
