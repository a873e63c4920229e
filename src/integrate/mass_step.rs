//! How a method steps the mass dofs (MODEL §2, §5, §9.1; docs/lines.md
//! P3): one rule a method — its [`Stage`] — and one driver,
//! [`MassSteps`], that applies it to every body a run has, a single mass
//! or a multi-mass pantograph (`mass_dofs.rs`). Before, each method
//! repeated its mass step for the chain (four `Chain*` steppers): the
//! method × body matrix is now a method's stage times the two bodies
//! here.
//!
//! **The rule.** Every method this crate steps solves its step for an
//! unknown u of each dof (an acceleration, a displacement increment or a
//! velocity change) with an effective matrix `A = c_m M + c_c C + c_k K`
//! over the body's dofs ([`Coefficients`]) and a right-hand side from the
//! dof's state at the start of the stage: its predictors q̃, q̇̃, and the
//! points where the dashpots and springs act ([`Predicted`]); the
//! contact pushes the head with −λ. So `u = u★ − λ A⁻¹e₁`, and the head's
//! unknown is `u₁ = u★₁ − λ/A_q` with A_q = 1/(A⁻¹)₁₁, the body's dynamic
//! stiffness seen from the contact: the [`MassPrediction`] the contact
//! problem takes. A stage says how it predicts a dof, how its load is
//! formed and how a dof is updated once u is known; the body says how A
//! is applied ([`Effective`]): a scalar division for a single mass, the
//! inverse of A (at most 3 × 3, formed once per run) for a chain.
//!
//! **State.** Each dof's state is the stage's own type ([`Dof`]): the
//! head's mirrors the contact's `State::q`, `q_dot` around a step
//! ([`MassSteps::begin`], [`MassSteps::end`]); the lower masses of a chain
//! live here. Nothing is allocated after [`MassSteps::new`].

use crate::scene::MAX_CHAIN;

use super::chain::{Chain, Mat, inverse};
use super::mass_dofs::{MassDof, MassDofs};
use super::state::State;
use super::step_map::MassPrediction;

/// The coefficients of a stage's effective matrix `A = c_m M + c_c C +
/// c_k K` (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Coefficients {
    /// c_m, on the masses.
    pub(crate) c_m: f64,
    /// c_c, on the dashpots, s.
    pub(crate) c_c: f64,
    /// c_k, on the springs, s².
    pub(crate) c_k: f64,
}

/// What a stage predicts for one dof: the parts of its end state that do
/// not depend on its unknown, and where its dashpots and springs act.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Predicted {
    /// q̃: q at the stage's end is q̃ + c_d u, m.
    pub(crate) q: f64,
    /// q̇̃: q̇ at the stage's end is q̇̃ + c_v u, m/s.
    pub(crate) q_dot: f64,
    /// The velocity the dashpots act on (C times it), m/s.
    pub(crate) c_at: f64,
    /// The displacement the springs act on (K times it), m.
    pub(crate) k_at: f64,
}

/// A dof's state as a method keeps it; the head's mirrors `State`.
pub(crate) trait Dof: Copy + Default {
    /// At rest at displacement `z` (m).
    fn rest(z: f64) -> Self;
    /// (q, q̇) of the dof, m and m/s.
    fn head(&self) -> (f64, f64);
    /// Set (q, q̇) from the contact's state.
    fn set_head(&mut self, q: f64, q_dot: f64);
}

/// One stage of a method's step of the mass dofs (module docs).
pub(crate) trait Stage {
    /// The dof state the method keeps.
    type Dof: Dof;

    /// The effective matrix's coefficients.
    fn matrix(&self) -> Coefficients;

    /// A dof's prediction from its state at the stage's start (a stage
    /// may keep a part of it in the dof for its update).
    fn predict(&self, dof: &mut Self::Dof) -> Predicted;

    /// [`Stage::predict`] of a chain's dof: the same in exact arithmetic;
    /// a stage overrides it where the chain's own stepper, before the
    /// mass dofs were one abstraction, ordered its floating-point
    /// operations differently, so that a chain's outputs keep their bits.
    #[inline]
    fn predict_in_chain(&self, dof: &mut Self::Dof) -> Predicted {
        self.predict(dof)
    }

    /// Whether a chain's head is updated, like its lower masses, with the
    /// unknown `u★₁ − λ (A⁻¹)₁₁` rather than the contact's `u★₁ − λ/A_q`
    /// (equal in exact arithmetic, A_q = 1/(A⁻¹)₁₁): Bathe's first
    /// sub-step, whose head state feeds only the chain's second sub-step,
    /// as the chain's own stepper did (bit-identical outputs).
    const CHAIN_HEAD_BY_INVERSE: bool = false;

    /// The right-hand side of a dof, from its constant force `f0` (N), its
    /// mass `m` (kg), its state, and `c_term`, `k_term` = the dof's rows of
    /// C c_at and K k_at (N).
    fn load(&self, f0: f64, m: f64, dof: &Self::Dof, c_term: f64, k_term: f64) -> f64;

    /// The dof at the stage's end, its unknown `u` known.
    fn update(&self, dof: &mut Self::Dof, predicted: &Predicted, u: f64);
}

/// A stage's effective matrix over one body (module docs).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Effective {
    /// A single mass: A_q = c_m m + c_c c + c_k k.
    Single(f64),
    /// A chain: A⁻¹, row-major.
    Chain(Mat),
}

impl Effective {
    /// The effective matrix of `coefs` over a single mass `m` or the chain
    /// `chain`.
    pub(crate) fn new(coefs: Coefficients, m: &MassDof, chain: Option<&Chain>) -> Self {
        let Coefficients { c_m, c_c, c_k } = coefs;
        match chain {
            None => Effective::Single(c_m * m.m + c_c * m.c + c_k * m.k),
            Some(ch) => Effective::Chain(inverse(ch, c_m, c_c, c_k)),
        }
    }

    /// A_q: the body's effective scalar seen from the head.
    #[cfg(test)]
    pub(crate) fn a_q(&self) -> f64 {
        match self {
            Effective::Single(a) => *a,
            Effective::Chain(inv) => 1.0 / inv[0][0],
        }
    }
}

/// One contact's body as a method steps it.
#[derive(Debug, Clone, PartialEq)]
struct Carried<D> {
    /// Each dof's state, the head first.
    dofs: [D; MAX_CHAIN],
    /// This stage's predictions.
    predicted: [Predicted; MAX_CHAIN],
    /// This stage's free unknowns u★ (a chain's; a single mass's is in
    /// its [`MassPrediction`]).
    u_star: [f64; MAX_CHAIN],
}

/// The mass dofs of a run as one method steps them (module docs): each
/// contact's body, and the predictions handed to the contact problem.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MassSteps<D> {
    bodies: Vec<Carried<D>>,
    predictions: Vec<MassPrediction>,
}

impl<D: Dof> MassSteps<D> {
    /// Every body of `masses` at rest in its static state (a chain's
    /// lower masses at [`Chain::z_start`]).
    pub(crate) fn new(masses: &MassDofs) -> Self {
        let bodies = masses
            .chains
            .iter()
            .map(|ch| {
                let mut dofs = [D::default(); MAX_CHAIN];
                if let Some(ch) = ch {
                    for (d, z) in dofs.iter_mut().zip(ch.z_start).take(ch.n) {
                        *d = D::rest(z);
                    }
                }
                Carried {
                    dofs,
                    predicted: [Predicted::default(); MAX_CHAIN],
                    u_star: [0.0; MAX_CHAIN],
                }
            })
            .collect();
        MassSteps {
            bodies,
            predictions: vec![MassPrediction::default(); masses.len()],
        }
    }

    /// The effective matrices of `stage` over every body, once per run.
    pub(crate) fn effective<S: Stage<Dof = D>>(stage: &S, masses: &MassDofs) -> Vec<Effective> {
        masses
            .heads
            .iter()
            .zip(&masses.chains)
            .map(|(m, ch)| Effective::new(stage.matrix(), m, ch.as_ref()))
            .collect()
    }

    /// Contact `j`'s head dof.
    pub(crate) fn head_mut(&mut self, j: usize) -> &mut D {
        &mut self.bodies[j].dofs[0]
    }

    /// At a step's start: each head's (q, q̇) from the contact's state.
    pub(crate) fn begin(&mut self, st: &State) {
        for (j, b) in self.bodies.iter_mut().enumerate() {
            b.dofs[0].set_head(st.q[j], st.q_dot[j]);
        }
    }

    /// At a step's end: each head's (q, q̇) into the contact's state.
    pub(crate) fn end(&self, st: &mut State) {
        for (j, b) in self.bodies.iter().enumerate() {
            (st.q[j], st.q_dot[j]) = b.dofs[0].head();
        }
    }

    /// The stage's predictions of every body (module docs), for the
    /// contact problem ([`MassSteps::predictions`]); `effective` is the
    /// stage's ([`MassSteps::effective`]).
    pub(crate) fn predict<S: Stage<Dof = D>>(
        &mut self,
        stage: &S,
        effective: &[Effective],
        masses: &MassDofs,
    ) {
        let bodies = self.bodies.iter_mut().zip(&mut self.predictions);
        for (j, (b, out)) in bodies.enumerate() {
            let m = &masses.heads[j];
            *out = match (&masses.chains[j], &effective[j]) {
                (None, &Effective::Single(a_eff)) => {
                    let p = stage.predict(&mut b.dofs[0]);
                    b.predicted[0] = p;
                    let load = stage.load(m.f0, m.m, &b.dofs[0], m.c * p.c_at, m.k * p.k_at);
                    MassPrediction {
                        q: p.q,
                        q_dot: p.q_dot,
                        u: load / a_eff,
                        a_eff,
                    }
                }
                (Some(ch), Effective::Chain(inv)) => {
                    let n = ch.n;
                    let mut c_at = [0.0; MAX_CHAIN];
                    let mut k_at = [0.0; MAX_CHAIN];
                    for i in 0..n {
                        let p = stage.predict_in_chain(&mut b.dofs[i]);
                        b.predicted[i] = p;
                        (c_at[i], k_at[i]) = (p.c_at, p.k_at);
                    }
                    let mut load = [0.0; MAX_CHAIN];
                    for (i, l) in load.iter_mut().enumerate().take(n) {
                        let (c_term, k_term) = (ch.mul(&ch.c, &c_at, i), ch.mul(&ch.k, &k_at, i));
                        *l = stage.load(ch.f0[i], ch.m[i], &b.dofs[i], c_term, k_term);
                    }
                    for i in 0..n {
                        b.u_star[i] = ch.mul(inv, &load, i);
                    }
                    let p = b.predicted[0];
                    MassPrediction {
                        q: p.q,
                        q_dot: p.q_dot,
                        u: b.u_star[0],
                        a_eff: 1.0 / inv[0][0],
                    }
                }
                _ => unreachable!("a body's effective matrix is of its kind"),
            };
        }
    }

    /// The predictions of the last [`MassSteps::predict`], one per contact.
    pub(crate) fn predictions(&self) -> &[MassPrediction] {
        &self.predictions
    }

    /// After the contact problem: every dof at the stage's end, with the
    /// multipliers `lambda` (one per contact). The head's unknown is
    /// u★₁ − λ/A_q (its [`MassPrediction::unknown`]), a chain's lower
    /// masses' u★_i − λ (A⁻¹)_{i1}.
    pub(crate) fn finish<S: Stage<Dof = D>>(
        &mut self,
        stage: &S,
        effective: &[Effective],
        masses: &MassDofs,
        lambda: &[f64],
    ) {
        let bodies = self.bodies.iter_mut().zip(&self.predictions);
        for (j, (b, pred)) in bodies.enumerate() {
            let l = lambda[j];
            match (&masses.chains[j], &effective[j]) {
                (Some(_), Effective::Chain(inv)) if S::CHAIN_HEAD_BY_INVERSE => {
                    let u = b.u_star[0] - l * inv[0][0];
                    stage.update(&mut b.dofs[0], &b.predicted[0], u);
                }
                _ => stage.update(&mut b.dofs[0], &b.predicted[0], pred.unknown(l)),
            }
            if let (Some(ch), Effective::Chain(inv)) = (&masses.chains[j], &effective[j]) {
                for i in 1..ch.n {
                    let u = b.u_star[i] - l * inv[i][0];
                    stage.update(&mut b.dofs[i], &b.predicted[i], u);
                }
            }
        }
    }

    /// Contact `j`'s dof `i` (0: the head), for checks.
    #[cfg(test)]
    pub(crate) fn dof(&self, j: usize, i: usize) -> &D {
        &self.bodies[j].dofs[i]
    }

    /// Contact `j`'s dof `i`, to set a start for checks.
    #[cfg(test)]
    pub(crate) fn dof_mut(&mut self, j: usize, i: usize) -> &mut D {
        &mut self.bodies[j].dofs[i]
    }
}

/// The dof state of a method that keeps displacement, velocity and
/// acceleration (generalized-α, Moreau–Jean and central difference use
/// the first two only).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Kinematics {
    /// z (= q of the head), m.
    pub(crate) z: f64,
    /// ż, m/s (central difference: at the half step before).
    pub(crate) zd: f64,
    /// z̈, m/s².
    pub(crate) za: f64,
}

impl Dof for Kinematics {
    fn rest(z: f64) -> Self {
        Kinematics {
            z,
            ..Kinematics::default()
        }
    }

    fn head(&self) -> (f64, f64) {
        (self.z, self.zd)
    }

    fn set_head(&mut self, q: f64, q_dot: f64) {
        (self.z, self.zd) = (q, q_dot);
    }
}
