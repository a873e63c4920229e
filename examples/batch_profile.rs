//! Time a batch of B reference runs (N = 1600, Δt = 6.25e-5 s) against the
//! same runs alone: `cargo run --release --example batch_profile -- B`.
use std::time::Instant;

fn main() {
    let b: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(4);
    let text = include_str!("../scenes/reference.toml");
    let scenes: Vec<taut::Resolved> = (0..b)
        .map(|i| {
            let o = vec![
                format!(
                    "mesh.elements={}",
                    std::env::args().nth(2).unwrap_or("1600".into())
                ),
                "time.step=6.25e-5".to_string(),
                "time.end=0.2".to_string(),
                format!("carrier.0.speed.cruise={}", 80.0 + 5.0 * i as f64),
            ];
            taut::resolve_scene(text, &o).expect("scene")
        })
        .collect();
    let t = Instant::now();
    for sc in &scenes {
        taut::run(sc, &mut |_, _| {}).expect("run");
    }
    let alone = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let out = taut::run_batch(&scenes, b, &mut |_| {});
    let batched = t.elapsed().as_secs_f64();
    assert!(out.iter().all(|r| r.is_ok()));
    println!(
        "B = {b}: alone {alone:.3} s, batched {batched:.3} s, speed-up {:.2}",
        alone / batched
    );
}
