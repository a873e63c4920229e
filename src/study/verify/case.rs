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
}

impl Variable {
    /// `h`, `dt`, `J` (the `variable` column).
    pub fn name(self) -> &'static str {
        match self {
            Variable::H => "h",
            Variable::Dt => "dt",
            Variable::J => "J",
        }
    }

    /// What a ladder in this variable leaves fixed, for "limited by …".
    pub fn others(self) -> &'static str {
        match self {
            Variable::Dt => "the mesh (h or J)",
            Variable::H | Variable::J => "Δt",
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
    /// The method's name (a built-in `integrator.method` or a custom factory's).
    pub method: &'a str,
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

/// What a combination should show when one variable is refined.
#[derive(Debug, Clone, PartialEq)]
pub enum Expect {
    /// The observed order lies within `tol` of `order`.
    Order {
        /// The formal order.
        order: f64,
        /// Allowed |observed − order| (a named constant with its reason).
        tol: f64,
    },
    /// A known deviation from the formal order, reported but not failed:
    /// `order` is the formal one, `why` the measured finding and what is
    /// known of its cause.
    Known {
        /// The formal order.
        order: f64,
        /// The finding.
        why: String,
    },
    /// The combination cannot show an order in this variable, and why.
    Cannot(String),
    /// The order of the exact solution's own modal tail: the error of
    /// v* truncated to the J lowest modes (the exact ones for `galerkin`,
    /// the FE ones for `modal`) at the same points and times, over the same
    /// J levels — what a J-mode basis can do at best, since v*'s modal
    /// coefficients set it (`docs/verification.md`). Within `tol` of it.
    ModalTail {
        /// Allowed |observed − tail order|.
        tol: f64,
    },
    /// Nothing declared (a custom method without a formal order, or a
    /// quantity whose order depends on the solution): reported, with why.
    Report(String),
}

/// One ladder of a case: the refined variable, its levels, and the fixed
/// (fine) values of the others. Level ℓ has N = elements·2^ℓ (h), Δt =
/// dt/2^ℓ (Δt) or J = modes·2^ℓ (J).
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
    /// True when the case runs the method named `name`.
    pub fn runs(&self, name: &str) -> bool {
        (self.only.is_empty() || self.only.contains(&name)) && !self.skip.contains(&name)
    }
}
