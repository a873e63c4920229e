//! What an accuracy-targeted sweep (`--tolerance`) asks and what each point
//! reached: plain data that the sweep's spec and records hold, apart from
//! the driver that refines the points (`accuracy.rs`).

use serde::{Deserialize, Serialize};

use super::accuracy::RunMade;

use super::nan_as_null;
use crate::error::{Error, Result};
use crate::quantity::{Offer, Quantity};
use crate::resolve::Resolved;
use crate::study::level::Level;
use crate::study::uncertainty::quantity;

/// A point's default budget (`--max-cost`): its refinements may cost this
/// many times its own run (unknowns × steps), pilots included. 64 allows
/// one variable refined 2⁴ times beyond the point's own and the other 2²,
/// with their check families.
pub(crate) const DEFAULT_BUDGET: f64 = 64.0;

/// The quantity `--tolerance` is on when `--quantity` is not given, for
/// `taut sweep` and `taut run` alike: the in-span loss fraction, the
/// figure the loss maps are drawn of.
pub const DEFAULT_QUANTITY: &str = "loss_fraction_span";

/// The level parameter must be a multiple of this, so the pilots can be
/// made 2 and 4 times coarser.
pub(crate) const LEVEL_MULTIPLE: usize = 4;

/// What an accuracy-targeted sweep asks: Q within EPS (in Q's unit).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SweepTolerance {
    /// Q: a quantity of `taut uncertainty` that `sweep.csv` has.
    pub quantity: String,
    /// EPS, in Q's unit (absolute).
    pub tolerance: f64,
    /// The most a point may cost, as a multiple of its own run.
    pub budget: f64,
}

/// The quantities a sweep can target: those given an error bar
/// ([`quantity::quantities`]) that are columns of `sweep.csv`
/// ([`Offer::RUN_TABLES`]), in the registry's order.
pub fn targets() -> Vec<&'static Quantity> {
    quantity::quantities()
        .into_iter()
        .filter(|q| q.offered_in(Offer::RUN_TABLES))
        .collect()
}

impl SweepTolerance {
    /// `--tolerance EPS --quantity Q [--max-cost F]`, checked.
    pub fn new(quantity: &str, tolerance: f64, budget: Option<f64>) -> Result<Self> {
        let targets = targets();
        if !targets.iter().any(|q| q.name == quantity) {
            let names: Vec<&str> = targets.iter().map(|q| q.name).collect();
            return Err(Error::invalid(
                "--quantity",
                quantity,
                format!("must be one of {} (with --tolerance)", names.join(", ")),
            ));
        }
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::invalid(
                "--tolerance",
                tolerance,
                "must be a finite number > 0, in the quantity's unit (absolute: 0.002 for P_l)",
            ));
        }
        let budget = budget.unwrap_or(DEFAULT_BUDGET);
        if !(budget.is_finite() && budget >= 2.0) {
            return Err(Error::invalid(
                "--max-cost",
                budget,
                "must be a finite number ≥ 2 (a point's cost, pilots included, as a multiple of its own run; the pilots alone cost 1.81)",
            ));
        }
        Ok(SweepTolerance {
            quantity: quantity.to_string(),
            tolerance,
            budget,
        })
    }

    /// Q's description (what it is read from, its formal orders).
    pub(crate) fn spec(&self) -> &'static Quantity {
        quantity::quantity(&self.quantity).expect("checked by new")
    }
}

/// What a point of an accuracy-targeted sweep reached (`runs/*.json`,
/// the tolerance columns of `sweep.csv`).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PointAccuracy {
    /// Q at the reported resolution.
    #[serde(with = "nan_as_null")]
    pub value: f64,
    /// Its u_num (null when none could be given).
    #[serde(with = "nan_as_null")]
    pub u_num: f64,
    /// u_num ≤ EPS.
    pub met: bool,
    /// The reported run's elements N.
    pub elements: usize,
    /// Its modes J on a modal basis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Its Δt, s.
    pub dt: f64,
    /// Runs made for the point.
    pub runs: usize,
    /// Their unknowns × steps.
    pub dof_steps: f64,
    /// The estimator of u_num (`gci`, `least_squares`, `exact`, …).
    pub estimator: String,
    /// Checks made after the pilots.
    pub checks: usize,
    /// What the pilots' error model predicted reaching EPS would cost, as a
    /// multiple of the point's own run, pilots included (absent: no scene
    /// the model takes reaches it, a ladder did not converge, or the
    /// pilots met EPS).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub predicted_cost: Option<f64>,
    /// Why a point not met stopped where it did (absent for a point met).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub not_met: Option<String>,
    /// u_num of each candidate in the order assessed: the point's own
    /// resolution (from the pilots), then each check's (null: none given).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub u_num_ladder: Vec<Option<f64>>,
    /// Every run made for the point, coarsest first, each with its cost:
    /// where the point's time went (`accuracy.csv` of `run --tolerance`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub runs_made: Vec<RunMade>,
}

/// Check that every point's level parameter can be coarsened by
/// [`LEVEL_MULTIPLE`] (called with the spec's validation).
pub(crate) fn check_level(sc: &Resolved) -> Result<()> {
    let level = Level::of(sc);
    let n = level.start();
    if n.is_multiple_of(LEVEL_MULTIPLE) {
        return Ok(());
    }
    Err(Error::invalid(
        if level.symbol() == "J" {
            "mesh.modes"
        } else {
            "mesh.elements"
        },
        n,
        format!(
            "must be a multiple of {LEVEL_MULTIPLE} with --tolerance: the pilots run the point 2 and 4 times coarser"
        ),
    ))
}
