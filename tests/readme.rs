//! The README's two set-up commands are the ones CI runs, and what they name exists.

const README: &str = include_str!("../README.md");
const CI: &str = include_str!("../.ci/run");

/// The set-up commands, as written in the README's first `sh` block.
const RUN_COMMAND: &str = "cargo run --release -- run scenes/reference.toml";
const TEST_COMMAND: &str = "cargo test --release";

#[test]
fn readme_shows_the_two_setup_commands_first() {
    let block_start = README.find("```sh\n").expect("an sh block") + 6;
    let block = &README[block_start..block_start + README[block_start..].find("```").unwrap()];
    let lines: Vec<&str> = block
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    assert_eq!(lines, [RUN_COMMAND, TEST_COMMAND]);
}

#[test]
fn ci_runs_the_readme_commands() {
    // CI adds --locked (and --quiet for the run) to the same commands
    assert!(CI.contains("cargo run --release --locked -- run scenes/reference.toml"));
    assert!(CI.contains("cargo test --release --locked"));
    assert!(CI.contains("cargo fmt --all -- --check"));
    assert!(CI.contains("-D warnings"));
    assert!(CI.contains("-- gate golden"), "CI runs the regression gate");
}

#[test]
fn the_python_install_command_is_the_one_ci_runs() {
    // README "From Python": one command installs the module; CI installs it
    // the same way (with the test extras) and runs its tests and example
    assert!(README.contains("pip install ./python"));
    // the install line brings the extras the README's example uses
    assert!(README.contains("pip install \"./python[all]\""));
    assert!(CI.contains("pip install --quiet --disable-pip-version-check \"./python[test]\""));
    assert!(CI.contains("pytest python/tests"));
    assert!(CI.contains("python/examples/speed_map.py --check"));
    let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    for f in [
        "python/pyproject.toml",
        "python/examples/speed_map.py",
        "docs/python.md",
    ] {
        assert!(root.join(f).is_file(), "{f}");
    }
}

#[test]
fn the_reference_scene_and_every_linked_doc_exist() {
    let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    assert!(root.join("scenes/reference.toml").is_file());
    // every `](docs/…)` link in the README points at a file
    let links: Vec<&str> = README
        .split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .filter(|target| target.starts_with("docs/"))
        .collect();
    for doc in [
        "docs/scene.md",
        "docs/output.md",
        "docs/numerics.md",
        "docs/methods.md",
        "docs/verification.md",
    ] {
        assert!(links.contains(&doc), "README links {doc}");
    }
    for target in links {
        // a link may point into a file (`docs/scene.md#output`)
        let file = target.split('#').next().unwrap_or(target);
        assert!(
            root.join(file).is_file(),
            "README links {target}, which does not exist"
        );
    }
}
