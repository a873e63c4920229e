//! Convergence studies with observed orders (MODEL §5, §4, §8), run through
//! `study::converge` on scenes with analytic references
//! (`scenes/moving_force_string.toml`, `scenes/moving_force_beam.toml`) and
//! on TARGETS T1.
//!
//! The default suite runs cut-down studies (a few levels, a second or so);
//! the full ones are `#[ignore]`d: `cargo test --release --test numerics convergence:: -- --ignored`.
//! Expected orders and why:
//! * time, generalized-α: 2, in an asymptotic range that starts at a Δt
//!   shrinking fast with h (N = 100: Δt ≤ 2.5e-5 s; N = 200: ≤ 1.6e-6 s);
//!   coarser steps give lower, erratic orders whose cause is not identified
//!   (it is not the mesh modes' ωΔt: docs/convergence.md);
//! * space, string (linear elements), displacement under the load: 1 — the
//!   exact solution has a kink at the load, inside an element, that a
//!   piecewise-linear field interpolates with an O(h) error;
//! * space, Hermite beam, same quantity: approaching 2 from below over the
//!   meshes affordable here (measured 1.56, 1.81, 1.93);
//! * FE against analytic: the error at the finest level is bounded by the
//!   coarsest error scaled by (h_f/h_c)^(p − 0.3), p the theory order.

use taut::study::converge::{Convergence, Refine, converge};
use taut::study::reference::analytic_w;

/// Acceptance band around the theoretical order on smooth cases (±0.3).
const ORDER_TOL: f64 = 0.3;

fn study(scene: &str, refine: Refine, levels: usize, sets: &[&str]) -> Convergence {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .join("scenes")
        .join(scene);
    let text = std::fs::read_to_string(path).unwrap();
    let o: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    converge(&text, &o, refine, levels, 2.0, &analytic_w, &mut |_, _| {}).unwrap()
}

/// Observed orders of a quantity at the levels where they are defined.
fn orders(c: &Convergence, quantity: &str) -> Vec<f64> {
    c.rows
        .iter()
        .filter(|r| r.quantity == quantity && r.observed_order.is_finite())
        .map(|r| r.observed_order)
        .collect()
}

fn errors(c: &Convergence, quantity: &str) -> Vec<f64> {
    c.rows
        .iter()
        .filter(|r| r.quantity == quantity)
        .map(|r| r.error)
        .collect()
}

fn assert_orders(c: &Convergence, quantity: &str, theory: f64) {
    let p = orders(c, quantity);
    println!("{quantity}: observed orders {p:.3?} (theory {theory})");
    assert!(!p.is_empty());
    for o in p {
        assert!(
            (o - theory).abs() <= ORDER_TOL,
            "{quantity}: order {o} vs {theory}"
        );
    }
}

#[test]
fn generalized_alpha_is_second_order_in_time() {
    // the beam at N = 100 with Δt from 5e-5 s (inside the measured asymptotic range)
    let c = study(
        "moving_force_beam.toml",
        Refine::Step,
        4,
        &["mesh.elements=100", "time.step=5e-5"],
    );
    assert_orders(&c, "displacement_history_l2", 2.0);
    assert_orders(&c, "displacement_history_max", 2.0);
}

#[test]
fn riding_mass_displacement_is_second_order_in_time() {
    let c = study(
        "t1_cantilever_riding_mass.toml",
        Refine::Step,
        4,
        &["mesh.elements=80", "time.step=2e-4"],
    );
    assert_orders(&c, "displacement_history_l2", 2.0);
}

#[test]
fn string_elements_are_first_order_at_the_load_point() {
    let c = study(
        "moving_force_string.toml",
        Refine::Mesh,
        4,
        &["time.step=5e-5"],
    );
    assert_orders(&c, "displacement_history_l2", 1.0);
    // FE against analytic, at the tolerance the rate gives
    let e = errors(&c, "displacement_history_l2");
    let bound = e[0] * 0.5f64.powi(3).powf(1.0 - ORDER_TOL);
    println!(
        "string: error against analytic {:.3e} → {:.3e} (bound {bound:.3e})",
        e[0], e[3]
    );
    assert!(e[3] <= bound);
    assert!(
        c.rows.iter().all(
            |r| r.quantity != "displacement_history_l2" || r.reference == "moving_force_series"
        )
    );
}

#[test]
fn hermite_beam_against_the_analytic_moving_load() {
    let c = study("moving_force_beam.toml", Refine::Both, 4, &[]);
    let e = errors(&c, "displacement_history_l2");
    let bound = e[0] * 0.5f64.powi(3).powf(2.0 - ORDER_TOL);
    println!("beam: error against analytic {e:?} (finest bound {bound:.3e})");
    assert!(e[3] <= bound);
    // and relative to the response, the finest level is within 1e-4
    let value = c
        .rows
        .iter()
        .rfind(|r| r.quantity == "displacement_history_l2")
        .unwrap()
        .value;
    assert!(e[3] / value < 1e-4, "{}", e[3] / value);
}

#[test]
#[ignore = "long: the full time-order study (6 levels down to Δt = 3.1e-6)"]
fn generalized_alpha_time_order_full() {
    let c = study(
        "moving_force_beam.toml",
        Refine::Step,
        6,
        &["mesh.elements=100", "time.step=1e-4"],
    );
    assert_orders(&c, "displacement_history_l2", 2.0);
    assert_orders(&c, "displacement_history_max", 2.0);
}

#[test]
#[ignore = "long: the string's spatial order over five meshes (N 50 → 800)"]
fn string_space_order_full() {
    let c = study(
        "moving_force_string.toml",
        Refine::Mesh,
        5,
        &["time.step=2.5e-5"],
    );
    assert_orders(&c, "displacement_history_l2", 1.0);
}
