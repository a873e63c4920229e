//! No subnormal number forms in a step (`model::banded`,
//! "Subnormals"). A banded solve's solution decays geometrically away from
//! the loads; unchecked, its tails and then the states pass through the
//! subnormal range, which many CPUs process one to two orders of magnitude
//! slower (a step was up to 10× slower at N ≥ 1400 on an Intel Xeon). The
//! sweeps drop values below `NEGLIGIBLE` to exactly zero; this test counts
//! subnormals in the beam's displacements and velocities after every step,
//! for every method, discretization and the batched path, on meshes where
//! the unflushed kernel forms them: with the flush disabled
//! (`NEGLIGIBLE = 0`) every Hermite and string case below failed, with
//! 29 (string) to 1967 (Moreau–Jean) subnormal values after a step, and so
//! did the batch. The diagonal bases (galerkin, modal) have no decaying
//! tails and formed none even then; they are checked so that they stay so.

use taut::integrate::{Batch, Integrator};
use taut::{Resolved, resolve_scene};

const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// Steps per case: the early steps are where the tails run ahead of the
/// waves over an undisturbed beam (most subnormals formed: about a third of
/// the dofs at step 1 on N = 1600 without the flush).
const STEPS: usize = 150;

fn scene(set: &[&str]) -> Resolved {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    resolve_scene(REFERENCE, &set).unwrap_or_else(|e| panic!("{set:?}: {e}"))
}

fn subnormals(xs: &[f64]) -> usize {
    xs.iter().filter(|x| x.is_subnormal()).count()
}

/// Step a run alone and return the most subnormals seen in d and v after
/// any step.
fn worst_alone(sc: &Resolved) -> usize {
    let mut it = Integrator::new(sc).expect("the scene builds");
    let mut worst = 0;
    for _ in 0..STEPS.min(sc.steps) {
        it.step().expect("the step succeeds");
        let st = it.state();
        worst = worst.max(subnormals(&st.d) + subnormals(&st.v));
    }
    worst
}

#[test]
fn no_subnormals_in_any_method_or_discretization() {
    let fine = ["mesh.elements=1600", "time.step=1e-4"];
    let cases: Vec<(&str, Vec<&str>)> = vec![
        ("generalized_alpha", vec![]),
        (
            "generalized_alpha rho_inf 0.5",
            vec!["integrator.rho_inf=0.5"],
        ),
        ("hht", vec!["integrator={ method = \"hht\" }"]),
        ("bathe", vec!["integrator={ method = \"bathe\" }"]),
        (
            "moreau_jean",
            vec![
                "integrator={ method = \"moreau_jean\" }",
                "contact.formulation=\"complementarity\"",
            ],
        ),
        (
            "graded mesh",
            vec!["mesh.grading=\"supports\"", "mesh.grading_ratio=8"],
        ),
        (
            "string",
            vec![
                "beam.youngs_modulus=0",
                "beam.left=\"pinned\"",
                "mesh.elements=3200",
            ],
        ),
        // two lines interleaved (band 7, docs/lines.md W5)
        (
            "messenger",
            vec![
                "messenger={ tension = 1.6e4, mass_per_length = 1.0, bending_stiffness = 100.0, height = 1.0, supports = [0.0, 50.0] }",
            ],
        ),
        // formed none without the flush either (module docs)
        ("galerkin", vec!["mesh.kind=\"galerkin\"", "mesh.modes=400"]),
    ];
    let mut found = Vec::new();
    for (name, extra) in &cases {
        let mut set: Vec<&str> = fine.to_vec();
        set.extend(extra);
        let worst = worst_alone(&scene(&set));
        if worst > 0 {
            found.push(format!("{name}: {worst} subnormal values after a step"));
        }
    }
    // central difference needs Δt below 2/ω_max: a coarser mesh, a small step
    let cd = scene(&[
        "mesh.elements=1600",
        "time.step=3e-6",
        "integrator={ method = \"central_difference\" }",
    ]);
    let worst = worst_alone(&cd);
    if worst > 0 {
        found.push(format!("central_difference: {worst} subnormal values"));
    }
    // the FE modal basis (a dense eigenproblem: a small model); formed none
    // without the flush either (module docs)
    let modal = scene(&[
        "mesh.elements=200",
        "time.step=1e-4",
        "mesh.kind=\"modal\"",
        "mesh.modes=399",
    ]);
    let worst = worst_alone(&modal);
    if worst > 0 {
        found.push(format!("modal: {worst} subnormal values"));
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn no_subnormals_in_a_batch() {
    let scenes: Vec<Resolved> = [90.0, 100.0, 110.0, 120.0]
        .iter()
        .map(|v| {
            let speed = format!("carrier.speed.cruise={v}");
            scene(&["mesh.elements=1600", "time.step=1e-4", &speed])
        })
        .collect();
    let list: Vec<(usize, &Resolved)> = scenes.iter().enumerate().collect();
    let (batch, errors) = Batch::new(&list);
    assert!(errors.is_empty(), "{}", errors.len());
    let mut b = batch.expect("the runs share a batch");
    assert!(b.supported(), "a kernel for four lanes");
    let mut worst = 0;
    for _ in 0..STEPS {
        b.step();
        let (d, v) = b.beam_vectors();
        worst = worst.max(subnormals(d) + subnormals(v));
    }
    assert_eq!(worst, 0, "subnormal values in the batch's beam vectors");
}
