//! The step loop allocates nothing (DESIGN habit 6). A counting global
//! allocator wraps the system one; after
//! the integrator is built, a stretch of steps must not allocate at all, for
//! one contact, two contacts (active set), a string, a moving force, the
//! penalty, impact and complementarity formulations, and every time
//! integrator. The complementarity law keeps one clarabel solver per problem
//! size for the run and updates its data in place (src/contact/complementarity.rs);
//! its cases also count the steps in which a contact was closed and open, so
//! they cannot pass without the law having solved QPs.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// Count only on the thread that measures: the test harness's own
    /// threads allocate when they like (a process-wide count was flaky).
    static MEASURING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

fn count() {
    if MEASURING.with(|m| m.get()) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: forwards to the system allocator, only counting calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

const REFERENCE: &str = include_str!("../scenes/reference.toml");
const T2_STRING: &str = include_str!("../scenes/t2_stationary_mass_string.toml");
const TWO_PANTOGRAPHS: &str = include_str!("../scenes/two_pantographs.toml");
const MMS_LOSS: &str = include_str!("../scenes/verify/mms_loss.toml");
const SPAN_DROPPERS: &str = include_str!("../scenes/span_droppers.toml");
const SPAN_MESSENGER: &str = include_str!("../scenes/span_messenger.toml");

/// What a measured stretch of steps did.
struct Stretch {
    /// Allocations counted during the steps.
    allocations: usize,
    /// Carrier-steps with the contact closed and a positive force.
    closed: usize,
    /// Carrier-steps with the contact open.
    open: usize,
}

fn allocations_in_steps(text: &str, overrides: &[&str], steps: usize) -> usize {
    measure_steps(text, overrides, steps).allocations
}

fn measure_steps(text: &str, overrides: &[&str], steps: usize) -> Stretch {
    MEASURING.with(|m| m.set(true));
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let sc = taut::resolve_scene(text, &o).unwrap();
    let start = ALLOCATIONS.load(Ordering::Relaxed);
    let mut it = taut::integrate::Integrator::new(&sc).unwrap();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    // the counter works: building the model allocates its buffers
    assert!(before > start, "the counting allocator must see the setup");
    let (mut closed, mut open) = (0, 0);
    for _ in 0..steps {
        it.step().unwrap();
        for i in 0..it.carriers() {
            let s = it.sample(i);
            it.check(&s, i).unwrap();
            if s.in_contact && s.force > 0.0 {
                closed += 1;
            } else if !s.in_contact {
                open += 1;
            }
        }
    }
    Stretch {
        allocations: ALLOCATIONS.load(Ordering::Relaxed) - before,
        closed,
        open,
    }
}

/// Allocations while a batch of runs (`integrate::batch`) steps: four
/// reference runs at different speeds, through contact loss.
fn batch_allocations(steps: usize) -> (usize, usize) {
    MEASURING.with(|m| m.set(true));
    let scenes: Vec<taut::Resolved> = (0..4)
        .map(|i| {
            let o = vec![format!("carrier.0.speed.cruise={}", 90.0 + 5.0 * i as f64)];
            taut::resolve_scene(REFERENCE, &o).unwrap()
        })
        .collect();
    let list: Vec<(usize, &taut::Resolved)> = scenes.iter().enumerate().collect();
    let (batch, errors) = taut::integrate::Batch::new(&list);
    assert!(errors.is_empty());
    let mut b = batch.unwrap();
    assert!(b.supported());
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    let mut open = 0;
    for _ in 0..steps {
        b.step();
        for l in 0..b.lanes().len() {
            assert!(b.lanes()[l].failed.is_none());
            open += usize::from(!b.sample(l, 0).in_contact);
        }
    }
    (ALLOCATIONS.load(Ordering::Relaxed) - before, open)
}

// One test function: the counter is global, so parallel tests would mix counts.
#[test]
fn step_loop_does_not_allocate() {
    // through contact loss near the right support (steps 5000–6000)
    assert_eq!(allocations_in_steps(REFERENCE, &[], 6000), 0, "one contact");
    for f in ["penalty", "impact"] {
        let o = format!("contact.formulation={f}");
        assert_eq!(allocations_in_steps(REFERENCE, &[&o], 6000), 0, "{f}");
    }
    complementarity();
    line_outputs();
    droppers();
    // batched stepping: four runs as lanes of one sweep, through contact loss
    let (allocations, open) = batch_allocations(5500);
    assert_eq!(allocations, 0, "a batch of four runs");
    assert!(open > 0, "the batch must pass through contact loss");
    // the space discretizations (MODEL §9.2): dense point vectors refilled
    // in place; graded meshes, a Moreau–Jean step (slope vectors too)
    for (kind, extra) in [
        ("mesh.kind=galerkin", "mesh.modes=60"),
        ("mesh.kind=modal", "mesh.modes=60"),
        ("mesh.grading=supports", "mesh.grading_ratio=8"),
    ] {
        assert_eq!(
            allocations_in_steps(REFERENCE, &[kind, extra], 6000),
            0,
            "{kind}"
        );
        let mj = "integrator={ method = \"moreau_jean\" }";
        assert_eq!(
            allocations_in_steps(REFERENCE, &[kind, extra, mj], 6000),
            0,
            "{kind} with moreau_jean"
        );
    }
    assert_eq!(
        allocations_in_steps(REFERENCE, &["contact.kind=bilateral"], 2000),
        0,
        "bilateral"
    );
    // every time integrator, through contact loss; central difference at a
    // step below its stability limit (2/ω_max = 6.1e-5 s at N = 400)
    for (method, extra) in [
        ("newmark", ""),
        ("bathe", ""),
        ("central_difference", "time.step=5e-5"),
        ("moreau_jean", ""),
    ] {
        let m = format!("integrator={{ method = \"{method}\" }}");
        let mut o = vec![m.as_str()];
        if !extra.is_empty() {
            o.push(extra);
        }
        assert_eq!(allocations_in_steps(REFERENCE, &o, 6000), 0, "{method}");
        o.push("contact.formulation=impact");
        if method != "moreau_jean" {
            assert_eq!(
                allocations_in_steps(REFERENCE, &o, 6000),
                0,
                "{method} with the impact law"
            );
        }
    }
    let two = REFERENCE.replacen(
        "[contact]",
        "[[carrier]]\nmass = 1.0\nstiffness = 987.0\npreload = 0.05\nside = \"above\"\nstart = 10.0\nspeed = { profile = \"smooth_ramp\", cruise = 100.0 }\n\n[contact]",
        1,
    );
    assert_eq!(allocations_in_steps(&two, &[], 4000), 0, "two contacts");
    // a mesh so small that the banded kernels take their general path
    assert_eq!(
        allocations_in_steps(REFERENCE, &["mesh.elements=2", "time.end=0.1"], 500),
        0,
        "two elements"
    );
    assert_eq!(
        allocations_in_steps(T2_STRING, &["time.end=0.5"], 4000),
        0,
        "string"
    );
    let force = T2_STRING.replacen(
        "mass = 1.0               # kg\nstiffness = 987.0        # N/m\npreload = 0.05           # m\n",
        "force = 50.0\n",
        1,
    );
    assert!(force.contains("force = 50.0"));
    assert_eq!(
        allocations_in_steps(&force, &["time.end=0.5"], 4000),
        0,
        "moving force"
    );
    // a manufactured source (MODEL §11): its load vectors, point loads and
    // mass source evaluated every step, through the prescribed loss and
    // reattachment, on every discretization and under every method
    let m = measure_steps(MMS_LOSS, &[], 300);
    assert_eq!(m.allocations, 0, "manufactured");
    assert!(m.open > 0 && m.closed > 0, "through the loss: {}", m.open);
    for o in [
        &["mesh.kind=galerkin", "mesh.modes=32"][..],
        &["mesh.kind=modal", "mesh.modes=32"],
        &["integrator={ method = \"bathe\" }"],
        &["integrator={ method = \"moreau_jean\" }"],
        &[
            "integrator={ method = \"central_difference\" }",
            "time.step=2e-5",
        ],
    ] {
        assert_eq!(
            allocations_in_steps(MMS_LOSS, o, 300),
            0,
            "manufactured {o:?}"
        );
    }
    modal_exact(&force);
    external_forces();
}

/// External forces on the mass (`external_force` series, a force held
/// between steps) and a run stepped on request (`run::SteppedRun`, what
/// `app::Simulation` steps): the series is evaluated and the held force
/// applied every step, through contact loss, with the run recorded.
fn external_forces() {
    let series = "carrier.0.external_force={time=[0.0,0.3,1.0],force=[0.0,-5.0,3.0]}";
    for o in [
        &[series][..],
        &[
            series,
            "mesh.kind=galerkin",
            "mesh.modes=60",
            "integrator={ method = \"modal_exact\" }",
        ],
        &[
            series,
            "integrator={ method = \"central_difference\" }",
            "time.step=5e-5",
        ],
    ] {
        assert_eq!(allocations_in_steps(REFERENCE, o, 6000), 0, "series {o:?}");
    }
    MEASURING.with(|m| m.set(true));
    let sc = taut::resolve_scene(REFERENCE, &[]).unwrap();
    let mut it = taut::integrate::Integrator::new(&sc).unwrap();
    // the first hold allocates the external forces' buffers, once
    it.hold_external_force(0, 1.0).unwrap();
    let mut run = taut::run::SteppedRun::new(&sc, it, std::time::Instant::now()).unwrap();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for n in 0..6000 {
        run.integrator_mut()
            .hold_external_force(0, (n % 7) as f64)
            .unwrap();
        run.step(&sc).unwrap();
    }
    assert_eq!(
        ALLOCATIONS.load(Ordering::Relaxed) - before,
        0,
        "a held force, stepped and recorded"
    );
}

/// Tension-only droppers (`integrate::dropper`, docs/lines.md D7–D10):
/// the rows of the slack droppers packed per step, the set grown and the
/// small problem solved again, the corrections added to the free
/// solution, under each law that carries them, on fixed anchors and on a
/// messenger, through slackening and re-tension; with Kelvin–Voigt
/// dashpots on every dropper too (D12: the free rates in each row).
fn droppers() {
    MEASURING.with(|m| m.set(true));
    // the messenger span's droppers slacken under a pantograph pushing with
    // 530 N (preload 0.15 m) instead of 100 N
    for (text, what, preload) in [
        (SPAN_DROPPERS, "fixed anchors", "0.0357"),
        (SPAN_MESSENGER, "messenger", "0.15"),
    ] {
        for (f, c_d) in [
            ("lagrange", 0.0),
            ("complementarity", 0.0),
            ("penalty", 0.0),
            ("lagrange", 200.0),
        ] {
            let mut o = vec![
                format!("contact.formulation={f}"),
                format!("carrier.0.preload={preload}"),
            ];
            if c_d > 0.0 {
                o.extend((0..7).map(|i| format!("dropper.{i}.damping={c_d}")));
            }
            let sc = taut::resolve_scene(text, &o).unwrap();
            let mut it = taut::integrate::Integrator::new(&sc).unwrap();
            let mut samples = vec![taut::integrate::DropperSample::default(); sc.droppers.len()];
            let mut was_slack = vec![false; samples.len()];
            let before = ALLOCATIONS.load(Ordering::Relaxed);
            let (mut slack, mut taut_after_slack) = (0, 0);
            for _ in 0..3000 {
                it.step().unwrap();
                it.dropper_samples_into(&mut samples);
                for (s, w) in samples.iter().zip(was_slack.iter_mut()) {
                    slack += usize::from(s.slack);
                    taut_after_slack += usize::from(*w && !s.slack);
                    *w = s.slack;
                }
            }
            assert_eq!(
                ALLOCATIONS.load(Ordering::Relaxed) - before,
                0,
                "droppers on {what}, {f}, c_d = {c_d}"
            );
            assert!(
                slack > 0 && taut_after_slack > 0,
                "through slack and re-tension on {what}, {f}: {slack} {taut_after_slack}"
            );
        }
    }
}

/// The line's outputs in a recorded run (`run::SteppedRun`, the
/// recorder [`taut::run`] drives): the span statistics, the uplift at the
/// supports from point vectors made once, and the envelope at every node,
/// through contact loss.
fn line_outputs() {
    MEASURING.with(|m| m.set(true));
    let o: Vec<String> = [
        "output.supports=[0.0, 12.5, 30.0, 50.0]",
        "output.envelope=true",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let sc = taut::resolve_scene(REFERENCE, &o).unwrap();
    let it = taut::integrate::Integrator::new(&sc).unwrap();
    let mut run = taut::run::SteppedRun::new(&sc, it, std::time::Instant::now()).unwrap();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..6000 {
        run.step(&sc).unwrap();
    }
    assert_eq!(
        ALLOCATIONS.load(Ordering::Relaxed) - before,
        0,
        "supports and envelope, stepped and recorded"
    );
    let h = run.history();
    assert_eq!((h.supports.len(), h.envelope.x.len()), (4, sc.elements + 1));
}

/// `modal_exact` (MODEL §9.3): on each diagonal basis through contact loss,
/// the fast shapes near the clamped end (its boundary-layer table) and
/// mid-span, two contacts, the penalty, complementarity and impact laws, a moving
/// force with self-weight, and a batch of runs sharing one basis.
fn modal_exact(force: &str) {
    let me = "integrator={ method = \"modal_exact\" }";
    for (kind, extra) in [
        ("mesh.kind=galerkin", "mesh.modes=200"),
        ("mesh.kind=modal", "mesh.modes=60"),
    ] {
        let s = measure_steps(REFERENCE, &[me, kind, extra], 6000);
        assert_eq!(s.allocations, 0, "modal_exact, {kind}");
        assert!(s.open > 0, "modal_exact, {kind}: the contact never opened");
    }
    let g = ["mesh.kind=galerkin", "mesh.modes=100"];
    for f in ["penalty", "complementarity"] {
        let o = format!("contact.formulation={f}");
        assert_eq!(
            allocations_in_steps(REFERENCE, &[me, g[0], g[1], &o], 6000),
            0,
            "modal_exact, {f}"
        );
    }
    // the impact law: 8 re-contacts in these 3000 steps, each step re-taken
    // in place
    let impact = [
        "contact.formulation=impact",
        "beam.left=pinned",
        "carrier.speed={ profile = \"constant\", value = 165 }",
    ];
    let s = measure_steps(
        REFERENCE,
        &[me, g[0], g[1], impact[0], impact[1], impact[2]],
        3000,
    );
    assert_eq!(s.allocations, 0, "modal_exact, impact");
    assert!(s.open > 0, "modal_exact, impact: the contact never opened");
    assert_eq!(
        allocations_in_steps(TWO_PANTOGRAPHS, &[me, g[0], g[1]], 4000),
        0,
        "modal_exact, two contacts"
    );
    assert_eq!(
        allocations_in_steps(
            force,
            &[
                me,
                g[0],
                g[1],
                "gravity.beam_self_weight=true",
                "time.end=0.5"
            ],
            4000
        ),
        0,
        "modal_exact, a moving force"
    );
    MEASURING.with(|m| m.set(true));
    let scenes: Vec<taut::Resolved> = (0..3)
        .map(|i| {
            let o = vec![
                me.to_string(),
                g[0].to_string(),
                "mesh.modes=200".to_string(),
                format!("carrier.0.speed.cruise={}", 96.0 + 2.0 * i as f64),
            ];
            taut::resolve_scene(REFERENCE, &o).unwrap()
        })
        .collect();
    let list: Vec<(usize, &taut::Resolved)> = scenes.iter().enumerate().collect();
    let (batch, errors) = taut::integrate::new_batch(&list);
    assert!(errors.is_empty());
    let mut b = batch.unwrap();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    let mut open = 0;
    let steps = scenes.iter().map(|s| s.steps).min().unwrap();
    for _ in 0..steps {
        b.step();
        for l in 0..b.lanes().len() {
            assert!(b.lanes()[l].failed.is_none());
            open += usize::from(!b.sample(l, 0).in_contact);
        }
    }
    assert_eq!(
        ALLOCATIONS.load(Ordering::Relaxed) - before,
        0,
        "a modal_exact batch"
    );
    assert!(open > 0, "the modal batch must pass through contact loss");
}

/// The complementarity law (clarabel, one solver per problem size updated in
/// place): one contact through contact loss, two contacts, bilateral, and the
/// velocity-level moreau_jean step whose index set changes size. Each case
/// must see closed contacts (λ > 0 from a QP) during the measured steps.
fn complementarity() {
    let qp = "contact.formulation=complementarity";
    let one = measure_steps(REFERENCE, &[qp], 6000);
    assert_eq!(one.allocations, 0, "complementarity, one contact");
    // in contact for most of the run, and through the loss near the support
    assert!(one.closed > 4000, "closed in {} steps", one.closed);
    assert!(one.open > 0, "the contact never opened");

    let two = measure_steps(TWO_PANTOGRAPHS, &[qp], 4000);
    assert_eq!(two.allocations, 0, "complementarity, two contacts");
    assert!(
        two.closed > 2 * 3000,
        "closed in {} carrier-steps",
        two.closed
    );

    let bilateral = measure_steps(REFERENCE, &[qp, "contact.kind=bilateral"], 2000);
    assert_eq!(bilateral.allocations, 0, "complementarity, bilateral");
    assert!(
        bilateral.closed > 1000,
        "closed in {} steps",
        bilateral.closed
    );

    let mj = "integrator={ method = \"moreau_jean\" }";
    let velocity = measure_steps(TWO_PANTOGRAPHS, &[qp, mj], 4000);
    assert_eq!(velocity.allocations, 0, "complementarity, moreau_jean");
    assert!(
        velocity.closed > 0 && velocity.open > 0,
        "closed {} open {}",
        velocity.closed,
        velocity.open
    );
}
