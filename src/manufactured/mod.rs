//! Manufactured solutions for the whole problem (MODEL §11): a smooth beam
//! motion v*(x, t) chosen from a small family, and for each carrier the
//! contact force λ*(t) and mass motion q*(t) consistent with it, with the
//! source that makes them the exact solution of the model.
//!
//! **The motion.** `v*(x, t) = Σᵢ aᵢ Xᵢ(x) T̂ᵢ(t)`: each x-shape a product of
//! polynomials, sines and exponentials in ξ = x/L corrected to meet the
//! supports ([`supports`]), each time part a product of the same kinds in t
//! with its value and rate at t = 0 removed, `T̂ = T − T(0) − T'(0)t`, so
//! the beam starts straight and at rest, as every run does (MODEL §5).
//!
//! **The source.** `p*(x, t) = ρA v*_tt + EI v*_xxxx − T v*_xx − Σ_c P_c(t)
//! δ(x − x_c(t))`: a smooth part, separable as `Σᵢ aᵢ[T̂ᵢ''(t) ρA Xᵢ(x) +
//! T̂ᵢ(t) (EI Xᵢ'''' − T Xᵢ'')(x)]` ([`Manufactured::source_shapes`],
//! [`Manufactured::source_coefficients`]), whose x-parts a discretization
//! projects once per run (`model::source`); and a point load at each
//! carrier that cancels the carrier's own ([`Manufactured::point_load`]):
//! `−s F` for a moving force, `−s λ*(t)` for a mass–spring, whose contact
//! then has to deliver λ* for the beam to follow v* — the contact coupling
//! is verified, not bypassed.
//!
//! The consistent carrier force and a loss interval are derived on
//! [`Manufactured::new`], two coupled wires and their droppers on
//! [`Manufactured::dropper_weights`], point attachments, dashpots and self-weight
//! on [`Manufactured::attachment_weights`].

pub mod factor;
pub mod jet;
pub mod supports;

use factor::{Factor, Product};
use jet::Jet;
use supports::{Ends, Shape};

use crate::error::{Error, Result};
use crate::scene::manufactured::{LossSpec, ManufacturedSpec, TFactor, TermSpec, XFactor};
use crate::scene::{
    Attachment, BeamProps, CarrierKind, CarrierProps, ContactKind, Dropper, Motion, Support,
};

/// Time samples of the consistency checks per step of the run (at least
/// [`MIN_CHECK_SAMPLES`], at most [`MAX_CHECK_SAMPLES`]): λ* of a smooth
/// motion cannot change sign between samples a quarter step apart without
/// the run itself missing it.
pub const CHECK_SAMPLES_PER_STEP: usize = 4;
/// Fewest samples of the consistency checks.
pub const MIN_CHECK_SAMPLES: usize = 2001;
/// Most samples of the consistency checks (bounds validation's cost).
pub const MAX_CHECK_SAMPLES: usize = 400_001;

/// A shape whose largest value on the span, sampled at
/// [`SHAPE_SAMPLES`] points, is below this fraction of its raw shape's is
/// taken as removed by the support correction (the raw shape was a
/// polynomial of the correction's own powers).
const VANISHED: f64 = 1e-10;
const SHAPE_SAMPLES: usize = 257;

/// A messenger support within this fraction of L of a line end is that
/// end's support (the same round-off bound as `resolve::messenger`'s
/// support-on-a-node check).
const SUPPORT_AT_END: f64 = 1e-9;

/// One term a·X(x)·T̂(t).
#[derive(Debug, Clone, PartialEq)]
struct Term {
    amplitude: f64,
    shape: Shape,
    time: Product,
    /// T(0) and T'(0).
    start: (f64, f64),
}

impl Term {
    /// T̂ and its derivatives at t.
    fn time_jet(&self, t: f64) -> Jet {
        let mut j = self.time.jet(t);
        j.0[0] -= self.start.0 + self.start.1 * t;
        j.0[1] -= self.start.1;
        j
    }
}

/// A carrier of a manufactured scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CarrierRole {
    /// A moving force F, N.
    Force(f64),
    /// A mass–spring (MODEL §2).
    Mass {
        /// m, kg.
        m: f64,
        /// k, N/m.
        k: f64,
        /// c_s, N·s/m.
        c: f64,
        /// kδ0 − s m g, N.
        f0: f64,
    },
}

/// One carrier's part.
#[derive(Debug, Clone, PartialEq)]
struct Carrier {
    s: f64,
    motion: Motion,
    role: CarrierRole,
}

/// The prescribed loss (`Manufactured::new`'s docs).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Loss {
    start: f64,
    end: f64,
    gap: f64,
    blend: f64,
}

/// The C³ step 35u⁴ − 84u⁵ + 70u⁶ − 20u⁷ on [0, 1] (0 → 1, three
/// derivatives zero at both ends).
fn smoothstep(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * u * u * (35.0 + u * (-84.0 + u * (70.0 - 20.0 * u)))
}

impl Loss {
    /// χ(t): 1 in contact, 0 in the loss, a C³ step over each blend.
    fn chi(&self, t: f64) -> f64 {
        if t <= self.start {
            smoothstep((self.start - t) / self.blend)
        } else if t >= self.end {
            smoothstep((t - self.end) / self.blend)
        } else {
            0.0
        }
    }

    /// g*, ġ*, g̈* at t.
    fn gap(&self, t: f64) -> [f64; 3] {
        if t <= self.start || t >= self.end {
            return [0.0; 3];
        }
        // G (4u(1 − u))⁴ = G 256 p⁴, p = u(1 − u)
        let d = self.end - self.start;
        let u = (t - self.start) / d;
        let p = u * (1.0 - u);
        let (dp, ddp) = (1.0 - 2.0 * u, -2.0);
        let g = 256.0 * self.gap;
        [
            g * p.powi(4),
            g * 4.0 * p.powi(3) * dp / d,
            g * (12.0 * p * p * dp * dp + 4.0 * p.powi(3) * ddp) / (d * d),
        ]
    }
}

/// v* and the derivatives a carrier's motion needs, at one (x, t).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fields {
    /// v, m.
    pub v: f64,
    /// v_x.
    pub v_x: f64,
    /// v_xx, 1/m.
    pub v_xx: f64,
    /// v_t, m/s.
    pub v_t: f64,
    /// v_tt, m/s².
    pub v_tt: f64,
    /// v_xt, 1/s.
    pub v_xt: f64,
}

/// The manufactured solution of a scene (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Manufactured {
    terms: Vec<Term>,
    length: f64,
    rho_a: f64,
    ei: f64,
    tension: f64,
    carriers: Vec<Carrier>,
    loss: Option<Loss>,
    /// The messenger's motion v_m* (`None`: no `[messenger]`, or v_m* = 0).
    messenger: Option<LineMotion>,
    /// The droppers, whose forces N_d* of the manufactured motion the
    /// source cancels (`Manufactured::dropper_weights`' docs).
    droppers: Vec<DropperLoad>,
    /// The scene's own point attachments (`[[attachment]]`), whose forces
    /// of the manufactured motion the source cancels (`Manufactured::attachment_weights`' docs).
    attachments: Vec<AttachmentLoad>,
    /// The source has rate parts aᵢT̂ᵢ'(t) (a dashpot c_a or c_d > 0).
    rates: bool,
    /// The lines' self-weight the source gives back, N/m (+ρA g on the
    /// contact wire, +ρA_m g on the messenger; 0 without
    /// `gravity.beam_self_weight`): a constant distributed load that
    /// cancels the model's, so v* stays the solution (M7).
    weight: [f64; 2],
}

/// A line's manufactured motion: its terms and section (the messenger's).
#[derive(Debug, Clone, PartialEq)]
struct LineMotion {
    terms: Vec<Term>,
    rho_a: f64,
    ei: f64,
    tension: f64,
}

/// A dropper as the source sees it (`docs/lines.md` D1, W2).
#[derive(Debug, Clone, PartialEq)]
struct DropperLoad {
    name: String,
    /// x_d, m.
    x: f64,
    /// k_d, N/m.
    k: f64,
    /// e₀ = z_a − ℓ_0 (or h_m − ℓ_0), m.
    e0: f64,
    /// Hangs from the messenger (r_d = r_c − r_m) rather than a fixed anchor.
    on_messenger: bool,
    /// Tension-only (must stay taut: N_d* > 0).
    tension_only: bool,
    /// c_d, N·s/m (`docs/lines.md` D11; 0: none).
    c: f64,
}

/// A point attachment as the source sees it (`docs/lines.md` A0, §10.4):
/// on the contact wire (or the messenger: an elastic support, a clamp,
/// E1) at x_a, anchored at v = 0, no preload.
#[derive(Debug, Clone, Copy, PartialEq)]
struct AttachmentLoad {
    /// On the messenger (r_m(x_a), v_m*) rather than the contact wire.
    on_messenger: bool,
    /// x_a, m.
    x: f64,
    /// m_a, kg.
    m: f64,
    /// c_a, N·s/m.
    c: f64,
    /// k_a, N/m.
    k: f64,
}

/// Which line a source shape is projected on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Line {
    /// The contact wire (the beam).
    Contact,
    /// The messenger wire (`[messenger]`).
    Messenger,
}

fn x_factor(f: &XFactor) -> Factor {
    match f {
        XFactor::Polynomial { coefficients } => Factor::Polynomial(coefficients.clone()),
        XFactor::Sine { half_waves, phase } => Factor::Sine {
            rate: half_waves * std::f64::consts::PI,
            phase: *phase,
        },
        XFactor::Exponential { rate } => Factor::Exponential { rate: *rate },
    }
}

fn t_factor(f: &TFactor) -> Factor {
    match f {
        TFactor::Polynomial { coefficients } => Factor::Polynomial(coefficients.clone()),
        TFactor::Sine { frequency, phase } => Factor::Sine {
            rate: 2.0 * std::f64::consts::PI * frequency,
            phase: *phase,
        },
        TFactor::Exponential { rate } => Factor::Exponential { rate: *rate },
    }
}

/// What a manufactured solution is built for: the beam, the carriers, the
/// contact kind, gravity and the run's time grid.
#[derive(Debug, Clone, Copy)]
pub struct Setting<'a> {
    /// The beam.
    pub beam: &'a BeamProps,
    /// The carriers, in scene order.
    pub carriers: &'a [CarrierProps],
    /// `contact.kind`.
    pub contact: ContactKind,
    /// Gravity on the carriers' masses, m/s².
    pub g: f64,
    /// The run's end, s.
    pub t_end: f64,
    /// Its steps.
    pub steps: usize,
    /// The scene's droppers (`[[dropper]]`, resolved).
    pub droppers: &'a [Dropper],
    /// The scene's own point attachments (`[[attachment]]`, resolved; not
    /// the linear droppers' springs, which `droppers` carries).
    pub attachments: &'a [Attachment],
}

/// Build one line's terms from `specs` (`prefix`: the scene key of the
/// terms, `manufactured` or `manufactured.messenger`), each shape corrected
/// to meet `ends` and, with a `weight`, to vanish where it does.
fn line_terms(
    specs: &[TermSpec],
    ends: &Ends,
    weight: Option<&Product>,
    prefix: &str,
    t_end: f64,
) -> Result<Vec<Term>> {
    let mut terms = Vec::with_capacity(specs.len());
    for (i, t) in specs.iter().enumerate() {
        let field = format!("{prefix}.term.{i}.x");
        let raw = Product(t.x.iter().map(x_factor).collect());
        let shape = match weight {
            None => Shape::new(raw.clone(), ends, &field)?,
            Some(w) => Shape::weighted(raw.clone(), ends, w.clone(), &field)?,
        };
        let (mut big, mut raw_big) = (0.0f64, 0.0f64);
        for k in 0..SHAPE_SAMPLES {
            let x = ends.length * k as f64 / (SHAPE_SAMPLES - 1) as f64;
            let xi = x / ends.length;
            big = big.max(shape.jet(x).d(0).abs());
            let r = raw.jet(xi).d(0) * weight.map_or(1.0, |w| w.jet(xi).d(0));
            raw_big = raw_big.max(r.abs());
        }
        if big.is_nan() || big <= VANISHED * raw_big {
            return Err(Error::invalid(
                field,
                if raw_big == 0.0 {
                    "zero everywhere"
                } else {
                    "a shape of the correction's form (a polynomial of degree ≤ 3 on these supports)"
                },
                "is removed entirely by the correction that makes a shape meet the supports (X = 0): multiply it by another factor or raise its degree",
            ));
        }
        let time = Product(t.t.iter().map(t_factor).collect());
        let j0 = time.jet(0.0);
        let term = Term {
            amplitude: t.amplitude,
            shape,
            time,
            start: (j0.d(0), j0.d(1)),
        };
        let moves = (0..=64).any(|k| term.time_jet(t_end * k as f64 / 64.0).d(2) != 0.0);
        if !moves {
            return Err(Error::invalid(
                format!("{prefix}.term.{i}.t"),
                "a time part linear in t",
                "leaves nothing once its value and rate at t = 0 are removed (T̂ = T − T(0) − T'(0)t = 0): use a factor curved in t",
            ));
        }
        terms.push(term);
    }
    Ok(terms)
}

/// Σ aᵢ Xᵢ⁽ᵖ⁾(x) T̂ᵢ⁽ᵏ⁾(t) of one line's terms: the `(p, k)` derivative
/// in x and t of its v*.
fn line_d(terms: &[Term], x: f64, t: f64, (p, k): (usize, usize)) -> f64 {
    terms
        .iter()
        .map(|term| term.amplitude * term.shape.jet(x).d(p) * term.time_jet(t).d(k))
        .sum()
}

/// Σ aᵢ Xᵢ(x) T̂ᵢ(t) of one line's terms.
fn line_v(terms: &[Term], x: f64, t: f64) -> f64 {
    line_d(terms, x, t, (0, 0))
}

/// Σ aᵢ Xᵢ(x) T̂ᵢ'(t) of one line's terms: the rate v_t, m/s.
fn line_v_t(terms: &[Term], x: f64, t: f64) -> f64 {
    line_d(terms, x, t, (0, 1))
}

impl Manufactured {
    /// Build the solution of `spec` for `at` and check that it is one: every
    /// shape meets the supports and is not removed by the correction, every
    /// time part is more than linear, and a unilateral contact keeps λ* > 0
    /// outside the prescribed loss (below).
    ///
    /// **A mass–spring carrier** (MODEL §2). In contact its mass follows the
    /// beam, `q* = w* = s v*(x_m(t), t)`, whose second derivative carries the
    /// convective terms, `ẅ* = s(v_tt + 2V v_xt + V² v_xx + V̇ v_x)` at x_m;
    /// the consistent force is the mass equation's,
    /// `λ_c = kδ0 − s m g − m ẅ* − c_s ẇ* − k w*`. Without a loss interval
    /// λ* = λ_c and the mass needs no source. With `[manufactured.loss]`
    /// (t_a, t_b, gap G, blend τ): λ* = χ(t) λ_c, χ a C³ step from 1 to 0 over
    /// [t_a − τ, t_a] and back over [t_b, t_b + τ]; the gap opens as
    /// g* = G (4u(1 − u))⁴, u = (t − t_a)/(t_b − t_a), on [t_a, t_b] (zero with
    /// three derivatives at both ends), q* = w* − g*, and the mass equation gets
    /// the source `f_q = m q̈* + c_s q̇* + k q* − (kδ0 − s m g) + λ*`, zero
    /// wherever χ = 1. Signorini holds exactly: λ* = 0 while g* > 0, g* = 0
    /// while λ* > 0. A unilateral contact must keep λ* > 0 outside the loss:
    /// [`Manufactured::new`] checks it on a fine time grid and refuses the scene
    /// otherwise, naming the time and the value.
    pub fn new(spec: &ManufacturedSpec, at: Setting) -> Result<Self> {
        spec.check(at.t_end)?;
        let b = at.beam;
        let ends = Ends {
            left: b.left,
            right: b.right,
            length: b.length,
            ei: b.ei,
            tension: b.tension,
        };
        let terms = line_terms(&spec.terms, &ends, None, "manufactured", at.t_end)?;
        let messenger = Self::messenger_motion(spec, at)?;
        let droppers = Self::dropper_loads(at);
        let load = |on_messenger: bool| {
            move |a: &Attachment| AttachmentLoad {
                on_messenger,
                x: a.x,
                m: a.mass,
                c: a.damping,
                k: a.stiffness,
            }
        };
        // the messenger's own (elastic supports, clamps) act on v_m*
        let attachments: Vec<AttachmentLoad> = at
            .attachments
            .iter()
            .map(load(false))
            .chain(
                b.messenger
                    .iter()
                    .flat_map(|m| m.attachments.iter().map(load(true))),
            )
            .collect();
        let rates = droppers.iter().any(|d| d.c != 0.0) || attachments.iter().any(|a| a.c != 0.0);
        let carriers: Vec<Carrier> = at
            .carriers
            .iter()
            .map(|c| {
                let s = c.side.sign();
                Carrier {
                    s,
                    motion: c.motion.clone(),
                    role: match c.kind {
                        CarrierKind::Force { force } => CarrierRole::Force(force),
                        CarrierKind::MassSpring {
                            mass,
                            stiffness,
                            damping,
                            preload,
                        } => CarrierRole::Mass {
                            m: mass,
                            k: stiffness,
                            c: damping,
                            f0: stiffness * preload - s * mass * at.g,
                        },
                    },
                }
            })
            .collect();
        let loss = spec.loss.as_ref().map(|l: &LossSpec| Loss {
            start: l.start,
            end: l.end,
            gap: l.gap,
            blend: l.blend,
        });
        let masses = carriers
            .iter()
            .filter(|c| matches!(c.role, CarrierRole::Mass { .. }))
            .count();
        if loss.is_some() {
            if masses == 0 {
                return Err(Error::invalid(
                    "manufactured.loss",
                    "a scene without a mass–spring carrier",
                    "prescribes a loss of contact, which needs a mass–spring carrier: remove [manufactured.loss] or add one",
                ));
            }
            if at.contact == ContactKind::Bilateral {
                return Err(Error::invalid(
                    "manufactured.loss",
                    "contact.kind = bilateral",
                    "a bilateral contact never opens: use contact.kind = \"unilateral\" or remove [manufactured.loss]",
                ));
            }
        }
        let m = Manufactured {
            terms,
            length: b.length,
            rho_a: b.rho_a,
            ei: b.ei,
            tension: b.tension,
            carriers,
            loss,
            messenger,
            droppers,
            attachments,
            rates,
            weight: [
                -b.distributed_load,
                b.messenger.as_ref().map_or(0.0, |m| -m.distributed_load),
            ],
        };
        if at.contact == ContactKind::Unilateral {
            m.check_contact_kept(at.t_end, at.steps)?;
        }
        m.check_droppers_taut(at.t_end, at.steps)?;
        Ok(m)
    }

    /// The messenger's motion (`Manufactured::dropper_weights`' docs): its shapes meet the
    /// messenger's ends (pinned where a support sits at x = 0 or L, free
    /// beyond the outermost supports otherwise) and vanish at every
    /// interior support through the weight P(ξ) = Π (ξ − ξ_s).
    fn messenger_motion(spec: &ManufacturedSpec, at: Setting) -> Result<Option<LineMotion>> {
        let b = at.beam;
        let Some(ms) = &spec.messenger else {
            return Ok(None);
        };
        let Some(m) = &b.messenger else {
            return Err(Error::invalid(
                "manufactured.messenger",
                "(present)",
                "is the messenger wire's motion and needs a [messenger] section: add one or remove [manufactured.messenger]",
            ));
        };
        let l = b.length;
        let at_end = |x: f64, end: f64| (x - end).abs() <= SUPPORT_AT_END * l;
        // an elastic support (E1) does not hold v_m* = 0: its spring's
        // force is in the source; only the pinned ones enter the shapes
        let pinned: Vec<f64> = m.pinned().collect();
        let first = pinned.first().copied().unwrap_or(f64::NAN);
        let last = pinned.last().copied().unwrap_or(f64::NAN);
        let ends = Ends {
            left: if at_end(first, 0.0) {
                Support::Pinned
            } else {
                Support::Free
            },
            right: if at_end(last, l) {
                Support::Pinned
            } else {
                Support::Free
            },
            length: l,
            ei: m.ei,
            tension: m.tension,
        };
        let weight = Product(
            pinned
                .iter()
                .filter(|&&x| !at_end(x, 0.0) && !at_end(x, l))
                .map(|&x| Factor::Polynomial(vec![-x / l, 1.0]))
                .collect(),
        );
        let terms = line_terms(
            &ms.terms,
            &ends,
            Some(&weight),
            "manufactured.messenger",
            at.t_end,
        )?;
        Ok(Some(LineMotion {
            terms,
            rho_a: m.rho_a,
            ei: m.ei,
            tension: m.tension,
        }))
    }

    /// The droppers the source cancels (`Manufactured::dropper_weights`' docs).
    fn dropper_loads(at: Setting) -> Vec<DropperLoad> {
        at.droppers
            .iter()
            .map(|d| DropperLoad {
                name: d.name.clone(),
                x: d.x,
                k: d.stiffness,
                e0: d.rest_extension(),
                on_messenger: d.on_messenger(),
                tension_only: !d.linear,
                c: d.damping,
            })
            .collect()
    }

    /// A tension-only dropper must stay taut (N_d* > 0) over the run, or
    /// it would go slack where the manufactured solution keeps it pulling.
    fn check_droppers_taut(&self, t_end: f64, steps: usize) -> Result<()> {
        let n = (CHECK_SAMPLES_PER_STEP * steps).clamp(MIN_CHECK_SAMPLES, MAX_CHECK_SAMPLES);
        for (i, d) in self.droppers.iter().enumerate() {
            if !d.tension_only {
                continue;
            }
            for k in 0..=n {
                let t = t_end * k as f64 / n as f64;
                let force = self.dropper_force(i, t);
                if force.is_nan() || force <= 0.0 {
                    return Err(Error::invalid(
                        format!("dropper.{i}.linear"),
                        format!(
                            "false (dropper {}: manufactured force N_d* = {force:.6e} N at t = {t:.6e} s)",
                            d.name
                        ),
                        "a tension-only dropper must stay taut (N_d* > 0) over a manufactured run, else it goes slack where the manufactured solution keeps it pulling: lower the amplitudes, shorten the dropper (a larger preload k_d(e₀)), or declare it linear = true",
                    ));
                }
            }
        }
        Ok(())
    }

    /// The force N_d*(t) = k_d e_d* + c_d ė_d* of dropper d in the
    /// manufactured motion, N (tension positive): e_d* = e₀ + v_m*(x_d) −
    /// v_c*(x_d) on the messenger (`docs/lines.md` W2), e₀ − v_c*(x_d) on a
    /// fixed anchor (D1), and its dashpot's ė_d* = v̇_m*(x_d) − v̇_c*(x_d)
    /// (D11; −v̇_c*(x_d) on a fixed anchor).
    pub fn dropper_force(&self, d: usize, t: f64) -> f64 {
        let dr = &self.droppers[d];
        let vm = if dr.on_messenger {
            self.v_m(dr.x, t)
        } else {
            0.0
        };
        let spring = dr.k * (dr.e0 + vm - self.v(dr.x, t));
        if dr.c == 0.0 {
            return spring;
        }
        let vm_t = match (&self.messenger, dr.on_messenger) {
            (Some(m), true) => line_v_t(&m.terms, dr.x, t),
            _ => 0.0,
        };
        spring + dr.c * (vm_t - line_v_t(&self.terms, dr.x, t))
    }

    /// v_m*(x, t) of the messenger, m (0 without `[manufactured.messenger]`).
    pub fn v_m(&self, x: f64, t: f64) -> f64 {
        self.messenger
            .as_ref()
            .map_or(0.0, |m| line_v(&m.terms, x, t))
    }

    /// ∂v_m*/∂x (x, t) of the messenger (0 without
    /// `[manufactured.messenger]`): the slope its Hermite nodes carry.
    pub fn v_m_x(&self, x: f64, t: f64) -> f64 {
        self.messenger
            .as_ref()
            .map_or(0.0, |m| line_d(&m.terms, x, t, (1, 0)))
    }

    /// v* of `line` at (x, t), m.
    pub fn v_on(&self, line: Line, x: f64, t: f64) -> f64 {
        match line {
            Line::Contact => self.v(x, t),
            Line::Messenger => self.v_m(x, t),
        }
    }

    /// The droppers the source carries.
    pub fn droppers(&self) -> usize {
        self.droppers.len()
    }

    /// Dropper d's position x_d (m) and whether it hangs from the messenger.
    pub fn dropper_at(&self, d: usize) -> (f64, bool) {
        (self.droppers[d].x, self.droppers[d].on_messenger)
    }

    /// The weights w_k of dropper d's point load −N_d*(t) = Σ_k c_k(t) w_k
    /// over the source's parts (c_k of [`Manufactured::source_coefficients`]),
    /// into `out` (overwritten): with N_d* = k_d(e₀ + v_m* − v_c*) + c_d(v̇_m*
    /// − v̇_c*) at x_d, w = k_d X_c,i(x_d) on contact term i's T̂ part and
    /// c_d X_c,i(x_d) on its T̂' part, −k_d X_m,j(x_d) and −c_d X_m,j(x_d) on
    /// messenger term j's, −k_d e₀ on the constant part. The load acts
    /// along r_d (r_c − r_m, or r_c): the model's own spring and dashpot add
    /// +N_d r_d, so the two cancel only when the run delivers N_d = N_d*.
    ///
    /// **Two coupled wires** (`docs/lines.md` W1–W6, D1–D2). With a
    /// `[messenger]`, the messenger has its own motion
    /// `v_m*(x, t) = Σⱼ bⱼ X_m,j(x) T̂ⱼ(t)` (`[manufactured.messenger]`; absent:
    /// v_m* = 0), each shape `X_m = (S − c)·P`, `P(ξ) = Π (ξ − ξ_s)` over the
    /// messenger's pinned interior supports (so X_m = 0 there whatever c is) and c the
    /// correction of its ends (pinned where a pinned support sits at x = 0 or L, free
    /// otherwise, [`supports::Shape::weighted`]); an elastic support
    /// (`docs/lines.md` E1) is a point attachment on the messenger, below, and
    /// does not hold X_m = 0; its smooth source is
    /// `ρA_m v_m,tt + EI_m v_m,xxxx − T_m v_m,xx`. Each dropper d carries in the
    /// manufactured motion the force `N_d*(t) = k_d(e₀ + v_m*(x_d) − v_c*(x_d))`
    /// (W2; `e₀ − v_c*(x_d)` on a fixed anchor, D1), and the source gets the
    /// point load `−N_d*(t) r_d`, `r_d = r_c(x_d) − r_m(x_d)` (−N_d* on the
    /// contact wire, +N_d* on the messenger): the model's own dropper spring
    /// adds `k_d(e₀ − r_dᵀd) r_d`, which cancels it only when the run delivers
    /// N_d = N_d* — the coupling is verified, not bypassed. Separable again:
    /// `−N_d* = Σ_k c_k(t) w_k` over the source's parts plus a constant part
    /// `−k_d e₀` ([`Manufactured::dropper_weights`]). A dropper's dashpot c_d
    /// (D11) is in its force, `N_d* = k_d e_d* + c_d ė_d*` with
    /// `ė_d* = v̇_m*(x_d) − v̇_c*(x_d)` (`docs/verification.md` M6). A
    /// tension-only dropper must stay taut (N_d* > 0, dashpot included: the
    /// Kelvin–Voigt link's max(0, k_d e_d + c_d ė_d)) on the check grid, else
    /// the scene is refused naming the dropper and the time.
    pub fn dropper_weights(&self, d: usize, out: &mut [f64]) {
        out.fill(0.0);
        let dr = &self.droppers[d];
        let nc = self.terms.len();
        for (i, term) in self.terms.iter().enumerate() {
            let x = term.shape.jet(dr.x).d(0);
            out[2 * i + 1] = dr.k * x;
            if dr.c != 0.0 {
                out[self.rate_part(i)] = dr.c * x;
            }
        }
        if dr.on_messenger
            && let Some(m) = &self.messenger
        {
            for (j, term) in m.terms.iter().enumerate() {
                let x = term.shape.jet(dr.x).d(0);
                out[2 * nc + 2 * j + 1] = -dr.k * x;
                if dr.c != 0.0 {
                    out[self.rate_part(nc + j)] = -dr.c * x;
                }
            }
        }
        let constant = self.constant_part().expect("droppers have a constant part");
        out[constant] = -dr.k * dr.e0;
    }

    /// The point attachments the source carries (the scene's own).
    pub fn attachments(&self) -> usize {
        self.attachments.len()
    }

    /// Attachment a's position x_a, m (on the contact wire).
    pub fn attachment_at(&self, a: usize) -> f64 {
        self.attachments[a].x
    }

    /// True when attachment a acts on the messenger (an elastic support or
    /// a clamp, E1): its point vector is r_m(x_a).
    pub fn attachment_on_messenger(&self, a: usize) -> bool {
        self.attachments[a].on_messenger
    }

    /// The force attachment a exerts on its line in the manufactured
    /// motion, N in +v: −(m_a v*_tt + c_a v*_t + k_a v*) at x_a
    /// (`docs/verification.md` M4; v_m* on the messenger).
    pub fn attachment_force(&self, a: usize, t: f64) -> f64 {
        let at = &self.attachments[a];
        let terms = self.attachment_terms(a).map_or(&[][..], |(t, _)| t);
        let d = |k| line_d(terms, at.x, t, (0, k));
        -(at.m * d(2) + at.c * d(1) + at.k * d(0))
    }

    /// The terms attachment a's line moves with and the index of the first
    /// of them among both lines' (`None`: a messenger without motion).
    fn attachment_terms(&self, a: usize) -> Option<(&[Term], usize)> {
        if self.attachments[a].on_messenger {
            let m = self.messenger.as_ref()?;
            Some((&m.terms, self.terms.len()))
        } else {
            Some((&self.terms, 0))
        }
    }

    /// The weights w_k of attachment a's point load
    /// `(m_a v*_tt + c_a v*_t + k_a v*)(x_a, t) = Σ_k c_k(t) w_k` over the source's parts, into
    /// `out` (overwritten): m_a Xᵢ(x_a) on term i's T̂'' part, k_a Xᵢ(x_a)
    /// on its T̂ part, c_a Xᵢ(x_a) on its T̂' part (M5). The load acts along
    /// r_a, the model's interpolation vector at x_a (MODEL §4): the
    /// model's own m_a r_a r_aᵀ, c_a r_a r_aᵀ, k_a r_a r_aᵀ cancel it only
    /// when r_aᵀd follows v*(x_a), to the interpolation error between
    /// nodes.
    ///
    /// **Point attachments, dashpots, self-weight** (`docs/verification.md`
    /// M4–M7). Each `[[attachment]]` a (spring k_a, dashpot c_a, mass m_a at
    /// x_a to a fixed anchor, no preload; on the messenger, with v_m* and r_m,
    /// the messenger's elastic supports and clamps, E1) exerts in the manufactured motion the
    /// force `−(m_a v*_tt + c_a v*_t + k_a v*)(x_a, t)`; the source gets the
    /// point load `+(m_a v*_tt + c_a v*_t + k_a v*)(x_a, t) r_a`, r_a the
    /// interpolation vector the model's attachment is assembled with
    /// (`BeamModel::attach`), so only the model's own `m_a r_a r_aᵀ`,
    /// `c_a r_a r_aᵀ` and `k_a r_a r_aᵀ` cancel it — between nodes to the
    /// interpolation error of r_aᵀd against v*(x_a), order 4 in h for Hermite
    /// ([`Manufactured::attachment_weights`]). A dashpot (c_a or c_d > 0) adds
    /// a **rate part** `aᵢ T̂ᵢ'(t)` per term of each line to the separable
    /// source (none otherwise: a scene without dashpots keeps its parts). With
    /// `gravity.beam_self_weight` the constant part gives each line's weight
    /// back (+ρA g, N/m), so v* stays the solution. Rayleigh damping is not in
    /// the source and is refused (`resolve::damping`).
    pub fn attachment_weights(&self, a: usize, out: &mut [f64]) {
        out.fill(0.0);
        let at = &self.attachments[a];
        let Some((terms, first)) = self.attachment_terms(a) else {
            return;
        };
        for (j, term) in terms.iter().enumerate() {
            let (i, x) = (first + j, term.shape.jet(at.x).d(0));
            out[2 * i] = at.m * x;
            out[2 * i + 1] = at.k * x;
            if at.c != 0.0 {
                out[self.rate_part(i)] = at.c * x;
            }
        }
    }

    /// True when the source has a constant part: the droppers' preloads,
    /// the lines' self-weight.
    fn has_constant(&self) -> bool {
        !self.droppers.is_empty() || self.weight != [0.0; 2]
    }

    /// The index of the constant part, if any.
    fn constant_part(&self) -> Option<usize> {
        self.has_constant().then(|| 2 * self.term_count())
    }

    /// True when the source has parts on the messenger wire: its own
    /// motion, or its self-weight.
    pub fn loads_messenger(&self) -> bool {
        self.messenger.is_some() || self.weight[1] != 0.0
    }

    /// The index of the rate part aᵢT̂ᵢ'(t) of term i (the contact wire's
    /// terms, then the messenger's); only with dashpots.
    fn rate_part(&self, i: usize) -> usize {
        debug_assert!(self.rates, "rate parts exist only with dashpots");
        2 * self.term_count() + usize::from(self.has_constant()) + i
    }

    /// Terms of both lines.
    fn term_count(&self) -> usize {
        self.terms.len() + self.messenger.as_ref().map_or(0, |m| m.terms.len())
    }

    /// A unilateral contact must press (λ* > 0) wherever it is closed.
    fn check_contact_kept(&self, t_end: f64, steps: usize) -> Result<()> {
        let n = (CHECK_SAMPLES_PER_STEP * steps).clamp(MIN_CHECK_SAMPLES, MAX_CHECK_SAMPLES);
        for (c, carrier) in self.carriers.iter().enumerate() {
            if !matches!(carrier.role, CarrierRole::Mass { .. }) {
                continue;
            }
            for k in 0..=n {
                let t = t_end * k as f64 / n as f64;
                if self.loss.is_some_and(|l| t >= l.start && t <= l.end) {
                    continue;
                }
                let lambda = self.lambda(c, t);
                if lambda.is_nan() || lambda <= 0.0 {
                    return Err(Error::invalid(
                        "manufactured.term",
                        format!(
                            "contact force λ* = {lambda:.6e} N of carrier {c} at t = {t:.6e} s"
                        ),
                        "must stay > 0 while a unilateral contact is closed (else the contact opens where the manufactured solution keeps it shut): lower the amplitudes, raise carrier.preload or the mass's weight, prescribe the opening with [manufactured.loss], or use contact.kind = \"bilateral\"",
                    ));
                }
            }
        }
        Ok(())
    }

    /// v*(x, t), m.
    pub fn v(&self, x: f64, t: f64) -> f64 {
        line_v(&self.terms, x, t)
    }

    /// v* and its derivatives at (x, t).
    pub fn fields(&self, x: f64, t: f64) -> Fields {
        let mut f = Fields::default();
        for term in &self.terms {
            let (xs, ts) = (term.shape.jet(x), term.time_jet(t));
            let a = term.amplitude;
            f.v += a * xs.d(0) * ts.d(0);
            f.v_x += a * xs.d(1) * ts.d(0);
            f.v_xx += a * xs.d(2) * ts.d(0);
            f.v_t += a * xs.d(0) * ts.d(1);
            f.v_tt += a * xs.d(0) * ts.d(2);
            f.v_xt += a * xs.d(1) * ts.d(1);
        }
        f
    }

    /// The smooth source p_s(x, t) = ρA v_tt + EI v_xxxx − T v_xx, N/m.
    pub fn smooth_source(&self, x: f64, t: f64) -> f64 {
        self.terms
            .iter()
            .map(|term| {
                let (xs, ts) = (term.shape.jet(x), term.time_jet(t));
                term.amplitude
                    * (self.rho_a * xs.d(0) * ts.d(2)
                        + (self.ei * xs.d(4) - self.tension * xs.d(2)) * ts.d(0))
            })
            .sum()
    }

    /// The fastest rate of change of the x-shapes, 1/m: the largest |rate|
    /// of a sine or exponential factor, or a polynomial's degree, over L
    /// (at least the correction's degree 5 over L). A quadrature panel a
    /// fraction of 1/x_rate long resolves every shape.
    pub fn x_rate(&self) -> f64 {
        let per_xi = self
            .terms
            .iter()
            .chain(self.messenger.iter().flat_map(|m| m.terms.iter()))
            .flat_map(|t| t.shape.raw().0.iter())
            .map(|f| match f {
                Factor::Polynomial(c) => c.len().saturating_sub(1) as f64,
                Factor::Sine { rate, .. } | Factor::Exponential { rate } => rate.abs(),
            })
            .fold(5.0, f64::max);
        per_xi / self.length
    }

    /// Number of separable parts of the source: two per term of each
    /// line (its T̂'' and T̂ parts), one constant part when there are
    /// droppers (their preloads' share of N_d*) or self-weight (given back,
    /// M7), and one rate part (T̂')
    /// per term of each line when a dashpot (c_a or c_d > 0) is carried.
    pub fn source_count(&self) -> usize {
        let terms = self.term_count();
        2 * terms + usize::from(self.has_constant()) + if self.rates { terms } else { 0 }
    }

    /// The x-parts of the contact wire's smooth source at x into `out`
    /// ([`Manufactured::source_count`] long): ρA Xᵢ (N·s²/m² per m of
    /// amplitude·T̂'') and EI Xᵢ'''' − T Xᵢ'' (N/m²), term by term; the
    /// other parts 0.
    pub fn source_shapes(&self, x: f64, out: &mut [f64]) {
        self.source_shapes_on(Line::Contact, x, out)
    }

    /// As [`Manufactured::source_shapes`], on `line`: that line's parts
    /// from its own ρA, EI, T, the constant part its self-weight given back
    /// (+ρA g, N/m; 0 without), the other line's parts and the rate parts 0
    /// (the lines themselves are undamped: only the dashpots' point loads
    /// weigh the rate parts).
    pub fn source_shapes_on(&self, line: Line, x: f64, out: &mut [f64]) {
        out.fill(0.0);
        if let Some(k) = self.constant_part() {
            out[k] = match line {
                Line::Contact => self.weight[0],
                Line::Messenger => self.weight[1],
            };
        }
        let nc = self.terms.len();
        let (terms, rho_a, ei, tension, first) = match (line, &self.messenger) {
            (Line::Contact, _) => (&self.terms, self.rho_a, self.ei, self.tension, 0),
            (Line::Messenger, Some(m)) => (&m.terms, m.rho_a, m.ei, m.tension, 2 * nc),
            (Line::Messenger, None) => return,
        };
        for (i, term) in terms.iter().enumerate() {
            let xs = term.shape.jet(x);
            out[first + 2 * i] = rho_a * xs.d(0);
            out[first + 2 * i + 1] = ei * xs.d(4) - tension * xs.d(2);
        }
    }

    /// True when the messenger has a manufactured motion of its own.
    pub fn moves_messenger(&self) -> bool {
        self.messenger.is_some()
    }

    /// The time parts of the source at t into `out`: aᵢ T̂ᵢ''(t) and
    /// aᵢ T̂ᵢ(t) of each term (contact wire's, then the messenger's), 1 for
    /// the constant part, and aᵢ T̂ᵢ'(t) for the rate parts, so that
    /// p = Σ out[k]·shape[k].
    pub fn source_coefficients(&self, t: f64, out: &mut [f64]) {
        let all = self
            .terms
            .iter()
            .chain(self.messenger.iter().flat_map(|m| m.terms.iter()));
        for (i, term) in all.enumerate() {
            let ts = term.time_jet(t);
            out[2 * i] = term.amplitude * ts.d(2);
            out[2 * i + 1] = term.amplitude * ts.d(0);
            if self.rates {
                out[self.rate_part(i)] = term.amplitude * ts.d(1);
            }
        }
        if let Some(k) = self.constant_part() {
            out[k] = 1.0;
        }
    }

    /// The prescribed loss's window (s): from the start of the blend in
    /// which λ* falls to the end of the one in which it rises again;
    /// `None` without a `[manufactured.loss]`.
    pub fn loss_window(&self) -> Option<(f64, f64)> {
        self.loss.map(|l| (l.start - l.blend, l.end + l.blend))
    }

    /// The carriers, in scene order.
    pub fn carriers(&self) -> usize {
        self.carriers.len()
    }

    /// What carrier c is.
    pub fn role(&self, c: usize) -> CarrierRole {
        self.carriers[c].role
    }

    /// Carrier c's position x_m(t), m.
    pub fn position(&self, c: usize, t: f64) -> f64 {
        self.carriers[c].motion.position(t)
    }

    /// w* = s v*(x_m(t), t) under carrier c and its first two total time
    /// derivatives (with the convective terms, `Manufactured::new`'s docs).
    pub fn w(&self, c: usize, t: f64) -> [f64; 3] {
        let car = &self.carriers[c];
        let (x, v, a) = (
            car.motion.position(t),
            car.motion.speed(t),
            car.motion.acceleration(t),
        );
        let f = self.fields(x, t);
        [
            car.s * f.v,
            car.s * (f.v_t + v * f.v_x),
            car.s * (f.v_tt + 2.0 * v * f.v_xt + v * v * f.v_xx + a * f.v_x),
        ]
    }

    /// The prescribed gap g* of a mass carrier and its rates (0 without a loss).
    fn gap(&self, t: f64) -> [f64; 3] {
        self.loss.map_or([0.0; 3], |l| l.gap(t))
    }

    /// q* of mass carrier c (m, positive into the beam): w* − g*. For a
    /// force carrier, w*.
    pub fn q(&self, c: usize, t: f64) -> f64 {
        let w = self.w(c, t)[0];
        match self.carriers[c].role {
            CarrierRole::Force(_) => w,
            CarrierRole::Mass { .. } => w - self.gap(t)[0],
        }
    }

    /// The gap g* of carrier c, m (0 for a force).
    pub fn gap_of(&self, c: usize, t: f64) -> f64 {
        match self.carriers[c].role {
            CarrierRole::Force(_) => 0.0,
            CarrierRole::Mass { .. } => self.gap(t)[0],
        }
    }

    /// λ* of carrier c, N: the applied F for a force, χ·λ_c for a mass.
    pub fn lambda(&self, c: usize, t: f64) -> f64 {
        match self.carriers[c].role {
            CarrierRole::Force(f) => f,
            CarrierRole::Mass { m, k, c: cs, f0 } => {
                let [w, wd, wdd] = self.w(c, t);
                let consistent = f0 - m * wdd - cs * wd - k * w;
                self.loss.map_or(consistent, |l| l.chi(t) * consistent)
            }
        }
    }

    /// The source on mass carrier c's equation, N (`Manufactured::new`'s docs; 0 without
    /// a loss, and for a force).
    pub fn mass_source(&self, c: usize, t: f64) -> f64 {
        let Some(loss) = self.loss else {
            return 0.0;
        };
        match self.carriers[c].role {
            CarrierRole::Force(_) => 0.0,
            CarrierRole::Mass { m, k, c: cs, f0 } => {
                // m q̈* + c q̇* + k q* − f0 = −λ_c − (m g̈* + c ġ* + k g*) with
                // q* = w* − g*, so f_q = (χ − 1)λ_c − (m g̈* + c ġ* + k g*):
                // exactly 0 where χ = 1 and g* = 0
                let [w, wd, wdd] = self.w(c, t);
                let [g, gd, gdd] = loss.gap(t);
                let consistent = f0 - m * wdd - cs * wd - k * w;
                (loss.chi(t) - 1.0) * consistent - (m * gdd + cs * gd + k * g)
            }
        }
    }

    /// The point part of p* at carrier c, N in +v (module docs): −s F for
    /// a force, −s λ*(t) for a mass.
    pub fn point_load(&self, c: usize, t: f64) -> f64 {
        -self.carriers[c].s * self.lambda(c, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::manufactured::TermSpec;
    use crate::scene::{Side, SpeedProfile, Support};

    fn beam(left: Support, right: Support) -> BeamProps {
        BeamProps {
            length: 2.0,
            rho_a: 1.5,
            ei: 4.0,
            ea: None,
            tension: 60.0,
            left,
            right,
            distributed_load: 0.0,
            attachments: Vec::new(),
            messenger: None,
        }
    }

    fn spec(loss: Option<LossSpec>) -> ManufacturedSpec {
        ManufacturedSpec {
            terms: vec![
                TermSpec {
                    amplitude: 2e-3,
                    x: vec![XFactor::Sine {
                        half_waves: 1.0,
                        phase: 0.0,
                    }],
                    t: vec![TFactor::Sine {
                        frequency: 3.0,
                        phase: 0.0,
                    }],
                },
                TermSpec {
                    amplitude: 1e-3,
                    x: vec![
                        XFactor::Polynomial {
                            coefficients: vec![0.0, 1.0, 0.5],
                        },
                        XFactor::Exponential { rate: 0.5 },
                    ],
                    t: vec![
                        TFactor::Polynomial {
                            coefficients: vec![1.0, 2.0],
                        },
                        TFactor::Exponential { rate: -1.0 },
                    ],
                },
            ],
            loss,
            messenger: None,
        }
    }

    fn mass_carrier(speed: SpeedProfile) -> CarrierProps {
        CarrierProps {
            kind: CarrierKind::MassSpring {
                mass: 0.5,
                stiffness: 200.0,
                damping: 0.3,
                preload: 0.05,
            },
            chain: None,
            side: Side::Above,
            motion: Motion::new(0.2, speed, 2.0),
        }
    }

    /// Central differences of step δ = 1e-4 s: truncation ≈ δ²·(fourth
    /// derivative) ~ 1e-8·(2π·3)⁴·|w| ≈ 1e-6 relative; 1e-5 separates a
    /// right formula from a wrong term.
    const FD_REL: f64 = 1e-5;

    #[test]
    fn the_carrier_s_motion_is_the_total_derivative_under_it() {
        let b = beam(Support::Clamped, Support::Pinned);
        let c = [mass_carrier(SpeedProfile::SmoothRamp { cruise: 4.0 })];
        let m = Manufactured::new(
            &spec(None),
            Setting {
                beam: &b,
                carriers: &c,
                contact: ContactKind::Bilateral,
                g: 9.81,
                t_end: 0.4,
                steps: 100,
                droppers: &[],
                attachments: &[],
            },
        )
        .unwrap();
        let d = 1e-4;
        for t in [0.05, 0.13, 0.3] {
            let w = |t: f64| m.w(0, t)[0];
            let [_, wd, wdd] = m.w(0, t);
            let fd1 = (w(t + d) - w(t - d)) / (2.0 * d);
            let fd2 = (w(t + d) - 2.0 * w(t) + w(t - d)) / (d * d);
            assert!(
                (fd1 - wd).abs() <= FD_REL * wd.abs().max(1e-3),
                "{t}: {wd} {fd1}"
            );
            assert!(
                (fd2 - wdd).abs() <= FD_REL * 10.0 * wdd.abs().max(1e-2),
                "{t}: {wdd} {fd2}"
            );
        }
        // starts straight and at rest
        assert_eq!(m.v(0.7, 0.0), 0.0);
        assert!(m.w(0, 0.0)[1].abs() < 1e-18);
    }

    #[test]
    fn the_source_is_the_operator_on_v() {
        let b = beam(Support::Pinned, Support::Pinned);
        let m = Manufactured::new(
            &spec(None),
            Setting {
                beam: &b,
                carriers: &[],
                contact: ContactKind::Unilateral,
                g: 0.0,
                t_end: 0.4,
                steps: 100,
                droppers: &[],
                attachments: &[],
            },
        )
        .unwrap();
        let (x, t, d) = (0.83, 0.21, 1e-3);
        let v = |x: f64, t: f64| m.v(x, t);
        let vtt = (v(x, t + d) - 2.0 * v(x, t) + v(x, t - d)) / (d * d);
        let vxx = (v(x + d, t) - 2.0 * v(x, t) + v(x - d, t)) / (d * d);
        let vxxxx = (v(x + 2.0 * d, t) - 4.0 * v(x + d, t) + 6.0 * v(x, t) - 4.0 * v(x - d, t)
            + v(x - 2.0 * d, t))
            / d.powi(4);
        let fd = b.rho_a * vtt + b.ei * vxxxx - b.tension * vxx;
        let p = m.smooth_source(x, t);
        // the fourth difference loses ε/δ⁴ ≈ 2e-4 of |v| ~ 1e-3: 1e-3 relative to p
        assert!((fd - p).abs() <= 1e-3 * p.abs(), "{p} {fd}");
        let mut shapes = vec![0.0; m.source_count()];
        let mut coef = vec![0.0; m.source_count()];
        m.source_shapes(x, &mut shapes);
        m.source_coefficients(t, &mut coef);
        let sum: f64 = shapes.iter().zip(&coef).map(|(a, b)| a * b).sum();
        assert!((sum - p).abs() <= 1e-12 * p.abs());
    }

    #[test]
    fn a_loss_keeps_signorini_and_the_mass_equation() {
        let b = beam(Support::Pinned, Support::Pinned);
        let c = [mass_carrier(SpeedProfile::Constant { value: 3.0 })];
        let loss = LossSpec {
            start: 0.15,
            end: 0.25,
            gap: 1e-4,
            blend: 0.05,
        };
        let m = Manufactured::new(
            &spec(Some(loss)),
            Setting {
                beam: &b,
                carriers: &c,
                contact: ContactKind::Unilateral,
                g: 9.81,
                t_end: 0.4,
                steps: 400,
                droppers: &[],
                attachments: &[],
            },
        )
        .unwrap();
        for k in 0..=400 {
            let t = 0.4 * k as f64 / 400.0;
            let (lambda, gap) = (m.lambda(0, t), m.gap_of(0, t));
            assert!(lambda >= 0.0 && gap >= 0.0 && lambda * gap == 0.0, "{t}");
            if !(0.1..=0.3).contains(&t) {
                assert_eq!(m.mass_source(0, t), 0.0);
            }
        }
        assert!(m.gap_of(0, 0.2) > 0.99e-4 && m.lambda(0, 0.2) == 0.0);
        assert!(m.lambda(0, 0.05) > 0.0 && m.lambda(0, 0.35) > 0.0);
        // the mass equation with its source, by differences of q*
        let d = 1e-5;
        let t = 0.18;
        let q = |t: f64| m.q(0, t);
        let (qd, qdd) = (
            (q(t + d) - q(t - d)) / (2.0 * d),
            (q(t + d) - 2.0 * q(t) + q(t - d)) / (d * d),
        );
        let CarrierRole::Mass {
            m: mm,
            k,
            c: cs,
            f0,
        } = m.role(0)
        else {
            panic!()
        };
        let residual = mm * qdd + cs * qd + k * q(t) - (f0 - m.lambda(0, t) + m.mass_source(0, t));
        assert!(residual.abs() < 1e-4 * f0.abs(), "{residual}");
    }

    #[test]
    fn a_unilateral_contact_that_would_open_is_refused() {
        let b = beam(Support::Pinned, Support::Pinned);
        let mut c = mass_carrier(SpeedProfile::Constant { value: 3.0 });
        c.kind = CarrierKind::MassSpring {
            mass: 0.5,
            stiffness: 200.0,
            damping: 0.0,
            preload: 0.0,
        };
        let mut s = spec(None);
        s.terms[0].amplitude = 0.5;
        let e = Manufactured::new(
            &s,
            Setting {
                beam: &b,
                carriers: &[c],
                contact: ContactKind::Unilateral,
                g: 9.81,
                t_end: 0.4,
                steps: 100,
                droppers: &[],
                attachments: &[],
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("manufactured.term") && e.contains("λ*"), "{e}");
    }

    /// The bundled two-wire scene (`scenes/verify/mms_two_wires.toml`).
    const TWO_WIRES: &str = include_str!("../../scenes/verify/mms_two_wires.toml");

    /// Round-off of O(1) shapes times a correction solved to 1e-11.
    const ZERO: f64 = 1e-12;

    #[test]
    fn the_messenger_motion_meets_its_supports_and_the_droppers_weights_give_their_force() {
        let sc = crate::resolve::resolve_scene(TWO_WIRES, &[]).unwrap();
        let m = sc.manufactured.as_ref().unwrap();
        assert!(m.moves_messenger() && m.droppers() == 4);
        let d = 1e-4;
        for t in [0.03, 0.11, 0.2] {
            // pinned at 0, 1, 2 m; moment-free at the two ends (W3)
            for x in [0.0, 1.0, 2.0] {
                assert!(m.v_m(x, t).abs() < ZERO, "v_m({x}, {t}) = {}", m.v_m(x, t));
            }
            for (c, x) in [(0.0, d), (2.0, 2.0 - d)] {
                let vxx = (m.v_m(x, t) - 2.0 * m.v_m(c, t) + m.v_m(2.0 * c - x, t)) / (d * d);
                // v is odd about a pinned, moment-free end: the central
                // second difference there is round-off
                assert!(vxx.abs() < 1e-3, "v_m'' at {c}: {vxx}");
            }
            assert!(m.v_m(0.5, t).abs() > 1e-5, "the messenger moves");
            // Σ c_k(t) w_k = −N_d*(t), each dropper
            let k = m.source_count();
            let (mut c, mut w) = (vec![0.0; k], vec![0.0; k]);
            m.source_coefficients(t, &mut c);
            for dr in 0..m.droppers() {
                m.dropper_weights(dr, &mut w);
                let load: f64 = c.iter().zip(&w).map(|(a, b)| a * b).sum();
                let n = m.dropper_force(dr, t);
                assert!((load + n).abs() < 1e-12 * n.abs(), "{load} {n}");
            }
            // the messenger's parts are its own operator on v_m*
            let x = 0.63;
            let mut shapes = vec![0.0; k];
            m.source_shapes_on(Line::Messenger, x, &mut shapes);
            let p: f64 = shapes.iter().zip(&c).map(|(a, b)| a * b).sum();
            let v = |x: f64, t: f64| m.v_m(x, t);
            let h = 1e-3;
            let vtt = (v(x, t + h) - 2.0 * v(x, t) + v(x, t - h)) / (h * h);
            let vxx = (v(x + h, t) - 2.0 * v(x, t) + v(x - h, t)) / (h * h);
            let vxxxx = (v(x + 2.0 * h, t) - 4.0 * v(x + h, t) + 6.0 * v(x, t) - 4.0 * v(x - h, t)
                + v(x - 2.0 * h, t))
                / h.powi(4);
            // ρA_m = 1, EI_m = 2, T_m = 50 (the scene's)
            let fd = vtt + 2.0 * vxxxx - 50.0 * vxx;
            // the fourth difference loses ε|v|/h⁴ ≈ 1e-5 and truncation h²
            assert!((fd - p).abs() < 1e-3 * p.abs().max(1.0), "{p} {fd}");
        }
    }

    /// Central differences of the attachment's v* in time (δ = 1e-4 s):
    /// truncation δ²·(third/fourth derivative) ≈ 1e-8·(2π·8)⁴ ≈ 6e-3 of
    /// |v| for the 8 Hz term at most, so 1e-2 relative separates a right
    /// weight from a missing term (each is ≥ 10 % of the force here).
    const ATTACHMENT_FD_REL: f64 = 1e-2;

    /// The bundled attachment scene (`scenes/verify/mms_attachments.toml`).
    const ATTACHMENTS: &str = include_str!("../../scenes/verify/mms_attachments.toml");

    #[test]
    fn the_attachments_weights_give_their_force_and_the_rate_parts_are_v_t() {
        let sc = crate::resolve::resolve_scene(ATTACHMENTS, &[]).unwrap();
        let m = sc.manufactured.as_ref().unwrap();
        assert_eq!(m.attachments(), 2);
        // two terms: T̂'', T̂ and T̂' parts each, no constant part
        assert_eq!(m.source_count(), 6);
        let k = m.source_count();
        let (mut c, mut w) = (vec![0.0; k], vec![0.0; k]);
        let d = 1e-4;
        for t in [0.03, 0.11, 0.2] {
            m.source_coefficients(t, &mut c);
            for (a, (xa, ma, ca, ka)) in [(0.7, 0.2, 3.0, 300.0), (1.5, 0.3, 2.0, 200.0)]
                .into_iter()
                .enumerate()
            {
                assert_eq!(m.attachment_at(a), xa);
                m.attachment_weights(a, &mut w);
                let load: f64 = c.iter().zip(&w).map(|(a, b)| a * b).sum();
                let v = |t: f64| m.v(xa, t);
                let vt = (v(t + d) - v(t - d)) / (2.0 * d);
                let vtt = (v(t + d) - 2.0 * v(t) + v(t - d)) / (d * d);
                let fd = ma * vtt + ca * vt + ka * v(t);
                assert!(
                    (load - fd).abs() < ATTACHMENT_FD_REL * fd.abs(),
                    "attachment {a} at {t}: {load} {fd}"
                );
                assert!((load + m.attachment_force(a, t)).abs() < 1e-12 * load.abs());
            }
        }
    }

    /// The two-wire scene with dashpots on its droppers: −N_d* from the
    /// weights is k_d e_d* + c_d ė_d*, ė_d* by central differences.
    #[test]
    fn a_damped_dropper_s_weights_carry_its_dashpot() {
        let damped = TWO_WIRES.replace("linear = true", "linear = true\ndamping = 5.0");
        let sc = crate::resolve::resolve_scene(&damped, &[]).unwrap();
        let m = sc.manufactured.as_ref().unwrap();
        let k = m.source_count();
        // two contact terms and one messenger term: 3 × (T̂'', T̂, T̂') + 1
        assert_eq!(k, 10);
        let (mut c, mut w) = (vec![0.0; k], vec![0.0; k]);
        let d = 1e-4;
        let mut dashpot_max = 0.0f64;
        for t in [0.03, 0.11, 0.2] {
            m.source_coefficients(t, &mut c);
            for dr in 0..m.droppers() {
                m.dropper_weights(dr, &mut w);
                let load: f64 = c.iter().zip(&w).map(|(a, b)| a * b).sum();
                let (x, _) = m.dropper_at(dr);
                let e = |t: f64| m.v_m(x, t) - m.v(x, t);
                let spring = 500.0 * (0.05 + e(t));
                let dashpot = 5.0 * (e(t + d) - e(t - d)) / (2.0 * d);
                dashpot_max = dashpot_max.max(dashpot.abs());
                let n = m.dropper_force(dr, t);
                assert!((load + n).abs() < 1e-12 * n.abs(), "{load} {n}");
                assert!(
                    (n - spring - dashpot).abs() < DASHPOT_FD * n.abs(),
                    "{n} {spring} {dashpot}"
                );
            }
        }
        // the dashpot is a visible share of the 25 N preload
        assert!(dashpot_max > 0.5, "{dashpot_max}");
    }

    /// A central difference of ė (δ = 1e-4 s) is off by c_d δ²/6·|e'''| ≈
    /// 5·1.7e-9·(2π·8)³·1.3e-2 ≈ 1.4e-5 N, 6e-7 of N_d* ≈ 25 N.
    const DASHPOT_FD: f64 = 1e-5;

    /// A tension-only dropper's taut check uses N_d* with the dashpot
    /// (the Kelvin–Voigt link N_d = max(0, k_d e_d + c_d ė_d)): built here
    /// from a resolved dropper with its dashpot set directly.
    #[test]
    fn the_taut_check_of_a_tension_only_dropper_counts_its_dashpot() {
        let sc = crate::resolve::resolve_scene(TWO_WIRES, &[]).unwrap();
        let spec = sc.scene.manufactured.as_ref().unwrap();
        let setting = |droppers: &[Dropper]| {
            Manufactured::new(
                spec,
                Setting {
                    beam: &sc.beam,
                    carriers: &sc.carriers,
                    contact: ContactKind::Unilateral,
                    g: 9.81,
                    t_end: 0.25,
                    steps: 2500,
                    droppers,
                    attachments: &[],
                },
            )
        };
        // every dropper tension-only with a 25 N preload: taut with springs
        // alone (12.7 N at the least, tests/mms_two_wires.rs)
        let mut droppers = sc.droppers.clone();
        for d in &mut droppers {
            d.linear = false;
        }
        setting(&droppers).unwrap();
        // with the 5 N·s/m dashpots of tests/mms_attachments.rs still taut
        for d in &mut droppers {
            d.damping = 5.0;
        }
        setting(&droppers).unwrap();
        // a dashpot whose c_d ė_d* exceeds that margin slackens one
        for d in &mut droppers {
            d.damping = 100.0;
        }
        let e = setting(&droppers).unwrap_err().to_string();
        assert!(
            e.contains(".linear`") && e.contains("N_d*") && e.contains("t = "),
            "{e}"
        );
    }
}
