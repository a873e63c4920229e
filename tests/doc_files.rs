//! Every file a doc or a doc comment names is in the repository:
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

/// The folders (and files) a reader of the repository meets, whose text
/// must not name a tracker's issue number: a reader has no tracker, so a
/// comment, a doc or a test says what and why in its own words.
const NO_TRACKER_NUMBERS_IN: [&str; 11] = [
    "src/",
    "cli/",
    "tests/",
    "xtask/",
    "scripts/",
    "python/",
    "benches/",
    "examples/",
    "scenes/",
    "docs/",
    "README.md",
];

/// The word a tracker reference starts with, built from pieces so that
/// this file does not name one itself.
const TRACKER_WORD: &str = concat!("iss", "ue");

/// The places in `text` (1-based line numbers) where an issue number is
/// named: the tracker's word, singular or plural, then an optional `#` and
/// a number (also across a comment's line break), or a `#` and a number
/// standing alone (after a space, a bracket or a comma), not part of a
/// colour, an anchor (`#5-contact`) or a word.
fn tracker_numbers(text: &str) -> Vec<usize> {
    let lower = text.to_lowercase();
    let b = lower.as_bytes();
    let line_of = |i: usize| lower[..i].matches('\n').count() + 1;
    let mut hits = Vec::new();
    // the word, then a number
    let mut from = 0;
    while let Some(k) = lower[from..].find(TRACKER_WORD) {
        let at = from + k;
        from = at + TRACKER_WORD.len();
        if at > 0 && b[at - 1].is_ascii_alphanumeric() {
            continue;
        }
        let mut i = from;
        if b.get(i) == Some(&b's') {
            i += 1;
        }
        while i < b.len() && (b[i] == b' ' || b[i] == b'\t') {
            i += 1;
        }
        if b.get(i) == Some(&b'\n') {
            // a comment's next line: its indentation and marker
            i += 1;
            while i < b.len() && b" \t/!#*\"".contains(&b[i]) {
                i += 1;
            }
        }
        if b.get(i) == Some(&b'#') {
            i += 1;
        }
        if b.get(i).is_some_and(u8::is_ascii_digit) {
            hits.push(line_of(at));
        }
    }
    // a `#` and a number standing alone
    for (at, _) in lower.match_indices('#') {
        let before_ok = at == 0 || b" \t([,".contains(&b[at - 1]);
        let digits = b[at + 1..]
            .iter()
            .take_while(|c| c.is_ascii_digit())
            .count();
        let after = b.get(at + 1 + digits).copied().unwrap_or(b' ');
        let after_ok = !(after.is_ascii_alphanumeric() || b"-_.".contains(&after));
        if before_ok && digits > 0 && after_ok {
            hits.push(line_of(at));
        }
    }
    hits.sort_unstable();
    hits.dedup();
    hits
}

#[test]
fn the_tracker_finder_sees_numbers_but_not_words() {
    let w = TRACKER_WORD;
    let found = |t: &str| !tracker_numbers(t).is_empty();
    for t in [
        format!("fixed ({w} 41)"),
        format!("{}{} 12: the fix", w[..1].to_uppercase(), &w[1..]),
        format!("{w}s 30-32"),
        format!("{w} {h}7", h = '#'),
        format!("// the case ({w}\n// 27; docs)"),
        format!("a regression ({h}44).", h = '#'),
        format!("see {h}44, then", h = '#'),
    ] {
        assert!(found(&t), "{t:?} names an issue number");
    }
    for t in [
        format!("the {w}'s band, ±0.3"),
        format!("an {w} number, never named"),
        format!("t{w} 3"),
        "color:#222; fill=\"#1f77b4\"".to_string(),
        "[4. Loss](#4-contact-loss), MODEL §12".to_string(),
        "#[derive(Debug)] # 3 cases".to_string(),
    ] {
        assert!(!found(&t), "{t:?} names no issue number");
    }
    assert_eq!(tracker_numbers(&format!("a\nb ({w} 5)\nc")), [2]);
}

/// No file a reader meets ([`NO_TRACKER_NUMBERS_IN`]) names an issue
/// number; the failure lists every file and line that does.
#[test]
fn no_file_names_an_issue_number() {
    let root = root();
    let mut files = Vec::new();
    walk(&root, &root, &mut files);
    let mut seen = 0;
    let mut named = Vec::new();
    for f in &files {
        let s = f.to_string_lossy().replace('\\', "/");
        if !NO_TRACKER_NUMBERS_IN.iter().any(|p| s.starts_with(p)) {
            continue;
        }
        // a binary file (a picture, a compiled module) has no prose
        let Ok(text) = std::fs::read_to_string(root.join(f)) else {
            continue;
        };
        seen += 1;
        for line in tracker_numbers(&text) {
            let shown = text.lines().nth(line - 1).unwrap_or("").trim();
            named.push(format!("{s}:{line}: {shown}"));
        }
    }
    assert!(seen > 300, "found the files ({seen})");
    assert!(
        named.is_empty(),
        "{} lines name an issue number (say what and why instead):\n{}",
        named.len(),
        named.join("\n")
    );
}

/// Most lines a module's doc header (the `//!` block at the top of a file
/// of `src/`) may have: enough to say what the module is, why it is so,
/// the MODEL.md equation it implements and its key design decision (about
/// 25 lines, and a little slack for a list or a formula). Measured
/// figures (timings, tables of errors) belong in tests that assert them
/// and in docs/ that quote them, not in a header that grows with each
/// measurement.
const MODULE_HEADER_MAX_LINES: usize = 30;

/// The `//!` lines a file opens with (blank lines between them do not end
/// the header: rustdoc joins the blocks).
fn module_header_lines(text: &str) -> usize {
    text.lines()
        .map(str::trim_start)
        .take_while(|l| l.is_empty() || l.starts_with("//!"))
        .filter(|l| l.starts_with("//!"))
        .count()
}

#[test]
fn module_headers_are_short() {
    assert_eq!(
        module_header_lines("//! a\n//!\n//! b\n\n//! c\nuse x;\n//! d"),
        4
    );
    let root = root();
    let mut files = Vec::new();
    walk(&root, &root.join("src"), &mut files);
    assert!(files.len() > 50, "found src/ ({} files)", files.len());
    let mut long: Vec<String> = files
        .iter()
        .filter(|f| f.extension().is_some_and(|e| e == "rs"))
        .filter_map(|f| {
            let text = std::fs::read_to_string(root.join(f)).ok()?;
            let n = module_header_lines(&text);
            (n > MODULE_HEADER_MAX_LINES).then(|| format!("{}: {n} lines", f.display()))
        })
        .collect();
    long.sort();
    assert!(
        long.is_empty(),
        "module headers longer than {MODULE_HEADER_MAX_LINES} lines:\n{}",
        long.join("\n")
    );
}

/// The guide's size: docs/ a reader gets through in an evening (7,000
/// lines, about 140 pages of text at 50 lines a page), no page longer than
/// a sitting (600 lines), and a README of a few screens (200 lines). A page
/// that grows past them is split or condensed, and measured tables go to the
/// files `cargo xtask` writes, not into the pages.
const DOCS_MAX_LINES: usize = 7_000;
const PAGE_MAX_LINES: usize = 600;
const README_MAX_LINES: usize = 200;

#[test]
fn the_guide_stays_within_its_size() {
    let root = root();
    let mut total = 0;
    let mut long = Vec::new();
    let mut pages: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    pages.sort();
    for p in &pages {
        let n = std::fs::read_to_string(p).unwrap().lines().count();
        total += n;
        if n > PAGE_MAX_LINES {
            long.push(format!("{}: {n} lines", p.display()));
        }
    }
    assert!(
        long.is_empty(),
        "pages over {PAGE_MAX_LINES} lines: {long:?}"
    );
    assert!(
        total <= DOCS_MAX_LINES,
        "docs/*.md is {total} lines, over {DOCS_MAX_LINES}"
    );
    let readme = std::fs::read_to_string(root.join("README.md"))
        .unwrap()
        .lines()
        .count();
    assert!(
        readme <= README_MAX_LINES,
        "README.md is {readme} lines, over {README_MAX_LINES}"
    );
}

/// The names quoted (`"name"`) in the row of `key` under the heading
/// `table` of docs/scene.md.
fn scene_row_names(page: &str, table: &str, key: &str) -> Vec<String> {
    let under = page
        .split("\n## ")
        .find(|s| s.starts_with(table))
        .unwrap_or_else(|| panic!("docs/scene.md has no section {table}"));
    let row = under
        .lines()
        .find(|l| l.starts_with(&format!("| `{key}` |")))
        .unwrap_or_else(|| panic!("docs/scene.md's {table} has no row `{key}`"));
    row.split("`\"")
        .skip(1)
        .filter_map(|s| s.split_once("\"`").map(|(name, _)| name.to_string()))
        .collect()
}

#[test]
fn the_scene_reference_lists_every_method_law_and_kind() {
    // the lists of scene.md's reference rows are held to the enums they
    // document: a new method, contact law or mesh kind fails here until
    // the page names it
    use taut::scene::{Formulation, MeshKind, Method};
    let page = std::fs::read_to_string(root().join("docs/scene.md")).unwrap();
    let kinds: Vec<&str> = MeshKind::ALL.iter().map(|k| k.name()).collect();
    let laws: Vec<&str> = Formulation::ALL.iter().map(|f| f.name()).collect();
    let methods: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
    for (table, key, names) in [
        ("`[mesh]`", "kind", kinds),
        ("`[contact]`", "formulation", laws),
        ("`[integrator]`", "method", methods),
    ] {
        let listed = scene_row_names(&page, table, key);
        for name in names {
            assert!(
                listed.iter().any(|l| l == name),
                "docs/scene.md's {table} row `{key}` does not list {name:?}: {listed:?}"
            );
        }
    }
}
