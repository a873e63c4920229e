//! Droppers during a run (MODEL §10, `docs/lines.md` eq. D1–D10): every
//! dropper's spring is in the step matrix, and a tension-only dropper
//! gets a row of the step's contact problem only while it is slack.
//!
//! A dropper d at x_d pulls the beam up with N_d along r_d = r_b(x_d)
//! (MODEL §4); one hanging from the messenger wire pulls the contact wire
//! up and the messenger down along r_d = r_b(x_d) − r_m(x_d)
//! (`docs/lines.md` eq. W2), and everything below holds with that r_d.
//! A tension-only dropper obeys the compliant unilateral law (D3)
//! `0 ≤ N_d ⊥ N_d/k_d − e_d ≥ 0`, e_d = e₀,d − r_dᵀd, imposed at the
//! generalized-α force level d_{n+1−α_f} = (1 − α_f) d_{n+1} + α_f d_n,
//! where the method's K acts (MODEL §5).
//!
//! **Springs in K (D7).** Every dropper's spring k_d r_d r_dᵀ is in K and
//! its preload k_d e₀,d r_d in the constant load (a linear one's by
//! `resolve::dropper`, a tension-only one's by [`Droppers::add_springs`]
//! and [`Droppers::add_preloads`]), so the step matrix is the linear
//! twin's, A' = A + κ Σ_d k_d r_d r_dᵀ with κ = (1 − α_f) c_d, factored
//! once. A tension-only dropper that would push gets a correction
//! μ_d ≥ 0 along r_d that cancels its spring: N_d = k_d e_d + μ_d with
//! `0 ≤ μ_d ⊥ N_d ≥ 0` (D8); μ_d = 0 for a taut one, which is then
//! exactly the linear dropper.
//!
//! The step's rows (D9) are derived on [`Droppers::prepare`], the check
//! that grows the slack set (D10) on [`Droppers::add_responses`], dashpots
//! (D12) on [`Droppers::add_dashpots`]. Nothing here allocates in a step.

use super::state::State;
use super::step_map::{StepMap, VelocityPrediction};
use crate::contact::ContactFailure;
use crate::model::banded::SymBand;
use crate::model::beam::{BeamModel, PointVector};
use crate::scene::Dropper;

/// Relative round-off of a taut dropper's force k_d e_d evaluated from the
/// affine relation (D10): below −this × the step's force scale
/// (max_d k_d |e_free,d|) it is a push, and the dropper gets a row. The
/// same meaning as the Lagrange law's gap round-off (1e-12 of the free
/// gaps' scale).
pub(crate) const FORCE_ROUNDOFF: f64 = 1e-12;

/// One dropper's state after a step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DropperSample {
    /// Force N_d, N (positive in tension: the dropper pulls the wire up).
    pub force: f64,
    /// Slack this step (N_d = 0 with the dropper's row open).
    pub slack: bool,
}

/// One dropper during a run.
#[derive(Debug, Clone)]
struct Link {
    /// r_b(x_d) on the contact wire, fixed for the run.
    pv: PointVector,
    /// r_m(x_d) on the messenger wire for a messenger dropper (eq. W2:
    /// r_d = r_b(x_d) − r_m(x_d)); `None` for a fixed anchor (r_d = r_b).
    pm: Option<PointVector>,
    /// k_d, N/m.
    k: f64,
    /// c_d, N·s/m (eq. D11 linear, D12 tension-only; 0: none).
    c: f64,
    /// e₀ = z_a − ℓ_0, m: the extension with the beam straight.
    e0: f64,
    /// The dropper's row among the tension-only ones (`None`: linear).
    row: Option<usize>,
}

impl Link {
    /// r_dᵀx.
    #[inline]
    fn dot(&self, x: &[f64]) -> f64 {
        match &self.pm {
            None => self.pv.dot(x),
            Some(pm) => self.pv.dot(x) - pm.dot(x),
        }
    }

    /// r_dᵀx on column `col` of `stride` interleaved columns.
    #[inline]
    fn dot_strided(&self, x: &[f64], stride: usize, col: usize) -> f64 {
        match &self.pm {
            None => self.pv.dot_strided(x, stride, col),
            Some(pm) => self.pv.dot_strided(x, stride, col) - pm.dot_strided(x, stride, col),
        }
    }

    /// y += a·r_d on column `col` of `stride`.
    #[inline]
    fn scatter(&self, a: f64, y: &mut [f64], stride: usize, col: usize) {
        self.pv.scatter(a, y, stride, col);
        if let Some(pm) = &self.pm {
            pm.scatter(-a, y, stride, col);
        }
    }
}

/// The contacts' own pair (g_free, W) of a step, as the contact problem
/// formed it: `w` row-major at stride `stride`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactPair<'a> {
    /// The contacts' free gaps, m.
    pub(crate) g: &'a [f64],
    /// Their Delassus matrix, m/N.
    pub(crate) w: &'a [f64],
    /// W's row stride.
    pub(crate) stride: usize,
}

/// The run's droppers, in scene order (module docs).
#[derive(Debug, Clone, Default)]
pub(crate) struct Droppers {
    links: Vec<Link>,
    /// The link of each tension-only row, in scene order.
    tension: Vec<usize>,
    /// Beam unknowns n.
    n: usize,
    /// Contacts nc of the run (the problem's rows before the droppers').
    nc: usize,
    /// z'_d = A'⁻¹ r_d of each row, row d at `z[d·n..(d+1)·n]`.
    z: Vec<f64>,
    /// Q_ab = r_aᵀ z'_b, m × m row-major.
    q: Vec<f64>,
    /// α: the weight of d_n in the dropper rows (α_f).
    weight: f64,
    /// κ = (1 − α) c_d.
    coef: f64,
    /// k_eff,d = k_d + c_d c_v/c_d of each row, N/m ([`Droppers::add_dashpots`], D12;
    /// k_d without a dashpot).
    keff: Vec<f64>,
    /// True once a method formed z and Q ([`Droppers::prepare`]).
    ready: bool,
    /// Each row's force N_d after the last step, N.
    force: Vec<f64>,
    /// Each row's correction μ_d after the last step, N (0 when taut).
    mu: Vec<f64>,
    /// Each row slack after the last step.
    slack: Vec<bool>,
    /// The step's scratch (module docs).
    scratch: Scratch,
}

/// A step's dense quantities (D9, [`Droppers::prepare`]), sized once for the run.
#[derive(Debug, Clone, Default)]
struct Scratch {
    /// ê_d = N_free,d / k_eff,d of each row, m: the free extension e_free,d
    /// without a dashpot (D9), the free force in k_eff's units with one
    /// (D12).
    e_free: Vec<f64>,
    /// P_dc = r_dᵀz'_c, m × nc row-major, m/N·(1/c_d).
    p: Vec<f64>,
    /// coef_c s_c r_cᵀ z'_d, nc × m row-major.
    e_c: Vec<f64>,
    /// The contacts' own free gaps g'_c and block W'_cc (nc × nc).
    g_c: Vec<f64>,
    w_c: Vec<f64>,
    /// The rows S of the step, ascending.
    set: Vec<usize>,
    in_set: Vec<bool>,
    /// H's Cholesky factor, then G = H⁻¹ (|S| × |S|).
    chol: Vec<f64>,
    g_inv: Vec<f64>,
    /// Ê G, nc × |S|.
    y: Vec<f64>,
    /// max_d |N_free,d|, N.
    scale: f64,
}

impl Droppers {
    /// The droppers of a scene on `beam` (their point vectors formed once),
    /// for a run of `nc` contacts.
    pub(crate) fn new(droppers: &[Dropper], beam: &BeamModel, nc: usize) -> Self {
        let mut tension = Vec::new();
        let links = droppers
            .iter()
            .enumerate()
            .map(|(i, d)| {
                let row = (!d.linear).then(|| {
                    tension.push(i);
                    tension.len() - 1
                });
                Link {
                    pv: beam.point_vector(d.x),
                    pm: d.on_messenger().then(|| beam.messenger_point_vector(d.x)),
                    k: d.stiffness,
                    c: d.damping,
                    e0: d.rest_extension(),
                    row,
                }
            })
            .collect();
        let m = tension.len();
        Droppers {
            links,
            tension,
            n: beam.n,
            nc,
            force: vec![0.0; m],
            mu: vec![0.0; m],
            slack: vec![false; m],
            scratch: Scratch {
                e_free: vec![0.0; m],
                p: vec![0.0; m * nc],
                e_c: vec![0.0; nc * m],
                g_c: vec![0.0; nc],
                w_c: vec![0.0; nc * nc],
                set: Vec::with_capacity(m),
                in_set: vec![false; m],
                chol: vec![0.0; m * m],
                g_inv: vec![0.0; m * m],
                y: vec![0.0; nc * m],
                scale: 0.0,
            },
            ..Droppers::default()
        }
    }

    /// Tension-only droppers: the problem's rows after the contacts, at most.
    pub(crate) fn rows(&self) -> usize {
        self.tension.len()
    }

    /// All droppers.
    pub(crate) fn len(&self) -> usize {
        self.links.len()
    }

    /// True when the method formed what the rows need (always, without them).
    pub(crate) fn ready(&self) -> bool {
        self.tension.is_empty() || self.ready
    }

    /// Add every dropper's preload k_d e₀ r_d (up) to the beam's constant
    /// load `load` (D2, D7).
    pub(crate) fn add_preloads(&self, load: &mut [f64]) {
        for l in &self.links {
            l.scatter(l.k * l.e0, load, 1, 0);
        }
    }

    /// Add every tension-only dropper's spring k_d r_d r_dᵀ to `k` (D7: a
    /// linear dropper's is there already, from `resolve::dropper`).
    pub(crate) fn add_springs(&self, k: &mut SymBand) {
        self.add_outer(k, |l| l.k);
    }

    /// True when a tension-only dropper has a dashpot (D12).
    pub(crate) fn has_dashpots(&self) -> bool {
        self.tension.iter().any(|&i| self.links[i].c != 0.0)
    }

    /// Add every tension-only dropper's dashpot c_d r_d r_dᵀ to `c` (D12; a
    /// linear dropper's is there already, D11).
    ///
    /// **Dashpots (D12).** A tension-only dropper with a dashpot c_d is a
    /// Kelvin–Voigt link, N_d = max(0, k_d e_d + c_d ė_d), ė_d = −r_dᵀv: its
    /// dashpot c_d r_d r_dᵀ is in C ([`Droppers::add_dashpots`]) as its spring
    /// is in K, and the slack correction μ_d cancels both together, N_d =
    /// k_d e_d + c_d ė_d + μ_d with `0 ≤ μ_d ⊥ N_d ≥ 0`. At the force level
    /// e_d and ė_d respond to μ (and λ) through the same z'_d, with κ and
    /// κ_v = (1 − α_f) c_v (v_{n+1} = ṽ + c_v u), so the spring and dashpot
    /// answer as one spring of stiffness k_eff,d = k_d + c_d c_v/c_d
    /// (= k_d + c_d γ/(βΔt)): every formula above holds with k_d → k_eff,d
    /// and k_d e_free,d → N_free,d = k_d e_free,d + c_d ė_free,d (the force of
    /// the free step). Without a dashpot k_eff,d = k_d and nothing changes.
    pub(crate) fn add_dashpots(&self, c: &mut SymBand) {
        self.add_outer(c, |l| l.c);
    }

    /// Add coef(l) r_d r_dᵀ of every tension-only dropper to `a`.
    fn add_outer(&self, a: &mut SymBand, coef: impl Fn(&Link) -> f64) {
        for l in self.tension.iter().map(|&i| &self.links[i]) {
            let c = coef(l);
            if c == 0.0 {
                continue;
            }
            let mut entries = [(0usize, 0.0f64); 8];
            for (e, (i, v)) in entries.iter_mut().zip(l.pv.idx.iter().zip(l.pv.val)) {
                *e = (*i, v);
            }
            if let Some(pm) = &l.pm {
                for (e, (i, v)) in entries[4..].iter_mut().zip(pm.idx.iter().zip(pm.val)) {
                    *e = (*i, -v);
                }
            }
            a.add_outer(&entries, c);
        }
    }

    /// The initial state (t = 0, wire at `d0`: straight at rest, or the
    /// static start; `None` is the straight wire): each row's force
    /// N_d = k_d max(e_d, 0) and correction μ_d = k_d max(−e_d, 0) (D8),
    /// and μ_d r_d into column 0 of `rhs` (k columns), a known load of the
    /// initial acceleration problem (the springs and preloads are in K and
    /// the load).
    pub(crate) fn initial(&mut self, d0: Option<&[f64]>, rhs: &mut [f64], k: usize) {
        for (r, &li) in self.tension.iter().enumerate() {
            let l = &self.links[li];
            let e = match d0 {
                None => l.e0,
                Some(d) => l.e0 - l.dot(d),
            };
            self.force[r] = l.k * e.max(0.0);
            self.mu[r] = l.k * (-e).max(0.0);
            self.slack[r] = self.force[r] <= 0.0;
            if self.mu[r] != 0.0 {
                l.scatter(self.mu[r], rhs, k, 0);
            }
        }
    }

    /// The force k_d (e₀ − r_dᵀd) of each tension-only dropper at `d`, in
    /// scene order with its index (the static start's check that each is
    /// taut).
    pub(crate) fn taut_forces<'a>(
        &'a self,
        d: &'a [f64],
    ) -> impl Iterator<Item = (usize, f64)> + 'a {
        self.tension.iter().map(move |&i| {
            (
                i,
                self.links[i].k * (self.links[i].e0 - self.links[i].dot(d)),
            )
        })
    }

    /// Dropper `i`'s force k_d (e₀ − r_dᵀd) at `d` taken taut, N (the
    /// form-finding's forces at rest, `form_finding.rs`).
    pub(crate) fn taut_force(&self, i: usize, d: &[f64]) -> f64 {
        let l = &self.links[i];
        l.k * (l.e0 - l.dot(d))
    }

    /// y += a·r_d of dropper `i` (its direction, W2).
    pub(crate) fn scatter_direction(&self, i: usize, a: f64, y: &mut [f64]) {
        self.links[i].scatter(a, y, 1, 0);
    }

    /// k_d of dropper `i`, N/m.
    pub(crate) fn stiffness(&self, i: usize) -> f64 {
        self.links[i].k
    }

    /// Set dropper `i`'s e₀ (its length changed, `form_finding.rs`); the
    /// load must then be formed again ([`Droppers::add_preloads`]).
    pub(crate) fn set_rest_extension(&mut self, i: usize, e0: f64) {
        self.links[i].e0 = e0;
    }

    /// Form z'_d = A'⁻¹ r_d and Q once (D9, below), for a method with
    /// constant A' (the droppers' springs and dashpots in it): `solve`
    /// overwrites a right-hand side with A'⁻¹ of it; `c_d`, `c_v` as in
    /// d_{n+1} = d̃ + c_d u, v_{n+1} = ṽ + c_v u; `weight` = α_f.
    ///
    /// **The rows of a step (D9).** z'_d = A'⁻¹r_d and Q_ab = r_aᵀz'_b are
    /// formed once ([`Droppers::prepare`]). A step's set S holds the droppers
    /// slack at the previous step and those whose free extension e_free,d
    /// (no μ, no contact force) is negative. With the contacts' forces λ and
    /// μ_S, e_d = e_free,d − κ(Σ_c P_dc λ_c + Σ_{b∈S} Q_db μ_b), P_dc =
    /// r_dᵀz'_c (z'_c the contact columns of the step). Written in the
    /// droppers' forces N_S (the law's multipliers, as before) the problem
    /// over the contacts and S is
    ///
    /// ```text
    ///   H = diag(k_S) − κ diag(k_S) Q_SS diag(k_S),   G = H⁻¹   (S × S, SPD)
    ///   g_S = G(−k∘e_free + κ diag(k) P λ + N_S)        [= μ_S / k_S]
    ///   g_c = g'_c + W'_cc λ + Ê G(−k∘e_free + κ diag(k) P λ + N_S)
    /// ```
    ///
    /// (Ê_cd = coef_c s_c r_cᵀz'_d k_d, the contact row's coefficient coef_c
    /// at its placement): the same pair as the problem with every dropper a
    /// row over A (the taut ones condensed exactly), so every law gives the
    /// same forces. The law's slack rows give μ_d = k_d g_d, its taut rows
    /// μ_d = 0.
    pub(crate) fn prepare(&mut self, solve: impl Fn(&mut [f64]), c_d: f64, c_v: f64, weight: f64) {
        let (n, m) = (self.n, self.rows());
        self.z = vec![0.0; n * m];
        for (r, &li) in self.tension.iter().enumerate() {
            let z = &mut self.z[r * n..(r + 1) * n];
            self.links[li].scatter(1.0, z, 1, 0);
            solve(z);
        }
        self.weight = weight;
        self.coef = (1.0 - weight) * c_d;
        self.keff = self
            .tension
            .iter()
            .map(|&i| {
                let l = &self.links[i];
                if l.c == 0.0 {
                    l.k
                } else {
                    l.k + l.c * c_v / c_d
                }
            })
            .collect();
        self.q = vec![0.0; m * m];
        for (a, &la) in self.tension.iter().enumerate() {
            for b in 0..m {
                self.q[a * m + b] = self.links[la].dot(&self.z[b * n..(b + 1) * n]);
            }
        }
        self.ready = true;
    }

    /// z'_d of row `r`.
    fn response(&self, r: usize) -> &[f64] {
        &self.z[r * self.n..(r + 1) * self.n]
    }

    /// Begin a step's dropper problem (D9, [`Droppers::prepare`]), from the
    /// method's step `map` (`k` columns) and the state `st` at t_n: the
    /// free extensions from d̃, the free solution (column 0) and d_n, and
    /// with a dashpot (D12) the free rates from ṽ, the same column and
    /// v_n; P from the contact columns 1 + c; the contacts' couplings Ê
    /// from their gap rows `(i, s_i, r_i)` at the placement with
    /// coefficient `coef_c`; the contacts' own pair `pair`; and the step's
    /// first set S.
    pub(crate) fn begin<'a>(
        &mut self,
        map: &StepMap,
        k: usize,
        st: &State,
        contacts: impl Iterator<Item = (usize, f64, &'a PointVector)>,
        coef_c: f64,
        pair: ContactPair,
    ) {
        let (solved, c_d, d_pred, d_n) = (map.solved, map.c_d, map.d_pred, &st.d[..]);
        let (v_pred, v_n, c_v) = (map.v_pred, &st.v[..], map.c_v);
        let ContactPair { g, w, stride } = pair;
        let (nc, m, a) = (self.nc, self.rows(), self.weight);
        let s = &mut self.scratch;
        s.scale = 0.0;
        for (r, &li) in self.tension.iter().enumerate() {
            let l = &self.links[li];
            let u_free = l.dot_strided(solved, k, 0);
            let end = l.dot(d_pred) + c_d * u_free;
            s.e_free[r] = l.e0 - ((1.0 - a) * end + a * l.dot(d_n));
            if l.c != 0.0 {
                // ê = (k e_free + c ė_free)/k_eff, ė_free = −r_dᵀv_free at
                // the force level (D12)
                let r_vn = l.dot(v_n);
                let v_end = match v_pred {
                    VelocityPrediction::Vector(v) => l.dot(v),
                    VelocityPrediction::Shifted { shift, coef } => r_vn + coef * l.dot(shift),
                } + c_v * u_free;
                let rate = -((1.0 - a) * v_end + a * r_vn);
                s.e_free[r] = (l.k * s.e_free[r] + l.c * rate) / self.keff[r];
            }
            s.scale = s.scale.max(self.keff[r] * s.e_free[r].abs());
            for c in 0..nc {
                s.p[r * nc + c] = l.dot_strided(solved, k, 1 + c);
            }
        }
        for (i, sign, pv) in contacts {
            for r in 0..m {
                s.e_c[i * m + r] = coef_c * sign * pv.dot(&self.z[r * self.n..(r + 1) * self.n]);
            }
        }
        for i in 0..nc {
            s.g_c[i] = g[i];
            s.w_c[i * nc..(i + 1) * nc].copy_from_slice(&w[i * stride..i * stride + nc]);
        }
        s.set.clear();
        for r in 0..m {
            s.in_set[r] = self.slack[r] || s.e_free[r] < 0.0;
            if s.in_set[r] {
                s.set.push(r);
            }
        }
    }

    /// The pair (g, W) over the contacts and the set S (D9, [`Droppers::prepare`])
    /// into `g`, `w` (row-major, stride nc + |S|, the set's rows after the
    /// contacts); returns nc + |S|. A non-positive pivot of H (round-off
    /// destroying its definiteness) is [`ContactFailure::Singular`].
    pub(crate) fn assemble(
        &mut self,
        g: &mut [f64],
        w: &mut [f64],
    ) -> Result<usize, ContactFailure> {
        let (nc, m, kappa) = (self.nc, self.rows(), self.coef);
        let s = &mut self.scratch;
        let ms = s.set.len();
        let ns = nc + ms;
        let k_of = |r: usize| self.keff[r];
        // H = diag(k) − κ diag(k) Q diag(k) over S, its Cholesky factor L
        let h = &mut s.chol[..ms * ms];
        for (i, &a) in s.set.iter().enumerate() {
            for (j, &b) in s.set.iter().enumerate() {
                let mut v = -kappa * k_of(a) * self.q[a * m + b] * k_of(b);
                if i == j {
                    v += k_of(a);
                }
                h[i * ms + j] = v;
            }
        }
        for j in 0..ms {
            let mut d = h[j * ms + j];
            for p in 0..j {
                d -= h[j * ms + p] * h[j * ms + p];
            }
            if !(d > 0.0 && d.is_finite()) {
                return Err(ContactFailure::Singular);
            }
            let d = d.sqrt();
            h[j * ms + j] = d;
            for i in j + 1..ms {
                let mut v = h[i * ms + j];
                for p in 0..j {
                    v -= h[i * ms + p] * h[j * ms + p];
                }
                h[i * ms + j] = v / d;
            }
        }
        // G = H⁻¹, column by column (L Lᵀ x = e_j)
        let gi = &mut s.g_inv[..ms * ms];
        for j in 0..ms {
            for i in 0..ms {
                let mut v = if i == j { 1.0 } else { 0.0 };
                for p in 0..i {
                    v -= h[i * ms + p] * gi[p * ms + j];
                }
                gi[i * ms + j] = v / h[i * ms + i];
            }
            for i in (0..ms).rev() {
                let mut v = gi[i * ms + j];
                for p in i + 1..ms {
                    v -= h[p * ms + i] * gi[p * ms + j];
                }
                gi[i * ms + j] = v / h[i * ms + i];
            }
        }
        // the droppers' rows: g_S = −G k∘e_free, W_SS = G, W_Sc = κ G diag(k) P
        for (i, _) in s.set.iter().enumerate() {
            let row = nc + i;
            let mut gf = 0.0;
            for (j, &b) in s.set.iter().enumerate() {
                gf -= gi[i * ms + j] * k_of(b) * s.e_free[b];
                w[row * ns + nc + j] = gi[i * ms + j];
            }
            g[row] = gf;
            for c in 0..nc {
                let mut v = 0.0;
                for (j, &b) in s.set.iter().enumerate() {
                    v += gi[i * ms + j] * k_of(b) * s.p[b * nc + c];
                }
                w[row * ns + c] = kappa * v;
            }
        }
        // the contacts' rows: Y = Ê G; g_c = g'_c − Y k∘e_free,
        // W_cS = Y, W_cc = W'_cc + κ Y diag(k) P
        for c in 0..nc {
            for j in 0..ms {
                let mut v = 0.0;
                for (i, &a) in s.set.iter().enumerate() {
                    v += s.e_c[c * m + a] * k_of(a) * gi[i * ms + j];
                }
                s.y[c * ms + j] = v;
                w[c * ns + nc + j] = v;
            }
            let mut gf = s.g_c[c];
            for (j, &b) in s.set.iter().enumerate() {
                gf -= s.y[c * ms + j] * k_of(b) * s.e_free[b];
            }
            g[c] = gf;
            for c2 in 0..nc {
                let mut v = 0.0;
                for (j, &b) in s.set.iter().enumerate() {
                    v += s.y[c * ms + j] * k_of(b) * s.p[b * nc + c2];
                }
                w[c * ns + c2] = s.w_c[c * nc + c2] + kappa * v;
            }
        }
        Ok(ns)
    }

    /// After the law solved the pair of [`Droppers::assemble`] (`g`, `w`,
    /// stride `ns`) into `lambda`, `active` (ns each): the set's
    /// corrections μ_d = k_eff,d g_d (0 for a taut row), then the check of the
    /// droppers outside S (D10, [`Droppers::add_responses`]). Returns false when some of
    /// them pushed and joined S (assemble and solve again), true when the
    /// step settled: the forces, corrections and slack states are then the
    /// step's.
    pub(crate) fn settle(&mut self, g: &[f64], w: &[f64], lambda: &[f64], active: &[bool]) -> bool {
        let (nc, m, kappa) = (self.nc, self.rows(), self.coef);
        let ns = lambda.len();
        let s = &mut self.scratch;
        self.mu.fill(0.0);
        for (i, &a) in s.set.iter().enumerate() {
            let row = nc + i;
            if !active[row] {
                let gap: f64 = g[row] + (0..ns).map(|j| w[row * ns + j] * lambda[j]).sum::<f64>();
                self.mu[a] = self.keff[a] * gap;
            }
        }
        let tol = FORCE_ROUNDOFF * s.scale;
        let mut settled = true;
        for r in 0..m {
            if s.in_set[r] {
                continue;
            }
            let mut shift = 0.0;
            for c in 0..nc {
                shift += s.p[r * nc + c] * lambda[c];
            }
            for &a in &s.set {
                shift += self.q[r * m + a] * self.mu[a];
            }
            let force = self.keff[r] * (s.e_free[r] - kappa * shift);
            if force < -tol {
                settled = false;
                s.in_set[r] = true;
            } else {
                self.force[r] = force;
                self.slack[r] = false;
            }
        }
        if !settled {
            s.set.clear();
            s.set.extend((0..m).filter(|&r| s.in_set[r]));
            return false;
        }
        for (i, &a) in s.set.iter().enumerate() {
            self.force[a] = lambda[nc + i];
            self.slack[a] = !active[nc + i];
        }
        true
    }

    /// Add Σ μ_d z'_d of the slack droppers to column 0 of `solved` (k
    /// columns): the free solution becomes the solution with the dropper
    /// corrections, as the contacts' columns are added by the method's
    /// update.
    ///
    /// **Check (D10).** After the solve, each dropper outside S has
    /// N_d = k_d e_d; one below −[`FORCE_ROUNDOFF`] of the step's force scale
    /// joins S and the small problem is solved again (S only grows, so at
    /// most m + 1 passes). The free solution then gains Σ_S μ_d z'_d
    /// ([`Droppers::add_responses`]): a step costs O(n·(1 + |S|)) beyond the
    /// linear twin's, and the dense problem has nc + |S| rows. Nothing here
    /// allocates in a step.
    pub(crate) fn add_responses(&self, solved: &mut [f64], k: usize) {
        for (r, &mu) in self.mu.iter().enumerate() {
            if mu == 0.0 {
                continue;
            }
            for (row, z) in solved.chunks_exact_mut(k).zip(self.response(r)) {
                row[0] += mu * z;
            }
        }
    }

    /// Add coef·μ_d r_d of every slack dropper into lane `lane` of `y`
    /// (`lanes` interleaved runs): the corrections' part of a right-hand
    /// side.
    pub(crate) fn scatter_forces(&self, y: &mut [f64], lanes: usize, lane: usize, coef: f64) {
        for (r, &mu) in self.mu.iter().enumerate() {
            if mu != 0.0 {
                self.links[self.tension[r]].scatter(coef * mu, y, lanes, lane);
            }
        }
    }

    /// Each dropper's force and slack state, in scene order, into `out`:
    /// a tension-only one's from the last step, a linear one's
    /// k_d (e₀ − r_dᵀd) − c_d r_dᵀv (its dashpot's part, eq. D11, only when
    /// c_d ≠ 0), never slack.
    pub(crate) fn samples_into(&self, d: &[f64], v: &[f64], out: &mut [DropperSample]) {
        for (o, l) in out.iter_mut().zip(&self.links) {
            *o = match l.row {
                Some(r) => DropperSample {
                    force: self.force[r],
                    slack: self.slack[r],
                },
                None => {
                    let mut force = l.k * (l.e0 - l.dot(d));
                    if l.c != 0.0 {
                        force -= l.c * l.dot(v);
                    }
                    DropperSample {
                        force,
                        slack: false,
                    }
                }
            };
        }
    }
}
