//! One definition per quantity: a quantity registered here, in a test and
//! nowhere else, appears in the run summary, the compare, precision and
//! sweep tables, converge, uncertainty, `run --tolerance`, the gate and
//! the names the Python module reads — without editing any other file.
//! A binary of its own: the registration is process-wide, and the other
//! binaries' tables must not gain its column.

use taut::quantity::{self, ErrorKind, Offer, Quantity, Window};
use taut::study::sweep::{Axis, SweepSpec};

const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// The test's own statistic: the largest gap under carrier 0 over the run
/// (a real quantity: the gap's extreme, m).
static LARGEST_GAP: Quantity = Quantity {
    name: "largest_gap_test",
    label: "largest gap (test)",
    unit: "m",
    definition: "the largest gap g = w − q over the recorded rows (a test's quantity)",
    window: Window::Run,
    count: false,
    smooth: false,
    error: ErrorKind::Contact,
    offer: Offer::ALL,
    read: |r| r.trace.gap.iter().copied().reduce(f64::max),
};

fn register() -> &'static Quantity {
    // one registration per process: tests run in parallel threads
    static ONCE: std::sync::OnceLock<&'static Quantity> = std::sync::OnceLock::new();
    ONCE.get_or_init(|| quantity::register(LARGEST_GAP).unwrap())
}

/// A short, coarse reference case: the carrier loses contact in it.
fn short() -> Vec<String> {
    vec![
        "mesh.elements=40".into(),
        "time.step=4e-4".into(),
        "time.end=0.3".into(),
    ]
}

/// One name, one column; and every column that is not a quantity is one
/// the registry reserves, so that no quantity a program registers can
/// take its name.
fn assert_unique(names: &[&str]) {
    for (i, n) in names.iter().enumerate() {
        assert!(!names[..i].contains(n), "column {n} twice: {names:?}");
        assert!(
            quantity::by_name(n).is_some() || quantity::registry::RESERVED.contains(n),
            "column {n} is neither a quantity nor reserved"
        );
    }
}

#[test]
fn a_registered_quantity_is_in_every_table() {
    let q = register();
    let name = q.name;
    let sc = taut::resolve_scene(REFERENCE, &short()).unwrap();
    let out = taut::run(&sc, &mut |_, _| {}).unwrap();
    let value = q.of(&out, 0).unwrap();
    assert!(value.is_finite());

    // the run summary, and its JSON
    let s = taut::report::Summary::new(&sc, &out);
    assert_eq!(s.quantities[0].get(q), Some(value));
    let json = serde_json::to_value(&s).unwrap();
    assert_eq!(json["quantities"][0][name], value);

    // the gate, by name and for carrier 0 by suffix
    assert_eq!(taut::study::gate::quantity(&out, name), Some(value));
    assert_eq!(
        taut::study::gate::quantity(&out, &format!("{name}_0")),
        Some(value)
    );

    // compare (and its CSV columns)
    let c = taut::study::compare::compare(
        REFERENCE,
        &short(),
        &[taut::scene::Formulation::Lagrange],
        taut::scene::Formulation::Lagrange,
        &mut |_, _| {},
    )
    .unwrap();
    let t = taut::report::compare_rows(&c);
    assert!(t.names().contains(&name), "{:?}", t.names());
    assert_unique(&t.names());
    assert_eq!(c.rows[0].quantities.get(q), Some(value));

    // precision's table: the quantity, and its own steps and dofs once
    let p = taut::study::precision::precision(
        REFERENCE,
        &short(),
        &[taut::scene::Formulation::Lagrange],
        2,
        2,
        &mut |_, _| {},
    )
    .unwrap();
    let t = taut::report::precision_rows(&p);
    assert!(t.names().contains(&name), "{:?}", t.names());
    assert_unique(&t.names());

    // a sweep's records and sweep.csv
    let spec = SweepSpec {
        scene_text: REFERENCE.to_string(),
        set: short(),
        axes: vec![Axis::parse("speed_ratio=0.5:0.6:2", false).unwrap()],
        check_refinement: false,
        paired: false,
        tolerance: None,
    };
    let tmp = tempfile::tempdir().unwrap();
    let records = taut::study::sweep::sweep(&spec, tmp.path(), None, &|_, _| {}).unwrap();
    assert!(records.iter().all(|r| r.quantities.get(q).is_some()));
    let t = taut::report::sweep_table(&spec, &records);
    assert!(t.names().contains(&name), "{:?}", t.names());
    assert_unique(&t.names());

    // converge: a row per level
    let conv = taut::study::converge::converge(
        REFERENCE,
        &short(),
        taut::study::converge::Refine::Step,
        2,
        2.0,
        &taut::study::reference::analytic_w,
        &mut |_, _| {},
    )
    .unwrap();
    assert_eq!(conv.rows.iter().filter(|r| r.quantity == name).count(), 2);

    // uncertainty: a row with its assessment
    let u = taut::study::uncertainty::uncertainty(REFERENCE, &short(), 3, &mut |_, _| {}).unwrap();
    assert!(u.quantities.iter().any(|r| r.quantity == name));

    // run --tolerance's results, and a sweep may target it
    assert!(taut::study::tolerance::results().contains(&q));
    assert!(taut::study::sweep::targets().contains(&q));
}

/// Every table offers exactly the registered quantities its kind names,
/// built-ins and registered alike: a list kept anywhere else would drift
/// from the registry and fail here.
#[test]
fn every_table_offers_what_the_registry_says() {
    let q = register();
    let all = quantity::all();
    assert!(all.contains(&q));
    for r in [Offer::RUN_TABLES, Offer::CONVERGE, Offer::UNCERTAINTY] {
        assert!(quantity::offered(r).contains(&q));
    }
    // the uncertainty table: every quantity offered to it but the exact ones
    let u: Vec<&str> = taut::study::uncertainty::quantities()
        .iter()
        .map(|q| q.name)
        .collect();
    let want: Vec<&str> = quantity::offered(Offer::UNCERTAINTY)
        .iter()
        .filter(|q| q.error != ErrorKind::Exact)
        .map(|q| q.name)
        .collect();
    assert_eq!(u, want);
    // the gate can check every quantity
    let gate = taut::study::gate::quantity_names();
    for q in &all {
        assert!(gate.contains(&q.name), "{}", q.name);
    }
    // a sweep table's columns hold every quantity offered to run tables, in
    // the registry's order
    let cols: Vec<String> = quantity::offered(Offer::RUN_TABLES)
        .iter()
        .map(|q| q.name.to_string())
        .collect();
    let t = taut::report::sweep_table(
        &SweepSpec {
            scene_text: REFERENCE.to_string(),
            set: vec![],
            axes: vec![Axis::parse("speed_ratio=0.5:0.5:1", false).unwrap()],
            check_refinement: false,
            paired: false,
            tolerance: None,
        },
        &[],
    );
    let names: Vec<String> = t.names().iter().map(|s| s.to_string()).collect();
    let found: Vec<&String> = names.iter().filter(|n| cols.contains(n)).collect();
    assert_eq!(found.len(), cols.len(), "{names:?}");
    // one name, one definition
    assert!(quantity::register(LARGEST_GAP).is_err());
}
