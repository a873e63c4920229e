//! The check behind docs/accuracy.md: does an accuracy-targeted run's
//! u_num cover its actual error against a finer run?
//!
//! ```sh
//! # `taut run --tolerance TOL --quantity Q`, then a run K× finer in h (J on
//! # a modal basis) and Δt, and each result's change to it beside its u_num
//! cargo xtask accuracy-check check scenes/reference.toml loss_fraction_span 2e-3 4 [key=value ...]
//! ```
//!
//! Trailing `key=value` arguments are `--set` overrides. Wall times go to the
//! terminal and depend on the machine.

use taut::study::sweep::SweepTolerance;
use taut::study::tolerance::tolerance_run;

fn usage() -> ! {
    eprintln!("usage: cargo xtask accuracy-check check SCENE QUANTITY TOL K [key=value ...]");
    std::process::exit(2)
}

/// The command: `cargo xtask accuracy-check check …`.
pub fn main() {
    let a: Vec<String> = std::env::args().skip(2).collect();
    if a.len() < 5 || a[0] != "check" {
        usage();
    }
    let text = std::fs::read_to_string(&a[1]).unwrap_or_else(|e| panic!("{}: {e}", a[1]));
    check(&text, &a[2], &a[3], &a[4], &a[5..]);
}

fn check(text: &str, q: &str, tol: &str, k: &str, sets: &[String]) {
    let tol: f64 = tol.parse().unwrap_or_else(|e| panic!("TOL {tol}: {e}"));
    let k: usize = k.parse().unwrap_or_else(|e| panic!("K {k}: {e}"));
    let target = SweepTolerance::new(q, tol, None).unwrap_or_else(|e| panic!("{e}"));
    let start = std::time::Instant::now();
    let r = tolerance_run(text, sets, &target, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"));
    let total = start.elapsed().as_secs_f64();
    let a = &r.accuracy;
    let p = &a.point;
    println!(
        "--tolerance {tol:e} --quantity {q}: N = {}, J = {:?}, Δt = {:e} s ({} runs, {:.2e} DOF-steps); value {:.6e} ± {:.3e} ({}); {total:.2} s wall",
        p.elements, p.modes, p.dt, p.runs, p.dof_steps, p.value, p.u_num, p.estimator
    );
    if k <= 1 {
        return;
    }
    let mut o = sets.to_vec();
    match p.modes {
        Some(j) => o.push(format!("mesh.modes={}", k * j)),
        None => o.push(format!("mesh.elements={}", k * p.elements)),
    }
    o.push(format!("time.step={:e}", p.dt / k as f64));
    let sc = taut::resolve_scene(text, &o).unwrap_or_else(|e| panic!("{e}"));
    let fine = taut::run(&sc, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"));
    println!(
        "finer run (×{k} in the level and 1/{k} Δt, {:.1} s wall):",
        fine.wall_seconds
    );
    for res in &a.results {
        let finer = taut::quantity::by_name(res.name).and_then(|q| q.of(&fine, 0));
        let change = match (res.value, finer) {
            (Some(x), Some(y)) => format!("{:.2e}", (x - y).abs()),
            _ => "n/a".into(),
        };
        println!(
            "  {:<24} reported {:>12} finer {:>12}  |change| {change:>9}  u_num {}",
            res.name,
            res.value.map_or("none".into(), |v| format!("{v:.5}")),
            finer.map_or("none".into(), |v| format!("{v:.5}")),
            res.u_num
                .map_or(format!("none ({})", res.behaviour), |u| format!("{u:.2e}"))
        );
    }
}
