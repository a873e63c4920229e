//! A moving mass verified independently (MODEL §2, §9.2): a riding mass on a
//! pinned–pinned tensioned beam against the Galerkin solution in the exact
//! modes (`src/analytic/riding_mass.rs`), which has no finite-element code on
//! its path (its equations carry the convective terms w_tt + 2V w_xt + V² w_xx
//! at x_m explicitly; RK4 in time).
//!
//! Configuration: `scenes/riding_mass_pinned.toml` — the study's wire
//! (L = 50 m, T = 30 kN, ρA = 1.335 kg/m, EI = 129.2 N·m², c = 149.9 m/s),
//! pinned at both ends; a 30 kg mass without spring riding on top (bilateral
//! contact, gravity on the mass) at 75 m/s = 0.5 c from x = 0, for 0.4 s.
//!
//! Checks:
//! * the Galerkin solution converges in J (w and filtered λ);
//! * `taut converge` picks it as the analytic reference for this scene (and
//!   not for a spring or a unilateral contact), and the CLI reports its errors;
//! * the FE displacement under the mass converges to it as (N, Δt) are
//!   refined together, (50, 4e-4 s) → (200, 1e-4 s), with an observed order
//!   and a finest-level error bounded by named tolerances;
//! * the FE contact force, low-pass filtered (both signals alike), converges
//!   to the Galerkin force on the same ladder.
//!
//! The longer ladder (N = 400, J = 1600) is `#[ignore]`d: run it with
//! `cargo test --release --test numerics verification_riding_mass:: -- --ignored --nocapture`.

use crate::common;
use common::{out_dir, run, scene, taut_bin};
use taut::analytic::RidingMassHistory;
use taut::study::uncertainty::observed_order;

const SCENE: &str = "riding_mass_pinned.toml";

/// Galerkin modes of the default reference: w within ≈ 5e-6 m of the J → ∞
/// limit (measured: 1.8e-5 m change from 800 to 1600 modes, falling like
/// J^-2.3), ten times below the finest FE error checked here.
const J_REFERENCE: usize = 800;

/// Lowest observed order of the FE error in w against the reference under
/// joint (h, Δt) halving: generalized-α is second order in time and the
/// Hermite interpolation of the moving contact second order in space;
/// measured 1.79 and 2.03, so 1.6 allows pre-asymptotic scatter, not a
/// first-order error.
const MIN_FE_ORDER: f64 = 1.6;

/// Max error in w at (N, Δt) = (200, 1e-4 s), m: measured 4.36e-5 m
/// (2.2e-4 of max |w| = 0.196 m); the bound adds 15 % for the reference's
/// own ≈ 5e-6 m truncation error.
const MAX_FE_ERROR_W: f64 = 5.0e-5;

/// Lowest observed order of the Galerkin w under J doubling (200 → 400 →
/// 800): measured 2.4; a string-like J⁻¹ tail would give 1, so 1.5
/// separates the two.
const MIN_J_ORDER: f64 = 1.5;

/// Half-width of the centred moving average applied to both forces, in
/// coarse samples (4e-4 s): a 20 ms window removes the element-crossing
/// excitation (V/h = 75–300 Hz on this ladder) and the step-to-step
/// oscillation of the bilateral multiplier, keeping the response below
/// ≈ 25 Hz that the mesh resolves. It is applied to FE and reference alike.
const FILTER_HALF_WIDTH: usize = 25;

/// ρ∞ of generalized-α for the force ladder. A mass riding over C¹ Hermite
/// elements gets a kick in its multiplier at every node (the curvature of
/// its path jumps there), which excites the mesh's highest modes. ρ∞ = 0
/// annihilates the unresolved ones in a step; with ρ∞ = 1 (the scene's
/// default, no dissipation) the filtered force error does not fall
/// monotonically (measured 13.2, 20.9, 30.7, 8.1 N at N = 50 … 400) and with
/// ρ∞ = 0.8 it stalls (13.0, 7.9, 5.6, 4.2 N).
const FORCE_RHO_INF: &str = "integrator.rho_inf=0";

/// Max filtered-force error at (200, 1e-4 s), N: measured 2.32 N (0.8 % of
/// the 294 N weight); the bound leaves 15 % for platform round-off and the
/// reference's own filtered error (0.06 N change from J = 400 to 800).
const MAX_FE_ERROR_FORCE: f64 = 2.7;

/// Each (h, Δt) halving must shrink the filtered-force error by at least
/// this factor: measured 2.33 and 2.0 (3.2 on to N = 400): about first
/// order, the node kicks above; 1.6 fails a stalled or diverging force.
const MIN_FORCE_RATIO: f64 = 1.6;

/// `analytic_w` at a sample time is the Hermite interpolant at s ≈ 0: the
/// sample itself up to a few ulps of w.
const SAMPLE_ULPS: f64 = 16.0 * f64::EPSILON;

/// The (N, Δt) ladder, coarsest first; Δt halves with h as in
/// `taut converge --refine both`.
const LADDER: [(usize, &str); 3] = [(50, "4e-4"), (100, "2e-4"), (200, "1e-4")];

/// The coarse sampling interval of the ladder, s.
const DT0: f64 = 4e-4;

fn galerkin(modes: usize) -> RidingMassHistory {
    let sc = scene(SCENE, &[]);
    let r = taut::study::reference::riding_mass_beam(&sc).expect("a riding-mass scene");
    r.solve(modes, r.max_step(modes), DT0, sc.steps as f64 * sc.dt)
        .unwrap()
}

/// (w, λ) of one FE level sampled on the coarse grid.
fn fe(n: usize, dt: &str, extra: &[&str]) -> (Vec<f64>, Vec<f64>) {
    let mut o = vec![format!("mesh.elements={n}"), format!("time.step={dt}")];
    o.extend(extra.iter().map(|s| s.to_string()));
    let o: Vec<&str> = o.iter().map(String::as_str).collect();
    let sc = scene(SCENE, &o);
    let stride = (DT0 / sc.dt).round() as usize;
    let out = run(&sc);
    let c = &out.history.carriers[0];
    (
        c.w.iter().step_by(stride).copied().collect(),
        c.force.iter().step_by(stride).copied().collect(),
    )
}

/// `[a, b, …]` in scientific notation.
fn sci(v: &[f64]) -> String {
    let s: Vec<String> = v.iter().map(|x| format!("{x:.3e}")).collect();
    format!("[{}]", s.join(", "))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Centred moving average over full windows only: the first and last
/// [`FILTER_HALF_WIDTH`] samples are dropped (a one-sided window at the ends
/// would pass the oscillation the filter is there to remove).
fn filtered(v: &[f64]) -> Vec<f64> {
    let k = FILTER_HALF_WIDTH;
    (k..v.len().saturating_sub(k))
        .map(|i| v[i - k..=i + k].iter().sum::<f64>() / (2 * k + 1) as f64)
        .collect()
}

#[test]
fn galerkin_solution_converges_in_the_number_of_modes() {
    let h: Vec<RidingMassHistory> = [200, 400, J_REFERENCE].map(galerkin).into();
    let dw: Vec<f64> = h.windows(2).map(|p| max_diff(&p[0].w, &p[1].w)).collect();
    let df: Vec<f64> = h
        .windows(2)
        .map(|p| max_diff(&filtered(&p[0].force), &filtered(&p[1].force)))
        .collect();
    let order = observed_order(dw[0], dw[1], 2.0);
    println!(
        "Galerkin J = 200, 400, 800: Δw {} m (order {order:.2}), filtered Δλ {} N",
        sci(&dw),
        sci(&df)
    );
    assert!(order >= MIN_J_ORDER, "order in J {order} < {MIN_J_ORDER}");
    assert!(df[1] < df[0], "filtered force not converging in J: {df:?}");
}

#[test]
fn converge_uses_the_galerkin_reference_for_this_scene() {
    let sc = scene(SCENE, &[]);
    let w = taut::study::reference::analytic_w(&sc).expect("a riding-mass reference");
    let g = galerkin(taut::study::reference::riding_mass_modes(sc.elements));
    for (i, &t) in g.t.iter().enumerate().step_by(50) {
        let d = (w(t) - g.w[i]).abs();
        assert!(
            d <= SAMPLE_ULPS * g.w[i].abs(),
            "t = {t}: {} vs {}",
            w(t),
            g.w[i]
        );
    }
    // a spring or a unilateral contact is not this case: the declared
    // reference refuses the scene, naming reference.kind and the key
    for (o, key) in [
        ("carrier.0.stiffness=1000", "carrier.stiffness"),
        ("contact.kind=unilateral", "contact.kind"),
    ] {
        let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
            .join("scenes")
            .join(SCENE);
        let e = taut::load_scene(&path, &[o.to_string()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("reference.kind") && e.contains(key), "{o}: {e}");
    }
    // without the declaration the scene has no exact reference
    let plain = scene(SCENE, &["reference.kind=richardson"]);
    assert!(taut::study::reference::analytic_w(&plain).is_none());
}

#[test]
fn fe_displacement_and_filtered_force_converge_to_the_galerkin_solution() {
    let g = galerkin(J_REFERENCE);
    let ew: Vec<f64> = LADDER
        .iter()
        .map(|&(n, dt)| max_diff(&fe(n, dt, &[]).0, &g.w))
        .collect();
    let gf = filtered(&g.force);
    let ef: Vec<f64> = LADDER
        .iter()
        .map(|&(n, dt)| max_diff(&filtered(&fe(n, dt, &[FORCE_RHO_INF]).1), &gf))
        .collect();
    let orders: Vec<f64> = ew
        .windows(2)
        .map(|e| observed_order(e[0], e[1], 2.0))
        .collect();
    println!(
        "FE vs Galerkin (J = {J_REFERENCE}), N = 50, 100, 200: max |Δw| {} m, orders {orders:.2?}; filtered max |Δλ| {} N",
        sci(&ew),
        sci(&ef)
    );
    for p in &orders {
        assert!(
            *p >= MIN_FE_ORDER,
            "observed order {p} < {MIN_FE_ORDER}: {orders:?}"
        );
    }
    assert!(ew[2] <= MAX_FE_ERROR_W, "w error {} m", ew[2]);
    for e in ef.windows(2) {
        assert!(e[0] >= MIN_FORCE_RATIO * e[1], "force errors {ef:?}");
    }
    assert!(ef[2] <= MAX_FE_ERROR_FORCE, "force error {} N", ef[2]);
}

/// The CLI path: `taut converge` on the bundled scene reports errors against
/// the analytic (Galerkin) reference, and they match the test's ladder.
#[test]
fn taut_converge_reports_the_galerkin_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "conv");
    let o = taut_bin(&[
        "converge",
        "scenes/riding_mass_pinned.toml",
        "--levels",
        "3",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("converge.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (quantity, error, reference) = (col("quantity"), col("error"), col("reference"));
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .filter(|r: &Vec<&str>| r[quantity] == "displacement_history_max")
        .collect();
    assert_eq!(rows.len(), 3);
    let errors: Vec<f64> = rows.iter().map(|r| r[error].parse().unwrap()).collect();
    for r in &rows {
        assert_eq!(r[reference], "riding_mass_galerkin", "{r:?}");
    }
    println!(
        "taut converge --levels 3: displacement_max errors {}",
        sci(&errors)
    );
    assert!(errors[2] <= MAX_FE_ERROR_W, "{errors:?}");
    for e in errors.windows(2) {
        assert!(
            observed_order(e[0], e[1], 2.0) >= MIN_FE_ORDER,
            "{errors:?}"
        );
    }
}

/// The longer ladder: N = 400 at Δt = 5e-5 s against J = 1600 (≈ 10 s).
#[test]
#[ignore]
fn longer_ladder() {
    let g = galerkin(1600);
    let g8 = galerkin(J_REFERENCE);
    println!(
        "Galerkin J = 800 → 1600: Δw {:.3e} m, filtered Δλ {:.3e} N",
        max_diff(&g8.w, &g.w),
        max_diff(&filtered(&g8.force), &filtered(&g.force))
    );
    let gf = filtered(&g.force);
    let mut ladder = LADDER.to_vec();
    ladder.push((400, "5e-5"));
    let ew: Vec<f64> = ladder
        .iter()
        .map(|&(n, dt)| max_diff(&fe(n, dt, &[]).0, &g.w))
        .collect();
    let ef: Vec<f64> = ladder
        .iter()
        .map(|&(n, dt)| max_diff(&filtered(&fe(n, dt, &[FORCE_RHO_INF]).1), &gf))
        .collect();
    let orders: Vec<f64> = ew
        .windows(2)
        .map(|e| observed_order(e[0], e[1], 2.0))
        .collect();
    println!(
        "FE vs Galerkin (J = 1600), N = 50 … 400: max |Δw| {} m, orders {orders:.2?}; filtered max |Δλ| {} N",
        sci(&ew),
        sci(&ef)
    );
    for p in &orders {
        assert!(
            *p >= MIN_FE_ORDER,
            "observed order {p} < {MIN_FE_ORDER}: {orders:?}"
        );
    }
}
