//! The front ends' words as typed values: the one place where the text of
//! `--methods`, `--formulations`, `--discretizations`, `--reference…` (and
//! Python's keyword arguments of the same names) is read, so that both
//! front ends refuse the same words with the same message.

use crate::error::{Error, Result};
use crate::integrate::{MethodFactory, parse_methods};
use crate::scene::Formulation;
use crate::study::compare::parse_formulations;
use crate::study::request;
use crate::study::space::SpaceChoice;

/// `lagrange,penalty,…` (at least one, none twice).
pub fn formulations(list: &str) -> Result<Vec<Formulation>> {
    parse_formulations(list)
}

/// One formulation (`--reference`): the first of a list.
pub fn formulation(name: &str) -> Result<Formulation> {
    Ok(parse_formulations(name)?[0])
}

/// A comma list of methods (built-in or registered by name); none given:
/// the scene's own (an empty list).
pub fn methods(list: Option<&str>) -> Result<Vec<&'static dyn MethodFactory>> {
    Ok(list.map(parse_methods).transpose()?.unwrap_or_default())
}

/// A comma list of space discretizations; none given: the scene's own (an
/// empty list).
pub fn discretizations(list: Option<&str>) -> Result<Vec<SpaceChoice>> {
    Ok(list
        .map(SpaceChoice::parse_list)
        .transpose()?
        .unwrap_or_default())
}

/// `--reference-method NAME` as an index into `methods` (0 when absent).
pub fn reference_method(
    name: Option<&str>,
    methods: &[&'static dyn MethodFactory],
) -> Result<usize> {
    match name {
        None => Ok(0),
        Some(name) if methods.is_empty() => Err(Error::invalid(
            "--reference-method",
            name,
            "needs --methods",
        )),
        Some(name) => {
            let m = parse_methods(name)?[0].name();
            methods.iter().position(|x| x.name() == m).ok_or_else(|| {
                Error::invalid("--reference-method", name, "must be one of --methods")
            })
        }
    }
}

/// `--solver`: `direct` or `clarabel`.
pub(crate) fn complementarity_solver(name: &str) -> Result<crate::scene::ComplementaritySolver> {
    use crate::scene::ComplementaritySolver;
    match name {
        "direct" => Ok(ComplementaritySolver::Direct),
        "clarabel" => Ok(ComplementaritySolver::Clarabel),
        other => Err(Error::invalid(
            "--solver",
            other,
            "must be `direct` or `clarabel`",
        )),
    }
}

/// The words of `taut compare` (Python: `taut.compare`) as its typed study.
pub fn compare(
    formulations: &str,
    (methods, discretizations): (Option<&str>, Option<&str>),
    (reference, reference_method): (&str, Option<&str>),
    batch: Option<usize>,
    yes: bool,
) -> Result<request::CompareStudy> {
    let batch = request::batch_width(batch)?;
    let formulations = self::formulations(formulations)?;
    let methods = self::methods(methods)?;
    let discretizations = self::discretizations(discretizations)?;
    let reference = formulation(reference)?;
    let reference_method = self::reference_method(reference_method, &methods)?;
    Ok(request::CompareStudy {
        formulations,
        methods,
        discretizations,
        reference,
        reference_method,
        batch,
        yes,
    })
}

/// The words of `taut converge` (Python: `taut.converge`) as its typed
/// study; levels and ratio are checked by the study.
pub fn converge(
    refine: &str,
    (levels, ratio): (usize, f64),
    (methods, discretizations): (Option<&str>, Option<&str>),
    yes: bool,
) -> Result<request::ConvergeStudy> {
    Ok(request::ConvergeStudy {
        refine: refine.parse()?,
        levels,
        ratio,
        methods: self::methods(methods)?,
        discretizations: self::discretizations(discretizations)?,
        yes,
    })
}

/// The words of `taut precision` (Python: `taut.precision`) as its typed
/// study; levels and ratio are checked by the study.
pub fn precision(
    formulations: &str,
    (methods, discretizations): (Option<&str>, Option<&str>),
    (levels, ratio): (usize, usize),
    batch: Option<usize>,
    yes: bool,
) -> Result<request::PrecisionStudy> {
    let batch = request::batch_width(batch)?;
    Ok(request::PrecisionStudy {
        formulations: self::formulations(formulations)?,
        methods: self::methods(methods)?,
        discretizations: self::discretizations(discretizations)?,
        levels,
        ratio,
        batch,
        yes,
    })
}

/// The words of `taut uncertainty` (Python: `taut.uncertainty`) as its
/// typed study; the levels and `--max-cost` are checked here, before the
/// scene is read.
pub fn uncertainty(
    levels: usize,
    max_cost: Option<&str>,
    yes: bool,
) -> Result<request::UncertaintyStudy> {
    crate::study::uncertainty::check_levels(levels)?;
    let max_cost = max_cost
        .map(|text| {
            text.trim()
                .parse::<f64>()
                .map_err(|_| {
                    Error::invalid(
                        "--max-cost",
                        text,
                        crate::study::uncertainty::MAX_COST_ALLOWED,
                    )
                })
                .and_then(crate::study::uncertainty::check_max_cost)
        })
        .transpose()?
        .unwrap_or(crate::study::uncertainty::DEFAULT_MAX_COST);
    Ok(request::UncertaintyStudy {
        levels,
        max_cost,
        yes,
    })
}

/// `taut sweep` or `taut run --tolerance TOL [--quantity Q] [--max-cost
/// F]` (Python: `tolerance=`, `quantity=`, `max_cost=`): one target for
/// both, Q defaulting to [`crate::study::sweep::DEFAULT_QUANTITY`]; none
/// without a tolerance.
pub fn sweep_tolerance(
    tol: Option<&str>,
    quantity: Option<&str>,
    max_cost: Option<&str>,
) -> Result<Option<crate::study::sweep::SweepTolerance>> {
    let Some(tol) = tol else {
        return Ok(None);
    };
    let number = |flag: &str, text: &str, what: &str| -> Result<f64> {
        text.trim()
            .parse::<f64>()
            .map_err(|_| Error::invalid(flag, text, what.to_string()))
    };
    let t = number(
        "--tolerance",
        tol,
        "must be a finite number > 0, in the quantity's unit (absolute: 0.002 for P_l)",
    )?;
    let budget = max_cost
        .map(|b| number("--max-cost", b, "must be a finite number ≥ 2"))
        .transpose()?;
    crate::study::sweep::SweepTolerance::new(
        quantity.unwrap_or(crate::study::sweep::DEFAULT_QUANTITY),
        t,
        budget,
    )
    .map(Some)
}

/// `--vary KEY=START:STOP:COUNT` or `KEY=V1,V2,...` (one or two), spaced
/// logarithmically with `log`.
pub fn axes(vary: &[String], log: bool) -> Result<Vec<crate::study::sweep::Axis>> {
    vary.iter()
        .map(|v| crate::study::sweep::Axis::parse(v, log))
        .collect()
}

/// `--unset KEY` (Python: `set={KEY: None}`) as its entry of the override
/// list ([`crate::scene::UNSET`]).
pub fn unset(key: &str) -> String {
    format!("{}{}", crate::scene::UNSET, key.trim())
}
