//! Where a `modal_exact` step's time goes: the whole step, the
//! fast shapes, the direct shapes, and a Hermite step for scale.
//!
//! `cargo run --release --example modal_profile [-- J [N]]` (default J = 800
//! galerkin modes, Hermite N = 1600, the reference scene at V0/c = 0.9,
//! Δt = 6.25e-5 s). A step is the mean over a whole run (the fastest of 7
//! runs: the clamped end's boundary layer costs more near it, and a
//! Hermite run's first steps carry subnormal numbers); the shapes are the
//! fastest of 30 blocks of 500 calls. The minimum is robust to a busy
//! machine; criterion's `cargo bench --bench step` has the careful
//! statistics.
use std::hint::black_box;
use std::time::Instant;

use taut::analytic::{FastShapes, ModeShapes};
use taut::integrate::Integrator;

const SCENE: &str = include_str!("../scenes/reference.toml");
const BLOCKS: usize = 30;
const REPS: usize = 500;
const RUNS: usize = 7;

fn fastest(g: &mut dyn FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..BLOCKS {
        let t0 = Instant::now();
        for _ in 0..REPS {
            g();
        }
        best = best.min(t0.elapsed().as_secs_f64() / REPS as f64);
    }
    best
}

/// Seconds per step over whole runs (the integrator built outside the
/// timing; every step of the run timed, sampled as a run records it): the
/// fastest of `RUNS` runs.
fn step_time(o: &[String]) -> f64 {
    let sc = taut::resolve_scene(SCENE, o).expect("scene");
    let mut best = f64::INFINITY;
    for _ in 0..RUNS {
        let mut it = Integrator::new(&sc).expect("integrator");
        let t0 = Instant::now();
        for _ in 0..sc.steps {
            it.step().expect("step");
            black_box(it.sample(0));
        }
        best = best.min(t0.elapsed().as_secs_f64() / sc.steps as f64);
    }
    best
}

/// Seconds per run-step of 8 runs at different speeds, stepped alone
/// (each a whole run in turn) and as one batch, over the first 4000 steps
/// (the fastest of `RUNS` repetitions).
fn batch_times(o: &[String]) -> (f64, f64) {
    use taut::integrate::new_batch;
    let steps = 4000;
    let scenes: Vec<taut::Resolved> = (0..8)
        .map(|i| {
            let mut o = o.to_vec();
            o.push(format!("carrier.speed.cruise={}", 100.0 + 5.0 * i as f64));
            taut::resolve_scene(SCENE, &o).expect("scene")
        })
        .collect();
    let (mut alone, mut batch) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..RUNS {
        let mut its: Vec<Integrator> = scenes
            .iter()
            .map(|s| Integrator::new(s).expect("run"))
            .collect();
        let t0 = Instant::now();
        for it in &mut its {
            for _ in 0..steps {
                it.step().expect("step");
                black_box(it.sample(0));
            }
        }
        alone = alone.min(t0.elapsed().as_secs_f64() / (8 * steps) as f64);
        let list: Vec<(usize, &taut::Resolved)> = scenes.iter().enumerate().collect();
        let mut b = new_batch(&list).0.expect("a batch");
        let t0 = Instant::now();
        for _ in 0..steps {
            b.step();
            for l in 0..8 {
                black_box(b.sample(l, 0));
            }
        }
        batch = batch.min(t0.elapsed().as_secs_f64() / (8 * steps) as f64);
    }
    (alone, batch)
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number"))
        .collect();
    let j = args.first().copied().unwrap_or(800);
    let n = args.get(1).copied().unwrap_or(1600);
    let speed = 0.9 * (3.0e4f64 / 1.335).sqrt();
    let common = vec![
        "time.step=6.25e-5".to_string(),
        format!("carrier.speed.cruise={speed}"),
    ];
    let mut modal = common.clone();
    modal.extend([
        "mesh.kind=galerkin".to_string(),
        format!("mesh.modes={j}"),
        "integrator={ method = \"modal_exact\" }".to_string(),
    ]);
    let mut hermite = common.clone();
    hermite.push(format!("mesh.elements={n}"));
    let t_modal = step_time(&modal);
    if std::env::var_os("MODAL_ONLY").is_some() {
        println!(
            "modal_exact step, galerkin J = {j}: {:8.3} µs",
            1e6 * t_modal
        );
        return;
    }
    let (t_alone, t_batch) = batch_times(&modal);
    let t_herm = step_time(&hermite);
    let sc = taut::resolve_scene(SCENE, &modal).expect("scene");
    let shapes = ModeShapes::new(&sc.beam, j).expect("basis");
    let fast = FastShapes::new(&shapes);
    let mut out = vec![0.0; j];
    let mut x = 0.0;
    let t_fast_mid = fastest(&mut || {
        x = if x > 40.0 { 10.0 } else { x + 0.0084 };
        fast.values_into(black_box(x), &mut out);
    });
    let t_fast_end = fastest(&mut || {
        x = if x > 1.0 { 0.0 } else { x + 0.0084 };
        fast.values_into(black_box(x), &mut out);
    });
    let t_direct = fastest(&mut || {
        x = if x > 40.0 { 10.0 } else { x + 0.0084 };
        shapes.values_into(black_box(x), &mut out);
    });
    // a cruise's restart (every RESYNC_STEPS rotated steps): the phasors'
    // imaginary parts from the tables, scalar
    let t_restart = fastest(&mut || {
        x = if x > 40.0 { 10.0 } else { x + 0.0084 };
        fast.phasor_im_into(black_box(x), &mut out);
    });
    println!(
        "modal_exact step, galerkin J = {j}:   {:8.3} µs",
        1e6 * t_modal
    );
    println!(
        "generalized-α step, Hermite N = {n}: {:8.3} µs  (ratio {:.1})",
        1e6 * t_herm,
        t_herm / t_modal
    );
    println!(
        "fast shapes, mid-span:              {:8.3} µs",
        1e6 * t_fast_mid
    );
    println!(
        "fast shapes, within 1 m of the clamp: {:6.3} µs",
        1e6 * t_fast_end
    );
    println!(
        "direct shapes (ModeShapes):         {:8.3} µs",
        1e6 * t_direct
    );
    println!(
        "a cruise's phasor restart:          {:8.3} µs (once every {} rotated steps)",
        1e6 * t_restart,
        taut::integrate::CRUISE_RESYNC_STEPS
    );
    println!(
        "8 runs (speeds 100…135 m/s), per run-step: alone {:.3} µs, as one batch {:.3} µs (×{:.2})",
        1e6 * t_alone,
        1e6 * t_batch,
        t_alone / t_batch
    );
}
