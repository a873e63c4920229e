//! A list of points (`--points FILE.csv`): sweep points given one by one
//! (a Latin hypercube, an optimizer's proposals) rather than as a grid.
//!
//! The file is a CSV table of numbers: a header of dotted scene keys (or
//! the study's dimensionless axes), then one row a point. Empty lines and
//! lines starting with `#` are skipped. Each column becomes a listed
//! [`Axis`] and the sweep walks them together ([`SweepSpec::paired`]).

use std::path::Path;

use super::axis::Axis;
use super::spec::SweepSpec;
use crate::error::{Error, Result, one_line};

/// The listed axes of a points file.
pub(crate) fn read_points(path: &Path) -> Result<Vec<Axis>> {
    let text = crate::input::read_text(path, "a points file", crate::input::MAX_INPUT_BYTES)?;
    parse_points(&text).map_err(|e| e.explained(&format!(" (in {})", path.display())))
}

/// The listed axes of a points table's text (see the module doc).
pub(crate) fn parse_points(text: &str) -> Result<Vec<Axis>> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(Error::invalid(
            "--points",
            "an empty file",
            "a header of scene keys, then one row of numbers a point",
        ));
    };
    let columns = header.split(',').count();
    if columns > super::MAX_POINT_KEYS {
        // refused before any row is read: a row of that many cells is no
        // list of scene keys
        return Err(Error::invalid(
            "--points",
            format!("{columns} columns"),
            format!(
                "a list of points sets at most {} keys (one a column): vary fewer scene values",
                super::MAX_POINT_KEYS
            ),
        ));
    }
    let keys: Vec<String> = header
        .split(',')
        .map(|k| k.trim().trim_matches('"').trim().to_string())
        .collect();
    if let Some(k) = keys.iter().position(|k| k.is_empty()) {
        return Err(Error::invalid(
            "--points",
            one_line(header),
            format!("column {} of the header has no key", k + 1),
        ));
    }
    let mut rows = Vec::new();
    for (line, row) in lines {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != keys.len() {
            return Err(Error::invalid(
                "--points",
                format!("line {line}: {} cells", cells.len()),
                format!(
                    "every row has one number for each of the {} keys",
                    keys.len()
                ),
            ));
        }
        let values: Result<Vec<f64>> = cells
            .iter()
            .zip(&keys)
            .map(|(c, k)| {
                c.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| {
                        Error::invalid(
                            "--points",
                            format!("line {line}, `{k}` = {}", one_line(c)),
                            "must be a finite number",
                        )
                    })
            })
            .collect();
        rows.push(values?);
    }
    if rows.is_empty() {
        return Err(Error::invalid(
            "--points",
            "a header only",
            "give at least one point (a row of numbers under the header)",
        ));
    }
    SweepSpec::points_axes(&keys, &rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_become_listed_axes() {
        let axes = parse_points("# a hypercube\nbeam.tension, carrier.mass\n2e4,1.0\n\n3e4,0.5\n")
            .unwrap();
        assert_eq!(axes.len(), 2);
        assert_eq!(axes[0].key, "beam.tension");
        assert_eq!(axes[0].values, Some(vec![2e4, 3e4]));
        assert_eq!(axes[1].values, Some(vec![1.0, 0.5]));
        for bad in ["", "a,b\n", "a,b\n1\n", "a,\n1,2\n", "a\nx\n", "a\nnan\n"] {
            assert!(parse_points(bad).is_err(), "{bad:?}");
        }
        // a file wider than the cap is refused at its header, in a line
        let wide = format!("{}\n", vec!["beam.tension"; 40_000].join(","));
        let e = parse_points(&wide).unwrap_err().to_string();
        assert!(e.contains("40000 columns") && e.len() < 300, "{e}");
    }

    #[test]
    fn a_byte_order_mark_is_not_part_of_the_first_key() {
        let tmp = tempfile::tempdir().unwrap();
        let p = tmp.path().join("p.csv");
        std::fs::write(&p, "\u{feff}carrier.mass,beam.tension\n1.0,2e4\n").unwrap();
        let axes = read_points(&p).unwrap();
        assert_eq!(axes[0].key, "carrier.mass");
    }
}
