//! `taut precision` (work–precision) on a short reference case: every
//! formulation gets a (mesh, Δt) grid, errors against a finer Lagrange
//! reference, costs, and a non-empty Pareto front; the displacement error
//! falls with the mesh (the quantity whose order is known, docs/convergence.md).

use taut::scene::Formulation;
use taut::study::precision::precision;

const REFERENCE: &str = include_str!("../scenes/reference.toml");

#[test]
fn grid_errors_costs_and_pareto_front() {
    let set: Vec<String> = ["time.end=0.2", "mesh.elements=50", "time.step=4e-4"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let f = [Formulation::Lagrange, Formulation::Penalty];
    let p = precision(REFERENCE, &set, &f, 2, 2, &mut |_, _| {}).unwrap();
    assert_eq!(p.rows.len(), 2 * 2 * 2);
    assert_eq!(p.reference, (200, 1e-4));
    for name in ["lagrange", "penalty"] {
        let rows: Vec<_> = p.rows.iter().filter(|r| r.formulation == name).collect();
        assert!(rows.iter().any(|r| r.pareto), "{name}: a Pareto front");
        for r in &rows {
            assert!(r.force_error.is_finite() && r.displacement_error.is_finite());
            assert_eq!(r.dof_steps, r.dofs as f64 * r.steps as f64);
        }
        let coarse = rows
            .iter()
            .find(|r| r.mesh_level == 0 && r.step_level == 1)
            .unwrap();
        let fine = rows
            .iter()
            .find(|r| r.mesh_level == 1 && r.step_level == 1)
            .unwrap();
        assert!(
            fine.displacement_error < coarse.displacement_error,
            "{name}"
        );
    }
}
