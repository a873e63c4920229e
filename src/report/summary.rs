//! `summary.json`: the resolved scene, derived figures and contact statistics.

use std::path::Path;

use serde::Serialize;

use crate::error::Result;
use crate::record::ContactStats;
use crate::run::RunOutput;
use crate::scene::{Resolved, Scene};

/// Figures derived from the scene and the run.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Derived {
    /// Mass per length ρA, kg/m.
    pub mass_per_length: f64,
    /// Bending stiffness EI, N·m².
    pub bending_stiffness: f64,
    /// Axial stiffness EA, N (null unless `youngs_modulus` and `area` are given).
    pub axial_stiffness: Option<f64>,
    /// String wave speed c = sqrt(T/ρA), m/s.
    pub wave_speed: f64,
    /// V0/c for carrier 0 (its cruise speed; null when T = 0).
    pub speed_ratio: Option<f64>,
    /// T/EA (null unless EA is known).
    pub tension_ratio: Option<f64>,
    /// Beam mass M = ρA L, kg.
    pub beam_mass: f64,
    /// Element length h, m.
    pub element_length: f64,
    /// Unknowns (beam dofs + mass dofs).
    pub dofs: usize,
    /// Steps taken.
    pub steps: usize,
    /// Time step, s.
    pub dt: f64,
    /// End time, s.
    pub end_time: f64,
    /// Element family: "hermite" or "string".
    pub elements: &'static str,
}

/// The whole `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// taut's version.
    pub taut_version: &'static str,
    /// The scene after overrides; defaults of `[contact]`, `[integrator]` and
    /// `[gravity]` are written out, optional carrier keys only when given.
    pub scene: Scene,
    /// Derived figures.
    pub derived: Derived,
    /// Contact statistics of carrier 0.
    pub contact: ContactStats,
    /// Contact statistics of every carrier, in scene order.
    pub carriers: Vec<ContactStats>,
    /// Wall-clock seconds of the run: model assembly, factorization, initial
    /// accelerations and the time loop with recording.
    pub wall_seconds: f64,
    /// Findings that make the numbers suspect (empty when none).
    pub warnings: Vec<String>,
}

impl Summary {
    /// Collect the summary of a run.
    pub fn new(sc: &Resolved, out: &RunOutput) -> Self {
        let b = &sc.beam;
        let c = b.wave_speed();
        let v0 = sc.carriers[0].motion.profile.cruise_speed();
        Summary {
            taut_version: env!("CARGO_PKG_VERSION"),
            scene: sc.scene.clone(),
            derived: Derived {
                mass_per_length: b.rho_a,
                bending_stiffness: b.ei,
                axial_stiffness: b.ea,
                wave_speed: c,
                speed_ratio: (c > 0.0).then(|| v0 / c),
                tension_ratio: b.ea.map(|ea| b.tension / ea),
                beam_mass: b.total_mass(),
                element_length: b.length / sc.elements as f64,
                dofs: out.dofs,
                steps: out.steps,
                dt: out.dt,
                end_time: out.history.t.last().copied().unwrap_or(0.0),
                elements: if b.is_string() { "string" } else { "hermite" },
            },
            contact: out.stats[0].clone(),
            carriers: out.stats.clone(),
            wall_seconds: out.wall_seconds,
            warnings: out.warnings.clone(),
        }
    }
}

/// Write `summary.json` (pretty-printed).
pub fn write_summary(path: &Path, s: &Summary) -> Result<()> {
    super::write_json(path, s)
}
