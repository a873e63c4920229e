//! A study as its caller names it: method, formulation and discretization
//! lists as text, a batch width that may be absent. Parsed and run here
//! once, for the CLI (`taut compare | converge | precision`) and the Python
//! module alike, so that both make the same runs from the same words.

use crate::error::{Error, Result};
use crate::integrate::{MethodFactory, parse_methods};

use super::compare::{CompareSpec, Comparison, NotRun, compare_methods, parse_formulations};
use super::converge::{ConvergeRow, Convergence, MethodStudy, Refine, converge, converge_variants};
use super::cost::{Estimate, run_dof_steps};
use super::precision::{Precision, precision_variants};
use super::space::SpaceChoice;
use super::sweep::BatchWidth;

/// `--batch B` (Python: `batch=`): 1 ..= [`crate::integrate::MAX_LANES`] runs
/// stepped together, or the automatic width when absent.
pub fn batch_width(b: Option<usize>) -> Result<BatchWidth> {
    let max = crate::integrate::MAX_LANES;
    match b {
        None => Ok(BatchWidth::Auto),
        Some(b) if (1..=max).contains(&b) => Ok(BatchWidth::Fixed(b)),
        Some(b) => Err(Error::invalid(
            "--batch",
            b,
            format!("must be in 1 ..= {max} (runs stepped together; 1 steps every run alone)"),
        )),
    }
}

/// [`batch_width`] as a number of lanes.
pub fn batch_lanes(b: Option<usize>) -> Result<usize> {
    Ok(match batch_width(b)? {
        BatchWidth::Auto => super::sweep::AUTO_BATCH_LANES,
        BatchWidth::Fixed(b) => b,
    })
}

/// A comma list of methods (built-in or registered by name), or the
/// scene's own when absent.
fn methods(list: Option<&str>) -> Result<Option<Vec<&'static dyn MethodFactory>>> {
    list.map(parse_methods).transpose()
}

/// The methods as the studies take them (empty: the scene's own).
fn factories(methods: &Option<Vec<&'static dyn MethodFactory>>) -> Vec<&'static dyn MethodFactory> {
    methods.iter().flatten().copied().collect()
}

/// The scene a study starts from (its own resolution), for its estimate.
fn base_dof_steps(text: &str, overrides: &[String]) -> Result<f64> {
    Ok(run_dof_steps(&crate::resolve::resolve_scene(
        text, overrides,
    )?))
}

/// A comma list of discretizations (empty: the scene's own).
fn spaces(list: Option<&str>) -> Result<Vec<SpaceChoice>> {
    Ok(list
        .map(SpaceChoice::parse_list)
        .transpose()?
        .unwrap_or_default())
}

/// `taut compare`: formulations × methods × discretizations of one scene.
#[derive(Debug, Clone)]
pub struct CompareRequest {
    /// `lagrange,penalty,…`.
    pub formulations: String,
    /// Time integrators (`--methods`); the scene's own when absent.
    pub methods: Option<String>,
    /// Space discretizations (`--discretizations`); the scene's own when absent.
    pub discretizations: Option<String>,
    /// The formulation the differences are measured against.
    pub reference: String,
    /// The method they are measured against (one of `methods`; default its first).
    pub reference_method: Option<String>,
    /// Runs stepped together (`--batch`).
    pub batch: Option<usize>,
    /// Start even above the cost bound (`--yes`, [`super::cost`]).
    pub yes: bool,
}

impl CompareRequest {
    /// The study's estimated work: every run at the scene's resolution.
    pub fn estimate(&self, text: &str, overrides: &[String]) -> Result<Estimate> {
        let mut e = Estimate::new("taut compare");
        e.add(self.runs()?, base_dof_steps(text, overrides)?);
        Ok(e)
    }

    /// Number of runs, for a progress bar (an estimate: the reference
    /// formulation is run too when not listed).
    pub fn runs(&self) -> Result<usize> {
        let f = parse_formulations(&self.formulations)?.len();
        let m = methods(self.methods.as_deref())?.map_or(1, |m| m.len());
        Ok(f * m * spaces(self.discretizations.as_deref())?.len().max(1))
    }

    /// Parse and run the comparison on scene `text` with `overrides`.
    pub fn run(
        &self,
        text: &str,
        overrides: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Comparison> {
        self.estimate(text, overrides)?.check(self.yes)?;
        let formulations = parse_formulations(&self.formulations)?;
        let reference = parse_formulations(&self.reference)?
            .first()
            .copied()
            .expect("parse_formulations returns at least one");
        let list = methods(self.methods.as_deref())?;
        let reference_method = match (self.reference_method.as_deref(), &list) {
            (None, _) => 0,
            (Some(name), Some(list)) => {
                let m = parse_methods(name)?[0].name();
                list.iter().position(|x| x.name() == m).ok_or_else(|| {
                    Error::invalid("--reference-method", name, "must be one of --methods")
                })?
            }
            (Some(name), None) => {
                return Err(Error::invalid(
                    "--reference-method",
                    name,
                    "needs --methods",
                ));
            }
        };
        let spec = CompareSpec {
            methods: factories(&list),
            formulations,
            discretizations: spaces(self.discretizations.as_deref())?,
            reference_method,
            reference_discretization: 0,
            reference,
            batch: batch_lanes(self.batch)?,
        };
        compare_methods(text, overrides, &spec, progress)
    }
}

/// `taut converge`: a refinement ladder, per method and discretization.
#[derive(Debug, Clone)]
pub struct ConvergeRequest {
    /// `mesh`, `step` or `both`.
    pub refine: String,
    /// Levels (≥ 3 for observed orders).
    pub levels: usize,
    /// Refinement ratio between levels.
    pub ratio: f64,
    /// Time integrators (`--methods`); the scene's own when absent.
    pub methods: Option<String>,
    /// Space discretizations (`--discretizations`); the scene's own when absent.
    pub discretizations: Option<String>,
    /// Start even above the cost bound (`--yes`, [`super::cost`]).
    pub yes: bool,
}

/// What a convergence study gives: one ladder (the scene's own method and
/// discretization) or one per variant, with the variants that could not run.
pub enum ConvergeOutcome {
    /// The scene's own method and discretization.
    One(Convergence),
    /// `--methods` and/or `--discretizations`.
    Variants {
        /// One study per variant that ran.
        studies: Vec<MethodStudy>,
        /// The variants that did not, and why.
        skipped: Vec<NotRun>,
    },
}

impl ConvergeOutcome {
    /// The rows of `converge.csv`, study after study.
    pub fn rows(&self) -> Vec<&ConvergeRow> {
        match self {
            ConvergeOutcome::One(c) => c.rows.iter().collect(),
            ConvergeOutcome::Variants { studies, .. } => {
                studies.iter().flat_map(|s| &s.study.rows).collect()
            }
        }
    }

    /// The variants that did not run.
    pub fn skipped(&self) -> &[NotRun] {
        match self {
            ConvergeOutcome::One(_) => &[],
            ConvergeOutcome::Variants { skipped, .. } => skipped,
        }
    }
}

impl ConvergeRequest {
    /// The study's estimated work: level l refines the scene's mesh and/or
    /// step by ratio^l, for every method and discretization.
    pub fn estimate(&self, text: &str, overrides: &[String]) -> Result<Estimate> {
        let refine: Refine = self.refine.parse()?;
        // in range first: the estimate loops over the levels
        super::converge::check_levels(self.levels)?;
        super::converge::check_ratio(self.ratio)?;
        let base = base_dof_steps(text, overrides)?;
        let variants = self.runs()? / self.levels;
        let per_level = match refine {
            Refine::Mesh | Refine::Step => self.ratio,
            Refine::Both => self.ratio * self.ratio,
        };
        let mut e = Estimate::new("taut converge");
        for l in 0..self.levels {
            e.add(
                variants,
                base * per_level.powi(l.min(i32::MAX as usize) as i32),
            );
        }
        Ok(e)
    }

    /// Number of runs, for a progress bar.
    pub fn runs(&self) -> Result<usize> {
        super::converge::check_levels(self.levels)?;
        let m = methods(self.methods.as_deref())?.map_or(1, |m| m.len());
        Ok(self.levels * m * spaces(self.discretizations.as_deref())?.len().max(1))
    }

    /// Parse and run the study on scene `text` with `overrides`, against
    /// the analytic reference where the scene has one
    /// ([`super::reference::analytic_w`]).
    pub fn run(
        &self,
        text: &str,
        overrides: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<ConvergeOutcome> {
        let refine: Refine = self.refine.parse()?;
        self.estimate(text, overrides)?.check(self.yes)?;
        let list = methods(self.methods.as_deref())?;
        let spaces = spaces(self.discretizations.as_deref())?;
        let analytic = &super::reference::analytic_w;
        if list.is_none() && self.discretizations.is_none() {
            return converge(
                text,
                overrides,
                refine,
                self.levels,
                self.ratio,
                analytic,
                progress,
            )
            .map(ConvergeOutcome::One);
        }
        let (studies, skipped) = converge_variants(
            text,
            overrides,
            &factories(&list),
            &spaces,
            refine,
            self.levels,
            self.ratio,
            analytic,
            progress,
        )?;
        Ok(ConvergeOutcome::Variants { studies, skipped })
    }
}

/// `taut precision`: work against precision over a (mesh, Δt) grid.
#[derive(Debug, Clone)]
pub struct PrecisionRequest {
    /// `lagrange,penalty,…`.
    pub formulations: String,
    /// Time integrators (`--methods`); the scene's own when absent.
    pub methods: Option<String>,
    /// Space discretizations (`--discretizations`); the scene's own when absent.
    pub discretizations: Option<String>,
    /// Grid levels per axis.
    pub levels: usize,
    /// Refinement ratio (integer).
    pub ratio: usize,
    /// Runs stepped together (`--batch`).
    pub batch: Option<usize>,
    /// Start even above the cost bound (`--yes`, [`super::cost`]).
    pub yes: bool,
}

impl PrecisionRequest {
    /// The study's estimated work: grid point (i, j) at N₀·rⁱ elements and
    /// Δt₀/rʲ for every formulation, method and discretization, and the
    /// reference one level beyond the finest on both.
    pub fn estimate(&self, text: &str, overrides: &[String]) -> Result<Estimate> {
        // in range first, then the scene
        super::precision::check_levels(self.levels)?;
        super::precision::check_ratio(self.ratio)?;
        let sc = crate::resolve::resolve_scene(text, overrides)?;
        // the study's own refusal of an overflowing ratio comes first
        super::precision::reference_elements(sc.elements, self.ratio, self.levels)?;
        let base = run_dof_steps(&sc);
        let variants = (self.runs()? - 1) / (self.levels * self.levels);
        let r = self.ratio as f64;
        let level = |k: usize| r.powi(k.min(i32::MAX as usize) as i32);
        let mut e = Estimate::new("taut precision");
        e.add(1, base * level(self.levels) * level(self.levels));
        for i in 0..self.levels {
            for j in 0..self.levels {
                e.add(variants, base * level(i) * level(j));
            }
        }
        Ok(e)
    }

    /// Number of runs (with the reference run), for a progress bar.
    pub fn runs(&self) -> Result<usize> {
        super::precision::check_levels(self.levels)?;
        let f = parse_formulations(&self.formulations)?.len();
        let m = methods(self.methods.as_deref())?.map_or(1, |m| m.len());
        let s = spaces(self.discretizations.as_deref())?.len().max(1);
        Ok(1 + m * s * f * self.levels * self.levels)
    }

    /// Parse and run the study on scene `text` with `overrides`.
    pub fn run(
        &self,
        text: &str,
        overrides: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Precision> {
        self.estimate(text, overrides)?.check(self.yes)?;
        let formulations = parse_formulations(&self.formulations)?;
        let list = methods(self.methods.as_deref())?;
        let spaces = spaces(self.discretizations.as_deref())?;
        precision_variants(
            text,
            overrides,
            (&factories(&list), &spaces),
            &formulations,
            (self.levels, self.ratio, batch_lanes(self.batch)?),
            progress,
        )
    }
}
