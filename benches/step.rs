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
//! Group `discretizations`: the per-step cost of each space discretization
//! (`[mesh] kind`, MODEL §9.2) on the reference beam: Hermite uniform and
//! graded at N = 800, and the modal bases (`galerkin`, `modal` of the
//! N = 800 model) at J = 50, 200 and 800, under generalized-α and under
//! `modal_exact`. The carrier crawls at 0.5 m/s so a
//! long-lived integrator is timed block after block (a modal basis's
//! eigenproblem is paid once per run, outside the timing; its cost is in
//! `model::eigen`'s docs).
//!
//! Group `fine`: the step loop from N = 800 to 6400 at Δt = 1e-4 s, alone
//! and as a batch of four speeds (`integrate::batch`), DOF-steps/s. The first
//! 1000 steps are timed, when the solve's decaying tails run ahead of the
//! waves over an undisturbed beam: without the sweeps' flush of negligible
//! values (`model::banded`, "Subnormals") they passed through the subnormal
//! range there, and DOF-steps/s fell up to 10× at N ≥ 1400 on an Intel Xeon.
//! The target: DOF-steps/s flat within 1.5× across N, alone and batched.
//!
//! Group `run`: one complete `taut::run` of the reference scene as shipped
//! (400 elements, 6000 steps, recording included), for context.
//!
//! Group `modal_exact`: one complete run of the reference case
//! at V0/c = 0.9, Δt = 6.25e-5 s (7115 steps, recording every step),
//! reported as steps per second: `modal_exact` on `galerkin` J = 400 and
//! 800, and generalized-α on Hermite N = 1600 for the per-step ratio (the
//! target: J = 800 at least 10× faster per step than N = 1600). Then eight
//! runs of a speed sweep at J = 800 alone and as one batch (sharing the
//! basis, `integrate::modal_batch`).
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
    // modal_exact needs a modal basis: the `modal` group below
    for m in taut::scene::Method::ALL.into_iter().filter(|m| {
        let hermite = taut::scene::Discretization::Hermite;
        m.accepts(&taut::scene::ContactSpec::default(), hermite)
            .is_ok()
    }) {
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

fn bench_discretizations(c: &mut Criterion) {
    let mut group = c.benchmark_group("discretizations");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    let crawl = [
        "mesh.elements=800".to_string(),
        "carrier.0.speed={ profile = \"constant\", value = 0.5 }".to_string(),
        "time.end=90".to_string(),
        "output.record_every=100000".to_string(),
    ];
    let exact = "integrator={ method = \"modal_exact\" }";
    let kinds: [(&str, &[&str]); 12] = [
        ("hermite", &[]),
        (
            "hermite_graded",
            &["mesh.grading=supports", "mesh.grading_ratio=8"],
        ),
        ("galerkin_J=50", &["mesh.kind=galerkin", "mesh.modes=50"]),
        ("galerkin_J=200", &["mesh.kind=galerkin", "mesh.modes=200"]),
        ("galerkin_J=800", &["mesh.kind=galerkin", "mesh.modes=800"]),
        ("modal_J=50", &["mesh.kind=modal", "mesh.modes=50"]),
        ("modal_J=200", &["mesh.kind=modal", "mesh.modes=200"]),
        ("modal_J=800", &["mesh.kind=modal", "mesh.modes=800"]),
        (
            "galerkin_J=50_modal_exact",
            &["mesh.kind=galerkin", "mesh.modes=50", exact],
        ),
        (
            "galerkin_J=200_modal_exact",
            &["mesh.kind=galerkin", "mesh.modes=200", exact],
        ),
        (
            "galerkin_J=800_modal_exact",
            &["mesh.kind=galerkin", "mesh.modes=800", exact],
        ),
        (
            "modal_J=800_modal_exact",
            &["mesh.kind=modal", "mesh.modes=800", exact],
        ),
    ];
    for (name, set) in kinds {
        let mut o = crawl.to_vec();
        o.extend(set.iter().map(|s| s.to_string()));
        let sc = resolved(&o);
        let mut it = Integrator::new(&sc).expect("integrator builds");
        let mut taken = 0;
        let dofs = it.dofs();
        group.throughput(Throughput::Elements((dofs * STEPS_PER_ITER) as u64));
        group.bench_function(format!("{name}/dofs={dofs}"), |b| {
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                for _ in 0..iters {
                    if taken + STEPS_PER_ITER > sc.steps {
                        // the carrier nears the end: start again, untimed
                        it = Integrator::new(&sc).expect("integrator builds");
                        taken = 0;
                    }
                    taken += STEPS_PER_ITER;
                    let start = std::time::Instant::now();
                    for _ in 0..STEPS_PER_ITER {
                        it.step().expect("step succeeds");
                    }
                    total += start.elapsed();
                    black_box(it.beam_dofs()[0]);
                }
                total
            });
        });
    }
    group.finish();
}

/// Group `batch`: runs that share a matrix stepped together
/// (`integrate::batch`): B reference runs at N = 1600 (a speed sweep,
/// Δt = 6.25e-5 s, 0.05 s of motion each) alone one after the other and as
/// one batch, reported as DOF-steps per second of all B runs on one core.
/// The target: batched throughput ≥ 4× the single-run throughput.
fn bench_batch(c: &mut Criterion) {
    let mut group = c.benchmark_group("batch");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(8));
    for b in [1usize, 2, 4, 8] {
        let scenes: Vec<taut::Resolved> = (0..b)
            .map(|i| {
                resolved(&[
                    "mesh.elements=1600".to_string(),
                    "time.step=6.25e-5".to_string(),
                    "time.end=0.05".to_string(),
                    format!("carrier.0.speed.cruise={}", 80.0 + 5.0 * i as f64),
                ])
            })
            .collect();
        let dofs = Integrator::new(&scenes[0]).expect("integrator").dofs();
        let steps: usize = scenes.iter().map(|s| s.steps).sum();
        group.throughput(Throughput::Elements((dofs * steps) as u64));
        group.bench_function(format!("alone/B={b}"), |bch| {
            bch.iter(|| {
                for sc in &scenes {
                    black_box(taut::run(sc, &mut |_, _| {}).expect("run").steps);
                }
            })
        });
        if b > 1 {
            group.bench_function(format!("batched/B={b}"), |bch| {
                bch.iter(|| black_box(taut::run_batch(&scenes, b, &mut |_| {}).len()))
            });
        }
    }
    group.finish();
}

/// Group `fine` (module docs).
fn bench_fine(c: &mut Criterion) {
    let mut group = c.benchmark_group("fine");
    group.sample_size(10).warm_up_time(Duration::from_secs(1));
    for n in [800usize, 1600, 3200, 6400] {
        // ≈ 10 ns per DOF-step: 0.13 s per iteration at N = 6400
        group.measurement_time(Duration::from_secs(if n >= 3200 { 15 } else { 6 }));
        let at = |speed: f64| {
            resolved(&[
                format!("mesh.elements={n}"),
                "time.step=1e-4".to_string(),
                format!("carrier.0.speed.cruise={speed}"),
            ])
        };
        bench_steps(&mut group, &format!("alone/N={n}"), &at(100.0));
        let scenes: Vec<taut::Resolved> = [90.0, 100.0, 110.0, 120.0].map(at).to_vec();
        let list: Vec<(usize, &taut::Resolved)> = scenes.iter().enumerate().collect();
        let dofs = Integrator::new(&scenes[0]).expect("integrator").dofs();
        group.throughput(Throughput::Elements(
            (dofs * STEPS_PER_ITER * scenes.len()) as u64,
        ));
        group.bench_function(format!("batched4/N={n}/dofs={dofs}"), |b| {
            b.iter_batched(
                || taut::integrate::Batch::new(&list).0.expect("one batch"),
                |mut batch| {
                    for _ in 0..STEPS_PER_ITER {
                        batch.step();
                    }
                    black_box(batch.lanes().len());
                    batch
                },
                BatchSize::PerIteration,
            );
        });
    }
    group.finish();
}

fn bench_modal_exact(c: &mut Criterion) {
    let mut group = c.benchmark_group("modal_exact");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(6));
    let speed = 0.9 * (3.0e4f64 / 1.335).sqrt();
    let case = |set: &[&str]| {
        let mut o = vec![
            "time.step=6.25e-5".to_string(),
            format!("carrier.0.speed.cruise={speed}"),
        ];
        o.extend(set.iter().map(|s| s.to_string()));
        resolved(&o)
    };
    let exact = "integrator={ method = \"modal_exact\" }";
    for (name, set) in [
        (
            "galerkin_J=400",
            vec!["mesh.kind=galerkin", "mesh.modes=400", exact],
        ),
        (
            "galerkin_J=800",
            vec!["mesh.kind=galerkin", "mesh.modes=800", exact],
        ),
        (
            "hermite_N=1600_generalized_alpha",
            vec!["mesh.elements=1600"],
        ),
    ] {
        let sc = case(&set);
        group.throughput(Throughput::Elements(sc.steps as u64));
        group.bench_function(name, |b| {
            b.iter(|| black_box(taut::run(&sc, &mut |_, _| {}).expect("run").steps))
        });
    }
    let sweep: Vec<taut::Resolved> = (0..8)
        .map(|i| {
            let v = format!("carrier.0.speed.cruise={}", 100.0 + 5.0 * i as f64);
            case(&["mesh.kind=galerkin", "mesh.modes=800", exact, v.as_str()])
        })
        .collect();
    let steps: usize = sweep.iter().map(|s| s.steps).sum();
    group.throughput(Throughput::Elements(steps as u64));
    group.bench_function("sweep_of_8_J=800/alone", |b| {
        b.iter(|| black_box(taut::run_batch(&sweep, 1, &mut |_| {}).len()))
    });
    group.bench_function("sweep_of_8_J=800/batched", |b| {
        b.iter(|| black_box(taut::run_batch(&sweep, 8, &mut |_| {}).len()))
    });
    group.finish();
}

criterion_group!(
    benches,
    bench_fine,
    bench_step,
    bench_shapes,
    bench_methods,
    bench_discretizations,
    bench_batch,
    bench_run,
    bench_modal_exact
);
criterion_main!(benches);
