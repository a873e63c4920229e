//! Results tables: the columns of `history.csv`, `sweep.csv`,
//! `compare.csv`, `converge.csv` and `precision.csv`, built once.
//!
//! Each table is made here from a run's or a study's results, then either
//! written as CSV (the CLI) or handed to the Python module as arrays, so the
//! two can never disagree on a column's name, order or value: the CSV
//! writers and the module read the same [`Table`].

use std::io::Write;
use std::path::Path;

use super::fmt_f64;
use crate::error::{Error, Result};

/// One column. The kinds differ in how a CSV cell is written and in what
/// array the Python module makes of them (docs/python.md).
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Real numbers, every cell written in shortest round-trip form (so a
    /// CSV reader gets the same `f64` bits back); NaN is written `NaN`.
    Real(Vec<f64>),
    /// Real numbers where a non-finite value means "none" (a sweep point
    /// that stopped, an order that cannot be measured): written as an
    /// empty cell, NaN in Python.
    RealOrNone(Vec<f64>),
    /// Counts and indices.
    Count(Vec<u64>),
    /// Counts that may be absent (empty cell; NaN in Python).
    CountOrNone(Vec<Option<u64>>),
    /// Yes/no written `1` / `0` (a state per row: `in_contact`).
    Bit(Vec<bool>),
    /// Yes/no written `true` / `false` (a flag per row: `pareto`).
    Bool(Vec<bool>),
    /// Names and short codes (method, formulation, quantity), written as
    /// they are: they hold no commas or quotes.
    Label(Vec<String>),
    /// Free text (an error message) or none: written quoted with any `"`
    /// turned into `'`, or empty.
    Text(Vec<Option<String>>),
}

impl Column {
    /// Number of rows.
    pub fn len(&self) -> usize {
        match self {
            Column::Real(v) | Column::RealOrNone(v) => v.len(),
            Column::Count(v) => v.len(),
            Column::CountOrNone(v) => v.len(),
            Column::Bit(v) | Column::Bool(v) => v.len(),
            Column::Label(v) => v.len(),
            Column::Text(v) => v.len(),
        }
    }

    /// True when the column has no rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Append row `i`'s CSV cell to `out`.
    fn write_cell(&self, i: usize, out: &mut String) {
        match self {
            Column::Real(v) => out.push_str(&fmt_f64(v[i])),
            Column::RealOrNone(v) => {
                if v[i].is_finite() {
                    out.push_str(&fmt_f64(v[i]));
                }
            }
            Column::Count(v) => out.push_str(&v[i].to_string()),
            Column::CountOrNone(v) => {
                if let Some(n) = v[i] {
                    out.push_str(&n.to_string());
                }
            }
            Column::Bit(v) => out.push(if v[i] { '1' } else { '0' }),
            Column::Bool(v) => out.push_str(if v[i] { "true" } else { "false" }),
            Column::Label(v) => out.push_str(&v[i]),
            Column::Text(v) => {
                if let Some(t) = &v[i] {
                    out.push('"');
                    out.push_str(&t.replace('"', "'"));
                    out.push('"');
                }
            }
        }
    }
}

/// Named columns of equal length, in output order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    /// `(name, column)` in order.
    pub columns: Vec<(String, Column)>,
}

impl Table {
    /// An empty table.
    pub fn new() -> Self {
        Table::default()
    }

    /// Append a column. Every column of a table has the same number of
    /// rows; a column of another length is a bug in the table's builder.
    pub fn push(&mut self, name: impl Into<String>, column: Column) {
        let name = name.into();
        if let Some((first, c)) = self.columns.first() {
            assert_eq!(
                c.len(),
                column.len(),
                "column lengths differ: {first} and {name}"
            );
        }
        self.columns.push((name, column));
    }

    /// Number of rows (0 for a table without columns).
    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, |(_, c)| c.len())
    }

    /// The column named `name`.
    pub fn get(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, c)| c)
    }

    /// Append a column for each quantity the tables with one row per run
    /// offer ([`crate::quantity::Offer::RUN_TABLES`], in the registry's
    /// order) from `rows`' values, one row each: the one place a study
    /// table gains its quantities. A count is written as a count, any
    /// other quantity as a real; a value a row does not have is an empty
    /// cell. A quantity the table already has a column for (precision's
    /// `steps` and `dofs`) keeps that column: one name, one column.
    pub(crate) fn push_quantities<'a>(
        &mut self,
        rows: impl Iterator<Item = &'a crate::quantity::Values> + Clone,
    ) {
        for q in crate::quantity::offered(crate::quantity::Offer::RUN_TABLES) {
            if self.get(q.name).is_some() {
                continue;
            }
            let column = if q.count {
                Column::CountOrNone(rows.clone().map(|r| r.get(q).map(|v| v as u64)).collect())
            } else {
                Column::RealOrNone(rows.clone().map(|r| r.real(q)).collect())
            };
            self.push(q.name, column);
        }
    }

    /// The column names, in order.
    pub fn names(&self) -> Vec<&str> {
        self.columns.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The table as CSV: a header line, then one line per row.
    pub fn to_csv(&self) -> String {
        let mut s = String::new();
        self.rows_into(&mut |line| {
            s.push_str(line);
            Ok(())
        })
        .expect("writing to a String cannot fail");
        s
    }

    /// Write [`Table::to_csv`] to `path`, a line at a time (a long run's
    /// history is never held as one text).
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let io = |e| Error::io(path, e);
        let file = std::fs::File::create(path).map_err(io)?;
        let mut w = std::io::BufWriter::new(file);
        self.rows_into(&mut |line| w.write_all(line.as_bytes()))
            .map_err(io)?;
        w.flush().map_err(io)
    }

    /// Hand the header and then each row, as a CSV line with its line
    /// break, to `sink`.
    fn rows_into(&self, sink: &mut dyn FnMut(&str) -> std::io::Result<()>) -> std::io::Result<()> {
        self.lines_into(true, sink)
    }

    /// The CSV lines (with the header line first when `header`) into
    /// `sink`, one at a time: a table written in parts (`history.csv`, a
    /// block of rows at a time) gives the same bytes as written whole.
    pub(crate) fn lines_into(
        &self,
        header: bool,
        sink: &mut dyn FnMut(&str) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        let mut line = String::new();
        if header {
            line = self.names().join(",");
            line.push('\n');
            sink(&line)?;
        }
        for i in 0..self.rows() {
            line.clear();
            for (k, (_, c)) in self.columns.iter().enumerate() {
                if k > 0 {
                    line.push(',');
                }
                c.write_cell(i, &mut line);
            }
            line.push('\n');
            sink(&line)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_written_by_kind() {
        let mut t = Table::new();
        t.push("x", Column::Real(vec![0.1, f64::NAN]));
        t.push("y", Column::RealOrNone(vec![f64::NAN, 2e-7]));
        t.push("n", Column::CountOrNone(vec![Some(3), None]));
        t.push("b", Column::Bit(vec![true, false]));
        t.push("p", Column::Bool(vec![false, true]));
        t.push("m", Column::Label(vec!["bathe".into(), String::new()]));
        t.push("e", Column::Text(vec![Some("a \"b\", c".into()), None]));
        assert_eq!(t.rows(), 2);
        assert_eq!(
            t.to_csv(),
            "x,y,n,b,p,m,e\n0.1,,3,1,false,bathe,\"a 'b', c\"\nNaN,2e-7,,0,true,,\n"
        );
    }

    #[test]
    #[should_panic(expected = "column lengths differ")]
    fn columns_of_other_lengths_are_a_bug() {
        let mut t = Table::new();
        t.push("x", Column::Real(vec![1.0]));
        t.push("y", Column::Count(vec![1, 2]));
    }
}
