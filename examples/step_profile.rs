//! Where a step's time goes, and how far it is from its limit.
//!
//! `cargo run --release --example step_profile [-- N [BLOCKS]]` (default
//! N = 800 elements, 40 blocks). Each figure is the fastest of BLOCKS blocks
//! of 1000 repetitions (the minimum is robust to a busy machine; the careful
//! statistics are criterion's, `cargo bench --bench step`). Printed per
//! unknown (ns per DOF) so the parts add up to the step:
//!
//! * the latency of one dependent f64 add and multiply on this machine;
//! * the dependency-chain floor of a step, 2·(t_mul + t_add) per unknown: in
//!   each of the two triangular sweeps, row i needs row i − 1 through one
//!   multiply and one subtract, whatever else the sweep computes
//!   (docs/performance.md, "The limit");
//! * the two sweeps alone, for the free step and one contact direction
//!   (k = 2 right-hand sides, as in the reference scene);
//! * the generalized-α residual as a pass of its own, and the residual fused
//!   into the forward sweep (`BandedLdlt::solve_affine`, as the step runs);
//! * the whole `Integrator::step` on the reference scene.
use std::hint::black_box;
use std::time::Instant;

use taut::integrate::Integrator;
use taut::model::banded::{Affine, BandedLdlt, affine_into};
use taut::model::beam::BeamModel;

const SCENE: &str = include_str!("../scenes/reference.toml");

/// Repetitions per timed block.
const REPS: usize = 1000;

/// Dependent operations per latency measurement.
const CHAIN: usize = 20_000_000;

/// Fastest of `blocks` blocks of REPS calls of `g`, seconds per call.
fn fastest(blocks: usize, g: &mut dyn FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..blocks {
        let t0 = Instant::now();
        for _ in 0..REPS {
            g();
        }
        best = best.min(t0.elapsed().as_secs_f64() / REPS as f64);
    }
    best
}

/// Seconds per operation of a chain of dependent f64 operations.
fn latency(op: fn(f64, f64) -> f64, y: f64) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let (mut x, y) = (black_box(1.0), black_box(y));
        let t0 = Instant::now();
        for _ in 0..CHAIN {
            x = op(x, y);
        }
        black_box(x);
        best = best.min(t0.elapsed().as_secs_f64() / CHAIN as f64);
    }
    best
}

fn main() {
    let mut args = std::env::args().skip(1);
    let elements: usize = args.next().map_or(800, |s| s.parse().expect("N: elements"));
    let blocks: usize = args.next().map_or(40, |s| s.parse().expect("BLOCKS"));
    let sc = taut::resolve_scene(SCENE, &[format!("mesh.elements={elements}")]).expect("scene");

    let t_add = latency(|x, y| x + y, 1e-9);
    let t_mul = latency(|x, y| x * y, 1.000_000_001);

    // the matrices of the reference scene; A as the integrator forms it
    let beam = BeamModel::new(&sc.beam, sc.elements);
    let n = beam.n;
    let taut::scene::Scheme::GenAlpha(ga) = sc.method.scheme else {
        unreachable!("the reference scene runs generalized-α")
    };
    let c_k = (1.0 - ga.alpha_f) * ga.beta * sc.dt * sc.dt;
    let fac = BandedLdlt::factor(&beam.mass.combine(1.0 - ga.alpha_m, &beam.stiffness, c_k))
        .expect("A is positive definite");
    let h: Vec<f64> = (0..n).map(|i| 1e-3 * (i as f64 * 0.01).sin()).collect();
    let u: Vec<f64> = (0..n).map(|i| 1e-4 * (i as f64 * 0.02).cos()).collect();
    let k = 2;
    let src: Vec<f64> = (0..n * k).map(|i| (i as f64 * 0.37).sin()).collect();
    let mut x = vec![0.0; n * k];
    let r = Affine {
        h: &h,
        k: &beam.stiffness,
        u: &u,
    };
    let mut b0 = vec![0.0; n];

    let copy = fastest(blocks, &mut || {
        x.copy_from_slice(&src);
        black_box(&x);
    });
    let sweeps = fastest(blocks, &mut || {
        x.copy_from_slice(&src);
        fac.solve_many(&mut x, k);
        black_box(&x);
    }) - copy;
    let mut x1 = vec![0.0; n];
    let sweeps_one = fastest(blocks, &mut || {
        x1.copy_from_slice(&src[..n]);
        fac.solve_many(&mut x1, 1);
        black_box(&x1);
    }) - copy / 2.0;
    let residual = fastest(blocks, &mut || {
        affine_into(&r, &mut x, k);
        black_box(&x);
    });
    let fused = fastest(blocks, &mut || {
        x.copy_from_slice(&src);
        fac.solve_affine(&mut x, k, &r, &mut b0);
        black_box(&x);
    }) - copy;
    let mut it = Integrator::new(&sc).expect("integrator");
    let dofs = it.dofs();
    let mut taken = 0;
    let step = fastest(blocks, &mut || {
        // restart before the carrier can leave the beam
        if taken + 1 >= sc.steps {
            it = Integrator::new(&sc).expect("integrator");
            taken = 0;
        }
        it.step().expect("step");
        taken += 1;
    });

    let per = |t: f64| t * 1e9 / n as f64;
    println!("N = {elements} elements, {n} beam unknowns ({dofs} with the mass)");
    println!(
        "  dependent add {:.3} ns, dependent multiply {:.3} ns",
        t_add * 1e9,
        t_mul * 1e9
    );
    println!("  {:<44} {:>9} {:>12}", "part", "µs", "ns per dof");
    let row = |name: &str, t: f64| println!("  {name:<44} {:>9.2} {:>12.3}", t * 1e6, per(t));
    row(
        "chain floor of a step: 2(t_mul + t_add)·n",
        2.0 * (t_mul + t_add) * n as f64,
    );
    row("two sweeps, k = 1 (no contact)", sweeps_one);
    row("two sweeps, k = 2", sweeps);
    row("residual as its own pass", residual);
    row("residual fused into the sweeps", fused);
    row("whole step (Integrator::step)", step);
    println!(
        "  step: {:.3e} DOF-steps/s; fusion hides {:.0} % of the residual pass",
        dofs as f64 / step,
        100.0 * (1.0 - (fused - sweeps) / residual)
    );
}
