//! The coverage study's cases: a scene, the quantity checked, where its true
//! value comes from, and the grid of starting resolutions (N₀ or J₀, Δt₀),
//! each the coarsest level of one `taut uncertainty` family.

/// Where a case's true value comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Truth {
    /// The exact modal series of a moving force on a pinned–pinned beam
    /// (MODEL §8; `taut::analytic::MovingForceBeam`): exact.
    Series,
    /// The riding mass's Galerkin solution in the exact modes with the
    /// convective terms (`taut::analytic::RidingMassBeam`), J =
    /// [`RIDING_MASS_MODES`]: no finite elements on its path.
    RidingMass,
    /// A refined run: `modal_exact` on the exact modes of the beam
    /// (`galerkin`, J = `modes`) at Δt = `dt`, an independent
    /// discretization whose own error is measured in the report.
    Refined {
        /// J.
        modes: usize,
        /// Δt, s.
        dt: f64,
    },
}

/// The riding-mass reference's modes: the cap of
/// `taut::study::reference::riding_mass_modes` (its truncation error is
/// ≈ 10× below the FE error of a mesh of J/4 elements; the finest mesh of
/// the grid below is 1600 elements).
pub const RIDING_MASS_MODES: usize = 3200;

/// One case of the study.
#[derive(Debug, Clone)]
pub struct Case {
    /// Its name in the tables.
    pub name: &'static str,
    /// The scene file, relative to the repository.
    pub scene: &'static str,
    /// Fixed overrides.
    pub set: &'static [&'static str],
    /// The quantity checked (a row of `uncertainty.csv`).
    pub quantity: &'static str,
    /// Its true value's source.
    pub truth: Truth,
    /// The starting resolutions: the level parameter (N, or J on a
    /// `galerkin` basis) and Δt₀ (s).
    pub starts: Vec<(usize, f64)>,
}

/// The reference case at V0/c = 0.8 (inside the study's loss band) on the
/// exact modes with `modal_exact`.
const BAND_MODAL_EXACT: &[&str] = &[
    "carrier.speed.cruise=119.93",
    "mesh.kind=galerkin",
    "integrator={ method = \"modal_exact\" }",
];

/// The reference case at V0/c = 0.9 on the exact modes with `modal_exact`
/// (the map's route).
const FAST_MODAL_EXACT: &[&str] = &[
    "carrier.speed.cruise=134.92",
    "mesh.kind=galerkin",
    "integrator={ method = \"modal_exact\" }",
];

/// Every pair of `levels` × `steps`.
fn grid(levels: &[usize], steps: &[f64]) -> Vec<(usize, f64)> {
    levels
        .iter()
        .flat_map(|&n| steps.iter().map(move |&dt| (n, dt)))
        .collect()
}

/// The moving force, clamped–pinned (the study's supports).
const CLAMPED: &[&str] = &["beam.left=\"clamped\"", "reference.kind=\"richardson\""];

/// The reference case at V0/c = 0.9 (in-span loss, TARGETS T3's band).
const FAST: &[&str] = &["carrier.speed.cruise=134.92"];

/// The steps Δt₀ of the smooth cases' grids, s.
const STEPS: &[f64] = &[4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5];

/// The refined truth of the P_l cases.
const REFINED_PL: Truth = Truth::Refined {
    modes: 3200,
    dt: 3.125e-6,
};

/// One row of [`cases`]: name, scene file, overrides, quantity, truth,
/// starting levels, steps, and the pairs the quick study keeps.
type Row = (
    &'static str,
    &'static str,
    &'static [&'static str],
    &'static str,
    Truth,
    &'static [usize],
    &'static [f64],
    &'static [usize],
);

/// The cases of the full study (`cargo xtask uncertainty`), or of the
/// quick one (`quick`: a few pairs of each, for a look in a minute). The
/// P_l grids start at N₀, J₀ = 200: below it the support zone (4h, 4L/J)
/// is a metre or more and the in-span P_l a different quantity
/// (docs/contact_loss.md); a start whose finest level is the truth's own
/// resolution is left out (its true error would be zero). The riding mass
/// stops at N₀ = 100: its finest mesh (800) keeps the reference's J =
/// 3200 at four modes an element.
pub fn cases(quick: bool) -> Vec<Case> {
    const MF: &str = "scenes/moving_force_beam.toml";
    const RM: &str = "scenes/riding_mass_pinned.toml";
    const REF: &str = "scenes/reference.toml";
    const PL: &str = "loss_fraction_span";
    let clamped_truth = Truth::Refined {
        modes: 3200,
        dt: 5e-6,
    };
    let quick3: &[usize] = &[0, 6, 12];
    let rows: [Row; 9] = [
        (
            "moving force, pinned–pinned",
            MF,
            &[],
            "displacement_max",
            Truth::Series,
            &[25, 50, 100, 200],
            STEPS,
            quick3,
        ),
        (
            "moving force, pinned–pinned",
            MF,
            &[],
            "displacement_rms",
            Truth::Series,
            &[25, 50, 100, 200],
            STEPS,
            quick3,
        ),
        (
            "moving force, clamped–pinned",
            MF,
            CLAMPED,
            "displacement_max",
            clamped_truth,
            &[25, 50, 100, 200],
            STEPS,
            quick3,
        ),
        (
            "riding mass, pinned–pinned",
            RM,
            &[],
            "displacement_max",
            Truth::RidingMass,
            &[25, 50, 100],
            STEPS,
            quick3,
        ),
        (
            "riding mass, pinned–pinned",
            RM,
            &[],
            "displacement_rms",
            Truth::RidingMass,
            &[25, 50, 100],
            STEPS,
            quick3,
        ),
        (
            "riding mass, pinned–pinned",
            RM,
            &[],
            "force_mean",
            Truth::RidingMass,
            &[25, 50, 100],
            STEPS,
            quick3,
        ),
        (
            "reference case V0/c = 0.9, Hermite",
            REF,
            FAST,
            PL,
            REFINED_PL,
            &[200, 400],
            &[2e-4, 1e-4, 5e-5, 2.5e-5],
            &[1],
        ),
        (
            "reference case V0/c = 0.9, modal_exact",
            REF,
            FAST_MODAL_EXACT,
            PL,
            REFINED_PL,
            &[200, 400],
            &STEPS[..4],
            &[1, 6],
        ),
        (
            "reference case V0/c = 0.8, modal_exact",
            REF,
            BAND_MODAL_EXACT,
            PL,
            REFINED_PL,
            &[200, 400],
            &STEPS[..4],
            &[2],
        ),
    ];
    rows.into_iter()
        .map(|(name, scene, set, quantity, truth, levels, steps, keep)| {
            let full = grid(levels, steps);
            Case {
                name,
                scene,
                set,
                quantity,
                truth,
                starts: if quick {
                    keep.iter().map(|&i| full[i]).collect()
                } else {
                    full
                },
            }
        })
        .collect()
}
