//! The `taut` command line: a thin layer over the library's application
//! layer ([`taut::app`]). Each subcommand takes its command's options as
//! the library declares them (`taut::app::args`: the same struct Python's
//! keyword arguments fill), adds what only a command line has (the scene
//! file, `--set`/`--unset`, the output folder, `--quiet`), makes the typed
//! request, calls `taut::app::<command>` and prints the outcome
//! ([`terminal`]).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, CommandFactory, FromArgMatches, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

mod terminal;

use taut::app::args::CommandArgs;
use taut::app::{
    self, Frontend, GateArgs, ModesArgs, Note, ReplayArgs, RunArgs, SceneSource, StudyCommand,
    StudyVisitor, SweepArgs, VerifyArgs,
};
use taut::report::gate_table;

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
    let matches = with_studies(Cli::command()).get_matches();
    let mut dispatch = Dispatch {
        matches: &matches,
        result: None,
    };
    app::each_study(&mut dispatch);
    let result = match dispatch.result {
        Some(study) => study,
        None => command(Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())),
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

/// `taut`'s commands: those declared here, and the studies of one scene
/// of the library's list ([`app::each_study`]), each with the options of
/// [`OnScene`], its own and [`Quiet`].
fn with_studies(cli: clap::Command) -> clap::Command {
    struct Add(Option<clap::Command>);
    impl StudyVisitor for Add {
        fn visit<S: StudyCommand>(&mut self)
        where
            S::Outcome: Send,
        {
            let sub = clap::Command::new(<S::Args as CommandArgs>::COMMAND);
            let sub = Quiet::augment_args(S::Args::augment_args(OnScene::augment_args(sub)));
            // after the groups, whose own doc would be the command's help
            let sub = sub.about(S::ABOUT);
            self.0 = self.0.take().map(|c| c.subcommand(sub));
        }
    }
    let mut add = Add(Some(cli));
    app::each_study(&mut add);
    let cli = add.0.expect("kept");
    // `taut --help` lists `run`, then the studies of one scene, then the
    // other commands, each group in its order of declaration
    let studies: Vec<String> = {
        struct Names(Vec<String>);
        impl StudyVisitor for Names {
            fn visit<S: StudyCommand>(&mut self)
            where
                S::Outcome: Send,
            {
                self.0.push(<S::Args as CommandArgs>::COMMAND.to_string());
            }
        }
        let mut names = Names(Vec::new());
        app::each_study(&mut names);
        names.0
    };
    let mut order: Vec<String> = vec!["run".to_string()];
    order.extend(studies);
    for sub in cli.get_subcommands() {
        let name = sub.get_name().to_string();
        if !order.contains(&name) {
            order.push(name);
        }
    }
    order.iter().enumerate().fold(cli, |c, (k, name)| {
        c.mut_subcommand(name, |s| s.display_order(k))
    })
}

/// The study of [`app::each_study`] the command line names, run
/// ([`cmd_study`]); none when it names another command.
struct Dispatch<'a> {
    matches: &'a clap::ArgMatches,
    result: Option<taut::Result<bool>>,
}

impl StudyVisitor for Dispatch<'_> {
    fn visit<S: StudyCommand>(&mut self)
    where
        S::Outcome: Send,
    {
        if let Some((name, m)) = self.matches.subcommand()
            && name == <S::Args as CommandArgs>::COMMAND
        {
            self.result = Some(cmd_study::<S>(m));
        }
    }
}

/// A study of one scene: its outputs in `--out` (default: out/<scene
/// stem><suffix>), a progress bar of runs, its table printed; returns
/// whether the outcome is whole.
fn cmd_study<S: StudyCommand>(m: &clap::ArgMatches) -> taut::Result<bool>
where
    S::Outcome: Send,
{
    let parsed = |e: clap::Error| -> ! { e.exit() };
    let on = OnScene::from_arg_matches(m).unwrap_or_else(|e| parsed(e));
    let args = S::Args::from_arg_matches(m).unwrap_or_else(|e| parsed(e));
    let quiet = Quiet::from_arg_matches(m)
        .unwrap_or_else(|e| parsed(e))
        .quiet;
    let request = app::StudyRequest {
        scene: on.source(),
        set: on.overrides(),
        study: args.typed()?,
        out: Some(on.dir(S::SUFFIX)),
    };
    let outcome = Terminal::new(S::UNIT, quiet).run(|fe| S::command(&request, fe))?;
    let (kind, table) = request.study.terminal(&outcome);
    let dir = request.out.as_deref().expect("given");
    let files = S::OUTPUTS.files().join(", ");
    print!("{}", terminal::study(&kind, &on.scene, &table, dir, &files));
    Ok(S::whole(&outcome))
}

/// A command declared here, run.
fn command(cli: Cli) -> taut::Result<bool> {
    match cli.command {
        Command::Run { on, args, q } => cmd_run(&on, &args, q.quiet).map(|()| true),
        Command::Replay { args } => cmd_replay(&args).map(|()| true),
        Command::Sweep { on, args, q } => cmd_sweep(&on, &args, q.quiet),
        Command::Verify { args, out, q } => cmd_verify(&args, out, q.quiet),
        Command::Merge { shards, out } => cmd_merge(&shards, &out),
        Command::Report { dirs, out } => cmd_report(dirs, out).map(|()| true),
        Command::Modes { on, args } => cmd_modes(&on, &args).map(|()| true),
        Command::Gate { args, out, q } => cmd_gate(&args, out, q.quiet),
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

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    #[test]
    fn every_command_python_offers_is_a_subcommand_with_its_options() {
        // the library's one table of commands (`taut::app::args::schema`)
        // against the CLI's subcommands: each is one, taking each option
        let cli = super::with_studies(super::Cli::command());
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
