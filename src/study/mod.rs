//! Studies: loops of runs over scenes. They never reach inside the integrator.
//!
//! What they share is here once: a run as typed changes to a base scene
//! (`variant`), time grids that nest and resampling ([`grid`]), observed
//! orders and the estimators of a numerical uncertainty ([`uncertainty`]),
//! the space discretizations
//! ([`space`]) and their level parameter ([`level`]).

pub mod compare;
pub mod converge;
pub mod cost;
pub mod cpu_time;
pub mod filter;
pub mod gate;
pub mod grid;
pub mod level;
pub mod lock;
pub mod modes;
pub mod precision;
pub mod reference;
pub mod request;
pub mod space;
pub(crate) mod standing_force;
pub mod sweep;
pub mod threads;
pub mod tolerance;
pub mod uncertainty;
pub(crate) mod variant;
pub mod verify;

/// ‖a − b‖/‖b‖ (RMS); the absolute RMS difference when b is identically 0.
pub fn relative_rms(a: &[f64], b: &[f64]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let den: f64 = b.iter().map(|y| y * y).sum();
    if den > 0.0 {
        (num / den).sqrt()
    } else {
        (num / a.len().max(1) as f64).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_rms_is_relative_to_the_second() {
        assert!((relative_rms(&[1.1, 2.2], &[1.0, 2.0]) - 0.1).abs() < 1e-12);
        assert_eq!(relative_rms(&[0.0, 0.0], &[0.0, 0.0]), 0.0);
    }
}
