//! The rows of `converge.csv`: one per level and quantity, and how a
//! study's runs become them (errors, orders, GCI, regime).

use serde::Serialize;

use super::regime::{Context, ratio_change, regime};
use crate::resolve::Resolved;
use crate::run::RunOutput;

use crate::study::grid::{GCI_SAFETY_FACTOR, observed_order, resample};
use crate::study::scalars::Scalar;
/// One row of `converge.csv`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ConvergeRow {
    /// Time integrator.
    pub method: String,
    /// Space discretization (`mesh.kind`).
    pub discretization: String,
    /// Level ℓ (0 = coarsest).
    pub level: usize,
    /// The length the discretization resolves, m: the element length h
    /// (the longest of a graded mesh), L/J for a modal basis
    /// ([`Resolved::resolution`]).
    pub h: f64,
    /// Modes J of a modal basis (the level parameter of `galerkin` and
    /// `modal`); `None` for elements.
    pub modes: Option<usize>,
    /// Time step, s.
    pub dt: f64,
    /// Quantity name.
    pub quantity: String,
    /// Value at this level (scalar, or norm of the history).
    pub value: f64,
    /// Error against the reference (analytic or Richardson); NaN when unknown.
    pub error: f64,
    /// Observed order at this level; NaN when not yet defined.
    pub observed_order: f64,
    /// Grid convergence index (relative); NaN when not defined.
    pub gci: f64,
    /// What `error` is against: the scene's declared reference
    /// (`manufactured`, `moving_force_series`, `riding_mass_galerkin`,
    /// `standing_force_modes`), else `richardson`, or `finest` when no
    /// order could be observed for an extrapolation.
    pub reference: String,
    /// Order of `error` between levels ℓ−1 and ℓ, against an exact
    /// reference only (NaN for `richardson` and `finest`, whose error is
    /// built from the same runs).
    pub error_order: f64,
    /// Ratio of successive error ratios (e_{ℓ−2}/e_{ℓ−1})/(e_{ℓ−1}/e_ℓ),
    /// from the errors against an exact reference, else from successive
    /// differences: 1 in the asymptotic range (`ORDER_DRIFT`).
    pub ratio_change: f64,
    /// The formal order of the displacement in the refined variable
    /// (Δt: the method's; h: Hermite 4, string elements 2; `both`: the
    /// smaller), NaN when unknown (a modal basis's J, other quantities).
    pub formal_order: f64,
    /// `asymptotic`, `pre-asymptotic`, `limited by …` (the error against
    /// an exact reference does not fall with the refined variable),
    /// `growing: round-off or an instability` (it rises as the refined
    /// variable falls), `not converging` (successive differences do not
    /// fall, or rise), `exact`, or empty before a level can tell
    /// (`docs/convergence.md`).
    pub regime: String,
    /// ω_max·Δt of the level's model (ω_max: the highest natural
    /// frequency, `central_difference_limit`): above 1 its top modes are
    /// not resolved in time, which caps a moving load's Δt order.
    pub omega_max_dt: f64,
}

/// Quantities reported, in order.
pub(crate) const QUANTITIES: [&str; 12] = [
    "displacement_max",
    "displacement_l2",
    "force_max",
    "force_l2",
    "loss_fraction",
    "loss_fraction_span",
    "loss_fraction_support",
    "first_loss_position",
    "filtered_force_mean",
    "filtered_force_std",
    "filtered_force_max",
    "filtered_force_min",
];

/// The scalar outputs ([`Scalar`]) among [`QUANTITIES`], in that order.
pub(crate) const SCALARS: [Scalar; 8] = [
    Scalar::LossFraction,
    Scalar::LossFractionSpan,
    Scalar::LossFractionSupport,
    Scalar::FirstLossPosition,
    Scalar::FilteredForceMean,
    Scalar::FilteredForceStd,
    Scalar::FilteredForceMax,
    Scalar::FilteredForceMin,
];

pub(super) fn max_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

pub(super) fn l2_norm(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

pub(super) fn diff(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

/// The rows of one quantity over the levels.
pub(super) struct Rows {
    value: Vec<f64>,
    error: Vec<f64>,
    error_order: Vec<f64>,
    observed: Vec<f64>,
    gci: Vec<f64>,
    ratio_change: Vec<f64>,
    regime: Vec<String>,
    reference: String,
}

/// Orders between successive entries of `e` (NaN at index 0).
pub(super) fn orders_of(e: &[f64], r: f64) -> Vec<f64> {
    (0..e.len())
        .map(|l| {
            if l == 0 {
                f64::NAN
            } else {
                observed_order(e[l - 1], e[l], r)
            }
        })
        .collect()
}

/// Errors, orders, GCI and regime of a quantity given per level as
/// `values` (a scalar, or the norm of a history) and the successive
/// differences `d` (`d[ℓ−1]` between levels ℓ−1 and ℓ); `errors` against
/// an exact reference when known, else built from Richardson or the finest.
pub(super) fn quantity_rows(
    values: Vec<f64>,
    d: Vec<f64>,
    errors: Option<Vec<f64>>,
    richardson: &dyn Fn(f64) -> Vec<f64>,
    r: f64,
    ctx: &Context,
    formal: Option<f64>,
) -> Rows {
    let k = values.len();
    // the successive-difference order of level ℓ (ℓ ≥ 2)
    let observed: Vec<f64> = (0..k)
        .map(|l| {
            if l >= 2 {
                observed_order(d[l - 2], d[l - 1], r)
            } else {
                f64::NAN
            }
        })
        .collect();
    let gci: Vec<f64> = (0..k)
        .map(|l| {
            let p = observed[l];
            if l >= 2 && p.is_finite() && p > 0.0 && values[l] != 0.0 {
                GCI_SAFETY_FACTOR * (d[l - 1] / values[l].abs()) / (r.powf(p) - 1.0)
            } else {
                f64::NAN
            }
        })
        .collect();
    let ctx = Context {
        formal,
        omega_dt: Vec::new(),
        ..*ctx
    };
    match errors {
        Some(e) => {
            let error_order = orders_of(&e, r);
            let regime = (0..k)
                .map(|l| regime(&e, &error_order, l, &ctx, true))
                .collect();
            let ratio_change = (0..k)
                .map(|l| {
                    if l >= 2 {
                        ratio_change(e[l - 2], e[l - 1], e[l])
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            Rows {
                value: values,
                error: e,
                error_order,
                observed,
                gci,
                ratio_change,
                regime,
                reference: ctx.name.to_string(),
            }
        }
        None => {
            let (reference, error) = if k >= 3 {
                let p = observed_order(d[k - 3], d[k - 2], r);
                if p.is_finite() && p > 0.0 {
                    ("richardson", richardson(p))
                } else {
                    ("finest", richardson(f64::NAN))
                }
            } else {
                ("finest", richardson(f64::NAN))
            };
            // orders from successive differences: the regime reads them
            let regime = (0..k)
                .map(|l| regime(&d_padded(&d), &observed, l, &ctx, false))
                .collect();
            let ratio_change = (0..k)
                .map(|l| {
                    if l >= 3 {
                        ratio_change(d[l - 3], d[l - 2], d[l - 1])
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            Rows {
                value: values,
                error,
                error_order: vec![f64::NAN; k],
                observed,
                gci,
                ratio_change,
                regime,
                reference: reference.to_string(),
            }
        }
    }
}

/// The differences as the regime reads them without an exact reference
/// (index ℓ − 1 for level ℓ): as given.
pub(super) fn d_padded(d: &[f64]) -> Vec<f64> {
    d.to_vec()
}

pub(super) fn tabulate(
    scenes: &[Resolved],
    runs: &[RunOutput],
    stride: &[usize],
    r: f64,
    ctx: &Context,
) -> Vec<ConvergeRow> {
    let k = runs.len();
    let t0: Vec<f64> = runs[0].history.t.clone();
    let coarse = 0..runs[0].history.len();
    let on_coarse = |pick: fn(&crate::record::CarrierTrace) -> &[f64]| -> Vec<Vec<f64>> {
        (0..k)
            .map(|l| {
                resample(
                    pick(&runs[l].history.carriers[0]),
                    stride[l],
                    coarse.clone(),
                )
            })
            .collect()
    };
    let w = on_coarse(|c| &c.w);
    let f = on_coarse(|c| &c.force);
    let w_exact: Option<Vec<f64>> = ctx.w.map(|a| t0.iter().map(|&t| a(t)).collect());
    // each level's force against the exact one at the time it acts
    let f_exact: Option<Vec<Vec<f64>>> = ctx.force.map(|a| {
        (0..k)
            .map(|l| {
                let lag = runs[l].force_lag * scenes[l].dt;
                t0.iter()
                    .enumerate()
                    .map(|(i, &t)| if i == 0 { a(0.0) } else { a(t - lag) })
                    .collect()
            })
            .collect()
    });

    let mut all: Vec<(String, Rows)> = Vec::new();
    let hist = |name: &str,
                h: &[Vec<f64>],
                norm: fn(&[f64]) -> f64,
                exact: Option<Vec<Vec<f64>>>,
                formal: Option<f64>|
     -> (String, Rows) {
        let d: Vec<f64> = (1..k).map(|l| norm(&diff(&h[l - 1], &h[l]))).collect();
        let values: Vec<f64> = h.iter().map(|x| norm(x)).collect();
        let errors = exact.map(|e| (0..k).map(|l| norm(&diff(&h[l], &e[l]))).collect());
        let richardson = |p: f64| -> Vec<f64> {
            let refvec: Vec<f64> = if p.is_finite() {
                let fac = 1.0 / (r.powf(p) - 1.0);
                h[k - 1]
                    .iter()
                    .zip(&h[k - 2])
                    .map(|(fine, mid)| fine + (fine - mid) * fac)
                    .collect()
            } else {
                h[k - 1].clone()
            };
            (0..k).map(|l| norm(&diff(&h[l], &refvec))).collect()
        };
        (
            name.to_string(),
            quantity_rows(values, d, errors, &richardson, r, ctx, formal),
        )
    };
    let same = |e: &Vec<f64>| Some(vec![e.clone(); k]);
    all.push(hist(
        "displacement_max",
        &w,
        max_norm,
        w_exact.as_ref().and_then(same),
        ctx.formal,
    ));
    all.push(hist(
        "displacement_l2",
        &w,
        l2_norm,
        w_exact.as_ref().and_then(same),
        ctx.formal,
    ));
    all.push(hist("force_max", &f, max_norm, f_exact.clone(), None));
    all.push(hist("force_l2", &f, l2_norm, f_exact, None));

    // scalars: a value a run does not have (no first loss) is NaN: an
    // empty cell, JSON null
    for q in SCALARS {
        let vals: Vec<f64> = runs
            .iter()
            .map(|o| q.of(o, 0).unwrap_or(f64::NAN))
            .collect();
        let d: Vec<f64> = (1..k).map(|l| (vals[l - 1] - vals[l]).abs()).collect();
        let richardson = |p: f64| -> Vec<f64> {
            let refval = if p.is_finite() {
                vals[k - 1] + (vals[k - 1] - vals[k - 2]) / (r.powf(p) - 1.0)
            } else {
                vals[k - 1]
            };
            vals.iter().map(|v| (v - refval).abs()).collect()
        };
        all.push((
            q.name().to_string(),
            quantity_rows(vals.clone(), d, None, &richardson, r, ctx, None),
        ));
    }

    let mut out: Vec<ConvergeRow> = Vec::with_capacity(all.len() * k);
    for (quantity, rows) in &all {
        for l in 0..k {
            out.push(ConvergeRow {
                method: String::new(),
                discretization: scenes[l].discretization.name().to_string(),
                level: l,
                h: scenes[l].resolution(),
                modes: scenes[l].discretization.modes(),
                dt: scenes[l].dt,
                quantity: quantity.clone(),
                value: rows.value[l],
                error: rows.error[l],
                observed_order: rows.observed[l],
                gci: rows.gci[l],
                reference: rows.reference.clone(),
                error_order: rows.error_order[l],
                ratio_change: rows.ratio_change[l],
                formal_order: if quantity.starts_with("displacement") {
                    ctx.formal.unwrap_or(f64::NAN)
                } else {
                    f64::NAN
                },
                regime: rows.regime[l].clone(),
                omega_max_dt: ctx.omega_dt[l],
            });
        }
    }
    out.sort_by_key(|r| (r.level, QUANTITIES.iter().position(|q| *q == r.quantity)));
    out
}
