//! §4 of `docs/convergence.md`: contact loss on the reference case.

use super::common::*;
// ---------------------------------------------------------------- §4 reference

/// What §4 keeps of one reference-case run.
pub(super) struct RefRun {
    n: usize,
    dt: f64,
    pl: f64,
    pl_long: f64,
    intervals: usize,
    short: usize,
    short_after: usize,
    switches: usize,
    max_force: f64,
    rms_all: f64,
    rms_pre: f64,
    first_loss: f64,
    /// λ and x_m/L on the 1e-4 s grid (empty when Δt > 1e-4 s).
    f_grid: Vec<f64>,
    x_grid: Vec<f64>,
}

/// A short loss interval starting within this time (s) of the end of the
/// previous one counts as a bounce after re-contact.
pub(super) const BOUNCE_WINDOW: f64 = 1e-3;

pub(super) fn ref_run(out: &RunOutput, n: usize, length: f64) -> RefRun {
    let st = &out.stats[0];
    let tr = &out.history.carriers[0];
    let t_total = out.steps as f64 * out.dt;
    let iv = &st.loss_intervals_time;
    let is_long = |i: &[f64; 2]| i[1] - i[0] > LONG_LOSS * (1.0 + 1e-6);
    let long: f64 = iv.iter().filter(|i| is_long(i)).map(|i| i[1] - i[0]).sum();
    let short = iv.iter().filter(|i| !is_long(i)).count();
    let short_after = iv
        .windows(2)
        .filter(|p| !is_long(&p[1]) && p[1][0] - p[0][1] <= BOUNCE_WINDOW)
        .count();
    let pre: Vec<f64> = tr.force[1..]
        .iter()
        .zip(&tr.x[1..])
        .filter(|(_, x)| **x / length <= PRE_LOSS_X)
        .map(|(f, _)| *f)
        .collect();
    let grid = out.dt <= 1e-4;
    RefRun {
        n,
        dt: out.dt,
        pl: st.loss_fraction,
        pl_long: long / t_total,
        intervals: iv.len(),
        short,
        short_after,
        switches: st.contact_switches,
        max_force: st.force.max,
        rms_all: l2_norm(&tr.force[1..]),
        rms_pre: l2_norm(&pre),
        first_loss: st.first_loss_position.unwrap_or(f64::NAN),
        f_grid: if grid {
            on_grid(out, 1e-4, |tr, i| tr.force[i])
        } else {
            Vec::new()
        },
        x_grid: if grid {
            on_grid(out, 1e-4, |tr, i| tr.x[i] / length)
        } else {
            Vec::new()
        },
    }
}

pub(super) fn key(n: usize, dt: f64) -> (usize, u64) {
    (n, (dt * 1e12).round() as u64)
}

/// Relative L2 norm of the difference of two histories, over the samples
/// whose x/L passes `keep`.
pub(super) fn rel_l2(a: &[f64], b: &[f64], x: &[f64], keep: impl Fn(f64) -> bool) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for ((p, q), &xi) in a.iter().zip(b).zip(x) {
        if keep(xi) {
            num += (p - q) * (p - q);
            den += q * q;
        }
    }
    (num / den).sqrt()
}

pub(super) fn section_reference(d: &mut String, clock: &mut Clock) -> Vec<String> {
    w!(d, "## 4. Contact loss: the reference case\n");
    let text = scene_text("reference");
    let length = resolve_scene(&text, &[]).expect("reference").beam.length;
    w!(
        d,
        "`scenes/reference.toml`: the study's moving case (1 kg on a 987 N/m spring, \
         preloaded 0.05 m, riding a 50 m clamped–pinned wire, ramp to 100 m/s, unilateral \
         Lagrange contact, `end` placement, ρ∞ = 1, 0.6 s; contact is lost near the right \
         support). Three library studies, then a grid of single runs. In the study tables \
         ‖Δλ‖_L2 is the RMS of the difference of successive force histories on the coarsest \
         level's times; \"λ RMS\" is the library's force_history_l2 value (RMS of λ on those times); \
         GCIs are the library's (relative; for λ from the history differences, for P_l from \
         the values); \"pre-loss\" is ‖Δλ‖/‖λ‖ over the samples with x_m/L ≤ {PRE_LOSS_X}, \
         before the loss region.\n"
    );
    let mut cache: HashMap<(usize, u64), RefRun> = HashMap::new();
    let mut gci_f = Vec::new();
    let (mut pre_mesh, mut pre_step) = (Vec::new(), Vec::new());
    let (mut mesh_orders, mut mesh_gci) = (Vec::new(), Vec::new());
    let mut both_pl: Vec<(f64, f64, f64)> = Vec::new();
    let mut study_orders: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
    let mut step_rms = Vec::new();
    for (refine, sets, title) in [
        (
            Refine::Mesh,
            vec![set("time.step", "2.5e-5"), set("mesh.elements", 400)],
            "4a. Mesh refined at Δt = 2.5e-5 s",
        ),
        (
            Refine::Step,
            vec![set("mesh.elements", 3200), set("time.step", "1e-4")],
            "4b. Δt refined at N = 3200",
        ),
        (
            Refine::Both,
            vec![set("mesh.elements", 200), set("time.step", "2e-4")],
            "4c. Mesh and Δt refined together",
        ),
    ] {
        let levels = 5;
        let s = study("reference", &sets, refine, levels, false, clock);
        let c = &s.c;
        let f: Vec<Vec<f64>> = (0..levels)
            .map(|l| coarse(c, l, |tr, i| tr.force[i]))
            .collect();
        let x: Vec<f64> = coarse(c, 0, |tr, i| tr.x[i] / length);
        let df = successive(&f, l2_norm);
        check_orders(c, "force_history_l2", &orders(&df));
        study_orders.push((
            title[..2].to_string(),
            (0..levels)
                .map(|l| row(c, l, "force_history_l2").observed_order)
                .collect(),
            (0..levels)
                .map(|l| row(c, l, "loss_fraction").observed_order)
                .collect(),
        ));
        if refine == Refine::Step {
            step_rms = (0..levels)
                .map(|l| row(c, l, "force_history_l2").value)
                .collect();
        }
        let mut rows = Vec::new();
        for l in 0..levels {
            let sc = &c.scenes[l];
            let r = ref_run(&c.runs[l], sc.elements, length);
            let pre = if l == 0 {
                f64::NAN
            } else {
                rel_l2(&f[l - 1], &f[l], &x, |xi| xi <= PRE_LOSS_X)
            };
            let (rf, rp) = (row(c, l, "force_history_l2"), row(c, l, "loss_fraction"));
            let pl_diff = if l == 0 {
                f64::NAN
            } else {
                (rp.value - row(c, l - 1, "loss_fraction").value).abs()
            };
            if rf.gci.is_finite() {
                gci_f.push(format!("{} ({})", pct(rf.gci), &title[..2]));
            }
            if refine == Refine::Mesh {
                pre_mesh.push(pre);
                mesh_orders.push(rf.observed_order);
                mesh_gci.push(rf.gci);
            }
            if refine == Refine::Step {
                pre_step.push(pre);
            }
            if refine == Refine::Both {
                both_pl.push((rp.value, rp.observed_order, rp.gci));
            }
            rows.push(vec![
                l.to_string(),
                sc.elements.to_string(),
                format!("{:e}", sc.dt),
                format!("{:.3}", rf.value),
                e3(df[l]),
                f2(rf.observed_order),
                pct(rf.gci),
                pct(pre),
                format!("{:.5}", r.pl),
                e3(pl_diff),
                f2(rp.observed_order),
                pct(rp.gci),
                format!("{:.4}", r.first_loss),
                format!("{:.0}", r.max_force),
                r.switches.to_string(),
            ]);
            let k = key(sc.elements, sc.dt);
            if let Some(prev) = cache.get(&k) {
                // runs are deterministic: a repeated (N, Δt) must agree bit for bit
                assert!(
                    prev.pl == r.pl && prev.f_grid == r.f_grid,
                    "(N = {}, Δt = {}) differs between studies",
                    sc.elements,
                    sc.dt
                );
            }
            cache.insert(k, r);
        }
        w!(d, "### {title}\n\n`{}`\n", s.cmd);
        table(
            d,
            &[
                "level",
                "N",
                "Δt (s)",
                "λ RMS (N)",
                "‖Δλ‖_L2 (N)",
                "order",
                "GCI λ",
                "pre-loss ‖Δλ‖/‖λ‖",
                "P_l",
                "|ΔP_l|",
                "order",
                "GCI P_l",
                "first loss x/L",
                "max λ (N)",
                "switches",
            ],
            &rows,
        );
    }

    // the grid, and N = 1600 one step further
    let ns = [400usize, 800, 1600, 3200];
    let dts = [1e-4, 5e-5, 2.5e-5, 1.25e-5, 6.25e-6];
    let extra = [(1600usize, 3.125e-6)];
    let cells = ns
        .iter()
        .flat_map(|&n| dts.iter().map(move |&dt| (n, dt)))
        .chain(extra);
    for (n, dt) in cells {
        if cache.contains_key(&key(n, dt)) {
            continue;
        }
        let sets = [set("mesh.elements", n), set("time.step", format!("{dt:e}"))];
        let sc = resolve_scene(&text, &sets).expect("reference");
        let out = run(&sc, &mut |_, _| {}).expect("run");
        cache.insert(key(n, dt), ref_run(&out, n, length));
    }
    clock.lap("reference grid");
    let get = |n: usize, dt: f64| -> &RefRun { &cache[&key(n, dt)] };
    let finest = get(3200, 6.25e-6);
    let rel_diff = |r: &RefRun, pre_only: bool| -> f64 {
        rel_l2(&r.f_grid, &finest.f_grid, &finest.x_grid, |x| {
            !pre_only || x <= PRE_LOSS_X
        })
    };
    let head: Vec<String> = std::iter::once("N \\ Δt (s)".to_string())
        .chain(dts.iter().map(|dt| format!("{dt:e}")))
        .collect();
    let head: Vec<&str> = head.iter().map(String::as_str).collect();
    let grid_table = |d: &mut String, cell: &dyn Fn(&RefRun) -> String| {
        let rows: Vec<Vec<String>> = ns
            .iter()
            .map(|&n| {
                std::iter::once(n.to_string())
                    .chain(dts.iter().map(|&dt| cell(get(n, dt))))
                    .collect()
            })
            .collect();
        table(d, &head, &rows);
    };
    let n6400 = get(6400, 2.5e-5);
    let x1600 = get(1600, 3.125e-6);
    w!(d, "### 4d. The (N, Δt) grid\n");
    w!(
        d,
        "Every cell is one run, `taut run scenes/reference.toml --set mesh.elements=N --set \
         time.step=Δt`; cells shared with 4a–4c are the same runs (checked bit for bit). \
         Outside the grid: N = 6400 at Δt = 2.5e-5 s (from 4a): P_l = {:.5}, max λ = {:.0} N; \
         N = 1600 at Δt = 3.125e-6 s: P_l = {:.5}, P_l in long intervals {:.5}, {} intervals, \
         max λ = {:.0} N.\n",
        n6400.pl,
        n6400.max_force,
        x1600.pl,
        x1600.pl_long,
        x1600.intervals,
        x1600.max_force
    );
    w!(d, "**P_l** (steps with the contact open / all steps):\n");
    grid_table(d, &|r| format!("{:.5}", r.pl));
    w!(
        d,
        "**P_l counted over loss intervals longer than {} ms only**, and (in brackets) the \
         number of loss intervals / of those no longer than {} ms:\n",
        LONG_LOSS * 1e3,
        LONG_LOSS * 1e3
    );
    grid_table(d, &|r| {
        format!("{:.5} ({} / {})", r.pl_long, r.intervals, r.short)
    });
    w!(d, "**max λ** (N), the largest re-contact spike:\n");
    grid_table(d, &|r| format!("{:.0}", r.max_force));
    w!(
        d,
        "**RMS of λ over all steps** (N): whole run / steps with x_m/L ≤ {PRE_LOSS_X}:\n"
    );
    grid_table(d, &|r| format!("{:.3} / {:.3}", r.rms_all, r.rms_pre));
    w!(
        d,
        "**Difference to the finest cell (N = 3200, Δt = 6.25e-6 s)**: ‖λ − λ_finest‖_L2 / \
         ‖λ_finest‖_L2 on the 1e-4 s grid, whole run / x_m/L ≤ {PRE_LOSS_X}:\n"
    );
    grid_table(d, &|r| {
        if std::ptr::eq(r, finest) {
            "(reference)".into()
        } else {
            format!("{} / {}", pct(rel_diff(r, false)), pct(rel_diff(r, true)))
        }
    });

    // ---- answers, computed
    let grid_cells: Vec<&RefRun> = ns
        .iter()
        .flat_map(|&n| dts.iter().map(move |&dt| (n, dt)))
        .map(|(n, dt)| get(n, dt))
        .filter(|r| !std::ptr::eq(*r, finest))
        .collect();
    let list = |pred: &dyn Fn(&RefRun) -> bool| -> String {
        let v: Vec<String> = grid_cells
            .iter()
            .filter(|r| pred(r))
            .map(|r| format!("({}, {:e})", r.n, r.dt))
            .collect();
        if v.is_empty() {
            "none".into()
        } else {
            v.join(", ")
        }
    };
    let row_n = |n: usize| -> Vec<&RefRun> { dts.iter().map(|&dt| get(n, dt)).collect() };
    let fmt = |v: &[&RefRun], f: &dyn Fn(&RefRun) -> String| joined(v.iter().map(|r| f(r)), ", ");
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let best_whole = grid_cells
        .iter()
        .map(|r| (rel_diff(r, false), r.n, r.dt))
        .fold((f64::MAX, 0, 0.0), |a, b| if b.0 < a.0 { b } else { a });
    let r3200 = row_n(3200);
    let r1600 = row_n(1600);
    let steps_pct = |v: &[&RefRun], f: fn(&RefRun) -> f64| {
        joined(v.windows(2).map(|p| pct(rel(f(p[1]), f(p[0])))), ", ")
    };

    w!(d, "### 4e. Answers\n");
    w!(
        d,
        "Criterion: the relative difference to the finest level ≤ 1 %. The three-grid GCIs \
         of 4a–4c are printed above, but they presume a monotone asymptotic sequence, which \
         λ and P_l do not follow here (their observed orders scatter, some negative), so the \
         **difference to the finest cell** of the grid, (N, Δt) = (3200, 6.25e-6 s), is the \
         criterion used. Cells are written (N, Δt in s).\n"
    );
    let (mesh_lo, mesh_hi) = study_orders[0]
        .1
        .iter()
        .filter(|x| x.is_finite())
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    let orders_text = joined(
        study_orders
            .iter()
            .map(|(t, f, p)| format!("{t}: λ {}; P_l {}", finite_f2(f), finite_f2(p))),
        " · ",
    );
    w!(
        d,
        "**Observed orders (library, successive differences).** {orders_text}. Only the \
         mesh refinement at fixed Δt gives a consistent, positive order for λ \
         ({mesh_lo:.2}–{mesh_hi:.2}); \
         with Δt refined the orders are near zero or negative (no convergence), and the P_l \
         orders change sign from level to level.\n"
    );
    w!(
        d,
        "**1. The force history, L2 over the whole run: not converged to 1 % at any tested \
         (N, Δt)** (N ≤ 3200, Δt ≥ 6.25e-6 s; 6400 at 2.5e-5 s). History within 1 % of the \
         finest cell: {}; the closest is {} at ({}, {:e}). The RMS over all steps happens to \
         fall within 1 % of the finest at {}, but it is not settled: at N = 3200 it reads \
         {} N for Δt = 1e-4 … 6.25e-6 s, changes of {} per halving. What moves it is the \
         re-contact spikes near the right support, which grow as Δt falls (max λ at N = 3200: \
         {} N). The library's λ RMS on the coarsest grid is no steadier (4b: {} N: whether a \
         spike falls on a coarse sample is chance), and its GCIs for λ are {}. At fixed \
         Δt = 2.5e-5 s the whole-run history does converge in the mesh, though not yet to \
         1 % (4a: orders {}, GCI {} at N = 6400): the non-convergence is in Δt.\n",
        list(&|r| rel_diff(r, false) <= TARGET),
        pct(best_whole.0),
        best_whole.1,
        best_whole.2,
        list(&|r| rel(r.rms_all, finest.rms_all) <= TARGET),
        fmt(&r3200, &|r| format!("{:.2}", r.rms_all)),
        steps_pct(&r3200, |r| r.rms_all),
        fmt(&r3200, &|r| format!("{:.0}", r.max_force)),
        joined(step_rms.iter().map(|x| format!("{x:.2}")), ", "),
        joined(gci_f.iter().cloned(), ", "),
        finite_f2(&mesh_orders),
        pct(*mesh_gci.last().unwrap())
    );
    let pre_rms_spread = [1600usize, 3200]
        .iter()
        .flat_map(|&n| row_n(n))
        .map(|r| rel(r.rms_pre, finest.rms_pre))
        .fold(0.0, f64::max);
    w!(
        d,
        "**2. The force history before the loss region (x_m/L ≤ {PRE_LOSS_X}).** Its RMS \
         is within 1 % of the finest cell at {}; at N ≥ 1600 it agrees to {} over every Δt \
         (N = 3200: {} N). On coarse meshes a smaller Δt makes it worse (N = 400: {} N), the \
         element-crossing artefact of verification.md. The history itself, compared sample \
         by sample, is within 1 % of the finest cell at: {}. At N = 3200 it differs from the \
         finest cell by {} over Δt = 1e-4 … 1.25e-5 s, and successive Δt levels differ by {} \
         (4b, not falling with Δt); in the mesh at Δt = 2.5e-5 s successive levels differ \
         by {} (4a, falling with N). **Answer: its RMS is converged to 1 % from N = 1600 at \
         any Δt ≤ 1e-4 s; the history itself is not converged to 1 % at any tested cell \
         (about 2 % at N = 3200, {} between N = 3200 and 6400).** What remains \
         shrinks with N (4a) and not with Δt (4b), as the element-crossing fluctuation of \
         verification.md does.\n",
        list(&|r| rel(r.rms_pre, finest.rms_pre) <= TARGET),
        pct(pre_rms_spread),
        fmt(&r3200, &|r| format!("{:.3}", r.rms_pre)),
        fmt(&row_n(400), &|r| format!("{:.2}", r.rms_pre)),
        list(&|r| rel_diff(r, true) <= TARGET),
        joined(r3200[..4].iter().map(|r| pct(rel_diff(r, true))), ", "),
        joined(
            pre_step.iter().filter(|x| x.is_finite()).map(|x| pct(*x)),
            ", "
        ),
        joined(
            pre_mesh.iter().filter(|x| x.is_finite()).map(|x| pct(*x)),
            ", "
        ),
        pct(*pre_mesh.last().unwrap())
    );
    let mesh_steps = joined(
        dts.iter()
            .map(|&dt| pct(rel(get(3200, dt).pl, get(1600, dt).pl))),
        ", ",
    );
    w!(
        d,
        "**3. P_l.** In the mesh at fixed Δt it settles: at Δt = 2.5e-5 s, N = 400 … 3200 \
         give {}, and N = 6400 gives {:.5} ({} from N = 3200); the change from N = 1600 to \
         3200 is {} at Δt = 1e-4 … 6.25e-6 s. In Δt at fixed N it does not: N = 3200 gives \
         {} for Δt = 1e-4 … 6.25e-6 s (changes of {} per halving; {} over the range), \
         N = 1600 gives {} and {:.5} at 3.125e-6 s. Within 1 % of the finest cell: {}. \
         **Answer: P_l is converged to 1 % in the mesh at N = 3200 (checked against N = 6400 \
         at one Δt), and not converged in Δt at any tested Δt (down to 6.25e-6 s at N = 3200, \
         3.125e-6 s at N = 1600).** A P_l quoted to 1 % must quote its Δt.\n",
        fmt(
            &ns.iter().map(|&n| get(n, 2.5e-5)).collect::<Vec<_>>(),
            &|r| format!("{:.5}", r.pl)
        ),
        n6400.pl,
        pct(rel(n6400.pl, get(3200, 2.5e-5).pl)),
        mesh_steps,
        fmt(&r3200, &|r| format!("{:.5}", r.pl)),
        steps_pct(&r3200, |r| r.pl),
        pct(r3200[4].pl / r3200[0].pl - 1.0),
        fmt(&r1600, &|r| format!("{:.5}", r.pl)),
        x1600.pl,
        list(&|r| rel(r.pl, finest.pl) <= TARGET)
    );
    let early: Vec<&RefRun> = grid_cells
        .iter()
        .copied()
        .chain(std::iter::once(finest))
        .filter(|r| r.first_loss < 0.984)
        .collect();
    let early_text = if early.is_empty() {
        "none".to_string()
    } else {
        joined(
            early
                .iter()
                .map(|r| format!("({}, {:e}): {:.4}", r.n, r.dt, r.first_loss)),
            "; ",
        )
    };
    let early_max_n = early.iter().map(|r| r.n).max().unwrap_or(0);
    let (fl_min, fl_max) = r3200
        .iter()
        .map(|r| r.first_loss)
        .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let (short_total, short_after_total): (usize, usize) = grid_cells
        .iter()
        .copied()
        .chain(std::iter::once(finest))
        .filter(|r| r.n >= 1600)
        .fold((0, 0), |(a, b), r| (a + r.short, b + r.short_after));
    w!(
        d,
        "**4. Does a converged P_l depend on Δt in ways a figure could hide? Yes.** The \
         part of P_l in loss intervals longer than {} ms settles once Δt ≤ 1.25e-5 s \
         (N = 3200: {}; N = 1600: {} and {:.5} at 3.125e-6 s), but P_l keeps moving there \
         (N = 3200: {:.5} → {:.5}; N = 1600: {:.5} → {:.5} → {:.5}), because the number of \
         short loss intervals grows as Δt falls (N = 3200, intervals no longer than {} ms: \
         {}). They are bounces after a re-contact: at N ≥ 1600, {short_after_total} of the \
         {short_total} short intervals start within {} ms of the end of the previous loss. \
         The re-contact spikes grow as Δt falls at every mesh (max λ, N = 3200: {} N; \
         N = 400: {} N; N = 1600 at 3.125e-6 s: {:.0} N): the model has no impact law \
         (TARGETS), so a spike height is a property of Δt. What does converge: the first loss \
         position, x/L = {fl_min:.4}–{fl_max:.4} at N = 3200 for every Δt (earlier first \
         losses occur only at N ≤ {early_max_n}: {early_text}), \
         and the long loss intervals. A figure made at one Δt (the study does not state its \
         Δt) therefore shows a P_l and spike heights that belong to that Δt. A refine-both \
         study can hide this: in 4c, where N and Δt change together, the two effects mix, \
         and P_l goes {} with observed orders {} and GCIs {} — a three-grid GCI of {} at one \
         level reads as converged, which the grid refutes.\n",
        LONG_LOSS * 1e3,
        fmt(&r3200[3..], &|r| format!("{:.5}", r.pl_long)),
        fmt(&r1600[3..], &|r| format!("{:.5}", r.pl_long)),
        x1600.pl_long,
        r3200[3].pl,
        r3200[4].pl,
        r1600[3].pl,
        r1600[4].pl,
        x1600.pl,
        LONG_LOSS * 1e3,
        fmt(&r3200, &|r| r.short.to_string()),
        BOUNCE_WINDOW * 1e3,
        fmt(&r3200, &|r| format!("{:.0}", r.max_force)),
        fmt(&row_n(400), &|r| format!("{:.0}", r.max_force)),
        x1600.max_force,
        joined(both_pl.iter().map(|x| format!("{:.5}", x.0)), " → "),
        finite_f2(&both_pl.iter().map(|x| x.1).collect::<Vec<_>>()),
        joined(
            both_pl.iter().filter(|x| x.2.is_finite()).map(|x| pct(x.2)),
            ", "
        ),
        pct(both_pl
            .iter()
            .map(|x| x.2)
            .filter(|x| x.is_finite())
            .fold(f64::MAX, f64::min))
    );
    vec![
        format!(
            "**Reference case, force history.** L2 over the whole run: not converged to 1 % at \
             any tested (N, Δt) (best {} from the finest cell); it converges in the mesh at \
             fixed Δt but not in Δt, because the re-contact spikes grow as Δt falls (max λ at \
             N = 3200: {} N for Δt = 1e-4 … 6.25e-6 s). Before the loss region its RMS is \
             converged to 1 % from N = 1600 at any Δt ≤ 1e-4 s.",
            pct(best_whole.0),
            fmt(&r3200, &|r| format!("{:.0}", r.max_force))
        ),
        format!(
            "**Reference case, P_l.** Converged to 1 % in the mesh at N = 3200 (N = 6400 \
             equal at Δt = 2.5e-5 s); not converged in Δt: {} at N = 3200 for Δt = 1e-4 … \
             6.25e-6 s (+{}); below Δt = 1.25e-5 s the change comes from short bounces \
             after re-contact, whose number grows as Δt falls, while P_l over the loss \
             intervals longer than 0.1 ms settles. The first loss position converges \
             (x/L = {fl_min:.4}–{fl_max:.4} at N = 3200). A P_l must be quoted with its Δt; \
             re-contact spike heights are Δt's.",
            fmt(&r3200, &|r| format!("{:.5}", r.pl)),
            pct(r3200[4].pl / r3200[0].pl - 1.0),
        ),
    ]
}
