//! taut's own quantities, each defined once (MODEL §7, §12). The order of
//! [`BUILTIN`] is the order of every table's columns and rows.

use super::definition::{ErrorKind, Offer, Quantity, Window};
use crate::record::window::time_rms;

const RUN_TABLES: Offer = Offer::RUN_TABLES;
const STUDIES: Offer = Offer::RUN_TABLES
    .and(Offer::CONVERGE)
    .and(Offer::UNCERTAINTY);

/// Steps taken.
pub static STEPS: Quantity = Quantity {
    name: "steps",
    label: "steps",
    unit: "-",
    definition: "time steps the run took to reach t_end",
    window: Window::Discretization,
    count: true,
    smooth: true,
    error: ErrorKind::Exact,
    offer: RUN_TABLES,
    read: |r| Some(r.out.steps as f64),
};

/// Unknowns of the run.
pub static DOFS: Quantity = Quantity {
    name: "dofs",
    label: "unknowns",
    unit: "-",
    definition: "unknowns of the beam and carriers (degrees of freedom or modes)",
    window: Window::Discretization,
    count: true,
    smooth: true,
    error: ErrorKind::Exact,
    offer: RUN_TABLES,
    read: |r| Some(r.out.dofs as f64),
};

/// Contact switches.
pub static CONTACT_SWITCHES: Quantity = Quantity {
    name: "contact_switches",
    label: "switches",
    unit: "-",
    definition: "changes of the contact state (closed → open and open → closed) over the run",
    window: Window::Run,
    count: true,
    smooth: false,
    error: ErrorKind::Contact,
    offer: RUN_TABLES,
    read: |r| Some(r.stats.contact_switches as f64),
};

/// P_l.
pub static LOSS_FRACTION: Quantity = Quantity {
    name: "loss_fraction",
    label: "contact loss P_l",
    unit: "-",
    definition: "P_l: the time with the contact open (λ = 0) over the window [0, T], each loss and re-contact located within its step",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.stats.loss_fraction),
};

/// P_l as the source study counts it.
pub static LOSS_FRACTION_STEPS: Quantity = Quantity {
    name: "loss_fraction_steps",
    label: "P_l (steps)",
    unit: "-",
    definition: "the steps with the contact open over all steps: P_l as the source study counts it, in whole steps",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: RUN_TABLES,
    read: |r| Some(r.stats.loss_fraction_steps),
};

/// P_l's in-span part.
pub static LOSS_FRACTION_SPAN: Quantity = Quantity {
    name: "loss_fraction_span",
    label: "P_l in span",
    unit: "-",
    definition: "the part of P_l with the carrier outside the support zones: the part to quote",
    window: Window::RunSplitAtSupports,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.stats.loss_fraction_span),
};

/// P_l's part at the supports.
pub static LOSS_FRACTION_SUPPORT: Quantity = Quantity {
    name: "loss_fraction_support",
    label: "P_l at supports",
    unit: "-",
    definition: "the part of P_l with the carrier in a support zone (its arrival at a support)",
    window: Window::RunSplitAtSupports,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.stats.loss_fraction_support),
};

/// P_l in span from sustained losses.
pub static LOSS_FRACTION_SPAN_SUSTAINED: Quantity = Quantity {
    name: "loss_fraction_span_sustained",
    label: "P_l in span, ≥0.2 ms",
    unit: "-",
    definition: "the part of P_l in span from losses lasting at least 0.2 ms: the bounces after a re-contact, whose number grows as Δt falls, left out",
    window: Window::RunSplitAtSupports,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.stats.loss_fraction_span_sustained),
};

/// Loss intervals.
pub static LOSS_INTERVAL_COUNT: Quantity = Quantity {
    name: "loss_interval_count",
    label: "loss intervals",
    unit: "-",
    definition: "the number of intervals of contact loss over the run",
    window: Window::Run,
    count: true,
    smooth: false,
    error: ErrorKind::Contact,
    offer: Offer::UNCERTAINTY,
    read: |r| Some(r.stats.loss_interval_count as f64),
};

/// Where contact is first lost.
pub static FIRST_LOSS_POSITION: Quantity = Quantity {
    name: "first_loss_position",
    label: "first loss x/L",
    unit: "x/L",
    definition: "x_m/L where the contact is first lost (none when it never is)",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| r.stats.first_loss_position,
};

/// Mean contact force.
pub static FORCE_MEAN: Quantity = Quantity {
    name: "force_mean",
    label: "force mean λ",
    unit: "N",
    definition: "the time average of the contact force λ over the window [0, T] (0 where the contact is lost)",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Contact,
    offer: RUN_TABLES.and(Offer::UNCERTAINTY),
    read: |r| Some(r.stats.force.mean),
};

/// The contact force's standard deviation.
pub static FORCE_STD: Quantity = Quantity {
    name: "force_std",
    label: "force std",
    unit: "N",
    definition: "the standard deviation of λ over the window [0, T] (time-weighted, population)",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: RUN_TABLES.and(Offer::UNCERTAINTY),
    read: |r| Some(r.stats.force.std),
};

/// Smallest contact force.
pub static FORCE_MIN: Quantity = Quantity {
    name: "force_min",
    label: "force min",
    unit: "N",
    definition: "the smallest λ over the steps",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: RUN_TABLES.and(Offer::UNCERTAINTY),
    read: |r| Some(r.stats.force.min),
};

/// Largest contact force.
pub static FORCE_MAX: Quantity = Quantity {
    name: "force_max",
    label: "force max",
    unit: "N",
    definition: "the largest λ over the steps (a re-contact spike grows as Δt falls)",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: RUN_TABLES.and(Offer::UNCERTAINTY),
    read: |r| Some(r.stats.force.max),
};

/// Mean of the filtered force.
pub static FILTERED_FORCE_MEAN: Quantity = Quantity {
    name: "filtered_force_mean",
    label: "0–20 Hz force mean",
    unit: "N",
    definition: "the time average over [0, T] of λ low-pass filtered to 0–20 Hz (zero-phase Butterworth; `[analysis] band`)",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.filtered()[0]),
};

/// Standard deviation of the filtered force.
pub static FILTERED_FORCE_STD: Quantity = Quantity {
    name: "filtered_force_std",
    label: "0–20 Hz force std",
    unit: "N",
    definition: "the standard deviation of the filtered force over the window [0, T] (time-weighted, population)",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.filtered()[1]),
};

/// Smallest filtered force.
pub static FILTERED_FORCE_MIN: Quantity = Quantity {
    name: "filtered_force_min",
    label: "0–20 Hz force min",
    unit: "N",
    definition: "the smallest filtered force over the steps",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.filtered()[2]),
};

/// Largest filtered force.
pub static FILTERED_FORCE_MAX: Quantity = Quantity {
    name: "filtered_force_max",
    label: "0–20 Hz force max",
    unit: "N",
    definition: "the largest filtered force over the steps",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Contact,
    offer: STUDIES,
    read: |r| Some(r.filtered()[3]),
};

/// Largest penetration.
pub static MAX_PENETRATION: Quantity = Quantity {
    name: "max_penetration",
    label: "max penetration",
    unit: "m",
    definition: "the largest penetration max(0, −g) over the steps (round-off for Lagrange, ≈ λ/κ for penalty)",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: Offer::NONE,
    read: |r| Some(r.stats.max_penetration),
};

/// Smallest gap.
pub static MIN_GAP: Quantity = Quantity {
    name: "min_gap",
    label: "min gap",
    unit: "m",
    definition: "the smallest gap g = w − q over the steps",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: Offer::NONE,
    read: |r| Some(r.stats.min_gap),
};

/// Largest complementarity residual.
pub static MAX_GAP_FORCE_PRODUCT: Quantity = Quantity {
    name: "max_gap_force_product",
    label: "max |g·λ|",
    unit: "N·m",
    definition: "the largest |g·λ| over the steps: the complementarity residual (0 for exact Signorini)",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: Offer::NONE,
    read: |r| Some(r.stats.max_gap_force_product),
};

/// w under the carrier at the end.
pub static FINAL_W: Quantity = Quantity {
    name: "final_w",
    label: "final w",
    unit: "m",
    definition: "the beam's displacement w under the carrier at the last recorded row",
    window: Window::End,
    count: false,
    smooth: true,
    error: ErrorKind::Displacement,
    offer: Offer::NONE,
    read: |r| r.w().last().copied(),
};

/// Largest w under the carrier.
pub static DISPLACEMENT_MAX: Quantity = Quantity {
    name: "displacement_max",
    label: "w max",
    unit: "m",
    definition: "the largest displacement w under the carrier over the run (w positive into the beam), the largest sample refined by the parabola through it and its neighbours",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Displacement,
    offer: Offer::UNCERTAINTY,
    read: |r| peak(r.w(), 1.0),
};

/// Smallest w under the carrier.
pub static DISPLACEMENT_MIN: Quantity = Quantity {
    name: "displacement_min",
    label: "w min",
    unit: "m",
    definition: "the smallest displacement w under the carrier over the run, refined as the largest",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Displacement,
    offer: Offer::UNCERTAINTY,
    read: |r| peak(r.w(), -1.0).map(|v| -v),
};

/// RMS of w under the carrier.
pub static DISPLACEMENT_RMS: Quantity = Quantity {
    name: "displacement_rms",
    label: "w RMS",
    unit: "m",
    definition: "the RMS of the displacement w under the carrier over the window [0, T]",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Displacement,
    offer: Offer::UNCERTAINTY,
    read: |r| {
        let t = &r.out.history.t;
        (t.len() > 1).then(|| time_rms(t, r.w(), r.out.window_end))
    },
};

/// Largest uplift at a support.
pub static UPLIFT_MAX: Quantity = Quantity {
    name: "uplift_max",
    label: "uplift max",
    unit: "m",
    definition: "the largest upward displacement v at any support of `[output] supports` over the run (none without supports)",
    window: Window::Run,
    count: false,
    smooth: true,
    error: ErrorKind::Displacement,
    offer: Offer::UNCERTAINTY,
    read: |r| {
        r.out
            .history
            .supports
            .iter()
            .map(|s| s.v_max)
            .reduce(f64::max)
    },
};

/// taut's own quantities, in the order of every table.
pub static BUILTIN: [&Quantity; 26] = [
    &LOSS_FRACTION,
    &LOSS_FRACTION_SPAN,
    &LOSS_FRACTION_SUPPORT,
    &LOSS_FRACTION_SPAN_SUSTAINED,
    &LOSS_FRACTION_STEPS,
    &LOSS_INTERVAL_COUNT,
    &FIRST_LOSS_POSITION,
    &FORCE_MEAN,
    &FORCE_STD,
    &FORCE_MIN,
    &FORCE_MAX,
    &FILTERED_FORCE_MEAN,
    &FILTERED_FORCE_STD,
    &FILTERED_FORCE_MIN,
    &FILTERED_FORCE_MAX,
    &CONTACT_SWITCHES,
    &STEPS,
    &DOFS,
    &MAX_PENETRATION,
    &MIN_GAP,
    &MAX_GAP_FORCE_PRODUCT,
    &FINAL_W,
    &DISPLACEMENT_MAX,
    &DISPLACEMENT_MIN,
    &DISPLACEMENT_RMS,
    &UPLIFT_MAX,
];

/// The largest of `sign`·w (`sign` = ±1) over the samples, refined by the
/// parabola through the largest sample and its two neighbours (its vertex,
/// when it lies between them). A sampled maximum jumps as the sample grid
/// moves against the peak, by up to w''Δt²/8, so it converges irregularly
/// in Δt; the vertex of the parabola is a smooth function of the samples
/// and within O(Δt³) of the sampled curve's peak. At the first or last
/// sample the sample itself.
pub fn peak(w: &[f64], sign: f64) -> Option<f64> {
    let k = (0..w.len()).max_by(|&a, &b| (sign * w[a]).total_cmp(&(sign * w[b])))?;
    let y = |i: usize| sign * w[i];
    if k == 0 || k + 1 == w.len() {
        return Some(y(k));
    }
    let (a, b, c) = (y(k - 1), y(k), y(k + 1));
    let curvature = a - 2.0 * b + c;
    if curvature >= 0.0 {
        return Some(b);
    }
    // vertex of the parabola through (−1, a), (0, b), (1, c)
    let x = 0.5 * (a - c) / curvature;
    Some(b - 0.25 * (a - c) * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_peak_between_samples_is_found_to_third_order() {
        // w = cos(t − 0.3) sampled every 0.1: the vertex is near 1, the
        // largest sample is cos(0.05)
        let w: Vec<f64> = (0..10).map(|i| (i as f64 * 0.1 - 0.35f64).cos()).collect();
        let p = peak(&w, 1.0).unwrap();
        assert!((p - 1.0).abs() < 2e-4, "{p}");
        assert!(p > w.iter().copied().fold(f64::MIN, f64::max));
        let m = peak(&w.iter().map(|x| -x).collect::<Vec<_>>(), -1.0).unwrap();
        assert!((m - 1.0).abs() < 2e-4, "{m}");
        // at an end, the sample
        assert_eq!(peak(&[1.0, 0.5, 0.2], 1.0), Some(1.0));
        assert_eq!(peak(&[], 1.0), None);
    }
}
