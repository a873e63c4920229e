//! The layers only look down (`docs/architecture.md`, "Layers, and what
//! each may import"): every `crate::<room>` path in the library's code
//! (comments and the `#[cfg(test)]` part of a file left out) names a room on
//! a lower floor than its own, or its own room. Read from the source text,
//! as a reviewer would with `grep`.

use std::path::Path;

/// The floors of `docs/architecture.md`'s table: a room may import only
/// rooms on a lower floor (and itself). `lib` is `src/lib.rs`; a path
/// through its re-exports (`crate::Error`) counts as the room it re-exports.
const FLOORS: [(&str, u32); 26] = [
    ("error", 1),
    ("interrupt", 1),
    ("numeric", 1),
    ("defects", 1),
    ("input", 2),
    ("json_keys", 2),
    ("scene", 3),
    ("analytic", 4),
    ("manufactured", 4),
    ("contact", 4),
    ("model", 5),
    ("resolve", 6),
    ("integrate", 7),
    ("budget", 7),
    ("record", 8),
    ("warnings", 9),
    ("run", 10),
    ("quantity", 11),
    ("study", 12),
    ("lib", 12),
    // lib.rs's test of docs/api.md's count (it imports nothing)
    ("api_surface", 12),
    ("report", 13),
    ("app", 14),
    // lib.rs's re-exports, by the room that defines them
    ("Error", 1),
    ("Resolved", 6),
    ("RunOutput", 10),
];

fn floor(room: &str) -> Option<u32> {
    FLOORS.iter().find(|(r, _)| *r == room).map(|&(_, f)| f)
}

/// The room of a file under `src/`: its folder, or its name for a file at
/// the top (`error.rs` → `error`).
fn room_of(rel: &str) -> String {
    let first = rel.split('/').next().unwrap_or(rel);
    first.trim_end_matches(".rs").to_string()
}

/// The upward imports of one file's text: (the room named, its line).
fn upward(room: &str, text: &str) -> Vec<(String, String)> {
    let own = floor(room).unwrap_or_else(|| panic!("room `{room}` has no floor in FLOORS"));
    let mut found = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("#[cfg(test)]") {
            break; // the file's tests may use what stands above it
        }
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(at) = rest.find("crate::") {
            rest = &rest[at + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if name == room {
                continue;
            }
            let target = floor(&name)
                .unwrap_or_else(|| panic!("`crate::{name}` names no room in FLOORS: {line}"));
            if target >= own {
                found.push((name, line.trim().to_string()));
            }
        }
    }
    found
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src/ lists") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn no_room_imports_a_room_above_it() {
    let src = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    assert!(files.len() > 100, "{} files under src/", files.len());
    let mut up = Vec::new();
    for f in files {
        let rel = f.strip_prefix(&src).expect("under src").to_string_lossy();
        let text = std::fs::read_to_string(&f).expect("a source file reads");
        for (name, line) in upward(&room_of(&rel), &text) {
            up.push(format!("{rel} -> {name}: {line}"));
        }
    }
    assert!(
        up.is_empty(),
        "imports that run back up:\n{}",
        up.join("\n")
    );
}

#[test]
fn the_check_sees_an_upward_import() {
    // the guard itself: a scene that reads the model, an error that
    // carries a contact type, are caught; comments and tests are not code
    let scene = "use crate::error::Result;\nuse crate::model::mesh::Mesh;\n";
    assert_eq!(upward("scene", scene).len(), 1);
    assert_eq!(
        upward("error", "use crate::contact::ContactFailure;").len(),
        1
    );
    assert!(upward("model", "use crate::scene::BeamProps; // crate::resolve").is_empty());
    assert!(upward("model", "#[cfg(test)]\nuse crate::study::grid;").is_empty());
    assert_eq!(room_of("scene/validate.rs"), "scene");
    assert_eq!(room_of("error.rs"), "error");
}
