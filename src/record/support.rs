//! The contact wire's uplift at the line's supports (`[output] supports`;
//! docs/output.md#supports): at each support x_s, the largest and smallest
//! beam displacement v(x_s, t) (positive up, m) over every recorded step,
//! and the time of the largest: the uplift the standards check at the
//! supports (EN 50318 §10, EN 50119 limits). v is the basis's own
//! interpolation r_b(x_s)ᵀ d (MODEL §4), the value a probe at x_s records.
//!
//! The uplift is also given from the support's static position
//! ([`SupportUplift::uplift`]), as the standards measure it.
//!
//! Row 0 (t = 0, the initial state) is included, as in the field and the
//! envelope (`envelope.rs`): the max over t of v, all recorded times.

use serde::Serialize;

/// The displacement's range at one support.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct SupportUplift {
    /// The support's position x_s, m.
    pub x: f64,
    /// Largest v(x_s, t), m (positive up: the uplift).
    pub v_max: f64,
    /// Smallest v(x_s, t), m.
    pub v_min: f64,
    /// The first time v reaches `v_max`, s.
    pub t_max: f64,
    /// The support's static position v_static(x_s), m: the wire at rest
    /// under its own loads (self-weight, droppers' preloads) with no
    /// carrier, every dropper taut (null when the wire is not held
    /// against rigid motion, K singular).
    pub v_static: Option<f64>,
    /// The uplift from the static position, v_max − v_static, m: what the
    /// standards read at a support (null without `v_static`).
    pub uplift: Option<f64>,
}

impl SupportUplift {
    /// No step yet at `x` (m).
    pub fn new(x: f64) -> Self {
        SupportUplift {
            x,
            v_max: f64::NEG_INFINITY,
            v_min: f64::INFINITY,
            t_max: 0.0,
            v_static: None,
            uplift: None,
        }
    }

    /// Set the static position (m) and the uplift from it.
    pub fn set_static(&mut self, v_static: Option<f64>) {
        self.v_static = v_static;
        self.uplift = v_static.map(|v| self.v_max - v);
    }

    /// Add v (m) at time t (s). A NaN never replaces a number (the step's
    /// own checks stop a run that diverges).
    pub fn push(&mut self, t: f64, v: f64) {
        if v > self.v_max {
            self.v_max = v;
            self.t_max = t;
        }
        self.v_min = self.v_min.min(v);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_time_of_the_largest_value_is_kept() {
        let mut s = SupportUplift::new(3.0);
        for (t, v) in [(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 2.0)] {
            s.push(t, v);
        }
        assert_eq!((s.v_max, s.v_min, s.t_max), (2.0, -1.0, 1.0));
    }
}
