//! The filtered contact force (0–20 Hz by default): a zero-phase low-pass
//! filter (the statistics of a filtered force: `record::filter`).
//!
//! Railway practice evaluates pantograph–catenary contact forces low-pass
//! filtered to 0–20 Hz (EN 50317 measurement, EN 50318 validation of
//! simulations, EN 50367 limits on mean and standard deviation). The filter is
//! what makes a force with re-contact spikes comparable across time steps: a
//! spike of height ~1/Δt and width ~Δt (MODEL §6 has no impact law, so its
//! height belongs to Δt, docs/convergence.md §4) enters the filtered force
//! through its impulse, which a consistent integrator converges.
//!
//! The filter: a 2nd-order Butterworth low-pass run forward, then backward
//! over the result (zero phase, so a filtered peak stays where the spike
//! was). Each pass integrates the analog filter
//! `y'' + √2 ω y' + ω² y = ω² u` with the trapezoidal rule, which *is* the
//! bilinear transform; the analog ω is pre-warped so the digital response
//! matches the analog one at the design cut-off. The state form is used
//! instead of the textbook difference equation because at ω Δt ~ 1e-4 the
//! difference equation's coefficients are 1 − O((ωΔt)²) and lose about
//! 1/(ωΔt)² of the precision; the state form loses none.
//!
//! Why this and not a 25 ms moving average (1/(2·20 Hz)): the moving average's
//! first side lobe passes −13 dB at 30 Hz and more above, so a spike leaks into
//! it at a level set by its shape; the Butterworth pair falls at 24 dB/octave
//! per pass. Both are consistent in Δt; the Butterworth is the closer match to
//! the standards' analog filters.
//!
//! The band is `[analysis] band` (default [`FORCE_BAND_HZ`]). Each pass starts from the steady state of its first sample (y = u, y' = 0),
//! the same for every run, so the ends are treated alike at every resolution.

/// The band of the evaluated contact force, Hz: 0–20 Hz (EN 50317/50318).
pub const FORCE_BAND_HZ: f64 = 20.0;

/// Forward–backward filtering squares the magnitude response, so a 2nd-order
/// Butterworth designed at f_d gives |H|² = 1/(1 + (f/f_d)⁴), which is −3 dB
/// at f = f_d·(√2 − 1)^{1/4}. The design cut-off is the band edge divided by
/// that factor, so the *combined* filter is −3 dB at [`FORCE_BAND_HZ`].
pub fn design_cutoff_hz(band_hz: f64) -> f64 {
    band_hz / (std::f64::consts::SQRT_2 - 1.0).powf(0.25)
}

/// The largest band a run of step `dt` (s) can be filtered to, Hz: the
/// design cut-off ([`design_cutoff_hz`]) below `MAX_NYQUIST_FRACTION` of
/// the Nyquist frequency.
pub fn max_band_hz(dt: f64) -> f64 {
    MAX_NYQUIST_FRACTION * 0.5 / dt / design_cutoff_hz(1.0)
}

/// Above this fraction of the Nyquist frequency the pre-warp tan(ωΔt/2)
/// runs away: the samples are too coarse to be filtered at this band, and
/// the signal is returned unchanged (a run with Δt ≳ 10 ms, far coarser than
/// any contact scene needs).
const MAX_NYQUIST_FRACTION: f64 = 0.9;

/// `x` sampled every `dt` seconds, low-pass filtered to `band_hz` with zero
/// phase (forward–backward 2nd-order Butterworth; −3 dB at `band_hz`).
pub fn lowpass_zero_phase(x: &[f64], dt: f64, band_hz: f64) -> Vec<f64> {
    let fd = design_cutoff_hz(band_hz);
    let nyquist = 0.5 / dt;
    if x.len() < 2 || fd >= MAX_NYQUIST_FRACTION * nyquist {
        return x.to_vec();
    }
    let pass = Pass::new(dt, fd);
    let mut y = pass.run(x.iter().copied());
    pass.run_backward_in_place(&mut y);
    y
}

/// The statistical max and min of a force are its mean ± this many σ
/// (EN 50367: F_m ± 3σ; EN 50318 reports them).
pub const STATISTICAL_SIGMAS: f64 = 3.0;

/// Mean and population standard deviation of `f` (two passes: the sum,
/// then the squared deviations); NaN for no values.
pub fn mean_std(f: &[f64]) -> (f64, f64) {
    let m = f.len().max(1) as f64;
    let mean = f.iter().sum::<f64>() / m;
    let std = (f.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / m).sqrt();
    if f.is_empty() {
        (f64::NAN, f64::NAN)
    } else {
        (mean, std)
    }
}

/// One pass: the trapezoidal update s₁ = P s₀ + Q (u₀ + u₁) of the state
/// s = (y, y'), with P = (I − Δt/2 A)⁻¹(I + Δt/2 A), Q = (I − Δt/2 A)⁻¹ Δt/2 B.
struct Pass {
    p: [[f64; 2]; 2],
    q: [f64; 2],
}

impl Pass {
    fn new(dt: f64, fd: f64) -> Self {
        // pre-warped analog cut-off: the bilinear map sends it to fd exactly
        let w = 2.0 / dt * (std::f64::consts::PI * fd * dt).tan();
        let zeta = std::f64::consts::FRAC_1_SQRT_2;
        // A = [[0, 1], [−ω², −2ζω]], B = [0, ω²]
        let a = [[0.0, 1.0], [-w * w, -2.0 * zeta * w]];
        let hh = 0.5 * dt;
        let m = [
            [1.0 - hh * a[0][0], -hh * a[0][1]],
            [-hh * a[1][0], 1.0 - hh * a[1][1]],
        ];
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        let inv = [
            [m[1][1] / det, -m[0][1] / det],
            [-m[1][0] / det, m[0][0] / det],
        ];
        let n = [
            [1.0 + hh * a[0][0], hh * a[0][1]],
            [hh * a[1][0], 1.0 + hh * a[1][1]],
        ];
        let mut p = [[0.0; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                p[i][j] = inv[i][0] * n[0][j] + inv[i][1] * n[1][j];
            }
        }
        let b1 = hh * w * w;
        Pass {
            p,
            q: [inv[0][1] * b1, inv[1][1] * b1],
        }
    }

    fn run(&self, mut u: impl Iterator<Item = f64>) -> Vec<f64> {
        let Some(u0) = u.next() else {
            return Vec::new();
        };
        let (mut y, mut v, mut prev) = (u0, 0.0, u0);
        let mut out = vec![u0];
        for ui in u {
            let s = prev + ui;
            let y1 = self.p[0][0] * y + self.p[0][1] * v + self.q[0] * s;
            let v1 = self.p[1][0] * y + self.p[1][1] * v + self.q[1] * s;
            y = y1;
            v = v1;
            prev = ui;
            out.push(y);
        }
        out
    }

    /// The same pass over `y` reversed, written back in place: the value
    /// at index i is the pass's output for the input y[i] (the arithmetic
    /// of `run` on the reversed sequence, reversed back, without a second
    /// buffer: a run's summary filters its whole force history, so one
    /// copy of it, not two, is the filter's memory).
    fn run_backward_in_place(&self, y: &mut [f64]) {
        let Some(&u0) = y.last() else {
            return;
        };
        let (mut f, mut v, mut prev) = (u0, 0.0, u0);
        for yi in y.iter_mut().rev().skip(1) {
            let ui = *yi;
            let s = prev + ui;
            let f1 = self.p[0][0] * f + self.p[0][1] * v + self.q[0] * s;
            let v1 = self.p[1][0] * f + self.p[1][1] * v + self.q[1] * s;
            f = f1;
            v = v1;
            prev = ui;
            *yi = f;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Amplitude of the steady filtered response to a sine of `f` Hz,
    /// measured over the middle of a long record (away from the ends).
    fn gain(f: f64, dt: f64) -> f64 {
        let n = (4.0 / dt) as usize;
        let x: Vec<f64> = (0..n)
            .map(|i| (2.0 * PI * f * i as f64 * dt).sin())
            .collect();
        let y = lowpass_zero_phase(&x, dt, FORCE_BAND_HZ);
        let mid = &y[n / 4..3 * n / 4];
        let xm = &x[n / 4..3 * n / 4];
        (mid.iter().map(|v| v * v).sum::<f64>() / xm.iter().map(|v| v * v).sum::<f64>()).sqrt()
    }

    #[test]
    fn constant_passes_unchanged() {
        let x = vec![46.0; 1000];
        let y = lowpass_zero_phase(&x, 1e-4, FORCE_BAND_HZ);
        assert!(y.iter().all(|v| (v - 46.0).abs() < 1e-9));
    }

    #[test]
    fn minus_three_db_at_the_band_edge() {
        // the combined forward–backward response is 1/√2 at 20 Hz, flat well
        // below it and 24 dB/octave·2 down above it
        let g = gain(FORCE_BAND_HZ, 1e-4);
        assert!((g - std::f64::consts::FRAC_1_SQRT_2).abs() < 2e-3, "{g}");
        assert!((gain(2.0, 1e-4) - 1.0).abs() < 1e-3);
        assert!(gain(200.0, 1e-4) < 1e-3);
    }

    #[test]
    fn the_in_place_backward_pass_is_the_reversed_pass_bit_for_bit() {
        let dt = 1e-4;
        let x: Vec<f64> = (0..5000)
            .map(|i| (i as f64 * 0.37).sin() * 40.0 + 50.0 + (i % 7) as f64)
            .collect();
        let pass = Pass::new(dt, design_cutoff_hz(FORCE_BAND_HZ));
        let mut y = pass.run(x.iter().copied());
        let mut two = y.clone();
        two.reverse();
        let mut z = pass.run(two.into_iter());
        z.reverse();
        pass.run_backward_in_place(&mut y);
        assert_eq!(y, z);
    }

    #[test]
    fn zero_phase_keeps_a_peak_in_place() {
        let dt = 1e-4;
        let n = 10_000;
        let mut x = vec![0.0; n];
        x[5000] = 1.0 / dt; // unit impulse
        let y = lowpass_zero_phase(&x, dt, FORCE_BAND_HZ);
        let imax = (0..n).max_by(|&a, &b| y[a].total_cmp(&y[b])).unwrap();
        assert_eq!(imax, 5000);
        // the area (impulse) is kept: DC gain 1
        let area: f64 = y.iter().sum::<f64>() * dt;
        assert!((area - 1.0).abs() < 1e-6, "{area}");
    }

    #[test]
    fn an_impulse_is_seen_by_its_area_not_its_height() {
        // the same impulse as one tall sample at Δt or two half-height
        // samples at Δt/2: filtered responses agree to O(Δt²)
        let t_end = 0.5;
        let resp = |dt: f64, width: usize| {
            let n = (t_end / dt).round() as usize + 1;
            let mut x = vec![0.0; n];
            let k = (0.25 / dt).round() as usize;
            for j in 0..width {
                x[k + j] = 1.0 / (width as f64 * dt);
            }
            let y = lowpass_zero_phase(&x, dt, FORCE_BAND_HZ);
            (0..=50).map(|i| y[i * (n - 1) / 50]).collect::<Vec<_>>()
        };
        let a = resp(1e-4, 1);
        let b = resp(5e-5, 2);
        let peak = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(diff < 0.02 * peak, "{diff} vs peak {peak}");
    }
}
