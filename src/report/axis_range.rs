//! The axis ranges a plot can draw, checked before any plot is drawn, and
//! the note drawn instead of a plot when a range cannot be.
//!
//! plotters' tick code loops without end (or grows without bound) on some
//! finite ranges: a log axis whose ends differ by more than f64 can hold
//! (1e-155 … 1e155: hi/lo overflows), a linear axis whose width overflows
//! (−9e307 … 9e307), or an end that is infinite or zero on a log axis. A
//! sweep over `carrier.stiffness=1e100:1e300` with `--log` hung in it after
//! writing its tables, never releasing its folder. Every plot of
//! taut (`force.svg`, `compare.svg`, `converge.svg`, `precision.svg` and the
//! sweep maps) therefore passes each of its axes through [`drawable`]
//! first; an axis that fails gets [`write_note`] in place of the plot, which
//! says why and where the numbers are (the tables are always written).
//!
//! The bounds below were found by drawing every range of a grid of ends
//! with plotters 0.3.7 under a time limit (`tests::every_accepted_range_draws_promptly`
//! draws the accepted ones again): linear axes up to ±8e307 and log axes up
//! to a ratio of 1e308 drew; ±9e307 and a ratio of 1e310 hung. The limits
//! keep a wide margin below those.

use std::path::Path;

use plotters::prelude::*;

use crate::error::{Error, Result};

/// Largest magnitude of an axis end (linear or log): ends within ±1e300
/// keep a linear width ≤ 2e300 and plotters' tick arithmetic finite (it
/// hung from a width of 1.8e308).
pub const MAX_AXIS_MAGNITUDE: f64 = 1e300;

/// Smallest lower end of a log axis: normal floats, and with
/// [`MAX_LOG_DECADES`] a ratio hi/lo that stays finite.
pub const MIN_LOG_END: f64 = 1e-300;

/// Most decades a log axis may span (hi/lo ≤ 1e300: plotters hung from a
/// ratio of 1e310).
pub const MAX_LOG_DECADES: f64 = 300.0;

/// A range `[lo, hi]` an axis can draw: both ends finite and within
/// ±[`MAX_AXIS_MAGNITUDE`]; on a log axis, lo ≥ [`MIN_LOG_END`] and at most
/// [`MAX_LOG_DECADES`] decades. An empty range (lo = hi) is widened around
/// its value. `Err` says, in words for a person, why the axis `name` cannot
/// be drawn.
pub(crate) fn drawable(
    name: &str,
    lo: f64,
    hi: f64,
    log: bool,
) -> std::result::Result<(f64, f64), String> {
    let scale = if log { "log" } else { "linear" };
    let shown = format!("{} … {}", compact(lo), compact(hi));
    let why = |reason: &str| format!("the {name} axis ({scale}, {shown}) {reason}");
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(why("has an end that is not a finite number"));
    }
    if lo > hi {
        return Err(why("is reversed"));
    }
    if lo.abs().max(hi.abs()) > MAX_AXIS_MAGNITUDE {
        return Err(why(&format!(
            "reaches beyond ±{MAX_AXIS_MAGNITUDE:e}, more than a plot can draw"
        )));
    }
    let (lo, hi) = if lo < hi {
        (lo, hi)
    } else if log {
        (lo / 1.1, hi * 1.1)
    } else {
        let h = if lo == 0.0 { 0.5 } else { 0.05 * lo.abs() };
        (lo - h, hi + h)
    };
    if log {
        if lo < MIN_LOG_END {
            return Err(why(&format!(
                "reaches down to {} on a log scale, whose lowest drawable end is {MIN_LOG_END:e}",
                compact(lo)
            )));
        }
        let decades = (hi / lo).log10();
        if decades.is_nan() || decades > MAX_LOG_DECADES {
            return Err(why(&format!(
                "spans {decades:.0} decades, more than the {MAX_LOG_DECADES:.0} a log axis can draw"
            )));
        }
    }
    Ok((lo, hi))
}

/// A number in at most 4 significant digits (`1e+300` → `1e300`), for
/// notes and messages.
fn compact(v: f64) -> String {
    crate::error::compact_number(v)
}

/// Draw a note in place of a plot: its title, why it cannot be drawn, and
/// where its numbers are.
pub(crate) fn write_note(
    path: &Path,
    size: (u32, u32),
    title: &str,
    reason: &str,
    tables: &str,
) -> Result<()> {
    let draw = || -> std::result::Result<(), Box<dyn std::error::Error>> {
        let root = SVGBackend::new(path, size).into_drawing_area();
        root.fill(&WHITE)?;
        let lines = [
            title.to_string(),
            String::new(),
            "This plot is not drawn:".to_string(),
            reason.to_string(),
            format!("The numbers are in {tables}."),
        ];
        for (k, line) in lines.iter().enumerate() {
            root.draw(&Text::new(
                line.clone(),
                (20, 30 + 26 * k as i32),
                ("sans-serif", if k == 0 { 18 } else { 15 }).into_font(),
            ))?;
        }
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hostile_ranges_are_refused_with_the_reason() {
        for (lo, hi, log, says) in [
            (0.0, 1.7e308, false, "beyond"),
            (f64::NAN, 1.0, false, "not a finite"),
            (0.0, f64::INFINITY, false, "not a finite"),
            (2.0, 1.0, false, "reversed"),
            (1e-301, 1.0, true, "lowest drawable end"),
            (0.0, 1.0, true, "lowest drawable end"),
            (-1.0, 1.0, true, "lowest drawable end"),
            (1e-300, 1e300, true, "decades"),
        ] {
            let e = drawable("y", lo, hi, log).unwrap_err();
            assert!(e.contains(says) && e.starts_with("the y axis"), "{e}");
        }
        assert_eq!(drawable("x", 1.0, 2.0, false), Ok((1.0, 2.0)));
        assert_eq!(drawable("x", 0.0, 0.0, false), Ok((-0.5, 0.5)));
        assert!(drawable("x", 1e-300, 1e-300, true).is_err());
    }

    /// Render a chart with ticks on a y axis of `lo..hi`, as the plots do.
    fn render(lo: f64, hi: f64, log: bool) {
        let mut svg = String::new();
        let root = SVGBackend::with_string(&mut svg, (400, 300)).into_drawing_area();
        let builder = || {
            let mut b = ChartBuilder::on(&root);
            b.x_label_area_size(30).y_label_area_size(60);
            b
        };
        if log {
            let mut c = builder()
                .build_cartesian_2d(0.0..1.0, (lo..hi).log_scale())
                .unwrap();
            c.configure_mesh().y_labels(10).draw().unwrap();
        } else {
            let mut c = builder().build_cartesian_2d(0.0..1.0, lo..hi).unwrap();
            c.configure_mesh().y_labels(10).draw().unwrap();
        }
    }

    /// How long one accepted range may take to draw: each draws in well
    /// under a millisecond; a hang is endless.
    const DRAW_LIMIT: std::time::Duration = std::time::Duration::from_secs(10);

    #[test]
    fn every_accepted_range_draws_promptly() {
        // ends over the whole float range, accepted or not; the accepted
        // ones are drawn on a thread that must finish within DRAW_LIMIT
        let mut ends: Vec<f64> = vec![0.0, f64::MIN_POSITIVE, 1.7e308, -1.7e308];
        for e in (-310..=308).step_by(26) {
            ends.push(10f64.powi(e));
            ends.push(-10f64.powi(e));
        }
        let mut accepted = Vec::new();
        for &lo in &ends {
            for &hi in &ends {
                for log in [false, true] {
                    if let Ok(r) = drawable("y", lo, hi, log) {
                        accepted.push((r.0, r.1, log));
                    }
                }
            }
        }
        assert!(accepted.len() > 300, "{}", accepted.len());
        let (tx, rx) = std::sync::mpsc::channel();
        let n = accepted.len();
        std::thread::spawn(move || {
            for (lo, hi, log) in accepted {
                render(lo, hi, log);
                tx.send(()).unwrap();
            }
        });
        for k in 0..n {
            rx.recv_timeout(DRAW_LIMIT)
                .unwrap_or_else(|_| panic!("range {k} of {n} did not draw"));
        }
    }
}
