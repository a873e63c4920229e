//! A study as the application layer ([`crate::app`]) hands it over: typed
//! methods, formulations and discretizations, a batch width. The words of
//! the front ends (`--methods newmark,bathe`, Python's `methods=`) become
//! these values once, at the edge ([`crate::app::words`]); here they are
//! estimated and run, for the CLI and the Python module alike.

use crate::error::{Error, Result};
use crate::integrate::MethodFactory;
use crate::scene::Formulation;

use super::compare::{CompareSpec, Comparison, NotRun, compare_methods};
use super::converge::{
    ConvergeRow, Convergence, Ladder, MethodStudy, Refine, converge, converge_variants,
};
use super::cost::{Estimate, run_dof_steps};
use super::precision::{Precision, precision_variants};
use super::space::SpaceChoice;
use super::sweep::BatchWidth;

/// `--batch B` (Python: `batch=`): 1 ..= [`crate::integrate::MAX_LANES`] runs
/// stepped together, or the automatic width when absent.
pub(crate) fn batch_width(b: Option<usize>) -> Result<BatchWidth> {
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

/// A batch width as a number of lanes.
pub fn lanes(b: BatchWidth) -> usize {
    match b {
        BatchWidth::Auto => super::sweep::AUTO_BATCH_LANES,
        BatchWidth::Fixed(b) => b,
    }
}

/// [`batch_width`] as a number of lanes.
pub(crate) fn batch_lanes(b: Option<usize>) -> Result<usize> {
    Ok(lanes(batch_width(b)?))
}

/// The scene a study starts from (its own resolution), for its estimate.
fn base_dof_steps(text: &str, overrides: &[String]) -> Result<f64> {
    Ok(run_dof_steps(&crate::resolve::resolve_scene(
        text, overrides,
    )?))
}

/// How many variants a study runs per grid point: every method (one: the
/// scene's own when none is named) under every discretization (likewise).
fn variants(methods: &[&'static dyn MethodFactory], spaces: &[SpaceChoice]) -> usize {
    methods.len().max(1) * spaces.len().max(1)
}

/// `taut compare`: formulations × methods × discretizations of one scene.
#[derive(Clone)]
pub struct CompareStudy {
    /// The formulations compared (at least one).
    pub formulations: Vec<Formulation>,
    /// Time integrators (`--methods`); empty: the scene's own.
    pub methods: Vec<&'static dyn MethodFactory>,
    /// Space discretizations (`--discretizations`); empty: the scene's own.
    pub discretizations: Vec<SpaceChoice>,
    /// The formulation the differences are measured against.
    pub reference: Formulation,
    /// The method they are measured against: an index into `methods` (0
    /// when `methods` is empty).
    pub reference_method: usize,
    /// Runs stepped together (`--batch`).
    pub batch: BatchWidth,
    /// Start even above the cost bound (`--yes`, [`super::cost`]).
    pub yes: bool,
}

impl CompareStudy {
    /// The study's estimated work: every run at the scene's resolution.
    pub fn estimate(&self, text: &str, overrides: &[String]) -> Result<Estimate> {
        let mut e = Estimate::new("taut compare");
        e.add(self.runs(), base_dof_steps(text, overrides)?);
        Ok(e)
    }

    /// Number of runs, for a progress bar (an estimate: the reference
    /// formulation is run too when not listed).
    pub fn runs(&self) -> usize {
        self.formulations.len() * variants(&self.methods, &self.discretizations)
    }

    /// Run the comparison on scene `text` with `overrides`.
    pub fn run(
        &self,
        text: &str,
        overrides: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Comparison> {
        self.estimate(text, overrides)?.check(self.yes)?;
        let spec = CompareSpec {
            methods: self.methods.clone(),
            formulations: self.formulations.clone(),
            discretizations: self.discretizations.clone(),
            reference_method: self.reference_method,
            reference_discretization: 0,
            reference: self.reference,
            batch: lanes(self.batch),
        };
        compare_methods(text, overrides, &spec, progress)
    }
}

/// `taut converge`: a refinement ladder, per method and discretization.
#[derive(Clone)]
pub struct ConvergeStudy {
    /// Mesh, step or both.
    pub refine: Refine,
    /// Levels (≥ 3 for observed orders).
    pub levels: usize,
    /// Refinement ratio between levels.
    pub ratio: f64,
    /// Time integrators (`--methods`); empty: the scene's own.
    pub methods: Vec<&'static dyn MethodFactory>,
    /// Space discretizations (`--discretizations`); empty: the scene's own.
    pub discretizations: Vec<SpaceChoice>,
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

impl ConvergeStudy {
    /// The study's estimated work: level l refines the scene's mesh and/or
    /// step by ratio^l, for every method and discretization (with `both`,
    /// the split runs of level ℓ's mesh at level ℓ − 1's Δt too).
    pub fn estimate(&self, text: &str, overrides: &[String]) -> Result<Estimate> {
        // in range first: the estimate loops over the levels
        super::converge::check_levels(self.levels)?;
        super::converge::check_ratio(self.ratio)?;
        let base = base_dof_steps(text, overrides)?;
        let variants = self.runs()? / self.levels;
        let per_level = match self.refine {
            Refine::Mesh | Refine::Step => self.ratio,
            Refine::Both => self.ratio * self.ratio,
        };
        let mut e = Estimate::new("taut converge");
        let power = |x: f64, l: usize| x.powi(l.min(i32::MAX as usize) as i32);
        for l in 0..self.levels {
            e.add(variants, base * power(per_level, l));
            // --refine both: level ℓ's mesh at level ℓ − 1's Δt
            if self.refine == Refine::Both && l > 0 {
                e.add(
                    variants,
                    base * power(self.ratio, l) * power(self.ratio, l - 1),
                );
            }
        }
        Ok(e)
    }

    /// Number of runs, for a progress bar.
    pub fn runs(&self) -> Result<usize> {
        super::converge::check_levels(self.levels)?;
        Ok(self.levels * variants(&self.methods, &self.discretizations))
    }

    /// Run the study on scene `text` with `overrides`, against the analytic
    /// reference where the scene has one ([`super::reference::analytic_w`]).
    pub fn run(
        &self,
        text: &str,
        overrides: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<ConvergeOutcome> {
        self.estimate(text, overrides)?.check(self.yes)?;
        let analytic = &super::reference::analytic_w;
        if self.methods.is_empty() && self.discretizations.is_empty() {
            return converge(
                text,
                overrides,
                self.refine,
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
            &self.methods,
            &self.discretizations,
            Ladder {
                refine: self.refine,
                levels: self.levels,
                ratio: self.ratio,
            },
            analytic,
            progress,
        )?;
        Ok(ConvergeOutcome::Variants { studies, skipped })
    }
}

/// `taut precision`: work against precision over a (mesh, Δt) grid.
#[derive(Clone)]
pub struct PrecisionStudy {
    /// The formulations studied (at least one).
    pub formulations: Vec<Formulation>,
    /// Time integrators (`--methods`); empty: the scene's own.
    pub methods: Vec<&'static dyn MethodFactory>,
    /// Space discretizations (`--discretizations`); empty: the scene's own.
    pub discretizations: Vec<SpaceChoice>,
    /// Grid levels per axis.
    pub levels: usize,
    /// Refinement ratio (integer).
    pub ratio: usize,
    /// Runs stepped together (`--batch`).
    pub batch: BatchWidth,
    /// Start even above the cost bound (`--yes`, [`super::cost`]).
    pub yes: bool,
}

impl PrecisionStudy {
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
        let f = self.formulations.len();
        let v = variants(&self.methods, &self.discretizations);
        Ok(1 + v * f * self.levels * self.levels)
    }

    /// Run the study on scene `text` with `overrides`.
    pub fn run(
        &self,
        text: &str,
        overrides: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Precision> {
        self.estimate(text, overrides)?.check(self.yes)?;
        precision_variants(
            text,
            overrides,
            (&self.methods, &self.discretizations),
            &self.formulations,
            (self.levels, self.ratio, lanes(self.batch)),
            progress,
        )
    }
}

/// `taut uncertainty`: the family of one scene (h and Δt refined together
/// and apart) and every quantity's numerical uncertainty.
#[derive(Debug, Clone, Copy)]
pub struct UncertaintyStudy {
    /// Diagonal levels K (`super::uncertainty::LEVELS`).
    pub levels: usize,
    /// The most the family may cost, in runs of the scene, when a level is
    /// added (`--max-cost`, [`super::uncertainty::DEFAULT_MAX_COST`]).
    pub max_cost: f64,
    /// Start even above the cost bound (`--yes`, [`super::cost`]).
    pub yes: bool,
}

impl UncertaintyStudy {
    /// The study's estimated work: every run of the family.
    pub fn estimate(&self, text: &str, overrides: &[String]) -> Result<Estimate> {
        super::uncertainty::estimate(text, overrides, self.levels)
    }

    /// Number of runs, for a progress bar: 2K − 1.
    pub fn runs(&self) -> Result<usize> {
        Ok(2 * super::uncertainty::check_levels(self.levels)? - 1)
    }

    /// Run the family on scene `text` with `overrides`.
    pub fn run(
        &self,
        text: &str,
        overrides: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<super::uncertainty::Uncertainty> {
        self.estimate(text, overrides)?.check(self.yes)?;
        super::uncertainty::uncertainty_within(
            text,
            overrides,
            self.levels,
            self.max_cost,
            progress,
        )
    }
}
