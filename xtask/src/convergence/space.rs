//! §2 of `docs/convergence.md`: refinement in space.

use super::common::*;
// ---------------------------------------------------------------- §2 space

/// One eigenfrequency table: relative errors of modes 1, 5, 10 and orders;
/// entries within 10× the round-off estimate ε(ω_max/ω_j)² are marked.
/// Returns the errors and orders per N (NaN where round-off).
pub(super) fn eigen_table(
    d: &mut String,
    props: &BeamProps,
    exact: &[f64],
    ns: &[usize],
    lb: f64,
) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let modes = [1usize, 5, 10];
    let mut prev: Option<[f64; 3]> = None;
    let mut rows = Vec::new();
    let mut all_orders = Vec::new();
    let mut all_errors = Vec::new();
    for &n in ns {
        let all = fe_frequencies(props, n, usize::MAX).expect("modal solve");
        let wmax = *all.last().unwrap();
        let mut e = [f64::NAN; 3];
        let mut r = vec![
            n.to_string(),
            format!("{:.2}", props.length / n as f64 / lb),
        ];
        let mut o = [f64::NAN; 3];
        for (i, &j) in modes.iter().enumerate() {
            let err = (all[j - 1] - exact[j - 1]) / exact[j - 1];
            let floor = f64::EPSILON * (wmax / exact[j - 1]).powi(2);
            if err.abs() >= 10.0 * floor {
                e[i] = err;
                o[i] = prev.map_or(f64::NAN, |p| order(p[i], err));
                r.push(e3(err));
                r.push(f2(o[i]));
            } else {
                r.push(format!("round-off ({})", e3(err)));
                r.push("—".into());
            }
        }
        rows.push(r);
        all_orders.push(o);
        all_errors.push(e);
        prev = Some(e);
    }
    table(
        d,
        &[
            "N", "h/ℓ_b", "mode 1", "order", "mode 5", "order", "mode 10", "order",
        ],
        &rows,
    );
    (all_errors, all_orders)
}

pub(super) fn section_space(d: &mut String, clock: &mut Clock, exact: &[f64]) -> Vec<String> {
    w!(d, "## 2. Space\n");

    // 2a. string
    w!(
        d,
        "### 2a. Moving force on the taut string: linear elements\n"
    );
    let both = study("moving_force_string", &[], Refine::Both, 5, true, clock);
    let mesh = study(
        "moving_force_string",
        &[set("time.step", "2.5e-5")],
        Refine::Mesh,
        5,
        true,
        clock,
    );
    let sc0 = &both.c.scenes[0];
    let b = &sc0.beam;
    let (force, speed) = force_and_speed(sc0);
    let te = b.tension - b.rho_a * speed * speed;
    let err = |c: &Convergence, l: usize, q: &str| row(c, l, q).error;
    let eorder = |c: &Convergence, l: usize, q: &str| {
        if l >= 1 {
            order(err(c, l - 1, q), err(c, l, q))
        } else {
            f64::NAN
        }
    };
    let (cb, cm) = (&both.c, &mesh.c);
    let mut rows = Vec::new();
    let (mut ratios, mut o_both, mut o_mesh, mut o_max, mut max_ratio) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for l in 0..5 {
        let h = b.length / cb.scenes[l].elements as f64;
        let kink = force * h / (4.0 * te);
        ratios.push(err(cb, l, "displacement_history_l2") / kink);
        max_ratio.push(err(cb, l, "displacement_history_max") / kink);
        o_both.push(eorder(cb, l, "displacement_history_l2"));
        o_mesh.push(eorder(cm, l, "displacement_history_l2"));
        o_max.push(eorder(cb, l, "displacement_history_max"));
        rows.push(vec![
            l.to_string(),
            cb.scenes[l].elements.to_string(),
            format!("{:e}", cb.scenes[l].dt),
            e3(kink),
            e3(err(cb, l, "displacement_history_l2")),
            f2(eorder(cb, l, "displacement_history_l2")),
            format!("{:.3}", ratios[l]),
            e3(err(cb, l, "displacement_history_max")),
            f2(eorder(cb, l, "displacement_history_max")),
            f2(row(cb, l, "displacement_history_l2").observed_order),
            e3(err(cm, l, "displacement_history_l2")),
            f2(eorder(cm, l, "displacement_history_l2")),
        ]);
    }
    w!(
        d,
        "`scenes/moving_force_string.toml` (EI = 0: linear C0 elements; F = 100 N at V = c/2, \
         pinned ends, 0.6 s). Error against the analytic string solution (the library's \
         `error` column, reference \"analytic\") on the coarsest time grid (4e-4 s), order \
         from successive errors. Left: `{}`; the last two columns: `{}` (Δt fixed; N as in the \
         second column).\n",
        both.cmd,
        mesh.cmd
    );
    table(
        d,
        &[
            "level",
            "N",
            "Δt (s)",
            "F h/(4T_e) (m)",
            "error L2 (m)",
            "order",
            "error L2 / (F h/4T_e)",
            "error max (m)",
            "order",
            "order, successive diff.",
            "Δt = 2.5e-5: error L2 (m)",
            "order",
        ],
        &rows,
    );
    let range = |v: &[f64]| {
        v.iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &r| (a.min(r), b.max(r)))
    };
    let (rmin, rmax) = range(&ratios);
    let (mmin, mmax) = range(&max_ratio);
    w!(
        d,
        "**Measured: first order.** L2 orders {} with h and Δt refined together, {} with Δt \
         fixed, so the error is the mesh's. **Why:** under a moving force the string's \
         quasi-static shape has a kink at the load, a slope jump F/T_e with \
         T_e = T − ρAV² = {te:.0} N. Linear elements carry kinks only at nodes; at a load \
         inside an element they give the chord, off by (F/T_e)·s(1 − s)·h at local position \
         s, at most (F/T_e)·h/4, which is first order in h. The L2 error is a fixed fraction \
         of that bound at every level ({rmin:.3}–{rmax:.3}; the chord error alone, averaged \
         over the load's position in the element, would give sqrt(16/30) = 0.730). The max \
         error converges more slowly (orders {}) and is {mmin:.1}–{mmax:.1} times the bound; \
         it is not analysed further here.\n",
        finite_f2(&o_both),
        finite_f2(&o_mesh),
        finite_f2(&o_max)
    );

    // 2b. Hermite beam under a moving force
    w!(
        d,
        "### 2b. Moving force on the Hermite beam: h refined at Δt = 6.25e-6 s\n"
    );
    let s = study(
        "moving_force_beam",
        &[set("time.step", "6.25e-6"), set("mesh.elements", 100)],
        Refine::Mesh,
        6,
        false,
        clock,
    );
    let c = &s.c;
    let bb = &c.scenes[0].beam;
    let lb = (bb.ei / bb.tension).sqrt();
    let w: Vec<Vec<f64>> = (0..6).map(|l| coarse(c, l, |tr, i| tr.w[i])).collect();
    let (dm, d2) = (successive(&w, max_norm), successive(&w, l2_norm));
    let (pm, p2) = (orders(&dm), orders(&d2));
    check_orders(c, "displacement_history_max", &pm);
    check_orders(c, "displacement_history_l2", &p2);
    let mut rows = Vec::new();
    let mut errs = Vec::new();
    for l in 0..6 {
        let n = c.scenes[l].elements;
        let h = bb.length / n as f64;
        let e = sub(&on_grid(&c.runs[l], EXACT_DT, |tr, i| tr.w[i]), exact);
        errs.push(l2_norm(&e));
        rows.push(vec![
            l.to_string(),
            n.to_string(),
            format!("{h}"),
            format!("{:.2}", h / lb),
            e3(dm[l]),
            f2(pm[l]),
            e3(d2[l]),
            f2(p2[l]),
            e3(row(c, l, "displacement_history_l2").gci),
            e3(max_norm(&e)),
            e3(l2_norm(&e)),
        ]);
    }
    w!(
        d,
        "`{}`. ℓ_b = sqrt(EI/T) = {lb:.4} m is the bending length; error against the \
         analytic series on the {EXACT_DT} s grid.\n",
        s.cmd
    );
    table(
        d,
        &[
            "level",
            "N",
            "h (m)",
            "h/ℓ_b",
            "‖Δw‖_max (m)",
            "order",
            "‖Δw‖_L2 (m)",
            "order",
            "GCI (L2)",
            "error max (m)",
            "error L2 (m)",
        ],
        &rows,
    );
    w!(
        d,
        "**Measured: no constant spatial order in this range.** The L2 orders rise {} \
         (max: {}) over N = 100 … 3200 (h/ℓ_b = {:.1} … {:.2}). On the coarse meshes the \
         elements are longer than ℓ_b: at the element scale the beam is string-like and its \
         near-kink under the load (width ~ℓ_b, §3) is not resolved, as for the string (§2a). \
         Where the asymptotic order lies (the finest pair, h < ℓ_b, gives {:.2}) is not \
         measured. The error against the analytic solution falls with the differences to \
         N = 1600 and then stops ({} → {} m) while the differences keep falling: the \
         remainder is common to both meshes, not spatial. The time error at Δt = 6.25e-6 s is \
         the likely remainder (§1a's successive differences at that Δt are 1e-7–3e-7 m); it \
         is not separated here.\n",
        joined(
            p2.iter()
                .filter(|x| x.is_finite())
                .map(|x| format!("{x:.2}")),
            " → "
        ),
        finite_f2(&pm),
        bb.length / 100.0 / lb,
        bb.length / 3200.0 / lb,
        p2[5],
        e3(errs[4]),
        e3(errs[5])
    );

    // 2c. eigenfrequencies
    w!(
        d,
        "### 2c. Eigenfrequencies of the clamped–pinned tensioned beam\n"
    );
    w!(
        d,
        "FE frequencies from `taut::model::modal::fe_frequencies` (consistent mass, dense \
         generalized eigenproblem, at most 2000 dofs) against the exact roots of \
         `taut::analytic::ClampedPinnedModes`; relative error (ω_h − ω)/ω and order. \
         Round-off limits the relative error to about ε(ω_max/ω_j)²; entries within 10 times \
         that are marked and give no order. No CLI equivalent: each row is \
         `fe_frequencies(&props, N, ·)` on the `BeamProps` stated. The reference section and \
         tension throughout \
         (EI = {:.1} N·m², T = {:.0} N, ρA = {} kg/m, ℓ_b = {lb:.4} m).\n",
        bb.ei,
        bb.tension,
        bb.rho_a
    );
    let reference = resolve_scene(&scene_text("reference"), &[]).expect("reference scene");
    let rb = reference.beam.clone();
    let mut cp = Vec::new();
    for (length, ns) in [
        (rb.length, vec![10usize, 20, 40, 80, 160, 320, 640]),
        (5.0, vec![10, 20, 40, 80, 160]),
    ] {
        let props = BeamProps {
            length,
            left: Support::Clamped,
            right: Support::Pinned,
            ..rb.clone()
        };
        let ex = ClampedPinnedModes::new(props.ei, props.tension, props.rho_a, length)
            .expect("modes")
            .frequencies(10);
        w!(
            d,
            "Clamped–pinned, L = {length} m (L/ℓ_b = {:.0}). Exact ω₁, ω₅, ω₁₀ = {:.4}, \
             {:.4}, {:.4} rad/s.\n",
            length / lb,
            ex[0],
            ex[4],
            ex[9]
        );
        cp.push(eigen_table(d, &props, &ex, &ns, lb));
    }
    let pp = BeamProps {
        left: Support::Pinned,
        right: Support::Pinned,
        ..rb.clone()
    };
    let ex = PinnedPinnedModes::new(pp.ei, pp.tension, pp.rho_a, pp.length)
        .expect("modes")
        .frequencies(10);
    w!(
        d,
        "The same 50 m beam pinned–pinned (exact: `PinnedPinnedModes`, sine modes; no \
         boundary layer):\n"
    );
    let (pp_errors, pp_orders) = eigen_table(d, &pp, &ex, &[10, 20, 40, 80, 160], lb);
    // clamped–pinned over pinned–pinned error, same N (the first five rows) and mode
    let decades: Vec<f64> = cp[0]
        .0
        .iter()
        .zip(&pp_errors)
        .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x / y).abs().log10()))
        .filter(|x| x.is_finite())
        .collect();
    let (dmin, dmax) = decades
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    // the reference mesh itself
    let props400 = BeamProps {
        left: Support::Clamped,
        right: Support::Pinned,
        ..rb.clone()
    };
    let ex400 = ClampedPinnedModes::new(rb.ei, rb.tension, rb.rho_a, rb.length)
        .expect("modes")
        .frequencies(10);
    let fe400 = fe_frequencies(&props400, reference.elements, 10).expect("modal solve");
    let (e400min, e400max) = fe400
        .iter()
        .zip(&ex400)
        .map(|(a, b)| (a - b) / b)
        .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    clock.lap("eigenfrequencies");
    let last50 = cp[0].1.last().unwrap();
    let last5 = cp[1].1.last().unwrap();
    w!(
        d,
        "**Measured.** Clamped–pinned, 50 m: every low mode is too high by the same relative \
         amount, and the order climbs from about 1 to {:.2} at N = 640 (h = {:.2} ℓ_b) \
         without settling. 5 m: the order reaches {:.2}–{:.2} at h = {:.2} ℓ_b, the Hermite \
         cubics' O(h⁴). At equal h/ℓ_b the two spans show similar orders: the order is set by \
         how well the elements resolve ℓ_b, not by the span. Pinned–pinned, the same 50 m \
         beam has errors {dmin:.1} to {dmax:.1} decades smaller than clamped–pinned at equal N \
         and mode, with orders {} for mode 10 (above 4: these modes are tension-dominated, \
         and cubics converge the tension part of the eigenvalue at h⁶, the bending part at \
         h⁴) until round-off. That contrast points at the clamp: it forces v′ = 0 on modes \
         that are string-like away from it, and the mode bends back to its string slope within \
         a boundary layer of width ~ℓ_b, which elements longer than ℓ_b cannot represent; \
         the explanation fits the numbers but is not itself measured. The FE frequencies of \
         the reference span reach the theory's h⁴ only for N ≳ L/ℓ_b ≈ {:.0}; the reference \
         mesh (N = {}) is {} to {} high in its first ten modes.\n",
        last50[0],
        rb.length / 640.0 / lb,
        last5.iter().cloned().fold(f64::MAX, f64::min),
        last5.iter().cloned().fold(f64::MIN, f64::max),
        5.0 / 160.0 / lb,
        finite_f2(&pp_orders.iter().map(|o| o[2]).collect::<Vec<_>>()),
        rb.length / lb,
        reference.elements,
        e3(e400min),
        e3(e400max)
    );
    vec![format!(
        "**Space.** Taut string, linear elements: first order (L2 {}), the kink under \
             the load inside an element. Hermite beam under a moving force: no constant order \
             up to N = 3200 (L2 orders {}), pre-asymptotic while h > ℓ_b = {lb:.3} m. \
             Clamped–pinned eigenfrequencies: order climbs to {:.2} at N = 640 on the \
             reference span; O(h⁴) ({:.2}) on a 5 m span once h < ℓ_b; the clamp's boundary \
             layer of width ℓ_b sets the asymptotic range.",
        finite_f2(&o_both),
        finite_f2(&p2),
        last50[0],
        last5[0]
    )]
}
