//! A two- or three-mass lumped pantograph pressed by its static uplift
//! against a rigid surface (docs/lines.md L9–L11): the independent
//! reference for multi-mass carriers (MODEL §10), built before them.
//!
//! The lumped-mass pantograph of this field (the "three-mass model" of EN
//! 50318's reference pantograph and e.g. Pombo & Ambrósio 2012, cited from
//! memory; two masses when the upper arm is lumped): masses in series from
//! the head m₁ (in contact) down to the frame m_n (MODEL §10), spring k_i
//! and dashpot c_i between m_i and m_{i+1}, k_n, c_n to the roof, the static
//! uplift F₀ on m_n; z_i positive up from the unloaded springs, no gravity.
//! The surface holds the head or meets it through a spring ([`SurfaceContact`]).
//!
//! In either case, with the free masses' z, the diagonal M and tridiagonal K, C
//! assembled from the springs and dashpots,
//!
//! ```text
//! (L9)  M z̈ + C ż + K z = F,  F = F₀ e_n + (k_c h e₁  |  (k₁ h + c₁ ḣ) e₂ when held)
//!       static: K z_s = F;  contact force λ = k_c (z₁ − h)  |  k₁(z₂ − h) + c₁ ż₂
//!       (the surface presses the head down by λ; λ_s = F₀ k_s/(k_s + k_n) with
//!       k_s the chain's series stiffness from m_n to the surface)
//! (L10) undamped or proportional C (ΦᵀCΦ diagonal): K φⱼ = ωⱼ² M φⱼ,
//!       φⱼᵀMφⱼ = 1 (symmetric eigenproblem of M^{−1/2} K M^{−1/2}),
//!       ζⱼ = φⱼᵀCφⱼ / (2ωⱼ), and from (z₀, ż₀) under a constant F
//!       z(t) = z_s + Σⱼ φⱼ qⱼ(t),  qⱼ(0) = φⱼᵀM(z₀ − z_s),  q̇ⱼ(0) = φⱼᵀM ż₀,
//!       each qⱼ the damped free vibration L13
//! (L11) any C: y = (z, ż), ẏ = A y + b, A = [[0, I], [−M⁻¹K, −M⁻¹C]],
//!       y(t) = y_s + e^{At} (y(0) − y_s); ωⱼ = |sⱼ|, ζⱼ = −Re sⱼ/|sⱼ| from
//!       A's complex eigenvalues sⱼ (Im sⱼ > 0: the underdamped modes).
//! ```

use nalgebra::{DMatrix, DVector, SymmetricEigen};

use super::modes::{require_nonnegative, require_positive};
use super::rayleigh::DampedOscillator;
use crate::error::{Error, Result};

/// Off-diagonal part of ΦᵀCΦ, relative to its diagonal, below which C counts
/// as proportional (L10): the eigenvectors' round-off, ≈ 1e-15, with room.
pub(crate) const PROPORTIONAL: f64 = 1e-10;

/// How the head meets the rigid surface.
///
/// The rigid surface at height h(t) is one of
/// - `Held`: the head follows the surface, z₁ = h (the classical reduction to
///   n − 1 degrees of freedom, m₂ … m_n);
/// - `Spring { k_c }`: a stiff contact spring from the surface to the head,
///   force `k_c (z₁ − h)` (n degrees of freedom).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfaceContact {
    /// The head follows the surface (n − 1 degrees of freedom).
    Held,
    /// A contact spring of stiffness `k_c`, N/m (> 0), to the surface.
    Spring {
        /// k_c, N/m.
        k_c: f64,
    },
}

/// A lumped pantograph on a rigid surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Pantograph {
    /// m₁ (head) … m_n, kg (> 0), n = 2 or 3.
    pub masses: Vec<f64>,
    /// k₁ … k_n, N/m: k_i between m_i and m_{i+1} (> 0), k_n to the roof (≥ 0).
    pub springs: Vec<f64>,
    /// c₁ … c_n, N·s/m (≥ 0), placed like the springs.
    pub dashpots: Vec<f64>,
    /// F₀, N: the static uplift on m_n.
    pub uplift: f64,
    /// The head's contact with the surface.
    pub contact: SurfaceContact,
}

/// A change from the static state at t = 0.
///
/// Steps start from the static state under F₀ and h = 0: an uplift step
/// F₀ → F₀ + ΔF, or a surface step h: 0 → Δh (when held, the dashpot c₁ then
/// gives m₂ the impulse c₁Δh: ż₂(0⁺) = c₁Δh/m₂).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PantographStep {
    /// F₀ → F₀ + ΔF, N.
    Uplift(f64),
    /// h: 0 → Δh, m.
    Surface(f64),
}

/// The natural frequencies and damping ratios of the held pantograph.
#[derive(Debug, Clone, PartialEq)]
pub struct PantographModes {
    /// ωⱼ, rad/s, ascending.
    pub omega: Vec<f64>,
    /// ζⱼ, in the same order.
    pub zeta: Vec<f64>,
}

/// The response to a [`PantographStep`] in closed form.
#[derive(Debug, Clone)]
pub struct StepResponse {
    m: DVector<f64>,
    /// z_s after the step, m.
    pub z_static: DVector<f64>,
    /// z(0⁺) and ż(0⁺).
    z0: DVector<f64>,
    v0: DVector<f64>,
    /// L10: mass-normalized modes and their oscillators (proportional C).
    modes: Option<(DMatrix<f64>, Vec<DampedOscillator>)>,
    /// L11: A for e^{At}.
    a: DMatrix<f64>,
    /// Surface height after the step, m; (k₁, c₁) or k_c for λ.
    h: f64,
    contact: SurfaceContact,
    k1c1: (f64, f64),
}

impl Pantograph {
    /// Check the inputs: 2 or 3 masses > 0, as many springs and dashpots,
    /// k₁ … k_{n−1} > 0, k_n ≥ 0, every c ≥ 0, F₀ finite, k_c > 0.
    pub fn new(
        masses: &[f64],
        springs: &[f64],
        dashpots: &[f64],
        uplift: f64,
        contact: SurfaceContact,
    ) -> Result<Self> {
        let n = masses.len();
        if !(2..=3).contains(&n) {
            return Err(Error::invalid("masses", n, "must hold 2 or 3 masses"));
        }
        if springs.len() != n || dashpots.len() != n {
            return Err(Error::invalid(
                "springs, dashpots",
                format!("{}, {}", springs.len(), dashpots.len()),
                format!("must hold one per mass ({n})"),
            ));
        }
        for (i, m) in masses.iter().enumerate() {
            require_positive(&format!("masses[{i}]"), *m, "kg")?;
        }
        for (i, k) in springs.iter().enumerate() {
            if i + 1 < n {
                require_positive(&format!("springs[{i}]"), *k, "N/m; it links two masses")?;
            } else {
                require_nonnegative(&format!("springs[{i}]"), *k, "N/m")?;
            }
        }
        for (i, c) in dashpots.iter().enumerate() {
            require_nonnegative(&format!("dashpots[{i}]"), *c, "N·s/m")?;
        }
        if !uplift.is_finite() {
            return Err(Error::invalid("uplift", uplift, "must be finite (N)"));
        }
        if let SurfaceContact::Spring { k_c } = contact {
            require_positive("contact.k_c", k_c, "N/m")?;
        }
        Ok(Pantograph {
            masses: masses.to_vec(),
            springs: springs.to_vec(),
            dashpots: dashpots.to_vec(),
            uplift,
            contact,
        })
    }

    /// The index of the first free mass: 1 when held, else 0.
    fn first(&self) -> usize {
        match self.contact {
            SurfaceContact::Held => 1,
            SurfaceContact::Spring { .. } => 0,
        }
    }

    /// Degrees of freedom: n − 1 when held, else n.
    pub fn dofs(&self) -> usize {
        self.masses.len() - self.first()
    }

    /// (M, C, K) over the free masses (L9).
    pub fn matrices(&self) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
        let n = self.masses.len();
        let f = self.first();
        let dofs = n - f;
        let mut m = DMatrix::zeros(dofs, dofs);
        let mut c = DMatrix::zeros(dofs, dofs);
        let mut k = DMatrix::zeros(dofs, dofs);
        for i in f..n {
            m[(i - f, i - f)] = self.masses[i];
        }
        // element i links mass i and mass i + 1 (i + 1 = n: the roof)
        let link = |a: &mut DMatrix<f64>, i: usize, v: f64| {
            let (p, q) = (i, i + 1);
            if p >= f {
                a[(p - f, p - f)] += v;
            }
            if q < n {
                a[(q - f, q - f)] += v;
                if p >= f {
                    a[(p - f, q - f)] -= v;
                    a[(q - f, p - f)] -= v;
                }
            }
        };
        for i in 0..n {
            link(&mut k, i, self.springs[i]);
            link(&mut c, i, self.dashpots[i]);
        }
        if let SurfaceContact::Spring { k_c } = self.contact {
            k[(0, 0)] += k_c;
        }
        (m, c, k)
    }

    /// The load vector F of L9 for uplift `f0` and surface height `h`.
    fn load(&self, f0: f64, h: f64) -> DVector<f64> {
        let dofs = self.dofs();
        let mut f = DVector::zeros(dofs);
        f[dofs - 1] += f0;
        match self.contact {
            SurfaceContact::Held => f[0] += self.springs[0] * h,
            SurfaceContact::Spring { k_c } => f[0] += k_c * h,
        }
        f
    }

    /// The static state z_s under F₀ and h = 0 (L9), m.
    pub fn static_state(&self) -> DVector<f64> {
        let (_, _, k) = self.matrices();
        k.cholesky()
            .expect("K is positive definite: the chain is held by the surface")
            .solve(&self.load(self.uplift, 0.0))
    }

    /// The static contact force λ_s, N (L9).
    pub fn static_contact_force(&self) -> f64 {
        let z = self.static_state();
        self.contact_force_of(&z, &DVector::zeros(z.len()), 0.0)
    }

    fn contact_force_of(&self, z: &DVector<f64>, v: &DVector<f64>, h: f64) -> f64 {
        match self.contact {
            SurfaceContact::Held => self.springs[0] * (z[0] - h) + self.dashpots[0] * v[0],
            SurfaceContact::Spring { k_c } => k_c * (z[0] - h),
        }
    }

    /// Mass-normalized undamped modes (L10): (ω ascending, Φ by columns).
    pub fn undamped_modes(&self) -> (Vec<f64>, DMatrix<f64>) {
        let (m, _, k) = self.matrices();
        let dofs = m.nrows();
        let s = DVector::from_fn(dofs, |i, _| 1.0 / m[(i, i)].sqrt());
        let a = DMatrix::from_fn(dofs, dofs, |i, j| s[i] * k[(i, j)] * s[j]);
        let eig = SymmetricEigen::new(a);
        let mut order: Vec<usize> = (0..dofs).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        let omega = order.iter().map(|&j| eig.eigenvalues[j].sqrt()).collect();
        let phi = DMatrix::from_fn(dofs, dofs, |i, c| s[i] * eig.eigenvectors[(i, order[c])]);
        (omega, phi)
    }

    /// Whether C is proportional (ΦᵀCΦ diagonal within `PROPORTIONAL`).
    pub fn proportional(&self) -> bool {
        let (_, c, _) = self.matrices();
        let (_, phi) = self.undamped_modes();
        let cm = phi.transpose() * c * &phi;
        let diag = (0..cm.nrows()).fold(0.0_f64, |a, i| a.max(cm[(i, i)].abs()));
        (0..cm.nrows())
            .all(|i| (0..cm.ncols()).all(|j| i == j || cm[(i, j)].abs() <= PROPORTIONAL * diag))
    }

    /// The state matrix A of L11.
    pub fn state_matrix(&self) -> DMatrix<f64> {
        let (m, c, k) = self.matrices();
        let n = m.nrows();
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
            for j in 0..n {
                a[(n + i, j)] = -k[(i, j)] / m[(i, i)];
                a[(n + i, n + j)] = -c[(i, j)] / m[(i, i)];
            }
        }
        a
    }

    /// Natural frequencies and damping ratios. Proportional C: L10 (ω
    /// undamped, ζ = φᵀCφ/2ω); otherwise L11 from A's eigenvalues, which
    /// must all be underdamped (else an error naming the overdamped count).
    pub fn modes(&self) -> Result<PantographModes> {
        let (omega, phi) = self.undamped_modes();
        if self.proportional() {
            let (_, c, _) = self.matrices();
            let zeta = omega
                .iter()
                .enumerate()
                .map(|(j, w)| {
                    let p = phi.column(j);
                    (p.transpose() * &c * p)[(0, 0)] / (2.0 * w)
                })
                .collect();
            return Ok(PantographModes { omega, zeta });
        }
        let ev = self.state_matrix().complex_eigenvalues();
        let mut pairs: Vec<(f64, f64)> = ev
            .iter()
            .filter(|s| s.im > 0.0)
            .map(|s| (s.norm(), -s.re / s.norm()))
            .collect();
        if pairs.len() != omega.len() {
            return Err(Error::invalid(
                "dashpots",
                format!("{:?}", self.dashpots),
                format!(
                    "leave {} of {} modes overdamped: damping ratios need underdamped modes",
                    omega.len() - pairs.len(),
                    omega.len()
                ),
            ));
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        Ok(PantographModes {
            omega: pairs.iter().map(|p| p.0).collect(),
            zeta: pairs.iter().map(|p| p.1).collect(),
        })
    }

    /// The closed-form response to `step` (L10 when C is proportional, and
    /// always L11).
    pub fn step(&self, step: PantographStep) -> Result<StepResponse> {
        let (f0, h) = match step {
            PantographStep::Uplift(df) => {
                if !df.is_finite() {
                    return Err(Error::invalid("step.uplift", df, "must be finite (N)"));
                }
                (self.uplift + df, 0.0)
            }
            PantographStep::Surface(dh) => {
                if !dh.is_finite() {
                    return Err(Error::invalid("step.surface", dh, "must be finite (m)"));
                }
                (self.uplift, dh)
            }
        };
        let (m, _, k) = self.matrices();
        let z0 = self.static_state();
        let mut v0 = DVector::zeros(z0.len());
        if self.contact == SurfaceContact::Held {
            // the dashpot c₁'s impulse c₁Δh on m₂
            v0[0] = self.dashpots[0] * h / m[(0, 0)];
        }
        let z_static = k
            .cholesky()
            .expect("K is positive definite")
            .solve(&self.load(f0, h));
        let modes = if self.proportional() {
            let (omega, phi) = self.undamped_modes();
            let zeta = self.modes()?.zeta;
            let osc = omega
                .iter()
                .zip(&zeta)
                .map(|(w, z)| DampedOscillator::new(*w, *z))
                .collect::<Result<Vec<_>>>()?;
            Some((phi, osc))
        } else {
            None
        };
        Ok(StepResponse {
            m: m.diagonal(),
            z_static,
            z0,
            v0,
            modes,
            a: self.state_matrix(),
            h,
            contact: self.contact,
            k1c1: (self.springs[0], self.dashpots[0]),
        })
    }
}

impl StepResponse {
    /// The initial state (z(0⁺), ż(0⁺)).
    pub fn initial(&self) -> (DVector<f64>, DVector<f64>) {
        (self.z0.clone(), self.v0.clone())
    }

    /// (z(t), ż(t)) by modal superposition (L10); `None` unless C is
    /// proportional.
    pub fn modal(&self, t: f64) -> Option<(DVector<f64>, DVector<f64>)> {
        let (phi, osc) = self.modes.as_ref()?;
        let dz = &self.z0 - &self.z_static;
        let mut z = self.z_static.clone();
        let mut v = DVector::zeros(z.len());
        for (j, o) in osc.iter().enumerate() {
            let p = phi.column(j);
            let q0: f64 = (0..dz.len()).map(|i| p[i] * self.m[i] * dz[i]).sum();
            let qd0: f64 = (0..dz.len()).map(|i| p[i] * self.m[i] * self.v0[i]).sum();
            let (q, qd) = o.free(q0, qd0, t);
            z += p * q;
            v += p * qd;
        }
        Some((z, v))
    }

    /// (z(t), ż(t)) by the state-space matrix exponential (L11), any C.
    pub fn state_space(&self, t: f64) -> (DVector<f64>, DVector<f64>) {
        let n = self.z0.len();
        let mut y0 = DVector::zeros(2 * n);
        for i in 0..n {
            y0[i] = self.z0[i] - self.z_static[i];
            y0[n + i] = self.v0[i];
        }
        let y = (&self.a * t).exp() * y0;
        let z = DVector::from_fn(n, |i, _| self.z_static[i] + y[i]);
        let v = DVector::from_fn(n, |i, _| y[n + i]);
        (z, v)
    }

    /// The contact force λ(t), N (L9), from a state.
    pub fn contact_force(&self, z: &DVector<f64>, v: &DVector<f64>) -> f64 {
        match self.contact {
            SurfaceContact::Held => self.k1c1.0 * (z[0] - self.h) + self.k1c1.1 * v[0],
            SurfaceContact::Spring { k_c } => k_c * (z[0] - self.h),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::Rayleigh;
    use approx::assert_relative_eq;

    /// Eigenvalues of 2×2/3×3 symmetric matrices against closed forms
    /// (quadratic formula, trace and determinant identities): round-off.
    const EIGEN: f64 = 1e-12;
    /// Closed forms (L10 modal sums, L11 Padé exponential) against each other
    /// and their initial states: round-off of the 6×6 exponential, measured
    /// ≤ 7e-15 of the step's size.
    const CLOSED_FORMS: f64 = 1e-10;
    /// RK4 at Δt = T_min/400 (T_min the shortest period) over ≈ 1 s: global
    /// error ≈ (ωΔt)⁴ ω t/120 ≈ 1e-9 of the step's size (measured ≤ 1.1e-9,
    /// the undamped held case).
    const RK4: f64 = 5e-9;
    /// A surface step as a smooth ramp of duration τ = 1e-7 s against the
    /// ideal step with the dashpot's impulse: the ramp's centre lags by τ/2,
    /// an O(ω_max τ) ≈ 6e-6 difference (measured 1.4e-7).
    const RAMP: f64 = 1e-5;

    /// Illustrative three-mass values of the field's magnitude (head, upper
    /// arm, frame): not the values of any standard's table.
    fn three_mass(contact: SurfaceContact, dashpots: [f64; 3]) -> Pantograph {
        Pantograph::new(
            &[6.6, 5.8, 10.0],
            &[7000.0, 14_000.0, 80.0],
            &dashpots,
            120.0,
            contact,
        )
        .unwrap()
    }

    /// Accelerations of the free masses from the chain, mass by mass
    /// (independent of `matrices()`): surface at (h, ḣ), uplift f0.
    fn accel(p: &Pantograph, z: &[f64], v: &[f64], h: f64, hd: f64, f0: f64) -> Vec<f64> {
        let n = p.masses.len();
        let held = p.contact == SurfaceContact::Held;
        let (mut zf, mut vf) = (vec![0.0; n + 1], vec![0.0; n + 1]); // index n: roof
        let off = usize::from(held);
        if held {
            zf[0] = h;
            vf[0] = hd;
        }
        zf[off..off + z.len()].copy_from_slice(z);
        vf[off..off + v.len()].copy_from_slice(v);
        let mut force = vec![0.0; n];
        for j in 0..n {
            let t = p.springs[j] * (zf[j] - zf[j + 1]) + p.dashpots[j] * (vf[j] - vf[j + 1]);
            force[j] -= t;
            if j + 1 < n {
                force[j + 1] += t;
            }
        }
        if let SurfaceContact::Spring { k_c } = p.contact {
            force[0] -= k_c * (zf[0] - h);
        }
        force[n - 1] += f0;
        (off..n).map(|i| force[i] / p.masses[i]).collect()
    }

    /// The rigid surface the head is held on: its height `h(t)` (m) and
    /// rate `rate(t)` (m/s).
    struct Surface<'a> {
        h: &'a dyn Fn(f64) -> f64,
        rate: &'a dyn Fn(f64) -> f64,
    }

    /// RK4 from (z0, v0) to time `t_end` in `steps` steps, the head held on
    /// `surface`: the final (z, ż).
    fn rk4(
        p: &Pantograph,
        z0: &[f64],
        v0: &[f64],
        f0: f64,
        surface: Surface,
        t_end: f64,
        steps: usize,
    ) -> (Vec<f64>, Vec<f64>) {
        let Surface { h, rate: hd } = surface;
        let dt = t_end / steps as f64;
        let (mut z, mut v) = (z0.to_vec(), v0.to_vec());
        let n = z.len();
        let axpy = |a: &[f64], s: f64, b: &[f64]| -> Vec<f64> {
            a.iter().zip(b).map(|(x, y)| x + s * y).collect()
        };
        for i in 0..steps {
            let t = i as f64 * dt;
            let f = |tt: f64, zz: &[f64], vv: &[f64]| {
                (vv.to_vec(), accel(p, zz, vv, h(tt), hd(tt), f0))
            };
            let (k1z, k1v) = f(t, &z, &v);
            let (k2z, k2v) = f(
                t + dt / 2.0,
                &axpy(&z, dt / 2.0, &k1z),
                &axpy(&v, dt / 2.0, &k1v),
            );
            let (k3z, k3v) = f(
                t + dt / 2.0,
                &axpy(&z, dt / 2.0, &k2z),
                &axpy(&v, dt / 2.0, &k2v),
            );
            let (k4z, k4v) = f(t + dt, &axpy(&z, dt, &k3z), &axpy(&v, dt, &k3v));
            for j in 0..n {
                z[j] += dt / 6.0 * (k1z[j] + 2.0 * k2z[j] + 2.0 * k3z[j] + k4z[j]);
                v[j] += dt / 6.0 * (k1v[j] + 2.0 * k2v[j] + 2.0 * k3v[j] + k4v[j]);
            }
        }
        (z, v)
    }

    fn max_diff(a: &DVector<f64>, b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn validation_names_the_field() {
        let held = SurfaceContact::Held;
        let e = Pantograph::new(&[1.0], &[1.0], &[0.0], 1.0, held).unwrap_err();
        assert!(e.to_string().contains("masses"), "{e}");
        let e = Pantograph::new(&[1.0, 2.0], &[0.0, 1.0], &[0.0, 0.0], 1.0, held).unwrap_err();
        assert!(e.to_string().contains("springs[0]"), "{e}");
        let e = Pantograph::new(&[1.0, -2.0], &[1.0, 1.0], &[0.0, 0.0], 1.0, held).unwrap_err();
        assert!(e.to_string().contains("masses[1]"), "{e}");
        let e = Pantograph::new(&[1.0, 2.0], &[1.0, 1.0], &[0.0, -1.0], 1.0, held).unwrap_err();
        assert!(e.to_string().contains("dashpots[1]"), "{e}");
        let e = Pantograph::new(&[1.0, 2.0], &[1.0], &[0.0, 0.0], 1.0, held).unwrap_err();
        assert!(e.to_string().contains("springs, dashpots"), "{e}");
        let e = Pantograph::new(
            &[1.0, 2.0],
            &[1.0, 0.0],
            &[0.0, 0.0],
            1.0,
            SurfaceContact::Spring { k_c: 0.0 },
        )
        .unwrap_err();
        assert!(e.to_string().contains("contact.k_c"), "{e}");
        let p = three_mass(held, [0.0; 3]);
        assert!(p.step(PantographStep::Uplift(f64::NAN)).is_err());
    }

    #[test]
    fn two_masses_match_their_closed_forms() {
        // held: one degree of freedom, ω² = (k₁ + k₂)/m₂, ζ = (c₁ + c₂)/(2m₂ω)
        let (m, k, c) = ([6.0, 11.0], [7000.0, 60.0], [15.0, 40.0]);
        let held = Pantograph::new(&m, &k, &c, 100.0, SurfaceContact::Held).unwrap();
        let modes = held.modes().unwrap();
        let w = ((k[0] + k[1]) / m[1]).sqrt();
        assert_relative_eq!(modes.omega[0], w, max_relative = EIGEN);
        assert_relative_eq!(
            modes.zeta[0],
            (c[0] + c[1]) / (2.0 * m[1] * w),
            max_relative = EIGEN
        );
        assert_relative_eq!(
            held.static_contact_force(),
            100.0 * k[0] / (k[0] + k[1]),
            max_relative = EIGEN
        );
        // contact spring: m₁m₂ω⁴ − (m₁K₂₂ + m₂K₁₁)ω² + det K = 0
        let kc = 2e5;
        let free = Pantograph::new(
            &m,
            &k,
            &[0.0, 0.0],
            100.0,
            SurfaceContact::Spring { k_c: kc },
        )
        .unwrap();
        let (k11, k22, k12) = (kc + k[0], k[0] + k[1], -k[0]);
        let (a, b, cc) = (
            m[0] * m[1],
            -(m[0] * k22 + m[1] * k11),
            k11 * k22 - k12 * k12,
        );
        let disc = (b * b - 4.0 * a * cc).sqrt();
        let (lo, hi) = ((-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a));
        let modes = free.modes().unwrap();
        assert_relative_eq!(modes.omega[0], lo.sqrt(), max_relative = EIGEN);
        assert_relative_eq!(modes.omega[1], hi.sqrt(), max_relative = EIGEN);
        assert!(modes.zeta.iter().all(|z| *z == 0.0));
        // series chain: λ_s = F₀ k_s/(k_s + k₂), 1/k_s = 1/k₁ + 1/k_c
        let ks = 1.0 / (1.0 / k[0] + 1.0 / kc);
        assert_relative_eq!(
            free.static_contact_force(),
            100.0 * ks / (ks + k[1]),
            max_relative = EIGEN
        );
    }

    #[test]
    fn three_masses_satisfy_their_characteristic_polynomial() {
        for contact in [SurfaceContact::Held, SurfaceContact::Spring { k_c: 5e4 }] {
            let p = three_mass(contact, [0.0; 3]);
            let (m, _, k) = p.matrices();
            let (omega, _) = p.undamped_modes();
            // Σω² = tr(M⁻¹K), Πω² = det K / det M
            let tr: f64 = (0..m.nrows()).map(|i| k[(i, i)] / m[(i, i)]).sum();
            let sum: f64 = omega.iter().map(|w| w * w).sum();
            let prod: f64 = omega.iter().map(|w| w * w).product();
            assert_relative_eq!(sum, tr, max_relative = EIGEN);
            assert_relative_eq!(
                prod,
                k.determinant() / m.determinant(),
                max_relative = EIGEN
            );
            for w in &omega {
                // det(K − ω²M) against the size of det K's terms, ‖K‖ⁿ
                let scale = k.norm().powi(k.nrows() as i32);
                let d = (&k - &m * (w * w)).determinant();
                assert!(d.abs() < 1e-12 * scale, "{contact:?}: ω = {w}");
            }
            // static force through the series chain
            let ks = match contact {
                SurfaceContact::Held => 1.0 / (1.0 / 7000.0 + 1.0 / 14_000.0),
                SurfaceContact::Spring { k_c } => 1.0 / (1.0 / 7000.0 + 1.0 / 14_000.0 + 1.0 / k_c),
            };
            assert_relative_eq!(
                p.static_contact_force(),
                120.0 * ks / (ks + 80.0),
                max_relative = EIGEN
            );
        }
    }

    #[test]
    fn stiffness_proportional_dashpots_damp_each_mode_at_its_rayleigh_ratio() {
        // c_i = β k_i with the head held: C = β K exactly (L10, L12)
        let beta = 2e-3;
        let p = three_mass(
            SurfaceContact::Held,
            [7000.0 * beta, 14_000.0 * beta, 80.0 * beta],
        );
        assert!(p.proportional());
        let modes = p.modes().unwrap();
        let r = Rayleigh::new(0.0, beta).unwrap();
        for (w, z) in modes.omega.iter().zip(&modes.zeta) {
            assert_relative_eq!(*z, r.ratio(*w), max_relative = EIGEN);
        }
        // the state-space eigenvalues (L11) agree
        let ev = p.state_matrix().complex_eigenvalues();
        let mut from_a: Vec<(f64, f64)> = ev
            .iter()
            .filter(|s| s.im > 0.0)
            .map(|s| (s.norm(), -s.re / s.norm()))
            .collect();
        from_a.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (j, (w, z)) in from_a.iter().enumerate() {
            assert_relative_eq!(*w, modes.omega[j], max_relative = 1e-10);
            assert_relative_eq!(*z, modes.zeta[j], max_relative = 1e-10);
        }
        // the field's dashpots with a contact spring are not proportional
        let q = three_mass(SurfaceContact::Spring { k_c: 5e4 }, [20.0, 0.0, 70.0]);
        assert!(!q.proportional());
        let m = q.modes().unwrap();
        assert!(m.zeta.iter().all(|z| *z > 0.0 && *z < 1.0), "{m:?}");
    }

    #[test]
    fn uplift_steps_match_rk4() {
        let beta = 2e-3;
        let cases = [
            // proportional: L10 and L11 both apply
            three_mass(
                SurfaceContact::Held,
                [7000.0 * beta, 14_000.0 * beta, 80.0 * beta],
            ),
            // undamped, held and on a contact spring
            three_mass(SurfaceContact::Held, [0.0; 3]),
            three_mass(SurfaceContact::Spring { k_c: 5e4 }, [0.0; 3]),
            // non-proportional: L11 only
            three_mass(SurfaceContact::Spring { k_c: 5e4 }, [20.0, 0.0, 70.0]),
        ];
        let df = 30.0;
        println!("  case  L10 vs L11    L11 vs RK4   (relative to the static change)");
        for (ci, p) in cases.iter().enumerate() {
            let resp = p.step(PantographStep::Uplift(df)).unwrap();
            let (z0, v0) = resp.initial();
            let size = (&resp.z_static - &z0).amax();
            let wmax = *p.undamped_modes().0.last().unwrap();
            let t_end = 0.7;
            let steps = (400.0 * wmax * t_end / (2.0 * std::f64::consts::PI)).ceil() as usize;
            let zero = |_: f64| 0.0;
            let fixed = Surface {
                h: &zero,
                rate: &zero,
            };
            let (zr, vr) = rk4(
                p,
                z0.as_slice(),
                v0.as_slice(),
                p.uplift + df,
                fixed,
                t_end,
                steps,
            );
            let (zs, vs) = resp.state_space(t_end);
            let rk = max_diff(&zs, &zr).max(max_diff(&vs, &vr) / wmax) / size;
            let modal = match resp.modal(t_end) {
                Some((zm, vm)) => {
                    let d = (&zm - &zs).amax().max((&vm - &vs).amax() / wmax) / size;
                    assert!(d < CLOSED_FORMS, "case {ci}: {d}");
                    format!("{d:.2e}")
                }
                None => "   -    ".into(),
            };
            println!("  {ci}     {modal}      {rk:.2e}");
            assert!(rk < RK4, "case {ci}: {rk}");
            // initial state reproduced
            let (za, va) = resp.state_space(0.0);
            assert!((&za - &z0).amax() < CLOSED_FORMS * size && va.amax() == 0.0);
        }
    }

    #[test]
    fn undamped_energy_is_conserved_and_damped_steps_settle() {
        let p = three_mass(SurfaceContact::Spring { k_c: 5e4 }, [0.0; 3]);
        let resp = p.step(PantographStep::Uplift(25.0)).unwrap();
        let (m, _, k) = p.matrices();
        let f = p.load(p.uplift + 25.0, 0.0);
        let energy = |z: &DVector<f64>, v: &DVector<f64>| {
            0.5 * (v.transpose() * &m * v)[(0, 0)] + 0.5 * (z.transpose() * &k * z)[(0, 0)]
                - f.dot(z)
        };
        let (z0, v0) = resp.initial();
        let e0 = energy(&z0, &v0);
        let swing = (energy(&resp.z_static, &DVector::zeros(3)) - e0).abs();
        for t in [0.01, 0.1, 0.37, 1.3] {
            let (z, v) = resp.modal(t).unwrap();
            assert!((energy(&z, &v) - e0).abs() < 1e-9 * swing, "t = {t}");
            let (z, v) = resp.state_space(t);
            assert!((energy(&z, &v) - e0).abs() < 1e-9 * swing, "t = {t}");
        }
        // damped: the step settles on the new static state, whose contact
        // force changes by ΔF k_s/(k_s + k₃)
        let d = three_mass(SurfaceContact::Spring { k_c: 5e4 }, [20.0, 10.0, 70.0]);
        let resp = d.step(PantographStep::Uplift(25.0)).unwrap();
        let (z, v) = resp.state_space(20.0);
        assert!((&z - &resp.z_static).amax() < 1e-9 && v.amax() < 1e-8);
        let ks = 1.0 / (1.0 / 7000.0 + 1.0 / 14_000.0 + 1.0 / 5e4);
        assert_relative_eq!(
            resp.contact_force(&z, &v),
            145.0 * ks / (ks + 80.0),
            max_relative = 1e-8
        );
    }

    #[test]
    fn held_surface_step_carries_the_dashpot_impulse() {
        // RK4 with the surface ramped over τ: the dashpot c₁ gives m₂ the
        // impulse c₁Δh the closed form puts in ż(0⁺)
        let p = three_mass(SurfaceContact::Held, [25.0, 10.0, 70.0]);
        let dh = 0.01;
        let resp = p.step(PantographStep::Surface(dh)).unwrap();
        let (z0, _) = resp.initial();
        let tau = 1e-7;
        // a smooth (half-cosine) ramp, resolved by RK4 in 40 steps
        let h = move |t: f64| 0.5 * dh * (1.0 - (std::f64::consts::PI * (t / tau).min(1.0)).cos());
        let hd = move |t: f64| {
            if t < tau {
                0.5 * dh * std::f64::consts::PI / tau * (std::f64::consts::PI * t / tau).sin()
            } else {
                0.0
            }
        };
        let ramp = Surface { h: &h, rate: &hd };
        let (zr, vr) = rk4(&p, z0.as_slice(), &[0.0, 0.0], p.uplift, ramp, tau, 40);
        let t_end = 0.5;
        let zero = |_: f64| 0.0;
        let hold = move |_: f64| dh;
        let held = Surface {
            h: &hold,
            rate: &zero,
        };
        let (zr, vr) = rk4(&p, &zr, &vr, p.uplift, held, t_end - tau, 40_000);
        let (zs, vs) = resp.state_space(t_end);
        let size = (&resp.z_static - &z0).amax();
        let wmax = *p.undamped_modes().0.last().unwrap();
        let d = max_diff(&zs, &zr).max(max_diff(&vs, &vr) / wmax) / size;
        println!("  surface step, ramp τ = {tau:e} s: rel. diff. {d:.2e}");
        assert!(d < RAMP, "{d}");
        // without the impulse the two would differ at O(1)
        let (_, v0) = resp.initial();
        assert!(v0[0] > 0.0 && (v0[0] - 25.0 * dh / 5.8).abs() < 1e-15);
    }
}
