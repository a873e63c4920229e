//! Studies: loops of runs over scenes. They never reach inside the integrator.

pub mod compare;
pub mod converge;
pub mod gate;
pub mod precision;
pub mod reference;
pub mod sweep;
pub mod tolerance;
