//! Colours of a sweep map: colour ramps and how a cell's value becomes a
//! colour.

use plotters::prelude::*;
/// Number of distinct colours of a colour scale (and steps of its bar).
pub(super) const COLOUR_STEPS: usize = 64;

/// Colour of a cell with no value (a run that stopped with an error, a bin
/// no step fell in).
pub(super) const NO_DATA: RGBColor = RGBColor(205, 205, 205);

/// Colour maps: piecewise-linear through control points.
#[derive(Clone, Copy)]
pub(super) enum Ramp {
    /// matplotlib's viridis (perceptually uniform).
    Viridis,
    /// White at zero, then light yellow → orange → red → dark red.
    Heat,
}

impl Ramp {
    fn stops(self) -> &'static [(u8, u8, u8)] {
        match self {
            Ramp::Viridis => &[
                (68, 1, 84),
                (72, 40, 120),
                (62, 74, 137),
                (49, 104, 142),
                (38, 130, 142),
                (31, 158, 137),
                (53, 183, 121),
                (109, 205, 89),
                (180, 222, 44),
                (253, 231, 37),
            ],
            Ramp::Heat => &[
                (255, 237, 160),
                (254, 217, 118),
                (254, 178, 76),
                (253, 141, 60),
                (240, 59, 32),
                (189, 0, 38),
                (110, 0, 30),
            ],
        }
    }

    /// Colour of `f` in [0, 1], in one of COLOUR_STEPS steps (equal
    /// neighbours merge into one rectangle: files a third the size).
    pub(super) fn at(self, f: f64) -> RGBColor {
        let s = self.stops();
        let n = COLOUR_STEPS as f64;
        let f = (((f.clamp(0.0, 1.0) * n).floor()).min(n - 1.0) + 0.5) / n;
        let x = f * (s.len() - 1) as f64;
        let i = (x.floor() as usize).min(s.len() - 2);
        let w = x - i as f64;
        let mix = |a: u8, b: u8| (a as f64 + w * (b as f64 - a as f64)).round() as u8;
        RGBColor(
            mix(s[i].0, s[i + 1].0),
            mix(s[i].1, s[i + 1].1),
            mix(s[i].2, s[i + 1].2),
        )
    }
}

/// How cell values become colours.
#[derive(Clone)]
pub(super) enum Paint {
    /// A colour ramp over [lo, hi] with a colour bar; `zero_white` paints
    /// exact zeros white (and shows a white swatch on the bar).
    Scale {
        ramp: Ramp,
        lo: f64,
        hi: f64,
        zero_white: bool,
        /// Logarithmic scale (lo > 0; positive values below lo take the
        /// bottom colour).
        log: bool,
        bar_label: String,
        /// The largest value when it is above `hi` (the bar says so).
        clipped_max: Option<f64>,
    },
    /// Black where the value is > 0, white where it is 0.
    BlackWhite,
}

impl Paint {
    pub(super) fn colour(&self, v: Option<f64>) -> RGBColor {
        let Some(v) = v.filter(|v| v.is_finite()) else {
            return NO_DATA;
        };
        match self {
            Paint::BlackWhite => {
                if v > 0.0 {
                    BLACK
                } else {
                    WHITE
                }
            }
            Paint::Scale {
                ramp,
                lo,
                hi,
                zero_white,
                log,
                ..
            } => {
                if *zero_white && v == 0.0 {
                    WHITE
                } else if *log {
                    let f = (v.max(*lo).ln() - lo.ln()) / (hi.ln() - lo.ln()).max(1e-300);
                    ramp.at(f)
                } else {
                    ramp.at((v - lo) / (hi - lo).max(1e-300))
                }
            }
        }
    }
}
