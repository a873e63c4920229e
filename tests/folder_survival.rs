//! A good run's folder survives every command that names it and stops,
//! byte for byte: a property over commands (run, compare, modes,
//! uncertainty) × the ways they stop (refused input, a run that diverges,
//! an output folder that cannot be written, a stop on request). Through the
//! library (`taut::app`), as the Python module calls it.
//!
//! A stop on request is process-wide ([`taut::interrupt`]), so this file is
//! its own test binary with a single test (cli/Cargo.toml).

use std::collections::BTreeMap;

mod common;
use std::path::{Path, PathBuf};

use proptest::prelude::*;
use taut::app::{self, SceneSource, Silent};
use taut::interrupt;

/// A small run of the reference scene: 20 elements, 0.02 s.
const SMALL: [&str; 2] = ["mesh.elements=20", "time.end=0.02"];

/// The bilateral α-level contact at 0.8 c: the run diverges within 0.1 s
/// (MODEL §5), at step 713.
const DIVERGES: [&str; 5] = [
    "contact.placement=alpha",
    "contact.kind=bilateral",
    "carrier.speed.cruise=120",
    "time.end=0.1",
    "mesh.elements=400",
];

#[derive(Debug, Clone, Copy)]
enum Command {
    Run,
    Compare,
    Modes,
    Uncertainty,
}

#[derive(Debug, Clone, Copy)]
enum Failure {
    /// A key that is not there (`mesh.elemnts`).
    Refused,
    /// A run that diverges (modes, which runs no steps: a bad value).
    Diverged,
    /// The staging folder cannot be made: a file holds its name.
    Unwritable,
    /// A stop requested before the work (`taut::interrupt`).
    Interrupted,
}

fn scene() -> SceneSource {
    SceneSource::File(
        Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scenes/reference.toml"
        ))
        .to_path_buf(),
    )
}

/// Every file of `dir` by name, with its bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    crate::common::folder_files(dir)
}

/// `command` on the reference scene with overrides `set`, writing `out`.
fn command(command: Command, set: &[&str], out: &Path) -> taut::Result<()> {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let out = Some(out.to_path_buf());
    let fe = &Silent;
    match command {
        Command::Run => app::run(
            &app::RunRequest {
                scene: scene(),
                set,
                out,
                tolerance: None,
            },
            fe,
        )
        .map(drop),
        Command::Compare => app::compare(
            &app::CompareRequest {
                scene: scene(),
                set,
                study: app::args::from_json::<app::CompareArgs>("{}")?.study()?,
                out,
            },
            fe,
        )
        .map(drop),
        Command::Modes => app::modes(
            &app::ModesRequest {
                scene: scene(),
                set,
                count: app::args::from_json::<app::ModesArgs>(r#"{"count": "3"}"#)?.count()?,
                out,
            },
            fe,
        )
        .map(drop),
        Command::Uncertainty => app::uncertainty(
            &app::UncertaintyRequest {
                scene: scene(),
                set,
                study: app::args::from_json::<app::UncertaintyArgs>(r#"{"levels": "3"}"#)?
                    .study()?,
                out,
            },
            fe,
        )
        .map(drop),
    }
}

/// The good run's folder, made once.
fn good_folder() -> &'static (PathBuf, BTreeMap<String, Vec<u8>>) {
    static GOOD: std::sync::OnceLock<(PathBuf, BTreeMap<String, Vec<u8>>)> =
        std::sync::OnceLock::new();
    GOOD.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("taut-folder-survival-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        command(Command::Run, &SMALL, &dir).expect("the good run");
        std::fs::write(dir.join("mine.txt"), "a user's file").unwrap();
        let before = files(&dir);
        (dir, before)
    })
}

/// Every command × every way it stops: 16 pairs, each checked (a sample
/// of them drawn at random left pairs unchecked from one run to the next).
#[test]
fn a_good_folder_survives_every_command_that_stops() {
    let commands = [
        Command::Run,
        Command::Compare,
        Command::Modes,
        Command::Uncertainty,
    ];
    let failures = [
        Failure::Refused,
        Failure::Diverged,
        Failure::Unwritable,
        Failure::Interrupted,
    ];
    for which in commands {
        for failure in failures {
            survives(which, failure).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}

/// The property for one command and one way to stop.
fn survives(which: Command, failure: Failure) -> Result<(), TestCaseError> {
    {
        let (dir, before) = good_folder();
        let mut set: Vec<&str> = SMALL.to_vec();
        // a file where the command's staging folder would go
        let blocker = dir.join(format!(".taut-staging-{}", std::process::id()));
        let mut held = None;
        match failure {
            Failure::Refused => set.push("mesh.elemnts=5"),
            Failure::Diverged if matches!(which, Command::Modes) => set.push("mesh.elements=-1"),
            Failure::Diverged => set.extend_from_slice(&DIVERGES),
            Failure::Unwritable => std::fs::write(&blocker, "not a folder").unwrap(),
            Failure::Interrupted => {
                let call = interrupt::Call::enter();
                interrupt::request();
                held = Some(call);
            }
        }
        let result = command(which, &set, dir);
        drop(held);
        let _ = std::fs::remove_file(&blocker);
        let Err(e) = result else {
            return Err(TestCaseError::fail(format!(
                "{which:?} with {failure:?} succeeded"
            )));
        };
        // stopped by the failure made, not by anything else
        let said = e.to_string();
        let why = match failure {
            Failure::Refused => "mesh.elemnts",
            Failure::Diverged if matches!(which, Command::Modes) => {
                "`mesh.elements`: invalid value: integer `-1`"
            }
            Failure::Diverged => "diverged",
            Failure::Unwritable => ".taut-staging-",
            Failure::Interrupted => "interrupted on request",
        };
        prop_assert!(
            said.contains(why),
            "{:?} with {:?}: {}",
            which,
            failure,
            said
        );
        let after = files(dir);
        let changed: Vec<&String> = after
            .keys()
            .chain(before.keys())
            .filter(|k| after.get(*k) != before.get(*k))
            .collect();
        prop_assert!(
            changed.is_empty(),
            "{which:?} with {failure:?} changed {changed:?}"
        );
        let left: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| n.starts_with('.') || n == "sweep.lock")
            .collect();
        prop_assert!(left.is_empty(), "{which:?} with {failure:?} left {left:?}");
    }
    Ok(())
}
