//! The 1-D studies (TARGETS T3–T6): their runs, sections and ridges.

use super::{common::*, measures::*};
// ------------------------------------------------------------ 1-D targets

/// A 1-D target of TARGETS.
pub(super) struct Target1 {
    pub(super) id: &'static str,
    pub(super) fig: &'static str,
    pub(super) title: &'static str,
    /// The sweep axis (key=start:stop:count).
    pub(super) axis: &'static str,
    /// Axis name in the text.
    pub(super) symbol: &'static str,
    /// Digits of the axis values in the text.
    pub(super) digits: usize,
    /// The published statement (TARGETS).
    pub(super) published: &'static str,
    /// Published trends of (level, fluctuation): +1 grows, −1 falls.
    pub(super) trends: Option<(i32, i32)>,
    /// Published parameter range of the loss near the right support.
    pub(super) loss: Option<(f64, f64)>,
}

pub(super) const TARGETS_1D: [Target1; 4] = [
    Target1 {
        id: "T3",
        fig: "Fig. 8",
        title: "speed sweep",
        axis: "speed_ratio=0.4:1.3:46",
        symbol: "V0/c",
        digits: 3,
        published: "V0/c from 0.4 to 1.3. The first encounter with the reflected wave gives a force ridge that is largest near V0/c ≈ 1; contact is lost near the right support for V0/c ≈ 0.7–0.9 and kept for V0/c < 0.7 or > 0.9.",
        trends: None,
        loss: Some((0.7, 0.9)),
    },
    Target1 {
        id: "T4",
        fig: "Fig. 9",
        title: "tension sweep",
        axis: "tension_ratio=0.001:0.002:41",
        symbol: "T/EA",
        digits: 4,
        published: "V0 = 100 m/s, T/EA from 0.001 to 0.002. c = 122.7 m/s at T/EA = 0.001; mean force and its fluctuation fall as tension rises; contact loss near the right support for T/EA ≈ 0.0010–0.0012.",
        trends: Some((-1, -1)),
        loss: Some((0.001, 0.0012)),
    },
    Target1 {
        id: "T5",
        fig: "Fig. 10",
        title: "mass sweep",
        axis: "mass_ratio=0.001:0.04:40",
        symbol: "m/M",
        digits: 3,
        published: "V0 = 100 m/s, m/M from 0.001 to 0.040. Force level and fluctuation grow with the mass; contact loss appears at the larger masses.",
        trends: Some((1, 1)),
        loss: None,
    },
    Target1 {
        id: "T6",
        fig: "Fig. 11",
        title: "spring stiffness sweep",
        axis: "stiffness_ratio=0.1:4:40",
        symbol: "k/(T/L)",
        digits: 3,
        published: "V0 = 100 m/s, k/(T/L) from 0.1 to 4 (δ0 fixed). Force level grows with stiffness, with rapid variation near the support at high stiffness but no loss there; contact loss for k/(T/L) ≈ 0.1–1.7.",
        trends: Some((1, 0)),
        loss: Some((0.1, 1.7)),
    },
];

/// Results of one 1-D target at one resolution.
pub(super) struct Run1 {
    pub(super) points: Vec<Point>,
    pub(super) xs: Vec<f64>,
    pub(super) step: f64,
}

impl Run1 {
    pub(super) fn span_loss(&self) -> Vec<(f64, f64)> {
        let on: Vec<bool> = self.points.iter().map(|p| p.pl_span > 0.0).collect();
        intervals(&self.xs, &on)
    }
    /// The longest interval of loss in the span (the first of equals).
    pub(super) fn main_band(&self) -> Option<(f64, f64)> {
        let count = |iv: &(f64, f64)| self.xs.iter().filter(|x| (iv.0..=iv.1).contains(x)).count();
        let mut best: Option<((f64, f64), usize)> = None;
        for iv in self.span_loss() {
            let n = count(&iv);
            if best.is_none_or(|(_, m)| n > m) {
                best = Some((iv, n));
            }
        }
        best.map(|b| b.0)
    }
    pub(super) fn any_loss(&self) -> Vec<(f64, f64)> {
        let on: Vec<bool> = self.points.iter().map(|p| p.pl > 0.0).collect();
        intervals(&self.xs, &on)
    }
    pub(super) fn rho(&self, f: fn(&Point) -> f64) -> f64 {
        let y: Vec<f64> = self.points.iter().map(f).collect();
        spearman(&self.xs, &y)
    }
}

pub(super) fn run_1d(clock: &Clock, t: &Target1, res: Res, maps: &Path) -> Run1 {
    let spec = SweepSpec {
        scene_text: reference_text(),
        set: res_sets(res),
        axes: vec![Axis::parse(t.axis, false).expect("valid axis")],
        check_refinement: false,
        paired: false,
        tolerance: None,
    };
    let name = format!("{}_{}", t.id.to_lowercase(), res.tag);
    let recs = run_sweep(clock, &name, &spec);
    let title = |what: &str| format!("{} {} ({}): {what}, {}", t.id, t.title, t.fig, res.label);
    write_force_map(
        &maps.join(format!("{name}_force.svg")),
        &spec,
        &recs,
        Some(&title("mean contact force")),
    )
    .expect("force map");
    write_loss_map(
        &maps.join(format!("{name}_loss.svg")),
        &spec,
        &recs,
        Some(&title("contact loss")),
    )
    .expect("loss map");
    let points: Vec<Point> = recs.iter().map(|r| measure(&spec, r)).collect();
    let a = &spec.axes[0];
    Run1 {
        xs: points.iter().map(|p| p.values[0]).collect(),
        step: (a.stop - a.start).abs() / (a.count.max(2) - 1) as f64,
        points,
    }
}

pub(super) fn verdict(ok: bool) -> &'static str {
    if ok { "agrees" } else { "**differs**" }
}

pub(super) fn write_1d(md: &mut String, t: &Target1, s: &Run1, c: &Run1) {
    let d = t.digits;
    let _ = writeln!(md, "## {} — {} (study {})\n", t.id, t.title, t.fig);
    let _ = writeln!(md, "**Published.** {}\n", t.published);
    let _ = writeln!(
        md,
        "**taut.** `taut sweep scenes/reference.toml --vary {}` at both resolutions ({} runs each).\n",
        t.axis,
        s.points.len()
    );
    let grid = (s.xs[0], *s.xs.last().unwrap());
    let _ = writeln!(
        md,
        "| feature | published | {} | {} | survives refinement |",
        STUDY.label, CONVERGED.label
    );
    let _ = writeln!(md, "|---|---|---|---|---|");
    // loss
    if let Some(pubr) = t.loss {
        let tol = BORDER_STEPS * s.step.max(c.step) + 1e-12;
        let _ = writeln!(
            md,
            "| {} with contact loss in the span (x_m/L < {SPAN_END}) | {}–{} | {} | {} | — |",
            t.symbol,
            g(pubr.0, d),
            g(pubr.1, d),
            show_intervals(&s.span_loss(), d),
            show_intervals(&c.span_loss(), d),
        );
        // the main band: the longest run of grid points with loss in the span
        let lo_ok = |r: &Run1| {
            r.main_band()
                .is_some_and(|(a, _)| (a - pubr.0).abs() <= tol)
        };
        let lo_show = |r: &Run1| opt(r.main_band().map(|b| b.0), d);
        let _ = writeln!(
            md,
            "| lower border of the main loss band, {} | {}{} | {} ({}) | {} ({}) | {} |",
            t.symbol,
            g(pubr.0, d),
            if (pubr.0 - grid.0).abs() <= 1e-12 {
                " (the grid's start)"
            } else {
                ""
            },
            lo_show(s),
            verdict(lo_ok(s)),
            lo_show(c),
            verdict(lo_ok(c)),
            survive(lo_ok(s), lo_ok(c))
        );
        let hi_ok = |r: &Run1| {
            r.main_band()
                .is_some_and(|(_, b)| b < grid.1 && (b - pubr.1).abs() <= tol)
        };
        let hi_show = |r: &Run1| match r.main_band() {
            Some((_, b)) if b < grid.1 => format!("{} (kept above)", g(b, d)),
            Some(_) => format!("none: loss to the grid's end, {}", g(grid.1, d)),
            None => "—".into(),
        };
        let _ = writeln!(
            md,
            "| upper border of the main loss band, {} (contact kept above it) | {} | {} ({}) | {} ({}) | {} |",
            t.symbol,
            g(pubr.1, d),
            hi_show(s),
            verdict(hi_ok(s)),
            hi_show(c),
            verdict(hi_ok(c)),
            survive(hi_ok(s), hi_ok(c))
        );
    } else {
        let (ms, mc) = (s.span_loss(), c.span_loss());
        // "appears at the larger masses": one interval reaching the grid's end
        let ok = |iv: &[(f64, f64)]| matches!(iv, [(a, b)] if *b == grid.1 && *a > grid.0);
        let _ = writeln!(
            md,
            "| {} with contact loss in the span (x_m/L < {SPAN_END}) | the larger values | {} ({}) | {} ({}) | {} |",
            t.symbol,
            show_intervals(&ms, d),
            verdict(ok(&ms)),
            show_intervals(&mc, d),
            verdict(ok(&mc)),
            survive(ok(&ms), ok(&mc))
        );
    }
    let _ = writeln!(
        md,
        "| {} with any contact loss (P_l > 0) | — | {} | {} | — |",
        t.symbol,
        show_intervals(&s.any_loss(), d),
        show_intervals(&c.any_loss(), d)
    );
    let first = |r: &Run1| {
        let v: Vec<f64> = r
            .points
            .iter()
            .filter(|p| p.pl_span > 0.0)
            .filter_map(|p| p.first_loss)
            .collect();
        let (lo, hi) = (
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        match v.len() {
            0 => "—".to_string(),
            _ if lo == hi => g(lo, 3),
            _ => format!("{}–{}", g(lo, 3), g(hi, 3)),
        }
    };
    let _ = writeln!(
        md,
        "| x_m/L of the first loss, over the runs with loss in the span | near the right support | {} | {} | — |",
        first(s),
        first(c)
    );
    if let Some((lt, ft)) = t.trends {
        for (what, sign, f) in [
            (
                "force level (mean over x_m/L 0.2–0.8)",
                lt,
                (|p: &Point| p.level) as fn(&Point) -> f64,
            ),
            (
                "fluctuation (max − min of bin means over 0.2–0.8)",
                ft,
                |p: &Point| p.range,
            ),
            ("whole-run mean force", lt, |p: &Point| p.mean),
            ("whole-run force std (spikes included)", ft, |p: &Point| {
                p.std
            }),
        ] {
            let (rs, rc) = (s.rho(f), c.rho(f));
            let word = match sign {
                1 => "grows",
                -1 => "falls",
                _ => "—",
            };
            let ok = |r: f64| sign != 0 && r.signum() as i32 == sign && r.abs() >= TREND_RHO;
            let first_last = |r: &Run1| {
                format!(
                    "{} → {} N",
                    g(f(&r.points[0]), 3),
                    g(f(r.points.last().unwrap()), 3)
                )
            };
            let _ = writeln!(
                md,
                "| {what} vs {} | {word} | {}, ρ = {:.2}{} | {}, ρ = {:.2}{} | {} |",
                t.symbol,
                first_last(s),
                rs,
                if sign != 0 {
                    format!(" ({})", verdict(ok(rs)))
                } else {
                    String::new()
                },
                first_last(c),
                rc,
                if sign != 0 {
                    format!(" ({})", verdict(ok(rc)))
                } else {
                    String::new()
                },
                if sign != 0 {
                    survive(ok(rs), ok(rc))
                } else {
                    "—".into()
                }
            );
        }
    }
    if t.id == "T3" {
        t3_extra(md, s, c);
    }
    if t.id == "T4" {
        let spec = SweepSpec {
            scene_text: reference_text(),
            set: vec![],
            axes: vec![Axis::parse("tension_ratio=0.001:0.001:1", false).unwrap()],
            check_refinement: false,
            paired: false,
            tolerance: None,
        };
        let sc = spec.resolve(0).unwrap();
        let cw = sc.beam.wave_speed();
        let ok = (cw - 122.7).abs() < 0.05;
        let _ = writeln!(
            md,
            "| c at T/EA = 0.001 (m/s) | 122.7 | {} ({}) | same (no resolution) | {} |",
            g(cw, 5),
            verdict(ok),
            if ok { "yes" } else { "—" }
        );
    }
    if t.id == "T6" {
        // near the support at high stiffness: rapid variation, no loss
        let near = |r: &Run1| {
            let hi: Vec<&Point> = r.points.iter().filter(|p| p.values[0] >= 3.0).collect();
            let lost = hi.iter().filter(|p| p.pl > 0.0).count();
            let lost_span = hi.iter().filter(|p| p.pl_span > 0.0).count();
            (hi.len(), lost, lost_span)
        };
        let (ns, ls, lss) = near(s);
        let (nc, lc, lsc) = near(c);
        let _ = writeln!(
            md,
            "| loss in the span at k/(T/L) ≥ 3 | none | {lss} of {ns} runs (any loss: {ls}) ({}) | {lsc} of {nc} runs (any loss: {lc}) ({}) | {} |",
            verdict(lss == 0),
            verdict(lsc == 0),
            survive(lss == 0, lsc == 0)
        );
    }
    let _ = writeln!(md);
    let id = t.id.to_lowercase();
    let _ = writeln!(
        md,
        "| {} | {} |\n|---|---|\n| ![](reproduction/{id}_study_force.svg) | ![](reproduction/{id}_refined_force.svg) |\n| ![](reproduction/{id}_study_loss.svg) | ![](reproduction/{id}_refined_loss.svg) |\n",
        STUDY.label, CONVERGED.label
    );
    // full table
    let _ = writeln!(
        md,
        "<details><summary>Every run of {} (study-like / refined)</summary>\n",
        t.id
    );
    let _ = writeln!(
        md,
        "| {} | V0/c | P_l | P_l,span | first loss x_m/L | level (N) | fluctuation (N) | mean (N) | max (N) |",
        t.symbol
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|");
    for (a, b) in s.points.iter().zip(&c.points) {
        let pair = |x: String, y: String| format!("{x} / {y}");
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |{}",
            g(a.values[0], d),
            g(a.ratio, 3),
            pair(g(a.pl, 3), g(b.pl, 3)),
            pair(g(a.pl_span, 3), g(b.pl_span, 3)),
            pair(opt(a.first_loss, 3), opt(b.first_loss, 3)),
            pair(g(a.level, 3), g(b.level, 3)),
            pair(g(a.range, 3), g(b.range, 3)),
            pair(g(a.mean, 3), g(b.mean, 3)),
            pair(g(a.max, 3), g(b.max, 3)),
            match (&a.error, &b.error) {
                (None, None) => String::new(),
                (x, y) => format!(" error: {x:?} / {y:?}"),
            }
        );
    }
    let _ = writeln!(md, "\n</details>\n");
}

pub(super) fn survive(a: bool, b: bool) -> String {
    match (a, b) {
        (true, true) => "yes".into(),
        (false, true) => "appears only when refined".into(),
        (true, false) => "**no**: gone when refined".into(),
        (false, false) => "(differs at both)".into(),
    }
}

/// The ridge's onset lag behind the predicted encounter, x_m/L: median and
/// range over the runs with V0/c ≤ 0.9, and the count.
pub(super) fn ridge_lag(r: &Run1) -> Option<(f64, f64, f64, usize)> {
    let d: Vec<f64> = r
        .points
        .iter()
        .filter(|p| p.ratio <= 0.9)
        .filter_map(|p| Some(p.ridge?.0 - p.encounter?))
        .collect();
    if d.is_empty() {
        return None;
    }
    let lo = d.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Some((median(d.clone()), lo, hi, d.len()))
}

/// The V0/c whose encounter ridge rises most: (rise, x_m/L of onset, V0/c).
pub(super) fn ridge_peak(r: &Run1) -> Option<(f64, f64, f64)> {
    r.points
        .iter()
        .filter_map(|p| p.ridge.map(|(x, h)| (h, x, p.ratio)))
        .max_by(|a, b| a.0.total_cmp(&b.0))
}

/// Least-squares slope of the ridge's onset x_m/L against the predicted
/// encounter x_m/L over the runs with V0/c ≤ 0.9.
pub(super) fn ridge_slope(r: &Run1) -> Option<f64> {
    let pts: Vec<(f64, f64)> = r
        .points
        .iter()
        .filter(|p| p.ratio <= 0.9)
        .filter_map(|p| Some((p.encounter?, p.ridge?.0)))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    Some(sxy / sxx)
}

/// The ridge tracks the encounter: its onset moves with the predicted
/// encounter, slope within TRACK_SLOPE_TOL of 1.
pub(super) fn ridge_tracks(r: &Run1) -> bool {
    ridge_slope(r).is_some_and(|k| (k - 1.0).abs() <= TRACK_SLOPE_TOL)
}

/// Is the peak of the ridge near V0/c = 1 (within 0.1)?
pub(super) fn ridge_near_one(r: &Run1) -> bool {
    ridge_peak(r).is_some_and(|(_, _, v)| (v - 1.0).abs() <= 0.1)
}

/// T3: the force ridge from the first encounter with the reflected wave.
pub(super) fn t3_extra(md: &mut String, s: &Run1, c: &Run1) {
    let show = |p: Option<(f64, f64, f64)>| {
        p.map_or("—".into(), |(h, x, r)| {
            format!(
                "V0/c = {} (+{} N after x_m/L = {})",
                g(r, 3),
                g(h, 3),
                g(x, 3)
            )
        })
    };
    let _ = writeln!(
        md,
        "| largest rise of the encounter ridge (bin means up to the first loss; encounter before x_m/L = {RIDGE_LAST}) | near V0/c ≈ 1 | {} ({}) | {} ({}) | {} |",
        show(ridge_peak(s)),
        verdict(ridge_near_one(s)),
        show(ridge_peak(c)),
        verdict(ridge_near_one(c)),
        survive(ridge_near_one(s), ridge_near_one(c))
    );
    let lag = |r: &Run1| {
        ridge_lag(r).map_or("—".into(), |(m, lo, hi, n)| {
            format!(
                                "onset moves with it, slope {}; {} L after it (median; {} to {} over {n} runs) ({})",
                opt(ridge_slope(r), 2),
                g(m, 2),
                g(lo, 2),
                g(hi, 2),
                verdict(ridge_tracks(r))
            )
        })
    };
    let _ = writeln!(
        md,
        "| the ridge starts where the carrier meets the front launched at t = 0 and reflected at x = L (x_m = 2L − ct), V0/c ≤ 0.9 | yes | {} | {} | {} |",
        lag(s),
        lag(c),
        survive(ridge_tracks(s), ridge_tracks(c))
    );
}
