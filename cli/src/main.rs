//! The `taut` command line: a thin layer over the library's application
//! layer ([`taut::app`]). Each subcommand reads its arguments (the clap
//! structs below; counts and lists checked at this edge, with the library's
//! messages), makes the typed request, calls `taut::app::<command>` and
//! prints the outcome ([`terminal`]).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

mod terminal;

use taut::app::{self, Frontend, Note, SceneSource};
use taut::report::{compare_table, converge_table, gate_table};
use taut::study::request::ConvergeOutcome;

/// taut: dynamic contact of a tensioned beam and a moving mass–spring.
#[derive(Parser)]
#[command(version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scene and write history.csv, summary.json and force.svg.
    Run {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Override a scene value: --set beam.tension=2.01e4 (repeatable).
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Remove a scene key so that its default applies (repeatable; applied
        /// before the --set overrides): --unset integrator.rho_inf.
        #[arg(long = "unset", value_name = "KEY.PATH")]
        unset: Vec<String>,
        /// Output folder (default: out/<scene name>).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Choose mesh and Δt from measured convergence so the error of
        /// --quantity is at most TOL (relative; absolute for loss_fraction),
        /// and print an estimated error next to every result (docs/accuracy.md).
        #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
        tolerance: Option<String>,
        /// What --tolerance is on: force (0–20 Hz contact force), force_raw,
        /// loss_fraction or displacement.
        #[arg(long, value_name = "Q", requires = "tolerance")]
        quantity: Option<String>,
    },
    /// Refine mesh, step or both and report errors, observed orders and GCI
    /// (converge.csv, converge.json, converge.svg).
    Converge {
        /// Scene file (TOML).
        scene: PathBuf,
        /// What to refine: mesh, step or both.
        #[arg(long, default_value = "both")]
        refine: String,
        /// Number of levels (2 ..= 12; ≥ 3 for observed orders).
        #[arg(long, default_value = "4", allow_hyphen_values = true)]
        levels: String,
        /// Refinement ratio between levels (> 1).
        #[arg(long, default_value = "2", allow_hyphen_values = true)]
        ratio: String,
        #[arg(long, help = methods_help("to study side by side", "the scene's own"))]
        methods: Option<String>,
        /// Comma-separated space discretizations to study side by side:
        /// hermite, galerkin[:J], modal[:J] (J: the number of modes; default
        /// the scene's mesh.modes). Default: the scene's own.
        #[arg(long, value_name = "LIST")]
        discretizations: Option<String>,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Remove a scene key so that its default applies (repeatable; applied
        /// before the --set overrides): --unset integrator.rho_inf.
        #[arg(long = "unset", value_name = "KEY.PATH")]
        unset: Vec<String>,
        /// Output folder (default: out/<scene name>-converge).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Start even when the study's estimated cost is above 1e11
        /// DOF-steps (unknowns × steps over its runs; docs/scene.md#study-cost).
        #[arg(long)]
        yes: bool,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Solution verification: run a small family of the scene refined in
    /// space and time, together and apart, and give every reported quantity
    /// its numerical uncertainty u_num (GCI, Eça–Hoekstra least squares),
    /// observed orders and the space/time split (uncertainty.csv,
    /// uncertainty.json, uncertainty.svg; docs/verification.md).
    Uncertainty {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Diagonal levels of the family (3 ..= 6; 2K − 1 runs).
        #[arg(long, default_value = "4", allow_hyphen_values = true)]
        levels: String,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Remove a scene key so that its default applies (repeatable; applied
        /// before the --set overrides): --unset integrator.rho_inf.
        #[arg(long = "unset", value_name = "KEY.PATH")]
        unset: Vec<String>,
        /// Output folder (default: out/<scene name>-uncertainty).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Start even when the study's estimated cost is above 1e11
        /// DOF-steps (unknowns × steps over its runs; docs/scene.md#study-cost).
        #[arg(long)]
        yes: bool,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Re-run a golden suite and compare each quantity with its reference
    /// (gate.json, junit.xml); exit code 1 when any check fails.
    Gate {
        /// Suite folder of case files (*.json).
        #[arg(default_value = "golden")]
        suite: PathBuf,
        /// Output folder for gate.json and junit.xml (default: out/gate).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Accept this run's values as the new references and show what changed.
        #[arg(long)]
        update: bool,
        /// Cases stepped together when their runs share the effective
        /// matrix (1 ..= 8, 1: every case alone; default 4). The checks are
        /// the same whatever it is.
        #[arg(long, value_name = "B", allow_hyphen_values = true)]
        batch: Option<String>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Sweep scene values or the study's dimensionless axes (speed_ratio,
    /// tension_ratio, mass_ratio, stiffness_ratio) in parallel; resumable.
    Sweep {
        /// Scene file (TOML).
        scene: PathBuf,
        /// An axis, key=start:stop:count, or key=v1,v2,... (a list of
        /// values); one or two.
        #[arg(
            long = "vary",
            value_name = "KEY=START:STOP:COUNT",
            required_unless_present = "points"
        )]
        vary: Vec<String>,
        /// A list of points instead of a grid: a CSV file whose header
        /// names the keys and whose rows are the points (docs/sweeps.md).
        #[arg(long, value_name = "FILE.csv", conflicts_with_all = ["vary", "log"])]
        points: Option<PathBuf>,
        /// Logarithmic spacing on every axis.
        #[arg(long)]
        log: bool,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Remove a scene key so that its default applies (repeatable; applied
        /// before the --set overrides): --unset integrator.rho_inf.
        #[arg(long = "unset", value_name = "KEY.PATH")]
        unset: Vec<String>,
        /// Output folder (default: out/<scene name>-sweep).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Start even when the study's estimated cost is above 1e11
        /// DOF-steps (unknowns × steps over its runs; docs/scene.md#study-cost).
        #[arg(long)]
        yes: bool,
        /// Run only the points with index ≡ i (mod n): i/n.
        #[arg(long, value_name = "I/N")]
        shard: Option<String>,
        /// Run each point a second time with twice the elements and half the
        /// step, and add the change of P_l and of its in-span part as columns
        /// (and, for a 2-D sweep, a map of where the loss map is converged).
        #[arg(long)]
        check_refinement: bool,
        /// Refine each point until the numerical uncertainty u_num of
        /// --quantity is at most TOL (absolute, in its unit), only as far as
        /// it must; adds u_num and the resolution used to sweep.csv
        /// (docs/sweeps.md).
        #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
        tolerance: Option<String>,
        /// What --tolerance is on: a column of sweep.csv (loss_fraction_span,
        /// the default; loss_fraction, loss_fraction_support, force_mean,
        /// force_std, force_max, force_min, first_loss_position).
        #[arg(long, value_name = "Q", requires = "tolerance")]
        quantity: Option<String>,
        /// With --tolerance: the most a point may cost, pilots included, as a
        /// multiple of its run at the scene's resolution (default 64).
        #[arg(
            long,
            value_name = "F",
            requires = "tolerance",
            allow_hyphen_values = true
        )]
        max_cost: Option<String>,
        /// Worker threads (default: all cores; at most 4 per core, 1024).
        #[arg(long, value_name = "N", allow_hyphen_values = true)]
        threads: Option<String>,
        /// Runs stepped together when they share their effective matrix
        /// (1 ..= 8; 1: every run alone; default 4, one AVX2 vector of
        /// lanes). The records are the same bytes whatever the width.
        #[arg(long, value_name = "B", allow_hyphen_values = true)]
        batch: Option<String>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Natural frequencies and mode shapes of the scene's beam, attachments
    /// included (modes.csv, mode_shapes.csv; docs/output.md#modes).
    Modes {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Number of modes (default 10, or the mesh's unknowns if fewer).
        #[arg(long, value_name = "K", allow_hyphen_values = true)]
        count: Option<String>,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Output folder (default: out/<scene name>-modes).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Join shard folders of one sweep into a single result.
    Merge {
        /// Shard output folders.
        #[arg(required = true)]
        shards: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Work–precision: error against cost for each formulation over a
    /// (mesh, Δt) grid, with the Pareto front (precision.csv, precision.svg).
    Precision {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Comma-separated formulations.
        #[arg(long, default_value = "lagrange,penalty,complementarity,impact")]
        formulations: String,
        #[arg(long, help = methods_help("", "the scene's own"))]
        methods: Option<String>,
        /// Comma-separated space discretizations to study side by side:
        /// hermite, galerkin[:J], modal[:J] (J: the number of modes; default
        /// the scene's mesh.modes). Default: the scene's own.
        #[arg(long, value_name = "LIST")]
        discretizations: Option<String>,
        /// Grid levels per axis (N₀·rⁱ, Δt₀/rʲ, i, j < levels; 1 ..= 5).
        #[arg(long, default_value = "3", allow_hyphen_values = true)]
        levels: String,
        /// Refinement ratio (an integer ≥ 2).
        #[arg(long, default_value = "2", allow_hyphen_values = true)]
        ratio: String,
        /// Runs stepped together when they share their effective matrix
        /// (the formulations of a grid point; 1 ..= 8, 1: every run alone;
        /// default 4). The table is the same whatever it is.
        #[arg(long, value_name = "B", allow_hyphen_values = true)]
        batch: Option<String>,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Remove a scene key so that its default applies (repeatable; applied
        /// before the --set overrides): --unset integrator.rho_inf.
        #[arg(long = "unset", value_name = "KEY.PATH")]
        unset: Vec<String>,
        /// Output folder (default: out/<scene name>-precision).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Start even when the study's estimated cost is above 1e11
        /// DOF-steps (unknowns × steps over its runs; docs/scene.md#study-cost).
        #[arg(long)]
        yes: bool,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Run the verification matrix: every method × discretization ×
    /// formulation × support pair on the declared cases (manufactured and
    /// exact), each observed order beside the expected one (verify.csv,
    /// verify.json); exit code 1 when any row fails.
    Verify {
        #[arg(long, help = methods_help("", "every built-in one"))]
        methods: Option<String>,
        /// Comma-separated discretizations: hermite, graded, galerkin,
        /// modal (default: all; string elements run on the string cases).
        #[arg(long, value_name = "LIST")]
        discretizations: Option<String>,
        /// Comma-separated contact formulations (default: all four).
        #[arg(long)]
        formulations: Option<String>,
        /// The cut-down matrix of the default test suite (two support pairs).
        #[arg(long)]
        quick: bool,
        /// Worker threads (default: all cores; at most 4 per core, 1024).
        #[arg(long, value_name = "N", allow_hyphen_values = true)]
        threads: Option<String>,
        /// Output folder (default: out/verify).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Solve a saved contact problem again (a `failed_contact_step_N.json`
    /// written by a failed run) and print the forces or the failure.
    Replay {
        /// The saved problem (JSON).
        problem: PathBuf,
        /// Override the saved iteration limit (1 ..= 4294967295).
        #[arg(long, value_name = "N", allow_hyphen_values = true)]
        max_iter: Option<String>,
        /// Override the saved complementarity solver: `direct` or `clarabel`.
        #[arg(long)]
        solver: Option<String>,
    },
    /// Run one scene under several contact formulations and time integrators
    /// and compare them (compare.csv, compare.json, compare.svg).
    Compare {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Comma-separated formulations: lagrange, penalty, complementarity, impact.
        #[arg(long, default_value = "lagrange,penalty,complementarity,impact")]
        formulations: String,
        #[arg(long, help = methods_help("", "the scene's own"))]
        methods: Option<String>,
        /// Comma-separated space discretizations to study side by side:
        /// hermite, galerkin[:J], modal[:J] (J: the number of modes; default
        /// the scene's mesh.modes). Default: the scene's own.
        #[arg(long, value_name = "LIST")]
        discretizations: Option<String>,
        /// The formulation the differences are measured against.
        #[arg(long, default_value = "lagrange")]
        reference: String,
        /// The method the differences are measured against (default: the
        /// first of --methods).
        #[arg(long, value_name = "METHOD")]
        reference_method: Option<String>,
        /// Runs stepped together when they share their effective matrix
        /// (formulations under one method and discretization; 1 ..= 8,
        /// 1: every run alone; default 4). The table is the same whatever it is.
        #[arg(long, value_name = "B", allow_hyphen_values = true)]
        batch: Option<String>,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Remove a scene key so that its default applies (repeatable; applied
        /// before the --set overrides): --unset integrator.rho_inf.
        #[arg(long = "unset", value_name = "KEY.PATH")]
        unset: Vec<String>,
        /// Output folder (default: out/<scene name>-compare).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Start even when the study's estimated cost is above 1e11
        /// DOF-steps (unknowns × steps over its runs; docs/scene.md#study-cost).
        #[arg(long)]
        yes: bool,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Multi-span lines generated from a scene's `[line]` table
    /// (docs/lines.md#the-line-generator-g1g7).
    Line {
        #[command(subcommand)]
        action: LineAction,
    },
}

/// `taut line …`.
#[derive(Subcommand)]
enum LineAction {
    /// Print the scene with its `[line]` expanded into the plain keys it
    /// stands for (beam length, mesh, droppers, steady arms, messenger): TOML
    /// that runs identically when given back.
    Expand {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Remove a scene key so that its default applies (repeatable; applied
        /// before the --set overrides).
        #[arg(long = "unset", value_name = "KEY.PATH")]
        unset: Vec<String>,
    },
}

/// The help of `--methods`: the names come from the method registry
/// (`taut::scene::method_names`), so a new method needs no edit here.
fn methods_help(what: &str, default: &str) -> String {
    let what = if what.is_empty() {
        String::new()
    } else {
        format!(" {what}")
    };
    format!(
        "Comma-separated time integrators{what} (default: {default}): {}",
        taut::scene::method_names().join(", ")
    )
}

/// The override list of `--unset` and `--set`: the removals first (so that
/// `--unset integrator --set integrator.method=newmark` replaces a table),
/// then the values, each in its order.
fn overrides(unset: Vec<String>, set: Vec<String>) -> Vec<String> {
    unset
        .iter()
        .map(|k| app::words::unset(k))
        .chain(set)
        .collect()
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            scene,
            set,
            unset,
            out,
            quiet,
            tolerance,
            quantity,
        } => cmd_run(
            scene,
            overrides(unset, set),
            out,
            quiet,
            tolerance,
            quantity,
        )
        .map(|()| true),
        Command::Replay {
            problem,
            max_iter,
            solver,
        } => cmd_replay(problem, max_iter, solver).map(|()| true),
        Command::Sweep {
            scene,
            vary,
            points,
            log,
            set,
            unset,
            out,
            shard,
            check_refinement,
            tolerance,
            quantity,
            max_cost,
            threads,
            batch,
            quiet,
            yes,
        } => cmd_sweep(
            scene,
            (&vary, points.as_deref(), log, check_refinement),
            (tolerance, quantity, max_cost),
            overrides(unset, set),
            out,
            shard.as_deref(),
            (threads, batch),
            (quiet, yes),
        ),
        Command::Verify {
            methods,
            discretizations,
            formulations,
            quick,
            threads,
            out,
            quiet,
        } => cmd_verify(
            (
                methods.as_deref(),
                discretizations.as_deref(),
                formulations.as_deref(),
            ),
            quick,
            threads,
            out,
            quiet,
        ),
        Command::Merge { shards, out } => cmd_merge(&shards, &out),
        Command::Modes {
            scene,
            count,
            set,
            out,
        } => cmd_modes(scene, count, set, out).map(|()| true),
        Command::Precision {
            scene,
            formulations,
            methods,
            discretizations,
            levels,
            ratio,
            batch,
            set,
            unset,
            out,
            quiet,
            yes,
        } => cmd_precision(
            scene,
            (
                &formulations,
                methods.as_deref(),
                discretizations.as_deref(),
            ),
            (levels, ratio, batch),
            overrides(unset, set),
            out,
            (quiet, yes),
        )
        .map(|()| true),
        Command::Gate {
            suite,
            out,
            update,
            batch,
            quiet,
        } => cmd_gate(suite, out, (update, batch), quiet),
        Command::Converge {
            scene,
            refine,
            levels,
            ratio,
            methods,
            discretizations,
            set,
            unset,
            out,
            quiet,
            yes,
        } => cmd_converge(
            scene,
            &refine,
            (levels, ratio),
            (methods.as_deref(), discretizations.as_deref()),
            overrides(unset, set),
            out,
            (quiet, yes),
        )
        .map(|()| true),
        Command::Uncertainty {
            scene,
            levels,
            set,
            unset,
            out,
            quiet,
            yes,
        } => {
            cmd_uncertainty(scene, levels, overrides(unset, set), out, (quiet, yes)).map(|()| true)
        }
        Command::Compare {
            scene,
            formulations,
            methods,
            discretizations,
            reference,
            reference_method,
            batch,
            set,
            unset,
            out,
            quiet,
            yes,
        } => cmd_compare(
            scene,
            &formulations,
            (methods.as_deref(), discretizations.as_deref()),
            (&reference, reference_method.as_deref(), batch),
            overrides(unset, set),
            out,
            (quiet, yes),
        ),
        Command::Line {
            action: LineAction::Expand { scene, set, unset },
        } => app::line::expand(&SceneSource::File(scene), &overrides(unset, set)).map(|text| {
            print!("{text}");
            true
        }),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        // tables were written, but a run, point, row or check failed
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// A count given on the command line (`--threads`, `--batch`, `--levels`,
/// `--ratio` of precision, `--max-iter`), checked by the library's `check`:
/// text that is not a whole number (`-1`, `x`, `1.5`, a number past
/// `usize`) gets the same error, naming the flag, the text and the range, as
/// a number out of range (not the parser's "unexpected argument" or
/// "invalid digit"). Every integer option of every subcommand goes through
/// here (`tests/cli.rs` tries each with `-1`).
fn count(
    text: Option<String>,
    check: impl Fn(usize) -> taut::Result<usize>,
) -> taut::Result<Option<usize>> {
    let Some(text) = text else { return Ok(None) };
    match text.trim().parse::<usize>() {
        Ok(n) => check(n).map(Some),
        // 0 is outside every count's range: its error, with the text given
        Err(_) => match check(0) {
            Err(taut::Error::Invalid { field, allowed, .. }) => {
                Err(taut::Error::invalid(field, text, allowed))
            }
            other => other.map(Some),
        },
    }
}

fn threads_arg(text: Option<String>) -> taut::Result<Option<usize>> {
    count(text, taut::study::threads::check_threads)
}

fn batch_arg(text: Option<String>) -> taut::Result<Option<usize>> {
    count(text, |n| {
        taut::study::request::batch_width(Some(n)).map(|_| n)
    })
}

/// A count with a default (clap gives the default's text when absent).
fn required_count(
    text: String,
    check: impl Fn(usize) -> taut::Result<usize>,
) -> taut::Result<usize> {
    Ok(count(Some(text), check)?.expect("a count was given"))
}

/// `taut replay --max-iter N`: 1 ..= u32::MAX, the solver's iteration limit.
fn max_iter_arg(text: Option<String>) -> taut::Result<Option<u32>> {
    let n = count(text, |n| {
        if n >= 1 && u32::try_from(n).is_ok() {
            Ok(n)
        } else {
            Err(taut::Error::invalid(
                "--max-iter",
                n,
                format!("must be in 1 ..= {}", u32::MAX),
            ))
        }
    })?;
    Ok(n.map(|n| u32::try_from(n).expect("checked")))
}

/// `taut converge --levels L --ratio R`: L by the study's own range, R a
/// number > 1 (text that is not a number gets the same error).
fn converge_levels_arg(levels: String, ratio: String) -> taut::Result<(usize, f64)> {
    use taut::study::converge::{check_levels, check_ratio};
    let levels = required_count(levels, check_levels)?;
    let ratio = match ratio.trim().parse::<f64>() {
        Ok(r) => check_ratio(r)?,
        Err(_) => match check_ratio(f64::NAN) {
            Err(taut::Error::Invalid { field, allowed, .. }) => {
                return Err(taut::Error::invalid(field, ratio, allowed));
            }
            other => other?,
        },
    };
    Ok((levels, ratio))
}

/// `taut precision --levels L --ratio R`, by the study's own ranges.
fn precision_levels_arg(levels: String, ratio: String) -> taut::Result<(usize, usize)> {
    use taut::study::precision::{check_levels, check_ratio};
    Ok((
        required_count(levels, check_levels)?,
        required_count(ratio, check_ratio)?,
    ))
}

/// Default output folder: out/<scene stem><suffix>.
fn default_dir(scene: &Path, suffix: &str) -> PathBuf {
    let stem = scene.file_stem().map(|s| s.to_string_lossy().into_owned());
    PathBuf::from("out").join(format!("{}{suffix}", stem.unwrap_or_else(|| "run".into())))
}

/// The terminal as the application layer's front end: a progress bar
/// (hidden with `--quiet`) and notes on stderr.
struct Terminal {
    bar: ProgressBar,
}

impl Terminal {
    fn new(unit: &str, quiet: bool) -> Terminal {
        if quiet {
            return Terminal {
                bar: ProgressBar::hidden(),
            };
        }
        let bar = ProgressBar::new(0);
        let template = format!(
            "{{spinner}} [{{elapsed_precise}}] {{bar:40}} {{pos}}/{{len}} {unit} ({{eta}} left)"
        );
        bar.set_style(ProgressStyle::with_template(&template).expect("valid template"));
        Terminal { bar }
    }

    /// Run `command` with this front end, the bar cleared after it.
    fn run<R>(&self, command: impl FnOnce(&dyn Frontend) -> R) -> R {
        let r = command(self);
        self.bar.finish_and_clear();
        r
    }
}

impl Frontend for Terminal {
    fn progress(&self, done: usize, total: usize) {
        self.bar.set_length(total as u64);
        self.bar.set_position(done as u64);
    }

    fn note(&self, note: Note<'_>) {
        self.bar.suspend(|| match note {
            Note::Cleared(text) => eprintln!("{text}"),
            Note::AboveBound(e) => {
                eprintln!("note: {} (above the bound; --yes given)", e.describe())
            }
            Note::FailureSaved(path) => {
                eprintln!("saved the failing contact problem to {}", path.display())
            }
        });
    }
}

/// A study of the scene file `scene` with overrides `set`, its outputs in
/// `out` (default: out/<scene stem><suffix>), run by `command` with a
/// progress bar of runs; returns its outcome and output folder.
fn on_scene<S, R>(
    (scene, set, out, suffix): (&Path, Vec<String>, Option<PathBuf>, &str),
    study: S,
    quiet: bool,
    command: fn(&app::StudyRequest<S>, &dyn Frontend) -> taut::Result<R>,
) -> taut::Result<(R, PathBuf)> {
    let dir = out.unwrap_or_else(|| default_dir(scene, suffix));
    let request = app::StudyRequest {
        scene: SceneSource::File(scene.to_path_buf()),
        set,
        study,
        out: Some(dir),
    };
    let outcome = Terminal::new("runs", quiet).run(|fe| command(&request, fe))?;
    Ok((outcome, request.out.expect("given")))
}

fn cmd_run(
    scene: PathBuf,
    set: Vec<String>,
    out: Option<PathBuf>,
    quiet: bool,
    tolerance: Option<String>,
    quantity: Option<String>,
) -> taut::Result<()> {
    let tolerance = tolerance
        .map(|t| app::words::tolerance(&t, quantity.as_deref()))
        .transpose()?;
    let dir = out.unwrap_or_else(|| default_dir(&scene, ""));
    let request = app::RunRequest {
        scene: SceneSource::File(scene.clone()),
        set,
        out: Some(dir.clone()),
        tolerance,
    };
    let unit = if tolerance.is_some() { "runs" } else { "steps" };
    let outcome = Terminal::new(unit, quiet).run(|fe| app::run(&request, fe))?;
    print!(
        "{}",
        terminal::summary(&scene, &dir, &outcome.summary, outcome.accuracy.as_ref())
    );
    Ok(())
}

fn cmd_modes(
    scene: PathBuf,
    count_text: Option<String>,
    set: Vec<String>,
    out: Option<PathBuf>,
) -> taut::Result<()> {
    // ≥ 1 here; the scene's own upper bound is the library's
    let count = count(count_text, |n| {
        if n >= 1 {
            Ok(n)
        } else {
            Err(taut::Error::invalid("--count", n, "must be ≥ 1"))
        }
    })?;
    let dir = out.unwrap_or_else(|| default_dir(&scene, "-modes"));
    let request = app::ModesRequest {
        scene: SceneSource::File(scene.clone()),
        set,
        count,
        out: Some(dir.clone()),
    };
    let m = Terminal::new("", true).run(|fe| app::modes(&request, fe))?;
    print!("{}", terminal::modes(&scene, &dir, &m));
    Ok(())
}

fn cmd_converge(
    scene: PathBuf,
    refine: &str,
    (levels, ratio): (String, String),
    words: (Option<&str>, Option<&str>),
    set: Vec<String>,
    out: Option<PathBuf>,
    (quiet, yes): (bool, bool),
) -> taut::Result<()> {
    let (levels, ratio) = converge_levels_arg(levels, ratio)?;
    let study = app::words::converge(refine, (levels, ratio), words, yes)?;
    let kind = format!("converge ({:?}, r = {ratio})", study.refine);
    let place = (scene.as_path(), set, out, "-converge");
    let (outcome, dir) = on_scene(place, study, quiet, app::converge)?;
    let table = match &outcome {
        ConvergeOutcome::One(c) => converge_table(c),
        ConvergeOutcome::Variants { studies, skipped } => {
            taut::report::converge_methods_table(studies, skipped)
        }
    };
    let files = "converge.csv, converge.json, converge.svg";
    print!("{}", terminal::study(&kind, &scene, &table, &dir, files));
    Ok(())
}

fn cmd_uncertainty(
    scene: PathBuf,
    levels: String,
    set: Vec<String>,
    out: Option<PathBuf>,
    (quiet, yes): (bool, bool),
) -> taut::Result<()> {
    let levels = required_count(levels, taut::study::uncertainty::check_levels)?;
    let study = app::words::uncertainty(levels, yes)?;
    let place = (scene.as_path(), set, out, "-uncertainty");
    let (u, dir) = on_scene(place, study, quiet, app::uncertainty)?;
    let runs = u.family.len();
    let kind = format!(
        "uncertainty ({} levels, {runs} runs in {:.2} s wall)",
        u.levels, u.wall_seconds
    );
    let files = "uncertainty.csv, uncertainty.json, uncertainty.svg";
    print!(
        "{}",
        terminal::study(&kind, &scene, &terminal::family(&u), &dir, files)
    );
    Ok(())
}

/// Returns whether every row passed (or is known, cannot, reported).
fn cmd_verify(
    (methods, spaces, formulations): (Option<&str>, Option<&str>, Option<&str>),
    quick: bool,
    threads: Option<String>,
    out: Option<PathBuf>,
    quiet: bool,
) -> taut::Result<bool> {
    let threads = threads_arg(threads)?;
    let request = app::VerifyRequest {
        selection: taut::study::verify::selection(methods, spaces, formulations, quick)?,
        threads,
        out: out.unwrap_or_else(|| PathBuf::from("out").join("verify")),
    };
    let v = Terminal::new("combinations", quiet).run(|fe| app::verify(&request, fe))?;
    println!(
        "taut {} — verify ({} rows, {:.1} s on {} threads)",
        env!("CARGO_PKG_VERSION"),
        v.rows.len(),
        v.wall_seconds,
        v.threads
    );
    print!("{}", taut::report::verify_table(&v.rows));
    println!(
        "  wrote    {}/{{verify.csv, verify.json, verify.md}}",
        request.out.display()
    );
    Ok(v.passed)
}

/// Returns whether the gate passed.
fn cmd_gate(
    suite: PathBuf,
    out: Option<PathBuf>,
    (update, batch): (bool, Option<String>),
    quiet: bool,
) -> taut::Result<bool> {
    let request = app::GateRequest {
        batch: taut::study::request::batch_lanes(batch_arg(batch)?)?,
        suite,
        out: out.unwrap_or_else(|| PathBuf::from("out").join("gate")),
        update,
    };
    let g = Terminal::new("cases", quiet).run(|fe| app::gate(&request, fe))?;
    println!(
        "taut {} — gate {}",
        env!("CARGO_PKG_VERSION"),
        request.suite.display()
    );
    print!("{}", gate_table(&g.report, update));
    println!(
        "  wrote    {}/{{gate.json, junit.xml}}",
        request.out.display()
    );
    Ok(g.passed)
}

/// Returns whether every point ran (the tables are written either way).
#[allow(clippy::too_many_arguments)]
fn cmd_sweep(
    scene: PathBuf,
    (vary, points, log, check_refinement): (&[String], Option<&std::path::Path>, bool, bool),
    (tolerance, quantity, max_cost): (Option<String>, Option<String>, Option<String>),
    set: Vec<String>,
    out: Option<PathBuf>,
    shard: Option<&str>,
    (threads, batch): (Option<String>, Option<String>),
    (quiet, yes): (bool, bool),
) -> taut::Result<bool> {
    let threads = threads_arg(threads)?;
    let batch = taut::study::request::batch_width(batch_arg(batch)?)?;
    let axes = match points {
        Some(file) => taut::study::sweep::read_points(file)?,
        None => app::words::axes(vary, log)?,
    };
    let shard = shard.map(taut::study::sweep::Shard::parse).transpose()?;
    let tolerance = app::words::sweep_tolerance(
        tolerance.as_deref(),
        quantity.as_deref(),
        max_cost.as_deref(),
    )?;
    let request = app::SweepRequest {
        scene: SceneSource::File(scene.clone()),
        set,
        axes,
        points: points.is_some(),
        check_refinement,
        tolerance,
        out: out.unwrap_or_else(|| default_dir(&scene, "-sweep")),
        files: true,
        shard,
        threads,
        batch,
        yes,
    };
    let s = Terminal::new("runs", quiet).run(|fe| app::sweep(&request, fe))?;
    println!(
        "taut {} — sweep {}",
        env!("CARGO_PKG_VERSION"),
        scene.display()
    );
    let ran = s.records.len() - s.resumed.min(s.records.len());
    println!(
        "  {} runs{}{} in {:.2} s wall ({:.2} runs/s, {} threads); {} stopped with an error",
        s.records.len(),
        shard.map_or(String::new(), |s| format!(
            " (shard {}/{})",
            s.index, s.count
        )),
        if s.resumed > 0 {
            format!(" ({ran} run now, {} kept from an earlier start)", s.resumed)
        } else {
            String::new()
        },
        s.wall_seconds,
        ran as f64 / s.wall_seconds.max(1e-9),
        s.threads,
        s.stopped()
    );
    println!(
        "  wrote    {}/{{sweep.csv, sweep_force.csv, sweep_loss.csv, timing.csv, runs/}}",
        request.out.display()
    );
    print!("{}", terminal::maps(&s.maps, shard.is_some()));
    eprint!("{}", terminal::stopped(&s.records));
    Ok(s.stopped() == 0)
}

/// Returns whether every point of the merged sweep ran.
fn cmd_merge(shards: &[PathBuf], out: &Path) -> taut::Result<bool> {
    let m = app::merge(shards, out, &Terminal::new("", true))?;
    println!(
        "taut {} — merged {} shards: {} runs into {}",
        env!("CARGO_PKG_VERSION"),
        shards.len(),
        m.records.len(),
        out.display()
    );
    print!("{}", terminal::maps(&m.maps, false));
    eprint!("{}", terminal::stopped(&m.records));
    Ok(m.stopped() == 0)
}

fn cmd_precision(
    scene: PathBuf,
    (formulations, methods, discretizations): (&str, Option<&str>, Option<&str>),
    (levels, ratio, batch): (String, String, Option<String>),
    set: Vec<String>,
    out: Option<PathBuf>,
    (quiet, yes): (bool, bool),
) -> taut::Result<()> {
    let (levels, ratio) = precision_levels_arg(levels, ratio)?;
    let batch = batch_arg(batch)?;
    let study = app::words::precision(
        formulations,
        (methods, discretizations),
        (levels, ratio),
        batch,
        yes,
    )?;
    let place = (scene.as_path(), set, out, "-precision");
    let (p, dir) = on_scene(place, study, quiet, app::precision)?;
    let table = taut::report::precision_table(&p);
    print!(
        "{}",
        terminal::study(
            "precision",
            &scene,
            &table,
            &dir,
            "precision.csv, precision.svg"
        )
    );
    Ok(())
}

fn cmd_replay(
    problem: PathBuf,
    max_iter: Option<String>,
    solver: Option<String>,
) -> taut::Result<()> {
    use taut::contact::Level;
    let request = app::ReplayRequest {
        max_iter: max_iter_arg(max_iter)?,
        solver: solver
            .as_deref()
            .map(app::words::complementarity_solver)
            .transpose()?,
        problem,
    };
    let r = app::replay(&request)?;
    let (gap, force) = match r.problem.level {
        Level::Acceleration => ("m/s²", "N"),
        Level::Position => ("m", "N"),
        Level::Velocity => ("m/s", "N (N·s for impulses)"),
    };
    println!(
        "{} contact problem, formulation {}",
        match r.problem.level {
            Level::Acceleration => "acceleration-level (t = 0)",
            Level::Position => "position-level",
            Level::Velocity => "velocity-level",
        },
        r.problem.contact.formulation.name()
    );
    println!("g_free = {:?} ({gap})", r.problem.g_free);
    println!("W      = {:?}", r.problem.w);
    let solved = r.answer?;
    println!("λ      = {:?} {force}", solved.out.lambda);
    println!("g      = {:?} ({gap}) after the solve", solved.out.gap);
    match solved.verdict? {
        Some(v) => println!("contact conditions hold to {v:.3e} (relative)"),
        None => println!("penalty law: the gap closes only to λ/κ, by design"),
    }
    Ok(())
}

/// Returns false when a run of the comparison stopped (tables are written
/// for the others).
fn cmd_compare(
    scene: PathBuf,
    formulations: &str,
    words: (Option<&str>, Option<&str>),
    (reference, reference_method, batch): (&str, Option<&str>, Option<String>),
    set: Vec<String>,
    out: Option<PathBuf>,
    (quiet, yes): (bool, bool),
) -> taut::Result<bool> {
    let batch = batch_arg(batch)?;
    let study = app::words::compare(
        formulations,
        words,
        (reference, reference_method),
        batch,
        yes,
    )?;
    let place = (scene.as_path(), set, out, "-compare");
    let (c, dir) = on_scene(place, study, quiet, app::compare)?;
    let files = "compare.csv, compare.json, compare.svg";
    print!(
        "{}",
        terminal::study("compare", &scene, &compare_table(&c), &dir, files)
    );
    Ok(c.failed.is_empty())
}
