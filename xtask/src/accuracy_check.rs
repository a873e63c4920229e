//! Checks behind docs/accuracy.md: does a quantity converge, and does an
//! accuracy-targeted run meet its tolerance against a finer run?
//!
//! ```sh
//! # the quantity's difference over an (N, Δt) grid: to the finest cell, and
//! # successive differences along each axis (on the first cell's time grid)
//! cargo xtask accuracy-check grid scenes/reference.toml force 400,800,1600,3200 1e-4,5e-5,2.5e-5,1.25e-5,6.25e-6
//! # `taut run --tolerance TOL --quantity Q`, then a run K× finer in h and Δt,
//! # and the chosen run's actual difference to it beside the estimate
//! cargo xtask accuracy-check check scenes/reference.toml force 1e-3 4 [key=value ...]
//! ```
//!
//! Trailing `key=value` arguments are `--set` overrides. Wall times go to the
//! terminal and depend on the machine.

use taut::study::tolerance::{Quantity, quantity_difference, result_values, tolerance_run};

fn usage() -> ! {
    eprintln!(
        "usage: cargo xtask accuracy-check grid SCENE QUANTITY N1,N2,.. DT1,DT2,.. [key=value ...]\n       cargo xtask accuracy-check check SCENE QUANTITY TOL K [key=value ...]"
    );
    std::process::exit(2)
}

/// The command: `cargo xtask accuracy-check grid|check …`.
pub fn main() {
    let a: Vec<String> = std::env::args().skip(2).collect();
    if a.len() < 5 {
        usage();
    }
    let text = std::fs::read_to_string(&a[1]).unwrap_or_else(|e| panic!("{}: {e}", a[1]));
    let q: Quantity = a[2].parse().unwrap_or_else(|e| panic!("{e}"));
    let sets = a[5..].to_vec();
    match a[0].as_str() {
        "grid" => grid(&text, q, &a[3], &a[4], &sets),
        "check" => check(&text, q, &a[3], &a[4], &sets),
        _ => usage(),
    }
}

fn run_at(text: &str, sets: &[String], n: usize, dt: f64) -> taut::RunOutput {
    let mut o = sets.to_vec();
    o.push(format!("mesh.elements={n}"));
    o.push(format!("time.step={dt:e}"));
    let sc = taut::resolve_scene(text, &o).unwrap_or_else(|e| panic!("{e}"));
    taut::run(&sc, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"))
}

fn grid(text: &str, q: Quantity, ns: &str, dts: &str, sets: &[String]) {
    let ns: Vec<usize> = ns.split(',').map(|s| s.parse().unwrap()).collect();
    let dts: Vec<f64> = dts.split(',').map(|s| s.parse().unwrap()).collect();
    let runs: Vec<Vec<taut::RunOutput>> = ns
        .iter()
        .map(|&n| dts.iter().map(|&dt| run_at(text, sets, n, dt)).collect())
        .collect();
    let g = &runs[0][0];
    let d = |a: &taut::RunOutput, b: &taut::RunOutput| {
        quantity_difference(q, a, b, g).unwrap_or_else(|e| panic!("{e}"))
    };
    let fin = &runs[ns.len() - 1][dts.len() - 1];
    let head: Vec<String> = dts.iter().map(|dt| format!("{dt:e}")).collect();
    println!("`{}`: {}", q.name(), q.description());
    println!(
        "\ndifference to the finest cell (N = {}, Δt = {:e} s)\n\n| N \\ Δt (s) | {} |",
        ns[ns.len() - 1],
        dts[dts.len() - 1],
        head.join(" | ")
    );
    println!("|---|{}", "---|".repeat(dts.len()));
    for (i, n) in ns.iter().enumerate() {
        let c: Vec<String> = runs[i]
            .iter()
            .map(|r| format!("{:.2e}", d(r, fin)))
            .collect();
        println!("| {n} | {} |", c.join(" | "));
    }
    println!("\nsuccessive differences as Δt halves, per N\n");
    for (i, n) in ns.iter().enumerate() {
        let c: Vec<String> = (1..dts.len())
            .map(|j| format!("{:.2e}", d(&runs[i][j - 1], &runs[i][j])))
            .collect();
        println!("N = {n}: {}", c.join(", "));
    }
    println!("\nsuccessive differences as N doubles, per Δt\n");
    for (j, dt) in dts.iter().enumerate() {
        let c: Vec<String> = (1..ns.len())
            .map(|i| format!("{:.2e}", d(&runs[i - 1][j], &runs[i][j])))
            .collect();
        println!("Δt = {dt:e} s: {}", c.join(", "));
    }
}

fn check(text: &str, q: Quantity, tol: &str, k: &str, sets: &[String]) {
    let tol: f64 = tol.parse().unwrap();
    let k: usize = k.parse().unwrap();
    let start = std::time::Instant::now();
    let r = tolerance_run(text, sets, q, tol, &mut |_, _| {}).unwrap_or_else(|e| panic!("{e}"));
    let total = start.elapsed().as_secs_f64();
    let a = &r.accuracy;
    println!(
        "--tolerance {tol:e} --quantity {}: N = {}, Δt = {:e} s ({} steps, {:.2e} DOF-steps{}); estimate {:.3e} (mesh {:.3e}, step {:.3e}); p = {:.2}, q = {:.2}; wall: pilots {:.2} s, run {:.2} s, in all {total:.2} s",
        q.name(),
        a.elements,
        a.dt,
        a.steps,
        a.dof_steps,
        a.met_by_pilot
            .map_or(String::new(), |p| format!(", pilot `{p}`")),
        a.estimated_error.total,
        a.estimated_error.mesh,
        a.estimated_error.step,
        a.p,
        a.q,
        a.pilot_wall_seconds,
        a.run_wall_seconds
    );
    if k == 0 {
        for res in &a.results {
            println!(
                "  {:<22} {:>12} {}",
                res.name,
                res.value.map_or("none".into(), |v| format!("{v:.5}")),
                res.estimated_error
                    .map_or(res.status.clone(), |e| format!("± {e:.2e}"))
            );
        }
        return;
    }
    let fine = run_at(text, sets, k * a.elements, a.dt / k as f64);
    let actual = quantity_difference(q, &r.output, &fine, &r.output).unwrap();
    println!(
        "finer run (N = {}, Δt = {:e} s, {:.1} s wall): difference {actual:.3e}, estimate {:.3e}, ratio {:.2}",
        k * a.elements,
        a.dt / k as f64,
        fine.wall_seconds,
        a.estimated_error.total,
        actual / a.estimated_error.total
    );
    // each result of carrier 0: its change to the finer run beside its estimate
    let finer = result_values(&fine, 0);
    for (res, v) in a.results.iter().filter(|x| x.carrier == 0).zip(finer) {
        let change = match (res.value, v) {
            (Some(x), Some(y)) => format!("{:.2e}", (x - y).abs()),
            _ => "n/a".into(),
        };
        println!(
            "  {:<22} chosen {:>12} finer {:>12}  |change| {change:>9}  {}",
            res.name,
            res.value.map_or("none".into(), |v| format!("{v:.5}")),
            v.map_or("none".into(), |v| format!("{v:.5}")),
            res.estimated_error
                .map_or(res.status.clone(), |e| format!("estimate ± {e:.2e}"))
        );
    }
}
