//! The damping matrix C of the discretized wire (docs/lines.md §10.4,
//! eq. 10.4a):
//!
//! ```text
//!   C = α M + β K + Σ_a c_a r_a r_aᵀ + Σ_d c_d r_d r_dᵀ
//! ```
//!
//! Rayleigh damping of the assembled M and K (attachments' masses and
//! springs included, so each of the model's modes keeps its own damping
//! ratio ζ_j = α/(2ω_j) + βω_j/2, L12) plus each attachment's dashpot c_a
//! at x_a, assembled as `BeamModel::attach` assembles a spring: r_a the
//! interpolation vector at x_a (MODEL §4), so C has the band of M and K.
//! In a modal basis (M = I, K = diag ω_j²) the Rayleigh part is diagonal,
//! `α + β ω_j²`; a dashpot there is refused by the resolve layer (it
//! couples the modes). A linear dropper's dashpot c_d (docs/lines.md
//! eq. D11) is an attachment's for a fixed anchor; on the messenger its
//! r_d = r_c(x_d) − r_m(x_d) couples the lines (`tie_dashpots`, assembled
//! as [`BeamModel`]'s ties are). No damping gives no matrix: a run without it does
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
        self.damping_matrix_with_ties(rayleigh, attachments, &[], &[])
    }

    /// [`BeamModel::damping_matrix`] with the linear messenger droppers'
    /// dashpots `tie_dashpots` (x_d, c_d): c_d r_d r_dᵀ, r_d = r_c(x_d) −
    /// r_m(x_d) (eq. D11), and the messenger's own attachments'
    /// (`messenger_attachments`: its elastic supports' and clamps' c r_m r_mᵀ,
    /// eq. E1).
    pub fn damping_matrix_with_ties(
        &self,
        rayleigh: Rayleigh,
        attachments: &[Attachment],
        tie_dashpots: &[(f64, f64)],
        messenger_attachments: &[Attachment],
    ) -> Option<SymBand> {
        let dashpots = attachments
            .iter()
            .chain(messenger_attachments)
            .any(|a| a.damping != 0.0)
            || !tie_dashpots.is_empty();
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
                c.add_outer(&self.element_pairs(a.x), a.damping);
            }
            for &(x, cd) in tie_dashpots {
                c.add_outer(&self.tie_vector(x), cd);
            }
            for a in messenger_attachments.iter().filter(|a| a.damping != 0.0) {
                c.add_outer(&self.messenger_pairs(a.x), a.damping);
            }
        }
        Some(c)
    }
}
