//! Step 4 (module docs): every scalar result's own ladder fits from the
//! pilots and its estimated error at the chosen resolution.

use super::accuracy::{PilotRun, ResultEstimate};
use super::error_model::{
    ErrorModel, LadderFit, LadderStatus, MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT,
};
use crate::quantity::{Offer, Quantity, estimated};
use crate::run::RunOutput;

/// Every scalar result that gets an estimate, in print order: the
/// registry's quantities offered to `run --tolerance`
/// ([`Offer::TOLERANCE`]; names and units there), less any exact for its
/// discretization.
pub fn results() -> Vec<&'static Quantity> {
    estimated(Offer::TOLERANCE)
}

/// The values of [`results`] for one carrier of a run, in that order
/// (`None` where undefined, e.g. the first loss of a contact never lost).
pub fn result_values(out: &RunOutput, carrier: usize) -> Vec<Option<f64>> {
    crate::quantity::values(out, carrier, &results())
}

/// Per-result ladder fits from the pilots and estimates at (h, dt).
pub(super) fn estimate_results(
    pilots: &[PilotRun],
    chosen: &RunOutput,
    model: &ErrorModel,
    h: f64,
    dt: f64,
    h_fine: f64,
    dt_fine: f64,
) -> Vec<ResultEstimate> {
    let nc = chosen.stats.len();
    let mut out = Vec::new();
    for c in 0..nc {
        let at_pilots: Vec<Vec<Option<f64>>> =
            pilots.iter().map(|p| result_values(&p.output, c)).collect();
        let at_chosen = result_values(chosen, c);
        for (k, q) in results().iter().enumerate() {
            let (name, unit) = (q.name, q.unit);
            // the caps of a run whose contact switches: the method's own
            // order is not known here, and O(Δt) is the safe one
            let (mesh_cap, step_cap) = q
                .error
                .formal_orders(MAX_STEP_ORDER_CONTACT, true, false)
                .unwrap_or((MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT));
            let vals: Vec<Option<f64>> = at_pilots.iter().map(|v| v[k]).collect();
            let value = at_chosen[k];
            let defined = vals.iter().filter(|v| v.is_some()).count();
            if defined < vals.len() {
                out.push(ResultEstimate {
                    carrier: c,
                    name,
                    unit,
                    value,
                    estimated_error: None,
                    status: if defined == 0 {
                        "undefined".into()
                    } else {
                        "undefined at some pilots".into()
                    },
                    mesh: None,
                    step: None,
                });
                continue;
            }
            let v: Vec<f64> = vals.into_iter().flatten().collect();
            let scale = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let mesh = LadderFit::new(
                [(v[0] - v[1]).abs(), (v[1] - v[2]).abs()],
                h_fine,
                scale,
                mesh_cap,
            );
            let step = LadderFit::new(
                [(v[0] - v[3]).abs(), (v[3] - v[4]).abs()],
                dt_fine,
                scale,
                step_cap,
            );
            let (status, estimated_error) = match (mesh.usable(), step.usable()) {
                (true, true) => {
                    let m = ErrorModel {
                        mesh,
                        step,
                        safety_factor: model.safety_factor,
                    };
                    let exact =
                        mesh.status == LadderStatus::Exact && step.status == LadderStatus::Exact;
                    (
                        if exact { "exact" } else { "estimated" }.to_string(),
                        Some(m.estimate(h, dt).total),
                    )
                }
                (false, true) => ("not converging in h".to_string(), None),
                (true, false) => ("not converging in Δt".to_string(), None),
                (false, false) => ("not converging in h and Δt".to_string(), None),
            };
            out.push(ResultEstimate {
                carrier: c,
                name,
                unit,
                value,
                estimated_error,
                status,
                mesh: Some(mesh),
                step: Some(step),
            });
        }
    }
    out
}
