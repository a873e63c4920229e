//! The damping matrix C of the discretized wire (docs/lines.md §10.4,
//! eq. 10.4a):
//!
//! ```text
//!   C = α M + β K + Σ_a c_a r_a r_aᵀ
//! ```
//!
//! Rayleigh damping of the assembled M and K (attachments' masses and
//! springs included, so each of the model's modes keeps its own damping
//! ratio ζ_j = α/(2ω_j) + βω_j/2, L12) plus each attachment's dashpot c_a
//! at x_a, assembled as [`BeamModel::attach`] assembles a spring: r_a the
//! interpolation vector at x_a (MODEL §4), so C has the band of M and K.
//! In a modal basis (M = I, K = diag ω_j²) the Rayleigh part is diagonal,
//! `α + β ω_j²`; a dashpot there is refused by the resolve layer (it
//! couples the modes). No damping gives no matrix: a run without it does
//! no extra work.

use super::banded::SymBand;
use super::beam::{Basis, BeamModel};
use crate::scene::{Attachment, Rayleigh};

impl BeamModel {
    /// The damping matrix C of this model (module docs), or `None` when
    /// α = β = 0 and no attachment has a dashpot. On a modal basis the
    /// dashpots must be absent (the resolve layer refuses them).
    pub fn damping_matrix(
        &self,
        rayleigh: Rayleigh,
        attachments: &[Attachment],
    ) -> Option<SymBand> {
        let dashpots = attachments.iter().any(|a| a.damping != 0.0);
        if rayleigh.is_zero() && !dashpots {
            return None;
        }
        let mut c = self
            .mass
            .combine(rayleigh.alpha, &self.stiffness, rayleigh.beta);
        if dashpots {
            assert!(
                matches!(self.basis, Basis::Elements),
                "a dashpot on a modal basis is refused by resolve::check_damping"
            );
            for a in attachments.iter().filter(|a| a.damping != 0.0) {
                let (idx, val) = self.element_vector(a.x, false);
                for (i, vi) in idx.iter().zip(&val) {
                    for (j, vj) in idx.iter().zip(&val) {
                        if *vi != 0.0 && *vj != 0.0 {
                            c.add_entry(*i, *j, a.damping * vi * vj);
                        }
                    }
                }
            }
        }
        Some(c)
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::{Attachment, BeamProps, Rayleigh, Support};

    use super::*;

    fn props(attachments: Vec<Attachment>) -> BeamProps {
        BeamProps {
            length: 2.0,
            rho_a: 1.5,
            ei: 3.0,
            ea: None,
            tension: 10.0,
            left: Support::Pinned,
            right: Support::Clamped,
            distributed_load: 0.0,
            attachments,
        }
    }

    #[test]
    fn no_damping_is_no_matrix() {
        let b = BeamModel::new(&props(Vec::new()), 4);
        assert!(b.damping_matrix(Rayleigh::default(), &[]).is_none());
    }

    /// C = αM + βK entry by entry, and a dashpot between nodes adds
    /// c r rᵀ (rᵀ C r over a vector grows by c (rᵀr)²) without widening
    /// the band.
    #[test]
    fn rayleigh_and_a_dashpot_are_where_the_equation_puts_them() {
        let dash = Attachment {
            x: 0.7,
            stiffness: 0.0,
            mass: 0.0,
            damping: 5.0,
        };
        let b = BeamModel::new(&props(vec![dash]), 4);
        let r = Rayleigh {
            alpha: 0.3,
            beta: 2e-3,
        };
        let c0 = b.damping_matrix(r, &[]).unwrap();
        for i in 0..b.n {
            for j in 0..b.n {
                let want = 0.3 * b.mass.get(i, j) + 2e-3 * b.stiffness.get(i, j);
                assert_eq!(c0.get(i, j), want);
            }
        }
        let c1 = b.damping_matrix(r, &[dash]).unwrap();
        assert_eq!(c1.bandwidth(), b.mass.bandwidth());
        let pv = b.point_vector(0.7);
        let mut rv = vec![0.0; b.n];
        pv.scatter(1.0, &mut rv, 1, 0);
        let quad = |c: &SymBand| {
            let mut y = vec![0.0; b.n];
            c.mul_acc(&rv, 1.0, &mut y);
            y.iter().zip(&rv).map(|(a, b)| a * b).sum::<f64>()
        };
        let rr: f64 = rv.iter().map(|x| x * x).sum();
        let grown = quad(&c1) - quad(&c0);
        assert!(
            (grown - 5.0 * rr * rr).abs() < 1e-12 * 5.0 * rr * rr,
            "{grown}"
        );
    }
}
