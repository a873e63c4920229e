//! The rows of `converge.csv`: one per level and quantity, and how a
//! study's runs become them (errors, orders, GCI, regime).

use serde::Serialize;

use super::Refine;
use super::regime::{Context, ratio_change, regime};
use crate::quantity::formal_orders::{MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT};
use crate::quantity::{Offer, offered};
use crate::resolve::Resolved;
use crate::run::RunOutput;
use crate::study::grid::resample;
use crate::study::uncertainty::{Gci, Inputs, assess, observed_order, richardson_error};

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
    /// Roache's grid convergence index of this level from the three
    /// levels ending at it ([`Gci`]: F_s = 1.25 near the formal order, 3
    /// otherwise), relative to the value; NaN when not defined.
    pub gci: f64,
    /// The numerical uncertainty of this level's value from the levels up
    /// to it, in the quantity's unit (`taut uncertainty`'s estimators: the
    /// GCI, or least squares for a scalar whose levels scatter; for a
    /// history, the GCI of its norm of differences): of the refined
    /// variable's error only unless both are refined. NaN when none.
    pub u_num: f64,
    /// `--refine both`: the share of this level's change that its mesh
    /// refinement made (0–1; from the split run at level ℓ's mesh and
    /// level ℓ − 1's Δt), the rest being Δt's; NaN otherwise.
    pub mesh_share: f64,
    /// What `error` is against: the scene's declared reference
    /// (`manufactured`, `moving_force_series`, `riding_mass_galerkin`,
    /// `standing_force_modes`), else a Richardson extrapolation of the
    /// ladder, or its finest level when no order could be observed for one,
    /// naming the error it measures: `richardson (Δt error only)`, `…
    /// (mesh error only)`, `… (J error only)`, `… (mesh and Δt)`.
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
    /// fall, or rise), `diverged` (an error or difference as large as the
    /// quantity, or a run that blew up), `exact`, or empty before a level
    /// can tell; without an exact reference a one-variable ladder adds
    /// that the other variable's error is unmeasured (`docs/convergence.md`).
    pub regime: String,
    /// ω_max·Δt of the level's model (ω_max: the highest natural
    /// frequency, `central_difference_limit`): above 1 its top modes are
    /// not resolved in time, which caps a moving load's Δt order.
    pub omega_max_dt: f64,
}

/// The norms of a history converge reports beside the registry's
/// quantities: the max and L2 (RMS over the steps) norms of w under the
/// carrier and of λ, each with its error against the reference history.
pub(crate) const HISTORY_NORMS: [&str; 4] = [
    "displacement_history_max",
    "displacement_history_l2",
    "force_history_max",
    "force_history_l2",
];

/// Quantities reported, in order: [`HISTORY_NORMS`], then the registry's
/// quantities offered to converge ([`Offer::CONVERGE`]).
pub(crate) fn quantity_names() -> Vec<&'static str> {
    HISTORY_NORMS
        .into_iter()
        .chain(offered(Offer::CONVERGE).into_iter().map(|q| q.name))
        .collect()
}

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
    u_num: Vec<f64>,
    ratio_change: Vec<f64>,
    regime: Vec<String>,
    reference: String,
    /// `error` is against an exact reference.
    exact: bool,
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
/// an exact reference when known, else built from Richardson or the finest;
/// `sizes`: the quantity's size at each level for the `diverged` test (the
/// exact history's norm, or the level's own for a history; None for a
/// scalar).
#[allow(clippy::too_many_arguments)]
pub(super) fn quantity_rows(
    values: Vec<f64>,
    d: Vec<f64>,
    errors: Option<Vec<f64>>,
    sizes: Option<Vec<f64>>,
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
    let gcis: Vec<Option<Gci>> = (0..k)
        .map(|l| {
            (l >= 2)
                .then(|| Gci::from_differences(d[l - 2], d[l - 1], r, formal))
                .flatten()
        })
        .collect();
    let gci = (0..k)
        .map(|l| gcis[l].map_or(f64::NAN, |g| g.relative(values[l])))
        .collect();
    let u_num = gcis.iter().map(|g| g.map_or(f64::NAN, |g| g.u)).collect();
    let ctx = Context {
        formal,
        omega_dt: Vec::new(),
        ..*ctx
    };
    let size = |l: usize| sizes.as_ref().map(|s| s[l]);
    match errors {
        Some(e) => {
            let error_order = orders_of(&e, r);
            let regime = (0..k)
                .map(|l| regime(&e, &error_order, l, &ctx, true, size(l)))
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
                u_num,
                ratio_change,
                regime,
                reference: ctx.name.to_string(),
                exact: true,
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
                .map(|l| regime(&d_padded(&d), &observed, l, &ctx, false, size(l)))
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
                u_num,
                ratio_change,
                regime,
                reference: format!("{reference} ({})", measured(&ctx)),
                exact: false,
            }
        }
    }
}

/// What an error built from the ladder itself measures: the refined
/// variable's error only, or both's.
fn measured(ctx: &Context) -> String {
    match ctx.refine {
        Refine::Both => ctx.refined.to_string(),
        _ => format!("{} error only", ctx.refined),
    }
}

/// The differences as the regime reads them without an exact reference
/// (index ℓ − 1 for level ℓ): as given.
pub(super) fn d_padded(d: &[f64]) -> Vec<f64> {
    d.to_vec()
}

/// The rows of a finished ladder: `runs` at `scenes` (coarsest first),
/// each on the coarse grid by `stride`; `split` the `--refine both` runs
/// (level ℓ's mesh at level ℓ − 1's Δt, ℓ = 1 …), else empty.
pub(super) fn tabulate(
    scenes: &[Resolved],
    runs: &[RunOutput],
    stride: &[usize],
    split: &[RunOutput],
    r: f64,
    ctx: &Context,
) -> Vec<ConvergeRow> {
    let k = runs.len();
    let t0: Vec<f64> = runs[0].history.t.clone();
    let coarse = 0..runs[0].history.len();
    let (base_steps, base_dt) = (runs[0].steps, runs[0].dt);
    let on_coarse = |outs: &[RunOutput], pick: fn(&crate::record::CarrierTrace) -> &[f64]| {
        outs.iter()
            .enumerate()
            .map(|(l, o)| {
                // a level's stride, or a split run's (each reaches the coarse end)
                let m = stride
                    .get(l)
                    .copied()
                    .filter(|_| outs.len() == k)
                    .unwrap_or_else(|| {
                        crate::study::grid::nest(
                            (base_steps, base_dt),
                            (o.steps, o.dt),
                            crate::study::grid::Reach::AtLeast,
                        )
                        .expect("a split run's Δt is a level's")
                    });
                resample(pick(&o.history.carriers[0]), m, coarse.clone())
            })
            .collect::<Vec<Vec<f64>>>()
    };
    let w = on_coarse(runs, |c| &c.w);
    let f = on_coarse(runs, |c| &c.force);
    let (ws, fs) = (on_coarse(split, |c| &c.w), on_coarse(split, |c| &c.force));
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
    // --refine both: the mesh's share of each level's change
    let share = |dx: f64, dt: f64| {
        let (dx, dt) = (dx.abs(), dt.abs());
        if dx + dt > 0.0 {
            dx / (dx + dt)
        } else {
            f64::NAN
        }
    };
    let shares = |parts: &dyn Fn(usize) -> (f64, f64)| {
        (0..k)
            .map(|l| {
                if l == 0 || split.len() + 1 != k {
                    return f64::NAN;
                }
                let (dx, dt) = parts(l);
                share(dx, dt)
            })
            .collect::<Vec<f64>>()
    };

    let mut all: Vec<(String, Rows, Vec<f64>)> = Vec::new();
    let hist = |name: &str,
                h: &[Vec<f64>],
                hs: &[Vec<f64>],
                norm: fn(&[f64]) -> f64,
                exact: Option<Vec<Vec<f64>>>,
                formal: Option<f64>|
     -> (String, Rows, Vec<f64>) {
        let d: Vec<f64> = (1..k).map(|l| norm(&diff(&h[l - 1], &h[l]))).collect();
        let values: Vec<f64> = h.iter().map(|x| norm(x)).collect();
        let sizes = Some(match &exact {
            Some(e) => e.iter().map(|x| norm(x)).collect(),
            None => values.clone(),
        });
        let errors = exact.map(|e| (0..k).map(|l| norm(&diff(&h[l], &e[l]))).collect());
        let richardson = |p: f64| -> Vec<f64> {
            let refvec: Vec<f64> = if p.is_finite() {
                h[k - 1]
                    .iter()
                    .zip(&h[k - 2])
                    .map(|(fine, mid)| fine - richardson_error(mid - fine, r, p))
                    .collect()
            } else {
                h[k - 1].clone()
            };
            (0..k).map(|l| norm(&diff(&h[l], &refvec))).collect()
        };
        let mesh_share = shares(&|l| {
            (
                norm(&diff(&h[l - 1], &hs[l - 1])),
                norm(&diff(&hs[l - 1], &h[l])),
            )
        });
        (
            name.to_string(),
            quantity_rows(values, d, errors, sizes, &richardson, r, ctx, formal),
            mesh_share,
        )
    };
    let same = |e: &Vec<f64>| Some(vec![e.clone(); k]);
    for (name, h, hs, norm, exact, formal) in [
        (
            "displacement_history_max",
            &w,
            &ws,
            max_norm as fn(&[f64]) -> f64,
            w_exact.as_ref().and_then(same),
            ctx.formal,
        ),
        (
            "displacement_history_l2",
            &w,
            &ws,
            l2_norm,
            w_exact.as_ref().and_then(same),
            ctx.formal,
        ),
        (
            "force_history_max",
            &f,
            &fs,
            max_norm,
            f_exact.clone(),
            None,
        ),
        ("force_history_l2", &f, &fs, l2_norm, f_exact.clone(), None),
    ] {
        all.push(hist(name, h, hs, norm, exact, formal));
    }

    // scalars: a value a run does not have (no first loss) is NaN: an
    // empty cell, JSON null; their u_num from the estimators of `taut
    // uncertainty` (least squares where the levels scatter)
    let (p_space, p_time) = (MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT);
    let formal_scalar = match ctx.refine {
        Refine::Mesh => (p_space, p_space),
        Refine::Step => (p_time, p_time),
        Refine::Both => (p_space, p_time),
    };
    for q in offered(Offer::CONVERGE) {
        let of = |o: &RunOutput| q.of(o, 0);
        let vals: Vec<f64> = runs.iter().map(|o| of(o).unwrap_or(f64::NAN)).collect();
        let opt: Vec<Option<f64>> = runs.iter().map(of).collect();
        let mixed: Vec<Option<f64>> = split.iter().map(of).collect();
        let d: Vec<f64> = (1..k).map(|l| (vals[l - 1] - vals[l]).abs()).collect();
        let richardson = |p: f64| -> Vec<f64> {
            let refval = if p.is_finite() {
                vals[k - 1] - richardson_error(vals[k - 2] - vals[k - 1], r, p)
            } else {
                vals[k - 1]
            };
            vals.iter().map(|v| (v - refval).abs()).collect()
        };
        let mut rows = quantity_rows(vals.clone(), d, None, None, &richardson, r, ctx, None);
        rows.u_num = (0..k)
            .map(|l| {
                if l == 0 {
                    return f64::NAN;
                }
                let space = if mixed.len() + 1 == k {
                    &mixed[..l]
                } else {
                    &[][..]
                };
                let a = assess(&Inputs {
                    diagonal: &opt[..=l],
                    space,
                    ratio: r,
                    formal: formal_scalar,
                    smooth: false,
                });
                a.u_num.unwrap_or(f64::NAN)
            })
            .collect();
        let mesh_share = shares(&|l| {
            let m = mixed[l - 1].unwrap_or(f64::NAN);
            (vals[l - 1] - m, m - vals[l])
        });
        all.push((q.name.to_string(), rows, mesh_share));
    }

    // without an exact reference a one-variable ladder measures that
    // variable's error only: its regime says so
    let unmeasured = |regime: &str, exact: bool| {
        if exact
            || regime.is_empty()
            || ctx.refine == Refine::Both
            || regime.starts_with("diverged")
        {
            regime.to_string()
        } else {
            format!("{regime}; the error of {} is unmeasured", ctx.unrefined)
        }
    };
    let mut out: Vec<ConvergeRow> = Vec::with_capacity(all.len() * k);
    for (quantity, rows, mesh_share) in &all {
        let exact = rows.exact;
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
                u_num: rows.u_num[l],
                mesh_share: mesh_share[l],
                reference: rows.reference.clone(),
                error_order: rows.error_order[l],
                ratio_change: rows.ratio_change[l],
                formal_order: if quantity.starts_with("displacement_history") {
                    ctx.formal.unwrap_or(f64::NAN)
                } else {
                    f64::NAN
                },
                regime: unmeasured(&rows.regime[l], exact),
                omega_max_dt: ctx.omega_dt[l],
            });
        }
    }
    let names = quantity_names();
    out.sort_by_key(|r| (r.level, names.iter().position(|q| *q == r.quantity)));
    out
}

/// The rows of a level whose run diverged (`d`; `sc` its scene): every
/// quantity without a value, the regime naming the divergence.
pub(super) fn diverged_rows(sc: &Resolved, d: &super::Diverged) -> Vec<ConvergeRow> {
    quantity_names()
        .into_iter()
        .map(|q| ConvergeRow {
            method: String::new(),
            discretization: sc.discretization.name().to_string(),
            level: d.level,
            h: sc.resolution(),
            modes: sc.discretization.modes(),
            dt: sc.dt,
            quantity: q.to_string(),
            value: f64::NAN,
            error: f64::NAN,
            observed_order: f64::NAN,
            gci: f64::NAN,
            u_num: f64::NAN,
            mesh_share: f64::NAN,
            reference: String::new(),
            error_order: f64::NAN,
            ratio_change: f64::NAN,
            formal_order: f64::NAN,
            regime: format!("diverged: {}", d.reason),
            omega_max_dt: f64::NAN,
        })
        .collect()
}
