//! Step-loop throughput on the reference scene.
//!
//! Group `step`: a fixed number of `Integrator::step` calls at N = 200, 800
//! and 3200 elements, reported as DOF-steps per second (criterion's
//! "elements/s" = unknowns × steps / s). The integrator is rebuilt for every
//! iteration outside the timed part, so each timed block starts at t = 0 and
//! the carrier never runs off the beam.
//!
//! Group `shapes`: the same at N = 800 for the other shapes of a step — two
//! contacts (`scenes/two_pantographs.toml`: three right-hand-side columns,
//! padded to four) and a moving force without a contact
//! (`scenes/moving_force_beam.toml`: one column, padded to two).
//!
//! Group `methods`: the same at N = 800 for every time integrator
//! (`[integrator] method`, MODEL §9.1), the reference scene at its Δt =
//! 1e-4 s; central difference, explicit, at 0.9 of its stability limit
//! (2/ω_max ≈ 1.5e-5 s there), since it refuses larger steps.
//!
//! Group `run`: one complete `taut::run` of the reference scene as shipped
//! (400 elements, 6000 steps, recording included), for context.
//!
//! Run with `cargo bench --bench step`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use taut::integrate::Integrator;

const SCENE: &str = include_str!("../scenes/reference.toml");
const TWO_CONTACTS: &str = include_str!("../scenes/two_pantographs.toml");
const MOVING_FORCE: &str = include_str!("../scenes/moving_force_beam.toml");

/// Steps timed per iteration (0.1 s of simulated time at Δt = 1e-4 s).
const STEPS_PER_ITER: usize = 1000;

/// Element counts of the `step` group.
const ELEMENTS: [usize; 3] = [200, 800, 3200];

fn resolved(overrides: &[String]) -> taut::Resolved {
    taut::resolve_scene(SCENE, overrides).expect("reference scene resolves")
}

/// Time STEPS_PER_ITER steps of a fresh integrator for `sc` as DOF-steps/s.
fn bench_steps(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    name: &str,
    sc: &taut::Resolved,
) {
    let dofs = Integrator::new(sc).expect("integrator builds").dofs();
    group.throughput(Throughput::Elements((dofs * STEPS_PER_ITER) as u64));
    group.bench_function(format!("{name}/dofs={dofs}"), |b| {
        b.iter_batched(
            || Integrator::new(sc).expect("integrator builds"),
            |mut it| {
                for _ in 0..STEPS_PER_ITER {
                    it.step().expect("step succeeds");
                }
                black_box(it.beam_dofs()[0]);
                it
            },
            BatchSize::PerIteration,
        );
    });
}

fn bench_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group.sample_size(10).warm_up_time(Duration::from_secs(1));
    for n in ELEMENTS {
        // ≈ 5–10 ns per DOF-step: an iteration takes ≈ 2 ms at N = 200, 8 ms at
        // 800 and 65 ms at 3200, so N = 3200 needs a longer window for 10 samples.
        group.measurement_time(Duration::from_secs(if n >= 3200 { 10 } else { 4 }));
        let sc = resolved(&[format!("mesh.elements={n}")]);
        bench_steps(&mut group, &format!("N={n}"), &sc);
    }
    group.finish();
}

fn bench_shapes(c: &mut Criterion) {
    let mut group = c.benchmark_group("shapes");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    let n800 = ["mesh.elements=800".to_string()];
    for (name, text) in [
        ("two_contacts", TWO_CONTACTS),
        ("moving_force", MOVING_FORCE),
    ] {
        let sc = taut::resolve_scene(text, &n800).expect("bundled scene resolves");
        bench_steps(&mut group, &format!("{name}/N=800"), &sc);
    }
    group.finish();
}

fn bench_methods(c: &mut Criterion) {
    let mut group = c.benchmark_group("methods");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for m in taut::scene::Method::ALL {
        let mut o = vec![
            "mesh.elements=800".to_string(),
            format!("integrator={{ method = \"{}\" }}", m.name()),
        ];
        if m == taut::scene::Method::CentralDifference {
            let limit = taut::integrate::central_difference_limit(&resolved(&o)).expect("M");
            o.push(format!("time.step={:e}", 0.9 * limit.dt_max));
        }
        let sc = resolved(&o);
        bench_steps(&mut group, &format!("{}/N=800", m.name()), &sc);
    }
    group.finish();
}

fn bench_run(c: &mut Criterion) {
    let sc = resolved(&[]);
    let dofs = Integrator::new(&sc).expect("integrator builds").dofs();
    let mut group = c.benchmark_group("run");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(7))
        // DOF-steps of the whole run, comparable with the `step` group
        .throughput(Throughput::Elements((dofs * sc.steps) as u64));
    group.bench_function("reference", |b| {
        b.iter(|| {
            let out = taut::run(black_box(&sc), &mut |_, _| {}).expect("run succeeds");
            black_box(out.steps)
        });
    });
    group.finish();
}

criterion_group!(benches, bench_step, bench_shapes, bench_methods, bench_run);
criterion_main!(benches);
