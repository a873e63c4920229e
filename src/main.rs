//! The `taut` command line: a thin layer over the library.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use taut::report::{
    Summary, compare_table, converge_table, gate_table, write_compare, write_converge, write_gate,
    write_run, write_sweep,
};
use taut::study::converge::Refine;
use taut::{load_scene, run};

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
        /// An axis, key=start:stop:count (one or two).
        #[arg(long = "vary", value_name = "KEY=START:STOP:COUNT", required = true)]
        vary: Vec<String>,
        /// Logarithmic spacing on every axis.
        #[arg(long)]
        log: bool,
        /// Override a scene value (repeatable), as for `run`.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            scene,
            set,
            out,
            quiet,
            tolerance: Some(tol),
            quantity,
        } => cmd_run_tolerance(scene, set, out, quiet, &tol, quantity.as_deref()),
        Command::Run {
            scene,
            set,
            out,
            quiet,
            tolerance: None,
            ..
        } => cmd_run(scene, set, out, quiet),
        Command::Replay {
            problem,
            max_iter,
            solver,
        } => max_iter_arg(max_iter)
            .and_then(|max_iter| cmd_replay(&problem, max_iter, solver.as_deref())),
        Command::Sweep {
            scene,
            vary,
            log,
            set,
            out,
            shard,
            check_refinement,
            threads,
            batch,
            quiet,
            yes,
        } => match cmd_sweep(
            scene,
            (&vary, log, check_refinement),
            set,
            out,
            shard.as_deref(),
            (threads, batch),
            (quiet, yes),
        ) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
        Command::Verify {
            methods,
            discretizations,
            formulations,
            quick,
            threads,
            out,
            quiet,
        } => match threads_arg(threads).and_then(|threads| {
            cmd_verify(
                (
                    methods.as_deref(),
                    discretizations.as_deref(),
                    formulations.as_deref(),
                ),
                quick,
                threads,
                out,
                quiet,
            )
        }) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
        Command::Merge { shards, out } => match cmd_merge(&shards, &out) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
        Command::Precision {
            scene,
            formulations,
            methods,
            discretizations,
            levels,
            ratio,
            batch,
            set,
            out,
            quiet,
            yes,
        } => precision_levels_arg(levels, ratio).and_then(|(levels, ratio)| {
            cmd_precision(
                scene,
                (
                    &formulations,
                    methods.as_deref(),
                    discretizations.as_deref(),
                ),
                (levels, ratio, batch),
                set,
                out,
                (quiet, yes),
            )
        }),
        Command::Gate {
            suite,
            out,
            update,
            batch,
            quiet,
        } => match cmd_gate(&suite, out, (update, batch), quiet) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
        Command::Converge {
            scene,
            refine,
            levels,
            ratio,
            methods,
            discretizations,
            set,
            out,
            quiet,
            yes,
        } => converge_levels_arg(levels, ratio).and_then(|(levels, ratio)| {
            cmd_converge(
                scene,
                &refine,
                (levels, ratio),
                (methods.as_deref(), discretizations.as_deref()),
                set,
                out,
                (quiet, yes),
            )
        }),
        Command::Compare {
            scene,
            formulations,
            methods,
            discretizations,
            reference,
            reference_method,
            batch,
            set,
            out,
            quiet,
            yes,
        } => match cmd_compare(
            scene,
            &formulations,
            (methods.as_deref(), discretizations.as_deref()),
            (&reference, reference_method.as_deref(), batch),
            set,
            out,
            (quiet, yes),
        ) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
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

fn progress_bar(len: usize, unit: &str, quiet: bool) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::new(len as u64);
    let template = format!(
        "{{spinner}} [{{elapsed_precise}}] {{bar:40}} {{pos}}/{{len}} {unit} ({{eta}} left)"
    );
    b.set_style(ProgressStyle::with_template(&template).expect("valid template"));
    b
}

/// Remove the outputs an earlier command of this kind left in `dir`, saying
/// so on stderr: a folder holds one run's outputs (report::outputs).
fn fresh(dir: &Path, kind: taut::report::Outputs) -> taut::Result<()> {
    let removed = taut::report::clear_earlier(dir, kind)?;
    if let Some(note) = taut::report::cleared_note(dir, &removed) {
        eprintln!("{note}");
    }
    Ok(())
}

/// Refuse a study above the cost bound unless `yes` (study::cost); with
/// `yes`, say on stderr what is being started.
fn started(estimate: &taut::study::cost::Estimate, yes: bool) -> taut::Result<()> {
    estimate.check(yes)?;
    if estimate.over() {
        eprintln!(
            "note: {} (above the bound; --yes given)",
            estimate.describe()
        );
    }
    Ok(())
}

/// Save a failing contact problem next to the outputs so it can be replayed.
fn save_failure(dir: &Path, e: taut::Error) -> taut::Error {
    if let Some(path) = taut::report::save_failed_contact(dir, &e) {
        eprintln!("saved the failing contact problem to {}", path.display());
    }
    e
}

fn cmd_run(
    scene: PathBuf,
    set: Vec<String>,
    out: Option<PathBuf>,
    quiet: bool,
) -> taut::Result<()> {
    let dir = out.unwrap_or_else(|| default_dir(&scene, ""));
    fresh(&dir, taut::report::Outputs::Run)?;
    let sc = load_scene(&scene, &set)?;
    let bar = progress_bar(sc.steps, "steps", quiet);
    let output = run(&sc, &mut |done, _| bar.set_position(done as u64));
    bar.finish_and_clear();
    let output = output.map_err(|e| save_failure(&dir, e))?;
    let summary = write_run(&dir, &sc, &output)?;
    print_summary(&scene, &dir, &summary, None);
    Ok(())
}

/// `taut run --tolerance`: pilots, model, the chosen run, estimates.
fn cmd_run_tolerance(
    scene: PathBuf,
    set: Vec<String>,
    out: Option<PathBuf>,
    quiet: bool,
    tolerance: &str,
    quantity: Option<&str>,
) -> taut::Result<()> {
    use taut::study::tolerance::{Quantity, parse_tolerance, tolerance_run};
    let quantity: Quantity = quantity.unwrap_or("force").parse()?;
    let tol = parse_tolerance(tolerance)?;
    let dir = out.unwrap_or_else(|| default_dir(&scene, ""));
    fresh(&dir, taut::report::Outputs::Run)?;
    let text = taut::scene::read_scene(&scene)?;
    let bar = progress_bar(6, "runs", quiet);
    let result = tolerance_run(&text, &set, quantity, tol, &mut |done, _| {
        bar.set_position(done as u64)
    });
    bar.finish_and_clear();
    let r = result
        .map_err(|e| taut::scene::in_file(e, &scene))
        .map_err(|e| save_failure(&dir, e))?;
    let summary = taut::report::write_tolerant_run(&dir, &r)?;
    print_summary(&scene, &dir, &summary, Some(&r.accuracy));
    Ok(())
}

fn cmd_converge(
    scene: PathBuf,
    refine: &str,
    (levels, ratio): (usize, f64),
    (methods, discretizations): (Option<&str>, Option<&str>),
    set: Vec<String>,
    out: Option<PathBuf>,
    (quiet, yes): (bool, bool),
) -> taut::Result<()> {
    use taut::study::request::{ConvergeOutcome, ConvergeRequest};
    let request = ConvergeRequest {
        refine: refine.to_string(),
        levels,
        ratio,
        methods: methods.map(str::to_string),
        discretizations: discretizations.map(str::to_string),
        yes,
    };
    let refine: Refine = refine.parse()?;
    let dir = out.unwrap_or_else(|| default_dir(&scene, "-converge"));
    fresh(&dir, taut::report::Outputs::Converge)?;
    let text = taut::scene::read_scene(&scene)?;
    started(
        &request
            .estimate(&text, &set)
            .map_err(|e| taut::scene::in_file(e, &scene))?,
        yes,
    )?;
    let bar = progress_bar(request.runs()?, "runs", quiet);
    let result = request.run(&text, &set, &mut |done, _| bar.set_position(done as u64));
    bar.finish_and_clear();
    let kind = format!("converge ({refine:?}, r = {ratio})");
    let outcome = result
        .map_err(|e| taut::scene::in_file(e, &scene))
        .map_err(|e| save_failure(&dir, e))?;
    let table = match outcome {
        ConvergeOutcome::One(c) => {
            write_converge(&dir, &c)?;
            converge_table(&c)
        }
        ConvergeOutcome::Variants { studies, skipped } => {
            taut::report::write_converge_methods(&dir, &studies, &skipped)?;
            taut::report::converge_methods_table(&studies, &skipped)
        }
    };
    print_study(
        &kind,
        &scene,
        &table,
        &dir,
        "converge.csv, converge.json, converge.svg",
    );
    Ok(())
}

/// Returns whether every row passed (or is known, cannot, reported).
fn cmd_verify(
    (methods, spaces, formulations): (Option<&str>, Option<&str>, Option<&str>),
    quick: bool,
    threads: Option<usize>,
    out: Option<PathBuf>,
    quiet: bool,
) -> taut::Result<bool> {
    use taut::study::verify::{any_failed, cases::CASES, selection, verify};
    let sel = selection(methods, spaces, formulations, quick)?;
    taut::study::threads::start_pool(threads)?;
    let bar = progress_bar(0, "combinations", quiet);
    let start = std::time::Instant::now();
    let rows = verify(&CASES, &sel, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64)
    });
    bar.finish_and_clear();
    let rows = rows?;
    let wall = start.elapsed().as_secs_f64();
    let dir = out.unwrap_or_else(|| PathBuf::from("out").join("verify"));
    taut::report::write_verify(&dir, &rows, wall)?;
    println!(
        "taut {} — verify ({} rows, {wall:.1} s on {} threads)",
        env!("CARGO_PKG_VERSION"),
        rows.len(),
        rayon::current_num_threads()
    );
    print!("{}", taut::report::verify_table(&rows));
    println!(
        "  wrote    {}/{{verify.csv, verify.json, verify.md}}",
        dir.display()
    );
    Ok(!any_failed(&rows))
}

/// Returns whether the gate passed.
fn cmd_gate(
    suite: &Path,
    out: Option<PathBuf>,
    (update, batch): (bool, Option<String>),
    quiet: bool,
) -> taut::Result<bool> {
    let batch = taut::study::request::batch_lanes(batch_arg(batch)?)?;
    let dir = out.unwrap_or_else(|| PathBuf::from("out").join("gate"));
    fresh(&dir, taut::report::Outputs::Gate)?;
    let n = taut::study::gate::case_files(suite)?.len();
    let bar = progress_bar(n, "cases", quiet);
    let report = taut::study::gate::gate_batched(suite, update, batch, &mut |done, _, _| {
        bar.set_position(done as u64)
    });
    bar.finish_and_clear();
    let report = report?;
    write_gate(&dir, &report)?;
    println!(
        "taut {} — gate {}",
        env!("CARGO_PKG_VERSION"),
        suite.display()
    );
    print!("{}", gate_table(&report, update));
    println!("  wrote    {}/{{gate.json, junit.xml}}", dir.display());
    // an update accepts the new values: it passes unless a case could not run
    Ok(if update {
        report.errors.is_empty() && !report.checks.is_empty()
    } else {
        report.passed()
    })
}

#[allow(clippy::too_many_arguments)]
fn cmd_sweep(
    scene: PathBuf,
    (vary, log, check_refinement): (&[String], bool, bool),
    set: Vec<String>,
    out: Option<PathBuf>,
    shard: Option<&str>,
    (threads, batch): (Option<String>, Option<String>),
    (quiet, yes): (bool, bool),
) -> taut::Result<bool> {
    use taut::study::sweep::{Axis, Shard, SweepSpec, claim, sweep_batched};
    let threads = threads_arg(threads)?;
    let batch = taut::study::request::batch_width(batch_arg(batch)?)?;
    let axes = vary
        .iter()
        .map(|v| Axis::parse(v, log))
        .collect::<taut::Result<Vec<_>>>()?;
    let shard = shard.map(Shard::parse).transpose()?;
    let scene_text = taut::scene::read_scene(&scene)?;
    let spec = SweepSpec {
        scene_text,
        set,
        axes,
        check_refinement,
    };
    let dir = out.unwrap_or_else(|| default_dir(&scene, "-sweep"));
    // bounded, and a pool that cannot start is an error, not a panic
    taut::study::threads::start_pool(threads)?;
    let bar = progress_bar(spec.len(), "runs", quiet);
    let start = std::time::Instant::now();
    spec.validate()
        .map_err(|e| taut::scene::in_file(e, &scene))?;
    started(&spec.estimate(shard)?, yes)?;
    let claimed = claim(&dir)?;
    // tables and maps of this sweep only: a folder holding another sweep is
    // refused (by check_spec) with its tables left as they are
    taut::study::sweep::folder::check_spec(&dir, &spec)?;
    fresh(&dir, taut::report::Outputs::Sweep)?;
    // the first report says how many points an earlier start had finished
    let resumed = std::sync::OnceLock::new();
    let records = sweep_batched(&claimed, &spec, shard, batch, &|done, total| {
        resumed.get_or_init(|| done);
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    let records = records?;
    write_sweep(&dir, &spec, &records)?;
    let maps = taut::report::write_sweep_maps(&dir, &spec, &records)?;
    let wall = start.elapsed().as_secs_f64();
    let failed = stopped_points(&records);
    println!(
        "taut {} — sweep {}",
        env!("CARGO_PKG_VERSION"),
        scene.display()
    );
    let resumed = resumed.get().copied().unwrap_or(0);
    let ran = records.len() - resumed.min(records.len());
    println!(
        "  {} runs{}{} in {wall:.2} s wall ({:.2} runs/s, {} threads); {failed} stopped with an error",
        records.len(),
        shard.map_or(String::new(), |s| format!(
            " (shard {}/{})",
            s.index, s.count
        )),
        if resumed > 0 {
            format!(" ({ran} run now, {resumed} kept from an earlier start)")
        } else {
            String::new()
        },
        ran as f64 / wall.max(1e-9),
        rayon::current_num_threads()
    );
    println!(
        "  wrote    {}/{{sweep.csv, sweep_force.csv, sweep_loss.csv, timing.csv, runs/}}",
        dir.display()
    );
    print_maps(&maps, shard.is_some());
    report_stopped(&records);
    Ok(failed == 0)
}

/// Number of sweep points whose run stopped with an error.
fn stopped_points(records: &[taut::study::sweep::SweepRecord]) -> usize {
    records.iter().filter(|r| r.error.is_some()).count()
}

/// Most stopped points a sweep names on the terminal (all are in sweep.csv).
const STOPPED_SHOWN: usize = 5;

/// Name the points of a sweep whose run stopped, on stderr: the tables and
/// maps are written, and the exit status (1) says some points failed.
fn report_stopped(records: &[taut::study::sweep::SweepRecord]) {
    let stopped: Vec<_> = records.iter().filter(|r| r.error.is_some()).collect();
    if stopped.is_empty() {
        return;
    }
    eprintln!(
        "{} of {} points stopped with an error; their rows in sweep.csv carry it (column \
         `error`), the maps show them grey, and a resumed sweep keeps them:",
        stopped.len(),
        records.len()
    );
    for r in stopped.iter().take(STOPPED_SHOWN) {
        eprintln!(
            "  point {} {:?}: {}",
            r.index,
            r.values,
            r.error.as_deref().unwrap_or_default()
        );
    }
    if stopped.len() > STOPPED_SHOWN {
        eprintln!("  … and {} more", stopped.len() - STOPPED_SHOWN);
    }
}

/// Name the maps a sweep or merge drew (a shard draws none: merge does).
fn print_maps(maps: &[PathBuf], shard: bool) {
    if let Some((first, rest)) = maps.split_first() {
        let names: Vec<String> = rest
            .iter()
            .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .collect();
        if names.is_empty() {
            println!("  map      {}", first.display());
        } else {
            println!("  maps     {}, {}", first.display(), names.join(", "));
        }
    } else if shard {
        println!("  maps     none for a shard: `taut merge` draws them for the whole grid");
    }
}

fn cmd_merge(shards: &[PathBuf], out: &Path) -> taut::Result<bool> {
    let claimed = taut::study::sweep::claim(out)?;
    // clear the tables only of a folder that holds this sweep (or none):
    // merge_into refuses any other, which then keeps its tables
    if let Some(first) = shards.first()
        && let Ok(spec) = taut::study::sweep::read_spec(first)
        && taut::study::sweep::folder::check_spec(out, &spec).is_ok()
    {
        fresh(out, taut::report::Outputs::Sweep)?;
    }
    let (spec, records) = taut::study::sweep::merge_into(&claimed, shards)?;
    write_sweep(out, &spec, &records)?;
    let maps = taut::report::write_sweep_maps(out, &spec, &records)?;
    println!(
        "taut {} — merged {} shards: {} runs into {}",
        env!("CARGO_PKG_VERSION"),
        shards.len(),
        records.len(),
        out.display()
    );
    print_maps(&maps, false);
    report_stopped(&records);
    Ok(stopped_points(&records) == 0)
}

fn cmd_precision(
    scene: PathBuf,
    (formulations, methods, discretizations): (&str, Option<&str>, Option<&str>),
    (levels, ratio, batch): (usize, usize, Option<String>),
    set: Vec<String>,
    out: Option<PathBuf>,
    (quiet, yes): (bool, bool),
) -> taut::Result<()> {
    let request = taut::study::request::PrecisionRequest {
        formulations: formulations.to_string(),
        methods: methods.map(str::to_string),
        discretizations: discretizations.map(str::to_string),
        levels,
        ratio,
        batch: batch_arg(batch)?,
        yes,
    };
    let dir = out.unwrap_or_else(|| default_dir(&scene, "-precision"));
    fresh(&dir, taut::report::Outputs::Precision)?;
    let text = taut::scene::read_scene(&scene)?;
    started(
        &request
            .estimate(&text, &set)
            .map_err(|e| taut::scene::in_file(e, &scene))?,
        yes,
    )?;
    let bar = progress_bar(request.runs()?, "runs", quiet);
    let result = request.run(&text, &set, &mut |d, _| bar.set_position(d as u64));
    bar.finish_and_clear();
    let p = result
        .map_err(|e| taut::scene::in_file(e, &scene))
        .map_err(|e| save_failure(&dir, e))?;
    taut::report::write_precision(&dir, &p)?;
    print_study(
        "precision",
        &scene,
        &taut::report::precision_table(&p),
        &dir,
        "precision.csv, precision.svg",
    );
    Ok(())
}

fn cmd_replay(path: &Path, max_iter: Option<u32>, solver: Option<&str>) -> taut::Result<()> {
    use taut::contact::{Level, SIGNORINI_TOLERANCE, replay};
    let text = taut::input::read_text(
        path,
        "a saved contact problem",
        taut::input::MAX_REPLAY_BYTES,
    )?;
    taut::json_keys::reject_duplicate_keys(&text, path)?;
    let mut problem: taut::contact::ContactProblem = serde_json::from_str(&text)
        .map_err(|e| taut::Error::parse(format!("{}: {e}", path.display())))?;
    if let Some(n) = max_iter {
        problem.contact.complementarity.max_iter = n;
    }
    if let Some(name) = solver {
        use taut::scene::ComplementaritySolver;
        problem.contact.complementarity.solver = match name {
            "direct" => ComplementaritySolver::Direct,
            "clarabel" => ComplementaritySolver::Clarabel,
            other => {
                return Err(taut::Error::invalid(
                    "--solver",
                    other,
                    "must be `direct` or `clarabel`",
                ));
            }
        };
    }
    taut::contact::validate(&problem)?;
    let (gap, force) = match problem.level {
        Level::Acceleration => ("m/s²", "N"),
        Level::Position => ("m", "N"),
        Level::Velocity => ("m/s", "N (N·s for impulses)"),
    };
    println!(
        "{} contact problem, formulation {}",
        match problem.level {
            Level::Acceleration => "acceleration-level (t = 0)",
            Level::Position => "position-level",
            Level::Velocity => "velocity-level",
        },
        problem.contact.formulation.name()
    );
    println!("g_free = {:?} ({gap})", problem.g_free);
    println!("W      = {:?}", problem.w);
    let out = replay(&problem).map_err(|f| taut::Error::Replay {
        path: path.to_path_buf(),
        reason: f.to_string(),
    })?;
    println!("λ      = {:?} {force}", out.lambda);
    println!("g      = {:?} ({gap}) after the solve", out.gap);
    match out.violation {
        Some(v) if v > SIGNORINI_TOLERANCE => Err(taut::Error::Replay {
            path: path.to_path_buf(),
            reason: format!(
                "the answer violates the contact conditions by {v:.3e} (relative; at most {SIGNORINI_TOLERANCE:e} is a solution)"
            ),
        }),
        Some(v) => {
            println!("contact conditions hold to {v:.3e} (relative)");
            Ok(())
        }
        None => {
            println!("penalty law: the gap closes only to λ/κ, by design");
            Ok(())
        }
    }
}

/// Returns false when a run of the comparison stopped (tables are written
/// for the others).
fn cmd_compare(
    scene: PathBuf,
    formulations: &str,
    (methods, discretizations): (Option<&str>, Option<&str>),
    (reference, reference_method, batch): (&str, Option<&str>, Option<String>),
    set: Vec<String>,
    out: Option<PathBuf>,
    (quiet, yes): (bool, bool),
) -> taut::Result<bool> {
    let request = taut::study::request::CompareRequest {
        formulations: formulations.to_string(),
        methods: methods.map(str::to_string),
        discretizations: discretizations.map(str::to_string),
        reference: reference.to_string(),
        reference_method: reference_method.map(str::to_string),
        batch: batch_arg(batch)?,
        yes,
    };
    let dir = out.unwrap_or_else(|| default_dir(&scene, "-compare"));
    fresh(&dir, taut::report::Outputs::Compare)?;
    let text = taut::scene::read_scene(&scene)?;
    started(
        &request
            .estimate(&text, &set)
            .map_err(|e| taut::scene::in_file(e, &scene))?,
        yes,
    )?;
    let bar = progress_bar(request.runs()?, "runs", quiet);
    let result = request.run(&text, &set, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64)
    });
    bar.finish_and_clear();
    let c = result
        .map_err(|e| taut::scene::in_file(e, &scene))
        .map_err(|e| save_failure(&dir, e))?;
    write_compare(&dir, &c)?;
    print_study(
        "compare",
        &scene,
        &compare_table(&c),
        &dir,
        "compare.csv, compare.json, compare.svg",
    );
    Ok(c.failed.is_empty())
}

/// Header, table and written files of a study command.
fn print_study(kind: &str, scene: &Path, table: &str, dir: &Path, files: &str) {
    println!(
        "taut {} — {kind} {}",
        env!("CARGO_PKG_VERSION"),
        scene.display()
    );
    print!("{table}");
    println!("  wrote    {}/{{{files}}}", dir.display());
}

/// The run's one-screen summary; with `accuracy` (a `--tolerance` run) the
/// choice of resolution first and an estimated error beside every result.
/// The terminal's contact-loss lines of one carrier: P_l split into the
/// in-span part (the number to quote) and the support part, the first loss
/// flagged when the run does not resolve it, the re-contacts.
fn contact_loss_lines(c: &taut::record::ContactStats) -> String {
    use taut::record::LossClass;
    let mut s = format!(
        "             contact loss P_l = {:.4} = {:.4} in span + {:.4} at supports (zone {:.2} m); {} intervals, {} switches\n",
        c.loss_fraction,
        c.loss_fraction_span,
        c.loss_fraction_support,
        c.support_zone,
        c.loss_interval_count,
        c.contact_switches
    );
    if let Some(x) = c.first_loss_position {
        let note = match c.loss_interval_class.first() {
            Some(LossClass::Unresolved) => " (unresolved: see WARNING)",
            Some(LossClass::Support) => " (in a support zone)",
            _ => "",
        };
        s.push_str(&format!("             first loss at x/L = {x:.4}{note}\n"));
    }
    if c.recontact_count > 0 {
        let peak = c.recontacts.iter().map(|r| r.peak).fold(0.0, f64::max);
        let impulse = c.recontacts.iter().map(|r| r.impulse).fold(0.0, f64::max);
        s.push_str(&format!(
            "             {} re-contacts: peak λ up to {peak:.1} N (grows as Δt falls), impulse up to {impulse:.4} N·s\n",
            c.recontact_count
        ));
    }
    s
}

fn print_summary(
    scene: &std::path::Path,
    dir: &std::path::Path,
    s: &Summary,
    accuracy: Option<&taut::study::tolerance::Accuracy>,
) {
    let d = &s.derived;
    println!("taut {} — {}", s.taut_version, scene.display());
    if let Some(a) = accuracy {
        print!("{}", taut::report::accuracy_header(a));
    }
    println!(
        "  beam     L = {} m, ρA = {:.4} kg/m, EI = {:.4e} N·m², T = {:.4e} N, c = {:.2} m/s",
        s.scene.beam.length,
        d.mass_per_length,
        d.bending_stiffness,
        s.scene.beam.tension,
        d.wave_speed
    );
    let ratio = d
        .speed_ratio
        .map_or_else(|| "n/a".to_string(), |r| format!("{r:.4}"));
    println!(
        "  mesh     {}, {} dofs; Δt = {} s, {} steps to t = {:.4} s; V0/c = {ratio}",
        taut::report::mesh_label(s),
        d.dofs,
        d.dt,
        d.steps,
        d.end_time
    );
    for (i, c) in s.carriers.iter().enumerate() {
        if let Some(a) = accuracy {
            println!("  carrier {i} (± estimated error at this N and Δt):");
            print!("{}", taut::report::result_lines(a, i));
            continue;
        }
        let f = &c.force;
        println!(
            "  carrier {i}: force mean {:.4} N, std {:.4} N, min {:.4} N, max {:.4} N",
            f.mean, f.std, f.min, f.max
        );
        print!("{}", contact_loss_lines(c));
    }
    for w in &s.warnings {
        println!("  WARNING  {w}");
    }
    let rate = d.dofs as f64 * d.steps as f64 / s.wall_seconds.max(1e-12);
    println!(
        "  time     {:.3} s wall ({rate:.3e} dof-steps/s)",
        s.wall_seconds
    );
    if accuracy.is_some() {
        println!(
            "  wrote    {}/{{history.csv, summary.json, force.svg, accuracy.csv}}",
            dir.display()
        );
    } else {
        println!(
            "  wrote    {}/{{history.csv, summary.json, force.svg}}",
            dir.display()
        );
    }
}
