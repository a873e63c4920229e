//! Hostile input: scenes inside the documented ranges that would exhaust
//! memory or time, and random scene text and `--set` values.
//!
//! 1. Memory: the run's memory is estimated at validation, before anything
//!    is allocated, and a run above the budget is refused with the estimate,
//!    the budget and a way out (`[output] record_every`, which thins the
//!    history but not the statistics: those use every step whatever K).
//! 2. Quadratic checks: validation is O(n log n) or better in the number of
//!    probes and carriers, so 200 000 probes are checked at once.
//! 3. A property over random keys, values and TOML fragments applied to the
//!    bundled scenes: loading (and, for small scenes, a short run) returns
//!    `Ok` or a one-line, non-empty error — never a panic.

use std::panic::{AssertUnwindSafe, catch_unwind};

use proptest::prelude::*;
use taut::{Error, resolve_scene, run};

const REFERENCE: &str = include_str!("../scenes/reference.toml");
const STATIONARY: &str = include_str!("../scenes/t2_stationary_mass.toml");
const TWO: &str = include_str!("../scenes/two_pantographs.toml");

fn o(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

fn invalid_field(e: &Error) -> &str {
    match e {
        Error::Invalid { field, .. } => field,
        other => panic!("expected an invalid-scene error, got: {other}"),
    }
}

// ---------------------------------------------------------------- memory

/// A short scene with contact loss (the reference case on a coarse mesh
/// and step), two carriers and probes; its statistics must not depend on
/// which rows the history keeps.
#[test]
fn statistics_are_bit_identical_whatever_record_every() {
    for (text, extra) in [
        (REFERENCE, vec!["mesh.elements=60", "time.step=4e-4"]),
        (
            TWO,
            vec![
                "mesh.elements=60",
                "time.step=4e-4",
                "probe=[{ name = \"mid\", x = 25.0 }, { name = \"q\", x = 12.5 }]",
            ],
        ),
    ] {
        let full = resolve_scene(text, &o(&extra)).unwrap();
        let mut thin_o = extra.clone();
        thin_o.push("output.record_every=7");
        let thin = resolve_scene(text, &o(&thin_o)).unwrap();
        assert_eq!(full.record_every, 1);
        assert_eq!(thin.record_every, 7);
        let a = run(&full, &mut |_, _| {}).unwrap();
        let b = run(&thin, &mut |_, _| {}).unwrap();
        assert!(
            a.stats.iter().any(|s| s.contact_switches > 0),
            "the case must lose contact, else the statistics test little"
        );
        assert_eq!(a.stats, b.stats, "statistics differ with record_every = 7");
        assert_eq!(a.warnings, b.warnings);
        assert_eq!(a.steps, b.steps);
        // the thin history: row 0, every 7th step, and the last step
        let steps = a.steps;
        assert_eq!(a.history.len(), steps + 1);
        assert_eq!(b.history.len(), 1 + steps.div_ceil(7));
        assert_eq!(b.history.len(), thin.history_rows());
        assert_eq!(b.history.record_every, 7);
        let rows: Vec<usize> = (0..=steps).filter(|&n| n % 7 == 0 || n == steps).collect();
        for (j, &n) in rows.iter().enumerate() {
            assert_eq!(b.history.t[j].to_bits(), a.history.t[n].to_bits());
            for (ca, cb) in a.history.carriers.iter().zip(&b.history.carriers) {
                assert_eq!(cb.force[j].to_bits(), ca.force[n].to_bits());
                assert_eq!(cb.x[j].to_bits(), ca.x[n].to_bits());
                assert_eq!(cb.in_contact[j], ca.in_contact[n]);
            }
            for (pa, pb) in a.history.probes.iter().zip(&b.history.probes) {
                assert_eq!(pb.1[j].to_bits(), pa.1[n].to_bits());
            }
        }
        // the writers take the thin history: history.csv has its rows
        let dir = tempfile::tempdir().unwrap();
        taut::report::write_run(dir.path(), &thin, &b).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("history.csv")).unwrap();
        assert_eq!(csv.lines().count(), 1 + b.history.len());
        assert!(dir.path().join("force.svg").exists());
    }
}

#[test]
fn a_billion_steps_are_refused_at_once_with_the_estimate() {
    // 1e9 steps is inside the documented 1 ..= 10⁹; recorded row by row the
    // history alone is ≈ 45 GiB
    let over = o(&["time.step=1e-9", "time.end=1"]);
    let e = resolve_scene(STATIONARY, &over).unwrap_err();
    assert_eq!(invalid_field(&e), "output.record_every");
    let msg = e.to_string();
    assert!(msg.contains("estimated"), "{msg}");
    assert!(msg.contains("1000000001 rows"), "{msg}");
    assert!(msg.contains("memory budget of 2.000 GiB"), "{msg}");
    // the hint: the smallest record_every that fits, and it does fit
    let k: u64 = msg
        .split("record_every ≥ ")
        .nth(1)
        .and_then(|r| r.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|d| d.parse().ok())
        .unwrap_or_else(|| panic!("no record_every hint in: {msg}"));
    let mut ok = over.clone();
    ok.push(format!("output.record_every={k}"));
    let sc = resolve_scene(STATIONARY, &ok).unwrap();
    assert_eq!(sc.steps, 1_000_000_000);
    let mut short = over.clone();
    short.push(format!("output.record_every={}", k - 1));
    assert!(
        resolve_scene(STATIONARY, &short).is_err(),
        "K − 1 must not fit"
    );
}

#[test]
fn record_every_must_be_an_integer_of_at_least_one() {
    let e = resolve_scene(REFERENCE, &o(&["output.record_every=0"])).unwrap_err();
    assert_eq!(invalid_field(&e), "output.record_every");
    assert!(e.to_string().contains("≥ 1"), "{e}");
    for bad in ["1.5", "-3", "\"7\"", "true", "[7]"] {
        let e = resolve_scene(REFERENCE, &o(&[&format!("output.record_every={bad}")])).unwrap_err();
        assert!(
            matches!(e, Error::Parse { .. }) && e.to_string().contains("`output.record_every`"),
            "{bad}: {e}"
        );
    }
    let e = resolve_scene(REFERENCE, &o(&["output.every=2"])).unwrap_err();
    assert!(e.to_string().contains("unknown field `every`"), "{e}");
    // a file's [output] table as well as a --set
    let text = format!("{REFERENCE}\n[output]\nrecord_every = 3\n");
    assert_eq!(resolve_scene(&text, &[]).unwrap().record_every, 3);
}

#[test]
fn the_largest_mesh_fits_the_budget_but_not_with_thousands_of_carriers() {
    // the documented maximum of mesh.elements stays accepted
    let sc = resolve_scene(REFERENCE, &o(&["mesh.elements=1000000"])).unwrap();
    assert_eq!(sc.elements, 1_000_000);
    // 2000 carriers on it: each carrier's constraint column spans the mesh
    let mut extra = String::new();
    for i in 0..2000 {
        extra.push_str(&format!(
            "\n[[carrier]]\nforce = 1.0\nside = \"above\"\nstart = {}\nspeed = {{ profile = \"constant\", value = 0.0 }}\n",
            i as f64 * 0.01
        ));
    }
    let text = REFERENCE
        .replacen("[contact]", &format!("{extra}\n[contact]"), 1)
        .replace("end = \"carrier_leaves\"", "end = 0.01");
    let e = resolve_scene(&text, &o(&["mesh.elements=1000000"])).unwrap_err();
    assert_eq!(invalid_field(&e), "mesh.elements", "{e}");
    assert!(e.to_string().contains("2001 carrier(s)"), "{e}");
    assert!(e.to_string().contains("memory budget"), "{e}");
    // and on the scene's own 400 elements they fit
    resolve_scene(&text, &[]).unwrap();
}

// ----------------------------------------------------- quadratic checks

fn many_probes(n: usize, duplicate_of: Option<usize>) -> String {
    let mut text = String::from(REFERENCE);
    text.reserve(n * 40);
    for i in 0..n {
        let name = match duplicate_of {
            Some(j) if i == n - 1 => j,
            _ => i,
        };
        text.push_str(&format!(
            "[[probe]]\nname = \"p{name}\"\nx = {}\n",
            (i % 50) as f64
        ));
    }
    text
}

/// 200 000 probes: a check that scans the probes so far for every probe
/// makes 2·10¹⁰ comparisons (minutes); a set makes 2·10⁵ look-ups.
#[test]
fn two_hundred_thousand_probes_with_a_duplicate_at_the_end_are_refused() {
    let n = 200_000;
    let e = resolve_scene(&many_probes(n, Some(123)), &[]).unwrap_err();
    assert_eq!(invalid_field(&e), format!("probe.{}.name", n - 1));
    let msg = e.to_string();
    assert!(msg.contains("\"p123\""), "{msg}");
    assert!(msg.contains("probe.123.name has it too"), "{msg}");
    // without the duplicate, so many probes recorded every step do not fit
    // the memory budget: refused with the estimate, not run out of memory
    let e = resolve_scene(&many_probes(n, None), &[]).unwrap_err();
    assert_eq!(invalid_field(&e), "output.record_every", "{e}");
    assert!(e.to_string().contains("memory budget"), "{e}");
}

// -------------------------------------------- random keys and values

/// Keys the scenes have, and some they do not.
const KNOWN_KEYS: &[&str] = &[
    "beam",
    "beam.length",
    "beam.tension",
    "beam.left",
    "beam.right",
    "beam.density",
    "beam.area",
    "beam.youngs_modulus",
    "beam.second_moment",
    "beam.mass_per_length",
    "beam.bending_stiffness",
    "mesh",
    "mesh.elements",
    "carrier",
    "carrier.0",
    "carrier.1",
    "carrier.mass",
    "carrier.0.mass",
    "carrier.stiffness",
    "carrier.damping",
    "carrier.preload",
    "carrier.force",
    "carrier.side",
    "carrier.start",
    "carrier.speed",
    "carrier.speed.profile",
    "carrier.speed.cruise",
    "carrier.speed.value",
    "contact",
    "contact.kind",
    "contact.formulation",
    "contact.placement",
    "contact.penalty",
    "contact.penalty.stiffness",
    "contact.penalty.relative",
    "contact.complementarity.max_iter",
    "contact.complementarity.tol_feas",
    "contact.impact.restitution",
    "time",
    "time.step",
    "time.end",
    "integrator",
    "integrator.method",
    "integrator.rho_inf",
    "integrator.alpha",
    "integrator.gamma",
    "integrator.theta",
    "gravity.g",
    "gravity.beam_self_weight",
    "probe",
    "probe.0",
    "probe.0.x",
    "probe.0.name",
    "output",
    "output.record_every",
];

fn key() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => proptest::sample::select(KNOWN_KEYS).prop_map(str::to_string),
        1 => proptest::collection::vec("[a-z_0-9]{1,6}", 1..4).prop_map(|s| s.join(".")),
        1 => proptest::sample::select(&[
            "", ".", "beam.", ".beam", "a..b", "carrier.99.mass", "carrier.0.0",
            "beam.length.x", "time.step.0", "probe.5.x", "carrier.-1.mass",
            "carrier.18446744073709551616.mass", "mesh.elements.elements",
        ][..])
        .prop_map(str::to_string),
    ]
}

fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|x| format!("{x:e}")),
        any::<i64>().prop_map(|x| x.to_string()),
        (-3i32..8).prop_map(|e| format!("1e{e}")),
        (0u32..2000).prop_map(|x| x.to_string()),
        proptest::sample::select(
            &[
                "nan",
                "+nan",
                "-nan",
                "inf",
                "-inf",
                "+inf",
                "0",
                "-0",
                "-0.0",
                "1e308",
                "1e309",
                "-1e400",
                "5e-324",
                "18446744073709551615",
                "18446744073709551616",
                "-9223372036854775808",
                "4294967296",
                "1000000000",
                "1000000001",
                "0x10",
                "1_000",
                "0.5",
                "1.5",
            ][..]
        )
        .prop_map(str::to_string),
    ]
}

fn value() -> impl Strategy<Value = String> {
    let scalar = prop_oneof![
        4 => number(),
        1 => proptest::sample::select(&[
            "true", "false", "\"\"", "\"carrier_leaves\"", "carrier_leaves", "pinned",
            "free", "clamped", "bathe", "moreau_jean", "central_difference", "hht",
            "penalty", "impact", "complementarity", "bilateral", "alpha", "above",
            "below", "\"constant\"", "1979-05-27", "\"a\\nb\"", "'''x\ny'''",
        ][..])
        .prop_map(str::to_string),
        1 => "[ -~]{0,12}",
    ];
    prop_oneof![
        6 => scalar.clone(),
        1 => proptest::collection::vec(scalar.clone(), 0..3)
            .prop_map(|v| format!("[{}]", v.join(", "))),
        1 => (number(), proptest::sample::select(&["constant", "smooth_ramp", "x"][..]))
            .prop_map(|(n, p)| format!(
                "{{ profile = \"{p}\", value = {n}, cruise = {n} }}"
            )),
        1 => (number(), number()).prop_map(|(a, b)| format!(
            "{{ profile = \"constant\", value = {a} }}, {b}"
        )),
        1 => (number(), "[a-z0-9_-]{0,6}").prop_map(|(x, n)| format!(
            "[{{ name = \"{n}\", x = {x} }}]"
        )),
        1 => (key(), scalar).prop_map(|(k, v)| format!("{{ {k} = {v} }}")),
    ]
}

/// A TOML fragment appended to the scene text.
fn fragment() -> impl Strategy<Value = String> {
    prop_oneof![
        1 => (number()).prop_map(|n| format!("\n[output]\nrecord_every = {n}\n")),
        1 => (number(), "[a-z0-9_\"-]{0,6}").prop_map(|(x, n)| format!(
            "\n[[probe]]\nname = \"{n}\"\nx = {x}\n"
        )),
        1 => (number(), number()).prop_map(|(m, s)| format!(
            "\n[[carrier]]\nmass = {m}\nstiffness = 1.0\nside = \"below\"\nstart = {s}\nspeed = {{ profile = \"constant\", value = 0.0 }}\n"
        )),
        1 => (key(), value()).prop_map(|(k, v)| format!("\n{k} = {v}\n")),
        1 => "[ -~\n]{0,30}".prop_map(|s| format!("\n{s}\n")),
        5 => Just(String::new()),
    ]
}

fn scene_text() -> impl Strategy<Value = &'static str> {
    proptest::sample::select(
        &[
            include_str!("../scenes/reference.toml"),
            include_str!("../scenes/t1_cantilever_riding_mass.toml"),
            include_str!("../scenes/t2_stationary_mass.toml"),
            include_str!("../scenes/t2_stationary_mass_string.toml"),
            include_str!("../scenes/two_pantographs.toml"),
            include_str!("../scenes/moving_force_beam.toml"),
            include_str!("../scenes/moving_force_string.toml"),
            include_str!("../scenes/oscillator_one_dof.toml"),
            include_str!("../scenes/span_droppers.toml"),
        ][..],
    )
}

/// Overrides that make a scene small enough to run in a test.
const SHRINK: &[&str] = &["mesh.elements=8", "time.step=2e-3"];

/// Runs only scenes this small (the property is about input, not physics).
const MAX_RUN_ELEMENTS: usize = 64;
const MAX_RUN_STEPS: usize = 500;
const MAX_RUN_CARRIERS: usize = 4;

fn one_line_or_ok<T>(what: &str, r: std::thread::Result<taut::Result<T>>) -> Option<T> {
    match r {
        Err(_) => panic!("{what}: panicked"),
        Ok(Ok(v)) => Some(v),
        Ok(Err(e)) => {
            let msg = e.to_string();
            assert!(!msg.trim().is_empty(), "{what}: empty error");
            assert!(!msg.contains('\n'), "{what}: multi-line error: {msg}");
            None
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        // 192 by default (about a second in release); PROPTEST_CASES=n for a
        // longer search
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(192),
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::WithSource("proptest-regressions"),
        )),
        // a fixed seed (PROPTEST_RNG_SEED=n for another search)
        rng_seed: proptest::test_runner::RngSeed::Fixed(
            std::env::var("PROPTEST_RNG_SEED")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(0x7a07),
        ),
        ..ProptestConfig::default()
    })]

    /// Loading, and a short run of small scenes, is `Ok` or a one-line
    /// error: never a panic, an empty or a multi-line message.
    #[test]
    fn hostile_scenes_load_or_fail_in_one_line(
        base in scene_text(),
        frag in fragment(),
        sets in proptest::collection::vec((key(), value()), 0..3),
        shrink in any::<bool>(),
        raw in proptest::option::weighted(0.2, "[ -~]{0,20}"),
    ) {
        let text = format!("{base}{frag}");
        let mut overrides: Vec<String> = if shrink {
            SHRINK.iter().map(|s| s.to_string()).collect()
        } else {
            Vec::new()
        };
        overrides.extend(sets.iter().map(|(k, v)| format!("{k}={v}")));
        overrides.extend(raw);
        let what = format!("scene + {frag:?} with {overrides:?}");
        let loaded = catch_unwind(AssertUnwindSafe(|| resolve_scene(&text, &overrides)));
        if let Some(sc) = one_line_or_ok(&what, loaded)
            && sc.elements <= MAX_RUN_ELEMENTS
            && sc.steps <= MAX_RUN_STEPS
            && sc.carriers.len() <= MAX_RUN_CARRIERS
        {
            let out = catch_unwind(AssertUnwindSafe(|| run(&sc, &mut |_, _| {})));
            one_line_or_ok(&format!("run of {what}"), out);
        }
    }
}

/// Messages that used to span several lines: a TOML syntax error and a key
/// with a line break in it.
#[test]
fn parse_errors_are_one_line() {
    for text in [
        format!("{REFERENCE}\n[beam\n"),
        format!("{REFERENCE}\n\"a\\nb\" = 1\n"),
        "x = = 1".to_string(),
        "\u{feff}[beam]\nlength = \"\n".to_string(),
    ] {
        let e = resolve_scene(&text, &[]).unwrap_err();
        let msg = e.to_string();
        assert!(!msg.contains('\n') && !msg.is_empty(), "{msg}");
    }
    let e = resolve_scene(REFERENCE, &o(&["beam.length=[1,\n2"])).unwrap_err();
    assert!(!e.to_string().contains('\n'), "{e}");
    let e = resolve_scene(&format!("{REFERENCE}\n[beam\n"), &[]).unwrap_err();
    assert!(e.to_string().contains("line "), "{e}");
}
