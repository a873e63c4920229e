//! A function's value and first four derivatives at one point, with the
//! product rule: what a manufactured solution needs to form its source
//! exactly (MODEL §11: `EI w''''`, `T w''`, `ρA w_tt`).

use std::ops::{Add, Mul};

/// Derivatives 0 ..= 4 kept by a [`Jet`].
pub const ORDER: usize = 4;

/// f, f', f'', f''', f'''' at one point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet(pub [f64; ORDER + 1]);

/// Binomial coefficients C(k, i) for k ≤ 4 (Leibniz's rule).
const BINOMIAL: [[f64; ORDER + 1]; ORDER + 1] = [
    [1.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 1.0, 0.0, 0.0, 0.0],
    [1.0, 2.0, 1.0, 0.0, 0.0],
    [1.0, 3.0, 3.0, 1.0, 0.0],
    [1.0, 4.0, 6.0, 4.0, 1.0],
];

impl Jet {
    /// The constant c (all derivatives 0).
    pub fn constant(c: f64) -> Self {
        Jet([c, 0.0, 0.0, 0.0, 0.0])
    }

    /// Derivative k (0 = the value).
    #[inline]
    pub fn d(&self, k: usize) -> f64 {
        self.0[k]
    }

    /// The jet of f(s) with s = x/L, as a jet in x: derivative k is scaled
    /// by L⁻ᵏ (chain rule).
    pub fn rescaled(self, length: f64) -> Self {
        let mut out = self.0;
        let mut f = 1.0;
        for v in out.iter_mut().skip(1) {
            f /= length;
            *v *= f;
        }
        Jet(out)
    }

    /// Scale every derivative by a.
    pub fn scale(self, a: f64) -> Self {
        Jet(self.0.map(|v| a * v))
    }
}

impl Mul for Jet {
    type Output = Jet;
    /// Leibniz: (fg)⁽ᵏ⁾ = Σᵢ C(k, i) f⁽ⁱ⁾ g⁽ᵏ⁻ⁱ⁾.
    fn mul(self, g: Jet) -> Jet {
        let mut out = [0.0; ORDER + 1];
        for (k, o) in out.iter_mut().enumerate() {
            for i in 0..=k {
                *o += BINOMIAL[k][i] * self.0[i] * g.0[k - i];
            }
        }
        Jet(out)
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(self, g: Jet) -> Jet {
        let mut out = self.0;
        for (o, v) in out.iter_mut().zip(g.0) {
            *o += v;
        }
        Jet(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Products of exact jets are exact up to round-off of a few terms.
    const ROUND_OFF: f64 = 1e-13;

    #[test]
    fn product_rule_of_sine_and_exponential() {
        // f = sin s, g = e^{2s} at s = 0.3: (fg)'''' by hand
        let s: f64 = 0.3;
        let f = Jet([s.sin(), s.cos(), -s.sin(), -s.cos(), s.sin()]);
        let e = (2.0 * s).exp();
        let g = Jet([e, 2.0 * e, 4.0 * e, 8.0 * e, 16.0 * e]);
        let p = f * g;
        // (e^{2s} sin s)'''' = e^{2s}(−7 sin s + 24 cos s)
        let exact = e * (-7.0 * s.sin() + 24.0 * s.cos());
        assert!((p.d(4) - exact).abs() < ROUND_OFF * exact.abs().max(1.0));
        let exact1 = e * (2.0 * s.sin() + s.cos());
        assert!((p.d(1) - exact1).abs() < ROUND_OFF);
    }

    #[test]
    fn rescaling_is_the_chain_rule() {
        let j = Jet([1.0, 2.0, 3.0, 4.0, 5.0]).rescaled(2.0);
        assert_eq!(j.0, [1.0, 1.0, 0.75, 0.5, 0.3125]);
    }
}
