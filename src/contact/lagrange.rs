//! The Lagrange-multiplier formulation (MODEL §6): exact constraint g = 0 on
//! the active contacts, with an active set for unilateral contact (loss and
//! reattachment) and none for bilateral contact.

use super::dense::solve_in_place;
use super::{ContactFailure, ContactLaw};

/// Most active-set changes tried in one step before giving up. Each pass adds
/// or drops one contact; with nc contacts a non-cycling search needs at most
/// a few passes per contact.
const MAX_ACTIVE_SET_PASSES: usize = 64;

/// Relative gap tolerance when checking a trial active set: round-off of
/// g = g_free + Wλ, scaled by |g_free|.
const GAP_ROUNDOFF: f64 = 1e-12;

/// Lagrange multipliers, with preallocated scratch for several contacts.
pub(crate) struct Lagrange {
    bilateral: bool,
    /// Reduced matrix W_AA (row-major, up to nc×nc).
    waa: Vec<f64>,
    /// Reduced right-hand side / solution.
    rhs: Vec<f64>,
    /// Indices of the active contacts.
    set: Vec<usize>,
}

impl Lagrange {
    /// A law for `nc` contacts.
    pub(crate) fn new(bilateral: bool, nc: usize) -> Self {
        Lagrange {
            bilateral,
            waa: vec![0.0; nc * nc],
            rhs: vec![0.0; nc],
            set: Vec::with_capacity(nc),
        }
    }

    /// λ_A = −W_AA⁻¹ g_A for the current set; others 0.
    fn solve_set(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
    ) -> Result<(), ContactFailure> {
        let nc = g_free.len();
        let na = self.set.len();
        for (r, &i) in self.set.iter().enumerate() {
            for (c, &j) in self.set.iter().enumerate() {
                self.waa[r * na + c] = w[i * nc + j];
            }
            self.rhs[r] = -g_free[i];
        }
        if !solve_in_place(na, &mut self.waa[..na * na], &mut self.rhs[..na]) {
            return Err(ContactFailure::Singular);
        }
        lambda.fill(0.0);
        for (r, &i) in self.set.iter().enumerate() {
            lambda[i] = self.rhs[r];
        }
        Ok(())
    }
}

impl ContactLaw for Lagrange {
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        let nc = g_free.len();
        if self.bilateral {
            self.set.clear();
            self.set.extend(0..nc);
            active.fill(true);
            return self.solve_set(g_free, w, lambda);
        }
        if nc == 1 {
            // One contact: closed iff the free step penetrates; then λ = −g/W ≥ 0.
            let closed = g_free[0] < 0.0;
            active[0] = closed;
            lambda[0] = if closed { -g_free[0] / w[0] } else { 0.0 };
            return if w[0] > 0.0 || !closed {
                Ok(())
            } else {
                Err(ContactFailure::NotPositive {
                    contact: 0,
                    w: w[0],
                })
            };
        }
        // Several contacts: start from the penetrating ones, then drop the most
        // negative force or add the most penetrating open contact, one at a time.
        let scale = g_free.iter().fold(0.0f64, |m, g| m.max(g.abs()));
        let tol = GAP_ROUNDOFF * scale;
        self.set.clear();
        self.set.extend((0..nc).filter(|&i| g_free[i] < 0.0));
        for _ in 0..MAX_ACTIVE_SET_PASSES {
            self.solve_set(g_free, w, lambda)?;
            // most negative multiplier among the active
            let drop = self
                .set
                .iter()
                .enumerate()
                .filter(|&(_, &i)| lambda[i] < 0.0)
                .min_by(|a, b| lambda[*a.1].total_cmp(&lambda[*b.1]))
                .map(|(r, _)| r);
            if let Some(r) = drop {
                self.set.remove(r);
                continue;
            }
            // most penetrating among the open
            let mut add = None;
            let mut worst = -tol;
            for i in 0..nc {
                if self.set.contains(&i) {
                    continue;
                }
                let g: f64 = g_free[i] + (0..nc).map(|j| w[i * nc + j] * lambda[j]).sum::<f64>();
                if g < worst {
                    worst = g;
                    add = Some(i);
                }
            }
            match add {
                Some(i) => {
                    let pos = self.set.partition_point(|&j| j < i);
                    self.set.insert(pos, i);
                }
                None => {
                    for (i, a) in active.iter_mut().enumerate() {
                        *a = self.set.contains(&i);
                    }
                    return Ok(());
                }
            }
        }
        Err(ContactFailure::Cycling {
            passes: MAX_ACTIVE_SET_PASSES,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_contact_closes_only_when_penetrating() {
        let mut law = Lagrange::new(false, 1);
        let (mut l, mut a) = ([0.0], [false]);
        law.solve(&[-2e-3], &[1e-4], &mut l, &mut a).unwrap();
        assert!(a[0]);
        assert!((l[0] - 20.0).abs() < 1e-12);
        law.solve(&[1e-3], &[1e-4], &mut l, &mut a).unwrap();
        assert!(!a[0]);
        assert_eq!(l[0], 0.0);
    }

    #[test]
    fn bilateral_pulls_as_well_as_pushes() {
        let mut law = Lagrange::new(true, 1);
        let (mut l, mut a) = ([0.0], [false]);
        law.solve(&[1e-3], &[1e-4], &mut l, &mut a).unwrap();
        assert!((l[0] + 10.0).abs() < 1e-12);
    }

    #[test]
    fn two_contacts_satisfy_signorini() {
        // contact 1 would penetrate alone, but pushing contact 0 lifts it
        let w = [2.0, 1.5, 1.5, 2.0];
        let g = [-1.0, -0.5];
        let mut law = Lagrange::new(false, 2);
        let (mut l, mut a) = ([0.0; 2], [false; 2]);
        law.solve(&g, &w, &mut l, &mut a).unwrap();
        for i in 0..2 {
            let gi = g[i] + w[i * 2] * l[0] + w[i * 2 + 1] * l[1];
            assert!(
                l[i] >= 0.0 && gi >= -1e-12 && (l[i] * gi).abs() < 1e-12,
                "{l:?}"
            );
        }
        assert_eq!(a, [true, false]);
    }
}
