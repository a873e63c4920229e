//! The velocity-level law (MODEL §6, "an impact-capable velocity-level
//! variant"; MODEL §9.1, Moreau–Jean): Signorini–Newton on gap rates over
//! Moreau's index set,
//!
//! ```text
//!   for c with g_free,c ≤ 0 (every c when bilateral):
//!   0 ≤ ġ_{n+1,c} + e ġ_{n,c}  ⊥  λ_c ≥ 0,     ġ_{n+1} = ġ_free + W_v λ,
//! ```
//!
//! with e the coefficient of restitution (`contact.impact.restitution`).
//! The law owns what that needs beyond one step's numbers: the index set,
//! e, and the memory of the gap rates ġ_n of the step before. The rate
//! problem on the index set is solved by an inner rule on (g, W): Lagrange
//! for `contact.formulation = "impact"`, the scene's law (lagrange or
//! complementarity) for Moreau–Jean's impulses. The position gap is not
//! imposed: it drifts by O(Δt²) per step, and the largest penetration is
//! reported.
//!
//! The integrator forms the pairs — the position gaps g_free, and the gap
//! rates ġ_free with W_v of every contact (`integrate::contact_problem`) —
//! and hands them here; the law never reaches into a method.

use super::{ContactFailure, ContactLaw};

/// The velocity-level law (module docs).
pub(crate) struct Impact {
    /// The rule that solves the rate problem on the index set.
    rule: Box<dyn ContactLaw>,
    /// Coefficient of restitution e (0 ≤ e ≤ 1).
    restitution: f64,
    /// Bilateral contact: every contact is in the index set.
    bilateral: bool,
    /// Gap rates ġ_n of the last step, m/s.
    gap_rate: Vec<f64>,
    /// Moreau's index set: the contacts whose free step closes the gap.
    set: Vec<usize>,
    /// The problem on the index set: ġ_free + e ġ_n (m/s), W_v (row-major
    /// na × na), and the rule's impulses or forces and closed flags.
    red_g: Vec<f64>,
    red_w: Vec<f64>,
    red_l: Vec<f64>,
    red_a: Vec<bool>,
}

impl Impact {
    /// A law for `nc` contacts solving its rate problems with `rule`.
    pub(crate) fn new(
        rule: Box<dyn ContactLaw>,
        restitution: f64,
        bilateral: bool,
        nc: usize,
    ) -> Self {
        Impact {
            rule,
            restitution,
            bilateral,
            gap_rate: vec![0.0; nc],
            set: Vec::with_capacity(nc),
            red_g: vec![0.0; nc],
            red_w: vec![0.0; nc * nc],
            red_l: vec![0.0; nc],
            red_a: vec![false; nc],
        }
    }

    /// The acceleration-level problem at t = 0 (MODEL §5), by the rule.
    pub(crate) fn initial(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        self.rule.initial(g_free, w, lambda, active)
    }

    /// One step (module docs): `gaps` are the position-level free gaps
    /// (m), `rate_free` the free gap rates (m/s) and `w_v` the rate
    /// Delassus matrix (row-major nc × nc) of every contact. Writes the
    /// multipliers (zero off the index set) and the closed flags.
    ///
    /// A non-positive (or NaN) diagonal of W_v on the index set fails with
    /// [`ContactFailure::VelocityDelassus`] naming the contact and W; its
    /// `travel` and `h` are the kinematics' (the caller fills them in, zero
    /// here). On failure [`Impact::problem`] is the problem on the index set.
    pub(crate) fn solve(
        &mut self,
        gaps: &[f64],
        rate_free: &[f64],
        w_v: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        let nc = gaps.len();
        let e = self.restitution;
        self.set.clear();
        for (j, &g) in gaps.iter().enumerate() {
            if self.bilateral || g <= 0.0 {
                self.set.push(j);
            }
        }
        let na = self.set.len();
        for (r, &j) in self.set.iter().enumerate() {
            self.red_g[r] = rate_free[j] + e * self.gap_rate[j];
            for (rr, &jj) in self.set.iter().enumerate() {
                self.red_w[r * na + rr] = w_v[j * nc + jj];
            }
        }
        for (r, &j) in self.set.iter().enumerate() {
            let wv = self.red_w[r * na + r];
            if wv.is_nan() || wv <= 0.0 {
                return Err(ContactFailure::VelocityDelassus {
                    contact: j,
                    w: wv,
                    travel: 0.0,
                    h: 0.0,
                });
            }
        }
        self.rule.solve(
            &self.red_g[..na],
            &self.red_w[..na * na],
            &mut self.red_l[..na],
            &mut self.red_a[..na],
        )?;
        lambda.fill(0.0);
        active.fill(false);
        for (r, &j) in self.set.iter().enumerate() {
            lambda[j] = self.red_l[r];
            active[j] = self.red_a[r];
        }
        Ok(())
    }

    /// The problem last given to the rule (on the index set): the rates
    /// ġ_free + e ġ_n (m/s) and W_v (row-major).
    pub(crate) fn problem(&self) -> (&[f64], &[f64]) {
        let na = self.set.len();
        (&self.red_g[..na], &self.red_w[..na * na])
    }

    /// The memory of gap rates ġ_n (m/s, one per contact) that the next
    /// step's restitution term reads: the integrator writes ġ_{n+1} after
    /// each step.
    pub(crate) fn gap_rates_mut(&mut self) -> &mut [f64] {
        &mut self.gap_rate
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Lagrange;

    /// An approaching contact inside the index set stops with e·ġ_n
    /// rebound; an opening one outside it gets no impulse.
    #[test]
    fn restitution_acts_on_the_index_set_only() {
        let mut law = Impact::new(Box::new(Lagrange::new(false, 2)), 0.5, false, 2);
        law.gap_rates_mut().copy_from_slice(&[-2.0, -2.0]);
        let (mut l, mut a) = ([0.0; 2], [false; 2]);
        // contact 0 closes (g ≤ 0) approaching at −3 m/s; contact 1 is open
        let w_v = [0.5, 0.1, 0.1, 0.5];
        law.solve(&[-1e-6, 1e-3], &[-3.0, -3.0], &w_v, &mut l, &mut a)
            .unwrap();
        // ġ_{n+1} + e ġ_n = 0: −3 + 0.5 λ + 0.5·(−2) = 0
        assert!((l[0] - 8.0).abs() < 1e-12, "{l:?}");
        assert_eq!((l[1], a), (0.0, [true, false]));
        let (g, w) = law.problem();
        assert_eq!((g, w), (&[-4.0][..], &[0.5][..]));
    }

    /// A non-positive velocity Delassus number on the index set fails
    /// naming the contact.
    #[test]
    fn a_non_positive_rate_delassus_fails() {
        let mut law = Impact::new(Box::new(Lagrange::new(true, 1)), 0.0, true, 1);
        let (mut l, mut a) = ([0.0], [false]);
        let e = law.solve(&[1.0], &[-1.0], &[-0.25], &mut l, &mut a);
        assert!(
            matches!(e, Err(ContactFailure::VelocityDelassus { contact: 0, w, .. }) if w == -0.25),
            "{e:?}"
        );
    }
}
