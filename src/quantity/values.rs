//! A run's values of the registered quantities, as a table row holds them
//! ([`Values`]): by name, `null` where undefined, so that a quantity
//! registered later is one more key, not one more field.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::definition::{Offer, Quantity};
use super::reading::Reading;
use super::registry::offered;
use crate::run::RunOutput;

/// The values of `which` for `carrier` of `out`, in that order; all `None`
/// when the run has no such carrier. What several quantities share (the
/// filtered force) is computed once. NaN is read as `None`.
pub fn values(out: &RunOutput, carrier: usize, which: &[&Quantity]) -> Vec<Option<f64>> {
    let Some(r) = Reading::new(out, carrier) else {
        return vec![None; which.len()];
    };
    which
        .iter()
        .map(|q| (q.read)(&r).filter(|v| !v.is_nan()))
        .collect()
}

/// One run's values of the quantities a table offers, by name (a JSON
/// object of numbers and `null`s).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Values(BTreeMap<String, Option<f64>>);

impl Values {
    /// The quantities `offer` names, for `carrier` of `out`.
    pub fn of(out: &RunOutput, carrier: usize, offer: Offer) -> Self {
        Self::of_these(out, carrier, &offered(offer))
    }

    /// Every quantity of the registry, for `carrier` of `out` (a run's
    /// summary).
    pub fn of_all(out: &RunOutput, carrier: usize) -> Self {
        Self::of_these(out, carrier, &super::registry::all())
    }

    fn of_these(out: &RunOutput, carrier: usize, qs: &[&Quantity]) -> Self {
        let vs = values(out, carrier, qs);
        Values(
            qs.iter()
                .zip(vs)
                .map(|(q, v)| (q.name.to_string(), v))
                .collect(),
        )
    }

    /// No value for any quantity (a run that stopped).
    pub fn none() -> Self {
        Values::default()
    }

    /// The value of `q`, if the row has one.
    pub fn get(&self, q: &Quantity) -> Option<f64> {
        self.get_named(q.name)
    }

    /// The value of the quantity called `name`, if the row has one.
    pub fn get_named(&self, name: &str) -> Option<f64> {
        self.0.get(name).copied().flatten()
    }

    /// The value of `q`, NaN where the row has none (a table's cell).
    pub fn real(&self, q: &Quantity) -> f64 {
        self.get(q).unwrap_or(f64::NAN)
    }

    /// Set the value of `q`.
    pub fn set(&mut self, q: &Quantity, v: Option<f64>) {
        self.0.insert(q.name.to_string(), v.filter(|v| !v.is_nan()));
    }
}
