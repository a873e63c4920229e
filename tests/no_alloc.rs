//! The step loop allocates nothing (DESIGN habit 6; issue: "no allocation in
//! the step loop"). A counting global allocator wraps the system one; after
//! the integrator is built, a stretch of steps must not allocate at all, for
//! one contact, two contacts (active set), a string, a moving force, the
//! penalty and impact formulations, and every time integrator. The complementarity formulation is the
//! exception: clarabel builds its solver per step (documented in
//! docs/formulations.md).

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

fn allocations_in_steps(text: &str, overrides: &[&str], steps: usize) -> usize {
    MEASURING.with(|m| m.set(true));
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let sc = taut::resolve_scene(text, &o).unwrap();
    let start = ALLOCATIONS.load(Ordering::Relaxed);
    let mut it = taut::integrate::Integrator::new(&sc).unwrap();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    // the counter works: building the model allocates its buffers
    assert!(before > start, "the counting allocator must see the setup");
    for _ in 0..steps {
        it.step().unwrap();
        let s = it.sample(0);
        it.check(&s, 0).unwrap();
    }
    ALLOCATIONS.load(Ordering::Relaxed) - before
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
}
