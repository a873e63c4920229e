//! The statistics the railway standards ask of a simulated contact force
//! over an analysis section (docs/output.md#the-standards-statistics;
//! `[analysis]`): of the filtered force (0–`band` Hz, zero phase,
//! [`super::filter`]) the mean F_m, the standard deviation σ, the
//! statistical max and min F_m ± 3σ and the actual max and min; the
//! percentage of contact loss; and the largest uplift at the line's
//! supports in the section, measured from each support's static position.
//!
//! Each carrier is evaluated over the steps (rows 1 …, MODEL §5) whose own
//! contact point x_m lies in the section [x_start, x_end] (ends included):
//!
//! ```text
//! F_m = Σ F_i / n,   σ² = Σ (F_i − F_m)² / n,   loss % = 100 · (open steps) / n
//! ```
//!
//! with F the filtered force over the whole run, so the filter's start-up
//! at the run's first row is outside any section that starts later. The
//! uplift at a support x_s is max_t v(x_s, t) − v_static(x_s), the wire's
//! static position under its own loads with no carrier
//! ([`super::SupportUplift`]).

use serde::Serialize;

use super::filter::{STATISTICAL_SIGMAS, mean_std};
use super::{CarrierTrace, SupportUplift};

/// One carrier's standard statistics over the analysis section.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct StandardStats {
    /// The carrier's index, in scene order.
    pub carrier: usize,
    /// The section's start, m (carrier position x_m).
    pub x_start: f64,
    /// The section's end, m.
    pub x_end: f64,
    /// The filtered force's band, Hz (0 to this).
    pub band_hz: f64,
    /// The carrier's cruise speed, m/s.
    pub speed: f64,
    /// The same in km/h.
    pub speed_kmh: f64,
    /// Steps whose contact point lies in the section.
    pub samples: usize,
    /// Mean F_m of the filtered force, N (null without filtered force or
    /// samples).
    pub mean: Option<f64>,
    /// Its population standard deviation σ, N.
    pub std: Option<f64>,
    /// The statistical maximum F_m + 3σ, N.
    pub statistical_max: Option<f64>,
    /// The statistical minimum F_m − 3σ, N.
    pub statistical_min: Option<f64>,
    /// The largest filtered force in the section, N.
    pub max: Option<f64>,
    /// The smallest filtered force in the section, N.
    pub min: Option<f64>,
    /// Steps with the contact open over the section's steps, % (null
    /// without samples).
    pub loss_percent: Option<f64>,
    /// The largest uplift at a support in the section, from its static
    /// position, m (null when no support lies in the section or the static
    /// position is unknown).
    pub uplift_max: Option<f64>,
    /// The support where it is, m.
    pub uplift_x: Option<f64>,
}

/// Steps in the section and open steps among them, counted over every step
/// while the run goes (whatever rows the history keeps).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SectionCount {
    /// Steps whose contact point lies in the section.
    pub samples: usize,
    /// Those with the contact open.
    pub open: usize,
}

impl SectionCount {
    /// Count one step at `x` (m) with the contact `closed`.
    #[inline]
    pub fn push(&mut self, section: [f64; 2], x: f64, closed: bool) {
        if section[0] <= x && x <= section[1] {
            self.samples += 1;
            self.open += usize::from(!closed);
        }
    }
}

/// The section, band and speed a carrier is evaluated with.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Section {
    /// [x_start, x_end], m.
    pub x: [f64; 2],
    /// The filtered force's band, Hz.
    pub band_hz: f64,
    /// The carrier's cruise speed, m/s.
    pub speed: f64,
}

/// Carrier `carrier`'s statistics from its trace `tr` (its
/// `force_filtered` over every step, or empty), its step `count` and the
/// `supports`' uplift.
pub(crate) fn standard_stats(
    carrier: usize,
    sec: Section,
    tr: &CarrierTrace,
    count: SectionCount,
    supports: &[SupportUplift],
) -> StandardStats {
    let inside = |x: f64| sec.x[0] <= x && x <= sec.x[1];
    let f: Vec<f64> = if tr.force_filtered.len() == tr.x.len() {
        (1..tr.x.len())
            .filter(|&i| inside(tr.x[i]))
            .map(|i| tr.force_filtered[i])
            .collect()
    } else {
        Vec::new()
    };
    let some = |v: f64| (!f.is_empty()).then_some(v);
    let (mean, std) = mean_std(&f);
    let uplift = supports
        .iter()
        .filter(|s| inside(s.x))
        .filter_map(|s| s.uplift.map(|u| (u, s.x)))
        .fold(None, |best: Option<(f64, f64)>, (u, x)| match best {
            Some((b, _)) if b >= u => best,
            _ => Some((u, x)),
        });
    StandardStats {
        carrier,
        x_start: sec.x[0],
        x_end: sec.x[1],
        band_hz: sec.band_hz,
        speed: sec.speed,
        speed_kmh: sec.speed * 3.6,
        samples: count.samples,
        mean: some(mean),
        std: some(std),
        statistical_max: some(mean + STATISTICAL_SIGMAS * std),
        statistical_min: some(mean - STATISTICAL_SIGMAS * std),
        max: some(f.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        min: some(f.iter().copied().fold(f64::INFINITY, f64::min)),
        loss_percent: (count.samples > 0).then(|| 100.0 * count.open as f64 / count.samples as f64),
        uplift_max: uplift.map(|(u, _)| u),
        uplift_x: uplift.map(|(_, x)| x),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(x: &[f64], f: &[f64]) -> CarrierTrace {
        CarrierTrace {
            x: x.to_vec(),
            force: f.to_vec(),
            force_filtered: f.to_vec(),
            ..Default::default()
        }
    }

    #[test]
    fn only_the_sections_steps_count() {
        // row 0 is the initial state: never counted
        let tr = trace(&[0.0, 1.0, 2.0, 3.0, 4.0], &[99.0, 10.0, 20.0, 30.0, 99.0]);
        let mut count = SectionCount::default();
        let sec = Section {
            x: [1.0, 3.0],
            band_hz: 20.0,
            speed: 10.0,
        };
        for (i, &x) in tr.x.iter().enumerate().skip(1) {
            count.push(sec.x, x, i != 2);
        }
        let mut a = SupportUplift::new(2.0);
        a.push(0.0, 0.004);
        a.set_static(Some(0.001));
        let mut b = SupportUplift::new(4.0); // outside
        b.push(0.0, 0.05);
        b.set_static(Some(0.0));
        let s = standard_stats(0, sec, &tr, count, &[a, b]);
        assert_eq!(s.samples, 3);
        assert_eq!(s.mean, Some(20.0));
        let sd = (200.0f64 / 3.0).sqrt();
        assert_eq!(s.std, Some(sd));
        assert_eq!(s.statistical_max, Some(20.0 + 3.0 * sd));
        assert_eq!((s.max, s.min), (Some(30.0), Some(10.0)));
        assert_eq!(s.loss_percent, Some(100.0 / 3.0));
        assert_eq!(s.uplift_x, Some(2.0));
        assert!((s.uplift_max.unwrap() - 0.003).abs() < 1e-15);
        assert_eq!(s.speed_kmh, 36.0);
    }

    #[test]
    fn without_the_filtered_force_only_the_loss_is_known() {
        let mut tr = trace(&[0.0, 1.0], &[1.0, 1.0]);
        tr.force_filtered.clear();
        let count = SectionCount {
            samples: 1,
            open: 0,
        };
        let sec = Section {
            x: [0.0, 2.0],
            band_hz: 20.0,
            speed: 1.0,
        };
        let s = standard_stats(0, sec, &tr, count, &[]);
        assert_eq!(
            (s.mean, s.loss_percent, s.uplift_max),
            (None, Some(0.0), None)
        );
    }
}
