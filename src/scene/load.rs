//! Reading scene files and applying `--set key.path=value` overrides.
//!
//! Overrides act on the TOML tree before deserialization, so anything a scene
//! file can say, a `--set` can say, and an override with an unknown key is
//! rejected exactly as an unknown key in the file would be.

use std::path::Path;

use toml::{Table, Value};

use super::scene_file::Scene;
use crate::error::{Error, Result, one_line};

/// The top-level tables of a scene ([`Scene`]'s fields, as spelled in a
/// file). A file with none of them is not a scene, and is refused without
/// naming its keys ([`check_is_scene`]).
pub const SCENE_TABLES: [&str; 11] = [
    "beam",
    "mesh",
    "carrier",
    "contact",
    "time",
    "integrator",
    "gravity",
    "probe",
    "output",
    "manufactured",
    "reference",
];

/// Parse scene text into a TOML tree.
///
/// A syntax error is reported by line, column and reason only. The toml
/// crate's own message quotes the offending line, and the file may not be a
/// scene at all (`taut run /etc/passwd`, a gate case naming any file): its
/// content must never be reproduced in a message, a log or a JUnit report.
pub(crate) fn parse_scene(text: &str) -> Result<Table> {
    text.parse::<Table>().map_err(|e| {
        let reason = one_line(e.message().lines().next().unwrap_or("").trim());
        Error::parse(match e.span() {
            Some(span) => {
                let (line, column) = line_column(text, span.start);
                format!("TOML syntax error at line {line}, column {column}: {reason}")
            }
            None => format!("TOML syntax error: {reason}"),
        })
    })
}

/// 1-based line and column (in characters) of byte `offset` in `text`.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    // the span may fall inside a multi-byte character: back off to its start
    let mut at = offset.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

/// Refuse a TOML tree none of whose top-level keys is a scene table: it is
/// some other file, and naming its keys (as "unknown field" would) would
/// reproduce its content.
pub(crate) fn check_is_scene(tree: &Table) -> Result<()> {
    if tree.keys().any(|k| SCENE_TABLES.contains(&k.as_str())) {
        return Ok(());
    }
    Err(Error::parse(format!(
        "not a scene: none of its {} top-level keys is a scene table (a scene has [beam], [mesh], [[carrier]] and [time], optionally {}); the file's own keys are not shown",
        tree.len(),
        "[contact], [integrator], [gravity], [[probe]], [output], [manufactured], [reference]"
    )))
}

/// Apply one override `key.path=value` to a TOML tree.
///
/// Path segments walk tables by key and arrays by index (`carrier.0.mass`);
/// an array with exactly one entry may be walked without an index
/// (`carrier.mass`). The value is read as a TOML value (`3e4`, `true`,
/// `"text"`, `{ profile = "constant", value = 10 }`); if it is not valid TOML
/// it is taken as a bare string, so `contact.kind=bilateral` works.
///
/// `unset key.path` ([`UNSET`]: `--unset key.path`, Python `set={key: None}`)
/// removes the key (a table's key, or an array's entry by index) instead,
/// so that the scene's default applies; a key that is not there is refused
/// (a misspelt key would otherwise remove nothing, silently).
pub(crate) fn apply_override(tree: &mut Table, spec: &str) -> Result<()> {
    let bad = |reason: String| Error::Override {
        spec: one_line(spec),
        reason: one_line(&reason),
    };
    if let Some(path) = spec.strip_prefix(UNSET)
        && !spec.contains('=')
    {
        return unset(tree, path).map_err(bad);
    }
    let (path, raw) = spec
        .split_once('=')
        .ok_or_else(|| bad("expected key.path=value".into()))?;
    let path = path.trim();
    let raw = raw.trim();
    if path.is_empty() {
        return Err(bad("the key path is empty".into()));
    }
    if raw.is_empty() {
        return Err(bad("the value is empty".into()));
    }
    set_typed(tree, path, parse_value(raw), || spec.to_string())?;
    // a carrier table given as `{ file = "…" }` is read here, as a scene
    // file's is where the file is read (`super::table_files`), its path
    // relative to the working directory (where the override was typed)
    if raw.contains("file") || path.ends_with(".file") {
        super::table_files::inline_table_files(tree, Path::new("."))?;
    }
    Ok(())
}

/// The override-list spelling of a removal: `unset key.path` (`--unset
/// key.path`; Python `set={"key.path": None}`). A space cannot be in a key
/// path, so no `key=value` override is read as one.
pub const UNSET: &str = "unset ";

/// Remove the key at `path` from a tree (walked as [`set_path`] walks:
/// tables by key, arrays by index, a one-entry array without one).
fn unset(tree: &mut Table, path: &str) -> std::result::Result<(), String> {
    let path = path.trim();
    if path.is_empty() {
        return Err("the key path is empty".into());
    }
    let segments: Vec<&str> = path.split('.').collect();
    if segments.iter().any(|s| s.is_empty()) {
        return Err(format!("`{path}` has an empty segment"));
    }
    if remove_in_table(tree, &segments) {
        Ok(())
    } else {
        Err(format!("`{path}` is not in the scene: nothing to remove"))
    }
}

/// Remove `segs` from table `t`; whether something was removed.
fn remove_in_table(t: &mut Table, segs: &[&str]) -> bool {
    match segs {
        [last] => t.remove(*last).is_some(),
        [first, rest @ ..] => t.get_mut(*first).is_some_and(|v| remove_in_value(v, rest)),
        [] => false,
    }
}

/// Remove `segs` (at least one) below `v`; whether something was removed.
fn remove_in_value(v: &mut Value, segs: &[&str]) -> bool {
    match v {
        Value::Table(t) => remove_in_table(t, segs),
        Value::Array(a) => match segs[0].parse::<usize>() {
            Ok(idx) if segs.len() == 1 => {
                idx < a.len() && {
                    a.remove(idx);
                    true
                }
            }
            Ok(idx) => a
                .get_mut(idx)
                .is_some_and(|x| remove_in_value(x, &segs[1..])),
            // the only entry: apply the same segment to it
            Err(_) if a.len() == 1 => remove_in_value(&mut a[0], segs),
            Err(_) => false,
        },
        _ => false,
    }
}

/// Store a typed `value` at the key path `path` of a TOML tree: a sweep
/// axis's grid value or a value a study derives, with the walk and the
/// errors of [`apply_override`] and no text made of the value. `spec`
/// spells the change as a `--set` would, for an error only.
pub(crate) fn set_typed(
    tree: &mut Table,
    path: &str,
    value: Value,
    spec: impl Fn() -> String,
) -> Result<()> {
    let bad = |reason: String| Error::Override {
        spec: one_line(&spec()),
        reason: one_line(&reason),
    };
    let path = path.trim();
    if path.is_empty() {
        return Err(bad("the key path is empty".into()));
    }
    let segments: Vec<&str> = path.split('.').collect();
    if segments.iter().any(|s| s.is_empty()) {
        return Err(bad(format!("`{path}` has an empty segment")));
    }
    let mut root = Value::Table(std::mem::take(tree));
    let result = set_path(&mut root, &segments, value);
    if let Value::Table(t) = root {
        *tree = t;
    }
    result.map_err(bad)
}

/// Walk `segments` from `root` and store `value` at the end of the path.
fn set_path(root: &mut Value, segments: &[&str], value: Value) -> std::result::Result<(), String> {
    let mut node = root;
    let mut walked = String::new();
    let last = segments.len() - 1;
    let mut i = 0;
    while i <= last {
        let seg = segments[i];
        match node {
            Value::Table(t) => {
                if i == last {
                    t.insert(seg.to_string(), value);
                    return Ok(());
                }
                node = t
                    .entry(seg.to_string())
                    .or_insert_with(|| Value::Table(Table::new()));
            }
            Value::Array(a) => {
                let n = a.len();
                if let Ok(idx) = seg.parse::<usize>() {
                    let slot = a.get_mut(idx).ok_or_else(|| match n {
                        0 => format!("`{walked}` has no entries; index {idx} is out of range"),
                        1 => format!("`{walked}` has 1 entry; index {idx} is out of range: use 0"),
                        _ => format!(
                            "`{walked}` has {n} entries; index {idx} is out of range: use 0 ..= {}",
                            n - 1
                        ),
                    })?;
                    if i == last {
                        *slot = value;
                        return Ok(());
                    }
                    node = slot;
                } else if n == 1 {
                    // the only entry: apply the same segment to it
                    node = &mut a[0];
                    continue;
                } else {
                    return Err(format!(
                        "`{walked}` has {n} entries: give an index, e.g. `{walked}.0.{seg}`"
                    ));
                }
            }
            _ => return Err(format!("`{walked}` is a value, not a table")),
        }
        if !walked.is_empty() {
            walked.push('.');
        }
        walked.push_str(seg);
        i += 1;
    }
    Ok(())
}

/// Read a `--set` value: TOML if it parses, else a bare string.
fn parse_value(raw: &str) -> Value {
    let doc = format!("v = {raw}");
    match doc.parse::<Table>() {
        Ok(mut t) => t
            .remove("v")
            .unwrap_or_else(|| Value::String(raw.to_string())),
        Err(_) => Value::String(raw.to_string()),
    }
}

/// Deserialize a TOML tree into a [`Scene`], naming the key path on error.
///
/// The path is written the way `--set` takes it (`carrier.0.speed`, not
/// `carrier[0].speed`), and the toml crate's own trailing "in `…`" line,
/// which repeats the path without array indices, is dropped.
///
/// A `[line]` table is expanded into the plain keys it stands for first
/// ([`super::line::expand_line`]): here, after every override, so that `--set
/// line.spans=12` and sweeps over `line.*` regenerate the line.
pub(crate) fn scene_from_tree(tree: Table) -> Result<Scene> {
    let (tree, generated) = super::line::expand_line_with_origin(tree)?;
    let value = Value::Table(tree);
    let scene: Result<Scene> = super::tables::from_value(value).map_err(|e| {
        let path = e.path().to_string().replace('[', ".").replace(']', "");
        let inner = e.into_inner().to_string();
        let inner = inner.split("\nin `").next().unwrap_or(&inner).trim_end();
        if path.is_empty() || path == "." {
            Error::parse(one_line(inner))
        } else {
            Error::Parse {
                reason: one_line(&format!("at `{path}`: {inner}")),
                field: Some(one_line(&path)),
            }
        }
    });
    let mut scene = scene.map_err(|e| generated.user_error(e))?;
    scene.generated = generated;
    Ok(scene)
}

/// Parse scene text, apply overrides in order and deserialize, without
/// validating (a study applies its typed changes, then validates once).
pub(crate) fn scene_with_overrides(text: &str, overrides: &[String]) -> Result<Scene> {
    let mut tree = parse_scene(text)?;
    check_is_scene(&tree)?;
    for spec in overrides {
        apply_override(&mut tree, spec)?;
    }
    scene_from_tree(tree)
}

/// A scene file's text (an unreadable file is an I/O error naming it; one
/// larger than [`crate::input::MAX_INPUT_BYTES`], or not UTF-8 text, is
/// refused as soon as that shows).
pub(crate) fn read_scene(path: &Path) -> Result<String> {
    let text = crate::input::read_text(path, "a scene file", crate::input::MAX_INPUT_BYTES)?;
    let base = path.parent().unwrap_or(Path::new("."));
    with_table_files(text, base).map_err(|e| in_file(e, path))
}

/// The scene text with its carriers' table files read in
/// ([`super::table_files`]; paths relative to `base`): the same text when
/// it has no `file` key (or does not parse: its parse error is reported
/// where it is deserialized, by line and column, as before).
pub(crate) fn with_table_files(text: String, base: &Path) -> Result<String> {
    if !text.contains("file") {
        return Ok(text);
    }
    let Ok(mut tree) = parse_scene(&text) else {
        return Ok(text);
    };
    if !super::table_files::inline_table_files(&mut tree, base)? {
        return Ok(text);
    }
    toml::to_string(&tree).map_err(|e| {
        Error::invalid(
            "carrier",
            one_line(&e.to_string()),
            "tables TOML can hold (finite numbers)",
        )
    })
}

/// Name the scene file in a parse error of its text (made by a function
/// that was given the text only: a study, a sweep); other errors as they are.
pub(crate) fn in_file(e: Error, path: &Path) -> Error {
    match e {
        Error::Parse { reason, field } => Error::Parse {
            reason: format!("{}: {reason}", path.display()),
            field,
        },
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_tables_are_the_scene_fields() {
        let text = include_str!("../../scenes/reference.toml");
        let scene = scene_from_tree(parse_scene(text).unwrap()).unwrap();
        let value = Value::try_from(&scene).unwrap();
        let keys: Vec<&str> = value
            .as_table()
            .unwrap()
            .keys()
            .map(|k| k.as_str())
            .collect();
        // every field but the (empty, skipped) probes, the (default,
        // skipped) output and the (absent, skipped) manufactured and
        // reference tables is written
        for k in &keys {
            assert!(SCENE_TABLES.contains(k), "{k}");
        }
        assert_eq!(keys.len(), SCENE_TABLES.len() - 4, "{keys:?}");
    }

    #[test]
    fn unset_removes_a_key_so_the_default_applies() {
        let text = include_str!("../../scenes/reference.toml");
        let mut tree = parse_scene(text).unwrap();
        assert!(tree["integrator"].get("rho_inf").is_some());
        apply_override(&mut tree, "unset integrator.rho_inf").unwrap();
        assert!(tree["integrator"].get("rho_inf").is_none());
        // carrier has one entry: walked without an index, as --set walks it
        apply_override(&mut tree, "unset carrier.preload").unwrap();
        assert!(tree["carrier"][0].get("preload").is_none());
        let e = apply_override(&mut tree, "unset integrator.rho_inf")
            .unwrap_err()
            .to_string();
        assert!(e.contains("not in the scene"), "{e}");
        // a key=value override is never a removal
        apply_override(&mut tree, "integrator.rho_inf=0.5").unwrap();
        assert!(tree["integrator"].get("rho_inf").is_some());
    }

    #[test]
    fn a_syntax_error_gives_line_and_column_not_the_text() {
        let e = parse_scene("a = 1\nroot:x:0:0:SECRET:/root\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2, column "), "{e}");
        assert!(!e.contains("SECRET") && !e.contains("root"), "{e}");
        assert_eq!(line_column("ab\ncé\nx", 7), (3, 1));
        assert_eq!(line_column("ab\ncé", 5), (2, 2));
    }

    #[test]
    fn a_file_with_no_scene_table_is_not_a_scene_and_its_keys_are_not_named() {
        let e = scene_with_overrides("SECRET_TOKEN = \"abc\"\n[package]\nname = \"x\"\n", &[])
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a scene") && e.contains("[beam]"), "{e}");
        assert!(!e.contains("SECRET") && !e.contains("package"), "{e}");
        // a scene with a typo still has its unknown key named
        let e = scene_with_overrides("[beam]\nlenght = 3\n", &[])
            .unwrap_err()
            .to_string();
        assert!(e.contains("lenght") && e.contains("length"), "{e}");
    }
}
