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
