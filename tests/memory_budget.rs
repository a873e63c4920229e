//! scratch harness (replaced below)
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            // old and new are both held while copied
            let now = LIVE.fetch_add(new_size, Ordering::Relaxed) + new_size;
            PEAK.fetch_max(now, Ordering::Relaxed);
            LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        }
        p
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn measure(text: &str, sets: &[&str]) {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let sc = taut::resolve_scene(text, &sets).unwrap();
    let e = sc.memory_estimate();
    drop(sc);
    let tmp = tempfile::tempdir().unwrap();
    let before = LIVE.load(Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    let req = taut::app::RunRequest {
        scene: taut::app::SceneSource::Text(text.to_string()),
        set: sets.clone(),
        out: Some(tmp.path().join("o")),
        tolerance: None,
    };
    let r = taut::app::run(&req, &taut::app::Silent);
    let peak = PEAK.load(Ordering::SeqCst) - before;
    println!(
        "{sets:?}: ok={} estimate {:.2} MiB (hist {:.2} block {:.2} model {:.2} other {:.2} filter {:.2}) peak {:.2} MiB ratio {:.3}",
        r.is_ok(),
        e.total() as f64 / 1048576.0,
        e.history as f64 / 1048576.0,
        e.csv_block as f64 / 1048576.0,
        e.model as f64 / 1048576.0,
        e.other() as f64 / 1048576.0,
        e.filter as f64 / 1048576.0,
        peak as f64 / 1048576.0,
        peak as f64 / e.total() as f64
    );
}

#[test]
fn explore() {
    let root = env!("CARGO_MANIFEST_DIR");
    let read = |s: &str| std::fs::read_to_string(format!("{root}/scenes/{s}")).unwrap();
    let refs = read("reference.toml");
    let drop = read("span_droppers.toml");
    let line = read("line_10_spans.toml");
    measure(&refs, &["time.end=0.05"]);
    measure(&refs, &["time.end=0.01", "output.field={every=1, points=20000}"]);
    measure(&refs, &["time.end=0.01", "output.snapshots=[0.0,0.005,0.01]", "output.snapshot_points=100000"]);
    measure(&drop, &["time.end=0.02"]);
    measure(&drop, &["time.end=0.02", "mesh.elements=2160"]);
    measure(&line, &["time.end=0.004"]);
    measure(&line, &["time.end=0.004", "line.spans=3", "line.droppers.count=60"]);
    measure(&line, &["time.end=0.004", "line.spans=3", "line.droppers.count=60", "contact.formulation=complementarity"]);
    measure(&line, &["time.end=0.004", "line.spans=2", "line.droppers.count=30", "contact.formulation=complementarity", "contact.complementarity.solver=clarabel"]);
    measure(&line, &["time.end=0.004", "output.envelope=true"]);
}
