//! Closed-form and semi-analytic references (MODEL §8), each a small struct
//! that validates its inputs and carries its own tests.

#[cfg(test)]
mod dense_fe;
pub mod fast_shapes;
pub mod mode_shapes;
pub mod modes;
pub mod moving_load;
pub mod pantograph;
#[cfg(test)]
mod periodic_supports;
pub mod rayleigh;
pub mod riding_mass;
pub mod spring_supported;
pub mod static_load;

pub use fast_shapes::FastShapes;
#[cfg(target_arch = "x86_64")]
pub(crate) use fast_shapes::{BLOCK as SHAPE_BLOCK, Blocks, BlocksAvx, BlocksAvx512};
pub use mode_shapes::{MAX_MODES, ModeShapes};
#[cfg(test)]
pub(crate) use modes::Dispersion;
pub use modes::{ClampedPinnedModes, PinnedPinnedModes};
pub use moving_load::{MovingForceBeam, MovingForceString};
pub use pantograph::{Pantograph, PantographModes, PantographStep, StepResponse, SurfaceContact};
pub use rayleigh::{DampedOscillator, Rayleigh};
pub use riding_mass::{Rider, RidingMassBeam, RidingMassHistory};
pub use spring_supported::{DiscreteSpring, SpringSupportedLine};
pub use static_load::StaticPointLoad;
