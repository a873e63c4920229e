//! `snapshots.csv` and `field.csv`: the wire's displacement along the span
//! (docs/output.md#snapshots), long form, one row per (time, point).
//!
//! Written a line at a time from the recorded series: a field of 10⁸
//! values is never copied into columns (a copy of the time and x of every
//! row took four times the series' memory).

use std::io::Write;
use std::path::Path;

use super::fmt_f64;
use crate::error::{Error, Result};
use crate::record::{History, WireSeries};

/// Write `s` to `path` as the columns `t` (the step's time, s), `x` (m)
/// and `v` (m, positive up), a row per (time, point) in time order then x
/// order; with `requested`, `t_requested` (the time asked for, s) first.
fn write_long(path: &Path, s: &WireSeries, requested: bool) -> Result<()> {
    let io = |e| Error::io(path, e);
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).map_err(io)?);
    let header = if requested {
        "t_requested,t,x,v\n"
    } else {
        "t,x,v\n"
    };
    w.write_all(header.as_bytes()).map_err(io)?;
    let mut line = String::new();
    for k in 0..s.rows() {
        let (req, t) = (fmt_f64(s.requested[k]), fmt_f64(s.t[k]));
        for (x, v) in s.x.iter().zip(s.row(k)) {
            line.clear();
            if requested {
                line.push_str(&req);
                line.push(',');
            }
            line.push_str(&t);
            line.push(',');
            line.push_str(&fmt_f64(*x));
            line.push(',');
            line.push_str(&fmt_f64(*v));
            line.push('\n');
            w.write_all(line.as_bytes()).map_err(io)?;
        }
    }
    w.flush().map_err(io)
}

/// Write `snapshots.csv` (`t_requested`, `t`, `x`, `v`) and `field.csv`
/// (`t`, `x`, `v`) into `dir`, each only when the scene asked for it.
pub(crate) fn write_wire(dir: &Path, h: &History) -> Result<()> {
    if !h.snapshots.is_empty() {
        write_long(&dir.join("snapshots.csv"), &h.snapshots, true)?;
    }
    if !h.field.is_empty() {
        write_long(&dir.join("field.csv"), &h.field, false)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_times_then_points() {
        let s = WireSeries {
            requested: vec![0.1, 0.25],
            t: vec![0.1, 0.2500000000000001],
            x: vec![0.0, 0.5, 1.0],
            v: vec![0.0, -1e-3, 0.0, 0.0, 2.5e-7, 0.0],
        };
        let tmp = tempfile::tempdir().unwrap();
        let p = tmp.path().join("s.csv");
        write_long(&p, &s, true).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "t_requested,t,x,v");
        assert_eq!(lines[1], "0.1,0.1,0,0");
        assert_eq!(lines[2], "0.1,0.1,0.5,-0.001");
        assert_eq!(lines[5], "0.25,0.2500000000000001,0.5,2.5e-7");
        assert_eq!(lines.len(), 7);
        write_long(&p, &s, false).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        assert!(text.starts_with("t,x,v\n0.1,0,0\n"), "{text}");
    }
}
