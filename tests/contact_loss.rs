//! Contact loss you can trust (docs/contact_loss.md): P_l split at the
//! supports, the in-span part converging where the support part does not,
//! re-contact impulses converging where their peaks grow, and losses the run
//! does not resolve flagged. Reference case (TARGETS: the study's defaults),
//! generalized-α ρ∞ = 1, Lagrange contact; V0/c = 0.9 (134.92 m/s), where
//! contact is lost in the span. Cut-down ladders here; the full study is
//! `cargo xtask contact-loss`.

use crate::common;

use common::{run, scene, taut_bin};
use taut::record::LossClass;

/// The in-span P_l between the two finest steps of the cut-down ladder
/// (N = 1600, Δt = 2.5e-5 → 1.25e-5 s) changes by 0.02 % (measured,
/// docs/contact_loss.md); 2 % is the study's convergence criterion.
const SPAN_CONVERGED: f64 = 0.02;

/// Over the same halving the support part grows by 17 % (0.0024 → 0.0028):
/// more than this is "not converging".
const SUPPORT_GROWS: f64 = 0.10;

/// Re-contact impulses over the 2 ms window change by 0.02–0.9 % over the
/// same halving (measured); 3 % leaves room for the round-off of event timing.
const IMPULSE_CONVERGED: f64 = 0.03;

/// A re-contact whose contact is sustained over the window carries at least
/// the steady force (~50 N) over 2 ms, 0.1 N·s; one lost again inside the
/// window carries less, and its impulse depends on when the bounce ends
/// (±27 %, docs/contact_loss.md §2), so only sustained ones are compared.
const SUSTAINED_IMPULSE: f64 = 0.1;

/// Events of two runs are the same re-contact when their times differ by
/// less than this, s (one step of the coarser run is 2.5e-5 s).
const SAME_EVENT: f64 = 1e-3;

fn fast(dt: &str) -> taut::RunOutput {
    run(&scene(
        "reference.toml",
        &[
            "carrier.speed.cruise=134.92",
            "mesh.elements=1600",
            &format!("time.step={dt}"),
        ],
    ))
}

#[test]
fn the_in_span_part_converges_and_the_support_part_does_not() {
    let (a, b) = (fast("2.5e-5"), fast("1.25e-5"));
    for o in [&a, &b] {
        let s = &o.stats[0];
        assert_eq!(
            s.loss_fraction_span + s.loss_fraction_support,
            s.loss_fraction,
            "the parts add up to P_l"
        );
        // z = 4 ℓ_b = 4·sqrt(EI/T) at this resolution
        let lb = (1.34e11 * 9.64e-10 / 3.0e4_f64).sqrt();
        assert!(
            (s.support_zone - 4.0 * lb).abs() < 1e-12,
            "{}",
            s.support_zone
        );
    }
    let (sa, sb) = (&a.stats[0], &b.stats[0]);
    let span_change = (sb.loss_fraction_span - sa.loss_fraction_span).abs() / sb.loss_fraction_span;
    assert!(
        span_change < SPAN_CONVERGED,
        "in span {} → {}",
        sa.loss_fraction_span,
        sb.loss_fraction_span
    );
    assert!(sb.loss_fraction_span > 0.025, "contact is lost in the span");
    assert!(
        sb.loss_fraction_support > (1.0 + SUPPORT_GROWS) * sa.loss_fraction_support,
        "support {} → {}",
        sa.loss_fraction_support,
        sb.loss_fraction_support
    );

    // re-contacts in the span after a separation: impulses agree, the
    // largest peak grows
    let events = |o: &taut::RunOutput| -> Vec<taut::record::Recontact> {
        o.stats[0]
            .recontacts
            .iter()
            .filter(|r| !r.at_support && r.loss_before >= taut::record::stats::MIN_LOSS_TIME)
            .copied()
            .collect()
    };
    let (ea, eb) = (events(&a), events(&b));
    assert!(ea.len() >= 3, "{ea:?}");
    let mut matched = 0;
    for x in &ea {
        let Some(y) = eb.iter().find(|y| (y.time - x.time).abs() < SAME_EVENT) else {
            continue;
        };
        if x.window < taut::record::stats::RECONTACT_WINDOW * 0.99 || x.impulse < SUSTAINED_IMPULSE
        {
            continue; // cut by the end of the run, or lost again at once
        }
        matched += 1;
        assert!(
            (y.impulse - x.impulse).abs() <= IMPULSE_CONVERGED * y.impulse.abs(),
            "impulse at t = {}: {} → {}",
            x.time,
            x.impulse,
            y.impulse
        );
    }
    assert!(matched >= 1, "{ea:?}\n{eb:?}");
    let peak = |e: &[taut::record::Recontact]| e.iter().map(|r| r.peak).fold(0.0, f64::max);
    assert!(
        peak(&eb) > 1.2 * peak(&ea),
        "peaks {} → {}",
        peak(&ea),
        peak(&eb)
    );
}

/// At T = 38190 N, V0 = 149 m/s (`modal_exact`, J = 800) the in-span P_l
/// moves by 1.1e-3 and 9.3e-4 over Δt = 6.25e-5 → 3.125e-5 → 1.5625e-5 s
/// (measured): the bounces after each re-contact, more as Δt falls
/// (docs/contact_loss.md §3). More than this is "not converging".
const SPAN_WANDERS: f64 = 5e-4;

/// Over the same halvings its sustained part moves by 5e-5 and 6e-5
/// (measured); the 2e-4 of a loss fraction the study resolves (one 0.1 ms
/// step in a 0.5 s run) is "converged".
const SUSTAINED_SETTLES: f64 = 2e-4;

#[test]
fn the_sustained_part_settles_where_the_bounces_keep_the_in_span_part_moving() {
    let at = |dt: &str| {
        run(&scene(
            "reference.toml",
            &[
                "beam.tension=38190",
                "carrier.speed.cruise=149",
                "mesh.kind=\"galerkin\"",
                "mesh.modes=800",
                "integrator={ method = \"modal_exact\" }",
                &format!("time.step={dt}"),
            ],
        ))
        .stats[0]
            .clone()
    };
    let ladder = [at("6.25e-5"), at("3.125e-5"), at("1.5625e-5")];
    for w in ladder.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let span = (b.loss_fraction_span - a.loss_fraction_span).abs();
        let sustained = (b.loss_fraction_span_sustained - a.loss_fraction_span_sustained).abs();
        assert!(span > SPAN_WANDERS, "in span {a:?} → {b:?}");
        assert!(sustained < SUSTAINED_SETTLES, "sustained {sustained:e}");
        assert!(b.loss_fraction_span_sustained <= b.loss_fraction_span);
        assert!(
            b.loss_fraction_span_sustained > 0.02,
            "losses are sustained"
        );
    }
    // more bounces as Δt falls
    assert!(ladder[2].loss_interval_count > ladder[0].loss_interval_count);
}

#[test]
fn the_reference_scene_flags_its_unresolved_first_loss() {
    let out = run(&scene("reference.toml", &[]));
    let s = &out.stats[0];
    assert_eq!(s.loss_interval_class.first(), Some(&LossClass::Unresolved));
    assert!(s.suspect_loss_intervals >= 1);
    assert!(s.suspect_loss_fraction <= s.loss_fraction_span);
    let w: Vec<_> = out
        .warnings
        .iter()
        .filter(|w| w.contains("the run does not resolve them"))
        .collect();
    assert_eq!(w.len(), 1, "{:?}", out.warnings);
    assert!(w[0].contains("x/L = 0.6512"), "{}", w[0]);

    // the terminal says so beside the headline figure
    let tmp = tempfile::tempdir().unwrap();
    let o = taut_bin(&[
        "run",
        "scenes/reference.toml",
        "--quiet",
        "--out",
        tmp.path().to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("first loss at x/L = 0.6512 (unresolved: see WARNING)"),
        "{text}"
    );
    assert!(text.contains("in span +"), "{text}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("summary.json")).unwrap())
            .unwrap();
    for key in [
        "loss_fraction_span",
        "loss_fraction_support",
        "support_zone",
        "suspect_loss_intervals",
        "recontacts",
    ] {
        assert!(summary["contact"].get(key).is_some(), "{key}");
    }
}

#[test]
fn a_resolved_loss_is_not_flagged_and_a_free_end_has_no_zone() {
    // at N = 1600 and Δt = 5e-5 s the separations in the span at V0/c = 0.9
    // last longer than h/V and are not flagged; only the short bounces after
    // re-contacts are (3 steps' worth of the 0.0305)
    let out = fast("5e-5");
    let s = &out.stats[0];
    let resolved = s
        .loss_interval_class
        .iter()
        .filter(|c| **c == LossClass::Span)
        .count();
    assert!(resolved >= 3, "{:?}", s.loss_interval_class);
    assert!(
        s.suspect_loss_fraction < 0.02 * s.loss_fraction_span,
        "{} of {}",
        s.suspect_loss_fraction,
        s.loss_fraction_span
    );
    // the cantilever's free end holds nothing: the support zone is only at
    // x = 0 (an untensioned beam has no bending length ℓ_b = sqrt(EI/T),
    // hence no default zone: the scene gives one)
    let sc = scene(
        "t1_cantilever_riding_mass.toml",
        &["analysis.support_zone=0.5"],
    );
    let g = taut::record::LossGeometry::of(&sc, 0);
    assert!(g.in_support_zone(0.5 * g.support_zone));
    assert!(!g.in_support_zone(g.length - 0.5 * g.support_zone));
}

#[test]
fn sweep_check_refinement_adds_the_change_and_a_map() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    let o = taut_bin(&[
        "sweep",
        "scenes/reference.toml",
        "--vary",
        "speed_ratio=0.6:0.9:2",
        "--vary",
        "tension_ratio=0.001:0.0015:2",
        "--set",
        "mesh.elements=100",
        "--set",
        "time.step=2e-4",
        "--check-refinement",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for col in [
        "loss_fraction_span",
        "refined_elements",
        "refined_dt",
        "loss_fraction_span_change",
        "loss_fraction_span_converged",
    ] {
        assert!(header.contains(&col), "{col}: {header:?}");
    }
    let at = |c: &str| header.iter().position(|h| *h == c).unwrap();
    for row in csv.lines().skip(1) {
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells[at("refined_elements")], "200");
        assert_eq!(cells[at("refined_dt")], "0.0001");
        let (base, refined, change): (f64, f64, f64) = (
            cells[at("loss_fraction_span")].parse().unwrap(),
            cells[at("refined_loss_fraction_span")].parse().unwrap(),
            cells[at("loss_fraction_span_change")].parse().unwrap(),
        );
        assert_eq!(change, refined - base);
        assert!(["yes", "no"].contains(&cells[at("loss_fraction_span_converged")]));
    }
    let span = std::fs::read_to_string(out.join("loss_fraction_span_map.svg")).unwrap();
    assert!(span.contains("P_l in span"));
    let svg = std::fs::read_to_string(out.join("refinement_map.svg")).unwrap();
    assert!(
        svg.contains("under refinement"),
        "the map says what it shows"
    );

    // a 1-D sweep gets the two P_l curves, the unconverged stretch shaded
    let one = tmp.path().join("one");
    let o = taut_bin(&[
        "sweep",
        "scenes/reference.toml",
        "--vary",
        "speed_ratio=0.6:0.9:3",
        "--set",
        "mesh.elements=100",
        "--set",
        "time.step=2e-4",
        "--check-refinement",
        "--quiet",
        "--out",
        one.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(one.join("refinement.svg")).unwrap();
    assert!(svg.contains("points converged") && svg.contains("refined: 2N"));
}
