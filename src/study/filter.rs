//! The filtered contact force, where the studies have always found it: the
//! filter itself is the record layer's ([`crate::record::filter`]), since a
//! run's history carries the filtered force (`force_filtered`).

pub use crate::record::filter::*;
