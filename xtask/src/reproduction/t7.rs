//! The 2-D study (TARGETS T7): P_l over (V0/c, T) and its band borders.

use super::{common::*, measures::*, targets_1d::*};
// ------------------------------------------------------------ T7

pub(super) struct Run2 {
    pub(super) spec: SweepSpec,
    pub(super) points: Vec<Point>,
    pub(super) nx: usize,
    pub(super) ny: usize,
}

pub(super) fn t7_axes(n: usize) -> Vec<Axis> {
    vec![
        Axis::parse(&format!("beam.tension=2.01e4:4.02e4:{n}"), false).unwrap(),
        Axis::parse(&format!("carrier.speed.cruise=50:230:{n}"), false).unwrap(),
    ]
}

pub(super) fn run_t7(clock: &Clock, res: Res, n: usize, maps: &Path) -> Run2 {
    let spec = SweepSpec {
        scene_text: reference_text(),
        set: res_sets(res),
        axes: t7_axes(n),
        check_refinement: false,
        paired: false,
        tolerance: None,
    };
    let name = format!("t7_{}", res.tag);
    let recs = run_sweep(clock, &name, &spec);
    let points: Vec<Point> = recs.iter().map(|r| measure(&spec, r)).collect();
    write_loss_fraction_map(
        &maps.join(format!("{name}_pl.svg")),
        &spec,
        &recs,
        Some(&format!("T7 (Fig. 12): P_l over (T, V0), {}", res.label)),
        &SPEED_RATIO_LEVELS,
    )
    .expect("P_l map");
    // the same map counting only the loss in the span
    let span: Vec<SweepRecord> = recs
        .iter()
        .zip(&points)
        .map(|(r, p)| r.with_loss_fraction(p.pl_span))
        .collect();
    write_loss_fraction_map(
        &maps.join(format!("{name}_pl_span.svg")),
        &spec,
        &span,
        Some(&format!(
            "T7: P_l counting loss before x_m/L = {SPAN_END} only, {}",
            res.label
        )),
        &SPEED_RATIO_LEVELS,
    )
    .expect("P_l,span map");
    Run2 {
        spec,
        points,
        nx: n,
        ny: n,
    }
}

/// Per tension: (T/EA, lower border bracket in V0/c, whether loss-free
/// points lie above the loss).
pub(super) struct Border {
    pub(super) tension_ratio: f64,
    pub(super) below: Option<f64>,
    pub(super) above: Option<f64>,
    pub(super) upper_free: Option<f64>,
    pub(super) top: f64,
}

pub(super) fn borders(r: &Run2, pick: fn(&Point) -> f64) -> Vec<Border> {
    let ea = 1.34e11 * 1.5e-4;
    (0..r.nx)
        .map(|i| {
            let col: Vec<&Point> = (0..r.ny).map(|j| &r.points[i * r.ny + j]).collect();
            // the main band: the longest run of points with loss
            let mut band: Option<(usize, usize)> = None;
            let mut k = 0;
            while k < col.len() {
                if pick(col[k]) > 0.0 {
                    let mut e = k;
                    while e + 1 < col.len() && pick(col[e + 1]) > 0.0 {
                        e += 1;
                    }
                    if band.is_none_or(|(a, b)| e - k > b - a) {
                        band = Some((k, e));
                    }
                    k = e + 1;
                } else {
                    k += 1;
                }
            }
            let (below, above) = match band {
                Some((0, _)) => (None, Some(col[0].ratio)),
                Some((k, _)) => (Some(col[k - 1].ratio), Some(col[k].ratio)),
                None => (col.last().map(|p| p.ratio), None),
            };
            // the first loss-free V0/c above the band
            let upper_free = band.and_then(|(_, e)| col.get(e + 1).map(|p| p.ratio));
            Border {
                tension_ratio: r.spec.point(i * r.ny)[0] / ea,
                below,
                above,
                upper_free,
                top: col.last().unwrap().ratio,
            }
        })
        .collect()
}

/// The V0/c range every tension column covers: (largest column minimum,
/// smallest column maximum).
pub(super) fn column_extremes(r: &Run2) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..r.nx {
        let col = &r.points[i * r.ny..(i + 1) * r.ny];
        lo = lo.max(col.iter().map(|p| p.ratio).fold(f64::INFINITY, f64::min));
        hi = hi.min(
            col.iter()
                .map(|p| p.ratio)
                .fold(f64::NEG_INFINITY, f64::max),
        );
    }
    (lo, hi)
}

pub(super) fn write_t7(md: &mut String, s: &Run2, c: &Run2) {
    let _ = writeln!(
        md,
        "## T7 — possibility of contact loss over tension and speed (study Fig. 12)\n"
    );
    let _ = writeln!(
        md,
        "**Published.** P_l = (time with contact lost)/(total time), mapped over (T, V0): loss only inside a band whose borders follow V0/c ≈ 0.64 and V0/c ≈ 0.96; none outside.\n"
    );
    let _ = writeln!(
        md,
        "**taut.** `taut sweep scenes/reference.toml --vary beam.tension=2.01e4:4.02e4:N --vary carrier.speed.cruise=50:230:N`: T/EA from 0.001 to 0.002 and V0 from 50 to 230 m/s, so V0/c covers {}–{} ({}–{} at every tension). \
The study-like map is {} × {} ({} runs); the refined one {} × {} ({} runs){}. \
The lines are V0/c of each run (0.64 and 0.96 bold). The band is, at each tension, the longest run of speeds with loss; its lower border lies between the last V0/c without and the first with loss, and it agrees with the published one when within {T7_BORDER_TOL} of it (about one V0 step of the refined map).\n",
        g(
            s.points
                .iter()
                .map(|p| p.ratio)
                .fold(f64::INFINITY, f64::min),
            2
        ),
        g(
            s.points
                .iter()
                .map(|p| p.ratio)
                .fold(f64::NEG_INFINITY, f64::max),
            3
        ),
        g(column_extremes(s).0, 2),
        g(column_extremes(s).1, 3),
        s.nx,
        s.ny,
        s.points.len(),
        c.nx,
        c.ny,
        c.points.len(),
        if c.nx < T7_STUDY_GRID {
            format!(
                " — coarser than the study-like one to keep this page's run time near ten minutes; `-- --full` runs {0} × {0} (≈ 15 min more on two free cores; see docs/sweeps.md)",
                T7_STUDY_GRID
            )
        } else {
            String::new()
        }
    );
    let summarize = |r: &Run2, pick: fn(&Point) -> f64| {
        let b = borders(r, pick);
        let lows: Vec<f64> = b
            .iter()
            .filter_map(|x| Some(0.5 * (x.below? + x.above?)))
            .collect();
        let lo_min = lows.iter().copied().fold(f64::INFINITY, f64::min);
        let lo_max = lows.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let upper: Vec<f64> = b.iter().filter_map(|x| x.upper_free).collect();
        let always_below = b
            .iter()
            .filter(|x| x.below.is_none() && x.above.is_some())
            .count();
        let top = b.iter().map(|x| x.top).fold(f64::INFINITY, f64::min);
        (
            median(lows.clone()),
            lo_min,
            lo_max,
            upper,
            always_below,
            top,
            b.len(),
        )
    };
    let _ = writeln!(
        md,
        "| feature | published | {} | {} | survives refinement |",
        STUDY.label, CONVERGED.label
    );
    let _ = writeln!(md, "|---|---|---|---|---|");
    for (what, pick) in [
        (
            "P_l,span (loss before x_m/L = 0.99)",
            (|p: &Point| p.pl_span) as fn(&Point) -> f64,
        ),
        ("P_l (whole run)", |p: &Point| p.pl),
    ] {
        let (ms, ls, hs, us, bs, ts, n) = summarize(s, pick);
        let (mc, lc, hc, uc, bc, tc, nc) = summarize(c, pick);
        let lower_ok = |m: f64| (m - 0.64).abs() <= T7_BORDER_TOL;
        let show_lower = |m: f64, l: f64, h: f64, b: usize, n: usize| {
            if b == n {
                "loss at every grid point".to_string()
            } else {
                format!(
                    "median {} (range {}–{} over the tensions){}",
                    g(m, 3),
                    g(l, 3),
                    g(h, 3),
                    if b > 0 {
                        format!("; loss at the lowest V0 for {b} tensions")
                    } else {
                        String::new()
                    }
                )
            }
        };
        let _ = writeln!(
            md,
            "| lower border of {what}, V0/c | ≈ 0.64 | {} ({}) | {} ({}) | {} |",
            show_lower(ms, ls, hs, bs, n),
            verdict(lower_ok(ms) && bs < n),
            show_lower(mc, lc, hc, bc, nc),
            verdict(lower_ok(mc) && bc < nc),
            survive(lower_ok(ms) && bs < n, lower_ok(mc) && bc < nc)
        );
        let show_upper = |u: &[f64], top: f64, n: usize| {
            if u.is_empty() {
                format!(
                    "none: loss up to the top of every column (V0/c ≥ {})",
                    g(top, 3)
                )
            } else {
                format!(
                    "loss-free above the band at {} of {n} tensions (median V0/c {})",
                    u.len(),
                    g(median(u.to_vec()), 3)
                )
            }
        };
        let upper_ok = |u: &[f64], n: usize| {
            2 * u.len() >= n && (median(u.to_vec()) - 0.96).abs() <= T7_BORDER_TOL
        };
        let _ = writeln!(
            md,
            "| upper border of {what}, V0/c | ≈ 0.96 (none above) | {} ({}) | {} ({}) | {} |",
            show_upper(&us, ts, n),
            verdict(upper_ok(&us, n)),
            show_upper(&uc, tc, nc),
            verdict(upper_ok(&uc, nc)),
            survive(upper_ok(&us, n), upper_ok(&uc, nc))
        );
    }
    let _ = writeln!(md);
    let _ = writeln!(
        md,
        "| {} | {} |\n|---|---|\n| ![](reproduction/t7_study_pl.svg) | ![](reproduction/t7_refined_pl.svg) |\n| ![](reproduction/t7_study_pl_span.svg) | ![](reproduction/t7_refined_pl_span.svg) |\n",
        STUDY.label, CONVERGED.label
    );
    let _ = writeln!(
        md,
        "<details><summary>Lower border of P_l,span per tension (refined map)</summary>\n"
    );
    let _ = writeln!(
        md,
        "| T/EA | c (m/s) | last V0/c without loss | first V0/c with loss | lowest loss-free V0/c above it |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|");
    for b in borders(c, |p| p.pl_span) {
        let cw = (b.tension_ratio * 1.34e11 * 1.5e-4 / (8900.0 * 1.5e-4)).sqrt();
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} |",
            g(b.tension_ratio, 4),
            g(cw, 4),
            opt(b.below, 3),
            opt(b.above, 3),
            opt(b.upper_free, 3)
        );
    }
    let _ = writeln!(md, "\n</details>\n");
}
