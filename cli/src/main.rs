//! The `taut` command line: a thin layer over the library's application
//! layer ([`taut::app`]). Each subcommand takes its command's options as
//! the library declares them (`taut::app::args`: the same struct Python's
//! keyword arguments fill), adds what only a command line has (the scene
//! file, `--set`/`--unset`, the output folder, `--quiet`), makes the typed
//! request, calls `taut::app::<command>` and prints the outcome
//! ([`terminal`]).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

mod terminal;

use taut::app::{
    self, CompareArgs, ConvergeArgs, Frontend, GateArgs, ModesArgs, Note, PrecisionArgs,
    ReplayArgs, RunArgs, SceneSource, SweepArgs, UncertaintyArgs, VerifyArgs,
};
use taut::report::{compare_table, converge_table, gate_table};
use taut::study::request::ConvergeOutcome;

/// taut: dynamic contact of a tensioned beam and a moving mass–spring.
#[derive(Parser)]
#[command(name = "taut", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// What every command on one scene takes besides its own options.
#[derive(Args)]
struct OnScene {
    /// Scene file (TOML).
    scene: PathBuf,
    /// Override a scene value: --set beam.tension=2.01e4 (repeatable).
    #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
    set: Vec<String>,
    /// Remove a scene key so that its default applies (repeatable; applied
    /// before the --set overrides): --unset integrator.rho_inf.
    #[arg(long = "unset", value_name = "KEY.PATH")]
    unset: Vec<String>,
    /// Output folder (default: out/<scene name>, with the command's suffix).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

impl OnScene {
    /// The override list of `--unset` and `--set`: the removals first (so
    /// that `--unset integrator --set integrator.method=newmark` replaces a
    /// table), then the values, each in its order.
    fn overrides(&self) -> Vec<String> {
        self.unset
            .iter()
            .map(|k| app::words::unset(k))
            .chain(self.set.iter().cloned())
            .collect()
    }

    /// The output folder: `--out`, or out/<scene stem><suffix>.
    fn dir(&self, suffix: &str) -> PathBuf {
        self.out.clone().unwrap_or_else(|| {
            let stem = self
                .scene
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned());
            PathBuf::from("out").join(format!("{}{suffix}", stem.unwrap_or_else(|| "run".into())))
        })
    }

    fn source(&self) -> SceneSource {
        SceneSource::File(self.scene.clone())
    }
}

/// No progress bar.
#[derive(Args)]
struct Quiet {
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scene and write history.csv, summary.json and force.svg.
    Run {
        #[command(flatten)]
        on: OnScene,
        #[command(flatten)]
        args: RunArgs,
        #[command(flatten)]
        q: Quiet,
    },
    /// Refine mesh, step or both and report errors, observed orders and GCI
    /// (converge.csv, converge.json, converge.svg).
    Converge {
        #[command(flatten)]
        on: OnScene,
        #[command(flatten)]
        args: ConvergeArgs,
        #[command(flatten)]
        q: Quiet,
    },
    /// Solution verification: run a small family of the scene refined in
    /// space and time, together and apart, and give every reported quantity
    /// its numerical uncertainty u_num (GCI, Eça–Hoekstra least squares),
    /// observed orders and the space/time split (uncertainty.csv,
    /// uncertainty.json, uncertainty.svg; docs/verification.md).
    Uncertainty {
        #[command(flatten)]
        on: OnScene,
        #[command(flatten)]
        args: UncertaintyArgs,
        #[command(flatten)]
        q: Quiet,
    },
    /// Re-run a golden suite and compare each quantity with its reference
    /// (gate.json, junit.xml); exit code 1 when any check fails.
    Gate {
        #[command(flatten)]
        args: GateArgs,
        /// Output folder for gate.json and junit.xml (default: out/gate).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        #[command(flatten)]
        q: Quiet,
    },
    /// Sweep scene values or the study's dimensionless axes (speed_ratio,
    /// tension_ratio, mass_ratio, stiffness_ratio) in parallel; resumable.
    Sweep {
        #[command(flatten)]
        on: OnScene,
        #[command(flatten)]
        args: SweepArgs,
        #[command(flatten)]
        q: Quiet,
    },
    /// Natural frequencies and mode shapes of the scene's beam, attachments
    /// included (modes.csv, mode_shapes.csv; docs/output.md#modes).
    Modes {
        #[command(flatten)]
        on: OnScene,
        #[command(flatten)]
        args: ModesArgs,
    },
    /// One self-contained report.html (plots as embedded images, inline
    /// CSS, no script, no network) from the outputs taut wrote into one or
    /// more folders: scenes, summaries, the standards' statistics, plots
    /// and study tables with their verdicts.
    Report {
        /// Output folders of taut run, compare, converge, precision, sweep,
        /// verify or gate.
        #[arg(required = true, value_name = "OUT_DIR")]
        dirs: Vec<PathBuf>,
        /// The page (default: OUT_DIR/report.html for one folder,
        /// out/report.html for several).
        #[arg(long, value_name = "FILE")]
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
        #[command(flatten)]
        on: OnScene,
        #[command(flatten)]
        args: PrecisionArgs,
        #[command(flatten)]
        q: Quiet,
    },
    /// Run the verification matrix: every method × discretization ×
    /// formulation × support pair on the declared cases (manufactured and
    /// exact), each observed order beside the expected one (verify.csv,
    /// verify.json); exit code 1 when any row fails.
    Verify {
        #[command(flatten)]
        args: VerifyArgs,
        /// Output folder (default: out/verify).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        #[command(flatten)]
        q: Quiet,
    },
    /// Solve a saved contact problem again (a `failed_contact_step_N.json`
    /// written by a failed run) and print the forces or the failure.
    Replay {
        #[command(flatten)]
        args: ReplayArgs,
    },
    /// Run one scene under several contact formulations and time integrators
    /// and compare them (compare.csv, compare.json, compare.svg).
    Compare {
        #[command(flatten)]
        on: OnScene,
        #[command(flatten)]
        args: CompareArgs,
        #[command(flatten)]
        q: Quiet,
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run { on, args, q } => cmd_run(&on, &args, q.quiet).map(|()| true),
        Command::Replay { args } => cmd_replay(&args).map(|()| true),
        Command::Sweep { on, args, q } => cmd_sweep(&on, &args, q.quiet),
        Command::Verify { args, out, q } => cmd_verify(&args, out, q.quiet),
        Command::Merge { shards, out } => cmd_merge(&shards, &out),
        Command::Report { dirs, out } => cmd_report(dirs, out).map(|()| true),
        Command::Modes { on, args } => cmd_modes(&on, &args).map(|()| true),
        Command::Precision { on, args, q } => cmd_precision(&on, &args, q.quiet).map(|()| true),
        Command::Gate { args, out, q } => cmd_gate(&args, out, q.quiet),
        Command::Converge { on, args, q } => cmd_converge(&on, &args, q.quiet).map(|()| true),
        Command::Uncertainty { on, args, q } => cmd_uncertainty(&on, &args, q.quiet).map(|()| true),
        Command::Compare { on, args, q } => cmd_compare(&on, &args, q.quiet),
        Command::Line {
            action: LineAction::Expand { scene, set, unset },
        } => {
            let on = OnScene {
                scene,
                set,
                unset,
                out: None,
            };
            app::line::expand(&on.source(), &on.overrides()).map(|text| {
                print!("{text}");
                true
            })
        }
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
            Note::Replaced(text) | Note::Kept(text) => eprintln!("{text}"),
            Note::AboveBound(e) => {
                eprintln!("note: {} (above the bound; --yes given)", e.describe())
            }
            Note::FailureSaved(path) => {
                eprintln!("saved the failing contact problem to {}", path.display())
            }
        });
    }
}

/// A study of one scene (`compare`, `converge`, `precision`), its outputs
/// in `--out` (default: out/<scene stem><suffix>), run by `command` with a
/// progress bar of runs; returns its outcome and output folder.
fn on_scene<S, R>(
    on: &OnScene,
    suffix: &str,
    study: S,
    quiet: bool,
    command: fn(&app::StudyRequest<S>, &dyn Frontend) -> taut::Result<R>,
) -> taut::Result<(R, PathBuf)> {
    let request = app::StudyRequest {
        scene: on.source(),
        set: on.overrides(),
        study,
        out: Some(on.dir(suffix)),
    };
    let outcome = Terminal::new("runs", quiet).run(|fe| command(&request, fe))?;
    Ok((outcome, request.out.expect("given")))
}

fn cmd_run(on: &OnScene, args: &RunArgs, quiet: bool) -> taut::Result<()> {
    let tolerance = args.tolerance()?;
    let unit = if tolerance.is_some() { "runs" } else { "steps" };
    let dir = on.dir("");
    let request = app::RunRequest {
        scene: on.source(),
        set: on.overrides(),
        out: Some(dir.clone()),
        tolerance,
    };
    let outcome = Terminal::new(unit, quiet).run(|fe| app::run(&request, fe))?;
    print!(
        "{}",
        terminal::summary(&on.scene, &dir, &outcome.summary, outcome.accuracy.as_ref())
    );
    Ok(())
}

fn cmd_modes(on: &OnScene, args: &ModesArgs) -> taut::Result<()> {
    let dir = on.dir("-modes");
    let request = app::ModesRequest {
        scene: on.source(),
        set: on.overrides(),
        count: args.count()?,
        out: Some(dir.clone()),
    };
    let m = Terminal::new("", true).run(|fe| app::modes(&request, fe))?;
    print!("{}", terminal::modes(&on.scene, &dir, &m));
    Ok(())
}

fn cmd_converge(on: &OnScene, args: &ConvergeArgs, quiet: bool) -> taut::Result<()> {
    let study = args.study()?;
    let kind = format!("converge ({:?}, r = {})", study.refine, study.ratio);
    let (outcome, dir) = on_scene(on, "-converge", study, quiet, app::converge)?;
    let table = match &outcome {
        ConvergeOutcome::One(c) => converge_table(c),
        ConvergeOutcome::Variants { studies, skipped } => {
            taut::report::converge_methods_table(studies, skipped)
        }
    };
    let files = "converge.csv, converge.json, converge.svg";
    print!("{}", terminal::study(&kind, &on.scene, &table, &dir, files));
    Ok(())
}

fn cmd_uncertainty(on: &OnScene, args: &UncertaintyArgs, quiet: bool) -> taut::Result<()> {
    let study = args.study()?;
    let (u, dir) = on_scene(on, "-uncertainty", study, quiet, app::uncertainty)?;
    let runs = u.family.len();
    let kind = format!(
        "uncertainty ({} levels{}, {runs} runs in {:.2} s wall)",
        u.levels,
        match u.levels_added {
            0 => String::new(),
            n => format!(" ({n} added: level 0 pre-asymptotic)"),
        },
        u.wall_seconds
    );
    let files = "uncertainty.csv, uncertainty.json, uncertainty.svg";
    print!(
        "{}",
        terminal::study(&kind, &on.scene, &terminal::family(&u), &dir, files)
    );
    Ok(())
}

/// Returns whether every row passed (or is known, cannot, reported).
fn cmd_verify(args: &VerifyArgs, out: Option<PathBuf>, quiet: bool) -> taut::Result<bool> {
    let request = args.request(out.unwrap_or_else(|| PathBuf::from("out").join("verify")))?;
    let v = Terminal::new("combinations", quiet).run(|fe| app::verify(&request, fe))?;
    println!(
        "taut {} — verify ({} rows, {:.1} s on {} threads)",
        taut::VERSION,
        v.rows.len(),
        v.wall_seconds,
        v.threads
    );
    print!("{}", taut::report::verify_table(&v.rows));
    let g = &v.golden;
    if g.failed > 0 {
        println!(
            "  golden   {} pass rows above their golden error ({}): their notes give each",
            g.failed,
            taut::study::verify::GOLDEN_FILE
        );
    }
    if g.missing > 0 {
        println!(
            "  golden   {} pass rows have no golden error in {} (not judged on one; --update-golden adds them)",
            g.missing,
            taut::study::verify::GOLDEN_FILE
        );
    }
    if g.updated.is_some() {
        for line in &g.diff {
            println!("  {line}");
        }
        println!(
            "  updated  {} ({} constants moved, added or removed)",
            taut::study::verify::GOLDEN_FILE,
            g.diff.len()
        );
    }
    println!(
        "  wrote    {}/{{verify.csv, verify.json, verify.md}}",
        request.out.display()
    );
    Ok(v.passed)
}

/// Returns whether the gate passed.
fn cmd_gate(args: &GateArgs, out: Option<PathBuf>, quiet: bool) -> taut::Result<bool> {
    let request = args.request(out.unwrap_or_else(|| PathBuf::from("out").join("gate")))?;
    let g = Terminal::new("cases", quiet).run(|fe| app::gate(&request, fe))?;
    println!("taut {} — gate {}", taut::VERSION, request.suite.display());
    print!("{}", gate_table(&g.report, request.update));
    println!(
        "  wrote    {}/{{gate.json, junit.xml}}",
        request.out.display()
    );
    Ok(g.passed)
}

/// Returns whether every point ran (the tables are written either way).
fn cmd_sweep(on: &OnScene, args: &SweepArgs, quiet: bool) -> taut::Result<bool> {
    let study = args.study()?;
    let shard = study.shard;
    let request = app::SweepRequest::new(on.source(), on.overrides(), study, on.dir("-sweep"));
    let s = Terminal::new("runs", quiet).run(|fe| app::sweep(&request, fe))?;
    println!("taut {} — sweep {}", taut::VERSION, on.scene.display());
    let ran = s.records.len() - s.resumed.min(s.records.len());
    // with --tolerance a record is a point of several runs
    let points: Vec<_> = s
        .records
        .iter()
        .filter_map(|r| r.accuracy.as_ref())
        .collect();
    let (what, rate) = if points.is_empty() {
        (
            "runs".to_string(),
            format!("{:.2} runs/s", ran as f64 / s.wall_seconds.max(1e-9)),
        )
    } else {
        let runs: usize = points.iter().map(|a| a.runs).sum();
        let met = points.iter().filter(|a| a.met).count();
        let rate = if s.resumed == 0 {
            format!("{:.2} runs/s", runs as f64 / s.wall_seconds.max(1e-9))
        } else {
            format!("{:.2} points/s", ran as f64 / s.wall_seconds.max(1e-9))
        };
        (
            format!("points ({runs} runs, {met} within the tolerance)"),
            rate,
        )
    };
    println!(
        "  {} {what}{}{} in {:.2} s wall ({rate}, {} threads); {} stopped with an error",
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
        s.threads,
        s.stopped()
    );
    println!("{}", terminal::work_line(&s.records));
    println!(
        "  wrote    {}/{{sweep.csv, sweep_force.csv, sweep_loss.csv, timing.csv, runs/}}",
        request.out.display()
    );
    print!("{}", terminal::maps(&s.maps, shard.is_some()));
    eprint!("{}", terminal::stopped(&s.records));
    Ok(s.stopped() == 0)
}

/// Returns whether every point of the merged sweep ran.
fn cmd_report(dirs: Vec<PathBuf>, out: Option<PathBuf>) -> taut::Result<()> {
    let r = app::report(&app::ReportRequest { dirs, out })?;
    println!(
        "taut {} — report of {} folder{}: {} plots, {} tables\n  wrote    {}",
        env!("CARGO_PKG_VERSION"),
        r.folders,
        if r.folders == 1 { "" } else { "s" },
        r.plots,
        r.tables,
        r.path.display()
    );
    for dir in &r.incomplete {
        eprintln!(
            "WARNING {} is marked INCOMPLETE: shown as partial, not as results",
            dir.display()
        );
    }
    for why in &r.left_out {
        eprintln!("WARNING left out of the report: {why}");
    }
    if !r.not_shown.is_empty() {
        println!(
            "  {} file{} not shown, named on the page with the reason",
            r.not_shown.len(),
            if r.not_shown.len() == 1 { "" } else { "s" }
        );
    }
    Ok(())
}

fn cmd_merge(shards: &[PathBuf], out: &Path) -> taut::Result<bool> {
    let m = app::merge(shards, out, &Terminal::new("", true))?;
    println!(
        "taut {} — merged {} shards: {} runs into {}",
        taut::VERSION,
        shards.len(),
        m.records.len(),
        out.display()
    );
    print!("{}", terminal::maps(&m.maps, false));
    eprint!("{}", terminal::stopped(&m.records));
    Ok(m.stopped() == 0)
}

fn cmd_precision(on: &OnScene, args: &PrecisionArgs, quiet: bool) -> taut::Result<()> {
    let (p, dir) = on_scene(on, "-precision", args.study()?, quiet, app::precision)?;
    let table = taut::report::precision_table(&p);
    let files = "precision.csv, precision.svg";
    print!(
        "{}",
        terminal::study("precision", &on.scene, &table, &dir, files)
    );
    Ok(())
}

fn cmd_replay(args: &ReplayArgs) -> taut::Result<()> {
    use taut::contact::Level;
    let r = app::replay(&args.request()?)?;
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
fn cmd_compare(on: &OnScene, args: &CompareArgs, quiet: bool) -> taut::Result<bool> {
    let (c, dir) = on_scene(on, "-compare", args.study()?, quiet, app::compare)?;
    let files = "compare.csv, compare.json, compare.svg";
    print!(
        "{}",
        terminal::study("compare", &on.scene, &compare_table(&c), &dir, files)
    );
    Ok(c.failed.is_empty())
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    #[test]
    fn every_command_python_offers_is_a_subcommand_with_its_options() {
        // the library's one table of commands (`taut::app::args::schema`)
        // against the CLI's subcommands: each is one, taking each option
        let cli = super::Cli::command();
        for (name, options) in taut::app::args::schema() {
            let sub = cli
                .find_subcommand(name)
                .unwrap_or_else(|| panic!("`{name}` is no subcommand of taut"));
            for o in options {
                assert!(
                    sub.get_arguments().any(|a| a.get_id() == o.name.as_str()),
                    "taut {name} has no --{}",
                    o.name
                );
            }
        }
    }
}
