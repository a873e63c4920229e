//! What a finished sweep point contributes ([`SweepRecord`]): its
//! statistics and x_m/L profiles, or the error it stopped with.

use serde::{Deserialize, Serialize};
use toml::Table;

use super::nan_as_null;
use super::refine::{Refined, refined};
use super::spec::SweepSpec;
use super::tolerance_spec::PointAccuracy;
use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::run::{RunOutput, run};

/// Number of x_m/L bins of the per-run force and loss profiles.
pub const PROFILE_BINS: usize = 200;

/// What a finished run contributes to the sweep. A run that stopped is a
/// record too: its statistics are NaN (`null` in the file), its profiles
/// empty and `error` says why.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SweepRecord {
    /// The sweep this record belongs to (`super::folder::sweep_id`); empty in
    /// records of taut before stamping, which are refused.
    #[serde(default)]
    pub sweep_id: String,
    /// Grid index.
    pub index: usize,
    /// Axis values.
    pub values: Vec<f64>,
    /// V0/c of carrier 0 (null when c = 0).
    pub speed_ratio: Option<f64>,
    /// P_l (carrier 0).
    #[serde(with = "nan_as_null")]
    pub loss_fraction: f64,
    /// Its in-span part (outside the support zones): the part to quote.
    #[serde(with = "nan_as_null")]
    pub loss_fraction_span: f64,
    /// Its support part (the carrier's arrival at a support).
    #[serde(with = "nan_as_null")]
    pub loss_fraction_support: f64,
    /// Force statistics (carrier 0), N.
    #[serde(with = "nan_as_null")]
    pub force_mean: f64,
    /// Standard deviation, N.
    #[serde(with = "nan_as_null")]
    pub force_std: f64,
    /// Minimum, N.
    #[serde(with = "nan_as_null")]
    pub force_min: f64,
    /// Maximum, N.
    #[serde(with = "nan_as_null")]
    pub force_max: f64,
    /// x_m/L of the first loss (null if none).
    pub first_loss_position: Option<f64>,
    /// Contact switches.
    pub contact_switches: usize,
    /// The filtered force's mean, σ, max and min (carrier 0), N (NaN in a
    /// record of a taut before them, or a stopped run).
    #[serde(flatten, default)]
    pub filtered: crate::study::scalars::FilteredColumns,
    /// Mean force per x_m/L bin (PROFILE_BINS bins over [0, 1]), N; null for
    /// a bin no step fell in.
    pub force_profile: Vec<Option<f64>>,
    /// Fraction of steps with contact lost per x_m/L bin.
    pub loss_profile: Vec<Option<f64>>,
    /// Warnings of the run.
    pub warnings: Vec<String>,
    /// The same point refined (N × 2, Δt / 2), with `--check-refinement`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refined: Option<Refined>,
    /// With `--tolerance`: what the point reached (its statistics above are
    /// those of the reported run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<PointAccuracy>,
    /// The run's error, if it stopped (then the statistics are NaN/empty).
    pub error: Option<String>,
    /// Wall seconds (machine-dependent: written to timing.csv only).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub wall_seconds: Option<f64>,
}

impl SweepRecord {
    /// The record of a point that stopped before giving statistics (the
    /// caller sets `error`).
    pub(super) fn stopped(sweep_id: &str, index: usize, values: Vec<f64>) -> Self {
        SweepRecord {
            sweep_id: sweep_id.to_string(),
            index,
            values,
            speed_ratio: None,
            loss_fraction: f64::NAN,
            loss_fraction_span: f64::NAN,
            loss_fraction_support: f64::NAN,
            force_mean: f64::NAN,
            force_std: f64::NAN,
            force_min: f64::NAN,
            force_max: f64::NAN,
            first_loss_position: None,
            contact_switches: 0,
            filtered: crate::study::scalars::FilteredColumns::NONE,
            force_profile: vec![],
            loss_profile: vec![],
            warnings: vec![],
            refined: None,
            accuracy: None,
            error: None,
            wall_seconds: None,
        }
    }
}

/// Run point `index` and reduce it to its record.
/// `base`: the spec's [`SweepSpec::base_tree`], when it could be made.
fn record(spec: &SweepSpec, base: Option<&Table>, id: &str, index: usize) -> SweepRecord {
    let sc = spec.resolve_with(base, index);
    let ran = sc.as_ref().map(|sc| run(sc, &mut |_, _| {}));
    record_of(spec, base, id, index, sc.as_ref().ok(), ended(&ran))
}

/// What a point's run gave, its scene's refusal or its run's: the typed
/// error, made the record's text only by [`record_of`] (the record is
/// what `runs/` holds and a resumed sweep reads back).
pub(super) fn ended<'a>(
    ran: &'a std::result::Result<Result<RunOutput>, &'a Error>,
) -> std::result::Result<&'a RunOutput, &'a Error> {
    match ran {
        Ok(Ok(out)) => Ok(out),
        Ok(Err(e)) => Err(e),
        Err(e) => Err(*e),
    }
}

/// Point `index`'s record from its scene and what its run gave.
pub(super) fn record_of(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    index: usize,
    sc: Option<&Resolved>,
    out: std::result::Result<&RunOutput, &Error>,
) -> SweepRecord {
    let values = spec.point(index);
    let nan = SweepRecord::stopped(id, index, values.clone());
    let (sc, out) = match (sc, out) {
        (Some(sc), Ok(o)) => (sc, o),
        (_, Err(e)) => {
            return SweepRecord {
                error: Some(e.to_string()),
                ..nan
            };
        }
        (None, Ok(_)) => unreachable!("a run needs its scene"),
    };
    let s = &out.stats[0];
    let tr = &out.history.carriers[0];
    let l = sc.beam.length;
    let (mut fsum, mut lost, mut n) = (
        vec![0.0; PROFILE_BINS],
        vec![0usize; PROFILE_BINS],
        vec![0usize; PROFILE_BINS],
    );
    for i in 1..tr.x.len() {
        let b = ((tr.x[i] / l * PROFILE_BINS as f64) as usize).min(PROFILE_BINS - 1);
        fsum[b] += tr.force[i];
        lost[b] += usize::from(!tr.in_contact[i]);
        n[b] += 1;
    }
    let c = sc.beam.wave_speed();
    SweepRecord {
        sweep_id: id.to_string(),
        index,
        values,
        speed_ratio: (c > 0.0).then(|| sc.carriers[0].motion.profile.cruise_speed() / c),
        loss_fraction: s.loss_fraction,
        loss_fraction_span: s.loss_fraction_span,
        loss_fraction_support: s.loss_fraction_support,
        force_mean: s.force.mean,
        force_std: s.force.std,
        force_min: s.force.min,
        force_max: s.force.max,
        first_loss_position: s.first_loss_position,
        contact_switches: s.contact_switches,
        filtered: crate::study::scalars::FilteredColumns::of(out, 0),
        force_profile: (0..PROFILE_BINS)
            .map(|b| (n[b] > 0).then(|| fsum[b] / n[b] as f64))
            .collect(),
        loss_profile: (0..PROFILE_BINS)
            .map(|b| (n[b] > 0).then(|| lost[b] as f64 / n[b] as f64))
            .collect(),
        warnings: out.warnings.clone(),
        refined: spec.check_refinement.then(|| refined(spec, base, index)),
        accuracy: None,
        error: None,
        wall_seconds: Some(out.wall_seconds),
    }
}

/// [`record`], with a panic inside the run turned into that point's error,
/// so one bad point cannot take the sweep's other points down with it.
pub(super) fn record_guarded(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    index: usize,
) -> SweepRecord {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        record(spec, base, id, index)
    }))
    .unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".into());
        SweepRecord {
            error: Some(format!(
                "internal error (a panic in taut, please report it): {what}"
            )),
            ..SweepRecord::stopped(id, index, spec.point(index))
        }
    })
}
