//! The family a manufactured motion is built from (MODEL §11): polynomials,
//! sines and exponentials of one variable, and their products. Each is
//! evaluated as a [`Jet`] (value and four derivatives), exactly.

use super::jet::{Jet, ORDER};

/// One factor of a product, in a variable s (ξ = x/L in space, t in s in time).
#[derive(Debug, Clone, PartialEq)]
pub enum Factor {
    /// Σₖ cₖ sᵏ.
    Polynomial(Vec<f64>),
    /// sin(a s + φ).
    Sine {
        /// a, per unit of s.
        rate: f64,
        /// φ, rad.
        phase: f64,
    },
    /// e^{a s}.
    Exponential {
        /// a, per unit of s.
        rate: f64,
    },
}

impl Factor {
    /// Value and derivatives 1 ..= 4 at s.
    pub fn jet(&self, s: f64) -> Jet {
        match self {
            Factor::Polynomial(c) => {
                let mut out = [0.0; ORDER + 1];
                for (k, o) in out.iter_mut().enumerate() {
                    // dᵏ/dsᵏ Σ cⱼ sʲ = Σ_{j ≥ k} cⱼ j!/(j − k)! s^{j−k}, by Horner
                    let mut acc = 0.0;
                    for j in (k..c.len()).rev() {
                        let falling: f64 = ((j - k + 1)..=j).map(|i| i as f64).product();
                        acc = acc * s + c[j] * falling;
                    }
                    *o = acc;
                }
                Jet(out)
            }
            Factor::Sine { rate, phase } => {
                let (sn, cs) = (rate * s + phase).sin_cos();
                let a = *rate;
                Jet([sn, a * cs, -a * a * sn, -a * a * a * cs, a * a * a * a * sn])
            }
            Factor::Exponential { rate } => {
                let e = (rate * s).exp();
                let a = *rate;
                Jet([e, a * e, a * a * e, a * a * a * e, a * a * a * a * e])
            }
        }
    }
}

/// A product of factors (empty: the constant 1).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Product(pub Vec<Factor>);

impl Product {
    /// Value and derivatives 1 ..= 4 at s (Leibniz's rule over the factors).
    pub fn jet(&self, s: f64) -> Jet {
        self.0
            .iter()
            .fold(Jet::constant(1.0), |acc, f| acc * f.jet(s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of step δ = 1e-4 on O(1) functions: truncation
    /// δ²/6·f⁽ᵏ⁺³⁾ ≲ 1e-7 (|f⁽ᵏ⁺³⁾| ≲ 50 here) and round-off ε/δ ≈ 1e-12;
    /// 1e-6 separates a right derivative from a wrong one (O(1) off).
    const FD_TOL: f64 = 1e-6;

    fn fd_check(p: &Product, s: f64) {
        let d = 1e-4;
        let j = p.jet(s);
        for k in 0..4 {
            let f = |x: f64| p.jet(x).d(k);
            let fd = (f(s + d) - f(s - d)) / (2.0 * d);
            assert!(
                (fd - j.d(k + 1)).abs() <= FD_TOL * (1.0 + j.d(k + 1).abs()),
                "derivative {} at {s}: {} vs {fd}",
                k + 1,
                j.d(k + 1)
            );
        }
    }

    #[test]
    fn every_factor_and_a_product_differentiate_right() {
        let p = Product(vec![
            Factor::Polynomial(vec![0.5, -1.0, 2.0, 0.3, -0.7, 0.1]),
            Factor::Sine {
                rate: 2.5,
                phase: 0.4,
            },
            Factor::Exponential { rate: -0.8 },
        ]);
        for s in [0.0, 0.37, 1.0] {
            fd_check(&p, s);
            for f in &p.0 {
                fd_check(&Product(vec![f.clone()]), s);
            }
        }
        assert_eq!(Product::default().jet(0.3), Jet::constant(1.0));
    }
}
