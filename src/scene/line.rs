//! `[line]`: a multi-span line generated from a few keys
//! (docs/scene.md#line, docs/lines.md#the-line-generator-g1g7).
//!
//! The table is expanded into plain scene keys **at the document level**
//! (a TOML tree → TOML tree rewrite, [`expand_line`]), where every scene
//! tree becomes a [`super::Scene`] (`scene_from_tree`): after `--set`
//! overrides, so that `--set line.spans=12` and sweeps over `line.*` keys
//! regenerate the line, and before deserialization, so that the run, every
//! study and `taut line expand` see the same explicit scene. A tree without
//! `line` is handed back untouched.
//!
//! What it writes: `beam.length` (spans × span length; an error if given),
//! `beam.left`/`right` (`pinned` unless given), `mesh.elements` (uniform,
//! a node on every support and dropper; a given count is kept only if it
//! puts one there too), one
//! `[[dropper]]` per dropper with its design length (eq. G1–G7), a
//! `[[attachment]]` steady arm at every interior support when asked, and,
//! with `anchor = "messenger"`, the `[messenger]` table. Explicit
//! `[[dropper]]`s and `[[attachment]]`s of the scene are appended after the
//! generated ones.

use serde::Deserialize;
use toml::{Table, Value};

use super::generated::Generated;
use super::line_design::{PointSpring, StringLoad, dropper_forces, messenger_sag, presag_profile};
use super::line_props::{EndMasses, dropper_props};
use super::line_supports::{chord, line_supports, settlements};
use super::range::{non_negative, positive};
use super::scales::Scales;
use super::steady_arm::{SteadyArm, SteadyArmSpec};
use super::validate::MAX_ELEMENTS;
use crate::error::{Error, Result, one_line};

/// Most spans a line may have (a 1000-span line is 50 km: beyond any run).
pub(crate) const MAX_SPANS: usize = 1000;

/// Most droppers a span may have.
pub(crate) const MAX_DROPPERS_PER_SPAN: usize = 100;

/// How far (relative, in elements) a dropper may be from a node and still
/// count as on it: the round-off of x·N/L for positions written in decimal
/// (a dropper at 4.5 m of a 54 m span on 216 elements is 18.000000000000004).
const ON_NODE: f64 = 1e-9;

/// How much finer than `element_length` asks the mesh may be made to put a
/// node on every dropper (elements per span at most this many times
/// S/h): beyond it the positions are taken as off any common grid.
const MAX_REFINEMENT: usize = 64;

/// The `[line]` table as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct LineSpec {
    /// Number of spans (1 ..= [`MAX_SPANS`]).
    spans: usize,
    /// Span length S, m (> 0): supports at x = k S.
    span_length: f64,
    /// Droppers per span: `{ count, end_distance }` or a list of positions
    /// within a span, m.
    droppers: Value,
    /// Contact wire pre-sag p at mid-span, m (≥ 0, default 0).
    #[serde(default)]
    presag: f64,
    /// Dropper stiffness k_d, N/m (> 0): a number, one per dropper of a
    /// span, or a pattern of spans (`super::line_props`, E3).
    dropper_stiffness: Value,
    /// Target element length h, m (> 0): the mesh's h is at most this.
    element_length: f64,
    /// Where the droppers hang: the messenger wire, or fixed points on the
    /// messenger's design shape.
    anchor: LineAnchor,
    /// The messenger wire's properties (its design shape, and with
    /// `anchor = "messenger"` the emitted `[messenger]` table).
    messenger: MessengerDesign,
    /// A steady arm at every interior support (`[[attachment]]`).
    #[serde(default)]
    steady_arm: Option<SteadyArmSpec>,
    /// Droppers that never slack (`linear = true` on each).
    #[serde(default)]
    linear_droppers: bool,
    /// Each dropper's dashpot c_d, N·s/m (≥ 0, default 0): `damping` on
    /// each (`docs/lines.md` D11 linear, D12 tension-only); per dropper as
    /// `dropper_stiffness`.
    #[serde(default)]
    dropper_damping: Option<Value>,
    /// Each dropper's own mass, kg (≥ 0, default 0), half lumped at each
    /// end (E3); per dropper as `dropper_stiffness`.
    #[serde(default)]
    dropper_mass: Option<Value>,
    /// The clamps' masses `{ contact, messenger }`, kg (≥ 0, default 0),
    /// point masses on each wire at every dropper (E3).
    #[serde(default)]
    clamp_mass: Option<Value>,
    /// Form-find the dropper lengths (`docs/lines.md` eq. F1–F5): each
    /// dropper gets `design_height` = v_c(x_d) (G2), and the run solves
    /// for the lengths from the G6 ones (default false: G6's lengths).
    #[serde(default)]
    form_finding: bool,
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
enum LineAnchor {
    Messenger,
    Fixed,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct MessengerDesign {
    /// T_m, N (> 0).
    tension: f64,
    /// ρA_m, kg/m (> 0).
    mass_per_length: f64,
    /// EI_m, N·m² (≥ 0; required with `anchor = "messenger"`).
    #[serde(default)]
    bending_stiffness: Option<f64>,
    /// h_m: the messenger's support line above the contact wire's rest
    /// line, m (> 0).
    height: f64,
    /// Elastic supports (`super::line_supports`, E2): a table for every
    /// interior support, or a list for each; absent: pinned.
    #[serde(default)]
    support: Option<Value>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct EvenDroppers {
    count: usize,
    #[serde(default)]
    end_distance: Option<f64>,
}

/// One generated dropper (SI units), for the document and the tests.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DesignedDropper {
    /// Label `s<span>d<k>` (1-based).
    pub name: String,
    /// x_d, m.
    pub x: f64,
    /// Design force N_d, N (G3).
    pub force: f64,
    /// Messenger displacement v_m(x_d) from its support line, m (G5).
    pub messenger_v: f64,
    /// Contact wire's design height v_c(x_d), m (G2).
    pub contact_v: f64,
    /// Unstretched length ℓ_0, m (G6).
    pub length: f64,
}

/// Expand `[line]` into plain scene keys (see the module doc); a tree
/// without `line` is returned as it is.
pub(crate) fn expand_line(tree: Table) -> Result<Table> {
    expand_line_with_origin(tree).map(|(t, _)| t)
}

/// [`expand_line`], with what it generated: the keys an error names by
/// their path in the expanded scene are told apart from the ones a user
/// wrote ([`Generated::user_path`]).
pub(crate) fn expand_line_with_origin(mut tree: Table) -> Result<(Table, Generated)> {
    let Some(line) = tree.remove("line") else {
        return Ok((tree, Generated::default()));
    };
    let given_elements = tree.get("mesh").and_then(|m| m.get("elements")).is_some();
    let spec: LineSpec = super::tables::from_value(line).map_err(|e| {
        let path = e.path().to_string().replace('[', ".").replace(']', "");
        let inner = e.into_inner().to_string();
        let inner = inner.split("\nin `").next().unwrap_or(&inner).trim_end();
        let field = if path.is_empty() || path == "." {
            "line".to_string()
        } else {
            format!("line.{path}")
        };
        Error::Parse {
            reason: one_line(&format!("at `{field}`: {inner}")),
            field: Some(field),
        }
    })?;
    let line = Line::check(&spec)?;
    let design = line.design(&tree)?;
    line.write(&design, &mut tree)?;
    let generated = Generated {
        line: true,
        droppers: design.len(),
        attachments: line.generated_attachments(&spec),
        steady_arms: if spec.steady_arm.is_some() {
            line.interior_supports().count()
        } else {
            0
        },
        contact_clamps: line.end_mass.contact_count(),
        messenger: line.anchor == LineAnchor::Messenger,
        elements: !given_elements,
    };
    Ok((tree, generated))
}

/// The checked keys.
struct Line {
    spans: usize,
    span: f64,
    /// Dropper positions within a span, m, strictly increasing in (0, S).
    local: Vec<f64>,
    presag: f64,
    /// k_d of every dropper of the line, span by span, N/m.
    k_d: Vec<f64>,
    h: f64,
    anchor: LineAnchor,
    messenger: MessengerDesign,
    steady_arm: Option<SteadyArm>,
    linear: bool,
    /// c_d of every dropper, N·s/m (0: no `damping` key emitted).
    c_d: Vec<f64>,
    /// The point mass at each dropper's lower and upper end, kg: its clamp
    /// plus half its own mass (E3; 0: no attachment emitted).
    end_mass: EndMasses,
    /// Each dropper's own mass as written, kg (`line.dropper_mass`).
    own_mass: Vec<f64>,
    /// Each dropper's clamps as written, kg (`line.clamp_mass`: contact,
    /// messenger).
    clamp_mass: (Vec<f64>, Vec<f64>),
    /// `[messenger] support` to write, and each support's kind (E2).
    supports: (Option<Value>, Vec<Option<super::ElasticSupport>>),
    /// Emit each dropper's `design_height` (form-finding, F1–F5).
    form_finding: bool,
}

impl Line {
    fn check(s: &LineSpec) -> Result<Line> {
        if s.spans == 0 || s.spans > MAX_SPANS {
            return Err(Error::invalid(
                "line.spans",
                s.spans,
                format!("must be a count in 1 ..= {MAX_SPANS}"),
            ));
        }
        let span = positive("line.span_length", s.span_length, "m")?;
        let local = dropper_positions(&s.droppers, span)?;
        let presag = non_negative(
            "line.presag",
            s.presag,
            "m, the contact wire's sag at mid-span",
        )?;
        if presag >= span / 4.0 {
            return Err(Error::invalid(
                "line.presag",
                presag,
                format!(
                    "must be below a quarter of the span ({} m): the design takes small slopes",
                    span / 4.0
                ),
            ));
        }
        let props = dropper_props(
            (
                &s.dropper_stiffness,
                s.dropper_damping.as_ref(),
                s.dropper_mass.as_ref(),
                s.clamp_mass.as_ref(),
            ),
            (s.spans, local.len()),
            s.anchor == LineAnchor::Fixed,
        )?;
        let supports = line_supports(s.messenger.support.as_ref(), s.spans)?;
        if s.anchor == LineAnchor::Fixed && supports.0.is_some() {
            return Err(Error::invalid(
                "line.messenger.support",
                one_line(
                    &s.messenger
                        .support
                        .clone()
                        .unwrap_or(Value::Boolean(false))
                        .to_string(),
                ),
                "needs line.anchor = \"messenger\": with fixed anchors the messenger is not part of the run (leave it out)",
            ));
        }
        let h = positive("line.element_length", s.element_length, "m")?;
        if h > span {
            return Err(Error::invalid(
                "line.element_length",
                h,
                format!("must be at most the span length ({span} m)"),
            ));
        }
        // before the design: a line no mesh can hold is refused by its
        // lengths, not by what the design makes of them
        least_elements_per_span(s.spans, span, h)?;
        let m = &s.messenger;
        positive("line.messenger.tension", m.tension, "N")?;
        positive("line.messenger.mass_per_length", m.mass_per_length, "kg/m")?;
        positive(
            "line.messenger.height",
            m.height,
            "m, above the contact wire's rest line",
        )?;
        match m.bending_stiffness {
            Some(ei) => {
                non_negative("line.messenger.bending_stiffness", ei, "N·m²")?;
            }
            None if s.anchor == LineAnchor::Messenger => {
                return Err(Error::invalid(
                    "line.messenger.bending_stiffness",
                    "none",
                    "is required with line.anchor = \"messenger\" (N·m², ≥ 0): the messenger wire is part of the run",
                ));
            }
            None => {}
        }
        // the arm reduced to its tip (S1–S3)
        let steady_arm = s.steady_arm.map(|a| a.tip()).transpose()?;
        Ok(Line {
            spans: s.spans,
            span,
            local,
            presag,
            k_d: props.stiffness,
            h,
            anchor: s.anchor,
            messenger: m.clone(),
            steady_arm,
            linear: s.linear_droppers,
            c_d: props.damping,
            end_mass: props.end_mass,
            own_mass: props.own_mass,
            clamp_mass: props.clamp_mass,
            supports,
            form_finding: s.form_finding,
        })
    }

    fn length(&self) -> f64 {
        self.spans as f64 * self.span
    }

    /// Every dropper's position, length and design force (G1–G7), from
    /// the contact wire's `[beam]` and the scene's `[gravity]`.
    fn design(&self, tree: &Table) -> Result<Vec<DesignedDropper>> {
        let t_c = positive(
            "beam.tension",
            number(tree, "beam", "tension")?.unwrap_or(f64::NAN),
            "N",
        )?;
        let rho_a = match number(tree, "beam", "mass_per_length")? {
            Some(v) => v,
            None => match (
                number(tree, "beam", "density")?,
                number(tree, "beam", "area")?,
            ) {
                (Some(r), Some(a)) => r * a,
                _ => f64::NAN,
            },
        };
        let rho_a = positive("beam.mass_per_length", rho_a, "kg/m, or density × area")?;
        let g = number(tree, "gravity", "g")?.unwrap_or(9.81);
        let g = non_negative("gravity.g", g, "m/s²")?;
        let self_weight = match tree.get("gravity").and_then(|t| t.get("beam_self_weight")) {
            None => false,
            Some(Value::Boolean(b)) => *b,
            Some(other) => {
                return Err(Error::invalid(
                    "gravity.beam_self_weight",
                    other.clone(),
                    "must be true or false",
                ));
            }
        };
        self.check_plausible(tree, t_c, rho_a)?;
        let weight = |rho_a: f64| if self_weight { rho_a * g } else { 0.0 };
        let wire = StringLoad {
            tension: t_c,
            weight: weight(rho_a),
        };
        let messenger = StringLoad {
            tension: self.messenger.tension,
            weight: weight(self.messenger.mass_per_length),
        };
        let mut names = Vec::new();
        let mut xs = Vec::new();
        let mut vc = Vec::new();
        for span in 0..self.spans {
            for (k, &p) in self.local.iter().enumerate() {
                names.push(format!("s{}d{}", span + 1, k + 1));
                xs.push(span as f64 * self.span + p);
                vc.push(presag_profile(self.presag, self.span, p));
            }
        }
        let springs: Vec<PointSpring> = match self.steady_arm {
            Some(arm) => self
                .interior_supports()
                .map(|x| PointSpring {
                    x,
                    stiffness: arm.stiffness,
                })
                .collect(),
            None => Vec::new(),
        };
        let forces = dropper_forces(self.length(), &xs, &vc, wire, &springs);
        let supports = self.supports();
        let loads: Vec<(f64, f64)> = xs.iter().copied().zip(forces.iter().copied()).collect();
        // elastic supports sink under the messenger's reactions (E2)
        let delta = settlements(&supports, &self.supports.1, messenger, &loads);
        let mut out = Vec::with_capacity(xs.len());
        for (i, name) in names.into_iter().enumerate() {
            let force = forces[i];
            if force < 0.0 {
                return Err(Error::invalid(
                    "line.presag",
                    self.presag,
                    format!(
                        "is too large for the wire's weight: dropper {name} at x = {} m would have to push ({force:.4} N); lower the pre-sag, or turn on gravity.beam_self_weight",
                        xs[i]
                    ),
                ));
            }
            // the span's own supports and loads (G5: the supports are rigid)
            let k = i / self.local.len();
            let per = self.local.len();
            let vm = messenger_sag(
                &supports[k..=k + 1],
                messenger,
                &loads[k * per..(k + 1) * per],
                xs[i],
            ) + chord(
                xs[i],
                (supports[k], supports[k + 1]),
                (delta[k], delta[k + 1]),
            );
            let room = self.messenger.height + vm - vc[i];
            let stretch = force / self.k_d[i];
            let length = room - stretch;
            if !vm.is_finite() || !stretch.is_finite() {
                // the checks above leave no key that gives these; said
                // without a number that is none
                return Err(Error::invalid(
                    "line",
                    format!("dropper {name} (x = {} m)", xs[i]),
                    "has no finite design: the messenger's sag or the dropper's stretch there is not a number; check line.messenger (tension, support), line.steady_arm and line.dropper_stiffness",
                ));
            }
            if room > 0.0 && length <= 0.0 {
                return Err(Error::invalid(
                    "line.dropper_stiffness",
                    self.k_d[i],
                    format!(
                        "is too soft for dropper {name} (x = {} m): its design force {force:.4} N stretches it {stretch:.4e} m, more than the {room:.4} m between the wires there, which leaves it no length (N/m; raise it)",
                        xs[i]
                    ),
                ));
            }
            if length <= 0.0 {
                return Err(Error::invalid(
                    "line.messenger.height",
                    self.messenger.height,
                    format!(
                        "is too low: the messenger sags {:.4} m at dropper {name} (x = {} m), which leaves it no length; raise the height or the messenger's tension",
                        -vm, xs[i]
                    ),
                ));
            }
            out.push(DesignedDropper {
                name,
                x: xs[i],
                force,
                messenger_v: vm,
                contact_v: vc[i],
                length,
            });
        }
        Ok(out)
    }

    /// Every lumped key a user wrote in `[line]`, each value against the
    /// scales of the wire it acts on (`super::scales`): the contact wire's
    /// from `[beam]` (tension `t_c`, ρA `rho_a`), the messenger's from
    /// `line.messenger`, both on the line's mesh at `time.step`. Before the
    /// design uses them, so that a value no run can use is named as written
    /// and not as a sag or a clamp it makes. Without a usable `time.step`
    /// the expanded scene's check (on the generated keys) is the one.
    fn check_plausible(&self, tree: &Table, t_c: f64, rho_a: f64) -> Result<()> {
        // read leniently: a value of the wrong kind is refused by its own
        // check, with its own message
        let read = |table: &str, key: &str| number(tree, table, key).ok().flatten();
        let Some(dt) = read("time", "step").filter(|d| d.is_finite() && *d > 0.0) else {
            return Ok(());
        };
        let elements = match tree
            .get("mesh")
            .and_then(|m| m.get("elements"))
            .and_then(Value::as_integer)
        {
            Some(n) if n > 0 => n as usize,
            _ => match self.elements_per_span() {
                Ok(m) => m * self.spans,
                Err(_) => return Ok(()),
            },
        };
        let ei = match read("beam", "bending_stiffness") {
            Some(ei) => ei,
            None => match (
                read("beam", "youngs_modulus"),
                read("beam", "second_moment"),
            ) {
                (Some(e), Some(i)) => e * i,
                _ => 0.0,
            },
        };
        let ei = if ei.is_finite() { ei } else { 0.0 };
        let length = self.length();
        let wire = Scales::wire(length, (rho_a, t_c, ei), elements, dt);
        let m = &self.messenger;
        let messenger = Scales::wire(
            length,
            (
                m.mass_per_length,
                m.tension,
                m.bending_stiffness.unwrap_or(0.0),
            ),
            elements,
            dt,
        )
        .named("the messenger's");
        // the upper clamps hang on the messenger only when it is a wire of
        // the run; on fixed anchors they are refused by name earlier
        let upper = if self.anchor == LineAnchor::Messenger {
            &messenger
        } else {
            &wire
        };
        for i in 0..self.k_d.len() {
            wire.stiffness("line.dropper_stiffness", self.k_d[i])?;
            wire.damping("line.dropper_damping", self.c_d[i])?;
            wire.mass("line.dropper_mass", self.own_mass[i])?;
            wire.mass("line.clamp_mass.contact", self.clamp_mass.0[i])?;
            upper.mass("line.clamp_mass.messenger", self.clamp_mass.1[i])?;
        }
        if let Some(arm) = &self.steady_arm {
            wire.stiffness("line.steady_arm.stiffness", arm.stiffness)?;
            wire.mass("line.steady_arm.mass", arm.mass)?;
            wire.damping("line.steady_arm.damping", arm.damping)?;
        }
        for e in self.supports.1.iter().flatten() {
            messenger.stiffness("line.messenger.support.stiffness", e.stiffness)?;
            messenger.mass("line.messenger.support.mass", e.mass)?;
            messenger.damping("line.messenger.support.damping", e.damping)?;
        }
        Ok(())
    }

    fn supports(&self) -> Vec<f64> {
        (0..=self.spans).map(|k| k as f64 * self.span).collect()
    }

    fn interior_supports(&self) -> impl Iterator<Item = f64> + '_ {
        (1..self.spans).map(|k| k as f64 * self.span)
    }

    /// Elements per span m: the smallest with S/m ≤ h and every dropper on
    /// a node (p m / S an integer, to [`ON_NODE`]).
    fn elements_per_span(&self) -> Result<usize> {
        let first = least_elements_per_span(self.spans, self.span, self.h)? as usize;
        let most = (MAX_ELEMENTS / self.spans).min(MAX_REFINEMENT.saturating_mul(first));
        for m in first..=most.max(first) {
            if m * self.spans > MAX_ELEMENTS {
                break;
            }
            if self.on_nodes(m) {
                return Ok(m);
            }
        }
        Err(Error::invalid(
            "line.element_length",
            self.h,
            format!(
                "gives no uniform mesh with a node on every dropper and at most {MAX_REFINEMENT} times the elements it asks for (or {MAX_ELEMENTS} in all): put the dropper positions ({:?} m within a span) on a common grid of the span",
                self.local
            ),
        ))
    }

    /// Whether m uniform elements a span put a node on every dropper
    /// (p m / S an integer, to [`ON_NODE`]).
    fn on_nodes(&self, m: usize) -> bool {
        self.local.iter().all(|&p| {
            let at = p * m as f64 / self.span;
            (at - at.round()).abs() <= ON_NODE * at.max(1.0)
        })
    }

    /// Write the generated keys into the tree.
    fn write(&self, design: &[DesignedDropper], tree: &mut Table) -> Result<()> {
        let beam = table_mut(tree, "beam")?;
        if let Some(v) = beam.get("length") {
            return Err(Error::invalid(
                "beam.length",
                v.clone(),
                "is generated by [line] (spans × span_length): leave it out",
            ));
        }
        for end in ["left", "right"] {
            match beam.get(end) {
                None => {
                    beam.insert(end.into(), Value::String("pinned".into()));
                }
                Some(Value::String(s)) if s == "pinned" || s == "clamped" => {}
                Some(other) => {
                    return Err(Error::invalid(
                        format!("beam.{end}"),
                        other.clone(),
                        "must be \"pinned\" or \"clamped\" with [line] (its design holds the wire's ends at v = 0), or left out (pinned)",
                    ));
                }
            }
        }
        beam.insert("length".into(), Value::Float(self.length()));
        let mesh = table_mut(tree, "mesh")?;
        let elements = match mesh.get("elements") {
            None => self.elements_per_span()? * self.spans,
            // given (a refinement, an override): kept when it puts a node
            // on every support and dropper
            Some(Value::Integer(n))
                if *n > 0
                    && (*n as usize).is_multiple_of(self.spans)
                    && self.on_nodes(*n as usize / self.spans) =>
            {
                *n as usize
            }
            Some(v) => {
                return Err(Error::invalid(
                    "mesh.elements",
                    v.clone(),
                    format!(
                        "must put a node on every support and dropper of [line] (a multiple of {} elements per span, e.g. {}), or be left out (generated from line.element_length)",
                        self.spans,
                        self.elements_per_span()? * self.spans
                    ),
                ));
            }
        };
        if let Some(v) = mesh.get("grading")
            && v.as_str() != Some("uniform")
        {
            return Err(Error::invalid(
                "mesh.grading",
                v.clone(),
                "must be \"uniform\" (or absent) with [line]: a graded mesh moves the nodes off the droppers",
            ));
        }
        mesh.insert("elements".into(), Value::Integer(elements as i64));
        if self.anchor == LineAnchor::Messenger {
            if let Some(v) = tree.get("messenger") {
                return Err(Error::invalid(
                    "messenger",
                    one_line(&v.to_string()),
                    "is generated by [line] (line.messenger): leave it out",
                ));
            }
            let mut t = Table::new();
            t.insert("tension".into(), Value::Float(self.messenger.tension));
            t.insert(
                "mass_per_length".into(),
                Value::Float(self.messenger.mass_per_length),
            );
            t.insert(
                "bending_stiffness".into(),
                Value::Float(self.messenger.bending_stiffness.unwrap_or(0.0)),
            );
            t.insert("height".into(), Value::Float(self.messenger.height));
            t.insert(
                "supports".into(),
                Value::Array(self.supports().into_iter().map(Value::Float).collect()),
            );
            if let Some(list) = &self.supports.0 {
                t.insert("support".into(), list.clone());
            }
            tree.insert("messenger".into(), Value::Table(t));
        }
        let mut droppers: Vec<Value> = design
            .iter()
            .enumerate()
            .map(|(i, d)| {
                let mut t = Table::new();
                t.insert("name".into(), Value::String(d.name.clone()));
                t.insert("x".into(), Value::Float(d.x));
                t.insert("stiffness".into(), Value::Float(self.k_d[i]));
                match self.anchor {
                    LineAnchor::Fixed => {
                        t.insert(
                            "anchor_height".into(),
                            Value::Float(self.messenger.height + d.messenger_v),
                        );
                    }
                    LineAnchor::Messenger => {
                        t.insert("anchor".into(), Value::String("messenger".into()));
                    }
                }
                t.insert("length".into(), Value::Float(d.length));
                if self.linear {
                    t.insert("linear".into(), Value::Boolean(true));
                }
                if self.c_d[i] != 0.0 {
                    t.insert("damping".into(), Value::Float(self.c_d[i]));
                }
                if self.form_finding {
                    t.insert("design_height".into(), Value::Float(d.contact_v));
                }
                Value::Table(t)
            })
            .collect();
        droppers.extend(take_array(tree, "dropper")?);
        tree.insert("dropper".into(), Value::Array(droppers));
        let mut arms: Vec<Value> = match self.steady_arm {
            Some(arm) => self
                .interior_supports()
                .enumerate()
                .map(|(k, x)| {
                    let mut t = Table::new();
                    t.insert(
                        "name".into(),
                        Value::String(format!("steady_arm_{}", k + 1)),
                    );
                    t.insert("x".into(), Value::Float(x));
                    if arm.stiffness > 0.0 {
                        t.insert("stiffness".into(), Value::Float(arm.stiffness));
                    }
                    if arm.mass > 0.0 {
                        t.insert("mass".into(), Value::Float(arm.mass));
                    }
                    if arm.damping > 0.0 {
                        t.insert("damping".into(), Value::Float(arm.damping));
                    }
                    Value::Table(t)
                })
                .collect(),
            None => Vec::new(),
        };
        arms.extend(
            self.end_mass
                .tables(design.iter().map(|d| (d.name.as_str(), d.x))),
        );
        if !arms.is_empty() {
            arms.extend(take_array(tree, "attachment")?);
            tree.insert("attachment".into(), Value::Array(arms));
        }
        Ok(())
    }

    /// How many `[[attachment]]` the expansion writes: the steady arms and
    /// the clamps (E3).
    fn generated_attachments(&self, spec: &LineSpec) -> usize {
        let arms = if spec.steady_arm.is_some() {
            self.interior_supports().count()
        } else {
            0
        };
        arms + self.end_mass.count()
    }
}

/// The positions within a span (m) from `line.droppers` (G1): a list
/// (strictly increasing, each in (0, S)) or `{ count, end_distance }`
/// (count 1: mid-span; count ≥ 2: from e to S − e, evenly).
/// The fewest elements a span of `span` m takes at element length `h`
/// (S/m ≤ h, to [`ON_NODE`]), refused where `spans` of them exceed
/// [`MAX_ELEMENTS`]: the message names both lengths.
fn least_elements_per_span(spans: usize, span: f64, h: f64) -> Result<f64> {
    let first = ((span / h) * (1.0 - ON_NODE)).ceil().max(1.0);
    if first * spans as f64 > MAX_ELEMENTS as f64 {
        return Err(Error::invalid(
            "line.element_length",
            h,
            format!(
                "is too small: {spans} spans of {span} m (line.span_length) would need more than {MAX_ELEMENTS} elements in all (m; raise it, or shorten the spans)"
            ),
        ));
    }
    Ok(first)
}

fn dropper_positions(v: &Value, span: f64) -> Result<Vec<f64>> {
    let out = match v {
        Value::Array(list) => {
            let mut out = Vec::with_capacity(list.len());
            for (i, x) in list.iter().enumerate() {
                let field = format!("line.droppers.{i}");
                let x = match x {
                    Value::Float(f) => *f,
                    Value::Integer(k) => *k as f64,
                    other => {
                        return Err(Error::invalid(
                            field,
                            other.clone(),
                            "must be a position within the span (m)",
                        ));
                    }
                };
                if !(x > 0.0 && x < span) {
                    return Err(Error::invalid(
                        field,
                        x,
                        format!(
                            "must be inside the span, in (0, {span}) m (the supports are not dropper positions)"
                        ),
                    ));
                }
                if let Some(&prev) = out.last()
                    && x <= prev
                {
                    return Err(Error::invalid(
                        field,
                        x,
                        format!("must be above the previous position ({prev} m): the list rises"),
                    ));
                }
                out.push(x);
            }
            out
        }
        Value::Table(_) => {
            let even: EvenDroppers =
                super::tables::from_value(v.clone()).map_err(|e| Error::Parse {
                    reason: one_line(&format!("at `line.droppers`: {}", e.inner().message())),
                    field: Some("line.droppers".into()),
                })?;
            match even.count {
                n if n == 0 || n > MAX_DROPPERS_PER_SPAN => {
                    // refused before any list is built: a huge count must
                    // not allocate (or overflow) on its way to this error
                    return Err(Error::invalid(
                        "line.droppers.count",
                        n,
                        format!("must be in 1 ..= {MAX_DROPPERS_PER_SPAN}"),
                    ));
                }
                1 => vec![span / 2.0],
                n => {
                    let Some(e) = even.end_distance else {
                        return Err(Error::invalid(
                            "line.droppers.end_distance",
                            "none",
                            "is required with count ≥ 2 (m, from each support to its nearest dropper)",
                        ));
                    };
                    if !(e > 0.0 && 2.0 * e < span) {
                        return Err(Error::invalid(
                            "line.droppers.end_distance",
                            e,
                            format!("must be in (0, {}) m (half the span)", span / 2.0),
                        ));
                    }
                    let step = (span - 2.0 * e) / (n - 1) as f64;
                    (0..n).map(|i| e + i as f64 * step).collect()
                }
            }
        }
        other => {
            return Err(Error::invalid(
                "line.droppers",
                one_line(&other.to_string()),
                "must be { count = n, end_distance = e } or a list of positions within a span (m)",
            ));
        }
    };
    if out.is_empty() || out.len() > MAX_DROPPERS_PER_SPAN {
        return Err(Error::invalid(
            "line.droppers",
            out.len(),
            format!("must give 1 ..= {MAX_DROPPERS_PER_SPAN} droppers a span"),
        ));
    }
    Ok(out)
}

/// A number `table.key` of the tree (integer or float), if present.
fn number(tree: &Table, table: &str, key: &str) -> Result<Option<f64>> {
    match tree.get(table).and_then(|t| t.get(key)) {
        None => Ok(None),
        Some(Value::Float(f)) => Ok(Some(*f)),
        Some(Value::Integer(i)) => Ok(Some(*i as f64)),
        Some(other) => Err(Error::invalid(
            format!("{table}.{key}"),
            other.clone(),
            "must be a number",
        )),
    }
}

/// The table `key` of the tree, made if absent.
fn table_mut<'a>(tree: &'a mut Table, key: &str) -> Result<&'a mut Table> {
    match tree
        .entry(key.to_string())
        .or_insert_with(|| Value::Table(Table::new()))
    {
        Value::Table(t) => Ok(t),
        other => Err(Error::invalid(key, other.clone(), "must be a table")),
    }
}

/// Remove and return the array of tables `key` (empty if absent).
fn take_array(tree: &mut Table, key: &str) -> Result<Vec<Value>> {
    match tree.remove(key) {
        None => Ok(Vec::new()),
        Some(Value::Array(a)) => Ok(a),
        Some(other) => Err(Error::invalid(
            key,
            one_line(&other.to_string()),
            format!("must be a list of tables ([[{key}]])"),
        )),
    }
}

/// The line's designed droppers (for tests and the docs' figures): the
/// expansion's design without writing the document.
#[cfg(test)]
pub(crate) fn designed_droppers(tree: &Table) -> Result<Vec<DesignedDropper>> {
    let Some(line) = tree.get("line") else {
        return Ok(Vec::new());
    };
    let spec: LineSpec = line.clone().try_into().map_err(|e: toml::de::Error| {
        Error::parse(one_line(&format!("at `line`: {}", e.message())))
    })?;
    Line::check(&spec)?.design(tree)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load::{apply_override, parse_scene, scene_from_tree};

    /// The hand-computed figures below are sums of a few exact decimal
    /// terms: they and the code agree to round-off.
    const HAND: f64 = 1e-12;

    /// Two spans of 10 m, droppers at 2.5 and 7.5 m of each, pre-sag 1 cm,
    /// a steady arm spring at the middle support; T = 1000 N, w = 10 N/m
    /// (ρA = 1, g = 10), messenger T_m = 2000 N, w_m = 5 N/m, h_m = 1 m.
    const TWO_SPANS: &str = r#"
[beam]
tension = 1000.0
mass_per_length = 1.0
bending_stiffness = 1.0

[mesh]

[[carrier]]
mass = 1.0
stiffness = 1000.0
preload = 0.01
side = "below"
start = 0.0
speed = { profile = "constant", value = 10.0 }

[time]
step = 1e-3
end = 0.01

[gravity]
g = 10.0
beam_self_weight = true

[line]
spans = 2
span_length = 10.0
droppers = [2.5, 7.5]
presag = 0.01
dropper_stiffness = 1.0e4
element_length = 0.25
anchor = "fixed"
messenger = { tension = 2000.0, mass_per_length = 0.5, height = 1.0 }
steady_arm = { stiffness = 1000.0, mass = 1.0 }
"#;

    fn tree(overrides: &[&str]) -> Table {
        let mut t = parse_scene(TWO_SPANS).unwrap();
        for o in overrides {
            apply_override(&mut t, o).unwrap();
        }
        t
    }

    fn expand_err(overrides: &[&str]) -> String {
        expand_line(tree(overrides)).unwrap_err().to_string()
    }

    #[test]
    fn two_spans_against_the_hand_computed_design() {
        let d = designed_droppers(&tree(&[])).unwrap();
        let x: Vec<f64> = d.iter().map(|d| d.x).collect();
        assert_eq!(x, [2.5, 7.5, 12.5, 17.5]);
        // G2: v_c(2.5) = −4·0.01·0.25·0.75 = −0.0075 at every dropper
        for d in &d {
            assert!((d.contact_v + 0.0075).abs() < HAND, "{d:?}");
        }
        // G3 by hand. d1: its left segment [0, 2.5] (slope −0.003) pushes
        // T s + wL/2 = −3 + 12.5, its right one [2.5, 7.5] (flat) wL/2 = 25.
        let n1 = -3.0 + 12.5 + 25.0;
        // d2: [2.5, 7.5] pushes 25; [7.5, 12.5] holds the steady arm at 10:
        // v₀(10) = −0.0075 − 10·2.5·2.5/2000 = −0.03875, G = 2.5·2.5/5000,
        // v_s = v₀/(1 + 1000 G) = −0.03875/2.25, F = −1000 v_s, half of it at d2
        let f = 1000.0 * 0.03875 / 2.25;
        let n2 = 25.0 + 25.0 - f / 2.0;
        let want_n = [n1, n2, n2, n1];
        for (d, n) in d.iter().zip(want_n) {
            assert!((d.force - n).abs() < HAND * n, "{d:?} {n}");
        }
        // G5 by hand: span [0, 10], T_m = 2000, w_m = 5; G(2.5, 2.5) =
        // 2.5·7.5/20000, G(2.5, 7.5) = 2.5·2.5/20000
        let weight = -5.0 * 2.5 * 7.5 / 4000.0;
        let (g_near, g_far) = (2.5 * 7.5 / 20000.0, 2.5 * 2.5 / 20000.0);
        let vm1 = weight - n1 * g_near - n2 * g_far;
        let vm2 = weight - n1 * g_far - n2 * g_near;
        let want_vm = [vm1, vm2, vm2, vm1];
        for (d, vm) in d.iter().zip(want_vm) {
            assert!((d.messenger_v - vm).abs() < HAND, "{d:?} {vm}");
        }
        // G6: ℓ_0 = h_m + v_m − v_c − N/k_d
        for (i, d) in d.iter().enumerate() {
            let l0 = 1.0 + want_vm[i] + 0.0075 - want_n[i] / 1.0e4;
            assert!((d.length - l0).abs() < HAND, "{d:?} {l0}");
        }
        // the figures quoted in docs/lines.md
        assert!((n2 - 41.388_888_888_9).abs() < 1e-9);
        assert!((d[0].length - 0.935_334_722_2).abs() < 1e-9);
        assert!((d[1].length - 0.930_340_277_8).abs() < 1e-9);
    }

    #[test]
    fn the_document_gets_length_mesh_droppers_and_steady_arms() {
        let t = expand_line(tree(&[])).unwrap();
        assert!(t.get("line").is_none());
        assert_eq!(t["beam"]["length"].as_float(), Some(20.0));
        assert_eq!(t["beam"]["left"].as_str(), Some("pinned"));
        // h = 0.25 m puts nodes on 2.5 and 7.5: 40 elements a span
        assert_eq!(t["mesh"]["elements"].as_integer(), Some(80));
        let droppers = t["dropper"].as_array().unwrap();
        assert_eq!(droppers.len(), 4);
        assert_eq!(droppers[2]["name"].as_str(), Some("s2d1"));
        let d = designed_droppers(&tree(&[])).unwrap();
        assert_eq!(
            droppers[0]["anchor_height"].as_float(),
            Some(1.0 + d[0].messenger_v)
        );
        assert_eq!(droppers[0]["length"].as_float(), Some(d[0].length));
        assert!(t.get("messenger").is_none(), "fixed anchors: no messenger");
        let arms = t["attachment"].as_array().unwrap();
        assert_eq!(arms.len(), 1);
        assert_eq!(arms[0]["x"].as_float(), Some(10.0));
        assert_eq!(arms[0]["mass"].as_float(), Some(1.0));
        // the expanded scene deserializes and validates
        scene_from_tree(t.clone()).unwrap().validate().unwrap();
    }

    #[test]
    fn even_droppers_and_the_messenger_anchor() {
        let t = expand_line(tree(&[
            "line.droppers={ count = 3, end_distance = 2.0 }",
            "line.anchor=messenger",
            "line.messenger.bending_stiffness=50.0",
            "unset line.steady_arm",
        ]))
        .unwrap();
        let x: Vec<f64> = t["dropper"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| d["x"].as_float().unwrap())
            .collect();
        assert_eq!(x, [2.0, 5.0, 8.0, 12.0, 15.0, 18.0]);
        // 2.0 and 5.0 m on nodes: h = 0.25 m already does
        assert_eq!(t["mesh"]["elements"].as_integer(), Some(80));
        assert_eq!(t["dropper"][0]["anchor"].as_str(), Some("messenger"));
        assert!(t["dropper"][0].get("anchor_height").is_none());
        let m = &t["messenger"];
        assert_eq!(m["height"].as_float(), Some(1.0));
        assert_eq!(m["bending_stiffness"].as_float(), Some(50.0));
        let supports: Vec<f64> = m["supports"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_float().unwrap())
            .collect();
        assert_eq!(supports, [0.0, 10.0, 20.0]);
        assert!(t.get("attachment").is_none());
        // one dropper a span: at mid-span
        let t = expand_line(tree(&["line.droppers={ count = 1 }"])).unwrap();
        assert_eq!(t["dropper"][1]["x"].as_float(), Some(15.0));
    }

    #[test]
    fn explicit_droppers_and_attachments_are_appended() {
        let mut t = tree(&[]);
        let extra = parse_scene(
            "[[dropper]]\nname = \"extra\"\nx = 1.0\nstiffness = 1e4\nanchor_height = 1.0\nlength = 0.999\n[[attachment]]\nx = 3.0\nmass = 2.0\n",
        )
        .unwrap();
        t.extend(extra);
        let t = expand_line(t).unwrap();
        let droppers = t["dropper"].as_array().unwrap();
        assert_eq!(droppers.len(), 5);
        assert_eq!(droppers[4]["name"].as_str(), Some("extra"));
        let arms = t["attachment"].as_array().unwrap();
        assert_eq!(arms.len(), 2);
        assert_eq!(arms[1]["x"].as_float(), Some(3.0));
    }

    #[test]
    fn the_expanded_text_round_trips_to_the_same_scene() {
        for o in [
            &[][..],
            &[
                "line.anchor=messenger",
                "line.messenger.bending_stiffness=5.0",
            ][..],
        ] {
            let expanded = expand_line(tree(o)).unwrap();
            let text = toml::to_string(&expanded).unwrap();
            let again = parse_scene(&text).unwrap();
            assert_eq!(again, expanded, "{o:?}");
            if o.is_empty() {
                // no [line] left: the text's scene is the line's scene
                // (but for the record of what the line generated)
                let mut line = scene_from_tree(tree(o)).unwrap();
                assert!(line.generated.line && line.generated.droppers > 0);
                line.generated = Generated::default();
                assert_eq!(scene_from_tree(again).unwrap(), line);
            }
        }
    }

    #[test]
    fn bad_keys_name_the_field_the_value_and_the_range() {
        let cases: [(&[&str], &[&str]); 19] = [
            (&["line.spanz=3"], &["line", "spanz", "unknown"]),
            (
                &["line.droppers={ count = 2305843009213693952, end_distance = 3 }"],
                &["line.droppers.count", "2305843009213693952", "1 ..= 100"],
            ),
            (
                &["line.element_length=1e-300"],
                &["line.element_length", "too small", "elements in all"],
            ),
            (&["line.spans=0"], &["line.spans", "0", "1 ..= 1000"]),
            (&["line.span_length=-5"], &["line.span_length", "-5", "> 0"]),
            // refused by its lengths before the design (whose droppers
            // rounded onto the supports and panicked)
            (
                &["line.span_length=1e300"],
                &["line.span_length", "1e300", "elements in all"],
            ),
            (&["line.presag=-0.1"], &["line.presag", "-0.1", "≥ 0"]),
            (
                &["line.dropper_stiffness=0"],
                &["line.dropper_stiffness", "> 0"],
            ),
            (
                &["line.element_length=20"],
                &["line.element_length", "20", "span length"],
            ),
            (
                &["line.droppers=[7.5, 2.5]"],
                &["line.droppers.1", "2.5", "previous"],
            ),
            (
                &["line.droppers=[0.0, 2.5]"],
                &["line.droppers.0", "(0, 10)"],
            ),
            (
                &["line.droppers={ count = 3 }"],
                &["line.droppers.end_distance", "required"],
            ),
            (
                &["line.droppers={ count = 3, end_distance = 6 }"],
                &["line.droppers.end_distance", "6", "(0, 5)"],
            ),
            (
                &["line.droppers={ count = 3, spacing = 1 }"],
                &["line.droppers", "spacing"],
            ),
            (&["line.anchor=ground"], &["line.anchor", "ground"]),
            (
                &["line.anchor=messenger"],
                &["line.messenger.bending_stiffness", "required"],
            ),
            (
                &["line.messenger.height=0.05"],
                &["line.messenger.height", "0.05", "too low"],
            ),
            (
                &["gravity.beam_self_weight=false"],
                &["line.presag", "0.01", "push"],
            ),
            (
                &["line.steady_arm={ stiffness = 0 }"],
                &["line.steady_arm", "mass > 0"],
            ),
        ];
        for (o, want) in cases {
            let e = expand_err(o);
            for w in want {
                assert!(e.contains(w), "{o:?}: {e} (wanted {w})");
            }
        }
        for (o, want) in [
            ("beam.length=20", "beam.length"),
            ("mesh.elements=81", "mesh.elements"),
            ("mesh.grading=supports", "mesh.grading"),
            ("beam.left=free", "beam.left"),
        ] {
            let e = expand_err(&[o]);
            assert!(e.contains(want) && e.contains("[line]"), "{o}: {e}");
        }
        // a mesh that keeps a node on every dropper is taken (a refinement)
        let t = expand_line(tree(&["mesh.elements=160"])).unwrap();
        assert_eq!(t["mesh"]["elements"].as_integer(), Some(160));
        // positions off every grid: no uniform mesh puts a node on them
        let e = expand_err(&["line.droppers=[3.14159265358979]"]);
        assert!(
            e.contains("line.element_length") && e.contains("common grid"),
            "{e}"
        );
    }

    #[test]
    fn form_finding_gives_every_generated_dropper_its_design_height() {
        let t = expand_line(tree(&["line.form_finding=true"])).unwrap();
        let d = designed_droppers(&tree(&[])).unwrap();
        for (g, d) in t["dropper"].as_array().unwrap().iter().zip(&d) {
            assert_eq!(g["design_height"].as_float(), Some(d.contact_v));
            assert_eq!(g["length"].as_float(), Some(d.length), "G6: the start");
        }
        let t = expand_line(tree(&[])).unwrap();
        assert!(t["dropper"][0].get("design_height").is_none());
        let line = scene_from_tree(tree(&["line.form_finding=true"])).unwrap();
        assert_eq!(
            line.generated.user_path("dropper.2.design_height"),
            "line.presag"
        );
        assert_eq!(line.droppers[0].design_height, Some(d[0].contact_v));
    }

    #[test]
    fn a_scene_without_line_is_untouched() {
        let text = include_str!("../../scenes/span_droppers.toml");
        let t = parse_scene(text).unwrap();
        assert_eq!(expand_line(t.clone()).unwrap(), t);
    }
}
