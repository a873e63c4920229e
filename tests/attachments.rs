//! Point attachments along the beam (MODEL §10; docs/lines.md
//! "Point attachments"): springs and lumped masses at x_a assembled as
//! `k_a r_a r_aᵀ` into K and `m_a r_a r_aᵀ` into M, checked against
//! independent closed forms:
//!
//! * static deflection on discrete springs under a point load against the
//!   superposition of point-load Green's functions
//!   (`analytic::SpringSupportedLine`, docs/lines.md L1–L3), for a string,
//!   a bare beam and a tensioned beam, springs at nodes and between them;
//! * the fundamental frequency of a pinned–pinned string carrying a lumped
//!   mass (and a spring) at x_a against its frequency equation (below),
//!   through taut's own eigen-solver on the assembled model;
//! * a very stiff spring acting as a support;
//! * the scene keys, their refusals, and central difference's ω_max bound.

use taut::analytic::{DiscreteSpring, SpringSupportedLine};
use taut::model::banded::BandedLdlt;
use taut::model::beam::BeamModel;
use taut::model::eigen::lowest_eigenpairs;
use taut::resolve_scene;
use taut::scene::{Attachment, BeamProps, Support};

/// Span L, m.
const L: f64 = 10.0;
/// Tension T, N (a contact wire's order).
const T: f64 = 2.0e4;
/// Bending stiffness EI, N·m² (a contact wire's order: μ = sqrt(T/EI) ≈ 10 /m).
const EI: f64 = 195.0;
/// Mass per length ρA, kg/m.
const RHO_A: f64 = 1.35;
/// Point load P, N (down).
const P: f64 = -100.0;

fn props(ei: f64, tension: f64, attachments: &[Attachment]) -> BeamProps {
    BeamProps {
        length: L,
        rho_a: RHO_A,
        ei,
        ea: None,
        tension,
        left: Support::Pinned,
        right: Support::Pinned,
        distributed_load: 0.0,
        attachments: attachments.to_vec(),
        messenger: None,
    }
}

fn spring(x: f64, k: f64) -> Attachment {
    Attachment {
        x,
        stiffness: k,
        mass: 0.0,
        damping: 0.0,
    }
}

/// The FE static deflection K d = P r(x_P), read at each of `at`.
fn fe_static(p: &BeamProps, elements: usize, xp: f64, at: &[f64]) -> Vec<f64> {
    let beam = BeamModel::new(p, elements);
    let mut d = vec![0.0; beam.n];
    beam.point_vector(xp).scatter(P, &mut d, 1, 0);
    BandedLdlt::factor(&beam.stiffness).unwrap().solve(&mut d);
    at.iter().map(|&x| beam.point_vector(x).dot(&d)).collect()
}

/// The closed form (L3) at each of `at`.
fn exact_static(p: &BeamProps, xp: f64, at: &[f64]) -> Vec<f64> {
    let springs: Vec<DiscreteSpring> = p
        .attachments
        .iter()
        .map(|a| DiscreteSpring {
            x: a.x,
            k: a.stiffness,
        })
        .collect();
    let line = SpringSupportedLine::new(p.ei, p.tension, p.length, &springs).unwrap();
    let f = line.spring_forces(P, xp).unwrap();
    at.iter()
        .map(|&x| line.deflection_with(P, xp, &f, x))
        .collect()
}

/// max |fe − exact| / max |exact| over the points `at`.
fn rel_error(p: &BeamProps, elements: usize, xp: f64, at: &[f64]) -> f64 {
    let fe = fe_static(p, elements, xp, at);
    let ex = exact_static(p, xp, at);
    let scale = ex.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    fe.iter()
        .zip(&ex)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / scale
}

/// Every node of a uniform mesh of `elements` elements.
fn nodes(elements: usize) -> Vec<f64> {
    (0..=elements)
        .map(|i| L * i as f64 / elements as f64)
        .collect()
}

/// Round-off of the string's nodal values: a point load and springs at nodes
/// leave the exact deflection piecewise linear with kinks at nodes, which
/// linear elements hold exactly; measured ≤ 5.4e-15 up to N = 160.
const STRING_NODAL_ROUNDOFF: f64 = 1e-13;
/// Round-off of the bare beam's nodal values (cubic Hermite elements hold
/// the piecewise-cubic exact solution of `EI v'''' = point loads` exactly;
/// cond(K) ∝ N⁴ amplifies ε): measured 6.8e-12 at N = 160.
const BEAM_NODAL_ROUNDOFF: f64 = 1e-10;

/// Two springs and the load at nodes of every mesh used (x = 2.5, 6.0, 4.0).
fn two_springs() -> [Attachment; 2] {
    [spring(2.5, 5.0e3), spring(6.0, 2.0e4)]
}

/// The observed order of a sequence of errors on meshes halving h.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn string_and_bare_beam_on_springs_at_nodes_are_exact_at_the_nodes() {
    for n in [20, 40, 80, 160] {
        let e = rel_error(&props(0.0, T, &two_springs()), n, 4.0, &nodes(n));
        assert!(e <= STRING_NODAL_ROUNDOFF, "string N = {n}: {e:e}");
        let e = rel_error(&props(EI, 0.0, &two_springs()), n, 4.0, &nodes(n));
        assert!(e <= BEAM_NODAL_ROUNDOFF, "bare beam N = {n}: {e:e}");
    }
}

/// Fourth order at the nodes of the tensioned beam (Hermite cubics are not
/// its homogeneous solutions, so not nodally exact): measured orders 2.83,
/// 3.49, 3.84 from N = 20 to 160 (μh = 5 … 0.63, pre-asymptotic), the
/// last one held.
const TENSIONED_NODAL_ORDER: f64 = 3.7;
/// Its relative nodal error at N = 160: measured 4.6e-6.
const TENSIONED_NODAL_ERROR: f64 = 1e-5;

#[test]
fn tensioned_beam_on_springs_converges_at_fourth_order_at_the_nodes() {
    let p = props(EI, T, &two_springs());
    let errors: Vec<f64> = [20, 40, 80, 160]
        .iter()
        .map(|&n| rel_error(&p, n, 4.0, &nodes(n)))
        .collect();
    let o = orders(&errors);
    assert!(
        o[2] >= TENSIONED_NODAL_ORDER,
        "orders {o:?}, errors {errors:?}"
    );
    assert!(errors[3] <= TENSIONED_NODAL_ERROR, "errors {errors:?}");
}

/// A spring between nodes (x = 5 m at mid-element of N odd): its r_a is the
/// element's interpolation there. The deflection at the spring, against
/// L3, converges at the measured orders (N = 21, 41, 81, 161):
/// string ≈ 1 (first order, within the band below: the exact kink at x_a falls
/// inside a linear element); bare beam 2.90, 2.95, 2.97 (third order);
/// tensioned beam 1.91, 2.28, 2.60 (pre-asymptotic, μh = 4.8 … 0.62,
/// rising toward the bare beam's 3). Each band holds the last order.
const BETWEEN_NODES_ORDER: [(&str, f64, f64, f64, f64); 3] = [
    ("string", 0.0, T, 0.95, 1.05),
    ("bare beam", EI, 0.0, 2.9, 3.1),
    ("tensioned beam", EI, T, 2.5, 3.1),
];

#[test]
fn a_spring_between_nodes_converges_at_the_element_s_order() {
    for (name, ei, t, lo, hi) in BETWEEN_NODES_ORDER {
        let p = props(ei, t, &[spring(5.0, 2.0e4)]);
        let errors: Vec<f64> = [21, 41, 81, 161]
            .iter()
            .map(|&n| rel_error(&p, n, 3.0, &[5.0]))
            .collect();
        let o = orders(&errors);
        assert!(
            (lo..=hi).contains(&o[2]),
            "{name}: orders {o:?} (expected the last in [{lo}, {hi}]), errors {errors:?}"
        );
    }
}

// --- (b) a lumped mass on a string: the frequency equation ---------------------

/// The string's frequency equation with a lumped mass m_a and a spring k_a
/// at x = a (b = L − a), k = ω/c:
///
/// ```text
/// (A1) m_a ω² − k_a = T k (cot(k a) + cot(k b))
/// ```
///
/// Derivation: pinned ends give v = A sin(kx) for x < a and v = B sin(k(L −
/// x)) for x > a, equal at a (V = A sin(ka) = B sin(kb)); the mass moves
/// with the jump of the string's vertical force, −m_a ω² V = T (v'(a⁺) −
/// v'(a⁻)) − k_a V, and v'(a⁻) = V k cot(ka), v'(a⁺) = −V k cot(kb). (The
/// classical result for a string carrying a concentrated mass: Graff, *Wave
/// Motion in Elastic Solids*, 1975, §1.3; Meirovitch, *Principles and
/// Techniques of Vibrations*, 1997, §8.) The right side falls from +∞… T L /
/// (a b) at k → 0 to −∞ at k → π / max(a, b), monotonically, so the
/// fundamental is the one root there: bisection.
fn string_fundamental(a: f64, m_a: f64, k_a: f64) -> f64 {
    let c = (T / RHO_A).sqrt();
    let b = L - a;
    let g = |k: f64| {
        let w = k * c;
        T * k * (1.0 / (k * a).tan() + 1.0 / (k * b).tan()) + k_a - m_a * w * w
    };
    let (mut lo, mut hi) = (1e-9, std::f64::consts::PI / a.max(b) * (1.0 - 1e-15));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi) * c
}

/// The assembled model's lowest ω, rad/s, by taut's own eigen-solver.
fn fe_fundamental(a: f64, m_a: f64, k_a: f64, elements: usize) -> f64 {
    let p = props(
        0.0,
        T,
        &[Attachment {
            x: a,
            stiffness: k_a,
            mass: m_a,
            damping: 0.0,
        }],
    );
    let beam = BeamModel::new(&p, elements);
    let pairs = lowest_eigenpairs(&beam.mass, &beam.stiffness, 1).unwrap();
    pairs.omega_sq[0].sqrt()
}

/// The lumped mass at a node (a = 3 m, N = 100, 200, 400): linear string
/// elements converge at second order in ω (measured orders 2.00, 2.00 and
/// relative errors 1.47e-5, 3.69e-6, 9.2e-7); held within 0.05.
const MASS_AT_NODE_ORDER: (f64, f64) = (1.95, 2.05);
/// Its relative error at N = 400: measured 9.2e-7.
const MASS_AT_NODE_ERROR: f64 = 2e-6;
/// A mass between nodes (a = 3.33 m, never a node): first order in h with a
/// constant that depends on where in its element x_a falls; measured
/// relative error ≤ 0.12·h/L for N = 50 … 400 (with and without a spring).
const MASS_BETWEEN_NODES_CONSTANT: f64 = 0.15;

#[test]
fn a_lumped_mass_on_a_string_matches_its_frequency_equation() {
    let (a, m) = (3.0, 5.0);
    let exact = string_fundamental(a, m, 0.0);
    // the mass lowers the bare string's fundamental πc/L
    let bare = std::f64::consts::PI * (T / RHO_A).sqrt() / L;
    assert!(exact < 0.8 * bare, "{exact} vs bare {bare}");
    let errors: Vec<f64> = [100, 200, 400]
        .iter()
        .map(|&n| (fe_fundamental(a, m, 0.0, n) - exact) / exact)
        .collect();
    // consistent masses and an exact point mass: Rayleigh–Ritz, from above
    assert!(errors.iter().all(|e| *e > 0.0), "{errors:?}");
    let o = orders(&errors);
    for oi in &o {
        assert!(
            (MASS_AT_NODE_ORDER.0..=MASS_AT_NODE_ORDER.1).contains(oi),
            "orders {o:?}, errors {errors:?}"
        );
    }
    assert!(errors[2] <= MASS_AT_NODE_ERROR, "{errors:?}");
    for (m, k) in [(5.0, 0.0), (5.0, 1.0e4)] {
        let exact = string_fundamental(3.33, m, k);
        for n in [50, 100, 200, 400] {
            let e = (fe_fundamental(3.33, m, k, n) - exact) / exact;
            let h = L / n as f64;
            assert!(
                e > 0.0 && e <= MASS_BETWEEN_NODES_CONSTANT * h / L,
                "m = {m}, k = {k}, N = {n}: relative error {e:e}"
            );
        }
    }
}

// --- (c) a very stiff spring is a support --------------------------------------

/// A spring of 1e12 N/m is a support to within its compliance: the
/// deflection there over the largest is T/(k L)-small (measured 1.0e-8
/// string, 1.5e-10 bare beam, 1.1e-8 tensioned beam).
const STIFF_SPRING_RESIDUAL: f64 = 1e-7;

#[test]
fn a_very_stiff_spring_acts_as_a_support() {
    for (name, ei, t) in [
        ("string", 0.0, T),
        ("bare beam", EI, 0.0),
        ("tensioned beam", EI, T),
    ] {
        let n = 40;
        let stiff = props(ei, t, &[spring(5.0, 1e12), spring(7.5, 3e4)]);
        let fe = fe_static(&stiff, n, 3.0, &nodes(n));
        let scale = fe.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let at = fe_static(&stiff, n, 3.0, &[5.0])[0];
        assert!(
            at.abs() <= STIFF_SPRING_RESIDUAL * scale,
            "{name}: w(x_a) = {at:e}, max {scale:e}"
        );
        if ei == 0.0 || t == 0.0 {
            // nodally exact elements: the whole line is L3's rigid support's
            let rigid = props(ei, t, &[spring(5.0, f64::INFINITY), spring(7.5, 3e4)]);
            let ex = exact_static(&rigid, 3.0, &nodes(n));
            let e = fe
                .iter()
                .zip(&ex)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(
                e <= STIFF_SPRING_RESIDUAL * scale,
                "{name}: {e:e} from the rigid support"
            );
            // the residual is the spring's compliance: 100× softer, 100× more
            let softer = props(ei, t, &[spring(5.0, 1e10), spring(7.5, 3e4)]);
            let ratio = fe_static(&softer, n, 3.0, &[5.0])[0] / at;
            assert!(
                (ratio - 100.0).abs() <= 0.01 * 100.0,
                "{name}: ratio {ratio}"
            );
        }
    }
}

// --- the scene: keys, refusals, the explicit step's bound ----------------------

const REFERENCE: &str = include_str!("../scenes/reference.toml");

fn with(extra: &str, overrides: &[&str]) -> taut::Result<taut::Resolved> {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    resolve_scene(&format!("{REFERENCE}\n{extra}"), &o)
}

fn refused(extra: &str, overrides: &[&str], parts: &[&str]) {
    let e = with(extra, overrides).expect_err("should be refused");
    let msg = e.to_string();
    for p in parts {
        assert!(msg.contains(p), "{msg:?} should mention {p:?}");
    }
}

const STEADY_ARM: &str =
    "[[attachment]]\nname = \"arm\"\nx = 12.3\nstiffness = 2.0e5\nmass = 1.2\n";

#[test]
fn the_keys_reach_the_beam_and_nothing_changes_without_them() {
    let bare = with("", &[]).unwrap();
    assert!(bare.beam.attachments.is_empty());
    let sc = with(STEADY_ARM, &[]).unwrap();
    assert_eq!(
        sc.beam.attachments,
        vec![Attachment {
            x: 12.3,
            stiffness: 2.0e5,
            mass: 1.2,
            damping: 0.0,
        }]
    );
    // defaults: a spring alone, a mass alone
    let sc = with(
        "[[attachment]]\nx = 1.0\nmass = 2.0\n[[attachment]]\nx = 2.0\nstiffness = 3.0\n",
        &[],
    )
    .unwrap();
    assert_eq!(sc.beam.attachments[0].stiffness, 0.0);
    assert_eq!(sc.beam.attachments[1].mass, 0.0);
    // the assembled matrices differ exactly by the attachment's terms
    let a = BeamModel::build(&bare.beam, &bare.mesh_plan()).unwrap();
    let sc = with(STEADY_ARM, &[]).unwrap();
    let b = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
    let r = a.point_vector(12.3);
    let mut dk = 0.0;
    let mut dm = 0.0;
    for i in 0..a.n {
        for j in i.saturating_sub(3)..(i + 4).min(a.n) {
            let (ri, rj) = (weight(&r, i), weight(&r, j));
            dk += (b.stiffness.get(i, j) - a.stiffness.get(i, j) - 2.0e5 * ri * rj).abs();
            dm += (b.mass.get(i, j) - a.mass.get(i, j) - 1.2 * ri * rj).abs();
        }
    }
    assert!(
        dk < 1e-9 * 2.0e5 && dm < 1e-9,
        "ΔK off by {dk:e}, ΔM by {dm:e}"
    );
    assert_eq!(a.stiffness.bandwidth(), b.stiffness.bandwidth());
}

/// The weight of dof `i` in a mesh point vector.
fn weight(r: &taut::model::beam::PointVector, i: usize) -> f64 {
    (0..4).filter(|&k| r.idx[k] == i).map(|k| r.val[k]).sum()
}

#[test]
fn bad_attachments_are_refused_naming_the_field() {
    refused(
        "[[attachment]]\nx = 60.0\nstiffness = 1.0\n",
        &[],
        &["attachment.0.x", "60", "[0, 50] m"],
    );
    refused(
        "[[attachment]]\nx = 1.0\nstiffness = -1.0\n",
        &[],
        &["attachment.0.stiffness", "-1", "≥ 0 (N/m)"],
    );
    refused(
        "[[attachment]]\nx = 1.0\nmass = nan\n",
        &[],
        &["attachment.0.mass", "NaN", "finite"],
    );
    refused(
        "[[attachment]]\nx = 1.0\n",
        &[],
        &[
            "attachment.0.stiffness",
            "stiffness > 0 (N/m), mass > 0 (kg) or damping > 0 (N·s/m)",
        ],
    );
    // an unknown key is refused naming the known ones
    refused(
        "[[attachment]]\nx = 1.0\nstiffness = 1.0\nspring = 3.0\n",
        &[],
        &["unknown field `spring`", "`stiffness`", "`damping`"],
    );
    refused(
        &format!("{STEADY_ARM}[reference]\nkind = \"moving_force_series\"\n"),
        &[],
        &["reference.kind", "moving_force_series", "bare beam"],
    );
    // a manufactured solution carries attachments (tests/mms_attachments.rs)
    let mms = include_str!("../scenes/verify/mms_beam_time.toml");
    resolve_scene(
        &format!("{mms}\n[[attachment]]\nx = 1.0\nmass = 0.1\n"),
        &[],
    )
    .unwrap();
    refused(
        STEADY_ARM,
        &["mesh.kind=galerkin", "mesh.modes=20"],
        &["mesh.kind", "galerkin", "\"hermite\" or \"modal\""],
    );
}

#[test]
fn modal_and_modal_exact_accept_attachments_and_the_modal_basis_carries_them() {
    let sc = with(
        STEADY_ARM,
        &["mesh.kind=modal", "mesh.modes=10", "mesh.elements=40"],
    )
    .unwrap();
    let modal = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
    let fe = BeamModel::new(&sc.beam, 40);
    let pairs = lowest_eigenpairs(&fe.mass, &fe.stiffness, 10).unwrap();
    for j in 0..10 {
        // the same dense solve on the same matrices: round-off
        assert!((modal.stiffness.get(j, j) - pairs.omega_sq[j]).abs() <= 1e-12 * pairs.omega_sq[j]);
    }
    with(
        STEADY_ARM,
        &[
            "mesh.kind=modal",
            "mesh.modes=10",
            "mesh.elements=40",
            "integrator={ method = \"modal_exact\" }",
        ],
    )
    .unwrap();
}

/// Central difference's stable step is 2/ω_max of the assembled model; a
/// stiff attachment raises ω_max above the bare beam's element bound, and
/// the bound the run is held to must rise with it (`element::omega_max_attached`).
#[test]
fn central_difference_bound_counts_a_stiff_attachment() {
    let sc = with(
        "[[attachment]]\nx = 12.3\nstiffness = 1.0e9\n",
        &["mesh.elements=40"],
    )
    .unwrap();
    let beam = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
    let all = lowest_eigenpairs(&beam.mass, &beam.stiffness, beam.n).unwrap();
    let w_true = all.omega_sq.last().unwrap().sqrt();
    let bare = taut::model::element::omega_max(sc.beam.rho_a, sc.beam.ei, sc.beam.tension, beam.h);
    assert!(
        w_true > 1.5 * bare,
        "the attachment should dominate: {w_true} vs {bare}"
    );
    let limit = taut::integrate::central_difference_limit(&sc).unwrap();
    assert!(
        limit.omega_element_bound >= w_true * (1.0 - 1e-12),
        "element bound {} below the true ω_max {w_true}",
        limit.omega_element_bound
    );
    assert!(
        limit.dt_max <= 2.0 / w_true * (1.0 + 1e-9),
        "dt_max {} above 2/ω_max {}",
        limit.dt_max,
        2.0 / w_true
    );
}

/// Runs with attachments step alone: a batch shares its first run's K and
/// M, and the key has no place for the attachments (`integrate::batch_key`).
#[test]
fn runs_with_attachments_do_not_batch() {
    let bare = with("", &[]).unwrap();
    assert!(taut::integrate::batch_key(&bare).is_some());
    let sc = with(STEADY_ARM, &[]).unwrap();
    assert!(taut::integrate::batch_key(&sc).is_none());
    let sc = with(
        STEADY_ARM,
        &[
            "mesh.kind=modal",
            "mesh.modes=10",
            "mesh.elements=40",
            "integrator={ method = \"modal_exact\" }",
        ],
    )
    .unwrap();
    assert!(taut::integrate::batch_key(&sc).is_none());
}
