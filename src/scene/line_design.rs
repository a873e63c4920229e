//! Design statics of a generated line (`[line]`, docs/lines.md eq. G3–G7):
//! the dropper forces that hold the contact wire in its pre-sag shape, and
//! the messenger's static sag under its weight and those forces. Both
//! wires are taken as **strings** (EI neglected): between two points where
//! it is held, a string of tension T under its weight w per length is a
//! parabola below the chord, so every force has a closed form. Plain
//! arithmetic, no model: the run's static start then finds the exact
//! equilibrium with EI and the droppers' and steady arms' springs.

/// A string: tension T (N) and weight per length w (N/m, downward; 0 when
/// the scene's self-weight is off).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StringLoad {
    /// Tension T, N (> 0).
    pub tension: f64,
    /// Weight per length w = ρA g, N/m (≥ 0).
    pub weight: f64,
}

/// A vertical spring to the rest line v = 0 (a steady arm) at x, N/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointSpring {
    /// Position x, m.
    pub x: f64,
    /// Stiffness k_s, N/m (≥ 0).
    pub stiffness: f64,
}

/// The forces N_d (N, up on the contact wire) that hold a string on
/// `[0, length]`, pinned at v = 0 at both ends, at heights `heights[d]` (m,
/// v up) at the points `xs[d]` (strictly increasing, inside the span), with
/// at most one of `springs` (rising in x) between two consecutive held
/// points (eq. G3–G4).
///
/// Each segment [a, b] (L = b − a, chord slope s = (v_b − v_a)/L) holding a
/// spring k_s at x_s with the wire at v_s pushes on its two ends with
///
/// ```text
///   (G3) R_a = −T s + w L/2 − F (b − x_s)/L,   R_b = T s + w L/2 − F (x_s − a)/L,
///        F = −k_s v_s (the spring's force, up)
///   (G4) v_s = v₀(x_s) / (1 + k_s G),   v₀(x) = v_a + s (x − a) − w (x − a)(b − x)/(2T),
///        G = (x_s − a)(b − x_s)/(T L)   (the segment's Green's function at x_s)
/// ```
///
/// and N_d is the sum of the two segments' pushes on x_d. The weight w L
/// of each segment is shared by its ends, the chord term T s is the kink the
/// pre-sag puts into the polygon (negative for a sag: the ends carry it).
pub fn dropper_forces(
    length: f64,
    xs: &[f64],
    heights: &[f64],
    wire: StringLoad,
    springs: &[PointSpring],
) -> Vec<f64> {
    let n = xs.len();
    let point = |i: usize| -> (f64, f64) {
        match i {
            0 => (0.0, 0.0),
            i if i == n + 1 => (length, 0.0),
            i => (xs[i - 1], heights[i - 1]),
        }
    };
    let mut forces = vec![0.0; n];
    for seg in 0..=n {
        let ((a, va), (b, vb)) = (point(seg), point(seg + 1));
        // the springs strictly inside (a, b) (`springs` rise in x; none
        // where a = b, as points of a span of 1e300 m can round to)
        let first = springs.partition_point(|sp| sp.x <= a);
        let inside = &springs[first..springs.partition_point(|sp| sp.x < b).max(first)];
        let (ra, rb) = segment_pushes(a, va, b, vb, wire, inside);
        if seg >= 1 {
            forces[seg - 1] += ra;
        }
        if seg < n {
            forces[seg] += rb;
        }
    }
    forces
}

/// The pushes (R_a, R_b) of one string segment on its two held ends (G3),
/// with the spring (if any) strictly inside it (G4).
fn segment_pushes(
    a: f64,
    va: f64,
    b: f64,
    vb: f64,
    wire: StringLoad,
    springs: &[PointSpring],
) -> (f64, f64) {
    let (t, w) = (wire.tension, wire.weight);
    let l = b - a;
    let s = (vb - va) / l;
    let mut ra = -t * s + w * l / 2.0;
    let mut rb = t * s + w * l / 2.0;
    for sp in springs.iter().filter(|sp| sp.x > a && sp.x < b) {
        let v0 = va + s * (sp.x - a) - w * (sp.x - a) * (b - sp.x) / (2.0 * t);
        let g = (sp.x - a) * (b - sp.x) / (t * l);
        let vs = v0 / (1.0 + sp.stiffness * g);
        let f = -sp.stiffness * vs;
        ra -= f * (b - sp.x) / l;
        rb -= f * (sp.x - a) / l;
    }
    (ra, rb)
}

/// The messenger's static displacement v_m(x) (m, up, from its support
/// line) between pinned supports at v_m = 0, under its weight and the
/// point loads `loads` = (x_d, N_d) pulling it down (eq. G5):
///
/// ```text
///   (G5) v_m(x) = −w_m (x − a)(b − x)/(2 T_m) − Σ_d N_d (x_< − a)(b − x_>)/(T_m (b − a))
/// ```
///
/// over the span [a, b] of `supports` that holds x (x_< = min(x, x_d),
/// x_> = max(x, x_d); only the loads inside that span count: the supports
/// are rigid). `x` at a support gives 0.
pub fn messenger_sag(supports: &[f64], messenger: StringLoad, loads: &[(f64, f64)], x: f64) -> f64 {
    let Some(k) = supports.windows(2).position(|s| x >= s[0] && x <= s[1]) else {
        return 0.0;
    };
    let (a, b) = (supports[k], supports[k + 1]);
    let (t, w) = (messenger.tension, messenger.weight);
    let mut v = -w * (x - a) * (b - x) / (2.0 * t);
    for &(xd, nd) in loads.iter().filter(|(xd, _)| *xd > a && *xd < b) {
        let (lo, hi) = (x.min(xd), x.max(xd));
        v -= nd * (lo - a) * (b - hi) / (t * (b - a));
    }
    v
}

/// The contact wire's pre-sag profile in a span of length S (eq. G2):
/// v_c = −4 p ξ (1 − ξ), ξ = x_local / S, p the sag at mid-span, m.
pub fn presag_profile(presag: f64, span: f64, x_local: f64) -> f64 {
    let xi = x_local / span;
    -4.0 * presag * xi * (1.0 - xi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Round-off of a few sums of O(1) terms.
    const ROUND_OFF: f64 = 1e-12;

    #[test]
    fn forces_balance_the_weight_with_the_end_pushes_and_springs() {
        // the sum of the droppers' forces, the two end pushes and the
        // springs' forces is the whole weight (each segment's loads balance)
        let wire = StringLoad {
            tension: 1000.0,
            weight: 10.0,
        };
        let xs = [2.5, 7.5, 12.5, 17.5];
        let vs = [-0.0075, -0.004, -0.0075, -0.001];
        let springs = [PointSpring {
            x: 10.0,
            stiffness: 1000.0,
        }];
        let n = dropper_forces(20.0, &xs, &vs, wire, &springs);
        let (r0, _) = segment_pushes(0.0, 0.0, 2.5, vs[0], wire, &[]);
        let (_, r1) = segment_pushes(17.5, vs[3], 20.0, 0.0, wire, &[]);
        let v0 = vs[1] + (vs[2] - vs[1]) * 0.5 - 10.0 * 2.5 * 2.5 / 2000.0;
        let vs_spring = v0 / (1.0 + 1000.0 * 2.5 * 2.5 / 5000.0);
        let total = n.iter().sum::<f64>() + r0 + r1 - 1000.0 * vs_spring;
        assert!((total - 200.0).abs() < ROUND_OFF * 200.0, "{total}");
    }

    #[test]
    fn a_flat_wire_without_springs_hangs_by_its_tributary_weight() {
        let wire = StringLoad {
            tension: 1000.0,
            weight: 10.0,
        };
        let n = dropper_forces(10.0, &[2.0, 5.0], &[0.0, 0.0], wire, &[]);
        assert!((n[0] - 10.0 * 2.5).abs() < ROUND_OFF * 25.0);
        assert!((n[1] - 10.0 * 4.0).abs() < ROUND_OFF * 40.0);
    }

    #[test]
    fn messenger_sag_is_zero_at_supports_and_the_string_parabola_without_loads() {
        let m = StringLoad {
            tension: 2000.0,
            weight: 5.0,
        };
        assert_eq!(messenger_sag(&[0.0, 10.0], m, &[], 0.0), 0.0);
        assert_eq!(messenger_sag(&[0.0, 10.0], m, &[(5.0, 3.0)], 10.0), 0.0);
        let mid = messenger_sag(&[0.0, 10.0], m, &[], 5.0);
        assert!((mid + 5.0 * 100.0 / (8.0 * 2000.0)).abs() < ROUND_OFF);
    }
}
