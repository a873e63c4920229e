//! Every file a doc or a doc comment names is in the repository (issue 39):
//! the docs used to point ~100 times to a physics contract and a targets
//! page users never see. A name like `docs/lines.md`, `src/run.rs`,
//! `scenes/reference.toml` or `speed_map.py` in a Markdown page, a Rust
//! doc comment (`//!`, `///`) or the Python package must be a file here:
//! a path, from the repository's root or from the page's folder, or, for a
//! bare name, a file of that name anywhere in the repository.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// The extensions of the files a doc can point a reader to (outputs such
/// as `history.csv` or `force.svg` are made by runs, not kept here).
const SOURCE_EXTENSIONS: [&str; 7] = [".md", ".rs", ".py", ".pyi", ".toml", ".sh", ".sbatch"];

/// Names a doc uses for a file that is not ours to keep: a file of the
/// reader's own, an output taut writes (`taut verify`'s `verify.md`), a
/// source file of a dependency (clarabel's, in the complementarity
/// solver's notes).
const NOT_OURS: [&str; 10] = [
    "SCENE.toml",
    "my_scene.toml",
    "scene.toml",
    "case.toml",
    "FILE.toml",
    "tmp/two.toml",
    "verify.md",
    "solver/core/solver.rs",
    "solver/implementations/default/data_updating.rs",
    "timers/timers.rs",
];

/// The folder runs and the `cargo xtask` reports write into: a name under
/// it (`out/verify/verify.md`, `out/xtask/stability.md`) is a command's
/// output, made when the command runs, not a file the repository keeps.
const OUTPUTS: &str = "out/";

/// Folders that hold no source or docs of the repository.
const SKIP_DIRS: [&str; 5] = ["target", ".git", "out", "node_modules", "__pycache__"];

fn root() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).to_path_buf()
}

/// Every file under `dir`, relative to the root.
fn walk(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        let name = e.file_name().to_string_lossy().to_string();
        if p.is_dir() {
            if !SKIP_DIRS.contains(&name.as_str()) && !name.starts_with(".venv") {
                walk(root, &p, out);
            }
        } else if let Ok(rel) = p.strip_prefix(root) {
            out.push(rel.to_path_buf());
        }
    }
}

/// The file-like words of `text`: runs of path characters ending in one of
/// [`SOURCE_EXTENSIONS`], not part of a URL.
fn file_words(text: &str) -> Vec<String> {
    let is_path = |c: char| c.is_ascii_alphanumeric() || "_./-".contains(c);
    let mut words = Vec::new();
    for raw in text.split(|c: char| !is_path(c)) {
        let w = raw.trim_start_matches(['.', '/']).trim_end_matches('.');
        let w = w.trim_start_matches('-');
        if w.is_empty() || !SOURCE_EXTENSIONS.iter().any(|e| w.ends_with(e)) {
            continue;
        }
        // the extension alone (".md files") or a word before it is no name
        let stem = &w[..w.rfind('.').unwrap_or(0)];
        if stem.is_empty() || stem.ends_with('/') {
            continue;
        }
        words.push(w.to_string());
    }
    // URLs: drop words that follow "://" in the text
    words.retain(|w| !text.contains(&format!("://{w}")) && !text.contains(&format!(".com/{w}")));
    words
}

/// What a reader sees of a file: a Markdown page whole, a Rust file's doc
/// comments, a Python file whole (docstrings and comments).
fn doc_text(path: &Path, text: &str) -> String {
    match path.extension().and_then(|e| e.to_str()) {
        Some("rs") => text
            .lines()
            .map(str::trim_start)
            .filter(|l| l.starts_with("//!") || l.starts_with("///"))
            .collect::<Vec<_>>()
            .join("\n"),
        _ => text.to_string(),
    }
}

#[test]
fn every_file_a_doc_names_is_in_the_repository() {
    let root = root();
    let mut files = Vec::new();
    walk(&root, &root, &mut files);
    let paths: HashSet<String> = files
        .iter()
        .map(|p| p.to_string_lossy().replace('\\', "/"))
        .collect();
    let names: HashSet<String> = files
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().to_string()))
        .collect();
    let docs: Vec<&PathBuf> = files
        .iter()
        .filter(|p| {
            let s = p.to_string_lossy();
            (s.ends_with(".md") && !s.starts_with("golden/"))
                || (s.ends_with(".rs") && !s.starts_with("tests/"))
                || (s.starts_with("python/taut/") && (s.ends_with(".py") || s.ends_with(".pyi")))
        })
        .collect();
    assert!(docs.len() > 100, "found the docs ({} files)", docs.len());
    let mut missing = Vec::new();
    for doc in docs {
        let text = std::fs::read_to_string(root.join(doc)).unwrap_or_default();
        let folder = doc.parent().unwrap_or(Path::new(""));
        for w in file_words(&doc_text(doc, &text)) {
            if NOT_OURS.contains(&w.as_str()) || w.starts_with(OUTPUTS) {
                continue;
            }
            let found = if w.contains('/') {
                let here = folder.join(&w);
                let here = here.to_string_lossy().replace('\\', "/");
                paths.contains(&w)
                    || paths.contains(&format!(".{w}"))
                    || paths.contains(&here)
                    || root.join(folder).join(&w).exists()
                    || paths.iter().any(|p| p.ends_with(&format!("/{w}")))
            } else {
                names.contains(&w)
            };
            if !found {
                missing.push(format!("{}: {w}", doc.display()));
            }
        }
    }
    missing.sort();
    missing.dedup();
    assert!(
        missing.is_empty(),
        "docs name files that are not in the repository:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_word_finder_sees_names_and_paths_but_not_urls() {
    let w = file_words(
        "see MODEL.md §5, [lines](docs/lines.md#x), `src/run.rs`; https://example.org/a.md; .md files",
    );
    assert_eq!(w, ["MODEL.md", "docs/lines.md", "src/run.rs"]);
}

/// docs/model.md §7 lists every quantity of the registry, with its unit,
/// and no name the registry does not have: the reference a reader checks a
/// column against cannot drift from the code.
#[test]
fn the_model_lists_every_quantity_of_the_registry() {
    let text = std::fs::read_to_string(crate::common::crate_root().join("docs/model.md")).unwrap();
    let start = text.find("## 7. Measured quantities").expect("§7");
    let end = text[start..]
        .find("\n## 8.")
        .map_or(text.len(), |e| start + e);
    let section = &text[start..end];
    let rows: Vec<&str> = section.lines().filter(|l| l.starts_with("| `")).collect();
    let all = taut::quantity::all();
    for q in &all {
        let row = rows
            .iter()
            .find(|r| r.starts_with(&format!("| `{}` |", q.name)))
            .unwrap_or_else(|| panic!("docs/model.md §7 has no row for `{}`", q.name));
        assert!(
            row.contains(&format!("| {} |", q.unit)),
            "`{}`'s row does not give its unit {}: {row}",
            q.name,
            q.unit
        );
    }
    assert_eq!(
        rows.len(),
        all.len(),
        "a row for a quantity the registry has not"
    );
}
