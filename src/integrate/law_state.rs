//! The run's contact law and what it keeps between steps (MODEL §5, §6):
//! the law at the level it works at, the contact settings, how a method's
//! multipliers are read, the multipliers and active set of the last
//! solve, and the bounds and static forces the diagnoses and a static
//! start read. Nothing here knows the beam (`physics.rs`).

use crate::contact::{Level, RunLaw};
use crate::resolve::Resolved;
use crate::scene::{CarrierKind, ContactKind, ContactSpec, Placement};

use super::chain::Chain;
use super::step_map::Multipliers;

/// Contact forces beyond this multiple of the carriers' force scale
/// (k(δ0 + L) + m g + F) are taken as a blow-up: no physical run of this model
/// comes within orders of magnitude of it.
const FORCE_BOUND_FACTOR: f64 = 1e3;

/// The contact law's state during a run (module docs).
pub(crate) struct LawState {
    /// The contact law, at the level it works at.
    pub(crate) law: RunLaw,
    /// The contact settings, saved with a failed problem.
    pub(crate) contact: ContactSpec,
    /// Where the gap condition is imposed (MODEL §5).
    pub(crate) placement: Placement,
    /// True for a bilateral contact (λ of either sign).
    pub(crate) bilateral: bool,
    /// How the method's multipliers are read.
    pub(crate) multipliers: Multipliers,
    /// The multipliers of the last solve: one per contact, then one per
    /// slack tension-only dropper row during a solve (N, or N·s).
    pub(crate) lambda: Vec<f64>,
    /// Which rows the last solve closed.
    pub(crate) active: Vec<bool>,
    /// The previous step's multipliers ([`Multipliers::Held`] only).
    held_prev: Vec<f64>,
    /// The contacts' static forces of a static start (`static_start.rs`,
    /// W7–W8), N; empty otherwise.
    pub(crate) static_forces: Vec<f64>,
    /// Largest |λ| accepted before a run is taken as diverged, N.
    pub(crate) force_bound: f64,
    /// True when the velocity-level law takes the gap's increment over the
    /// step as its rate (`System::set_increment_rates`: central
    /// difference); false for the convective rate at t_{n+1}.
    pub(crate) increment_rates: bool,
}

impl LawState {
    /// The law of `sc` for `nc` contacts and `nd` tension-only dropper
    /// rows.
    pub(crate) fn new(sc: &Resolved, nc: usize, nd: usize) -> Self {
        LawState {
            law: RunLaw::with_droppers(&sc.contact, nc, nd),
            contact: sc.contact.clone(),
            placement: sc.contact.placement,
            bilateral: sc.contact.kind == ContactKind::Bilateral,
            multipliers: Multipliers::Forces,
            lambda: vec![0.0; nc + nd],
            active: vec![false; nc + nd],
            held_prev: vec![0.0; nc + nd],
            static_forces: Vec::new(),
            force_bound: FORCE_BOUND_FACTOR * force_scale(sc).max(f64::MIN_POSITIVE),
            increment_rates: false,
        }
    }

    /// The level the contact law works at.
    pub(crate) fn level(&self) -> Level {
        self.law.level()
    }

    /// Declare how the method's multipliers are read; impulses make the
    /// law work at velocity level for the run's `nc` contacts.
    pub(crate) fn set_multipliers(&mut self, m: Multipliers, nc: usize) {
        self.multipliers = m;
        if m == Multipliers::Impulses {
            self.law.make_velocity(&self.contact, nc);
        }
    }

    /// For a method that takes impacts itself (`modal_exact` with
    /// `contact.formulation = "impact"`, `modal_impact.rs`): the law
    /// becomes the force-level rule the impact law would solve its rate
    /// problems with (Lagrange), for the `nc` contacts, and the
    /// restitution e is returned; `None` (nothing changed) for any other
    /// formulation.
    pub(crate) fn impacts_taken_by_method(&mut self, nc: usize) -> Option<f64> {
        if self.contact.formulation != crate::scene::Formulation::Impact {
            return None;
        }
        self.law = RunLaw::Force(crate::contact::law_for(&self.contact, nc));
        Some(self.contact.impact.restitution)
    }

    /// Keep the multipliers of the step just taken before the next solve
    /// replaces them ([`Multipliers::Held`]: the reported force is the
    /// mean of the two held forces around a time step).
    ///
    /// One multiplier (a run's usual case, every step) by a move, not a
    /// call to the library's `memcpy`.
    #[inline]
    pub(crate) fn hold_multipliers(&mut self) {
        if let ([held], [lambda]) = (&mut self.held_prev[..], &self.lambda[..]) {
            *held = *lambda;
            return;
        }
        self.held_prev.copy_from_slice(&self.lambda);
    }

    /// The contact force of contact `j` reported after step `step` of Δt
    /// = `dt` (s), N ([`Multipliers`]).
    #[inline]
    pub(crate) fn reported_force(&self, j: usize, step: usize, dt: f64) -> f64 {
        match self.multipliers {
            Multipliers::Forces => self.lambda[j],
            // the impulse of the step over its length; at t = 0 the
            // recorded value is the initial force itself
            Multipliers::Impulses if step > 0 => self.lambda[j] / dt,
            Multipliers::Impulses => self.lambda[j],
            // at t_{n−1}: the mean of the forces held over the steps on
            // either side; after the first step, the initial force
            Multipliers::Held if step > 1 => 0.5 * (self.lambda[j] + self.held_prev[j]),
            Multipliers::Held if step == 1 => self.held_prev[j],
            Multipliers::Held => self.lambda[j],
        }
    }
}

/// The carriers' force scale, N: the largest of k(δ0 + L) + m g (a
/// chain's: k₁(δ0 + L) + |λ₀| + F₀ + g Σm + |c_a| V²) and a moving force F, from
/// which [`LawState::force_bound`] is set.
fn force_scale(sc: &Resolved) -> f64 {
    let l = sc.beam.length;
    let mut scale: f64 = 0.0;
    for p in &sc.carriers {
        scale = scale.max(match p.kind {
            CarrierKind::MassSpring {
                mass,
                stiffness,
                preload,
                ..
            } => match p.chain {
                Some(ch) => {
                    let static_force = Chain::new(&ch, p.side.sign(), sc.g).static_force;
                    let v = p.motion.profile.cruise_speed();
                    stiffness * (preload + l)
                        + static_force.abs()
                        + (ch.uplift + ch.total_mass() * sc.g)
                        + ch.uplift_coefficient.abs() * v * v
                }
                None => stiffness * (preload + l) + mass * sc.g,
            },
            CarrierKind::Force { force } => force,
        });
    }
    scale
}
