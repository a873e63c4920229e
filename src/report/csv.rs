//! `history.csv`: one row per recorded time.

use std::io::Write;
use std::path::Path;

use super::fmt_f64;
use crate::error::{Error, Result};
use crate::run::RunOutput;

/// Write the history: `t, x_m, beam_w, mass_q, gap, force, in_contact`, then
/// one column per probe. With several carriers the per-carrier columns are
/// suffixed `_0`, `_1`, … (carrier by carrier).
pub fn write_history(path: &Path, out: &RunOutput) -> Result<()> {
    let io = |e| Error::io(path, e);
    let file = std::fs::File::create(path).map_err(io)?;
    let mut w = std::io::BufWriter::new(file);
    let h = &out.history;
    let nc = h.carriers.len();
    let names = ["x_m", "beam_w", "mass_q", "gap", "force", "in_contact"];
    let mut header = vec!["t".to_string()];
    for c in 0..nc {
        for n in names {
            header.push(if nc == 1 {
                n.to_string()
            } else {
                format!("{n}_{c}")
            });
        }
    }
    for (name, _) in &h.probes {
        header.push(name.clone());
    }
    writeln!(w, "{}", header.join(",")).map_err(io)?;
    let mut line = String::with_capacity(256);
    for i in 0..h.len() {
        line.clear();
        line.push_str(&fmt_f64(h.t[i]));
        for tr in &h.carriers {
            for v in [tr.x[i], tr.w[i], tr.q[i], tr.gap[i], tr.force[i]] {
                line.push(',');
                line.push_str(&fmt_f64(v));
            }
            line.push_str(if tr.in_contact[i] { ",1" } else { ",0" });
        }
        for (_, col) in &h.probes {
            line.push(',');
            line.push_str(&fmt_f64(col[i]));
        }
        writeln!(w, "{line}").map_err(io)?;
    }
    w.flush().map_err(io)
}
