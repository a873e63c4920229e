//! Tables a scene reads from CSV files: a carrier's tabulated speed
//! profile and its external force series (`file = "profile.csv"` in place
//! of the inline `time = [...]` and `speed = [...]` / `force = [...]`
//! arrays, docs/scene.md).
//!
//! A file is read where the scene is read (relative to the scene file's
//! folder; to the working directory for a scene given as text) and written
//! into the TOML tree as the inline arrays it stands for, before any
//! `--set` and before deserialization: every study, batch and shard then
//! sees the same arrays, and a table's checks (times rising, covering the
//! run) name its rows as `carrier.0.speed.time.2` like an inline table's.
//! A scene without a `file` key is passed through as the same text.

use std::path::Path;

use toml::{Table, Value};

use crate::error::{Error, Result};

/// The tables a carrier may read from a file: (its key, the value column).
const TABLES: [(&str, &str); 2] = [("speed", "speed"), ("external_force", "force")];

/// Replace every carrier table's `file = "..."` by the `time` and value
/// arrays of that CSV file (`base`: the folder relative paths start from).
/// True when something was read.
pub fn inline_table_files(tree: &mut Table, base: &Path) -> Result<bool> {
    let Some(Value::Array(carriers)) = tree.get_mut("carrier") else {
        return Ok(false);
    };
    let mut changed = false;
    for (i, carrier) in carriers.iter_mut().enumerate() {
        let Value::Table(carrier) = carrier else {
            continue;
        };
        for (key, column) in TABLES {
            let Some(Value::Table(t)) = carrier.get_mut(key) else {
                continue;
            };
            let Some(file) = t.remove("file") else {
                continue;
            };
            let field = format!("carrier.{i}.{key}.file");
            let Value::String(name) = file else {
                return Err(Error::invalid(
                    field,
                    file,
                    "must be the path of a CSV file (a string), relative to the scene file's folder",
                ));
            };
            if t.contains_key("time") || t.contains_key(column) {
                return Err(Error::invalid(
                    field,
                    format!("\"{name}\" beside `time`/`{column}`"),
                    format!(
                        "gives the table once: either `file` or the inline `time` and `{column}` arrays"
                    ),
                ));
            }
            if key == "speed" {
                match t.get("profile") {
                    None => {
                        t.insert("profile".into(), Value::String("table".into()));
                    }
                    Some(Value::String(p)) if p == "table" => {}
                    Some(other) => {
                        return Err(Error::invalid(
                            format!("carrier.{i}.speed.profile"),
                            other.clone(),
                            "must be \"table\" (or absent) with a `file`",
                        ));
                    }
                }
            }
            let path = base.join(&name);
            let text =
                crate::input::read_text(&path, "a table file", crate::input::MAX_INPUT_BYTES)?;
            let (time, values) = read_columns(&text, column)
                .map_err(|why| Error::invalid(field.clone(), format!("\"{name}\""), why))?;
            let array = |v: Vec<f64>| Value::Array(v.into_iter().map(Value::Float).collect());
            t.insert("time".into(), array(time));
            t.insert(column.into(), array(values));
            changed = true;
        }
    }
    Ok(changed)
}

/// The `time` and `column` columns of a CSV text: a header line naming the
/// columns (others are ignored), then one row of numbers per line; blank
/// lines and lines starting with `#` are skipped. The error says what is
/// wrong and on which line.
fn read_columns(text: &str, column: &str) -> std::result::Result<(Vec<f64>, Vec<f64>), String> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(format!(
            "must hold a header line `time,{column}` and rows of numbers: it is empty"
        ));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |want: &str| {
        names.iter().position(|n| *n == want).ok_or_else(|| {
            format!(
                "must have a `{want}` column: its header names {}",
                names.join(", ")
            )
        })
    };
    let (it, iv) = (find("time")?, find(column)?);
    let (mut time, mut values) = (Vec::new(), Vec::new());
    for (line, row) in lines {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(format!(
                "line {line} has {} cells, the header {}",
                cells.len(),
                names.len()
            ));
        }
        let number = |cell: &str| {
            cell.parse::<f64>()
                .map_err(|_| format!("line {line}: `{cell}` is not a number"))
        };
        time.push(number(cells[it])?);
        values.push(number(cells[iv])?);
    }
    if time.is_empty() {
        return Err(format!("has a header but no rows (time,{column} per line)"));
    }
    Ok((time, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_read_by_name_and_bad_rows_name_their_line() {
        let (t, v) = read_columns("# a ramp\nspeed, time\n0.0,0\n\n20.5,0.1\n", "speed").unwrap();
        assert_eq!((t, v), (vec![0.0, 0.1], vec![0.0, 20.5]));
        assert!(
            read_columns("time,force\n0,1\n0.1\n", "force")
                .unwrap_err()
                .contains("line 3")
        );
        assert!(
            read_columns("time,force\n0,x\n", "force")
                .unwrap_err()
                .contains("`x`")
        );
        assert!(
            read_columns("t,force\n0,1\n", "force")
                .unwrap_err()
                .contains("`time`")
        );
        assert!(read_columns("", "force").unwrap_err().contains("empty"));
    }
}
