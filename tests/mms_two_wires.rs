//! Manufactured solutions for the coupled two-wire system
//! (`docs/verification.md`, "Two coupled wires"): a contact wire and a
//! messenger on an interior support, coupled by linear droppers, each line
//! with its own manufactured motion, and a mass–spring moving under the
//! contact wire (`scenes/verify/mms_two_wires.toml`).
//!
//! * Bad input: `[manufactured.messenger]` without a messenger, unknown
//!   keys, a tension-only dropper the motion would slacken — each refused
//!   by name (attachments, dashpots and self-weight are carried:
//!   `tests/mms_attachments.rs`).
//! * The run converges to the exact solution on **both** wires: observed
//!   orders in h (Hermite, 4 in displacement) and in Δt (generalized-α, 2)
//!   from two levels each in the default suite; the harness's full ladders
//!   (`taut verify`'s `mms_two_wires` case) behind `--ignored`.
//!
//! The error is the discrete max norm: the largest |v_h − v*| over the
//! recorded times t > 0 at the probes of each wire (x = 0.5 and 1.5 m on
//! the contact wire and on the messenger; under the carrier too on the
//! contact wire).

use taut::resolve_scene;
use taut::study::uncertainty::observed_order;
use taut::study::verify::{Status, any_failed, selection, verify};

use crate::common;

const SCENE: &str = include_str!("../scenes/verify/mms_two_wires.toml");

/// Allowed |observed − 4| of the h order from N = 8 → 32 (ratio 4): the
/// moving contact's node kicks scatter successive orders by ±0.6 (the
/// harness's `MOVING_CONTACT_TOL`, measured 3.4–4.7 per halving under the
/// carrier here, 4.0 over 8 → 64), so the two levels are two halvings apart.
const H_ORDER_TOL: f64 = 0.5;

/// Allowed |observed − 2| of the Δt order from 1e-3 → 5e-4 s at N = 32:
/// the harness's `ORDER_TOL` for a smooth case.
const DT_ORDER_TOL: f64 = 0.3;

#[test]
fn two_coupled_wires_converge_at_order_4_in_h_on_both_wires() {
    // Δt = 1e-5 s: the time error (≈ 3e-10 m) is below 2 % of the finer level's
    let (c1, m1) = common::manufactured_wire_errors(SCENE, &common::mesh_and_step(8, 1e-5));
    let (c2, m2) = common::manufactured_wire_errors(SCENE, &common::mesh_and_step(32, 1e-5));
    let (oc, om) = (observed_order(c1, c2, 4.0), observed_order(m1, m2, 4.0));
    println!(
        "two wires, h: contact {c1:.3e} → {c2:.3e} m (order {oc:.2}), messenger {m1:.3e} → {m2:.3e} m (order {om:.2})"
    );
    assert!((oc - 4.0).abs() < H_ORDER_TOL, "contact wire h order {oc}");
    assert!((om - 4.0).abs() < H_ORDER_TOL, "messenger h order {om}");
}

/// Second order in Δt on both wires under the scene's generalized-α and
/// under the other implicit methods that carry a messenger (Bathe, and
/// Moreau–Jean with θ = ½; central difference below, its stable steps are
/// too short for the time error to show over the mesh's).
#[test]
fn two_coupled_wires_converge_at_order_2_in_dt_on_both_wires() {
    for (method, coarse) in [
        (None, 1e-3),
        (Some("integrator={ method = \"bathe\" }"), 1e-3),
        (Some("integrator={ method = \"moreau_jean\" }"), 1e-3),
    ] {
        let with = |dt: f64| {
            let mut o = common::mesh_and_step(32, dt);
            o.extend(method.map(str::to_string));
            common::manufactured_wire_errors(SCENE, &o)
        };
        let (c1, m1) = with(coarse);
        let (c2, m2) = with(coarse / 2.0);
        let (oc, om) = (observed_order(c1, c2, 2.0), observed_order(m1, m2, 2.0));
        let name = method.unwrap_or("the scene's method");
        println!(
            "two wires, Δt {coarse:e} → {:e} s, {name}: contact {c1:.3e} → {c2:.3e} m (order {oc:.2}), messenger {m1:.3e} → {m2:.3e} m (order {om:.2})",
            coarse / 2.0
        );
        assert!(
            (oc - 2.0).abs() < DT_ORDER_TOL,
            "{name}: contact wire Δt order {oc}"
        );
        assert!(
            (om - 2.0).abs() < DT_ORDER_TOL,
            "{name}: messenger Δt order {om}"
        );
    }
}

/// Allowed |observed − 2| of central difference's Δt order from the
/// differences of three runs at one mesh (a smooth case: `DT_ORDER_TOL`).
const CD_ORDER_TOL: f64 = DT_ORDER_TOL;

/// Central difference's error against the manufactured solution may exceed
/// the mesh's own (the generalized-α run at Δt = 1e-5 s, time error
/// ≈ 3e-10 m) by this many times its time error's Richardson estimate
/// (the difference of the Δt and Δt/2 runs over 3): the two max norms are
/// taken at different points and times, so they do not simply add
/// (measured 1.0 and 1.4 times it on the contact wire and the messenger).
const CD_TIME_ERROR_FACTOR: f64 = 2.0;

/// Central difference on the two-wire model: within its stable step (2/ω_max
/// of the assembled two-line model, 9.5e-5 s at N = 32: ties and the
/// messenger's elements in the bound, `BeamModel::omega_bound`) it reaches
/// the manufactured solution to the mesh's error, and its time error, the
/// difference of runs at Δt and Δt/2 on the same mesh (the semi-discrete
/// solution cancels), falls at second order on both wires.
#[test]
fn central_difference_steps_two_coupled_wires_at_order_2_in_dt() {
    let cd = "integrator={ method = \"central_difference\" }".to_string();
    let run = |dt: f64| {
        let mut o = common::mesh_and_step(32, dt);
        o.push(cd.clone());
        let sc = resolve_scene(SCENE, &o).unwrap();
        let out = taut::run(&sc, &mut |_, _| {}).unwrap();
        let wires: Vec<bool> = sc
            .scene
            .probes
            .iter()
            .map(|p| p.wire == Some(taut::scene::Wire::Messenger))
            .collect();
        (out.history, wires)
    };
    // the largest difference on each wire at the coarser run's times
    let apart = |(a, wires): &(taut::record::History, Vec<bool>), b: &taut::record::History| {
        let (mut c, mut m) = (0.0f64, 0.0f64);
        for (p, (_, col)) in a.probes.iter().enumerate() {
            for (i, &t) in a.t.iter().enumerate() {
                assert!((b.t[2 * i] - t).abs() <= 1e-12, "the finer run's samples");
                let e = (col[i] - b.probes[p].1[2 * i]).abs();
                if wires[p] {
                    m = m.max(e);
                } else {
                    c = c.max(e);
                }
            }
        }
        (c, m)
    };
    let (r1, r2, r3) = (run(8e-5), run(4e-5), run(2e-5));
    let (c1, m1) = apart(&r1, &r2.0);
    let (c2, m2) = apart(&r2, &r3.0);
    let (oc, om) = (observed_order(c1, c2, 2.0), observed_order(m1, m2, 2.0));
    println!(
        "central difference, two wires, N = 32, Δt 8e-5 → 4e-5 → 2e-5 s: contact {c1:.3e} → {c2:.3e} m (order {oc:.2}), messenger {m1:.3e} → {m2:.3e} m (order {om:.2})"
    );
    assert!(
        (oc - 2.0).abs() < CD_ORDER_TOL,
        "contact wire Δt order {oc}"
    );
    assert!((om - 2.0).abs() < CD_ORDER_TOL, "messenger Δt order {om}");
    let (ec, em) = common::manufactured_wire_errors(
        SCENE,
        &[common::mesh_and_step(32, 2e-5), vec![cd.clone()]].concat(),
    );
    let (hc, hm) = common::manufactured_wire_errors(SCENE, &common::mesh_and_step(32, 1e-5));
    let (tc, tm) = (c2 / 3.0, m2 / 3.0);
    println!(
        "against the manufactured solution at Δt = 2e-5 s: contact {ec:.3e} m (mesh {hc:.3e}, time ≈ {tc:.1e}), messenger {em:.3e} m (mesh {hm:.3e}, time ≈ {tm:.1e})"
    );
    assert!(ec <= hc + CD_TIME_ERROR_FACTOR * tc, "contact wire {ec}");
    assert!(em <= hm + CD_TIME_ERROR_FACTOR * tm, "messenger {em}");
    // above the bound: refused, naming it
    let o = [common::mesh_and_step(32, 1e-4), vec![cd]].concat();
    let e = match resolve_scene(SCENE, &o) {
        Err(e) => e.to_string(),
        Ok(sc) => match taut::run(&sc, &mut |_, _| {}) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("Δt = 1e-4 s above the stable step ran"),
        },
    };
    assert!(e.contains("time.step") && e.contains("2/ω_max"), "{e}");
}

/// Largest |gap| of central difference with the impact law while the
/// contact stays closed, m: the gap is held at its value at t = 0 (zero)
/// to round-off, ε times the 1e-5 m scale of the motion over the run's
/// 10⁴–10⁵ steps (measured ≤ 1.5e-16 m at Δt = 1e-5 … 2.5e-6 s).
const CD_IMPACT_GAP: f64 = 1e-14;

/// Largest |λ_impact − λ_lagrange| relative to λ's 27 N scale: with the
/// gap's increment as its rate, impact imposes g_{n+1} = g_n where
/// Lagrange imposes g_{n+1} = 0, the same condition while g_n is at
/// round-off (measured 1e-12 relative).
const CD_IMPACT_LAGRANGE: f64 = 1e-9;

/// Central difference with the impact law keeps the contact on the two
/// wires. Before, its velocity-level law read the gap rate at
/// t_{n+1} with the half-step velocity v_{n+1/2}, an O(Δt) mismatch: the
/// position gap drifted at that rate (1.5e-8, 7.5e-9, 3.8e-9 m at
/// t = 0.1 s for Δt = 1e-5, 5e-6, 2.5e-6 s), and where it drifted open the
/// contact left Moreau's index set and came back with an impact: 1, 3 and
/// 6 loss intervals, re-contact peaks 51.7–53.0 N (λ* ≤ 27 N), although
/// the exact solution never loses contact. Now the rate is the gap's
/// increment over the step (`System::set_increment_rates`): no loss, the
/// gap at round-off, and the force the forward-increment Lagrange one's.
#[test]
fn central_difference_with_the_impact_law_keeps_the_contact_on_two_wires() {
    let run = |dt: f64, law: &str| {
        let mut o = common::mesh_and_step(32, dt);
        o.push("integrator={ method = \"central_difference\" }".into());
        o.push(format!("contact.formulation={law}"));
        let sc = resolve_scene(SCENE, &o).unwrap();
        taut::run(&sc, &mut |_, _| {}).unwrap()
    };
    for dt in [1e-5, 5e-6] {
        let (impact, lagrange) = (run(dt, "impact"), run(dt, "lagrange"));
        let c = &impact.history.carriers[0];
        let gap = c.gap.iter().fold(0.0f64, |m, g| m.max(g.abs()));
        let apart = c
            .force
            .iter()
            .zip(&lagrange.history.carriers[0].force)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        let scale = c.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
        let st = &impact.stats[0];
        println!(
            "central difference + impact, two wires, N = 32, Δt = {dt:e} s: {} loss intervals, max |gap| {gap:.2e} m, max |λ − λ_lagrange| {apart:.2e} N of {scale:.1} N",
            st.loss_interval_count
        );
        assert_eq!(st.loss_interval_count, 0, "the contact opened");
        assert!(gap <= CD_IMPACT_GAP, "max |gap| {gap:e} m");
        assert!(apart <= CD_IMPACT_LAGRANGE * scale, "{apart:e} N");
    }
}

#[test]
fn bad_two_wire_manufactured_scenes_are_refused_by_name() {
    // the messenger's motion needs a messenger
    let no_messenger = SCENE.split("\n[messenger]").next().unwrap().to_string()
        + "[mesh]\nelements = 8\n"
        + &SCENE[SCENE.find("\n[[carrier]]").unwrap()..SCENE.find("\n[[probe]]").unwrap()]
        + &SCENE[SCENE.find("\n[[manufactured.term]]").unwrap()..];
    let e = common::rejected(&no_messenger, &[]);
    assert!(
        e.contains("`manufactured.messenger`") && e.contains("[messenger]"),
        "{e}"
    );
    // unknown keys
    let e = common::rejected(
        &SCENE.replace("amplitude = 8.0e-3", "amplitude = 8.0e-3\nwave = 1"),
        &[],
    );
    assert!(e.contains("wave"), "{e}");
    let e = common::rejected(
        &SCENE.replace(
            "\n[[manufactured.messenger.term]]",
            "\n[manufactured.messenger]\nshape = 1\n[[manufactured.messenger.term]]",
        ),
        &[],
    );
    assert!(e.contains("shape"), "{e}");
    // a tension-only dropper that the motion would slacken: d3 with a 5 N
    // preload (e₀ = 1 cm) against the 12 N its linear twin loses
    let e = common::rejected(SCENE, &["dropper.2.linear=false", "dropper.2.length=0.49"]);
    assert!(
        e.contains("`dropper.2.linear`") && e.contains("d3") && e.contains("t = "),
        "{e}"
    );
    // the source gives the lines' self-weight back (tests/mms_attachments.rs)
    resolve_scene(SCENE, &["gravity.beam_self_weight=true".into()]).unwrap();
    // the lines start straight: no static start under the preloads
    let e = common::rejected(SCENE, &["time.initial=static"]);
    assert!(e.contains("`time.initial`"), "{e}");
    // attachments are in the source now (tests/mms_attachments.rs)
    resolve_scene(
        &format!("{SCENE}\n[[attachment]]\nx = 0.5\nstiffness = 10.0\n"),
        &[],
    )
    .unwrap();
}

#[test]
fn a_taut_tension_only_dropper_is_accepted_and_converges_like_the_linear_one() {
    // with a 25 N preload every dropper stays taut (12.7 N at the least): tension-only droppers
    // are the linear ones (docs/lines.md D6), the same errors to the
    // contact problem's tolerance
    let mut o = common::mesh_and_step(16, 2.5e-5);
    let (c_lin, m_lin) = common::manufactured_wire_errors(SCENE, &o);
    for d in 0..4 {
        o.push(format!("dropper.{d}.linear=false"));
    }
    let (c_to, m_to) = common::manufactured_wire_errors(SCENE, &o);
    println!(
        "tension-only vs linear: contact {c_to:.3e} / {c_lin:.3e}, messenger {m_to:.3e} / {m_lin:.3e}"
    );
    assert!((c_to - c_lin).abs() <= SAME_RUN * c_lin, "{c_to} {c_lin}");
    assert!((m_to - m_lin).abs() <= SAME_RUN * m_lin, "{m_to} {m_lin}");
}

/// Relative difference of two runs that differ by the taut droppers'
/// path (a row of the contact problem vs a spring in K, D6): round-off and
/// the contact solver's tolerance, far below the discretization error.
const SAME_RUN: f64 = 1e-3;

/// The harness's ladders on the case, every combination `taut verify`
/// runs for it: the methods that carry a messenger × the four
/// formulations, on `hermite` (Δt: 4 levels at N = 64; h: N = 8 → 64 at
/// Δt = 5e-6 s) and on `modal` (J = 8 → 64 on N = 32; Δt at N = 64 with
/// all 255 modes).
#[test]
#[ignore = "the mms_two_wires ladders: about a minute in release (cargo test --release -- --ignored)"]
fn the_two_wire_verification_case_passes() {
    let case = common::verify_case("mms_two_wires");
    let sel = selection(None, Some("hermite,modal"), None, false).unwrap();
    let rows = verify(&case, &sel, &|_, _| {}).unwrap();
    for r in &rows {
        println!(
            "{} {} {} {} {}: {:?} observed {:.2} ({})",
            r.method, r.formulation, r.variable, r.quantity, r.case, r.status, r.observed, r.note
        );
    }
    assert!(!any_failed(&rows));
    assert!(rows.iter().filter(|r| r.status == Status::Pass).count() >= 16);
}

/// A complete modal basis of the two-line model (J = its FE unknowns) is
/// the Hermite model in other coordinates, and generalized-α is invariant
/// under that change: the same run to the round-off of the eigenvectors
/// (faer's dense solve, ≈ 1e-13) amplified over the run's 2500 steps and
/// contact solves; measured 2.1e-10 of the largest force and 6.2e-13 of
/// the largest probe displacement.
const COMPLETE_BASIS: f64 = 1e-8;

/// The messenger on a `modal` basis (the modes of the two-line model,
/// ties in K before the eigen-solve; a point on either line is Φᵀ of its
/// FE point vector): complete, it is the Hermite run; truncated, its
/// manufactured error falls as J grows.
#[test]
fn a_modal_basis_of_the_two_line_model_carries_the_messenger() {
    let n = resolve_scene(SCENE, &common::mesh_and_step(16, 1e-4))
        .unwrap()
        .beam_unknowns();
    let run = |extra: &[String]| {
        let mut o = common::mesh_and_step(16, 1e-4);
        o.extend(extra.iter().cloned());
        let sc = resolve_scene(SCENE, &o).unwrap();
        taut::run(&sc, &mut |_, _| {}).unwrap()
    };
    let modal = |j: usize| vec!["mesh.kind=\"modal\"".to_string(), format!("mesh.modes={j}")];
    let (h, m) = (run(&[]), run(&modal(n)));
    let rel = |a: &[f64], b: &[f64]| {
        let scale = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        a.iter()
            .zip(b)
            .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()))
            / scale
    };
    let force = rel(&m.history.carriers[0].force, &h.history.carriers[0].force);
    let probes = h
        .history
        .probes
        .iter()
        .zip(&m.history.probes)
        .map(|((_, a), (_, b))| rel(b, a))
        .fold(0.0f64, f64::max);
    println!(
        "complete modal basis (J = {n}) against Hermite: force {force:.2e}, probes {probes:.2e}"
    );
    assert!(
        force < COMPLETE_BASIS && probes < COMPLETE_BASIS,
        "{force} {probes}"
    );
    // truncated: the manufactured error on both wires falls with J
    let mut last = (f64::INFINITY, f64::INFINITY);
    for j in [n / 4, n / 2, n] {
        let (c, me) = common::manufactured_wire_errors(
            SCENE,
            &[common::mesh_and_step(16, 1e-4), modal(j)].concat(),
        );
        println!("J = {j}: contact wire {c:.3e} m, messenger {me:.3e} m");
        assert!(
            c < last.0 && me < last.1,
            "J = {j}: {c} {me} after {last:?}"
        );
        last = (c, me);
    }
}

/// The harness's J ladder on a modal basis of the two-line model, one
/// combination (generalized-α, Lagrange): the displacement's observed
/// order in J matches the exact solution's own modal tail, which now
/// projects both lines' nodal interpolants onto the two-line modes and
/// reads the messenger's probes on the messenger (measured 3.62 against
/// 3.6; the full matrix: `taut verify --discretizations modal`).
#[test]
fn the_two_line_modal_j_ladder_follows_its_modal_tail() {
    let case = common::verify_case("mms_two_wires");
    // the scene's generalized-α alone (a selection by name brings its ρ∞ sets)
    let sel = taut::study::verify::Selection {
        methods: vec![
            &taut::scene::Method::GeneralizedAlpha as &dyn taut::integrate::MethodFactory,
        ],
        spaces: vec![taut::study::verify::case::Space::Modal],
        formulations: vec![taut::scene::Formulation::Lagrange],
        quick: false,
    };
    let rows = verify(&case, &sel, &|_, _| {}).unwrap();
    let j = rows
        .iter()
        .find(|r| r.variable == "J" && r.quantity == "displacement")
        .expect("a J row");
    println!(
        "J displacement: observed {:.2}, {:?} ({})",
        j.observed, j.status, j.note
    );
    assert_eq!(j.status, Status::Pass);
    assert!(!any_failed(&rows));
}
