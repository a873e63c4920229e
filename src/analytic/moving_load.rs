//! A constant force moving at constant speed over a taut string or a
//! pinned–pinned tensioned beam (MODEL §8), summed so that the series
//! converges fast and stays finite at and beyond the critical speeds.
//!
//! Setting: force `F` (+v, up) enters at x = 0 at t = 0 and moves at `V`;
//! it leaves at `t_e = L/V`, after which the span vibrates freely. With
//! `κ_j = jπ/L`, `Ω_j = κ_j V`, `K = 2F/(ρA L)` and the modal coordinate
//! `q_j`, `v(x, t) = Σ_j q_j(t) sin κ_j x` with (MODEL §8)
//!
//! ```text
//! 0 ≤ t ≤ t_e:  q_j = K [sin Ω_j t − (Ω_j/ω_j) sin ω_j t]/(ω_j² − Ω_j²)
//! t > t_e:      q_j = K Ω_j/(ω_j(ω_j² − Ω_j²)) [(−1)^j sin ω_j(t − t_e) − sin ω_j t]
//! ```
//!
//! (the second is free vibration from the state at `t_e`, where
//! `sin Ω_j t_e = 0`). Both are evaluated in a form that is regular at
//! resonance `Ω_j = ω_j`; with `d = ω − Ω` and `sinc u = sin u/u`,
//!
//! ```text
//! q/K = [sin ωt/ω − t cos((ω + Ω)t/2) sinc(d t/2)]/(ω + Ω)            (t ≤ t_e)
//! q/K = −Ω t_e cos(ωt − d t_e/2) sinc(d t_e/2)/(ω(ω + Ω))              (t > t_e)
//! ```
//!
//! whose limits at `d = 0` are `(sin ωt − ωt cos ωt)/(2ω²)` and
//! `−t_e cos ωt/(2ω)`, and `d` is formed from the factored
//! `ω² − Ω² = κ²(κ² EI + T − ρA V²)/ρA` (no cancellation).
//!
//! The quasi-static part `Σ K sin(Ω_j t) sin(κ_j x)/(ω_j² − Ω_j²)` is the
//! static Green's function with the effective tension `T_e = T − ρA V²`
//! (for the string `F x_<(L − x_>)/(L T_e)`, `T_e = T(1 − V²/c²)`).

use std::f64::consts::PI;

use super::StaticPointLoad;
use super::modes::{require_nonnegative, require_positive};
use crate::error::{Error, Result};
use crate::scene::Support;

/// `|1 − V/c|` below which the string is evaluated at exactly `V = c`: the
/// general closed form divides by `1 − V²/c²`, losing `≈ ε/|1 − V/c|`
/// relative accuracy, while the `V = c` form is off by `O(|1 − V/c|)` away
/// from the wave front; the two errors balance near 1e-8.
pub(crate) const RESONANCE_BAND: f64 = 1e-8;

/// Default relative accuracy of [`MovingForceBeam::deflection`]: the
/// truncation bound, relative to the static midspan deflection under `F`.
pub(crate) const DEFAULT_REL_TOL: f64 = 1e-9;

/// Cap on the number of modes summed by [`MovingForceBeam::deflection`]
/// (reached only for EI ≪ T L², where the string is the better reference;
/// the bound of [`MovingForceBeam::series_tail_bound`] then reports the
/// accuracy actually obtained).
pub const MAX_MODES: usize = 1_000_000;

/// Smallest `L sqrt(T_e/EI)` for which the quasi-static part is taken from
/// [`StaticPointLoad`]: its exponential basis becomes ill-conditioned like
/// `(μL)⁻³` as `μL → 0`, so below this the plain series is summed instead.
pub(crate) const QS_MIN_MU_L: f64 = 0.5;

/// `sin u / u`, regular at 0 (Taylor below 1e-4: error < u⁶/5040).
fn sinc(u: f64) -> f64 {
    if u.abs() < 1e-4 {
        let u2 = u * u;
        1.0 - u2 / 6.0 * (1.0 - u2 / 20.0)
    } else {
        u.sin() / u
    }
}

/// `q_j(t)/K` for one mode, regular at `ω = Ω` (module docs); `d = ω − Ω`
/// must be computed without cancellation by the caller.
fn modal_coordinate(omega: f64, big: f64, d: f64, t: f64, t_exit: f64) -> f64 {
    if t <= 0.0 {
        0.0
    } else if t <= t_exit {
        ((omega * t).sin() / omega - t * (0.5 * (omega + big) * t).cos() * sinc(0.5 * d * t))
            / (omega + big)
    } else {
        -big * t_exit / (omega * (omega + big))
            * (omega * t - 0.5 * d * t_exit).cos()
            * sinc(0.5 * d * t_exit)
    }
}

/// Validation shared by both structs.
fn check_load(rho_a: f64, length: f64, force: f64, speed: f64) -> Result<()> {
    require_positive("rho_a", rho_a, "kg/m")?;
    require_positive("length", length, "m")?;
    if !force.is_finite() {
        return Err(Error::invalid("force", force, "must be finite (N)"));
    }
    require_positive("speed", speed, "m/s; V = 0 leaves the force on the support")?;
    Ok(())
}

/// String Green's function `x_<(L − x_>)/L` for `0 ≤ x, a ≤ L`, m.
fn green(x: f64, a: f64, l: f64) -> f64 {
    let (lo, hi) = if x <= a { (x, a) } else { (a, x) };
    lo * (l - hi) / l
}

/// `Σ_j 2L/(jπ)² sin(jπy/L) sin(jπx/L)`: the odd, 2L-periodic extension of
/// [`green`] in its second argument, m.
fn green_extended(x: f64, y: f64, l: f64) -> f64 {
    let y = y.rem_euclid(2.0 * l);
    if y <= l {
        green(x, y, l)
    } else {
        -green(x, 2.0 * l - y, l)
    }
}

/// `Σ_j sin(jψ)/j`: the sawtooth `(π − ψ)/2` on (0, 2π), 0 at the jumps.
fn sawtooth(psi: f64) -> f64 {
    let p = psi.rem_euclid(2.0 * PI);
    if p == 0.0 { 0.0 } else { 0.5 * (PI - p) }
}

/// `Σ_j cos(jπy/L) sin(jπx/L)/j` in closed form (dimensionless).
fn cos_sin_sum(x: f64, y: f64, l: f64) -> f64 {
    0.5 * (sawtooth(PI * (x + y) / l) + sawtooth(PI * (x - y) / l))
}

/// Moving constant force on a taut string (EI = 0) with fixed ends, summed
/// in closed form (MODEL §8). With `c = sqrt(T/ρA)`, `β = V/c`,
/// `T_e = T − ρA V² = T(1 − β²)`, `G` the string Green's function and `G̃`
/// its odd 2L-periodic extension, the series equals
///
/// ```text
/// 0 ≤ t ≤ L/V:  v = F/T_e [G(x, Vt) − β G̃(x, ct)]
/// t > L/V:      v = F β/T_e [G̃(x, c(t − L/V) + L) − G̃(x, ct)]
/// ```
///
/// (the remainder `−Σ K(Ω/ω) sin ωt/(ω² − Ω²) sin κx` is itself a
/// Green's-function series because `Ω/ω = β` for every mode). At `V = c`
/// every mode is resonant; the limit terms sum to
/// `F/(2T) G̃(x, ct) − F ct/(πT) s(x, ct)` while the force is on (which is
/// `F x/(2T)` behind the force and 0 ahead: the front rides with the force)
/// and `−F L/(πT) s(x, ct)` after, with `s(x, y) = Σ cos(jπy/L) sin(jπx/L)/j`
/// a sum of sawtooth waves. There is no truncation error; `V > c` is covered
/// by the same formulas (`T_e < 0`). Displacement in m, positive up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingForceString {
    /// T, N (> 0).
    pub tension: f64,
    /// ρA, kg/m (> 0).
    pub rho_a: f64,
    /// L, m (> 0).
    pub length: f64,
    /// F, N, positive up (finite).
    pub force: f64,
    /// V, m/s (> 0).
    pub speed: f64,
}

impl MovingForceString {
    /// Check the inputs: T, ρA, L, V > 0 and F finite.
    pub fn new(tension: f64, rho_a: f64, length: f64, force: f64, speed: f64) -> Result<Self> {
        require_positive("tension", tension, "N; a string needs T > 0")?;
        check_load(rho_a, length, force, speed)?;
        Ok(MovingForceString {
            tension,
            rho_a,
            length,
            force,
            speed,
        })
    }

    /// Wave speed `c = sqrt(T/ρA)`, m/s.
    pub fn wave_speed(&self) -> f64 {
        (self.tension / self.rho_a).sqrt()
    }

    /// Time the force leaves the string, `L/V`, s.
    pub fn exit_time(&self) -> f64 {
        self.length / self.speed
    }

    /// `T_e = T − ρA V²`, N.
    fn effective_tension(&self) -> f64 {
        self.tension - self.rho_a * self.speed * self.speed
    }

    fn resonant(&self) -> bool {
        (1.0 - self.speed / self.wave_speed()).abs() < RESONANCE_BAND
    }

    /// The quasi-static part `F x_<(L − x_>)/(L T_e)`, m, `x_m = Vt`, while the
    /// force is on the string and `V ≠ c` (outside `RESONANCE_BAND`).
    pub fn quasi_static(&self, x: f64, t: f64) -> Option<f64> {
        let l = self.length;
        if self.resonant() || !(0.0..=self.exit_time()).contains(&t) || !(0.0..=l).contains(&x) {
            return None;
        }
        let a = (self.speed * t).min(l);
        Some(self.force * green(x, a, l) / self.effective_tension())
    }

    /// Deflection v(x, t), m, exact (closed form, see the type docs). Zero for
    /// t ≤ 0 and for x outside [0, L].
    pub fn deflection(&self, x: f64, t: f64) -> f64 {
        let l = self.length;
        if t <= 0.0 || !(0.0..=l).contains(&x) {
            return 0.0;
        }
        let c = self.wave_speed();
        let t_exit = self.exit_time();
        let f = self.force;
        if self.resonant() {
            let s = cos_sin_sum(x, c * t, l);
            return if t <= t_exit {
                f / (2.0 * self.tension) * green_extended(x, c * t, l)
                    - f * c * t / (PI * self.tension) * s
            } else {
                -f * l / (PI * self.tension) * s
            };
        }
        let beta = self.speed / c;
        let te = self.effective_tension();
        if t <= t_exit {
            let a = (self.speed * t).min(l);
            f / te * (green(x, a, l) - beta * green_extended(x, c * t, l))
        } else {
            f * beta / te
                * (green_extended(x, c * (t - t_exit) + l, l) - green_extended(x, c * t, l))
        }
    }

    /// The plain modal series of MODEL §8 truncated after `modes` terms, m
    /// (regular at V = c). Converges like 1/modes (Gibbs-like near the front).
    pub fn deflection_series(&self, x: f64, t: f64, modes: usize) -> f64 {
        let l = self.length;
        if t <= 0.0 || !(0.0..=l).contains(&x) {
            return 0.0;
        }
        let c = self.wave_speed();
        let v = self.speed;
        let t_exit = self.exit_time();
        let k = 2.0 * self.force / (self.rho_a * l);
        (1..=modes)
            .map(|j| {
                let kappa = j as f64 * PI / l;
                let q = modal_coordinate(kappa * c, kappa * v, kappa * (c - v), t, t_exit);
                k * q * (kappa * x).sin()
            })
            .sum()
    }

    /// Bound on `|deflection_series(x, t, modes) − deflection(x, t)|`, m, for
    /// any x: `2|F|(1 + β)L/(π²|T_e| N)` with the force on,
    /// `4|F|βL/(π²|T_e| N)` after (from `|q_j| ≤ bound/j²`); infinite at
    /// V = c, where the series converges only conditionally.
    pub fn series_tail_bound(&self, t: f64, modes: usize) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        if self.resonant() || modes == 0 {
            return f64::INFINITY;
        }
        let beta = self.speed / self.wave_speed();
        let per = 2.0 * self.force.abs() * self.length / (PI * PI * self.effective_tension().abs());
        let factor = if t <= self.exit_time() {
            1.0 + beta
        } else {
            2.0 * beta
        };
        per * factor / modes as f64
    }
}

/// Moving constant force on a pinned–pinned tensioned beam (MODEL §8):
/// the modal series with `ω_j = κ_j sqrt((κ_j² EI + T)/ρA)`, `κ_j = jπ/L`.
///
/// While the force is on and `μ_e L ≥ QS_MIN_MU_L` (`μ_e² = T_e/EI`,
/// `T_e = T − ρA V² ≥ 0`) the quasi-static part is summed in closed form by
/// [`StaticPointLoad`] (pinned–pinned, tension `T_e`, load at `Vt`) and only
/// the remainder `−Σ K(Ω_j/ω_j) sin(ω_j t) sin(κ_j x)/(ω_j² − Ω_j²)` is
/// summed; its terms fall like `j⁻⁵`. Otherwise (after the force leaves,
/// `T_e < 0` — above the string speed, with resonances at `V = c(2L/j)` of
/// `super::Dispersion` — or small `μ_e L`) the full series is summed in the
/// resonance-regular form (terms `∝ j⁻⁴` with the force on, `j⁻⁵` after).
///
/// Truncation bounds (`a = sqrt(EI/ρA)`, valid for `N ≥ j_min`, the first
/// mode with `κ² EI ≥ 2 max(0, −T_e)`, so that `ω² − Ω² ≥ κ⁴EI/(2ρA)`):
///
/// ```text
/// remainder, force on:     |F| V L⁴/(a EI π⁵ N⁴)
/// full series, force on:   8|F| L³/(3 EI π⁴ N³)
/// full series, after:      2|F| V L⁴/(a EI π⁵ N⁴)
/// ```
///
/// [`deflection`](Self::deflection) picks the smallest N meeting
/// `DEFAULT_REL_TOL` × (static midspan deflection under F), capped at
/// [`MAX_MODES`]. Displacement in m, positive up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingForceBeam {
    /// EI, N·m² (> 0; use [`MovingForceString`] for EI = 0).
    pub ei: f64,
    /// T, N (≥ 0).
    pub tension: f64,
    /// ρA, kg/m (> 0).
    pub rho_a: f64,
    /// L, m (> 0).
    pub length: f64,
    /// F, N, positive up (finite).
    pub force: f64,
    /// V, m/s (> 0).
    pub speed: f64,
}

/// Which series a truncation bound is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tail {
    /// The full series (force on or off, decided by t).
    Full,
    /// The remainder after the closed-form quasi-static part.
    Remainder,
}

impl MovingForceBeam {
    /// Check the inputs: EI, ρA, L, V > 0, T ≥ 0 and F finite.
    pub fn new(
        ei: f64,
        tension: f64,
        rho_a: f64,
        length: f64,
        force: f64,
        speed: f64,
    ) -> Result<Self> {
        require_positive("ei", ei, "N·m²; use MovingForceString for EI = 0")?;
        require_nonnegative("tension", tension, "N")?;
        check_load(rho_a, length, force, speed)?;
        Ok(MovingForceBeam {
            ei,
            tension,
            rho_a,
            length,
            force,
            speed,
        })
    }

    /// Time the force leaves the beam, `L/V`, s.
    pub fn exit_time(&self) -> f64 {
        self.length / self.speed
    }

    /// `T_e = T − ρA V²`, N.
    pub fn effective_tension(&self) -> f64 {
        self.tension - self.rho_a * self.speed * self.speed
    }

    /// `(κ, ω, Ω, ω − Ω)` of mode j, with `ω − Ω` from the factored
    /// `ω² − Ω² = κ²(κ² EI + T_e)/ρA`.
    fn mode(&self, j: usize) -> (f64, f64, f64, f64) {
        let kappa = j as f64 * PI / self.length;
        let omega = kappa * ((kappa * kappa * self.ei + self.tension) / self.rho_a).sqrt();
        let big = kappa * self.speed;
        let gap2 =
            kappa * kappa * (kappa * kappa * self.ei + self.effective_tension()) / self.rho_a;
        (kappa, omega, big, gap2 / (omega + big))
    }

    /// Static deflection at midspan under F at midspan, m: the scale of the
    /// default tolerance.
    fn scale(&self) -> f64 {
        let s = StaticPointLoad::new(
            self.ei,
            self.tension,
            self.length,
            Support::Pinned,
            Support::Pinned,
        )
        .expect("validated in new()");
        self.force.abs() * s.compliance(0.5 * self.length)
    }

    /// First mode from which the truncation bounds hold.
    fn j_min(&self) -> usize {
        let te = self.effective_tension();
        if te >= 0.0 {
            1
        } else {
            let j = self.length / PI * (-2.0 * te / self.ei).sqrt();
            (j.ceil() as usize).max(1)
        }
    }

    /// Bound `coef/N^p` on the tail after N modes: `(coef, p)`.
    fn tail(&self, t: f64, which: Tail) -> (f64, i32) {
        let (l, f) = (self.length, self.force.abs());
        let a = (self.ei / self.rho_a).sqrt();
        let c5 = f * self.speed * l.powi(4) / (a * self.ei * PI.powi(5));
        match which {
            Tail::Remainder => (c5, 4),
            Tail::Full if t <= self.exit_time() => {
                (8.0 * f * l.powi(3) / (3.0 * self.ei * PI.powi(4)), 3)
            }
            Tail::Full => (2.0 * c5, 4),
        }
    }

    /// Smallest N ≥ j_min whose tail bound is ≤ `tol` (m), capped at MAX_MODES.
    fn modes_for(&self, t: f64, which: Tail, tol: f64) -> usize {
        let (coef, p) = self.tail(t, which);
        let n = (coef / tol).powf(1.0 / p as f64).ceil();
        let n = if n.is_finite() {
            n.min(MAX_MODES as f64) as usize
        } else {
            MAX_MODES
        };
        n.max(self.j_min()).min(MAX_MODES)
    }

    /// Bound on `|deflection_series(x, t, modes) − exact|`, m, for any x
    /// (type docs); infinite when `modes < j_min`.
    pub fn series_tail_bound(&self, t: f64, modes: usize) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        if modes < self.j_min() || modes == 0 {
            return f64::INFINITY;
        }
        let (coef, p) = self.tail(t, Tail::Full);
        coef / (modes as f64).powi(p)
    }

    /// The quasi-static part `F·G_{T_e}(x, Vt)`, m, in closed form via
    /// [`StaticPointLoad`], while the force is on and `L sqrt(T_e/EI) ≥`
    /// `QS_MIN_MU_L` (or `T_e = 0` exactly).
    pub fn quasi_static(&self, x: f64, t: f64) -> Option<f64> {
        let l = self.length;
        let te = self.effective_tension();
        let ok = te == 0.0 || (te > 0.0 && l * (te / self.ei).sqrt() >= QS_MIN_MU_L);
        if !ok || !(0.0..=self.exit_time()).contains(&t) || !(0.0..=l).contains(&x) {
            return None;
        }
        let s = StaticPointLoad::new(self.ei, te, l, Support::Pinned, Support::Pinned).ok()?;
        Some(self.force * s.deflection((self.speed * t).min(l), x))
    }

    /// Deflection v(x, t), m, to `DEFAULT_REL_TOL` (type docs). Zero for
    /// t ≤ 0 and for x outside [0, L].
    pub fn deflection(&self, x: f64, t: f64) -> f64 {
        self.deflection_to(x, t, DEFAULT_REL_TOL)
    }

    /// Deflection v(x, t), m, with the truncation bound at most `rel_tol` ×
    /// the static midspan deflection under F (unless [`MAX_MODES`] binds).
    pub fn deflection_to(&self, x: f64, t: f64, rel_tol: f64) -> f64 {
        let l = self.length;
        if t <= 0.0 || !(0.0..=l).contains(&x) || self.force == 0.0 {
            return 0.0;
        }
        let tol = rel_tol * self.scale();
        let Some(qs) = self.quasi_static(x, t) else {
            let n = self.modes_for(t, Tail::Full, tol);
            return self.deflection_series(x, t, n);
        };
        let n = self.modes_for(t, Tail::Remainder, tol);
        let k = 2.0 * self.force / (self.rho_a * l);
        let rem: f64 = (1..=n)
            .map(|j| {
                let (kappa, omega, big, d) = self.mode(j);
                let gap2 = d * (omega + big);
                -(big / omega) * (omega * t).sin() / gap2 * (kappa * x).sin()
            })
            .sum();
        qs + k * rem
    }

    /// The plain modal series of MODEL §8 truncated after `modes` terms, m,
    /// regular at resonances; error ≤ [`series_tail_bound`](Self::series_tail_bound).
    pub fn deflection_series(&self, x: f64, t: f64, modes: usize) -> f64 {
        let l = self.length;
        if t <= 0.0 || !(0.0..=l).contains(&x) {
            return 0.0;
        }
        let t_exit = self.exit_time();
        let k = 2.0 * self.force / (self.rho_a * l);
        (1..=modes)
            .map(|j| {
                let (kappa, omega, big, d) = self.mode(j);
                k * modal_coordinate(omega, big, d, t, t_exit) * (kappa * x).sin()
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::Dispersion;
    use approx::assert_relative_eq;

    /// Two closed forms of the same quantity: round-off of a few operations,
    /// amplified at most 1e3× by cancellation near resonance.
    const CLOSED_FORM: f64 = 1e-12;

    // A contact-wire-like span: c = 121.7 m/s, bending length 0.099 m.
    const T: f64 = 2e4;
    const RA: f64 = 1.35;
    const L: f64 = 50.0;
    const EI: f64 = 195.0;
    const F: f64 = 100.0;

    fn c() -> f64 {
        (T / RA).sqrt()
    }

    #[test]
    fn validation_names_the_field() {
        let e = MovingForceString::new(0.0, RA, L, F, 10.0).unwrap_err();
        assert!(e.to_string().contains("`tension`"), "{e}");
        let e = MovingForceString::new(T, RA, L, F, 0.0).unwrap_err();
        assert!(e.to_string().contains("`speed`"), "{e}");
        let e = MovingForceBeam::new(0.0, T, RA, L, F, 10.0).unwrap_err();
        assert!(e.to_string().contains("`ei`"), "{e}");
        let e = MovingForceBeam::new(EI, T, RA, L, f64::INFINITY, 10.0).unwrap_err();
        assert!(e.to_string().contains("`force`"), "{e}");
        let e = MovingForceBeam::new(EI, -1.0, RA, L, F, 10.0).unwrap_err();
        assert!(e.to_string().contains("`tension`"), "{e}");
        assert!(MovingForceBeam::new(EI, 0.0, RA, L, F, 10.0).is_ok());
    }

    #[test]
    fn resonance_regular_form_matches_the_spec_form() {
        // away from resonance the rewritten q_j is the MODEL §8 expression;
        // mode j = 2 leaves at t_e with Ω t_e = 2π, so (−1)^j = 1
        let (w, big) = (7.3, 2.1);
        let te = 2.0 * PI / big;
        for t in [0.1, 1.0, 2.9, 3.5, 10.0] {
            let spec = if t <= te {
                ((big * t).sin() - big / w * (w * t).sin()) / (w * w - big * big)
            } else {
                big / (w * (w * w - big * big)) * ((w * (t - te)).sin() - (w * t).sin())
            };
            let q = modal_coordinate(w, big, w - big, t, te);
            assert_relative_eq!(q, spec, max_relative = CLOSED_FORM, epsilon = 1e-15);
        }
        // and its limit at resonance
        for t in [0.3, 2.0] {
            let q = modal_coordinate(w, w, 0.0, t, 5.0);
            let lim = ((w * t).sin() - w * t * (w * t).cos()) / (2.0 * w * w);
            assert_relative_eq!(q, lim, max_relative = CLOSED_FORM);
        }
    }

    #[test]
    fn string_quasi_static_closed_form_is_the_modal_sum() {
        // Σ_j K sin(Ω_j t) sin(κ_j x)/(ω_j² − Ω_j²) against F x_<(L − x_>)/(L T_e)
        for beta in [0.3, 0.9, 1.7] {
            let s = MovingForceString::new(T, RA, L, F, beta * c()).unwrap();
            let t = 0.37 * s.exit_time();
            let n = 200_000;
            let k = 2.0 * F / (RA * L);
            for x in [3.0, 18.5, 40.0] {
                let series: f64 = (1..=n)
                    .map(|j| {
                        let kappa = j as f64 * PI / L;
                        let gap2 = kappa * kappa * (T - RA * s.speed * s.speed) / RA;
                        k * (kappa * s.speed * t).sin() * (kappa * x).sin() / gap2
                    })
                    .sum();
                // tail: K/(κ²|c² − V²|) per mode → 2|F|L/(π²|T_e| N)
                let bound = 2.0 * F * L / (PI * PI * (T - RA * s.speed * s.speed).abs() * n as f64);
                let qs = s.quasi_static(x, t).unwrap();
                assert!((series - qs).abs() <= bound, "β = {beta}, x = {x}");
            }
        }
    }

    #[test]
    fn string_series_converges_to_the_closed_form() {
        println!("  string: max |series(N) − closed form| over x, / static midspan FL/4T");
        let scale = F * L / (4.0 * T);
        for beta in [0.5, 1.0, 1.5] {
            let s = MovingForceString::new(T, RA, L, F, beta * c()).unwrap();
            for tf in [0.3, 0.8, 1.6] {
                let t = tf * s.exit_time();
                let xs: Vec<f64> = (1..50).map(|i| L * i as f64 / 50.0).collect();
                // stay 2 % of L off the wave fronts (jumps at V = c)
                let front = |x: f64| {
                    let y = (c() * t).rem_euclid(2.0 * L);
                    let y = if y > L { 2.0 * L - y } else { y };
                    (x - y).abs() < 0.02 * L
                };
                let mut prev = f64::INFINITY;
                let mut line = format!("  β = {beta}, t = {tf}·L/V:");
                for n in [10, 100, 1000, 10_000] {
                    let err = xs
                        .iter()
                        .filter(|x| beta != 1.0 || !front(**x))
                        .map(|&x| (s.deflection_series(x, t, n) - s.deflection(x, t)).abs())
                        .fold(0.0, f64::max);
                    line += &format!("  N={n}: {:.2e}", err / scale);
                    assert!(err <= s.series_tail_bound(t, n), "β {beta} N {n}");
                    assert!(err < prev, "error must fall: β {beta} N {n}");
                    prev = err;
                }
                println!("{line}");
                // 1/N convergence: 10⁴ modes reach a few 1e-4 (1e-3 at V = c,
                // 2 % of L from the jump)
                assert!(prev / scale < 2e-3, "β {beta}");
            }
        }
    }

    #[test]
    fn string_at_the_wave_speed_rides_its_front() {
        // d'Alembert with the image source: v = F x/(2T) behind, 0 ahead
        let s = MovingForceString::new(T, RA, L, F, c()).unwrap();
        let t = 0.6 * s.exit_time();
        for x in [1.0, 10.0, 29.0] {
            assert_relative_eq!(
                s.deflection(x, t),
                F * x / (2.0 * T),
                max_relative = CLOSED_FORM
            );
        }
        for x in [31.0, 45.0] {
            assert!(s.deflection(x, t).abs() < 1e-15);
        }
        assert!(s.quasi_static(10.0, t).is_none());
    }

    #[test]
    fn string_is_continuous_in_speed_through_resonance() {
        // V = c(1 ± δ): v = F x/(T(1 + β)) behind the front, so the change
        // is δ/2 relative; ahead of both front and force it stays 0.
        let delta = 1e-6;
        let at = MovingForceString::new(T, RA, L, F, c()).unwrap();
        let t = 0.6 * at.exit_time();
        for sign in [-1.0, 1.0] {
            let near = MovingForceString::new(T, RA, L, F, c() * (1.0 + sign * delta)).unwrap();
            assert!(!near.resonant());
            for x in [1.0, 10.0, 29.0, 31.0, 45.0] {
                let (a, b) = (at.deflection(x, t), near.deflection(x, t));
                assert!(b.is_finite());
                // δ/2 of the value plus cancellation ε/δ of the static scale
                let tol = delta * a.abs() + 1e-9 * F * L / T;
                assert!((a - b).abs() <= tol, "x {x}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn string_is_continuous_when_the_force_leaves() {
        for beta in [0.4, 1.0, 2.0] {
            let s = MovingForceString::new(T, RA, L, F, beta * c()).unwrap();
            let te = s.exit_time();
            for x in [5.0, 25.0, 44.0] {
                let (a, b) = (s.deflection(x, te), s.deflection(x, te * (1.0 + 1e-12)));
                assert!((a - b).abs() < 1e-9 * F * L / T, "β {beta} x {x}: {a} {b}");
            }
        }
    }

    #[test]
    fn beam_quasi_static_closed_form_is_the_modal_sum() {
        // StaticPointLoad with T_e = T − ρAV² against the modal quasi-static sum
        for v in [0.0_f64, 60.0, 110.0] {
            let b = MovingForceBeam::new(EI, T, RA, L, F, v.max(1e-3)).unwrap();
            let t = 0.43 * b.exit_time();
            let te = b.effective_tension();
            let n = 100_000;
            let k = 2.0 * F / (RA * L);
            for x in [2.0, 21.5, 30.0] {
                let series: f64 = (1..=n)
                    .map(|j| {
                        let (kappa, _, big, _) = b.mode(j);
                        let gap2 = kappa * kappa * (kappa * kappa * EI + te) / RA;
                        k * (big * t).sin() * (kappa * x).sin() / gap2
                    })
                    .sum();
                // tail ≤ min over the two bounds on 1/(ω² − Ω²)
                let bound = (2.0 * F * L / (PI * PI * te * n as f64))
                    .min(2.0 * F * L.powi(3) / (3.0 * PI.powi(4) * EI * (n as f64).powi(3)));
                let qs = b.quasi_static(x, t).unwrap();
                assert!(
                    (series - qs).abs() <= bound + CLOSED_FORM * qs.abs(),
                    "V {v} x {x}: {series} vs {qs}"
                );
            }
        }
    }

    #[test]
    fn beam_series_converges_to_the_split_sum() {
        let scale = F * L / (4.0 * T);
        println!("  beam: max |series(N) − deflection| over x, / (F L/4T)");
        let c_beam = Dispersion::new(EI, T, RA).unwrap().phase_speed(2.0 * L);
        // sub-critical (closed-form quasi-static); just above the string
        // speed c but below the first resonance c(2L) (T_e < 0, full
        // series); and 200 m/s, between the resonances of modes 210 and 211
        for v in [60.0, 0.5 * (c_beam + c()), 200.0] {
            let b = MovingForceBeam::new(EI, T, RA, L, F, v).unwrap();
            for tf in [0.3, 0.8, 1.6] {
                let t = tf * b.exit_time();
                let xs: Vec<f64> = (1..25).map(|i| L * i as f64 / 25.0).collect();
                let exact: Vec<f64> = xs.iter().map(|&x| b.deflection(x, t)).collect();
                let mut line = format!("  V = {v:.1}, t = {tf}·L/V:");
                let mut prev = f64::INFINITY;
                for n in [10, 100, 1000, 10_000] {
                    let err = xs
                        .iter()
                        .zip(&exact)
                        .map(|(&x, e)| (b.deflection_series(x, t, n) - e).abs())
                        .fold(0.0, f64::max);
                    line += &format!("  N={n}: {:.2e}", err / scale);
                    // the bound, plus the reference's own tolerance
                    let tol = b.series_tail_bound(t, n) + DEFAULT_REL_TOL * b.scale();
                    assert!(err <= tol, "V {v} t {tf} N {n}: {err} > {tol}");
                    assert!(err < prev || err < 1e-12 * scale, "V {v} t {tf} N {n}");
                    prev = err;
                }
                println!("{line}");
            }
        }
    }

    #[test]
    fn beam_default_accuracy_meets_its_tolerance() {
        // against a plain series so long that its own bound is negligible
        let n = 100_000;
        println!("  beam: |deflection − series(1e5)| / static midspan, vs DEFAULT_REL_TOL");
        for (ei, v) in [(EI, 10.0), (EI, 80.0), (EI, 150.0), (5.0, 60.0)] {
            let b = MovingForceBeam::new(ei, T, RA, L, F, v).unwrap();
            for tf in [0.25, 0.75, 1.3] {
                let t = tf * b.exit_time();
                let bound = b.series_tail_bound(t, n);
                let err = [4.0, 17.0, 33.0, 46.0]
                    .iter()
                    .map(|&x| (b.deflection(x, t) - b.deflection_series(x, t, n)).abs())
                    .fold(0.0, f64::max);
                println!(
                    "  EI {ei}, V {v}, t {tf}·L/V: {:.2e} (series bound {:.1e})",
                    err / b.scale(),
                    bound / b.scale()
                );
                assert!(
                    err <= DEFAULT_REL_TOL * b.scale() + bound,
                    "EI {ei} V {v} t {tf}"
                );
            }
        }
    }

    #[test]
    fn beam_is_continuous_in_speed_through_a_resonance() {
        // V = c(2L/j): mode j is resonant (Ω_j = ω_j)
        let disp = Dispersion::new(EI, T, RA).unwrap();
        for j in [1, 3] {
            let vr = disp.phase_speed(2.0 * L / j as f64);
            let at = MovingForceBeam::new(EI, T, RA, L, F, vr).unwrap();
            let (_, w, big, _) = at.mode(j);
            assert_relative_eq!(w, big, max_relative = 1e-12);
            // a fixed time, so that only the speed changes
            let t = 0.7 * at.exit_time();
            let delta = 1e-6;
            for x in [7.0, 25.0, 38.0] {
                let v0 = at.deflection(x, t);
                let lo = MovingForceBeam::new(EI, T, RA, L, F, vr * (1.0 - delta))
                    .unwrap()
                    .deflection(x, t);
                let hi = MovingForceBeam::new(EI, T, RA, L, F, vr * (1.0 + delta))
                    .unwrap()
                    .deflection(x, t);
                assert!(v0.is_finite() && lo.is_finite() && hi.is_finite());
                // smooth in V: the second difference is much smaller than the
                // first, which is itself O(δ)
                let first = (hi - lo).abs();
                let second = (hi - 2.0 * v0 + lo).abs();
                let scale = at.scale();
                println!(
                    "  j = {j}, x = {x}: v = {v0:.6e}, |Δv| = {first:.2e}, |Δ²v| = {second:.2e}"
                );
                assert!(first < 1e-3 * scale, "x {x}");
                assert!(second < 1e-3 * first + 1e-8 * scale, "x {x}");
            }
        }
    }

    #[test]
    fn beam_is_continuous_in_speed_where_the_effective_tension_vanishes() {
        // V = c: T_e changes sign, the closed form hands over to the series
        let t_of = |b: &MovingForceBeam| 0.55 * b.exit_time();
        let at = MovingForceBeam::new(EI, T, RA, L, F, c()).unwrap();
        let t = t_of(&at);
        for x in [10.0, 27.0] {
            let v0 = at.deflection(x, t);
            for sign in [-1.0, 1.0] {
                let near =
                    MovingForceBeam::new(EI, T, RA, L, F, c() * (1.0 + sign * 1e-6)).unwrap();
                assert!((near.deflection(x, t) - v0).abs() < 1e-4 * at.scale());
            }
        }
    }

    #[test]
    fn beam_tends_to_the_string_as_ei_vanishes() {
        // bending length 1e-4 L: pinned ends and the load point carry
        // boundary layers of relative size O(lb/L)
        let lb = 1e-4 * L;
        let s = MovingForceString::new(T, RA, L, F, 0.5 * c()).unwrap();
        let b = MovingForceBeam::new(T * lb * lb, T, RA, L, F, 0.5 * c()).unwrap();
        let scale = F * L / (4.0 * T);
        for tf in [0.3, 0.9, 1.4] {
            let t = tf * s.exit_time();
            for x in [5.0, 20.0, 35.0] {
                let (vs, vb) = (s.deflection(x, t), b.deflection(x, t));
                assert!(
                    (vs - vb).abs() < 10.0 * lb / L * scale,
                    "t {tf} x {x}: {vs} {vb}"
                );
            }
        }
    }
}
