//! What `taut verify` runs: methods, discretizations, formulations and
//! the cut-down matrix.

use super::case::Space;
use crate::error::{Error, Result};
use crate::integrate::MethodFactory;
use crate::scene::Formulation;
/// What to run (`taut verify --methods --discretizations --formulations`).
pub struct Selection<'a> {
    /// Methods (built-in or custom).
    pub methods: Vec<&'a dyn MethodFactory>,
    /// Discretizations (each case runs those it declares).
    pub spaces: Vec<Space>,
    /// Formulations (cases with contact).
    pub formulations: Vec<Formulation>,
    /// Only the cases of the cut-down matrix, with two support pairs.
    pub quick: bool,
}

/// Parse `hermite,graded,galerkin,modal` (`--discretizations`).
pub(crate) fn parse_spaces(list: &str) -> Result<Vec<Space>> {
    let mut out = Vec::new();
    for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let s = Space::ALL
            .into_iter()
            .find(|s| s.name() == item)
            .ok_or_else(|| {
                Error::invalid(
                    "--discretizations",
                    item,
                    "each item must be hermite, graded, galerkin or modal (taut verify sets J and N itself)",
                )
            })?;
        if out.contains(&s) {
            return Err(Error::invalid("--discretizations", item, "is listed twice"));
        }
        out.push(s);
    }
    if out.is_empty() {
        return Err(Error::invalid(
            "--discretizations",
            list,
            "name at least one of hermite, graded, galerkin, modal",
        ));
    }
    Ok(out)
}

/// The methods, discretizations and formulations of a `taut verify`
/// request (`None`: every built-in method, every discretization and
/// formulation), and whether to run the cut-down matrix. Listed built-in
/// methods run in their own order, then listed registered ones. A built-in
/// method of the generalized-α family brings its parameter sets
/// (`tuned`): the full matrix runs each; the cut-down one runs
/// the scene's own and the one marked quick of each method (`wbz` that one
/// alone: at the scene's ρ∞ = 1 it is Newmark's parameter set).
pub fn selection(
    methods: Option<&str>,
    spaces: Option<&str>,
    formulations: Option<&str>,
    quick: bool,
) -> Result<Selection<'static>> {
    static ALL: [crate::scene::Method; crate::scene::Method::ALL.len()] = crate::scene::Method::ALL;
    let builtin_named = |named: &dyn Fn(&str) -> bool| -> Vec<&'static dyn MethodFactory> {
        let mut out: Vec<&'static dyn MethodFactory> = Vec::new();
        for m in ALL.iter().filter(|m| named(m.name())) {
            let tuned: Vec<&'static dyn MethodFactory> = super::tuned::tuned_of(*m)
                .map(|t| t as &dyn MethodFactory)
                .collect();
            let quick_set = super::tuned::tuned_of(*m)
                .filter(|t| t.quick)
                .map(|t| t as &dyn MethodFactory);
            match (*m, quick) {
                // wbz at the scene's ρ∞ = 1 is Newmark: its tuned sets only
                (crate::scene::Method::Wbz, false) => out.extend(tuned),
                (crate::scene::Method::Wbz, true) => out.extend(quick_set),
                (_, false) => {
                    out.push(m as &dyn MethodFactory);
                    out.extend(tuned);
                }
                (_, true) => {
                    out.push(m as &dyn MethodFactory);
                    out.extend(quick_set);
                }
            }
        }
        out
    };
    let methods: Vec<&'static dyn MethodFactory> = match methods {
        None => builtin_named(&|_| true),
        Some(list) => {
            let chosen = crate::integrate::parse_methods(list)?;
            let named = |n: &str| chosen.iter().any(|m| m.name() == n);
            let registered = chosen
                .iter()
                .copied()
                .filter(|m| crate::scene::Method::from_name(&m.name()).is_none());
            builtin_named(&named)
                .into_iter()
                .chain(registered)
                .collect()
        }
    };
    Ok(Selection {
        methods,
        spaces: spaces.map_or(Ok(Space::ALL.to_vec()), parse_spaces)?,
        formulations: formulations.map_or(Ok(Formulation::ALL.to_vec()), |f| {
            crate::study::compare::parse_formulations(f)
        })?,
        quick,
    })
}
