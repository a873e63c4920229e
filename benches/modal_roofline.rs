//! `modal_exact` against a minimal reference kernel, in ns per mode-step
//! (CPU time of the process's thread, not wall: the machine may be shared).
//!
//! The reference kernel does the per-step work of `modal_exact` with one
//! contact and nothing else: in one pass over the modes, the last step's
//! contact force held along the carrier's path (a0, a1, b0, b1), the exact
//! 2×2 step of each mode (cos, sin/ω, −ω sin), and the two sums of the
//! contact pair; then the mass's exact step and the Lagrange law
//! (`g_free + W λ = 0`, λ ≥ 0) with the force held over the step.
//! Coefficients and state are interleaved in blocks of eight modes
//! (`[cos, sin/ω, −ω sin, a0, a1, b0, b1]` and `[η, η̇]`: 88 bytes a
//! mode-step), a block in one AVX-512 register (x86-64 with AVX-512F
//! only). Its shapes:
//!
//! * pinned–pinned: `φ_j(x) = A sin(jπx/L)` by a rotation recurrence in
//!   registers, nothing streamed for them;
//! * clamped–pinned ("table"): each mode's shape a phasor kept in the
//!   interleaved state and rotated by its own fixed rotation each step
//!   (what taut's cruise does), 40 more bytes read and 24 written a mode.
//!
//! taut is timed on whole runs ([`taut::run`], and [`taut::run_batch`] of
//! eight speeds stepped together), recording included; the reference on
//! the same number of steps and modes. The row `steps` is a run alone less
//! the build of its basis, step maps and shape tables (a batch builds them
//! once). The scenes: the reference scene on
//! a `galerkin` basis, J = 800, at constant speed, without gravity (no
//! held distributed load, which the reference does not carry), clamped–
//! pinned as shipped and pinned–pinned. On pinned–pinned the reference
//! uses taut's own step coefficients, so its fraction of steps without
//! contact is printed beside taut's as a check that it does the same work.
//!
//! Run with `cargo bench --bench modal_roofline`; `-- clamped` (or
//! `pinned–pinned`, `alone`, `batch`) runs only the cases whose basis or
//! row contains each word given (a profile of one case).

use std::time::Duration;

use taut::integrate::{Integrator, ModeSteps};

const SCENE: &str = include_str!("../scenes/reference.toml");

/// Modes of the basis.
const MODES: usize = 800;

/// Timed repetitions of each case (the median is quoted).
const REPEATS: usize = 15;

/// Speeds of the batched case, m/s (eight runs stepped together).
const SWEEP: [f64; 8] = [60.0, 65.0, 70.0, 75.0, 80.0, 85.0, 90.0, 95.0];

/// Lanes of a block of modes.
const B: usize = 8;

/// CPU time of the calling thread.
fn cpu_now() -> Duration {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid clock id and a pointer to a timespec we own.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

fn scene(pinned: bool, speed: f64) -> taut::Resolved {
    let mut o: Vec<String> = [
        "mesh.kind=galerkin".to_string(),
        format!("mesh.modes={MODES}"),
        "integrator={ method = \"modal_exact\" }".to_string(),
        format!("carrier.0.speed={{ profile = \"constant\", value = {speed} }}"),
        "gravity.g=0".to_string(),
    ]
    .to_vec();
    if pinned {
        o.push("beam.left=\"pinned\"".to_string());
    }
    taut::resolve_scene(SCENE, &o).expect("reference scene resolves")
}

/// Coefficients of eight modes, interleaved.
#[derive(Clone, Copy, Default)]
#[repr(C, align(64))]
struct Coefs {
    c: [f64; B],
    so: [f64; B],
    mos: [f64; B],
    a0: [f64; B],
    a1: [f64; B],
    b0: [f64; B],
    b1: [f64; B],
}

/// State of eight modes, interleaved.
#[derive(Clone, Copy, Default)]
#[repr(C, align(64))]
struct Modes {
    d: [f64; B],
    v: [f64; B],
}

/// Eight modes' shapes as phasors (the "table" kernel): φ(x_{n−1}),
/// φ(x_n) = Re F, Im F and the fixed rotation.
#[derive(Clone, Copy, Default)]
#[repr(C, align(64))]
struct Phasors {
    prev: [f64; B],
    re: [f64; B],
    im: [f64; B],
    rr: [f64; B],
    ri: [f64; B],
}

/// One reference run: its modes, its mass and contact.
struct RefRun {
    modes: Vec<Modes>,
    phasors: Vec<Phasors>,
    q: f64,
    qd: f64,
    /// The force held over the last step, not yet added (N on the beam).
    pending: f64,
    speed: f64,
    lost: usize,
    steps: usize,
}

/// What every reference run shares: coefficients, the mass's step, the
/// geometry.
struct RefShared {
    coefs: Vec<Coefs>,
    amp: f64,
    length: f64,
    dt: f64,
    /// The mass's exact step: E (2×2) and its response G to a held force.
    e: [[f64; 2]; 2],
    g: [f64; 2],
    f0: f64,
    s: f64,
}

impl RefShared {
    fn new(sc: &taut::Resolved) -> Self {
        let it = Integrator::new(sc).expect("integrator builds");
        let beam = it.beam();
        let omega: Vec<f64> = (0..beam.n)
            .map(|j| (beam.stiffness.get(j, j) / beam.mass.get(j, j)).sqrt())
            .collect();
        let m = ModeSteps::new(&omega, sc.dt);
        let blocks = beam.n / B;
        assert_eq!(blocks * B, beam.n, "J a multiple of 8");
        let coefs = (0..blocks)
            .map(|b| {
                let mut c = Coefs::default();
                for l in 0..B {
                    let i = b * B + l;
                    c.c[l] = m.cos[i];
                    c.so[l] = m.sin_over_omega[i];
                    c.mos[l] = m.minus_omega_sin[i];
                    c.a0[l] = m.a0[i];
                    c.a1[l] = m.a1[i];
                    c.b0[l] = m.b0[i];
                    c.b1[l] = m.b1[i];
                }
                c
            })
            .collect();
        let b = &sc.beam;
        let rho_a = b.rho_a;
        let car = &sc.scene.carriers[0];
        let (mass, k) = (car.mass.expect("a mass"), car.stiffness.expect("a spring"));
        let w = (k / mass).sqrt();
        let (cs, sn) = ((w * sc.dt).cos(), (w * sc.dt).sin());
        RefShared {
            coefs,
            amp: (2.0 / (rho_a * b.length)).sqrt(),
            length: b.length,
            dt: sc.dt,
            e: [[cs, sn / w], [-w * sn, cs]],
            g: [(1.0 - cs) / k, sn / (mass * w)],
            f0: k * car.preload.unwrap_or(0.0),
            s: -1.0,
        }
    }

    fn run(&self, speed: f64) -> RefRun {
        let n = self.coefs.len();
        let mut phasors = vec![Phasors::default(); n];
        let k = std::f64::consts::PI / self.length;
        for (b, p) in phasors.iter_mut().enumerate() {
            for l in 0..B {
                let j = (b * B + l + 1) as f64;
                let r = j * k * speed * self.dt;
                p.rr[l] = r.cos();
                p.ri[l] = r.sin();
                p.im[l] = -self.amp;
            }
        }
        RefRun {
            modes: vec![Modes::default(); n],
            phasors,
            q: 0.0,
            qd: 0.0,
            pending: 0.0,
            speed,
            lost: 0,
            steps: 0,
        }
    }

    /// Lanes 1..=8 of `A sin(jθ)`, `A cos(jθ)` and the rotation by 8θ.
    fn start(&self, x: f64) -> ([f64; B], [f64; B], (f64, f64)) {
        let th = std::f64::consts::PI * x / self.length;
        let (s1, c1) = th.sin_cos();
        let (mut s, mut c) = ([0.0; B], [0.0; B]);
        let (mut sj, mut cj) = (s1, c1);
        for l in 0..B {
            s[l] = self.amp * sj;
            c[l] = self.amp * cj;
            (sj, cj) = (sj * c1 + cj * s1, cj * c1 - sj * s1);
        }
        let (s8, c8) = (8.0 * th).sin_cos();
        (s, c, (c8, s8))
    }
}

/// One step of one reference run, pinned–pinned (`TABLE` false: the
/// recurrence) or from its phasors (`TABLE` true); a block of eight modes
/// in one AVX-512 register.
///
/// # Safety
/// The CPU supports AVX-512F.
#[target_feature(enable = "avx512f")]
unsafe fn ref_step<const TABLE: bool>(sh: &RefShared, r: &mut RefRun) {
    use std::arch::x86_64::*;
    let n = r.steps as f64;
    let x = |k: f64| (r.speed * sh.dt * k).clamp(0.0, sh.length);
    // SAFETY (whole body): loads and stores of whole 64-byte-aligned
    // blocks of arrays of eight.
    unsafe {
        let ld = |a: &[f64; B]| _mm512_load_pd(a.as_ptr());
        let v8 = |a: [f64; B]| _mm512_loadu_pd(a.as_ptr());
        let (sp, cp, (c8, s8)) = sh.start(x(n - 1.0));
        let (sn, cn, (c8n, s8n)) = sh.start(x(n));
        let (s1, c1, (c81, s81)) = sh.start(x(n + 1.0));
        let (mut sp, mut cp, mut sn, mut cn, mut s1, mut c1) =
            (v8(sp), v8(cp), v8(sn), v8(cn), v8(s1), v8(c1));
        let rot = |c: f64, s: f64| (_mm512_set1_pd(c), _mm512_set1_pd(s));
        let ((c8, s8), (c8n, s8n), (c81, s81)) = (rot(c8, s8), rot(c8n, s8n), rot(c81, s81));
        let f = _mm512_set1_pd(r.pending);
        let (mut gs, mut ws) = (_mm512_setzero_pd(), _mm512_setzero_pd());
        let blocks = sh.coefs.len();
        let (co, st, ph) = (
            sh.coefs.as_ptr(),
            r.modes.as_mut_ptr(),
            r.phasors.as_mut_ptr(),
        );
        for b in 0..blocks {
            let (co, st) = (&*co.add(b), &mut *st.add(b));
            let (p0, p, q);
            if TABLE {
                let ph = &mut *ph.add(b);
                let (re, im, rr, ri) = (ld(&ph.re), ld(&ph.im), ld(&ph.rr), ld(&ph.ri));
                p0 = ld(&ph.prev);
                p = re;
                q = _mm512_fmsub_pd(re, rr, _mm512_mul_pd(im, ri));
                let im1 = _mm512_fmadd_pd(re, ri, _mm512_mul_pd(im, rr));
                _mm512_store_pd(ph.prev.as_mut_ptr(), re);
                _mm512_store_pd(ph.re.as_mut_ptr(), q);
                _mm512_store_pd(ph.im.as_mut_ptr(), im1);
            } else {
                (p0, p, q) = (sp, sn, s1);
                let turn = |s: __m512d, c: __m512d, c8: __m512d, s8: __m512d| {
                    (
                        _mm512_fmadd_pd(s, c8, _mm512_mul_pd(c, s8)),
                        _mm512_fmsub_pd(c, c8, _mm512_mul_pd(s, s8)),
                    )
                };
                (sp, cp) = turn(sp, cp, c8, s8);
                (sn, cn) = turn(sn, cn, c8n, s8n);
                (s1, c1) = turn(s1, c1, c81, s81);
            }
            let (a0, a1) = (ld(&co.a0), ld(&co.a1));
            let z = _mm512_fmadd_pd(a0, p0, _mm512_mul_pd(a1, p));
            let zv = _mm512_fmadd_pd(ld(&co.b0), p0, _mm512_mul_pd(ld(&co.b1), p));
            let e = _mm512_fmadd_pd(f, z, ld(&st.d));
            let ev = _mm512_fmadd_pd(f, zv, ld(&st.v));
            let c = ld(&co.c);
            let e1 = _mm512_fmadd_pd(c, e, _mm512_mul_pd(ld(&co.so), ev));
            let v1 = _mm512_fmadd_pd(ld(&co.mos), e, _mm512_mul_pd(c, ev));
            _mm512_store_pd(st.d.as_mut_ptr(), e1);
            _mm512_store_pd(st.v.as_mut_ptr(), v1);
            gs = _mm512_fmadd_pd(q, e1, gs);
            let zw = _mm512_fmadd_pd(a0, p, _mm512_mul_pd(a1, q));
            ws = _mm512_fmadd_pd(q, zw, ws);
        }
        let (dg, dw) = (_mm512_reduce_add_pd(gs), _mm512_reduce_add_pd(ws));
        let (q0, qd0) = (r.q, r.qd);
        let q = sh.e[0][0] * q0 + sh.e[0][1] * qd0 + sh.g[0] * sh.f0;
        let qd = sh.e[1][0] * q0 + sh.e[1][1] * qd0 + sh.g[1] * sh.f0;
        let gfree = sh.s * dg - q;
        let w = sh.s * sh.s * dw + sh.g[0];
        let lambda = (-gfree / w).max(0.0);
        r.q = q - sh.g[0] * lambda;
        r.qd = qd - sh.g[1] * lambda;
        r.pending = sh.s * lambda;
        r.lost += usize::from(lambda == 0.0);
        r.steps += 1;
    }
}

fn ref_steps(sh: &RefShared, runs: &mut [RefRun], steps: usize, table: bool) {
    assert!(
        is_x86_feature_detected!("avx512f"),
        "the reference kernel needs AVX-512F"
    );
    for _ in 0..steps {
        for r in runs.iter_mut() {
            // SAFETY: AVX-512F checked above.
            unsafe {
                if table {
                    ref_step::<true>(sh, r)
                } else {
                    ref_step::<false>(sh, r)
                }
            }
        }
    }
}

/// Median and minimum of `REPEATS` CPU timings of `f`, ns per mode-step.
fn timed(mode_steps: usize, mut f: impl FnMut()) -> (f64, f64) {
    f();
    let mut t: Vec<f64> = (0..REPEATS)
        .map(|_| {
            let a = cpu_now();
            f();
            (cpu_now() - a).as_secs_f64() * 1e9 / mode_steps as f64
        })
        .collect();
    t.sort_by(f64::total_cmp);
    (t[REPEATS / 2], t[0])
}

fn main() {
    if std::env::args().any(|a| a == "--list") {
        return;
    }
    // words a case's basis or row must contain (cargo's flags aside)
    let words: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let wanted = |name: &str, row: &str| {
        words
            .iter()
            .all(|w| name.contains(w.as_str()) || row.contains(w.as_str()))
    };
    println!(
        "modal_exact vs the reference kernel, J = {MODES}, CPU ns per mode-step (median, min of {REPEATS})"
    );
    println!(
        "{:<15} {:<8} {:>16} {:>16} {:>8}",
        "basis", "runs", "taut", "reference", "ratio"
    );
    for pinned in [true, false] {
        let name = if pinned {
            "pinned–pinned"
        } else {
            "clamped–pinned"
        };
        let sc = scene(pinned, 80.0);
        let sh = RefShared::new(&sc);
        let steps = sc.steps;
        if wanted(name, "alone steps") {
            // taut alone, and a check of the reference's work on pinned–pinned
            let out = taut::run(&sc, &mut |_, _| {}).expect("run");
            let mut one = [sh.run(80.0)];
            ref_steps(&sh, &mut one, steps, !pinned);
            if pinned {
                println!(
                    "  check: steps without contact, taut {:.5}, reference {:.5}",
                    out.stats[0].loss_fraction_steps,
                    one[0].lost as f64 / steps as f64
                );
            }
            let (ta, ta_min) = timed(steps * MODES, || {
                std::hint::black_box(taut::run(&sc, &mut |_, _| {}).expect("run").steps);
            });
            let (ra, ra_min) = timed(steps * MODES, || {
                let mut one = [sh.run(80.0)];
                ref_steps(&sh, &mut one, steps, !pinned);
                std::hint::black_box(one[0].q);
            });
            println!(
                "{name:<15} {:<8} {:>7.3} ({:.3}) {:>7.3} ({:.3}) {:>8.2}",
                "alone",
                ta,
                ta_min,
                ra,
                ra_min,
                ta / ra
            );
            // the run's basis, step maps and shape tables, built once a run
            // alone (once for a batch): its share of a run alone
            let (build, _) = timed(steps * MODES, || {
                std::hint::black_box(Integrator::new(&sc).expect("integrator builds").dofs());
            });
            println!(
                "{name:<15} {:<8} {:>7.3}         {:>16} {:>8.2}",
                "  steps",
                ta - build,
                "",
                (ta - build) / ra
            );
        }
        if !wanted(name, "batch 8") {
            continue;
        }
        let sweep: Vec<taut::Resolved> = SWEEP.iter().map(|&v| scene(pinned, v)).collect();
        let total: usize = sweep.iter().map(|s| s.steps).sum::<usize>() * MODES;
        let (tb, tb_min) = timed(total, || {
            std::hint::black_box(taut::run_batch(&sweep, SWEEP.len(), &mut |_| {}).len());
        });
        let (rb, rb_min) = timed(total, || {
            // lockstep to the longest run (the slowest, first), each run
            // only its own steps
            let mut runs: Vec<RefRun> = SWEEP.iter().map(|&v| sh.run(v)).collect();
            let most = sweep.iter().map(|s| s.steps).max().unwrap_or(0);
            for n in 0..most {
                let live: usize = sweep.iter().filter(|s| s.steps > n).count();
                ref_steps(&sh, &mut runs[..live], 1, !pinned);
            }
            std::hint::black_box(runs[0].q);
        });
        println!(
            "{name:<15} {:<8} {:>7.3} ({:.3}) {:>7.3} ({:.3}) {:>8.2}",
            "batch 8",
            tb,
            tb_min,
            rb,
            rb_min,
            tb / rb
        );
    }
}
