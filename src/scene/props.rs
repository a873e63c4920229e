//! The plain property structs a run is built from (SI units, MODEL §1–§3,
//! §10): the beam's, each carrier's and the time's, as the scene's checks
//! resolve them (`validate.rs`).

use super::attachment::Attachment;
use super::beam::Support;
use super::carrier::Side;
use super::messenger::Messenger;
use super::motion::Motion;
use super::pantograph::ChainProps;

/// The beam's resolved properties (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct BeamProps {
    /// Span L, m.
    pub length: f64,
    /// Mass per length ρA, kg/m.
    pub rho_a: f64,
    /// Bending stiffness EI, N·m² (0 = taut string, MODEL §6).
    pub ei: f64,
    /// Axial stiffness EA, N, when `youngs_modulus` and `area` are given.
    pub ea: Option<f64>,
    /// Tension T, N.
    pub tension: f64,
    /// Support at x = 0.
    pub left: Support,
    /// Support at x = L.
    pub right: Support,
    /// Distributed load p, N/m (self-weight −ρA g when asked for, else 0).
    pub distributed_load: f64,
    /// Point attachments (`[[attachment]]`, MODEL §10): springs and lumped
    /// masses at points of the span, assembled into K and M (empty: none).
    pub attachments: Vec<Attachment>,
    /// The messenger wire (`[messenger]`, `docs/lines.md` eq. W1–W6):
    /// a second line in the same model, coupled by droppers (`None`: the
    /// contact wire alone).
    pub messenger: Option<Messenger>,
}

impl BeamProps {
    /// String wave speed c = sqrt(T/ρA), m/s (MODEL §1).
    pub fn wave_speed(&self) -> f64 {
        (self.tension / self.rho_a).sqrt()
    }

    /// Beam mass M = ρA L, kg.
    pub fn total_mass(&self) -> f64 {
        self.rho_a * self.length
    }

    /// True when EI = 0: C0 string elements, one dof per node (MODEL §6).
    pub fn is_string(&self) -> bool {
        self.ei == 0.0
    }
}

/// What a carrier is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CarrierKind {
    /// A mass on a spring (k = 0: a riding mass), MODEL §2.
    MassSpring {
        /// m, kg.
        mass: f64,
        /// k, N/m.
        stiffness: f64,
        /// c_s, N·s/m.
        damping: f64,
        /// δ0, m.
        preload: f64,
    },
    /// A constant force F, N, pressing into the beam; no mass dof.
    Force {
        /// F, N.
        force: f64,
    },
}

/// A carrier's resolved properties.
#[derive(Debug, Clone, PartialEq)]
pub struct CarrierProps {
    /// Mass–spring or force.
    pub kind: CarrierKind,
    /// A multi-mass pantograph (MODEL §10, `scene/pantograph.rs`): `kind`
    /// is then its head's mass, spring and dashpot (preload 0), and the
    /// integrators step the whole chain; `None` for every other carrier.
    pub chain: Option<ChainProps>,
    /// Side sign s (+1 below, −1 above).
    pub side: Side,
    /// Its motion along the beam.
    pub motion: Motion,
}

/// `[time]` resolved (MODEL §5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeProps {
    /// Time step Δt, s.
    pub dt: f64,
    /// The run's end time, s: as given, or when the first moving carrier
    /// leaves the beam.
    pub t_end: f64,
    /// Number of steps: floor(t_end/Δt · (1 + `STEP_COUNT_SLACK`)).
    pub steps: usize,
}
