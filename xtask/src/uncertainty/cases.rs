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

/// The cases of the full study (`cargo xtask uncertainty`), or of the
/// quick one (`quick`: a few pairs of each, for a look in a minute). The
/// P_l grids start at N₀, J₀ = 200: below it the support zone (4h, 4L/J)
/// is a metre or more and the in-span P_l a different quantity
/// (docs/contact_loss.md); a start whose finest level is the truth's own
/// resolution is left out (its true error would be zero).
pub fn cases(quick: bool) -> Vec<Case> {
    let pick = |full: Vec<(usize, f64)>, keep: &[usize]| -> Vec<(usize, f64)> {
        if quick {
            keep.iter().map(|&i| full[i]).collect()
        } else {
            full
        }
    };
    vec![
        Case {
            name: "moving force, pinned–pinned",
            scene: "scenes/moving_force_beam.toml",
            set: &[],
            quantity: "displacement_max",
            truth: Truth::Series,
            starts: pick(
                grid(&[25, 50, 100, 200], &[4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5]),
                &[0, 6, 12],
            ),
        },
        Case {
            name: "moving force, pinned–pinned",
            scene: "scenes/moving_force_beam.toml",
            set: &[],
            quantity: "displacement_rms",
            truth: Truth::Series,
            starts: pick(
                grid(&[25, 50, 100, 200], &[4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5]),
                &[0, 6, 12],
            ),
        },
        Case {
            name: "moving force, clamped–pinned",
            scene: "scenes/moving_force_beam.toml",
            set: CLAMPED,
            quantity: "displacement_max",
            truth: Truth::Refined {
                modes: 3200,
                dt: 5e-6,
            },
            starts: pick(
                grid(&[25, 50, 100, 200], &[4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5]),
                &[0, 6, 12],
            ),
        },
        Case {
            name: "riding mass, pinned–pinned",
            scene: "scenes/riding_mass_pinned.toml",
            set: &[],
            quantity: "displacement_max",
            truth: Truth::RidingMass,
            starts: pick(
                grid(&[25, 50, 100], &[4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5]),
                &[0, 6, 12],
            ),
        },
        Case {
            name: "riding mass, pinned–pinned",
            scene: "scenes/riding_mass_pinned.toml",
            set: &[],
            quantity: "displacement_rms",
            truth: Truth::RidingMass,
            starts: pick(
                grid(&[25, 50, 100], &[4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5]),
                &[0, 6, 12],
            ),
        },
        Case {
            name: "riding mass, pinned–pinned",
            scene: "scenes/riding_mass_pinned.toml",
            set: &[],
            quantity: "force_mean",
            truth: Truth::RidingMass,
            starts: pick(
                grid(&[25, 50, 100], &[4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5]),
                &[0, 6, 12],
            ),
        },
        Case {
            name: "reference case V0/c = 0.9, Hermite",
            scene: "scenes/reference.toml",
            set: FAST,
            quantity: "loss_fraction_span",
            truth: Truth::Refined {
                modes: 3200,
                dt: 3.125e-6,
            },
            starts: pick(grid(&[200, 400], &[2e-4, 1e-4, 5e-5, 2.5e-5]), &[1]),
        },
        Case {
            name: "reference case V0/c = 0.9, modal_exact",
            scene: "scenes/reference.toml",
            set: FAST_MODAL_EXACT,
            quantity: "loss_fraction_span",
            truth: Truth::Refined {
                modes: 3200,
                dt: 3.125e-6,
            },
            starts: pick(grid(&[200, 400], &[4e-4, 2e-4, 1e-4, 5e-5]), &[1, 6]),
        },
        Case {
            name: "reference case V0/c = 0.8, modal_exact",
            scene: "scenes/reference.toml",
            set: BAND_MODAL_EXACT,
            quantity: "loss_fraction_span",
            truth: Truth::Refined {
                modes: 3200,
                dt: 3.125e-6,
            },
            starts: pick(grid(&[200, 400], &[4e-4, 2e-4, 1e-4, 5e-5]), &[2]),
        },
    ]
}
