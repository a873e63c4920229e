//! Stopping on request (`taut::interrupt`, what the Python module does on
//! Ctrl-C): a run stops at its next step with `Error::Interrupted`, a batch
//! stops every lane, and a sweep saves no record of a stopped run, so that
//! resuming it gives the table of an uninterrupted sweep.
//!
//! The request is process-wide, so this file is its own test binary with a
//! single test: no other test can run while the flag is set.

use taut::study::sweep::{Axis, BatchWidth, SweepSpec, claim, sweep_batched};
use taut::{Error, interrupt, resolve_scene};

const REFERENCE: &str = include_str!("../scenes/reference.toml");

fn short() -> Vec<String> {
    vec![
        "mesh.elements=60".into(),
        "time.step=2e-4".into(),
        "time.end=0.3".into(),
    ]
}

#[test]
fn a_stop_request_stops_runs_batches_and_sweeps_without_losing_or_faking_results() {
    // a request stands until the last call at work returns
    let (a, b) = (interrupt::Call::enter(), interrupt::Call::enter());
    interrupt::request();
    drop(a);
    assert!(interrupt::requested(), "one call still at work");
    drop(b);
    assert!(!interrupt::requested(), "withdrawn with the last call");

    // a Ctrl-C seen outside the calls (Python's main thread while a thread
    // pool's workers run them): nothing when none is at work; else a stop
    // that stands for the hold, so that the calls a shutting-down pool
    // starts from its queue stop too, and no longer
    let hold = std::time::Duration::from_millis(300);
    assert!(!interrupt::request_if_working(hold));
    assert!(
        !interrupt::requested(),
        "no call at work: nothing requested"
    );
    let a = interrupt::Call::enter();
    assert!(interrupt::request_if_working(hold));
    drop(a);
    assert!(interrupt::requested(), "held after the last call");
    let queued = interrupt::Call::enter();
    assert!(
        interrupt::requested(),
        "a call started within the hold stops"
    );
    drop(queued);
    std::thread::sleep(2 * hold);
    let later = interrupt::Call::enter();
    assert!(
        !interrupt::requested(),
        "a call started after the hold runs"
    );
    drop(later);

    let sc = resolve_scene(REFERENCE, &short()).unwrap();

    // a run stops at the step after the request, from inside its progress
    let mut reports = 0;
    let out = taut::run(&sc, &mut |_, _| {
        reports += 1;
        interrupt::request();
    });
    assert!(matches!(out, Err(Error::Interrupted)), "{out:?}");
    assert_eq!(reports, 1, "no step after the request");
    interrupt::clear();
    assert!(
        taut::run(&sc, &mut |_, _| {}).is_ok(),
        "cleared: runs again"
    );

    // a study stops as a whole: a stopped run is not one of its failures
    interrupt::request();
    let words = taut::app::words::compare(
        "lagrange,penalty",
        (Some("generalized_alpha,bathe"), None),
        ("lagrange", None),
        None,
        false,
    );
    let compare = words
        .expect("known words")
        .run(REFERENCE, &short(), &mut |_, _| {});
    let words = taut::app::words::converge("step", (3, 2.0), (Some("newmark,bathe"), None), false);
    let converge = words
        .expect("known words")
        .run(REFERENCE, &short(), &mut |_, _| {});
    interrupt::clear();
    assert!(
        matches!(compare, Err(Error::Interrupted)),
        "compare listed it"
    );
    assert!(
        matches!(converge, Err(Error::Interrupted)),
        "converge listed it"
    );

    // a batch: every lane stops
    interrupt::request();
    let outs = taut::run_batch(
        &[sc.clone(), sc.clone(), sc.clone(), sc.clone()],
        4,
        &mut |_| {},
    );
    interrupt::clear();
    assert_eq!(outs.len(), 4);
    assert!(outs.iter().all(|o| matches!(o, Err(Error::Interrupted))));

    // a sweep stopped after its second finished point keeps whole records
    // of finished points only, and resumes to the uninterrupted table
    let spec = SweepSpec {
        scene_text: REFERENCE.to_string(),
        set: short(),
        axes: vec![Axis::parse("speed_ratio=0.4:1.2:8", false).unwrap()],
        check_refinement: false,
        paired: false,
        tolerance: None,
    };
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    let stopped = {
        let claimed = claim(&dir).unwrap();
        sweep_batched(&claimed, &spec, None, BatchWidth::Fixed(1), &|done, _| {
            if done >= 2 {
                interrupt::request();
            }
        })
    };
    interrupt::clear();
    assert!(matches!(stopped, Err(Error::Interrupted)), "{stopped:?}");
    let saved = std::fs::read_dir(dir.join("runs")).unwrap().count();
    assert!((2..8).contains(&saved), "{saved} records saved");
    let resumed = sweep_batched(
        &claim(&dir).unwrap(),
        &spec,
        None,
        BatchWidth::Auto,
        &|_, _| {},
    )
    .unwrap();
    let fresh_dir = tmp.path().join("fresh");
    let fresh = sweep_batched(
        &claim(&fresh_dir).unwrap(),
        &spec,
        None,
        BatchWidth::Auto,
        &|_, _| {},
    )
    .unwrap();
    // as CSV: the same bytes (NaN cells included, which == would not equate)
    assert_eq!(
        taut::report::sweep_table(&spec, &resumed).to_csv(),
        taut::report::sweep_table(&spec, &fresh).to_csv()
    );
    assert!(resumed.iter().all(|r| r.error.is_none()));
}
