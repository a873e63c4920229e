//! Each command's options, declared once for both front ends.
//!
//! A command's options are one struct here (`CompareArgs`, `SweepArgs`, …):
//! its fields are the options' names, its doc comments their help, its
//! [`Default`] their defaults. The `taut` binary takes it as its
//! subcommand's arguments (with the `clap` feature each struct derives
//! `clap::Args`: the CLI flattens it into the subcommand) and the Python
//! module takes it as the keyword arguments of the function of the same
//! name, passed as JSON (`serde`, unknown names refused). Each struct then
//! makes its study's typed request in one place ([`CompareArgs::study`],
//! …): the words are read, the counts checked and the defaults applied
//! here, so both front ends refuse the same words with the same message
//! (naming the CLI's flag; the Python module names its keyword instead).
//! An option several commands share is a group declared once ([`Runs`],
//! [`FormulationList`], [`CostBound`], [`Workers`], [`Batch`], [`Levels`],
//! [`Ratio`], [`AccuracyTarget`]) and flattened into each, a command whose
//! help says more of it changing that with `mut_arg`;
//! Python's keywords are checked against the command's clap arguments.
//! `schema` lists every command's options (name, default, help), and the
//! Python module's tests hold its functions' signatures against it.
//!
//! What stays with a front end is what only it has: where the scene comes
//! from (a file; Python: a path, a bundled name, TOML text or a dict), the
//! `--set`/`--unset` words (Python: a dict), the output folder, progress.

use std::path::PathBuf;
use std::str::FromStr;
use std::sync::LazyLock;

use serde::Deserialize;

use super::words;
use crate::error::{Error, Result};
use crate::scene::Formulation;
#[cfg(feature = "clap")]
use crate::scene::MeshKind;
use crate::study::request;
#[cfg(feature = "clap")]
use crate::study::verify::case::Space;

/// An option's value as a front end gives it, before it is read: the
/// command line's text, or Python's number or string. Counts and ratios
/// are kept as text so that every value a front end can give — `-1`, `x`,
/// `2.5`, a number past any integer type — reaches the library's check and
/// gets its error naming the option, the value and the range, never a
/// parser's message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Word(pub String);

impl FromStr for Word {
    type Err = std::convert::Infallible;
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        Ok(Word(s.to_string()))
    }
}

impl std::fmt::Display for Word {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl<'de> Deserialize<'de> for Word {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Text;
        impl serde::de::Visitor<'_> for Text {
            type Value = Word;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a number or its text")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<Word, E> {
                Ok(Word(v.to_string()))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<Word, E> {
                Ok(Word(v.to_string()))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<Word, E> {
                Ok(Word(v.to_string()))
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<Word, E> {
                Ok(Word(v.to_string()))
            }
        }
        d.deserialize_any(Text)
    }
}

impl Word {
    /// The text as a count: a whole number checked by `check` (whose error
    /// names the option and its range); text that is no whole number (`-1`,
    /// `x`, `1.5`, a number past `usize`) gets the same error, with the text
    /// given, as a number out of range.
    pub fn count(&self, check: impl Fn(usize) -> Result<usize>) -> Result<usize> {
        match self.0.trim().parse::<usize>() {
            Ok(n) => check(n),
            // 0 is outside every count's range: its error, with the text given
            Err(_) => match check(0) {
                Err(Error::Invalid { field, allowed, .. }) => {
                    Err(Error::invalid(field, &self.0, allowed))
                }
                other => other,
            },
        }
    }

    /// The text as a real number checked by `check`; text that is no number
    /// gets the error `check` gives for NaN, with the text given.
    pub fn real(&self, check: impl Fn(f64) -> Result<f64>) -> Result<f64> {
        match self.0.trim().parse::<f64>() {
            Ok(v) => check(v),
            Err(_) => match check(f64::NAN) {
                Err(Error::Invalid { field, allowed, .. }) => {
                    Err(Error::invalid(field, &self.0, allowed))
                }
                other => other,
            },
        }
    }
}

/// An optional count ([`Word::count`]).
fn count(w: &Option<Word>, check: impl Fn(usize) -> Result<usize>) -> Result<Option<usize>> {
    w.as_ref().map(|w| w.count(check)).transpose()
}

/// The help of `--methods`: the names come from the method registry, so a
/// method of one's own needs no edit here.
#[cfg(feature = "clap")]
fn methods_help(what: &str, default: &str) -> String {
    format!(
        "Comma-separated time integrators{what} (default: {default}): {}",
        crate::scene::method_names().join(", ")
    )
}

/// The help of `compare --formulations`: the names come from
/// [`Formulation::ALL`], so a new contact law needs no edit here.
#[cfg(feature = "clap")]
fn formulations_help() -> String {
    format!(
        "Comma-separated formulations: {}",
        Formulation::ALL.map(Formulation::name).join(", ")
    )
}

/// The help of a study's `--discretizations`: the kinds come from
/// [`MeshKind::ALL`] (a modal basis with its optional J), so a new kind
/// needs no edit here.
#[cfg(feature = "clap")]
fn discretizations_help() -> String {
    let kinds: Vec<String> = MeshKind::ALL
        .iter()
        .map(|k| match k {
            MeshKind::Hermite => k.name().to_string(),
            _ => format!("{}[:J]", k.name()),
        })
        .collect();
    format!(
        "Comma-separated space discretizations to study side by side: {} (J: the number of \
         modes; default the scene's mesh.modes). Default: the scene's own",
        kinds.join(", ")
    )
}

/// The help of `verify --discretizations`: the names come from the
/// matrix's own list ([`Space::ALL`]).
#[cfg(feature = "clap")]
fn verify_discretizations_help() -> String {
    format!(
        "Comma-separated discretizations: {} (default: all; string elements run on the string cases)",
        Space::ALL.map(Space::name).join(", ")
    )
}

/// The help of `verify --formulations`: how many there are, in words,
/// counted from [`Formulation::ALL`].
#[cfg(feature = "clap")]
fn verify_formulations_help() -> String {
    const WORDS: [&str; 9] = [
        "one", "two", "three", "four", "five", "six", "seven", "eight", "nine",
    ];
    let n = Formulation::ALL.len();
    let all = WORDS
        .get(n - 1)
        .map_or_else(|| n.to_string(), |w| w.to_string());
    format!("Comma-separated contact formulations (default: all {all})")
}

/// Every contact formulation, comma-separated in the order of
/// [`Formulation::ALL`]: the default of `--formulations`.
pub(crate) static ALL_FORMULATIONS: LazyLock<String> =
    LazyLock::new(|| Formulation::ALL.map(Formulation::name).join(","));

/// The time integrators and space discretizations a study runs side by
/// side (`--methods`, `--discretizations`): declared once, flattened into
/// each study's options (a command whose help says more of them changes
/// it with `mut_arg`).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct Runs {
    /// Comma-separated time integrators (default: the scene's own).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "LIST", help = methods_help("", "the scene's own"))
    )]
    pub methods: Option<String>,
    /// Comma-separated space discretizations to study side by side: the
    /// kinds of `mesh.kind`, a modal one with `:J` (J: the number of modes;
    /// default the scene's mesh.modes). Default: the scene's own.
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "LIST", help = discretizations_help())
    )]
    pub discretizations: Option<String>,
}

impl Runs {
    /// The two lists as [`words`] reads them.
    fn lists(&self) -> (Option<&str>, Option<&str>) {
        (self.methods.as_deref(), self.discretizations.as_deref())
    }
}

/// The contact formulations a study runs side by side (`--formulations`;
/// default: every one, in the order of [`Formulation::ALL`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct FormulationList {
    /// Comma-separated formulations (default: every one, in the order of
    /// `Formulation::ALL`).
    #[cfg_attr(
        feature = "clap",
        arg(long, default_value = ALL_FORMULATIONS.as_str(), help = formulations_help())
    )]
    pub formulations: String,
}

impl Default for FormulationList {
    fn default() -> Self {
        FormulationList {
            formulations: ALL_FORMULATIONS.to_string(),
        }
    }
}

/// `--yes`: a study starts even above the cost bound.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct CostBound {
    /// Start even when the study's estimated cost is above 1e11
    /// DOF-steps (unknowns × steps over its runs; docs/scene.md#study-cost).
    #[cfg_attr(feature = "clap", arg(long))]
    pub yes: bool,
}

/// `--threads N`: the worker threads of a study that runs in parallel.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct Workers {
    /// Worker threads (default: all cores; at most 4 per core, 1024).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "N", allow_hyphen_values = true)
    )]
    pub threads: Option<Word>,
}

impl Workers {
    /// The count: 1 ..= the most worker threads the library starts.
    fn count(&self) -> Result<Option<usize>> {
        count(&self.threads, crate::study::threads::check_threads)
    }
}

/// `--batch B`: runs stepped together when they share their effective
/// matrix. The range is `request::batch_width`'s; each command's help
/// says what it steps together (`mut_arg`).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct Batch {
    /// Runs stepped together when they share their effective matrix
    /// (1 ..= 8, 1: every run alone; default 4). The results are the same
    /// whatever it is.
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "B", allow_hyphen_values = true)
    )]
    pub batch: Option<Word>,
}

impl Batch {
    /// The width given, checked: 1 ..= the most runs stepped together.
    fn width(&self) -> Result<Option<usize>> {
        count(&self.batch, |n| request::batch_width(Some(n)).map(|_| n))
    }
}

/// The digits a default of [`Levels`] is written with: a const generic
/// cannot be a `&str`, and clap's `default_value` takes one.
#[cfg(feature = "clap")]
const DIGITS: [&str; 10] = ["0", "1", "2", "3", "4", "5", "6", "7", "8", "9"];

/// `--levels K` of a refinement study, `D` levels by default (a digit).
/// The range is the study's own (its `check_levels`), which the command's
/// help states (`mut_arg`).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct Levels<const D: u8> {
    /// Number of levels.
    #[cfg_attr(
        feature = "clap",
        arg(long, default_value = Self::DEFAULT, allow_hyphen_values = true)
    )]
    pub levels: Word,
}

#[cfg(feature = "clap")]
impl<const D: u8> Levels<D> {
    /// `D` as text, evaluated when compiled: a default of more than one
    /// digit fails to build rather than at the command's start.
    const DEFAULT: &'static str = DIGITS[D as usize];
}

impl<const D: u8> Default for Levels<D> {
    fn default() -> Self {
        Levels {
            levels: Word(D.to_string()),
        }
    }
}

/// [`Levels`] as the keywords give it (serde derives no const generic).
#[derive(Deserialize)]
struct LevelsGiven {
    levels: Option<Word>,
}

impl<'de, const D: u8> Deserialize<'de> for Levels<D> {
    fn deserialize<De: serde::Deserializer<'de>>(d: De) -> std::result::Result<Self, De::Error> {
        let given = LevelsGiven::deserialize(d)?;
        Ok(given
            .levels
            .map_or_else(Levels::default, |levels| Levels { levels }))
    }
}

/// `--ratio R`: the refinement ratio between levels, 2 by default. What
/// it may be (a real > 1, an integer ≥ 2) is the study's own check, which
/// the command's help states (`mut_arg`).
#[derive(Debug, Clone, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct Ratio {
    /// Refinement ratio between levels.
    #[cfg_attr(
        feature = "clap",
        arg(long, default_value = "2", allow_hyphen_values = true)
    )]
    pub ratio: Word,
}

impl Default for Ratio {
    fn default() -> Self {
        Ratio {
            ratio: Word("2".to_string()),
        }
    }
}

/// `--tolerance TOL` with `--quantity Q` and `--max-cost F`: refine until
/// the numerical uncertainty u_num of a quantity is at most TOL (`taut run`
/// for one run, `taut sweep` for each point). Each command's help says
/// what is refined (`mut_arg`).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct AccuracyTarget {
    /// Refine until the numerical uncertainty u_num of --quantity is at
    /// most TOL (absolute, in its unit) (docs/accuracy.md).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "TOL", allow_hyphen_values = true)
    )]
    pub tolerance: Option<Word>,
    /// What --tolerance is on: a quantity of the registry
    /// (loss_fraction_span, the default; loss_fraction, force_mean, …).
    #[cfg_attr(feature = "clap", arg(long, value_name = "Q", requires = "tolerance"))]
    pub quantity: Option<String>,
    /// `--max-cost`, which needs `--tolerance` here (refused without it).
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub max_cost: MaxCost,
}

/// `--max-cost F`: the most a study may cost, as a multiple of one run at
/// the scene's resolution (unknowns × steps). With `--tolerance` it bounds
/// the refinement, pilots included (default 64); on `taut uncertainty` the
/// family grown by a finer level when level 0 is pre-asymptotic (default
/// 128). Each command's help says which (`mut_arg`).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct MaxCost {
    /// The most the refinement may cost, pilots included, as a multiple
    /// of a run at the scene's resolution (default 64).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "F", allow_hyphen_values = true)
    )]
    pub max_cost: Option<Word>,
}

impl MaxCost {
    /// The word given, if any.
    pub fn word(&self) -> Option<&str> {
        self.max_cost.as_ref().map(|w| w.0.as_str())
    }
}

impl AccuracyTarget {
    /// The error target, if one is given; `--quantity` or `--max-cost`
    /// without `--tolerance` is refused, the latter as bounding `refined`
    /// (`the refinement of --tolerance`).
    fn target(&self, refined: &str) -> Result<Option<super::Tolerance>> {
        if self.tolerance.is_none() {
            if let Some(q) = &self.quantity {
                return Err(Error::invalid(
                    "--quantity",
                    q,
                    "is what --tolerance is on: give tolerance too",
                ));
            }
            if let Some(f) = self.max_cost.word() {
                return Err(Error::invalid(
                    "--max-cost",
                    f,
                    format!("bounds {refined}: give tolerance too"),
                ));
            }
        }
        words::sweep_tolerance(
            self.tolerance.as_ref().map(|w| w.0.as_str()),
            self.quantity.as_deref(),
            self.max_cost.word(),
        )
    }
}

/// `taut run` / `taut.run`: one scene, or an accuracy-targeted run.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(
        mut_arg("tolerance", |a| a.help("Refine mesh and Δt until the numerical uncertainty u_num of --quantity is at most TOL (absolute, in its unit), as a one-point `taut sweep --tolerance` does, and print a u_num next to every result (docs/accuracy.md)")),
        mut_arg("quantity", |a| a.help("What --tolerance is on: a quantity `taut sweep --tolerance` takes (loss_fraction_span, the default; loss_fraction_span_sustained, loss_fraction, force_mean, force_std, …)")),
        mut_arg("max_cost", |a| a.help("With --tolerance: the most the run may cost, pilots included, as a multiple of its run at the scene's resolution (default 64)").requires("tolerance")),
    )
)]
pub struct RunArgs {
    /// `--tolerance`, `--quantity`, `--max-cost`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub target: AccuracyTarget,
}

impl RunArgs {
    /// The error target, if one is given.
    pub fn tolerance(&self) -> Result<Option<super::Tolerance>> {
        self.target.target("the refinement of --tolerance")
    }
}

/// `taut compare` / `taut.compare`: formulations × methods ×
/// discretizations of one scene.
#[derive(Debug, Clone, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(
        mut_arg("batch", |a| a.help("Runs stepped together when they share their effective matrix (formulations under one method and discretization; 1 ..= 8, 1: every run alone; default 4). The table is the same whatever it is")),
    )
)]
pub struct CompareArgs {
    /// `--formulations`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub formulations: FormulationList,
    /// `--methods`, `--discretizations`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub runs: Runs,
    /// The formulation the differences are measured against.
    #[cfg_attr(feature = "clap", arg(long, default_value = "lagrange"))]
    pub reference: String,
    /// The method the differences are measured against (default: the
    /// first of --methods).
    #[cfg_attr(feature = "clap", arg(long, value_name = "METHOD"))]
    pub reference_method: Option<String>,
    /// `--batch`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub batch: Batch,
    /// `--yes`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub cost: CostBound,
}

impl Default for CompareArgs {
    fn default() -> Self {
        CompareArgs {
            formulations: FormulationList::default(),
            runs: Runs::default(),
            reference: "lagrange".to_string(),
            reference_method: None,
            batch: Batch::default(),
            cost: CostBound::default(),
        }
    }
}

impl CompareArgs {
    /// The typed study.
    pub fn study(&self) -> Result<request::CompareStudy> {
        words::compare(
            &self.formulations.formulations,
            self.runs.lists(),
            (&self.reference, self.reference_method.as_deref()),
            self.batch.width()?,
            self.cost.yes,
        )
    }
}

/// `taut converge` / `taut.converge`: a refinement ladder.
#[derive(Debug, Clone, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(
        mut_arg("methods", |a| a.help(methods_help(" to study side by side", "the scene's own"))),
        mut_arg("levels", |a| a.help("Number of levels (2 ..= 12; ≥ 3 for observed orders)")),
        mut_arg("ratio", |a| a.help("Refinement ratio between levels (> 1)")),
    )
)]
pub struct ConvergeArgs {
    /// What to refine: mesh, step or both.
    #[cfg_attr(feature = "clap", arg(long, default_value = "both"))]
    pub refine: String,
    /// `--levels`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub levels: Levels<4>,
    /// `--ratio`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub ratio: Ratio,
    /// `--methods`, `--discretizations`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub runs: Runs,
    /// `--yes`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub cost: CostBound,
}

impl Default for ConvergeArgs {
    fn default() -> Self {
        ConvergeArgs {
            refine: "both".to_string(),
            levels: Levels::default(),
            ratio: Ratio::default(),
            runs: Runs::default(),
            cost: CostBound::default(),
        }
    }
}

impl ConvergeArgs {
    /// The typed study: levels and ratio by the study's own ranges.
    pub fn study(&self) -> Result<request::ConvergeStudy> {
        use crate::study::converge::{check_levels, check_ratio};
        let levels = self.levels.levels.count(check_levels)?;
        let ratio = self.ratio.ratio.real(check_ratio)?;
        words::converge(
            &self.refine,
            (levels, ratio),
            self.runs.lists(),
            self.cost.yes,
        )
    }
}

/// `taut uncertainty` / `taut.uncertainty`: the numerical uncertainty of
/// every reported quantity of one scene (solution verification).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(
        mut_arg("levels", |a| a.help("Diagonal levels of the family (3 ..= 6; 2K − 1 runs)")),
        mut_arg("max_cost", |a| a.help("The most the family may cost, in runs of the scene (unknowns × steps), when level 0 is pre-asymptotic and a finer level is added (default 128: a three-level family may grow to four)")),
    )
)]
pub struct UncertaintyArgs {
    /// `--levels`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub levels: Levels<4>,
    /// `--max-cost`: when level 0 is pre-asymptotic and a finer level is
    /// added (default 128 runs of the scene: three levels may grow to four).
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub max_cost: MaxCost,
    /// `--yes`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub cost: CostBound,
}

impl UncertaintyArgs {
    /// The typed study: the levels by the study's own range.
    pub fn study(&self) -> Result<request::UncertaintyStudy> {
        let levels = self
            .levels
            .levels
            .count(crate::study::uncertainty::check_levels)?;
        words::uncertainty(levels, self.max_cost.word(), self.cost.yes)
    }
}

/// `taut precision` / `taut.precision`: work against precision over a
/// (mesh, Δt) grid.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(
        mut_arg("formulations", |a| a.help("Comma-separated formulations")),
        mut_arg("levels", |a| a.help("Grid levels per axis (N₀·rⁱ, Δt₀/rʲ, i, j < levels; 1 ..= 5)")),
        mut_arg("ratio", |a| a.help("Refinement ratio (an integer ≥ 2)")),
        mut_arg("batch", |a| a.help("Runs stepped together when they share their effective matrix (the formulations of a grid point; 1 ..= 8, 1: every run alone; default 4). The table is the same whatever it is")),
    )
)]
pub struct PrecisionArgs {
    /// `--formulations`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub formulations: FormulationList,
    /// `--methods`, `--discretizations`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub runs: Runs,
    /// `--levels`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub levels: Levels<3>,
    /// `--ratio`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub ratio: Ratio,
    /// `--batch`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub batch: Batch,
    /// `--yes`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub cost: CostBound,
}

impl PrecisionArgs {
    /// The typed study: levels and ratio by the study's own ranges.
    pub fn study(&self) -> Result<request::PrecisionStudy> {
        use crate::study::precision::{check_levels, check_ratio};
        let levels = self.levels.levels.count(check_levels)?;
        let ratio = self.ratio.ratio.count(check_ratio)?;
        words::precision(
            &self.formulations.formulations,
            self.runs.lists(),
            (levels, ratio),
            self.batch.width()?,
            self.cost.yes,
        )
    }
}

/// `taut sweep` / `taut.sweep`: scene values or dimensionless axes over a
/// grid, or a list of points, in parallel; resumable.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(
        mut_arg("tolerance", |a| a.help("Refine each point until the numerical uncertainty u_num of --quantity is at most TOL (absolute, in its unit), only as far as it must; adds u_num and the resolution used to sweep.csv (docs/sweeps.md)")),
        mut_arg("quantity", |a| a.help("What --tolerance is on: a column of sweep.csv (loss_fraction_span, the default; loss_fraction_span_sustained, loss_fraction, loss_fraction_support, force_mean, force_std, force_max, force_min, first_loss_position)")),
        mut_arg("max_cost", |a| a.help("With --tolerance: the most a point may cost, pilots included, as a multiple of its run at the scene's resolution (default 64)").requires("tolerance")),
        mut_arg("batch", |a| a.help("Runs stepped together when they share their effective matrix (1 ..= 8; 1: every run alone; default 4, one AVX2 vector of lanes). The records are the same bytes whatever the width")),
    )
)]
pub struct SweepArgs {
    /// An axis, key=start:stop:count, or key=v1,v2,... (a list of
    /// values); one or two.
    #[cfg_attr(
        feature = "clap",
        arg(
            long = "vary",
            value_name = "KEY=START:STOP:COUNT",
            required_unless_present = "points"
        )
    )]
    pub vary: Vec<String>,
    /// A list of points instead of a grid: a CSV file whose header
    /// names the keys and whose rows are the points (docs/sweeps.md).
    /// (Python: a list of points, which the module writes as `vary` lists
    /// walked together.)
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "FILE.csv", conflicts_with_all = ["vary", "log"])
    )]
    pub points: Option<PathBuf>,
    /// The `vary` lists are a list of points, walked together (Python's
    /// `points=`; the CLI reads its points from a file instead).
    #[cfg_attr(feature = "clap", arg(skip))]
    pub paired: bool,
    /// Logarithmic spacing on every axis.
    #[cfg_attr(feature = "clap", arg(long))]
    pub log: bool,
    /// Run only the points with index ≡ i (mod n): i/n.
    #[cfg_attr(feature = "clap", arg(long, value_name = "I/N"))]
    pub shard: Option<String>,
    /// Run each point a second time with twice the elements and half the
    /// step, and add the change of P_l and of its in-span part as columns
    /// (and, for a 2-D sweep, a map of where the loss map is converged).
    #[cfg_attr(feature = "clap", arg(long))]
    pub check_refinement: bool,
    /// `--tolerance`, `--quantity`, `--max-cost`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub target: AccuracyTarget,
    /// `--threads`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub workers: Workers,
    /// `--batch`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub batch: Batch,
    /// `--yes`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub cost: CostBound,
}

/// A sweep as [`SweepArgs`] give it: what [`super::SweepRequest`] takes
/// besides the scene, the overrides and the folder.
#[derive(Debug, Clone)]
pub struct SweepStudy {
    /// The axes (a grid's, or a list of points' columns).
    pub axes: Vec<crate::study::sweep::Axis>,
    /// The axes are a list of points, walked together.
    pub points: bool,
    /// Run each point refined too.
    pub check_refinement: bool,
    /// Refine each point until its u_num is within a tolerance.
    pub tolerance: Option<crate::study::sweep::SweepTolerance>,
    /// One shard of the points.
    pub shard: Option<crate::study::sweep::Shard>,
    /// Worker threads (none: one per core).
    pub threads: Option<usize>,
    /// Runs stepped together.
    pub batch: crate::study::sweep::BatchWidth,
    /// Start even above the cost bound.
    pub yes: bool,
}

impl SweepArgs {
    /// The typed sweep: axes parsed (or read from the points file), counts
    /// checked.
    pub fn study(&self) -> Result<SweepStudy> {
        let threads = self.workers.count()?;
        let batch = request::batch_width(self.batch.width()?)?;
        let paired = self.paired || self.points.is_some();
        let axes = match &self.points {
            Some(file) => crate::study::sweep::read_points(file)?,
            None => words::axes(&self.vary, self.log && !paired)?,
        };
        if paired && self.log {
            return Err(Error::invalid(
                "--log",
                "true",
                "spaces a grid's ranges; a list of points has none",
            ));
        }
        let shard = self
            .shard
            .as_deref()
            .map(crate::study::sweep::Shard::parse)
            .transpose()?;
        let tolerance = self
            .target
            .target("a point's refinement under --tolerance")?;
        Ok(SweepStudy {
            axes,
            points: paired,
            check_refinement: self.check_refinement,
            tolerance,
            shard,
            threads,
            batch,
            yes: self.cost.yes,
        })
    }
}

/// `taut verify`: the verification matrix.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct VerifyArgs {
    /// Comma-separated time integrators (default: every built-in one).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "LIST", help = methods_help("", "every built-in one"))
    )]
    pub methods: Option<String>,
    /// Comma-separated discretizations of the matrix (default: all;
    /// string elements run on the string cases).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "LIST", help = verify_discretizations_help())
    )]
    pub discretizations: Option<String>,
    /// Comma-separated contact formulations (default: all of
    /// [`Formulation::ALL`]).
    #[cfg_attr(feature = "clap", arg(long, help = verify_formulations_help()))]
    pub formulations: Option<String>,
    /// The cut-down matrix of the default test suite (two support pairs).
    #[cfg_attr(feature = "clap", arg(long))]
    pub quick: bool,
    /// Accept this run's finest errors as the golden ones: rewrite
    /// golden/verify/quick_errors.json of the source tree (the rows that
    /// ran) and list every constant that moved.
    #[cfg_attr(feature = "clap", arg(long))]
    pub update_golden: bool,
    /// `--threads`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub workers: Workers,
}

impl VerifyArgs {
    /// The typed matrix into `out`.
    pub fn request(&self, out: PathBuf) -> Result<super::VerifyRequest> {
        let threads = self.workers.count()?;
        Ok(super::VerifyRequest {
            selection: crate::study::verify::selection(
                self.methods.as_deref(),
                self.discretizations.as_deref(),
                self.formulations.as_deref(),
                self.quick,
            )?,
            threads,
            out,
            update_golden: self.update_golden,
        })
    }
}

/// `taut gate`: a golden suite re-run against its references.
#[derive(Debug, Clone, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(
        mut_arg("batch", |a| a.help("Cases stepped together when their runs share the effective matrix (1 ..= 8, 1: every case alone; default 4). The checks are the same whatever it is")),
    )
)]
pub struct GateArgs {
    /// Suite folder of case files (*.json).
    #[cfg_attr(feature = "clap", arg(default_value = "golden"))]
    pub suite: PathBuf,
    /// Accept this run's values as the new references and show what changed.
    #[cfg_attr(feature = "clap", arg(long))]
    pub update: bool,
    /// `--batch`.
    #[serde(flatten)]
    #[cfg_attr(feature = "clap", command(flatten))]
    pub batch: Batch,
}

impl Default for GateArgs {
    fn default() -> Self {
        GateArgs {
            suite: PathBuf::from("golden"),
            update: false,
            batch: Batch::default(),
        }
    }
}

impl GateArgs {
    /// The typed gate, its reports into `out`.
    pub fn request(&self, out: PathBuf) -> Result<super::GateRequest> {
        Ok(super::GateRequest {
            batch: request::batch_lanes(self.batch.width()?)?,
            suite: self.suite.clone(),
            out,
            update: self.update,
        })
    }
}

/// `taut modes` / `taut.modes`: natural frequencies and mode shapes.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct ModesArgs {
    /// Number of modes (default 10, or the mesh's unknowns if fewer).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "K", allow_hyphen_values = true)
    )]
    pub count: Option<Word>,
}

impl ModesArgs {
    /// How many modes (≥ 1 here; the scene's own upper bound is the study's).
    pub fn count(&self) -> Result<Option<usize>> {
        count(&self.count, |n| {
            if n >= 1 {
                Ok(n)
            } else {
                Err(Error::invalid("--count", n, "must be ≥ 1"))
            }
        })
    }
}

/// `taut replay`: a saved contact problem solved again.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct ReplayArgs {
    /// The saved problem (JSON).
    pub problem: PathBuf,
    /// Override the saved iteration limit (1 ..= 4294967295).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "N", allow_hyphen_values = true)
    )]
    pub max_iter: Option<Word>,
    /// Override the saved complementarity solver: `direct` or `clarabel`.
    #[cfg_attr(feature = "clap", arg(long))]
    pub solver: Option<String>,
}

impl ReplayArgs {
    /// The typed replay.
    pub fn request(&self) -> Result<super::ReplayRequest> {
        let max_iter = count(&self.max_iter, |n| {
            if n >= 1 && u32::try_from(n).is_ok() {
                Ok(n)
            } else {
                Err(Error::invalid(
                    "--max-iter",
                    n,
                    format!("must be in 1 ..= {}", u32::MAX),
                ))
            }
        })?;
        Ok(super::ReplayRequest {
            max_iter: max_iter.map(|n| u32::try_from(n).expect("checked")),
            solver: self
                .solver
                .as_deref()
                .map(words::complementarity_solver)
                .transpose()?,
            problem: self.problem.clone(),
        })
    }
}

/// A command's options as [`from_json`] reads them: the names it accepts
/// are the command's flags as clap declares them (each option group
/// flattened in), so the keyword check has no list of its own; and what
/// the options make, read and checked ([`CommandArgs::typed`]), so that a
/// front end's glue is one generic path for every command.
#[cfg(feature = "clap")]
pub trait CommandArgs: clap::Args + for<'de> Deserialize<'de> {
    /// The command's name (`compare`: `taut compare`, `taut.compare`).
    const COMMAND: &'static str;

    /// Keywords the Python module passes that the CLI does not take (a
    /// field clap skips).
    const PYTHON_ONLY: &'static [&'static str] = &[];

    /// What the options make: the typed study, or what the command's
    /// request takes of them.
    type Typed;

    /// The options read and checked ([`CompareArgs::study`], …).
    fn typed(&self) -> Result<Self::Typed>;

    /// Every keyword the command accepts, in the order of its `--help`.
    fn keywords() -> Vec<String> {
        let command = Self::augment_args(clap::Command::new("keywords"));
        let declared = command.get_arguments().map(|a| a.get_id().to_string());
        declared
            .chain(Self::PYTHON_ONLY.iter().map(|k| k.to_string()))
            .collect()
    }
}

/// A command's [`CommandArgs`], one row: the command, its options (with
/// the keywords only Python passes, in brackets), what they make and the
/// function that makes it. A study of one scene writes its row beside its
/// [`super::StudyCommand`] (`app/compare.rs`); the others are here.
macro_rules! command_args {
    ($command:literal: $args:ty $([$($python:literal),*])? => $typed:ty, $make:expr) => {
        #[cfg(feature = "clap")]
        impl $crate::app::args::CommandArgs for $args {
            const COMMAND: &'static str = $command;
            $(const PYTHON_ONLY: &'static [&'static str] = &[$($python),*];)?
            type Typed = $typed;
            fn typed(&self) -> $crate::error::Result<$typed> {
                $make(self)
            }
        }
    };
}
pub(crate) use command_args;

command_args!("run": RunArgs => Option<super::Tolerance>, RunArgs::tolerance);
command_args!("sweep": SweepArgs ["paired"] => SweepStudy, SweepArgs::study);
command_args!("modes": ModesArgs => Option<usize>, ModesArgs::count);

/// Every command's options as the struct of this module declares them:
/// `(command, options)` for each command the Python module offers as well
/// (`run`, the studies of [`super::each_study`], `sweep`, `modes`), for its
/// tests to hold the Python signatures against.
#[cfg(feature = "clap")]
pub fn schema() -> Vec<(&'static str, Vec<OptionSchema>)> {
    struct Studies(Vec<(&'static str, Vec<OptionSchema>)>);
    impl super::StudyVisitor for Studies {
        fn visit<S: super::StudyCommand>(&mut self)
        where
            S::Outcome: Send,
        {
            let args = options_of::<S::Args>();
            self.0.push((<S::Args as CommandArgs>::COMMAND, args));
        }
    }
    let mut all = Studies(vec![("run", options_of::<RunArgs>())]);
    super::each_study(&mut all);
    all.0.push(("sweep", options_of::<SweepArgs>()));
    all.0.push(("modes", options_of::<ModesArgs>()));
    all.0
}

/// Read a command's options from JSON (the Python module's keyword
/// arguments): unknown names and values of the wrong kind are refused,
/// naming the option (an unknown one with the names allowed).
#[cfg(feature = "clap")]
pub fn from_json<A: CommandArgs>(json: &str) -> Result<A> {
    const ALLOWED: &str = "an option of this command, of its kind";
    let flag = |key: &str| format!("--{}", key.replace('_', "-"));
    // the names first: the option groups are flattened, which serde's own
    // check of unknown fields does not see through
    if let Ok(serde_json::Value::Object(given)) = serde_json::from_str(json) {
        let known = A::keywords();
        if let Some(key) = given.keys().find(|k| !known.contains(k)) {
            let expected = match known.as_slice() {
                [] => "there are no options".to_string(),
                [one] => format!("expected `{one}`"),
                many => format!("expected one of `{}`", many.join("`, `")),
            };
            let reason = format!("unknown field `{key}`, {expected}");
            return Err(Error::invalid(flag(key), reason, ALLOWED));
        }
        // a value of the wrong kind in a flattened group has no path:
        // the keyword is the one whose value alone is refused
        let all = serde_json::Value::Object(given.clone());
        return serde_json::from_value::<A>(all).map_err(|e| {
            let culprit = given.iter().find_map(|(k, v)| {
                let alone = [(k.clone(), v.clone())].into_iter().collect();
                let refused = serde_json::from_value::<A>(serde_json::Value::Object(alone));
                refused.err().map(|e| (flag(k), e))
            });
            let (field, e) = culprit.unwrap_or_else(|| ("arguments".to_string(), e));
            Error::invalid(field, e.to_string(), ALLOWED)
        });
    }
    // not an object of keywords: the arguments as a whole are refused
    serde_json::from_str(json).map_err(|e| Error::invalid("arguments", e.to_string(), ALLOWED))
}

/// One option as a front end declares it.
#[cfg(feature = "clap")]
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OptionSchema {
    /// Its name (the struct's field; the CLI's flag with `-` for `_`).
    pub name: String,
    /// Its default as text (`None`: no default, or a switch that is off).
    pub default: Option<String>,
    /// Its help text.
    pub help: String,
}

/// A command's options as its clap arguments declare them (hidden ones
/// left out).
#[cfg(feature = "clap")]
fn options_of<A: clap::Args>() -> Vec<OptionSchema> {
    A::augment_args(clap::Command::new("schema"))
        .get_arguments()
        .filter(|a| !a.is_hide_set())
        .map(|a| OptionSchema {
            name: a.get_id().to_string(),
            default: a
                .get_default_values()
                .first()
                .map(|v| v.to_string_lossy().into_owned())
                .filter(|v| v != "false"),
            help: a.get_help().map(|h| h.to_string()).unwrap_or_default(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_that_is_no_number_gets_the_range_error_with_its_text() {
        let check = |n: usize| {
            if (1..=8).contains(&n) {
                Ok(n)
            } else {
                Err(Error::invalid("--batch", n, "must be in 1 ..= 8"))
            }
        };
        for bad in ["-1", "x", "1.5", "99999999999999999999", "0"] {
            let e = Word(bad.into()).count(check).unwrap_err().to_string();
            assert!(
                e.contains("--batch") && e.contains(bad) && e.contains("1 ..= 8"),
                "{e}"
            );
        }
        assert_eq!(Word(" 3 ".into()).count(check).unwrap(), 3);
    }

    #[cfg(feature = "clap")]
    #[test]
    fn python_s_keywords_are_read_and_unknown_ones_refused() {
        let a: CompareArgs = from_json(r#"{"batch": 2, "methods": "bathe", "yes": true}"#).unwrap();
        assert_eq!(a.batch.batch, Some(Word("2".into())));
        assert_eq!(a.runs.methods.as_deref(), Some("bathe"));
        assert!(a.cost.yes);
        assert_eq!(a.formulations.formulations, *ALL_FORMULATIONS);
        let s: SweepArgs =
            from_json(r#"{"vary": ["a=1,2"], "paired": true, "threads": 3}"#).unwrap();
        assert!(s.paired);
        assert_eq!(s.workers.threads, Some(Word("3".into())));
        // an unknown keyword is named, with the ones allowed (options of
        // the flattened groups among them)
        let e = from_json::<CompareArgs>(r#"{"bach": 2}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bach"), "{e}");
        for allowed in [
            "`formulations`",
            "`methods`",
            "`discretizations`",
            "`batch`",
            "`yes`",
        ] {
            assert!(e.contains(allowed), "{e}");
        }
        assert!(!e.contains("paired"), "{e}");
        assert!(from_json::<CompareArgs>(r#"{"paired": true}"#).is_err());
        // a value of the wrong kind is named, in a group or not
        for (json, flag) in [
            (r#"{"levels": true}"#, "--levels"),
            (r#"{"refine": "mesh", "yes": 3}"#, "--yes"),
            (r#"{"methods": 3}"#, "--methods"),
        ] {
            let e = from_json::<ConvergeArgs>(json).unwrap_err().to_string();
            assert!(e.contains(flag), "{json}: {e}");
        }
        let e = from_json::<ConvergeArgs>("[1]").unwrap_err().to_string();
        assert!(e.contains("arguments"), "{e}");
    }

    #[cfg(feature = "clap")]
    #[test]
    fn the_lists_in_the_help_are_the_enums() {
        let s = schema();
        let help = |cmd: &str, opt: &str| {
            let o = s.iter().find(|(c, _)| *c == cmd).unwrap();
            o.1.iter().find(|x| x.name == opt).unwrap().help.clone()
        };
        for cmd in ["compare", "converge", "precision"] {
            let h = help(cmd, "discretizations");
            for k in MeshKind::ALL {
                assert!(h.contains(k.name()), "{cmd}: {h}");
            }
            let h = help(cmd, "methods");
            for m in crate::scene::method_names() {
                assert!(h.contains(&*m), "{cmd}: {h}");
            }
        }
        let h = help("compare", "formulations");
        for f in Formulation::ALL {
            assert!(h.contains(f.name()), "{h}");
        }
    }

    #[cfg(feature = "clap")]
    #[test]
    fn the_schema_holds_the_defaults_the_structs_apply() {
        // clap's defaults (what the CLI and the schema show) are the
        // structs' own (what Python's missing keywords get)
        let s = schema();
        let find = |cmd: &str, opt: &str| {
            s.iter()
                .find(|(c, _)| *c == cmd)
                .and_then(|(_, o)| o.iter().find(|x| x.name == opt))
                .unwrap_or_else(|| panic!("{cmd} {opt}"))
                .default
                .clone()
        };
        let c = ConvergeArgs::default();
        assert_eq!(find("converge", "levels"), Some(c.levels.levels.0));
        assert_eq!(find("converge", "ratio"), Some(c.ratio.ratio.0));
        assert_eq!(find("converge", "refine"), Some(c.refine));
        let p = PrecisionArgs::default();
        assert_eq!(find("precision", "levels"), Some(p.levels.levels.0));
        assert_eq!(
            find("precision", "formulations"),
            Some(p.formulations.formulations)
        );
        let k = CompareArgs::default();
        assert_eq!(find("compare", "reference"), Some(k.reference));
        assert_eq!(find("compare", "batch"), None);
        // a keyword left out takes the command's default through its
        // flattened group, as the CLI's flag does
        let p: PrecisionArgs = from_json("{}").unwrap();
        assert_eq!(Some(p.levels.levels.0), find("precision", "levels"));
        assert_eq!(Some(p.ratio.ratio.0), find("precision", "ratio"));
        let u: UncertaintyArgs = from_json(r#"{"yes": true}"#).unwrap();
        assert_eq!(Some(u.levels.levels.0), find("uncertainty", "levels"));
        let c: ConvergeArgs = from_json(r#"{"levels": 5}"#).unwrap();
        assert_eq!(c.levels.levels, Word("5".into()));
        assert_eq!(find("converge", "levels"), Some("4".into()));
    }
}
