//! The support zone of `docs/contact_loss.md`: its width and the split of
//! P_l into an in-span and a support part.

// ---------------------------------------------------------------------------
// The support zone: the library's constants (taut::record::zone), with the
// width in bending lengths left free so other widths can be tried; every run
// checks that this split at 4 ℓ_b is the library's loss_fraction_span.
// ---------------------------------------------------------------------------

use taut::record::zone::SUPPORT_BENDING_LENGTHS;

/// Elements in this report's support zone. The report reproduces a study
/// made with an earlier default zone, max(4ℓ_b, 4h, 4VΔt), that followed
/// the mesh and the step; the library's zone is now 4ℓ_b alone (a length
/// of the physics), and this report keeps the old one to regenerate its
/// tables as they were measured.
pub const SUPPORT_ELEMENTS: f64 = 4.0;

/// Steps of carrier travel in this report's support zone
/// ([`SUPPORT_ELEMENTS`]).
pub const SUPPORT_STEPS: f64 = 4.0;

/// Width z (m) of the support zone at each end support, with `bending`
/// bending lengths: z = max(bending·ℓ_b, 4h, 4VΔt). ℓ_b = 0 for a string.
pub fn support_zone_with(bending: f64, ei: f64, tension: f64, h: f64, speed: f64, dt: f64) -> f64 {
    let lb = if ei > 0.0 && tension > 0.0 {
        (ei / tension).sqrt()
    } else {
        0.0
    };
    (bending * lb)
        .max(SUPPORT_ELEMENTS * h)
        .max(SUPPORT_STEPS * speed * dt)
}

/// The support zone z = max(4ℓ_b, 4h, 4VΔt), m.
pub fn support_zone(ei: f64, tension: f64, h: f64, speed: f64, dt: f64) -> f64 {
    support_zone_with(SUPPORT_BENDING_LENGTHS, ei, tension, h, speed, dt)
}

/// P_l split in two parts over the same denominator (all steps), so that
/// `in_span + support` = P_l.
#[derive(Debug, Clone, Copy)]
pub struct LossSplit {
    /// Steps with the contact open and x_m in [z, L − z], over all steps.
    pub in_span: f64,
    /// Steps with the contact open and x_m < z or x_m > L − z, over all steps.
    pub support: f64,
}

/// Split P_l of one carrier's trace (row 0 = t = 0, rows 1.. = step ends;
/// a step is located by x_m at its end) at support-zone width `zone`.
pub fn split_loss(x: &[f64], in_contact: &[bool], length: f64, zone: f64) -> LossSplit {
    let steps = in_contact.len().saturating_sub(1).max(1) as f64;
    let (mut span, mut support) = (0usize, 0usize);
    for i in 1..in_contact.len() {
        if !in_contact[i] {
            if x[i] < zone || x[i] > length - zone {
                support += 1;
            } else {
                span += 1;
            }
        }
    }
    LossSplit {
        in_span: span as f64 / steps,
        support: support as f64 / steps,
    }
}

/// The two parts are sums of 1/steps over disjoint sets of steps; their sum
/// differs from the library's count/steps by round-off only.
pub(super) const PARTS_SUM_TOLERANCE: f64 = 1e-12;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    pub(super) fn zone_takes_the_largest_of_its_three_widths() {
        // reference beam: ℓ_b = sqrt(129.2/30000) = 0.0656 m
        let (ei, t): (f64, f64) = (129.2, 30000.0);
        let lb = (ei / t).sqrt();
        assert_eq!(support_zone(ei, t, 0.03125, 134.92, 2.5e-5), 4.0 * lb);
        assert_eq!(support_zone(ei, t, 0.125, 134.92, 2.5e-5), 0.5);
        assert_eq!(support_zone(ei, t, 0.01, 100.0, 1e-3), 0.4);
        // a string has no bending length
        assert_eq!(support_zone(0.0, t, 0.01, 100.0, 1e-5), 0.04);
    }

    #[test]
    pub(super) fn parts_add_up_and_fall_where_the_zone_says() {
        // L = 10, z = 1: rows 1..=6 at x = 0.5 (support), 2, 5, 8 (span), 9.5, 9.9 (support)
        let x = [0.0, 0.5, 2.0, 5.0, 8.0, 9.5, 9.9];
        let c = [true, false, true, false, false, false, true];
        let s = split_loss(&x, &c, 10.0, 1.0);
        assert_eq!(s.support, 2.0 / 6.0);
        assert_eq!(s.in_span, 2.0 / 6.0);
    }
}
