//! What a sweep point measures beyond its record: bins, encounters,
//! intervals, rank correlation, number formatting.

use super::common::*;
// ------------------------------------------------------------ measures

/// What the page reads off one run.
#[derive(Clone)]
pub(super) struct Point {
    /// Swept values.
    pub(super) values: Vec<f64>,
    /// V0/c.
    pub(super) ratio: f64,
    /// P_l (whole run).
    pub(super) pl: f64,
    /// P_l counting only the loss before x_m/L = SPAN_END.
    pub(super) pl_span: f64,
    /// x_m/L of the first loss.
    pub(super) first_loss: Option<f64>,
    /// Mean of the bin-mean forces over MID, N.
    pub(super) level: f64,
    /// Max − min of the bin-mean forces over MID, N.
    pub(super) range: f64,
    /// Whole-run force statistics, N.
    pub(super) mean: f64,
    pub(super) std: f64,
    pub(super) max: f64,
    /// x/L where the carrier first meets the wave its start launched,
    /// reflected at x = L (plain-string speed c), if before it leaves.
    pub(super) encounter: Option<f64>,
    /// The force ridge of that encounter: the x/L where the bin-mean force
    /// turns from falling to rising (its minimum over in-contact bins within
    /// RIDGE_WINDOW of the encounter), and the rise after it (N: the largest
    /// bin mean within RIDGE_WINDOW after it and before the first bin with
    /// loss, minus the minimum).
    pub(super) ridge: Option<(f64, f64)>,
    pub(super) error: Option<String>,
}

pub(super) fn bin_of(x: f64) -> usize {
    ((x * PROFILE_BINS as f64) as usize).min(PROFILE_BINS - 1)
}

pub(super) fn bin_mid(b: usize) -> f64 {
    (b as f64 + 0.5) / PROFILE_BINS as f64
}

/// Time the carrier spends in each x_m/L bin over the run, as a fraction
/// of the run (the weight of a bin's loss fraction in P_l).
pub(super) fn bin_weights(sc: &Resolved) -> Vec<f64> {
    let l = sc.beam.length;
    let m = &sc.carriers[0].motion;
    let t_end = m.time_to_leave(l).unwrap_or(f64::NAN);
    let time_at = |x: f64| {
        let (mut a, mut b) = (0.0, t_end);
        for _ in 0..80 {
            let c = 0.5 * (a + b);
            if m.position(c) < x { a = c } else { b = c }
        }
        0.5 * (a + b)
    };
    let edges: Vec<f64> = (0..=PROFILE_BINS)
        .map(|b| time_at(l * b as f64 / PROFILE_BINS as f64))
        .collect();
    edges.windows(2).map(|w| (w[1] - w[0]) / t_end).collect()
}

/// Where the carrier meets the front launched at x = 0, t = 0 after its
/// reflection at x = L: x_m(t) = 2L − c t.
pub(super) fn encounter(sc: &Resolved) -> Option<f64> {
    let l = sc.beam.length;
    let c = sc.beam.wave_speed();
    let m = &sc.carriers[0].motion;
    let t_leave = m.time_to_leave(l)?;
    let f = |t: f64| m.position(t) - (2.0 * l - c * t);
    let (mut a, mut b) = (l / c, t_leave.min(2.0 * l / c));
    if f(a) >= 0.0 || f(b) < 0.0 {
        return None;
    }
    for _ in 0..80 {
        let mid = 0.5 * (a + b);
        if f(mid) < 0.0 { a = mid } else { b = mid }
    }
    Some(m.position(0.5 * (a + b)) / l)
}

pub(super) fn measure(spec: &SweepSpec, r: &SweepRecord) -> Point {
    let sc = spec.resolve(r.index).expect("validated by the sweep");
    let ratio = r.speed_ratio.unwrap_or(f64::NAN);
    let w = bin_weights(&sc);
    let span_bins = bin_of(SPAN_END);
    let pl_span = r
        .loss_profile
        .iter()
        .zip(&w)
        .take(span_bins)
        .map(|(p, w)| p.unwrap_or(0.0) * w)
        .sum::<f64>();
    let mid: Vec<f64> = (bin_of(MID.0)..bin_of(MID.1))
        .filter_map(|b| r.force_profile.get(b).copied().flatten())
        .collect();
    let level = mid.iter().sum::<f64>() / mid.len().max(1) as f64;
    let range = mid.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        - mid.iter().copied().fold(f64::INFINITY, f64::min);
    let enc = encounter(&sc);
    let kept = |b: usize| {
        r.loss_profile.get(b).copied().flatten() == Some(0.0)
            && r.force_profile.get(b).copied().flatten().is_some()
    };
    let f = |b: usize| r.force_profile[b].unwrap_or(f64::NAN);
    let ridge = enc.filter(|&x| x <= RIDGE_LAST).and_then(|xe| {
        let turn = (0..PROFILE_BINS)
            .filter(|&b| (bin_mid(b) - xe).abs() <= RIDGE_WINDOW && kept(b))
            .min_by(|&a, &b| f(a).total_cmp(&f(b)))?;
        // up to the first bin with loss: a re-contact spike is not the ridge
        let top = (turn..PROFILE_BINS)
            .take_while(|&b| bin_mid(b) <= bin_mid(turn) + RIDGE_WINDOW && kept(b))
            .map(f)
            .fold(f64::NEG_INFINITY, f64::max);
        Some((bin_mid(turn), top - f(turn)))
    });
    Point {
        values: r.values.clone(),
        ratio,
        // the source study counts P_l in steps
        pl: r.value(&taut::quantity::LOSS_FRACTION_STEPS),
        pl_span,
        first_loss: r.quantities.get(&taut::quantity::FIRST_LOSS_POSITION),
        level,
        range,
        mean: r.value(&taut::quantity::FORCE_MEAN),
        std: r.value(&taut::quantity::FORCE_STD),
        max: r.value(&taut::quantity::FORCE_MAX),
        ridge,
        encounter: enc,
        error: r.error.clone(),
    }
}

/// Spearman's rank correlation.
pub(super) fn spearman(x: &[f64], y: &[f64]) -> f64 {
    pub(super) fn ranks(v: &[f64]) -> Vec<f64> {
        let mut idx: Vec<usize> = (0..v.len()).collect();
        idx.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
        let mut r = vec![0.0; v.len()];
        let mut i = 0;
        while i < idx.len() {
            let mut j = i;
            while j + 1 < idx.len() && v[idx[j + 1]] == v[idx[i]] {
                j += 1;
            }
            for k in i..=j {
                r[idx[k]] = 0.5 * (i + j) as f64;
            }
            i = j + 1;
        }
        r
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let n = x.len() as f64;
    let (mx, my) = (rx.iter().sum::<f64>() / n, ry.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    sxy / (sxx * syy).sqrt().max(1e-300)
}

/// Contiguous runs of grid points where `pred` holds, as value intervals.
pub(super) fn intervals(xs: &[f64], on: &[bool]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < xs.len() {
        if on[i] {
            let mut j = i;
            while j + 1 < xs.len() && on[j + 1] {
                j += 1;
            }
            out.push((xs[i], xs[j]));
            i = j + 1;
        } else {
            i += 1;
        }
    }
    out
}

/// Round to `d` significant digits and print short.
pub(super) fn g(v: f64, d: usize) -> String {
    if !v.is_finite() {
        return "—".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let r: f64 = format!("{v:.*e}", d.saturating_sub(1)).parse().unwrap_or(v);
    if (1e-4..1e6).contains(&r.abs()) {
        format!("{r}")
    } else {
        format!("{r:e}")
    }
}

pub(super) fn opt(v: Option<f64>, d: usize) -> String {
    v.map_or("—".into(), |v| g(v, d))
}

pub(super) fn show_intervals(iv: &[(f64, f64)], d: usize) -> String {
    if iv.is_empty() {
        return "none".into();
    }
    iv.iter()
        .map(|&(a, b)| {
            if a == b {
                g(a, d)
            } else {
                format!("{}–{}", g(a, d), g(b, d))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

pub(super) fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
