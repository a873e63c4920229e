//! Droppers during a run (MODEL §10, `docs/lines.md` eq. D1–D6): the
//! tension-only ones as rows of the step's contact problem, the linear
//! ones as their constant preload (their spring is an attachment in K,
//! `resolve::dropper`).
//!
//! A tension-only dropper d at x_d pulls the beam up with N_d ≥ 0 along
//! r_d = r_b(x_d) (MODEL §4); one hanging from the messenger wire pulls
//! the contact wire up and the messenger down along r_d = r_b(x_d) −
//! r_m(x_d) (`docs/lines.md` eq. W2), and everything below holds with
//! that r_d. Its compliant unilateral law (D3) is the
//! complementarity problem
//!
//! ```text
//!   0 ≤ N_d  ⊥  g_d = N_d/k_d − e_d ≥ 0,     e_d = e₀,d − r_dᵀ d
//! ```
//!
//! (tension N_d = k_d e_d when stretched, N_d = 0 with e_d ≤ 0 when slack),
//! the same shape as a contact's (MODEL §6) with the compliance 1/k_d on
//! W's diagonal. It is imposed at the generalized-α force level,
//! d_{n+1−α_f} = (1 − α_f) d_{n+1} + α_f d_n, where the method's K acts
//! (MODEL §5): a dropper that stays stretched is then exactly the spring
//! k_d r_d r_dᵀ of K with its preload (a linear dropper), whatever the
//! contacts' `placement`. With d_{n+1} = d̃ + c_d (u★ + Σ λ_j z_j), the
//! row is affine in the multipliers (D5):
//!
//! ```text
//!   g_d = g_free,d + Σ_j W_dj λ_j,
//!   g_free,d = r_dᵀ[(1 − α_f)(d̃ + c_d u★) + α_f d_n] − e₀,d
//!   W_dj = (1 − α_f) c_d r_dᵀ z_j  (+ 1/k_d when j = d)
//! ```
//!
//! Droppers do not move, so z_d = A⁻¹ r_d and the dropper block of W are
//! formed once per run ([`Droppers::prepare`], by the method that owns A);
//! a step adds Σ N_d z_d of the stretched droppers to the free solution
//! (O(n) per dropper, no solve) and reads the contacts' rows against z_d
//! through their four-entry point vectors. Nothing here allocates in a step.

use crate::model::beam::{BeamModel, PointVector};
use crate::scene::Dropper;

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

/// The run's droppers, in scene order (module docs).
#[derive(Debug, Clone, Default)]
pub(crate) struct Droppers {
    links: Vec<Link>,
    /// Tension-only droppers (rows of the problem after the contacts).
    rows: usize,
    /// Beam unknowns n.
    n: usize,
    /// z_d = A⁻¹ r_d of each row, row d at `z[d·n..(d+1)·n]`.
    z: Vec<f64>,
    /// The constant dropper block of W, rows × rows, row-major.
    w_dd: Vec<f64>,
    /// α: the weight of d_n in the dropper rows (α_f).
    weight: f64,
    /// (1 − α) c_d.
    coef: f64,
    /// True once a method formed z and the block ([`Droppers::prepare`]).
    ready: bool,
}

impl Droppers {
    /// The droppers of a scene on `beam` (their point vectors formed once).
    pub(crate) fn new(droppers: &[Dropper], beam: &BeamModel) -> Self {
        let mut rows = 0;
        let links = droppers
            .iter()
            .map(|d| {
                let row = (!d.linear).then(|| {
                    rows += 1;
                    rows - 1
                });
                Link {
                    pv: beam.point_vector(d.x),
                    pm: d.on_messenger().then(|| beam.messenger_point_vector(d.x)),
                    k: d.stiffness,
                    e0: d.rest_extension(),
                    row,
                }
            })
            .collect();
        Droppers {
            links,
            rows,
            n: beam.n,
            ..Droppers::default()
        }
    }

    /// Tension-only droppers: the problem's rows after the contacts.
    pub(crate) fn rows(&self) -> usize {
        self.rows
    }

    /// All droppers.
    pub(crate) fn len(&self) -> usize {
        self.links.len()
    }

    /// True when the method formed what the rows need (always, without them).
    pub(crate) fn ready(&self) -> bool {
        self.rows == 0 || self.ready
    }

    /// Add the linear droppers' preloads k_d e₀ r_d (up) to the beam's
    /// constant load `load` (D2).
    pub(crate) fn add_preloads(&self, load: &mut [f64]) {
        for l in self.links.iter().filter(|l| l.row.is_none()) {
            l.scatter(l.k * l.e0, load, 1, 0);
        }
    }

    /// The initial forces (t = 0, wire at `d0`: straight at rest, or the
    /// static start): N_d = k_d max(e₀ − r_dᵀd₀, 0) of each row into
    /// `n_out`, and each one's direction scaled by it into column 0 of
    /// `rhs` (k columns), a known load of the initial acceleration problem.
    /// `d0 = None` is the straight wire (N_d = k_d max(e₀, 0)).
    pub(crate) fn initial(&self, d0: Option<&[f64]>, n_out: &mut [f64], rhs: &mut [f64], k: usize) {
        for l in &self.links {
            let Some(r) = l.row else { continue };
            let e = match d0 {
                None => l.e0,
                Some(d) => l.e0 - l.dot(d),
            };
            n_out[r] = l.k * e.max(0.0);
            l.scatter(n_out[r], rhs, k, 0);
        }
    }

    /// The static start's operator and load (`docs/lines.md` eq. W6): every
    /// tension-only dropper taken taut, k_d r_d r_dᵀ into `k` and its
    /// k_d e₀ r_d into `f` (a linear dropper's are already in K and the
    /// load).
    pub(crate) fn add_taut(&self, k: &mut crate::model::banded::SymBand, f: &mut [f64]) {
        for l in self.links.iter().filter(|l| l.row.is_some()) {
            let mut entries: Vec<(usize, f64)> = Vec::with_capacity(8);
            for (i, v) in l.pv.idx.iter().zip(l.pv.val) {
                entries.push((*i, v));
            }
            if let Some(pm) = &l.pm {
                for (i, v) in pm.idx.iter().zip(pm.val) {
                    entries.push((*i, -v));
                }
            }
            for &(i, vi) in &entries {
                for &(j, vj) in &entries {
                    if vi != 0.0 && vj != 0.0 {
                        k.add_entry(i, j, l.k * vi * vj);
                    }
                }
            }
            l.scatter(l.k * l.e0, f, 1, 0);
        }
    }

    /// The force k_d (e₀ − r_dᵀd) of each tension-only dropper at `d`, in
    /// scene order with its index (the static start's check that each is
    /// taut).
    pub(crate) fn taut_forces<'a>(
        &'a self,
        d: &'a [f64],
    ) -> impl Iterator<Item = (usize, f64)> + 'a {
        self.links
            .iter()
            .enumerate()
            .filter(|(_, l)| l.row.is_some())
            .map(move |(i, l)| (i, l.k * (l.e0 - l.dot(d))))
    }

    /// Form z_d = A⁻¹ r_d and the dropper block of W once (module docs),
    /// for a method with constant A: `solve` overwrites a right-hand side
    /// with A⁻¹ of it; `c_d` as in d_{n+1} = d̃ + c_d u; `weight` = α_f.
    pub(crate) fn prepare(&mut self, solve: impl Fn(&mut [f64]), c_d: f64, weight: f64) {
        let (n, m) = (self.n, self.rows);
        self.z = vec![0.0; n * m];
        for l in &self.links {
            let Some(r) = l.row else { continue };
            let z = &mut self.z[r * n..(r + 1) * n];
            l.scatter(1.0, z, 1, 0);
            solve(z);
        }
        self.weight = weight;
        self.coef = (1.0 - weight) * c_d;
        self.w_dd = vec![0.0; m * m];
        for a in &self.links {
            let Some(i) = a.row else { continue };
            for b in &self.links {
                let Some(j) = b.row else { continue };
                let mut w = self.coef * a.dot(&self.z[j * n..(j + 1) * n]);
                if i == j {
                    w += 1.0 / a.k;
                }
                self.w_dd[i * m + j] = w;
            }
        }
        self.ready = true;
    }

    /// z_d of row `r`.
    pub(crate) fn response(&self, r: usize) -> &[f64] {
        &self.z[r * self.n..(r + 1) * self.n]
    }

    /// The dropper rows of a step's problem (module docs, D5), into `g_free`
    /// and `w` (stride `nt` = contacts + rows, rows after the `nc`
    /// contacts): the free extension's row from d̃, the free solution
    /// (column 0 of `solved`, k columns) and d_n; the columns against the
    /// contacts from their responses (columns 1 + j).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn fill_rows(
        &self,
        nc: usize,
        (solved, k): (&[f64], usize),
        c_d: f64,
        d_pred: &[f64],
        d_n: &[f64],
        g_free: &mut [f64],
        w: &mut [f64],
    ) {
        let (nt, m, a) = (nc + self.rows, self.rows, self.weight);
        for l in &self.links {
            let Some(r) = l.row else { continue };
            let i = nc + r;
            let end = l.dot(d_pred) + c_d * l.dot_strided(solved, k, 0);
            g_free[i] = (1.0 - a) * end + a * l.dot(d_n) - l.e0;
            for j in 0..nc {
                w[i * nt + j] = self.coef * l.dot_strided(solved, k, 1 + j);
            }
            w[i * nt + nc..i * nt + nt].copy_from_slice(&self.w_dd[r * m..(r + 1) * m]);
        }
    }

    /// Add Σ N_d z_d of the stretched droppers (`forces`, one per row, N)
    /// to column 0 of `solved` (k columns): the free solution becomes the
    /// solution with the dropper forces, as the contacts' columns are
    /// added by the method's update.
    pub(crate) fn add_responses(&self, forces: &[f64], solved: &mut [f64], k: usize) {
        for (r, &f) in forces.iter().enumerate() {
            if f == 0.0 {
                continue;
            }
            for (row, z) in solved.chunks_exact_mut(k).zip(self.response(r)) {
                row[0] += f * z;
            }
        }
    }

    /// Add coef·N_d r_d of every row (`forces`) into lane `lane` of `y`
    /// (`lanes` interleaved runs).
    pub(crate) fn scatter_forces(
        &self,
        forces: &[f64],
        y: &mut [f64],
        lanes: usize,
        lane: usize,
        coef: f64,
    ) {
        for l in &self.links {
            let Some(r) = l.row else { continue };
            l.scatter(coef * forces[r], y, lanes, lane);
        }
    }

    /// Each dropper's force and slack state, in scene order, into `out`:
    /// a tension-only one's multiplier (`forces`, one per row) and open
    /// row (`active` false), a linear one's k_d (e₀ − r_dᵀd), never slack.
    pub(crate) fn samples_into(
        &self,
        (forces, active): (&[f64], &[bool]),
        d: &[f64],
        out: &mut [DropperSample],
    ) {
        for (o, l) in out.iter_mut().zip(&self.links) {
            *o = match l.row {
                Some(r) => DropperSample {
                    force: forces[r],
                    slack: !active[r],
                },
                None => DropperSample {
                    force: l.k * (l.e0 - l.dot(d)),
                    slack: false,
                },
            };
        }
    }
}

impl Droppers {
    /// The contacts' columns against the droppers (module docs):
    /// W_{i,nc+d} = coef·s_i r_iᵀ z_d for each contact row `(i, s_i, r_i)`
    /// (the gap row at the contacts' placement, `coef` its coefficient),
    /// stride nt = nc + rows.
    pub(crate) fn fill_contact_columns<'a>(
        &self,
        contacts: impl Iterator<Item = (usize, f64, &'a PointVector)>,
        coef: f64,
        nc: usize,
        w: &mut [f64],
    ) {
        let nt = nc + self.rows;
        for (i, s, pv) in contacts {
            for r in 0..self.rows {
                w[i * nt + nc + r] = coef * s * pv.dot(self.response(r));
            }
        }
    }
}
