//! A row from a ladder's measurements and its expectation: orders, the
//! dominance check and the status.

use super::DOMINANCE_LIMIT;
use super::case::{Expect, Ladder, Quantity, Variable};
use super::measure::Measured;
use super::row::{Status, VerifyRow};
use crate::study::uncertainty::observed_order;
/// Fill a row from a ladder's measurements and its expectation.
pub(super) fn judge(row: &mut VerifyRow, m: &Measured, q: Quantity, e: Expect, ladder: &Ladder) {
    let (errors, refined, scale) = match q {
        Quantity::Displacement => (&m.displacement, m.refined.0, m.scale.0),
        Quantity::Force => (&m.force, m.refined.1, m.scale.1),
    };
    row.levels = m.levels.clone();
    row.errors = errors.clone();
    row.runs = m.runs;
    row.omega_max_dt = m.omega_max_dt;
    if let (Some(&a), Some(&b)) = (m.levels.first(), m.levels.last()) {
        row.range = (a, b);
    }
    let r = 2.0;
    row.orders = errors
        .windows(2)
        .map(|w| observed_order(w[0], w[1], r))
        .collect();
    let k = errors.len();
    if k >= 2 {
        row.observed = observed_order(errors[0], errors[k - 1], r.powi(k as i32 - 1));
        row.relative_error = errors[k - 1] / scale.max(f64::MIN_POSITIVE);
        row.other_share = (errors[k - 1] - refined).abs() / errors[k - 1];
    }
    let measured_ok = m.failed.is_none() && k == ladder.levels;
    let e = match e {
        Expect::ModalTail { tol } => match &m.tail {
            Some(t) if t.len() >= 2 && m.failed.is_none() => Expect::Order {
                order: observed_order(t[0], t[t.len() - 1], r.powi(t.len() as i32 - 1)),
                tol,
            },
            _ => Expect::Report(
                "the order of v*'s modal tail could not be computed for this basis".into(),
            ),
        },
        e => e,
    };
    match e {
        Expect::ModalTail { .. } => unreachable!("replaced above"),
        Expect::Order { order, tol } => {
            row.expected = order;
            row.tolerance = tol;
            if let Some(f) = &m.failed {
                row.status = Status::Fail;
                row.note = format!("a run failed: {f}");
            } else if !measured_ok || !row.observed.is_finite() {
                row.status = Status::Fail;
                row.note = "no order: an error is zero or not finite".into();
            } else if (row.observed - order).abs() > tol {
                row.status = Status::Fail;
                row.note = format!(
                    "observed order {:.2} is outside {order} ± {tol}",
                    row.observed
                );
            } else if row.other_share.is_nan() || row.other_share > DOMINANCE_LIMIT {
                row.status = Status::Fail;
                row.note = format!(
                    "the fixed variables ({}) make {:.0} % of the finest error (limit {:.0} %): the order is not the refined variable's",
                    match ladder.variable {
                        Variable::Dt => "the mesh",
                        _ => "Δt",
                    },
                    100.0 * row.other_share,
                    100.0 * DOMINANCE_LIMIT
                );
            } else {
                row.status = Status::Pass;
            }
        }
        Expect::Known { order, why } => {
            row.expected = order;
            row.status = Status::Known;
            row.note = match &m.failed {
                Some(f) => format!("{why} (a run failed: {f})"),
                None => why,
            };
        }
        Expect::Cannot(why) => {
            row.status = Status::Cannot;
            row.note = match &m.failed {
                Some(f) => format!("{why} (a run failed: {f})"),
                None => why,
            };
        }
        Expect::Report(why) => {
            row.status = Status::Reported;
            row.note = match &m.failed {
                Some(f) => format!("{why} (a run failed: {f})"),
                None => why,
            };
        }
    }
}
