//! The front ends' tests in one binary: the CLI, bad and hostile
//! input, sweeps and their faults, the gate, studies driven from the
//! binary, and the README's commands. Each file below is a module, run with
//! its name as a filter, e.g. `cargo test --release --test front cli::`.
//! `no_alloc.rs` (a counting global allocator), `interrupt.rs` and
//! `folder_survival.rs` (the process-wide interrupt flag), `memory_peak.rs` (a child's peak memory
//! includes its parent's: the parent must stay small) and
//! `memory_budget.rs` (a counting allocator of the whole process's bytes)
//! stay binaries of their own: tests beside them would disturb them or be
//! disturbed.

/// Shared helpers (one copy for the whole binary).
mod common;

#[path = "bad_input.rs"]
mod bad_input;
#[path = "catenary_designed.rs"]
mod catenary_designed;
#[path = "cli.rs"]
mod cli;
#[path = "doc_files.rs"]
mod doc_files;
#[path = "gate.rs"]
mod gate;
#[path = "hostile_input.rs"]
mod hostile_input;
#[path = "layers.rs"]
mod layers;
#[path = "line.rs"]
mod line;
#[path = "line_scenes.rs"]
mod line_scenes;
#[path = "output_folders.rs"]
mod output_folders;
#[path = "precision.rs"]
mod precision;
#[path = "python_build.rs"]
mod python_build;
#[path = "readme.rs"]
mod readme;
#[path = "reliability.rs"]
mod reliability;
#[path = "reliability_three.rs"]
mod reliability_three;
#[path = "report_hostile.rs"]
mod report_hostile;
#[path = "report_sections.rs"]
mod report_sections;
#[path = "simulation.rs"]
mod simulation;
#[path = "sweep.rs"]
mod sweep;
#[path = "sweep_faults.rs"]
mod sweep_faults;
#[path = "sweep_lists.rs"]
mod sweep_lists;
#[path = "sweep_tolerance.rs"]
mod sweep_tolerance;
#[path = "tolerance.rs"]
mod tolerance;
#[path = "uncertainty_engine.rs"]
mod uncertainty_engine;

/// Every test file in tests/ is a group's root, a module of a group, or a
/// binary of its own: a file in no group would never run (`autotests =
/// false` in Cargo.toml).
#[test]
fn every_test_file_runs_in_some_binary() {
    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("tests");
    let roots = [
        "numerics.rs",
        "front.rs",
        "no_alloc.rs",
        "interrupt.rs",
        "folder_survival.rs",
        "memory_peak.rs",
        "memory_budget.rs",
        "quantity_registry.rs",
    ];
    let mut included = String::new();
    for r in &roots[..2] {
        included += &std::fs::read_to_string(dir.join(r)).expect("a group file reads");
    }
    let manifest =
        std::fs::read_to_string(dir.join("../cli/Cargo.toml")).expect("cli/Cargo.toml reads");
    for r in roots {
        assert!(
            manifest.contains(&format!("path = \"../tests/{r}\"")),
            "{r} is not a [[test]] target in cli/Cargo.toml"
        );
    }
    for entry in std::fs::read_dir(&dir).expect("tests/ lists") {
        let name = entry
            .expect("an entry")
            .file_name()
            .into_string()
            .expect("UTF-8");
        if !name.ends_with(".rs") || roots.contains(&name.as_str()) {
            continue;
        }
        assert!(
            included.contains(&format!("#[path = \"{name}\"]")),
            "tests/{name} is in no test binary: add it to tests/numerics.rs or tests/front.rs"
        );
    }
}
