//! Time statistics over the scene's window [0, T], whatever the step
//! (MODEL §7).
//!
//! A run of step Δt reaches t_n = ⌊T/Δt⌋·Δt, not T. A statistic taken over
//! the rows it has (a mean of the samples) is then a statistic over
//! [Δt, t_n], a window that moves with Δt: between the levels of a
//! refinement study it moves the exact value by more than the
//! discretization error (a moving load's RMS displacement by 1.4e-6 m
//! where the error is 1e-7). So every time statistic is the integral over
//! [0, T] divided by T: the signal linear between its rows (the trapezoid
//! rule, O(Δt²)) and held at its last row from t_n to T (less than one
//! step, O(Δt²) too). Its definition is the same at every Δt; only its
//! quadrature error falls with Δt.

/// A time-weighted running mean and variance (West's update, Commun. ACM
/// 22 (1979) 532): each sample enters with its weight, the time it stands
/// for; a sample entered twice with weights a and b is the same as once
/// with a + b, so a step adds half its length to each of its two rows.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct TimeAverage {
    weight: f64,
    mean: f64,
    m2: f64,
}

impl TimeAverage {
    /// Add sample `x` standing for `w` seconds (w ≥ 0; 0 adds nothing).
    #[inline]
    pub(crate) fn add(&mut self, x: f64, w: f64) {
        if w <= 0.0 {
            return;
        }
        self.weight += w;
        let d = x - self.mean;
        self.mean += d * (w / self.weight);
        self.m2 += w * d * (x - self.mean);
    }

    /// Add the step from `(t0, x0)` to `(t1, x1)`: the trapezoid's half
    /// length to each end.
    #[inline]
    pub(crate) fn add_step(&mut self, x0: f64, x1: f64, dt: f64) {
        self.add(x0, 0.5 * dt);
        self.add(x1, 0.5 * dt);
    }

    /// The time average; NaN when nothing was entered.
    pub(crate) fn mean(&self) -> f64 {
        if self.weight > 0.0 {
            self.mean
        } else {
            f64::NAN
        }
    }

    /// The time-weighted population standard deviation; NaN when nothing
    /// was entered.
    pub(crate) fn std(&self) -> f64 {
        if self.weight > 0.0 {
            (self.m2.max(0.0) / self.weight).sqrt()
        } else {
            f64::NAN
        }
    }
}

/// The time average of `f` over [t₀, t_end] and its standard deviation,
/// for rows at times `t` (t₀ = `t[0]`): trapezoids between rows, the last
/// step's line carried on to `t_end` (module docs). NaN for no rows. A
/// `t_end` before the last row (a history that runs on past the window)
/// ends the window there: the rows after it are left out, the step across
/// it clipped. Rows beyond the shorter of `t` and `f` are ignored.
pub fn time_mean_std(t: &[f64], f: &[f64], t_end: f64) -> (f64, f64) {
    let a = time_average(t, f, t_end, |x| x);
    (a.mean(), a.std())
}

/// The time RMS of `f` over [t₀, t_end] (as [`time_mean_std`]).
pub fn time_rms(t: &[f64], f: &[f64], t_end: f64) -> f64 {
    time_average(t, f, t_end, |x| x * x).mean().sqrt()
}

fn time_average(t: &[f64], f: &[f64], t_end: f64, g: impl Fn(f64) -> f64) -> TimeAverage {
    let n = t.len().min(f.len());
    let mut a = TimeAverage::default();
    if n == 0 {
        return a;
    }
    if n == 1 {
        a.add(g(f[0]), 1.0);
        return a;
    }
    for i in 1..n {
        let (t0, t1) = (t[i - 1], t[i]);
        let dt = t1 - t0;
        if t1 <= t_end {
            a.add_step(g(f[i - 1]), g(f[i]), dt);
        } else {
            // the step across the window's end: linear to t_end
            let s = if dt > 0.0 {
                ((t_end - t0) / dt).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let at_end = f[i - 1] + s * (f[i] - f[i - 1]);
            a.add_step(g(f[i - 1]), g(at_end), s * dt);
            return a;
        }
    }
    // from the last row to t_end (less than a step): the last step's line
    // carried on, an error O(Δt³) where a held value would make O(Δt²)
    let dt = t[n - 1] - t[n - 2];
    let rest = (t_end - t[n - 1]).max(0.0);
    let at_end = if dt > 0.0 {
        f[n - 1] + rest / dt * (f[n - 1] - f[n - 2])
    } else {
        f[n - 1]
    };
    a.add_step(g(f[n - 1]), g(at_end), rest);
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_signal_averages_exactly_over_the_window() {
        // f = t on [0, 1] from rows every 0.3 s (t_n = 0.9): the trapezoids
        // and the last step's line carried on to 1.0 are exact: 1/2
        let f: Vec<f64> = (0..4).map(|i| 0.3 * i as f64).collect();
        let (m, _) = time_mean_std(&f, &f, 1.0);
        assert!((m - 0.5).abs() < 1e-15, "{m}");
        // rows on the window's end: exactly 1/2
        let f: Vec<f64> = (0..=4).map(|i| 0.25 * i as f64).collect();
        assert!((time_mean_std(&f, &f, 1.0).0 - 0.5).abs() < 1e-15);
        // a history past the window: clipped at it
        let f: Vec<f64> = (0..=8).map(|i| 0.25 * i as f64).collect();
        assert!((time_mean_std(&f, &f, 1.0).0 - 0.5).abs() < 1e-15);
    }

    /// The window's quadrature error falls as Δt² whatever Δt does to t_n
    /// (the samples' mean over the rows it has does not: its window moves).
    #[test]
    fn the_time_rms_converges_at_second_order_for_any_step() {
        let exact = {
            // RMS of sin(2πt) + 0.5 over [0, 1.05]
            let t = 1.05f64;
            let w = 2.0 * std::f64::consts::PI;
            // ∫ sin² + sin + 1/4 = 3t/4 − sin(2wt)/(4w) + (1 − cos wt)/w
            let int = 0.75 * t - (2.0 * w * t).sin() / (4.0 * w) + (1.0 - (w * t).cos()) / w;
            (int / t).sqrt()
        };
        let err = |dt: f64| {
            let n = (1.05 / dt).floor() as usize;
            let t: Vec<f64> = (0..=n).map(|i| i as f64 * dt).collect();
            let f: Vec<f64> = t
                .iter()
                .map(|t| (2.0 * std::f64::consts::PI * t).sin() + 0.5)
                .collect();
            (time_rms(&t, &f, 1.05) - exact).abs()
        };
        // steps that do not divide the window
        let (e1, e2, e3) = (err(0.04), err(0.02), err(0.01));
        for (a, b) in [(e1, e2), (e2, e3)] {
            let p = (a / b).log2();
            assert!(p > 1.6, "order {p}: {e1:e} {e2:e} {e3:e}");
        }
    }

    #[test]
    fn weights_split_and_join_alike() {
        let mut a = TimeAverage::default();
        a.add(1.0, 0.5);
        a.add(1.0, 0.5);
        a.add(3.0, 1.0);
        let mut b = TimeAverage::default();
        b.add(1.0, 1.0);
        b.add(3.0, 1.0);
        assert!((a.mean() - b.mean()).abs() < 1e-15 && (a.std() - b.std()).abs() < 1e-15);
        assert_eq!(b.mean(), 2.0);
        assert_eq!(b.std(), 1.0);
        assert!(TimeAverage::default().mean().is_nan());
    }
}
