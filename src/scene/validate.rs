//! The scene's own checks: every value against its allowed range, and the
//! physical parameters resolved (ρA, EI, EA) as MODEL §1–§3 define them,
//! as plain property structs. Checks that need the model, a reference or
//! the memory plan are the resolve layer's (`crate::resolve`), which calls
//! these in order.

use super::beam::Support;
use super::carrier::CarrierSpec;
use super::contact::ContactSpec;
use super::messenger::Messenger;
use super::scene_file::Scene;
use super::speed::SpeedProfile;
use super::time::EndTime;
use std::collections::HashMap;

use super::attachment::resolve_attachments;
use super::external_force::ForceSeries;
use super::motion::Motion;
use super::props::{BeamProps, CarrierKind, CarrierProps, TimeProps};
use super::range::{non_negative, positive};
use crate::error::{Error, Result};

/// Largest mesh accepted: beyond this the run would not fit a sane budget
/// (10⁶ elements is 2·10⁶ unknowns; banded storage ≈ 0.2 GB).
pub(crate) const MAX_ELEMENTS: usize = 1_000_000;

/// Largest number of steps accepted (10⁹ steps would take hours even at N = 4).
pub const MAX_STEPS: usize = 1_000_000_000;

/// Relative slack of the step count: a run has floor(t_end/Δt · (1 + slack))
/// steps, so an end time that is a whole number of steps up to the round-off
/// of the division (0.15 / 1e-4 = 1499.9999999999998) gets all its steps.
/// A few ulps: any more would add a step to an end time that is really short
/// of it.
pub(crate) const STEP_COUNT_SLACK: f64 = 4.0 * f64::EPSILON;

impl Scene {
    /// `mesh.elements` in its range (1 ..= `MAX_ELEMENTS`).
    pub fn elements(&self) -> Result<usize> {
        let elements = self.mesh.elements;
        if elements == 0 || elements > MAX_ELEMENTS {
            return Err(Error::invalid(
                "mesh.elements",
                elements,
                format!("must be in 1 ..= {MAX_ELEMENTS}"),
            ));
        }
        Ok(elements)
    }

    /// The carriers, checked and resolved (at least one; each on the beam
    /// of span `l`, m).
    pub fn resolve_carriers(&self, l: f64) -> Result<Vec<CarrierProps>> {
        if self.carriers.is_empty() {
            return Err(Error::invalid(
                "carrier",
                "[]",
                "at least one [[carrier]] is required",
            ));
        }
        self.carriers
            .iter()
            .enumerate()
            .map(|(i, c)| resolve_carrier(i, c, l))
            .collect::<Result<Vec<_>>>()
    }

    /// `gravity.g`, m/s² (≥ 0).
    pub fn gravity_g(&self) -> Result<f64> {
        non_negative("gravity.g", self.gravity.g, "m/s²")
    }

    /// `[time]` checked against the `carriers` on the beam of span `l`, m:
    /// the step, the end time (`"carrier_leaves"` resolved) and the number
    /// of steps.
    pub fn resolve_time(&self, carriers: &[CarrierProps], l: f64) -> Result<TimeProps> {
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

        Ok(TimeProps {
            dt,
            t_end,
            steps: steps_f as usize,
        })
    }

    /// `[[probe]]`: (name, x in m) on the beam of span `l`, m, each name
    /// unique and apart from the history's own columns.
    pub fn resolve_probes(&self, l: f64) -> Result<Vec<(String, f64)>> {
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

        Ok(probes)
    }

    /// `output.record_every` (≥ 1).
    pub fn record_every(&self) -> Result<usize> {
        if self.output.record_every == 0 {
            return Err(Error::invalid(
                "output.record_every",
                0,
                "must be an integer ≥ 1 (record every K-th step; 1 = every step)",
            ));
        }
        Ok(usize::try_from(self.output.record_every).unwrap_or(usize::MAX))
    }

    /// `[beam]` checked and resolved: ρA, EI, EA from whichever keys are
    /// given (MODEL §1), supports allowed for a string, the self-weight load.
    pub fn resolve_beam(&self) -> Result<BeamProps> {
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
            attachments: resolve_attachments(&self.attachments, length, false)?,
            messenger: self.resolve_messenger(ei == 0.0, length, g)?,
        })
    }
}

impl Scene {
    /// `[messenger]` resolved, with the scene's `[[attachment]] wire =
    /// "messenger"` after its elastic supports (eq. E1); such an
    /// attachment without a messenger is refused.
    fn resolve_messenger(&self, is_string: bool, length: f64, g: f64) -> Result<Option<Messenger>> {
        let Some(spec) = &self.messenger else {
            if let Some(i) = self.attachments.iter().position(|a| a.on_messenger()) {
                return Err(Error::invalid(
                    format!("attachment.{i}.wire"),
                    "\"messenger\"",
                    "needs a [messenger] section: use wire = \"contact\" (the default)",
                ));
            }
            return Ok(None);
        };
        let mut m = spec.resolve(is_string, length, g, self.gravity.beam_self_weight)?;
        m.attachments
            .extend(resolve_attachments(&self.attachments, length, true)?);
        Ok(Some(m))
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

/// A tabulated speed profile's knots: at least two, as many speeds as
/// times, times finite from 0 and strictly rising, speeds finite and ≥ 0.
/// (That they reach the run's end is checked once the end is known,
/// [`check_speed_tables_cover`].)
fn check_speed_table(i: usize, time: &[f64], speed: &[f64]) -> Result<()> {
    let f = |name: &str| format!("carrier.{i}.speed.{name}");
    if time.len() < 2 {
        return Err(Error::invalid(
            f("time"),
            format!("{} knots", time.len()),
            "must hold at least 2 knot times (V is linear between knots)",
        ));
    }
    if speed.len() != time.len() {
        return Err(Error::invalid(
            f("speed"),
            format!("{} values", speed.len()),
            format!(
                "must hold one speed per knot time: {} (as speed.time)",
                time.len()
            ),
        ));
    }
    if time[0] != 0.0 {
        return Err(Error::invalid(
            f("time.0"),
            time[0],
            "must be 0 s (the table starts with the run)",
        ));
    }
    for k in 1..time.len() {
        if !(time[k].is_finite() && time[k] > time[k - 1]) {
            return Err(Error::invalid(
                f(&format!("time.{k}")),
                time[k],
                format!(
                    "must be finite and > the knot before it ({} s): times rise strictly",
                    time[k - 1]
                ),
            ));
        }
    }
    for (k, &v) in speed.iter().enumerate() {
        non_negative(&f(&format!("speed.{k}")), v, "m/s")?;
    }
    Ok(())
}

/// Every tabulated speed profile reaches the run's end `t_end` (s): past its
/// last knot a table says nothing.
pub(crate) fn check_speed_tables_cover(carriers: &[CarrierProps], t_end: f64) -> Result<()> {
    for (i, c) in carriers.iter().enumerate() {
        if let SpeedProfile::Table { time, .. } = &c.motion.profile {
            let last = time[time.len() - 1];
            if last < t_end {
                return Err(Error::invalid(
                    format!("carrier.{i}.speed.time.{}", time.len() - 1),
                    last,
                    format!(
                        "the table must reach the run's end, {t_end} s: add knots up to it (or end the run earlier with time.end)"
                    ),
                ));
            }
        }
    }
    Ok(())
}

fn resolve_carrier(i: usize, c: &CarrierSpec, l: f64) -> Result<CarrierProps> {
    let f = |name: &str| format!("carrier.{i}.{name}");
    let start = c.start;
    if !(0.0..=l).contains(&start) {
        return Err(Error::invalid(
            f("start"),
            start,
            format!("must be on the beam, in [0, {l}] m"),
        ));
    }
    match &c.speed {
        SpeedProfile::Constant { value } => {
            non_negative(&f("speed.value"), *value, "m/s")?;
        }
        SpeedProfile::SmoothRamp { cruise } => {
            positive(&f("speed.cruise"), *cruise, "m/s")?;
            // the ramp over L/5 takes 2L/(5 V0) (MODEL §3): a cruise so slow
            // that this overflows leaves the carrier's position 0 × ∞, NaN
            // (2L/5 formed as 0.4 L: a length near the largest number is
            // the length's own fault, named by its own check, not the speed's)
            let ramp = 0.4 * l / cruise;
            if !ramp.is_finite() {
                let least = 0.4 * l / f64::MAX;
                return Err(Error::invalid(
                    f("speed.cruise"),
                    *cruise,
                    format!(
                        "is too slow: the smooth ramp over L/5 = {} m would take 2L/(5 V0) s, more than a number holds (m/s; give V0 > {least:.3e} m/s, or profile = \"constant\" with value = 0 for a carrier that stands)",
                        l / 5.0
                    ),
                ));
            }
        }
        SpeedProfile::Table { time, speed } => check_speed_table(i, time, speed)?,
    }
    let chain = super::pantograph::resolve_chain(i, c)?;
    let kind = if let Some(ch) = chain {
        // the head's mass, spring and dashpot; the chain is in `chain`
        CarrierKind::MassSpring {
            mass: ch.masses[0],
            stiffness: ch.stiffnesses[0],
            damping: ch.dampings[0],
            preload: 0.0,
        }
    } else if let Some(force) = c.force {
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
        chain,
        side: c.side,
        motion: Motion::new(start, c.speed.clone(), l),
    })
}

/// Default penalty stiffness relative to the step's contact stiffness 1/W:
/// the penalty force is then 1000/1001 of the Lagrange force per step.
pub(crate) const DEFAULT_PENALTY_RELATIVE: f64 = 1e3;

/// Check `[contact]`: penalty stiffness, QP tolerances, restitution.
pub(crate) fn validate_contact(c: &ContactSpec) -> Result<()> {
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
    if p.physical && p.stiffness.is_none() {
        return Err(Error::invalid(
            "contact.penalty.physical",
            "true",
            "a physical contact stiffness is given in N/m (contact.penalty.stiffness); a relative κ follows the step's 1/W and is no property of the contact",
        ));
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

impl Scene {
    /// Each carrier's external force series (scene order; `None`: none),
    /// checked against the resolved `carriers` (mass–spring only) and the
    /// run's end time `t_end`, s.
    pub fn resolve_external_forces(
        &self,
        carriers: &[CarrierProps],
        t_end: f64,
    ) -> Result<Vec<Option<ForceSeries>>> {
        self.carriers
            .iter()
            .zip(carriers)
            .enumerate()
            .map(|(i, (c, p))| {
                let Some(spec) = &c.external_force else {
                    return Ok(None);
                };
                if let CarrierKind::Force { force } = p.kind {
                    return Err(Error::invalid(
                        format!("carrier.{i}.external_force"),
                        format!("a series on a moving force (force = {force} N)"),
                        "is for mass–spring carriers only: a moving force has no mass to act on; vary its `force` instead",
                    ));
                }
                // the mass it acts on: any of a pantograph's, a single one's only
                let n = p.chain.map_or(1, |ch| ch.n);
                if let Some(mass) = spec.mass.filter(|&m| m >= n) {
                    let allowed = if n == 1 {
                        "must be 0 (or absent): a single mass–spring carrier has one mass".to_string()
                    } else {
                        format!(
                            "must be a mass index 0 (head) ..= {} (frame) of the {n} `masses`",
                            n - 1
                        )
                    };
                    return Err(Error::invalid(
                        format!("carrier.{i}.external_force.mass"),
                        mass,
                        allowed,
                    ));
                }
                ForceSeries::new(i, spec, t_end).map(Some)
            })
            .collect()
    }
}

/// Refuse a multi-mass carrier where a scene's machinery assumes one mass
/// per carrier: a `[manufactured]` solution (its mass source is one
/// equation per carrier, MODEL §11) and a `[reference]` (each analytic
/// reference is of a single-mass carrier or force). Nothing else reads the
/// chain beyond the integrators.
pub(crate) fn check_chain_scene(scene: &Scene, carriers: &[CarrierProps]) -> Result<()> {
    let Some(i) = carriers.iter().position(|c| c.chain.is_some()) else {
        return Ok(());
    };
    let what = if scene.manufactured.is_some() {
        "manufactured"
    } else if scene.reference.is_some() {
        "reference"
    } else {
        return Ok(());
    };
    Err(Error::invalid(
        format!("carrier.{i}.masses"),
        "given",
        format!(
            "a multi-mass carrier cannot be used with [{what}] (its solutions are of \
             single-mass carriers): give `mass`, or remove [{what}]"
        ),
    ))
}
