//! The one list of quantities: taut's own ([`super::builtin::BUILTIN`])
//! and those a program registers ([`register`]). Every table, study, gate,
//! report and the Python module asks here ([`all`], [`offered`],
//! [`by_name`]) instead of keeping a list of its own.

use std::sync::RwLock;

use super::builtin::BUILTIN;
use super::definition::{Offer, Quantity};
use crate::error::{Error, Result};

/// The quantities registered by a program, after the built-ins, in the
/// order they were registered. Each is leaked once to live as long as the
/// program (a registration is made once, at start-up).
static REGISTERED: RwLock<Vec<&'static Quantity>> = RwLock::new(Vec::new());

/// Names a table or record already uses for a field of its own (not a
/// quantity): a quantity of that name would make two columns, or two JSON
/// keys, of one name (the compare, precision and sweep rows flatten their
/// quantities beside these; converge and uncertainty rows name them).
pub const RESERVED: [&str; 46] = [
    // every table
    "method",
    "discretization",
    "formulation",
    "wall_seconds",
    "warnings",
    "error",
    // compare
    "loss_set_difference",
    "max_force_difference",
    "rms_force_difference",
    "max_penetration_all_carriers",
    "min_gap_all_carriers",
    "force_min_all_carriers",
    "max_gap_force_product_all_carriers",
    "droppers",
    // precision
    "mesh_level",
    "step_level",
    "elements",
    "modes",
    "dt",
    "dof_steps",
    "force_error",
    "displacement_error",
    "loss_fraction_error",
    "pareto",
    // a sweep's records and sweep.csv
    "sweep_id",
    "index",
    "values",
    "speed_ratio",
    "force_profile",
    "loss_profile",
    "refined",
    "accuracy",
    "u_num",
    "tolerance_met",
    "estimator",
    "dof_steps_used",
    "cpu_seconds",
    "predicted_cost",
    "not_met_because",
    // converge and uncertainty rows
    "level",
    "quantity",
    "carrier",
    "value",
    "h",
    "unit",
    // the gate's probes
    "final_probe",
];

/// Every quantity: the built-ins in their documented order, then the
/// registered ones in the order of registration.
pub fn all() -> Vec<&'static Quantity> {
    let registered = REGISTERED.read().unwrap_or_else(|p| p.into_inner());
    BUILTIN
        .iter()
        .copied()
        .chain(registered.iter().copied())
        .collect()
}

/// The quantities a table or study of kind `offer` offers, in [`all`]'s
/// order.
pub fn offered(offer: Offer) -> Vec<&'static Quantity> {
    all().into_iter().filter(|q| q.offered_in(offer)).collect()
}

/// The quantities `offer` offers that have an error to estimate (not a
/// count of the discretization itself): those a study gives an error bar
/// or an estimate.
pub fn estimated(offer: Offer) -> Vec<&'static Quantity> {
    offered(offer)
        .into_iter()
        .filter(|q| q.error != super::definition::ErrorKind::Exact)
        .collect()
}

/// The quantity called `name`.
pub fn by_name(name: &str) -> Option<&'static Quantity> {
    all().into_iter().find(|q| q.name == name)
}

/// The names of every quantity, comma-separated (for an error's allowed
/// values).
pub fn names() -> String {
    all().iter().map(|q| q.name).collect::<Vec<_>>().join(", ")
}

/// Add a quantity of one's own. It appears, from then on, in every table
/// and study its [`Quantity::offer`] names, in the run summary, the gate
/// and Python. Refused: a name that is not snake case (`[a-z][a-z0-9_]*`),
/// that ends in `_N` (the gate's suffix for carrier N), that a table uses
/// for a column of its own ([`RESERVED`]), or that a quantity already has.
pub fn register(q: Quantity) -> Result<&'static Quantity> {
    check_name(q.name)?;
    let mut registered = REGISTERED.write().unwrap_or_else(|p| p.into_inner());
    if BUILTIN
        .iter()
        .chain(registered.iter())
        .any(|d| d.name == q.name)
    {
        return Err(Error::invalid(
            "quantity name",
            q.name,
            "is already a quantity's name: one name, one definition",
        ));
    }
    let q: &'static Quantity = Box::leak(Box::new(q));
    registered.push(q);
    Ok(q)
}

fn check_name(name: &str) -> Result<()> {
    let snake = name.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    if !snake {
        return Err(Error::invalid(
            "quantity name",
            name,
            "must be snake case: a lowercase letter, then lowercase letters, digits and _",
        ));
    }
    if name
        .rsplit_once('_')
        .is_some_and(|(_, n)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()))
    {
        return Err(Error::invalid(
            "quantity name",
            name,
            "must not end in _N: the gate reads NAME_N as NAME of carrier N",
        ));
    }
    if RESERVED.contains(&name) {
        return Err(Error::invalid(
            "quantity name",
            name,
            format!(
                "is a column a table keeps for itself: none of {}",
                RESERVED.join(", ")
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quantity::{ErrorKind, Window};

    fn probe(name: &'static str) -> Quantity {
        Quantity {
            name,
            label: "test",
            unit: "-",
            definition: "a test's quantity",
            window: Window::Run,
            count: false,
            smooth: true,
            error: ErrorKind::Contact,
            offer: Offer::ALL,
            read: |r| Some(r.carrier as f64),
        }
    }

    #[test]
    fn builtin_names_are_unique_and_valid() {
        for (i, q) in BUILTIN.iter().enumerate() {
            check_name(q.name).unwrap();
            assert!(
                BUILTIN[..i].iter().all(|p| p.name != q.name),
                "{} twice",
                q.name
            );
        }
    }

    #[test]
    fn bad_and_taken_names_are_refused() {
        for (name, says) in [
            ("Force", "snake case"),
            ("force_1", "_N"),
            ("method", "keeps for itself"),
            ("force_mean", "already"),
        ] {
            let e = register(probe(name)).unwrap_err().to_string();
            assert!(e.contains(says), "{name}: {e}");
        }
        let q = register(probe("registry_test_quantity")).unwrap();
        assert_eq!(by_name("registry_test_quantity").unwrap(), q);
        assert!(offered(Offer::UNCERTAINTY).contains(&q));
        assert!(register(probe("registry_test_quantity")).is_err());
    }
}
