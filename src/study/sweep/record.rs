//! What a finished sweep point contributes ([`SweepRecord`]): its
//! statistics and x_m/L profiles, or the error it stopped with.

use serde::{Deserialize, Serialize};
use toml::Table;

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
    /// Carrier 0's values of the quantities the tables with one row per
    /// run offer ([`crate::quantity::Offer::RUN_TABLES`]), by name (`null`
    /// for a run that stopped, and for a value it does not have).
    #[serde(flatten)]
    pub quantities: crate::quantity::Values,
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
    /// Unknowns × steps of every run made for the point (its own, the
    /// refined one, a tolerance's pilots and checks): the point's work,
    /// the same on any machine (`sweep.csv`'s `dof_steps_used`). Absent in
    /// records of a taut that did not count it.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub dof_steps: Option<f64>,
    /// CPU seconds of those runs on the threads that stepped them (a
    /// batch's shared by unknowns × steps; [`crate::study::cpu_time`]).
    /// Machine-dependent: written to timing.csv only.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub cpu_seconds: Option<f64>,
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
            quantities: crate::quantity::Values::none(),
            force_profile: vec![],
            loss_profile: vec![],
            warnings: vec![],
            refined: None,
            accuracy: None,
            error: None,
            wall_seconds: None,
            dof_steps: None,
            cpu_seconds: None,
        }
    }
}

impl SweepRecord {
    /// The record without its machine-dependent times (wall and CPU
    /// seconds): what two runs of one point must agree on.
    pub fn without_timing(&self) -> Self {
        SweepRecord {
            wall_seconds: None,
            cpu_seconds: None,
            ..self.clone()
        }
    }

    /// Count `cpu` more CPU seconds to the point (none where the platform
    /// gives no thread clock).
    pub(super) fn add_cpu(&mut self, cpu: Option<f64>) {
        if let Some(c) = cpu {
            self.cpu_seconds = Some(self.cpu_seconds.unwrap_or(0.0) + c);
        }
    }

    /// Its value of `q` (carrier 0), NaN where it has none.
    pub fn value(&self, q: &crate::quantity::Quantity) -> f64 {
        self.quantities.real(q)
    }

    /// P_l (carrier 0), NaN for a run that stopped.
    pub fn loss_fraction(&self) -> f64 {
        self.value(&crate::quantity::LOSS_FRACTION)
    }

    /// P_l's in-span part (carrier 0), NaN for a run that stopped.
    pub fn loss_fraction_span(&self) -> f64 {
        self.value(&crate::quantity::LOSS_FRACTION_SPAN)
    }

    /// A copy whose P_l is `v`: how a map drawn from P_l draws another
    /// value of each point (its in-span part, its u_num).
    pub fn with_loss_fraction(&self, v: f64) -> Self {
        let mut r = self.clone();
        r.quantities.set(&crate::quantity::LOSS_FRACTION, Some(v));
        r
    }
}

/// Run point `index` and reduce it to its record.
/// `base`: the spec's [`SweepSpec::base_tree`], when it could be made.
fn record(spec: &SweepSpec, base: Option<&Table>, id: &str, index: usize) -> SweepRecord {
    let sc = spec.resolve_with(base, index);
    let (ran, cpu) =
        crate::study::cpu_time::timed(|| sc.as_ref().map(|sc| run(sc, &mut |_, _| {})));
    let mut r = record_of(spec, base, id, index, sc.as_ref().ok(), ended(&ran));
    r.add_cpu(cpu);
    r
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
    // the refined run (with --check-refinement) is part of the point's work
    let (refined_run, refined_cpu) = if spec.check_refinement {
        let (r, cpu) = crate::study::cpu_time::timed(|| refined(spec, base, index));
        (Some(r), cpu)
    } else {
        (None, None)
    };
    let dof_steps = out.dofs as f64 * out.steps as f64 + refined_run.as_ref().map_or(0.0, |r| r.1);
    let refined_run = refined_run.map(|r| r.0);
    SweepRecord {
        sweep_id: id.to_string(),
        index,
        values,
        speed_ratio: (c > 0.0).then(|| sc.carriers[0].motion.profile.cruise_speed() / c),
        quantities: crate::quantity::Values::of(out, 0, crate::quantity::Offer::RUN_TABLES),
        force_profile: (0..PROFILE_BINS)
            .map(|b| (n[b] > 0).then(|| fsum[b] / n[b] as f64))
            .collect(),
        loss_profile: (0..PROFILE_BINS)
            .map(|b| (n[b] > 0).then(|| lost[b] as f64 / n[b] as f64))
            .collect(),
        warnings: out.warnings.clone(),
        refined: refined_run,
        accuracy: None,
        error: None,
        wall_seconds: Some(out.wall_seconds),
        dof_steps: Some(dof_steps),
        cpu_seconds: refined_cpu,
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
