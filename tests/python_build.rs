//! The Python module's build reuses the CLI's: `pip install ./python` after
//! the README's `cargo run --release` must find every crate the two share
//! already built. Cargo picks a crate's features from the packages a build
//! selects, so a shared crate that pyo3 gives one more feature (syn's
//! `extra-traits`, once_cell's `default`) would be built again, and with it
//! everything above it: serde_derive, faer, the taut library. cli/Cargo.toml
//! turns those features on; this test holds the two sets equal.

use std::collections::BTreeMap;
use std::process::Command;

/// `cargo tree` of the packages given, as package → the feature sets it is
/// built with (a crate built for the host and for the target appears twice).
fn features(packages: &[&str]) -> BTreeMap<String, Vec<String>> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(&root)
        .args(["tree", "--locked", "--offline", "-e", "normal,build"])
        .args(["-f", "{p}|{f}", "--prefix", "none"]);
    for p in packages {
        cmd.args(["-p", p]);
    }
    let out = cmd.output().expect("cargo tree runs");
    assert!(
        out.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut map: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let line = line.trim_end_matches(" (*)");
        let Some((package, feats)) = line.split_once('|') else {
            continue;
        };
        // a workspace member is named with its path; the path is the same in both
        let package = package.trim().to_string();
        let sets = map.entry(package).or_default();
        let feats = feats.trim().to_string();
        if !sets.contains(&feats) {
            sets.push(feats);
        }
    }
    for sets in map.values_mut() {
        sets.sort();
    }
    map
}

#[test]
fn the_python_build_shares_every_crate_with_the_cli_build() {
    let cli = features(&["taut", "taut-cli"]);
    let python = features(&["taut-python"]);
    let differing: Vec<String> = python
        .iter()
        .filter_map(|(package, sets)| {
            let theirs = cli.get(package)?;
            (theirs != sets).then(|| format!("{package}: CLI {theirs:?}, Python {sets:?}"))
        })
        .collect();
    assert!(
        differing.is_empty(),
        "crates the Python module's build would build again after `cargo run --release` \
         (give the CLI the same features in cli/Cargo.toml):\n{}",
        differing.join("\n")
    );
    // the check is not empty: the two builds share the library and its tree
    assert!(python.keys().any(|p| p.starts_with("taut v")));
    assert!(python.keys().any(|p| p.starts_with("faer v")));
}
