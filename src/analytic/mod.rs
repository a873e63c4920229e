//! Closed-form and semi-analytic references (MODEL §8), each a small struct
//! that validates its inputs and carries its own tests.

pub mod static_load;

pub use static_load::StaticPointLoad;
