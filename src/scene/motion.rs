//! Carrier kinematics x_m(t), V(t) (MODEL §3).

use super::speed::SpeedProfile;
use std::f64::consts::PI;

/// How a carrier moves along the beam.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// x_m(0), m.
    pub start: f64,
    /// The speed profile.
    pub profile: SpeedProfile,
    /// Ramp time t0 = 2L/(5 V0), s (smooth ramp only; 0 otherwise).
    pub ramp_time: f64,
    /// A table's distance travelled at each knot, X_k = ∫₀^{t_k} V dt, m
    /// (empty for the other profiles).
    knots_travelled: Vec<f64>,
}

/// A tabulated profile's segment holding t: the knot k with t_k ≤ t (the
/// last segment for t beyond the last knot, the first before 0).
fn segment(time: &[f64], t: f64) -> usize {
    time.partition_point(|&tk| tk <= t)
        .saturating_sub(1)
        .min(time.len().saturating_sub(2))
}

/// V on the segment from knot k at τ = t − t_k: V_k + a τ, with
/// a = (V_{k+1} − V_k)/(t_{k+1} − t_k) (0 for a one-knot table or beyond the
/// last knot, where the last speed is held).
fn table_slope(time: &[f64], speed: &[f64], k: usize, t: f64) -> f64 {
    if k + 1 >= time.len() || t > time[time.len() - 1] {
        0.0
    } else {
        (speed[k + 1] - speed[k]) / (time[k + 1] - time[k])
    }
}

impl Motion {
    /// A motion starting at `start` (m) on a beam of length `length` (m).
    pub fn new(start: f64, profile: SpeedProfile, length: f64) -> Self {
        let ramp_time = match profile {
            SpeedProfile::SmoothRamp { cruise } => 2.0 * length / (5.0 * cruise),
            SpeedProfile::Constant { .. } | SpeedProfile::Table { .. } => 0.0,
        };
        let knots_travelled = match &profile {
            // X_{k+1} = X_k + (V_k + V_{k+1})/2 (t_{k+1} − t_k): exact for linear V
            SpeedProfile::Table { time, speed } => {
                let mut x = Vec::with_capacity(time.len());
                let mut acc = 0.0;
                for k in 0..time.len() {
                    if k > 0 {
                        acc += 0.5 * (speed[k - 1] + speed[k]) * (time[k] - time[k - 1]);
                    }
                    x.push(acc);
                }
                x
            }
            _ => Vec::new(),
        };
        Motion {
            start,
            profile,
            ramp_time,
            knots_travelled,
        }
    }

    /// A table's (X_k, V_k, a, τ) at t: the segment's start, its speed
    /// there, its acceleration and the time since its start.
    fn table_at(&self, time: &[f64], speed: &[f64], t: f64) -> (f64, f64, f64, f64) {
        let k = segment(time, t);
        let a = table_slope(time, speed, k, t);
        let (xk, vk, tau) = if t > time[time.len() - 1] {
            let last = time.len() - 1;
            (self.knots_travelled[last], speed[last], t - time[last])
        } else {
            (self.knots_travelled[k], speed[k], t - time[k])
        };
        (xk, vk, a, tau)
    }

    /// Distance travelled since t = 0, m.
    pub fn travelled(&self, t: f64) -> f64 {
        match self.profile {
            SpeedProfile::Constant { value } => value * t,
            SpeedProfile::SmoothRamp { cruise } => {
                let t0 = self.ramp_time;
                if t <= t0 {
                    // ∫ V0 (τ/t0 − sin(2πτ/t0)/(2π)) dτ
                    cruise
                        * (t * t / (2.0 * t0)
                            + t0 / (4.0 * PI * PI) * ((2.0 * PI * t / t0).cos() - 1.0))
                } else {
                    cruise * (0.5 * t0 + (t - t0))
                }
            }
            SpeedProfile::Table {
                ref time,
                ref speed,
            } => {
                // X_k + V_k τ + a τ²/2 (the exact integral of the linear V)
                let (xk, vk, a, tau) = self.table_at(time, speed, t);
                xk + vk * tau + 0.5 * a * tau * tau
            }
        }
    }

    /// Position x_m(t), m.
    pub fn position(&self, t: f64) -> f64 {
        self.start + self.travelled(t)
    }

    /// Speed V(t), m/s.
    pub fn speed(&self, t: f64) -> f64 {
        match self.profile {
            SpeedProfile::Constant { value } => value,
            SpeedProfile::SmoothRamp { cruise } => {
                let t0 = self.ramp_time;
                if t <= t0 {
                    cruise * (t / t0 - (2.0 * PI * t / t0).sin() / (2.0 * PI))
                } else {
                    cruise
                }
            }
            SpeedProfile::Table {
                ref time,
                ref speed,
            } => {
                let (_, vk, a, tau) = self.table_at(time, speed, t);
                vk + a * tau
            }
        }
    }

    /// Acceleration V̇(t), m/s² (MODEL §3: V0/t0 (1 − cos 2πt/t0) on the
    /// ramp, 0 at constant speed); a manufactured solution's mass motion
    /// needs it (MODEL §11).
    pub fn acceleration(&self, t: f64) -> f64 {
        match self.profile {
            SpeedProfile::Constant { .. } => 0.0,
            SpeedProfile::SmoothRamp { cruise } => {
                let t0 = self.ramp_time;
                if t <= t0 {
                    cruise / t0 * (1.0 - (2.0 * PI * t / t0).cos())
                } else {
                    0.0
                }
            }
            SpeedProfile::Table {
                ref time,
                ref speed,
            } => table_slope(time, speed, segment(time, t), t),
        }
    }

    /// The speed V, m/s, when the carrier moves at that one speed over the
    /// whole of `[t0, t1]` (s), so that `x_m(t1) − x_m(t0) = V (t1 − t0)`
    /// exactly in real arithmetic; `None` while it accelerates (a smooth
    /// ramp up to its end, a table's sloped segments) or when the interval
    /// crosses a knot. A `modal_exact` step advances the mode shapes at
    /// the carrier by a fixed rotation on such steps
    /// (`integrate/modal_exact.rs`, "Cruise").
    pub fn uniform_speed(&self, t0: f64, t1: f64) -> Option<f64> {
        match self.profile {
            SpeedProfile::Constant { value } => Some(value),
            SpeedProfile::SmoothRamp { cruise } => (t0 > self.ramp_time).then_some(cruise),
            SpeedProfile::Table {
                ref time,
                ref speed,
            } => {
                let last = time.len() - 1;
                if t0 > time[last] {
                    return Some(speed[last]);
                }
                let k = segment(time, t0);
                let flat = k < last && speed[k] == speed[k + 1];
                let inside = t0 >= time[k] && t1 <= time[k + 1];
                (flat && inside).then_some(speed[k])
            }
        }
    }

    /// True when the carrier never moves.
    pub fn is_stationary(&self) -> bool {
        self.profile.cruise_speed() == 0.0
    }

    /// Time at which x_m reaches the end x = `length`, s; `None` if it never moves.
    pub fn time_to_leave(&self, length: f64) -> Option<f64> {
        if self.is_stationary() {
            return None;
        }
        let dist = length - self.start;
        if dist <= 0.0 {
            return Some(0.0);
        }
        match self.profile {
            SpeedProfile::Table { ref time, .. } => {
                // x_m is non-decreasing (V ≥ 0): bisect in the segment that
                // reaches dist, or beyond the last knot at its held speed
                let last = time.len() - 1;
                let (mut lo, mut hi) = match self.knots_travelled.iter().position(|&x| x >= dist) {
                    Some(0) => return Some(0.0),
                    Some(k) => (time[k - 1], time[k]),
                    None => {
                        let v = self.speed(time[last]);
                        if v <= 0.0 {
                            return None;
                        }
                        let tl = time[last] + (dist - self.knots_travelled[last]) / v;
                        (time[last], tl)
                    }
                };
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if self.travelled(mid) < dist {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                Some(hi)
            }
            SpeedProfile::Constant { value } => Some(dist / value),
            SpeedProfile::SmoothRamp { cruise } => {
                let t0 = self.ramp_time;
                let ramp_dist = 0.5 * cruise * t0;
                if dist >= ramp_dist {
                    Some(t0 + (dist - ramp_dist) / cruise)
                } else {
                    // travelled() is increasing on [0, t0]: bisection to round-off
                    let (mut lo, mut hi) = (0.0, t0);
                    for _ in 0..200 {
                        let mid = 0.5 * (lo + hi);
                        if self.travelled(mid) < dist {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    Some(hi)
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Reference-case ramp: V0 = 100 m/s on L = 50 m.
    fn ramp() -> Motion {
        Motion::new(0.0, SpeedProfile::SmoothRamp { cruise: 100.0 }, 50.0)
    }

    #[test]
    fn ramp_covers_a_fifth_of_the_span_and_reaches_cruise() {
        let m = ramp();
        assert_relative_eq!(m.ramp_time, 0.2, max_relative = 1e-15);
        assert_relative_eq!(m.position(m.ramp_time), 10.0, max_relative = 1e-14);
        assert_relative_eq!(m.speed(m.ramp_time), 100.0, max_relative = 1e-14);
        assert_eq!(m.speed(0.0), 0.0);
    }

    /// `uniform_speed` names V exactly where x_m advances by V·Δt: never
    /// on the ramp or a sloped table segment, always at cruise, on a flat
    /// segment and beyond the last knot; and there the positions agree.
    #[test]
    fn uniform_speed_holds_only_where_the_speed_is_constant() {
        let m = ramp();
        assert_eq!(m.uniform_speed(0.1, 0.1001), None);
        assert_eq!(m.uniform_speed(0.2, 0.2001), None, "t0 at the ramp's end");
        assert_eq!(m.uniform_speed(0.25, 0.2501), Some(100.0));
        let (t0, t1) = (0.3, 0.3 + 6.25e-5);
        assert_relative_eq!(
            m.position(t1) - m.position(t0),
            100.0 * (t1 - t0),
            max_relative = 1e-9
        );
        let c = Motion::new(1.0, SpeedProfile::Constant { value: 30.0 }, 50.0);
        assert_eq!(c.uniform_speed(0.0, 1e-4), Some(30.0));
        let table = SpeedProfile::Table {
            time: vec![0.0, 1.0, 2.0, 3.0],
            speed: vec![0.0, 20.0, 20.0, 10.0],
        };
        let t = Motion::new(0.0, table, 100.0);
        assert_eq!(t.uniform_speed(0.5, 0.6), None, "sloped");
        assert_eq!(t.uniform_speed(1.2, 1.3), Some(20.0), "flat");
        assert_eq!(t.uniform_speed(1.95, 2.05), None, "crosses a knot");
        assert_eq!(t.uniform_speed(2.5, 2.6), None, "sloped");
        assert_eq!(
            t.uniform_speed(3.5, 3.6),
            Some(10.0),
            "beyond the last knot"
        );
        assert_relative_eq!(
            t.position(1.3) - t.position(1.2),
            20.0 * 0.1,
            max_relative = 1e-12
        );
    }

    #[test]
    fn speed_is_the_derivative_of_position() {
        let m = ramp();
        let h = 1e-6;
        for &t in &[0.01, 0.1, 0.19, 0.3] {
            let fd = (m.position(t + h) - m.position(t - h)) / (2.0 * h);
            assert_relative_eq!(fd, m.speed(t), max_relative = 1e-7);
        }
    }

    #[test]
    fn acceleration_is_the_derivative_of_speed() {
        let m = ramp();
        let h = 1e-6;
        for &t in &[0.01, 0.1, 0.19, 0.3] {
            let fd = (m.speed(t + h) - m.speed(t - h)) / (2.0 * h);
            assert!((fd - m.acceleration(t)).abs() <= 1e-6 * 1e3, "{t}: {fd}");
        }
        assert_eq!(m.acceleration(0.0), 0.0);
    }

    #[test]
    fn leave_time_inverts_position() {
        let m = ramp();
        let t = m.time_to_leave(50.0).unwrap();
        assert_relative_eq!(t, 0.2 + 0.4, max_relative = 1e-14);
        let short = Motion::new(45.0, SpeedProfile::SmoothRamp { cruise: 100.0 }, 50.0);
        let t = short.time_to_leave(50.0).unwrap();
        assert_relative_eq!(short.position(t), 50.0, max_relative = 1e-12);
    }
}
