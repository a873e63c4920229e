//! What a `modal_exact` step's memory traffic alone costs
//! (docs/performance.md "Fewer bytes a step"): J = 800 modes, arrays of J
//! doubles read and written as the step's passes read and write theirs,
//! with almost no arithmetic (a few adds per vector), so the time is the
//! traffic's. If a step takes about what its streams take here, the step
//! is bound by them, not by its operations.
//!
//! Layouts measured (loads + stores per mode and step):
//! * `two passes, tables` — the fused pass 11 + 3, the update pass 8 + 2 (24);
//! * `one pass, tables` — the deferred update in the fused pass: 14 + 3 (17);
//! * `one pass, cruise` — the phasor's rotation instead of the tables'
//!   rows: 14 + 4 (18).
//!
//! `cargo run --release --example stream_probe [-- J [STEPS]]`; prints the
//! fastest of five repetitions per layout (µs a step). AVX2 only.

use std::hint::black_box;
use std::time::Instant;

/// One pass over `j` modes reading `L` arrays and writing `S` arrays of
/// `mem` (arrays of `j` doubles, back to back), four modes at a time
/// (AVX2; `j` a multiple of 4).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn pass<const L: usize, const S: usize>(mem: &mut [f64], j: usize) -> f64 {
    use std::arch::x86_64::*;
    assert!(mem.len() >= (L + S) * j && j.is_multiple_of(4));
    let p = mem.as_mut_ptr();
    // SAFETY: every access is below (L + S)·j (asserted).
    unsafe {
        let (mut acc, scale) = (_mm256_setzero_pd(), _mm256_set1_pd(1e-9));
        let mut k = 0;
        while k < j {
            // two independent sums, so adds do not chain
            let (mut x, mut y) = (_mm256_setzero_pd(), _mm256_setzero_pd());
            for a in 0..L {
                let v = _mm256_loadu_pd(p.add(a * j + k));
                if a % 2 == 0 {
                    x = _mm256_add_pd(x, v);
                } else {
                    y = _mm256_add_pd(y, v);
                }
            }
            let x = _mm256_add_pd(x, y);
            for b in 0..S {
                _mm256_storeu_pd(p.add((L + b) * j + k), _mm256_mul_pd(x, scale));
            }
            acc = _mm256_add_pd(acc, x);
            k += 4;
        }
        let mut o = [0.0; 4];
        _mm256_storeu_pd(o.as_mut_ptr(), acc);
        o.iter().sum()
    }
}

/// The passes of a layout, one step.
///
/// # Safety
/// The CPU supports AVX2.
#[cfg(target_arch = "x86_64")]
unsafe fn step(layout: usize, mem: &mut [f64], j: usize) -> f64 {
    // SAFETY: the caller's AVX2; each pass's slice holds its arrays.
    unsafe {
        match layout {
            0 => {
                let (a, b) = mem.split_at_mut(14 * j);
                pass::<11, 3>(a, j) + pass::<8, 2>(b, j)
            }
            1 => pass::<14, 3>(mem, j),
            _ => pass::<14, 4>(mem, j),
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
fn main() {
    println!("stream_probe measures AVX2 kernels: x86_64 only");
}

#[cfg(target_arch = "x86_64")]
fn main() {
    if !std::arch::is_x86_feature_detected!("avx2") {
        println!("stream_probe measures AVX2 kernels: this CPU has none");
        return;
    }
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let j = args.first().copied().unwrap_or(800) / 4 * 4;
    let steps = args.get(1).copied().unwrap_or(100_000);
    let layouts = [
        ("two passes, tables", 24),
        ("one pass, tables", 17),
        ("one pass, cruise", 18),
    ];
    println!("J = {j}, {steps} steps; fastest of 5 (µs a step)");
    for (layout, (name, arrays)) in layouts.into_iter().enumerate() {
        let mut mem: Vec<f64> = (0..arrays * j).map(|i| 1e-3 * (i % 97) as f64).collect();
        let mut best = f64::INFINITY;
        for _ in 0..5 {
            let t = Instant::now();
            let mut acc = 0.0;
            for _ in 0..steps {
                // SAFETY: AVX2 checked above.
                acc += unsafe { step(layout, &mut mem, j) };
            }
            black_box(acc);
            best = best.min(t.elapsed().as_secs_f64() / steps as f64 * 1e6);
        }
        let kb = arrays * j * 8 / 1024;
        println!("{name:<20} {arrays:>2} streams ({kb} KB): {best:.3} µs");
    }
}
