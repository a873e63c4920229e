//! What a verification case declares: a scene (which names its reference,
//! `[manufactured]` or `[reference]`), the ladders that refine one variable
//! with the others held fine, and, per combination it runs, the order each
//! refined variable should show and the range of Δt or h where it holds.

use serde::Serialize;

use crate::scene::{Formulation, Support};

/// The variable a ladder refines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Variable {
    /// The element size h (N doubled per level).
    #[serde(rename = "h")]
    H,
    /// The time step Δt (halved per level).
    #[serde(rename = "dt")]
    Dt,
    /// The number of modes J of a modal basis (doubled per level).
    #[serde(rename = "J")]
    J,
    /// The penalty's compliance 1/ρ (`contact.penalty.relative` = ρ
    /// doubled per level, κ = ρ/W): the penalty force against the exact
    /// contact's as the penalty stiffens (MODEL §6).
    #[serde(rename = "kappa")]
    Kappa,
}

impl Variable {
    /// `h`, `dt`, `J` (the `variable` column).
    pub fn name(self) -> &'static str {
        match self {
            Variable::H => "h",
            Variable::Dt => "dt",
            Variable::J => "J",
            Variable::Kappa => "kappa",
        }
    }

    /// What a ladder in this variable leaves fixed, for "limited by …".
    pub fn others(self) -> &'static str {
        match self {
            Variable::Dt => "the mesh (h or J)",
            Variable::H | Variable::J => "Δt",
            Variable::Kappa => "Δt and the mesh",
        }
    }
}

/// A space discretization of the matrix (`--discretizations`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Space {
    /// Hermite elements (string elements when EI = 0) on a uniform mesh.
    Hermite,
    /// Hermite elements graded toward both supports (`mesh.grading = "supports"`, ratio 4).
    Graded,
    /// The exact modes of the continuous beam.
    Galerkin,
    /// The lowest modes of a fine Hermite mesh.
    Modal,
}

impl Space {
    /// Every discretization, in table order.
    pub const ALL: [Space; 4] = [Space::Hermite, Space::Graded, Space::Galerkin, Space::Modal];

    /// `hermite`, `graded`, `galerkin`, `modal`.
    pub fn name(self) -> &'static str {
        match self {
            Space::Hermite => "hermite",
            Space::Graded => "graded",
            Space::Galerkin => "galerkin",
            Space::Modal => "modal",
        }
    }

    /// The refined space variable: h for elements, J for a modal basis.
    pub fn variable(self) -> Variable {
        match self {
            Space::Hermite | Space::Graded => Variable::H,
            Space::Galerkin | Space::Modal => Variable::J,
        }
    }
}

/// One combination the matrix runs a case under.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Combo<'a> {
    /// The method's name (a built-in `integrator.method`, a parameter set
    /// of one, `wbz(rho_inf=0.5)`, or a custom factory's).
    pub method: &'a str,
    /// The built-in method it is (its name before any parameter set);
    /// the name itself for a custom factory.
    pub family: &'a str,
    /// The generalized-α family's parameters (α_m, α_f) of a built-in
    /// member; `None` for the other methods.
    pub alphas: Option<(f64, f64)>,
    /// Its formal order in Δt ([`crate::integrate::MethodFactory::time_order`]).
    pub time_order: Option<f64>,
    /// The discretization.
    pub space: Space,
    /// The contact formulation (the scene's own for a case without contact).
    pub formulation: Formulation,
    /// The supports (left, right).
    pub supports: (Support, Support),
}

/// The quantity an order is measured on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// The beam displacement: max over time of the largest error under the
    /// carrier and at the probes (and of the mass, for a mass carrier), m.
    Displacement,
    /// The contact force of carrier 0, compared at the time the method's
    /// multiplier acts ([`crate::RunOutput::force_lag`]), N.
    Force,
}

impl Quantity {
    /// `displacement`, `force`.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Displacement => "displacement",
            Quantity::Force => "force",
        }
    }
}

/// What a combination should show when one variable is refined: every
/// row the matrix runs is judged against one of these (`judge.rs`), and a
/// `cannot` is only a refused combination or a measured share
/// ([`Expect::Limited`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Expect {
    /// The ladder's order (first to last level) lies within `tol` of
    /// `order`, its finest pair within `pair` of it (widened by the shift
    /// the measured share of the fixed variables can cause, `judge.rs`),
    /// and every pair approaches (none falls short of `order − pair` by
    /// more than `APPROACH_SLACK`).
    Order {
        /// The formal order.
        order: f64,
        /// Allowed |ladder order − order| (a named constant with its reason).
        tol: f64,
        /// Allowed |finest pair's order − order| (the successive orders'
        /// measured scatter; a named constant with its reason).
        pair: f64,
    },
    /// The formal order as a lower bound: the ladder's order at least
    /// `order − tol`, its finest pair's at least `order − pair` (the contact
    /// force in h under a moving contact, whose node kicks bound it from
    /// below and whose smooth part converges faster; in J, the truncated
    /// basis's ripple), every pair approaching as in [`Expect::Order`].
    AtLeast {
        /// The formal order.
        order: f64,
        /// Allowed shortfall of the ladder's order.
        tol: f64,
        /// Allowed shortfall of the finest pair's.
        pair: f64,
    },
    /// The order of the exact solution's own modal tail: the error of
    /// v* truncated to the J lowest modes (the exact ones for `galerkin`,
    /// the FE modes for `modal`) at the same points and times, over the same
    /// J levels — what a J-mode basis can do at best, since v*'s modal
    /// coefficients set it (`docs/verification.md`). Judged as
    /// [`Expect::Order`], each pair against the tail's own pair.
    ModalTail {
        /// Allowed |ladder order − tail order|.
        tol: f64,
        /// Allowed |finest pair − the tail's finest pair|.
        pair: f64,
    },
    /// A measured deviation from the formal order, judged against its own
    /// bounds: the finest pair's order lies in `range`, the finest error
    /// relative to the exact solution is at most `bound`, and the fixed
    /// variables make at most `DOMINANCE_LIMIT` of it. Outside
    /// them the row fails. `cause` is the measured finding.
    Known {
        /// Allowed orders (least, largest).
        range: (f64, f64),
        /// Largest finest error relative to the exact solution's largest value.
        bound: f64,
        /// The measured cause, and the command or test that measures it.
        cause: String,
    },
    /// `inner`, unless the row's own runs measure the fixed variables (or,
    /// for penalty, the penalty's compliance; or, with a prescribed loss,
    /// the loss and reattachment) making more than
    /// `DOMINANCE_LIMIT` of the finest error: then `cannot`, with
    /// the measured share and `why` that was expected.
    Limited {
        /// The expectation judged when the share is within the limit.
        inner: Box<Expect>,
        /// Why the fixed variables may dominate here.
        why: String,
        /// True when the fixed variables' error is first order, so that
        /// refining them once removes only half of it: the measured share
        /// counts twice.
        first_order: bool,
    },
    /// `inner`, except that a ladder whose error stops falling at some
    /// level (a pair's order below `STALL_ORDER`, or a run stopped on an
    /// instability) or whose contact chatters (with no prescribed loss, the
    /// runs lose contact at every level, more often at each finer one) gets
    /// the verdict
    /// `diverges` with `why`: a method whose moving contact's constraint
    /// oscillation is undamped (Newmark) diverges where a run excites it
    /// and converges at its order where none does — both are judged.
    MayDiverge {
        /// The expectation of a ladder that does not grow.
        inner: Box<Expect>,
        /// The mechanism of the divergence.
        why: String,
    },
    /// `inner`, judged on the errors after the start (t > `START_WINDOW`):
    /// a penalty contact starts unloaded (λ = 0 at zero penetration, while
    /// the exact contact carries kδ0 + mg at once), and the start jump rings
    /// the unresolved penalty spring for tens of steps, at an amplitude its
    /// method's damping sets, not h, Δt or κ. The row gives the share of
    /// the whole run's finest error that the start makes (`start_share`).
    AfterStart(Box<Expect>),
    /// Nothing declared (a method of one's own that declares no formal
    /// order): reported, with why.
    Report(String),
}

impl Expect {
    /// `self`, but `cannot` when the row's runs measure the fixed variables
    /// above the dominance limit ([`Expect::Limited`]).
    pub fn limited(self, why: impl Into<String>) -> Expect {
        Expect::Limited {
            inner: Box::new(self),
            why: why.into(),
            first_order: false,
        }
    }

    /// [`Expect::limited`] where the fixed variables' error is first order.
    pub fn limited_first_order(self, why: impl Into<String>) -> Expect {
        Expect::Limited {
            inner: Box::new(self),
            why: why.into(),
            first_order: true,
        }
    }

    /// `self`, or `diverges` where the ladder grows ([`Expect::MayDiverge`]).
    pub fn may_diverge(self, why: impl Into<String>) -> Expect {
        Expect::MayDiverge {
            inner: Box::new(self),
            why: why.into(),
        }
    }

    /// `self` judged after the start ([`Expect::AfterStart`]).
    pub fn after_start(self) -> Expect {
        Expect::AfterStart(Box::new(self))
    }
}

/// One ladder of a case: the refined variable, its levels, and the fixed
/// (fine) values of the others. Level ℓ has N = elements·2^ℓ (h), Δt =
/// dt/2^ℓ (Δt), J = modes·2^ℓ (J) or ρ = ρ₀·2^ℓ (κ, from the scene's
/// `contact.penalty.relative`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ladder {
    /// The refined variable.
    pub variable: Variable,
    /// Levels (≥ 3).
    pub levels: usize,
    /// N at level 0 (h) or fixed.
    pub elements: usize,
    /// Δt at level 0 (Δt) or fixed, s.
    pub dt: f64,
    /// J at level 0 (J) or fixed (modal kinds).
    pub modes: usize,
    /// The run's end `time.end`, s, when the ladder sets one (`None`: the scene's).
    pub end: Option<f64>,
    /// True when the reference has no error in the fixed variables (the
    /// model's own exact solution, `standing_force_modes`): no dominance
    /// run, the share is 0 by construction.
    pub fixed_exact: bool,
}

/// A declared verification case (module docs).
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// Short name (the `case` column).
    pub name: &'static str,
    /// The bundled scene file.
    pub file: &'static str,
    /// Its text.
    pub text: &'static str,
    /// One line: what it checks.
    pub about: &'static str,
    /// Support pairs it runs under (empty: the scene's own). Manufactured
    /// shapes are corrected to meet any supports.
    pub supports: &'static [(Support, Support)],
    /// Discretizations it runs under.
    pub spaces: &'static [Space],
    /// True when its carrier has a contact, so formulations vary.
    pub contact: bool,
    /// The ladders for a discretization: a Δt ladder and one in its space
    /// variable (or fewer, when the case refines one variable only).
    pub ladders: fn(Space, &Combo) -> Vec<Ladder>,
    /// The expected order of a combination, variable and quantity.
    pub expect: fn(&Combo, Variable, Quantity) -> Expect,
    /// The quantities it measures.
    pub quantities: &'static [Quantity],
    /// Part of the cut-down matrix of the default test suite.
    pub quick: bool,
    /// Built-in methods it runs only (empty: all but `skip`).
    pub only: &'static [&'static str],
    /// Built-in methods it does not run (the case says why in its docs).
    pub skip: &'static [&'static str],
}

impl Case {
    /// True when the case runs the method named `name` (a parameter set,
    /// `wbz(rho_inf=0.5)`, as its method: `family`).
    pub fn runs(&self, name: &str) -> bool {
        let name = family(name);
        (self.only.is_empty() || self.only.contains(&name)) && !self.skip.contains(&name)
    }
}

/// The method a matrix name is: `wbz` for `wbz(rho_inf=0.5)`, the name
/// itself otherwise.
pub(crate) fn family(name: &str) -> &str {
    name.split_once('(').map_or(name, |(f, _)| f)
}
