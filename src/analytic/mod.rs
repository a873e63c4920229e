//! Closed-form and semi-analytic references (MODEL §8), each a small struct
//! that validates its inputs and carries its own tests.

pub mod fast_shapes;
pub mod mode_shapes;
pub mod modes;
pub mod moving_load;
pub mod riding_mass;
pub mod static_load;

pub use fast_shapes::FastShapes;
pub use mode_shapes::{MAX_MODES, ModeShapes};
pub use modes::{ClampedPinnedModes, Dispersion, PinnedPinnedModes};
pub use moving_load::{MovingForceBeam, MovingForceString};
pub use riding_mass::{RidingMassBeam, RidingMassHistory};
pub use static_load::StaticPointLoad;
