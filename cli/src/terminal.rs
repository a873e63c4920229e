//! What `taut` prints of an outcome: the text, so that the binary only
//! writes it out (stdout for results, stderr for the stopped points).

use std::fmt::Write;
use std::path::{Path, PathBuf};

use taut::record::{ContactStats, DropperStats, LossClass};
use taut::report::Summary;
use taut::study::sweep::SweepRecord;
use taut::study::tolerance::Accuracy;

/// Most stopped points a sweep names on the terminal (all are in sweep.csv).
pub const STOPPED_SHOWN: usize = 5;

/// Header, table and written files of a study command.
pub fn study(kind: &str, scene: &Path, table: &str, dir: &Path, files: &str) -> String {
    let mut s = format!(
        "taut {} — {kind} {}\n",
        env!("CARGO_PKG_VERSION"),
        scene.display()
    );
    s.push_str(table);
    let _ = writeln!(s, "  wrote    {}/{{{files}}}", dir.display());
    s
}

/// The terminal's contact-loss lines of one carrier: P_l split into the
/// in-span part (the number to quote) and the support part, the first loss
/// flagged when the run does not resolve it, the re-contacts.
pub fn contact_loss_lines(c: &ContactStats) -> String {
    let mut s = format!(
        "             contact loss P_l = {:.4} = {:.4} in span + {:.4} at supports (zone {:.2} m); {} intervals, {} switches\n",
        c.loss_fraction,
        c.loss_fraction_span,
        c.loss_fraction_support,
        c.support_zone,
        c.loss_interval_count,
        c.contact_switches
    );
    if let Some(x) = c.first_loss_position {
        let note = match c.loss_interval_class.first() {
            Some(LossClass::Unresolved) => " (unresolved: see WARNING)",
            Some(LossClass::Support) => " (in a support zone)",
            _ => "",
        };
        let _ = writeln!(s, "             first loss at x/L = {x:.4}{note}");
    }
    if c.recontact_count > 0 {
        let peak = c.recontacts.iter().map(|r| r.peak).fold(0.0, f64::max);
        let impulse = c.recontacts.iter().map(|r| r.impulse).fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "             {} re-contacts: peak λ up to {peak:.1} N (grows as Δt falls), impulse up to {impulse:.4} N·s",
            c.recontact_count
        );
    }
    s
}

/// The terminal's line of one dropper: its force range and slack.
pub fn dropper_line(d: &DropperStats) -> String {
    let kind = if d.linear { " (linear)" } else { "" };
    let slack = match d.slack_intervals_time.first() {
        Some([t0, _]) => format!(
            "slack {:.4} of the steps ({:.4} s) in {} intervals, first at t = {t0:.4} s",
            d.slack_fraction, d.slack_time, d.slack_interval_count
        ),
        None => "never slack".to_string(),
    };
    format!(
        "  dropper {} at x = {} m{kind}: force min {:.2} N, max {:.2} N; {slack}\n",
        d.name, d.x, d.force.min, d.force.max
    )
}

/// Droppers listed one a line up to this many; more (a line's 90) are
/// summed up in one line, and summary.json holds each.
pub const MAX_DROPPER_LINES: usize = 4;

/// The terminal's lines of a run's droppers: one each up to
/// [`MAX_DROPPER_LINES`], else one summary line — how many, the range of
/// their forces and which dropper holds each end, how many went slack.
pub fn dropper_lines(ds: &[DropperStats]) -> String {
    if ds.len() <= MAX_DROPPER_LINES {
        return ds.iter().map(dropper_line).collect();
    }
    let by = |f: fn(&DropperStats) -> f64| {
        let pick = |a: &&DropperStats, b: &&DropperStats| f(a).total_cmp(&f(b));
        (ds.iter().min_by(pick), ds.iter().max_by(pick))
    };
    let (lo, _) = by(|d| d.force.min);
    let (_, hi) = by(|d| d.force.max);
    let (Some(lo), Some(hi)) = (lo, hi) else {
        return String::new();
    };
    let linear = ds.iter().filter(|d| d.linear).count();
    let kind = match linear {
        0 => String::new(),
        n if n == ds.len() => " (all linear)".into(),
        n => format!(" ({n} linear)"),
    };
    let slack: Vec<&DropperStats> = ds.iter().filter(|d| d.slack_interval_count > 0).collect();
    let slack = match slack
        .iter()
        .max_by(|a, b| a.slack_fraction.total_cmp(&b.slack_fraction))
    {
        None => "none went slack".to_string(),
        Some(m) => format!(
            "{} of {} went slack, longest {} at x = {} m ({:.4} of the steps)",
            slack.len(),
            ds.len(),
            m.name,
            m.x,
            m.slack_fraction
        ),
    };
    format!(
        "  droppers {}{kind}: force min {:.2} N ({} at x = {} m), max {:.2} N ({} at x = {} m); {slack}; each in summary.json\n",
        ds.len(),
        lo.force.min,
        lo.name,
        lo.x,
        hi.force.max,
        hi.name,
        hi.x
    )
}

/// The run's one-screen summary; with `accuracy` (a tolerance run) the
/// choice of resolution first and an estimated error beside every result.
pub fn summary(scene: &Path, dir: &Path, s: &Summary, accuracy: Option<&Accuracy>) -> String {
    let d = &s.derived;
    let mut t = format!("taut {} — {}\n", s.taut_version, scene.display());
    if let Some(a) = accuracy {
        t.push_str(&taut::report::accuracy_header(a));
    }
    let _ = writeln!(
        t,
        "  beam     L = {} m, ρA = {:.4} kg/m, EI = {:.4e} N·m², T = {:.4e} N, c = {:.2} m/s",
        s.scene.beam.length,
        d.mass_per_length,
        d.bending_stiffness,
        s.scene.beam.tension,
        d.wave_speed
    );
    let ratio = d
        .speed_ratio
        .map_or_else(|| "n/a".to_string(), |r| format!("{r:.4}"));
    let _ = writeln!(
        t,
        "  mesh     {}, {} dofs; Δt = {} s, {} steps to t = {:.4} s; V0/c = {ratio}",
        taut::report::mesh_label(s),
        d.dofs,
        d.dt,
        d.steps,
        d.end_time
    );
    for (i, c) in s.carriers.iter().enumerate() {
        if let Some(a) = accuracy.filter(|_| i == 0) {
            let _ = writeln!(
                t,
                "  carrier {i} (± u_num at this resolution, from its own family of runs):"
            );
            t.push_str(&taut::report::result_lines(a));
            continue;
        }
        let f = &c.force;
        let _ = writeln!(
            t,
            "  carrier {i}: force mean {:.4} N, std {:.4} N, min {:.4} N, max {:.4} N",
            f.mean, f.std, f.min, f.max
        );
        if let taut::record::Filtered::Stats(f) = &c.force_filtered {
            let _ = writeln!(
                t,
                "             0–{} Hz force mean {:.4} N, std {:.4} N, min {:.4} N, max {:.4} N",
                f.cutoff_hz, f.mean, f.std, f.min, f.max
            );
        }
        t.push_str(&contact_loss_lines(c));
    }
    t.push_str(&dropper_lines(&s.droppers));
    if let Some(f) = &s.form_finding {
        let _ = writeln!(
            t,
            "  form     dropper lengths form-found in {} Newton step(s): the wire at rest within {:.2e} m of its design heights (tolerance {:.0e} m; {:.2e} m with the lengths given)",
            f.steps, f.error, f.tolerance, f.start_error
        );
    }
    t.push_str(&span_lines(s));
    if accuracy.is_none() {
        t.push_str(&standard_lines(s));
    }
    for w in &s.warnings {
        let _ = writeln!(t, "  WARNING  {w}");
    }
    let rate = d.dofs as f64 * d.steps as f64 / s.wall_seconds.max(1e-12);
    let _ = writeln!(
        t,
        "  time     {:.3} s wall ({rate:.3e} dof-steps/s)",
        s.wall_seconds
    );
    let accuracy_csv = if accuracy.is_some() {
        ", accuracy.csv"
    } else {
        ""
    };
    let o = &s.scene.output;
    let snapshots = if o.snapshots.is_empty() {
        ""
    } else {
        ", snapshots.csv"
    };
    let field = if o.field.is_some() { ", field.csv" } else { "" };
    let spans = match (s.spans.is_empty(), s.supports.is_empty()) {
        (false, _) => ", spans.csv, supports.csv",
        (true, false) => ", supports.csv",
        _ => "",
    };
    let envelope = if o.envelope {
        ", envelope.csv, line.svg"
    } else {
        ""
    };
    let form = if s.form_finding.is_some() {
        ", static_heights.csv, droppers_static.csv"
    } else {
        ""
    };
    let _ = writeln!(
        t,
        "  wrote    {}/{{history.csv, summary.json, force.svg, standard.csv, standard.json{accuracy_csv}{snapshots}{field}{spans}{envelope}{form}}}",
        dir.display()
    );
    t
}

/// The standards' statistics over the analysis section (`standard.csv`),
/// a line per carrier.
fn standard_lines(s: &taut::report::Summary) -> String {
    let mut t = String::new();
    let n = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2}"));
    for r in &s.standard {
        let uplift = match (r.uplift_max, r.uplift_x) {
            (Some(u), Some(x)) => format!(", uplift {:.2} mm at x = {x:.2} m", u * 1e3),
            _ => String::new(),
        };
        // a statistic shown as "-" says why it has no value
        let why = if r.samples == 0 {
            format!(
                "; no samples: the carrier's contact point was never in x_m ∈ [{}, {}] m during the run (move [analysis] or raise time.end)",
                r.x_start, r.x_end
            )
        } else if r.mean.is_none() {
            "; no filtered force recorded, so no F_m, σ, max or min".to_string()
        } else {
            String::new()
        };
        let _ = writeln!(
            t,
            "  standard carrier {}, x_m in {}–{} m, 0–{} Hz: F_m {} N, σ {} N, F_m ± 3σ {} / {} N, max {} N, min {} N, loss {} %{uplift}{why}",
            r.carrier,
            r.x_start,
            r.x_end,
            r.band_hz,
            n(r.mean),
            n(r.std),
            n(r.statistical_max),
            n(r.statistical_min),
            n(r.max),
            n(r.min),
            n(r.loss_percent),
        );
    }
    t
}

/// The per-span contact force table and the uplift at the supports
/// (`[output] supports`): a line per carrier and span, one per support;
/// nothing without supports.
fn span_lines(s: &taut::report::Summary) -> String {
    let mut t = String::new();
    if !s.spans.is_empty() {
        let _ = writeln!(
            t,
            "  spans    carrier span      x (m)          steps  mean (N)   std (N)   max (N)   min (N)  0–20 Hz mean/std (N)   P_l"
        );
    }
    let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2}"));
    for p in &s.spans {
        let _ = writeln!(
            t,
            "           {:>7} {:>4} {:>8.2}–{:<8.2} {:>7} {:>9} {:>9} {:>9} {:>9}  {:>9} / {:<9} {}",
            p.carrier,
            p.span,
            p.x_start,
            p.x_end,
            p.samples,
            num(p.force_mean),
            num(p.force_std),
            num(p.force_max),
            num(p.force_min),
            num(p.filtered_mean),
            num(p.filtered_std),
            p.loss_fraction
                .map_or("-".to_string(), |v| format!("{v:.4}"))
        );
    }
    for u in &s.supports {
        let _ = writeln!(
            t,
            "  support  x = {:.2} m: uplift max {:.2} mm at t = {:.4} s, min {:.2} mm{}",
            u.x,
            u.v_max * 1e3,
            u.t_max,
            u.v_min * 1e3,
            u.uplift.map_or(String::new(), |v| format!(
                "; {:.2} mm above its static position",
                v * 1e3
            ))
        );
    }
    t
}

/// Where a sweep's work went: its unknowns × steps and CPU seconds, split
/// between points met, not met and refused (a plain sweep: points that ran
/// and points that stopped).
pub fn work_line(records: &[SweepRecord]) -> String {
    use taut::study::sweep::{Work, WorkSplit};
    let s = WorkSplit::of(records);
    let tolerance = records.iter().any(|r| r.accuracy.is_some());
    let part = |name: &str, w: &Work| {
        format!(
            "{name} {} ({:.0} %, {:.1} s)",
            w.points,
            100.0 * s.share(w),
            w.cpu_seconds
        )
    };
    let t = s.total();
    let mut line = format!(
        "  work     {:.3e} DOF-steps, {:.1} s CPU: ",
        t.dof_steps, t.cpu_seconds
    );
    if tolerance {
        line.push_str(&part("met", &s.met));
        line.push_str(", ");
        line.push_str(&part("not met", &s.not_met));
    } else {
        line.push_str(&part("ran", &s.met));
    }
    line.push_str(", ");
    line.push_str(&part("refused or stopped", &s.refused));
    line
}

/// The maps a sweep or merge drew (a shard draws none: merge does).
pub fn maps(maps: &[PathBuf], shard: bool) -> String {
    if let Some((first, rest)) = maps.split_first() {
        let names: Vec<String> = rest
            .iter()
            .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .collect();
        if names.is_empty() {
            format!("  map      {}\n", first.display())
        } else {
            format!("  maps     {}, {}\n", first.display(), names.join(", "))
        }
    } else if shard {
        "  maps     none for a shard: `taut merge` draws them for the whole grid\n".to_string()
    } else {
        String::new()
    }
}

/// The points of a sweep whose run stopped (for stderr; empty when none):
/// the tables and maps are written, and the exit status (1) says some
/// points failed.
pub fn stopped(records: &[SweepRecord]) -> String {
    let stopped: Vec<_> = records.iter().filter(|r| r.error.is_some()).collect();
    if stopped.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "{} of {} points stopped with an error; their rows in sweep.csv carry it (column \
         `error`), the maps show them grey, and a resumed sweep keeps them:\n",
        stopped.len(),
        records.len()
    );
    for r in stopped.iter().take(STOPPED_SHOWN) {
        let _ = writeln!(
            s,
            "  point {} {:?}: {}",
            r.index,
            r.values,
            r.error.as_deref().unwrap_or_default()
        );
    }
    if stopped.len() > STOPPED_SHOWN {
        let _ = writeln!(s, "  … and {} more", stopped.len() - STOPPED_SHOWN);
    }
    s
}

/// `taut modes`' lines: one per mode (frequency, and the taut string's
/// where it applies), then the files written.
pub fn modes(scene: &Path, dir: &Path, m: &taut::study::modes::Modes) -> String {
    let mut s = format!(
        "taut {} — modes of {} ({}, shapes at {} points)\n",
        env!("CARGO_PKG_VERSION"),
        scene.display(),
        m.source.name(),
        m.x.len()
    );
    for (j, f) in m.frequencies_hz.iter().enumerate() {
        let string = m
            .string_hz
            .as_ref()
            .map_or(String::new(), |sh| format!("   string {:.6} Hz", sh[j]));
        let _ = writeln!(s, "  mode {:>3}  {f:.6} Hz{string}", j + 1);
    }
    let _ = writeln!(
        s,
        "  wrote    {}/{{modes.csv, mode_shapes.csv}}",
        dir.display()
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dropper(i: usize, min: f64, max: f64, slack: usize) -> DropperStats {
        DropperStats {
            name: format!("d{i}"),
            x: 3.5 + 6.0 * i as f64,
            linear: false,
            slack_fraction: 0.01 * slack as f64,
            slack_time: 0.0,
            slack_interval_count: slack,
            slack_intervals_time: vec![[0.1, 0.2]; slack.min(1)],
            force: taut::record::ForceStats {
                mean: 0.5 * (min + max),
                std: 1.0,
                min,
                max,
            },
        }
    }

    /// A line's 18 droppers are one line: count, the force range with the
    /// droppers that hold it, how many went slack; a few stay one a line.
    #[test]
    fn many_droppers_are_summed_up_in_one_line() {
        let ds: Vec<DropperStats> = (0..18)
            .map(|i| {
                dropper(
                    i,
                    10.0 + i as f64,
                    60.0 - i as f64,
                    usize::from(i % 6 == 0) * i,
                )
            })
            .collect();
        let t = dropper_lines(&ds);
        assert_eq!(t.lines().count(), 1, "{t}");
        assert!(t.contains("droppers 18"), "{t}");
        assert!(t.contains("force min 10.00 N (d0 at x = 3.5 m)"), "{t}");
        assert!(t.contains("max 60.00 N (d0 at x = 3.5 m)"), "{t}");
        assert!(t.contains("2 of 18 went slack, longest d12"), "{t}");
        let few = dropper_lines(&ds[..3]);
        assert_eq!(few.lines().count(), 3, "{few}");
    }
}
