//! Batched stepping (`integrate::batch`, `run::run_batch`): runs that share
//! their effective matrix step together, and every run's history and
//! statistics are bit-identical to the run alone — through retirement (runs
//! that end at different steps), a run that stops, and every batch width.

use taut::{Resolved, RunOutput, resolve_scene, run, run_batch};

const REFERENCE: &str = include_str!("../scenes/reference.toml");
const TWO: &str = include_str!("../scenes/two_pantographs.toml");

fn scene(text: &str, set: &[String]) -> Resolved {
    resolve_scene(text, set).unwrap_or_else(|e| panic!("{set:?}: {e}"))
}

/// Bits of everything a run records (wall time aside).
fn bits(o: &RunOutput) -> Vec<u64> {
    let mut v: Vec<u64> = o.history.t.iter().map(|x| x.to_bits()).collect();
    for c in &o.history.carriers {
        for col in [&c.x, &c.w, &c.q, &c.gap, &c.force] {
            v.extend(col.iter().map(|x| x.to_bits()));
        }
        v.extend(c.in_contact.iter().map(|&b| b as u64));
    }
    for (_, col) in &o.history.probes {
        v.extend(col.iter().map(|x| x.to_bits()));
    }
    v.push(o.steps as u64);
    v.push(o.dofs as u64);
    v
}

fn stats(o: &RunOutput) -> String {
    format!("{:?} {:?}", o.stats, o.warnings)
}

fn assert_same(scenes: &[Resolved], batch: usize) {
    let alone: Vec<_> = scenes.iter().map(|sc| run(sc, &mut |_, _| {})).collect();
    let together = run_batch(scenes, batch, &mut |_| {});
    assert_eq!(alone.len(), together.len());
    for (i, (a, b)) in alone.iter().zip(&together).enumerate() {
        match (a, b) {
            (Ok(a), Ok(b)) => {
                assert!(
                    bits(a) == bits(b),
                    "run {i} (batch {batch}): histories differ"
                );
                assert_eq!(stats(a), stats(b), "run {i} (batch {batch})");
            }
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "run {i}"),
            (a, b) => panic!(
                "run {i} (batch {batch}): alone {:?}, batched {:?}",
                a.as_ref().err().map(|e| e.to_string()),
                b.as_ref().err().map(|e| e.to_string())
            ),
        }
    }
}

#[test]
fn a_speed_sweep_is_bit_identical_in_batches_of_every_width() {
    // cruise speeds 60 … 130 m/s: the runs end at different steps (retirement)
    let scenes: Vec<Resolved> = (0..8)
        .map(|i| {
            scene(
                REFERENCE,
                &[
                    format!("carrier.0.speed.cruise={}", 60.0 + 10.0 * i as f64),
                    "mesh.elements=100".into(),
                    "time.step=2e-4".into(),
                ],
            )
        })
        .collect();
    for batch in [1, 2, 3, 4, 5, 8] {
        assert_same(&scenes, batch);
    }
}

#[test]
fn masses_springs_preloads_and_formulations_batch_bit_identically() {
    let mut scenes = Vec::new();
    for (m, k, pre) in [(1.0, 987.0, 0.05), (2.0, 500.0, 0.02), (0.5, 2000.0, 0.1)] {
        for f in ["lagrange", "penalty", "complementarity"] {
            scenes.push(scene(
                REFERENCE,
                &[
                    format!("carrier.0.mass={m}"),
                    format!("carrier.0.stiffness={k}"),
                    format!("carrier.0.preload={pre}"),
                    format!("contact.formulation={f}"),
                    "mesh.elements=100".into(),
                    "time.step=2e-4".into(),
                ],
            ));
        }
    }
    // the string (half-bandwidth 1) and two contacts (four columns per run)
    assert_same(&scenes, 4);
    let two: Vec<Resolved> = [0.5, 1.0, 1.5]
        .iter()
        .map(|m| scene(TWO, &[format!("carrier.1.mass={m}"), "time.end=0.2".into()]))
        .collect();
    assert_same(&two, 3);
    // wider than the four-column kernels: split into batches of at most four
    let six: Vec<Resolved> = (0..6)
        .map(|i| {
            scene(
                TWO,
                &[
                    format!("carrier.1.mass={}", 0.5 + 0.25 * i as f64),
                    "time.end=0.1".into(),
                ],
            )
        })
        .collect();
    assert_eq!(taut::integrate::max_lanes(4), 4);
    assert_same(&six, 8);
}

#[test]
fn a_run_that_stops_leaves_its_batch_without_touching_the_others() {
    // clarabel with one iteration fails at the first closed contact
    let mut scenes: Vec<Resolved> = (0..4)
        .map(|i| {
            scene(
                REFERENCE,
                &[
                    format!("carrier.0.speed.cruise={}", 80.0 + 10.0 * i as f64),
                    "mesh.elements=100".into(),
                    "time.step=2e-4".into(),
                ],
            )
        })
        .collect();
    scenes[1] = scene(
        REFERENCE,
        &[
            "carrier.0.speed.cruise=90".into(),
            "mesh.elements=100".into(),
            "time.step=2e-4".into(),
            "contact.formulation=complementarity".into(),
            "contact.complementarity.solver=clarabel".into(),
            "contact.complementarity.max_iter=1".into(),
        ],
    );
    let together = run_batch(&scenes, 4, &mut |_| {});
    assert!(together[1].is_err(), "the clarabel run must stop");
    assert_same(&scenes, 4);
}

#[test]
fn what_cannot_batch_runs_alone_with_the_same_answers() {
    // different meshes, a velocity-level law, another method, a modal basis
    let scenes: Vec<Resolved> = [
        vec!["mesh.elements=100".to_string()],
        vec!["mesh.elements=120".to_string()],
        vec![
            "mesh.elements=100".into(),
            "contact.formulation=impact".into(),
        ],
        vec!["mesh.elements=100".into(), "contact.placement=alpha".into()],
        vec!["mesh.kind=modal".into(), "mesh.modes=40".into()],
    ]
    .iter()
    .map(|s| {
        let mut s = s.clone();
        s.push("time.step=2e-4".into());
        s.push("time.end=0.1".into());
        scene(REFERENCE, &s)
    })
    .collect();
    assert_same(&scenes, 8);
}

#[test]
fn compare_and_precision_give_the_same_rows_batched() {
    use taut::study::compare::{CompareSpec, compare_methods};
    use taut::study::precision::precision_variants;
    let set = ["mesh.elements=100".to_string(), "time.end=0.15".to_string()];
    let rows = |batch: usize| {
        let spec = CompareSpec {
            methods: Vec::new(),
            formulations: taut::scene::Formulation::ALL.to_vec(),
            discretizations: Vec::new(),
            reference_method: 0,
            reference_discretization: 0,
            reference: taut::scene::Formulation::Lagrange,
            batch,
        };
        let c = compare_methods(REFERENCE, &set, &spec, &mut |_, _| {}).unwrap();
        c.rows
            .into_iter()
            .map(|mut r| {
                r.wall_seconds = 0.0;
                format!("{r:?}")
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(rows(1), rows(4));
    let grid = |batch: usize| {
        let p = precision_variants(
            REFERENCE,
            &set,
            (&[], &[]),
            &[
                taut::scene::Formulation::Lagrange,
                taut::scene::Formulation::Penalty,
                taut::scene::Formulation::Complementarity,
            ],
            (2, 2, batch),
            &mut |_, _| {},
        )
        .unwrap();
        // wall time and the Pareto flag (error against wall time) aside
        p.rows
            .into_iter()
            .map(|mut r| {
                r.wall_seconds = 0.0;
                r.pareto = false;
                format!("{r:?}")
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(grid(1), grid(4));
}

/// `modal_exact` runs on one basis and Δt step together (`integrate::
/// modal_batch`: the basis, step maps and shape tables built once), each
/// bit-identical to the run alone: speeds (retirement), masses, springs,
/// preloads, formulations (the impact law's located re-contacts too), two
/// carriers, a run that stops, and runs on
/// other bases or steps in the same list (other batches, or alone).
#[test]
fn modal_exact_runs_batch_bit_identically() {
    let exact = |more: &[String]| {
        let mut o = vec![
            "integrator={ method = \"modal_exact\" }".to_string(),
            "mesh.kind=galerkin".into(),
            // more than one block of modes (BLOCK_MODES = 64), the last one partial
            "mesh.modes=150".into(),
            "time.step=2e-4".into(),
        ];
        o.extend_from_slice(more);
        o
    };
    let mut scenes: Vec<Resolved> = (0..6)
        .map(|i| {
            scene(
                REFERENCE,
                &exact(&[format!("carrier.0.speed.cruise={}", 70.0 + 12.0 * i as f64)]),
            )
        })
        .collect();
    for (m, k, f) in [(2.0, 500.0, "penalty"), (0.5, 2000.0, "complementarity")] {
        scenes.push(scene(
            REFERENCE,
            &exact(&[
                format!("carrier.0.mass={m}"),
                format!("carrier.0.stiffness={k}"),
                format!("contact.formulation={f}"),
            ]),
        ));
    }
    // a run that stops at its first closed contact (clarabel, one iteration)
    scenes.push(scene(
        REFERENCE,
        &exact(&[
            "contact.formulation=complementarity".into(),
            "contact.complementarity.solver=clarabel".into(),
            "contact.complementarity.max_iter=1".into(),
        ]),
    ));
    // another basis, another step, an FE modal basis
    scenes.push(scene(REFERENCE, &exact(&["mesh.modes=50".into()])));
    // self-weight: a held load in every mode
    scenes.push(scene(
        REFERENCE,
        &exact(&[
            "gravity.beam_self_weight=true".into(),
            "time.end=0.2".into(),
        ]),
    ));
    scenes.push(scene(
        REFERENCE,
        &exact(&["time.step=1e-4".into(), "time.end=0.1".into()]),
    ));
    scenes.push(scene(
        REFERENCE,
        &exact(&[
            "mesh.kind=modal".into(),
            "mesh.elements=100".into(),
            "time.end=0.1".into(),
        ]),
    ));
    // the impact law: re-contacts located within their steps, one with a
    // held load in every mode (indices 12, 13)
    for more in [vec![], vec!["gravity.beam_self_weight=true".to_string()]] {
        let mut o = vec![
            "contact.formulation=impact".to_string(),
            "carrier.0.speed.cruise=160".to_string(),
        ];
        o.extend(more);
        scenes.push(scene(REFERENCE, &exact(&o)));
    }
    let keys: Vec<Option<taut::integrate::BatchKey>> =
        scenes.iter().map(taut::integrate::batch_key).collect();
    assert!(keys.iter().all(Option::is_some));
    assert_eq!(keys[0], keys[7]);
    assert_ne!(keys[0], keys[9]);
    assert_ne!(keys[0], keys[10]);
    let together = run_batch(&scenes, 8, &mut |_| {});
    assert!(together[8].is_err(), "the clarabel run must stop");
    for batch in [1, 2, 3, 8] {
        assert_same(&scenes, batch);
    }
    let two: Vec<Resolved> = [0.5, 1.5]
        .iter()
        .map(|m| {
            scene(
                TWO,
                &exact(&[format!("carrier.1.mass={m}"), "time.end=0.2".into()]),
            )
        })
        .collect();
    assert_same(&two, 2);
}
