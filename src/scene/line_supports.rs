//! Elastic messenger supports of a generated line (`[line]`
//! `messenger.support`, `docs/lines.md` eq. E2): the key's spelling in
//! `[line]`, and the supports' settlement in the design statics.
//!
//! `line.messenger.support = { stiffness, damping, mass }` makes every
//! **interior** support elastic (the line's two ends, its anchors, stay
//! pinned, as its steady arms sit at the interior supports only); a list
//! gives each of the spans + 1 supports, `"pinned"` or `{ … }`, as
//! `[messenger] support` does (`super::messenger_support`). The expansion
//! writes the list into `[messenger] support`.
//!
//! **Settlement (E2).** The messenger designed as a string (G5) on rigid
//! supports pushes each support with R⁰_k (its weight's and droppers'
//! shares of the two spans beside it). On a spring k_s the support sinks
//! by δ_k, and the string between two supports tilts with them, so the
//! support's balance couples its neighbours:
//!
//! ```text
//!   (E2) (k_s,k + T_m/S_l + T_m/S_r) δ_k − (T_m/S_l) δ_{k−1} − (T_m/S_r) δ_{k+1} = −R⁰_k
//!         (δ = 0 at a pinned support; S_l, S_r the spans beside k, absent at an end)
//!   v_m(x) = G5's v_m(x) + δ_a + (δ_b − δ_a)(x − a)/(b − a)   on the span [a, b]
//! ```
//!
//! a tridiagonal system, strictly diagonally dominant (k_s > 0), solved
//! once. The droppers' lengths (G6) then include δ, so the static start
//! puts the contact wire at its design height with the supports settled
//! (exactly for strings, `tests/line.rs`).

use toml::Value;

use super::line_design::StringLoad;
use super::messenger_support::{ElasticSupport, resolve_support};
use crate::error::Result;

/// `line.messenger.support` as the `[messenger] support` list to write
/// (`None`: every support pinned, nothing written) and each support's
/// kind, for a line of `spans` spans (module docs).
pub(crate) fn line_supports(
    v: Option<&Value>,
    spans: usize,
) -> Result<(Option<Value>, Vec<Option<ElasticSupport>>)> {
    let field = "line.messenger.support";
    let list = match v {
        None => return Ok((None, vec![None; spans + 1])),
        Some(t @ Value::Table(_)) => {
            let pinned = Value::String("pinned".into());
            let mut list = vec![pinned.clone()];
            list.extend(std::iter::repeat_n(t.clone(), spans - 1));
            list.push(pinned);
            // checked as the one table it is, so an error names its keys
            resolve_support(field, Some(t), 1)?;
            Value::Array(list)
        }
        Some(other) => other.clone(),
    };
    let kinds = resolve_support(field, Some(&list), spans + 1)?;
    if kinds.iter().all(Option::is_none) {
        return Ok((None, kinds));
    }
    Ok((Some(list), kinds))
}

/// Each support's settlement δ_k, m (v up; 0 where pinned), of the
/// messenger string `messenger` on `supports` (rising; `kinds` one per
/// support) under its weight and the dropper loads `loads` = (x_d, N_d)
/// pulling it down (eq. E2, module docs).
pub(crate) fn settlements(
    supports: &[f64],
    kinds: &[Option<ElasticSupport>],
    messenger: StringLoad,
    loads: &[(f64, f64)],
) -> Vec<f64> {
    let n = supports.len();
    let (t, w) = (messenger.tension, messenger.weight);
    // R⁰_k: each span's weight and loads shared by its two supports
    let mut r0 = vec![0.0; n];
    for k in 0..n.saturating_sub(1) {
        let (a, b) = (supports[k], supports[k + 1]);
        let l = b - a;
        r0[k] += w * l / 2.0;
        r0[k + 1] += w * l / 2.0;
        for &(xd, nd) in loads.iter().filter(|(xd, _)| *xd > a && *xd < b) {
            r0[k] += nd * (b - xd) / l;
            r0[k + 1] += nd * (xd - a) / l;
        }
    }
    // the tridiagonal rows (lower, diagonal, upper, right side)
    let mut lower = vec![0.0; n];
    let mut diag = vec![1.0; n];
    let mut upper = vec![0.0; n];
    let mut rhs = vec![0.0; n];
    for k in 0..n {
        let Some(s) = kinds[k] else { continue };
        diag[k] = s.stiffness;
        if k > 0 {
            let c = t / (supports[k] - supports[k - 1]);
            diag[k] += c;
            lower[k] = -c;
        }
        if k + 1 < n {
            let c = t / (supports[k + 1] - supports[k]);
            diag[k] += c;
            upper[k] = -c;
        }
        rhs[k] = -r0[k];
    }
    // Thomas: forward elimination, back substitution (diagonally dominant)
    for k in 1..n {
        let f = lower[k] / diag[k - 1];
        diag[k] -= f * upper[k - 1];
        rhs[k] -= f * rhs[k - 1];
    }
    let mut delta = vec![0.0; n];
    for k in (0..n).rev() {
        let next = if k + 1 < n {
            upper[k] * delta[k + 1]
        } else {
            0.0
        };
        delta[k] = (rhs[k] - next) / diag[k];
    }
    delta
}

/// The settlements' part of v_m at x on the span [a, b] whose supports
/// sank by δ_a, δ_b (E2): their chord.
pub(crate) fn chord(x: f64, (a, b): (f64, f64), (da, db): (f64, f64)) -> f64 {
    da + (db - da) * (x - a) / (b - a)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sums of a few exact decimal terms: round-off.
    const HAND: f64 = 1e-12;

    #[test]
    fn two_spans_on_a_middle_spring_by_hand() {
        // supports 0, 10, 20 (ends pinned), k_s = 1000 N/m in the middle,
        // T_m = 2000 N, w = 5 N/m, a 40 N dropper at 5 m: R⁰ = 25 + 25 + 20
        // at the middle; (k_s + 2 T/S) δ = −R⁰ → δ = −70/1400 = −0.05 m
        let s = ElasticSupport {
            stiffness: 1000.0,
            damping: 0.0,
            mass: 0.0,
        };
        let d = settlements(
            &[0.0, 10.0, 20.0],
            &[None, Some(s), None],
            StringLoad {
                tension: 2000.0,
                weight: 5.0,
            },
            &[(5.0, 40.0)],
        );
        assert_eq!(d[0], 0.0);
        assert_eq!(d[2], 0.0);
        assert!((d[1] + 0.05).abs() < HAND, "{d:?}");
        // the string's balance at the support: spring force −k δ equals the
        // rigid reaction plus the chords' tilt T(δ_k − δ_j)/S on each side
        let tilt = 2.0 * 2000.0 * d[1] / 10.0;
        assert!((-1000.0 * d[1] - (70.0 + tilt)).abs() < HAND * 70.0);
        assert!((chord(15.0, (10.0, 20.0), (d[1], d[2])) + 0.025).abs() < HAND);
    }

    #[test]
    fn the_line_key_makes_the_interior_supports_elastic() {
        let t: toml::Table = toml::from_str("s = { stiffness = 5e5, mass = 2.0 }").unwrap();
        let (list, kinds) = line_supports(Some(&t["s"]), 3).unwrap();
        assert_eq!(kinds.len(), 4);
        assert!(kinds[0].is_none() && kinds[3].is_none());
        assert!(kinds[1].is_some() && kinds[2].is_some());
        let list = list.unwrap();
        assert_eq!(list.as_array().unwrap()[0].as_str(), Some("pinned"));
        // one span: no interior support, nothing written
        assert!(line_supports(Some(&t["s"]), 1).unwrap().0.is_none());
        let bad: toml::Table = toml::from_str("s = { stiffness = -1.0 }").unwrap();
        let e = line_supports(Some(&bad["s"]), 3).unwrap_err().to_string();
        assert!(
            e.contains("line.messenger.support.stiffness") && e.contains("-1"),
            "{e}"
        );
    }
}
