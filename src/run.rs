//! One run: scene → integrator → history and statistics.

use std::time::Instant;

use serde::Serialize;

use crate::error::Error;
use crate::error::Result;
use crate::integrate::{
    CarrierSample, Integrator, Lane, MAX_LANES, MethodFactory, RunBatch, batch_key, lanes_cap,
    new_batch, scene_method,
};
use crate::record::{
    ContactAccumulator, ContactStats, DropperAccumulator, DropperSample, DropperStats, Envelope,
    History, LossGeometry, Section, SectionCount, SpanAccumulator, SpanStats, StandardStats,
    SupportUplift, WireSeries, span_of, standard_stats,
};
use crate::resolve::Resolved;

/// What a run produces.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// Recorded histories (row 0 = t = 0).
    pub history: History,
    /// Contact statistics per carrier, in scene order.
    pub stats: Vec<ContactStats>,
    /// Statistics per dropper (`[[dropper]]`), in scene order; empty without.
    pub droppers: Vec<DropperStats>,
    /// Contact force statistics per carrier and span (`[output] supports`),
    /// carrier by carrier, span by span; empty without supports. The
    /// filtered force's are left `None` (the summary fills them).
    pub spans: Vec<SpanStats>,
    /// Each carrier's standard statistics over the analysis section
    /// (`[analysis]`; `standard.csv`), in scene order.
    pub standard: Vec<StandardStats>,
    /// Number of unknowns (beam dofs + mass dofs).
    pub dofs: usize,
    /// Steps taken.
    pub steps: usize,
    /// Time step, s.
    pub dt: f64,
    /// Wall-clock time of the run (assembly, factorization, initial state,
    /// time loop and recording), s.
    pub wall_seconds: f64,
    /// Findings that make the numbers suspect (e.g. contact chatter).
    pub warnings: Vec<String>,
    /// The end of the window every time statistic is taken over, s: the
    /// scene's end time T for a run of all its steps (its last row may fall
    /// short of T by less than a step), the last row's time for one stopped
    /// early (MODEL §7, `record::window`).
    pub window_end: f64,
    /// The contact force recorded at t is the method's multiplier acting at
    /// t − force_lag·Δt ([`crate::integrate::System::force_lag`]; 0 for a
    /// run of no steps). A reference force is compared there.
    pub force_lag: f64,
    /// The line at rest after form-finding (`docs/lines.md` eq. F1–F5):
    /// each dropper's length, force and height against its design; `None`
    /// without a dropper `design_height`.
    pub form: Option<crate::integrate::FormFound>,
}

/// A contact that opens or closes on more than this fraction of the steps is
/// chattering: physical loss/reattachment events are separated by many steps,
/// a step-to-step on/off pattern is a numerical oscillation (MODEL §5).
pub(crate) const CHATTER_FRACTION: f64 = 0.05;

/// The words of the chatter warning that name it (a comparison finds its
/// chattering runs by them, `report::compare::chatter_note`).
pub(crate) const CHATTER: &str = "step-to-step chatter";

/// How a run ended: the status a study keeps beside each run it lists
/// (a row, or a combination that gave none), so that a table can say
/// which runs stopped and why without reading an error's text.
///
/// A run's steps end at the scene's end time (`time.end`, by default when
/// the carrier has left the beam): that is [`RunEnd::Completed`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunEnd {
    /// Every step to the end time was taken.
    Completed,
    /// The scene or the method refused the run before its first step (a
    /// combination that means nothing for this scene).
    Refused,
    /// The state grew without bound ([`Error::Diverged`]).
    Diverged,
    /// A contact solve failed ([`Error::Contact`]).
    ContactFailed,
    /// Stopped on request ([`Error::Interrupted`]).
    Interrupted,
    /// Any other error (reading or writing a file, a memory budget).
    Failed,
}

impl RunEnd {
    /// The end of a run that stopped with `e`.
    pub fn of_error(e: &Error) -> RunEnd {
        match e {
            Error::Diverged { .. } => RunEnd::Diverged,
            Error::Contact { .. } => RunEnd::ContactFailed,
            Error::Interrupted => RunEnd::Interrupted,
            Error::Invalid { .. } | Error::Parse { .. } | Error::Override { .. } => RunEnd::Refused,
            _ => RunEnd::Failed,
        }
    }

    /// The end of a run that gave `r`.
    pub fn of<T>(r: &Result<T>) -> RunEnd {
        r.as_ref()
            .map_or_else(RunEnd::of_error, |_| RunEnd::Completed)
    }
}

/// Run a validated scene with its own method (`[integrator]`).
/// `progress(done, total)` is called about 200 times.
pub fn run(sc: &Resolved, progress: &mut dyn FnMut(usize, usize)) -> Result<RunOutput> {
    drive(sc, &|sc| Integrator::new(sc), progress)
}

/// Run a validated scene with the method `factory` builds (a method of
/// one's own: `examples/custom_method.rs`).
pub fn run_with(
    sc: &Resolved,
    factory: &dyn MethodFactory,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunOutput> {
    drive(sc, &|sc| Integrator::with_method(sc, factory), progress)
}

/// Build the integrator, step it to the end, record and summarize.
fn drive(
    sc: &Resolved,
    build: &dyn Fn(&Resolved) -> Result<Integrator>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunOutput> {
    // this run's share of the process's memory budget, held to its end
    let _memory = crate::budget::reserve(sc.memory_estimate().total());
    let start = Instant::now();
    let mut run = SteppedRun::new(sc, build(sc)?, start)?;
    run.defer = sc.droppers.is_empty();
    let report_every = (sc.steps / 200).max(1);
    // the next multiple of report_every, counted rather than divided for
    let mut next_report = report_every;
    for n in 1..=sc.steps {
        if crate::interrupt::requested() {
            return Err(Error::Interrupted);
        }
        run.step(sc)?;
        if n == next_report || n == sc.steps {
            progress(n, sc.steps);
        }
        if n == next_report {
            next_report += report_every;
        }
    }
    Ok(run.finish(sc))
}

/// One run stepped on request: its integrator and its recorder, with the
/// row at t = 0 recorded. [`run`] steps it to the end in one go; a
/// co-simulation (`app::Simulation`) a few steps at a time, reading the
/// state and applying forces between them. Stepped to the end, it gives
/// what [`run`] gives, bit for bit (the same steps, the same records).
pub struct SteppedRun {
    it: Integrator,
    rec: Recorder,
    start: Instant,
    /// Steps leave their last update pending ([`Integrator::step_deferred`]):
    /// for [`run`], which reads nothing between steps but the samples and
    /// the wire's displacements, and only without droppers (their samples
    /// read the state itself).
    defer: bool,
}

impl SteppedRun {
    /// Start the run of `sc` with its built integrator `it` (at t = 0):
    /// record row 0. `start` is when the run's wall time starts.
    pub fn new(sc: &Resolved, it: Integrator, start: Instant) -> Result<Self> {
        let mut rec = Recorder::new(sc, it.beam(), it.carriers());
        rec.observe(it.time(), true, true, &it)?;
        rec.observe_droppers(it.time(), true, |out| it.dropper_samples_into(out));
        rec.observe_wire(0, it.time(), |pv| it.displacement_at(pv));
        Ok(SteppedRun {
            it,
            rec,
            start,
            defer: false,
        })
    }

    /// True once every step of `sc` (the scene it was started with) is taken.
    pub fn done(&self, sc: &Resolved) -> bool {
        self.it.steps_taken() >= sc.steps
    }

    /// Take one step and record it (no allocation beyond the history's
    /// reserved rows). `sc` is the scene it was started with; a step past
    /// its end is an error of the caller's (check [`SteppedRun::done`]).
    pub fn step(&mut self, sc: &Resolved) -> Result<()> {
        debug_assert!(!self.done(sc), "stepped past the run's end");
        let it = &mut self.it;
        if self.defer {
            it.step_deferred()?;
        } else {
            it.step()?;
        }
        let n = it.steps_taken();
        let it = &self.it;
        let keep = self.rec.keeps(n, sc.steps);
        self.rec.observe(it.time(), keep, false, it)?;
        self.rec
            .observe_droppers(it.time(), keep, |out| it.dropper_samples_into(out));
        self.rec
            .observe_wire(n, it.time(), |pv| it.displacement_at(pv));
        Ok(())
    }

    /// The integrator (its state, system and samples).
    pub fn integrator(&self) -> &Integrator {
        &self.it
    }

    /// The integrator, to apply forces between steps
    /// ([`Integrator::hold_external_force`]).
    pub fn integrator_mut(&mut self) -> &mut Integrator {
        &mut self.it
    }

    /// The run's record so far: histories of the steps taken.
    pub fn history(&self) -> &History {
        &self.rec.h
    }

    /// Statistics and warnings of the run as stepped (all of `sc`'s steps
    /// for [`run`]'s result).
    pub fn finish(self, sc: &Resolved) -> RunOutput {
        let it = self.it;
        let wall_seconds = self.start.elapsed().as_secs_f64();
        self.rec.finish(
            sc,
            Finish {
                wall_seconds,
                dofs: it.dofs(),
                steps: it.steps_taken(),
                force_bound: it.force_bound(),
                method: it.method().to_string(),
                damping_note: it.constraint_damping_note(),
                force_lag: if it.steps_taken() > 0 {
                    it.force_lag()
                } else {
                    0.0
                },
                form: it.system().form_found().cloned(),
            },
        )
    }
}

/// What a run's end adds to its record.
struct Finish {
    wall_seconds: f64,
    dofs: usize,
    steps: usize,
    force_bound: f64,
    /// The method's name ([`crate::scene::MethodInfo::name`]).
    method: String,
    damping_note: Option<String>,
    force_lag: f64,
    form: Option<crate::integrate::FormFound>,
}

/// A run's history and statistics as they are recorded, step by step:
/// what [`run`] and a batch of runs ([`run_batch`]) share.
struct Recorder {
    h: History,
    acc: Vec<ContactAccumulator>,
    support_peak: Vec<f64>,
    probes: Vec<crate::model::beam::PointVector>,
    every: usize,
    /// Per dropper: its statistics, and this step's samples (scratch).
    droppers: Vec<DropperAccumulator>,
    dropper_now: Vec<DropperSample>,
    /// The wire's snapshots and field: what to record when, and where.
    wire: WireRecorder,
    /// The line's supports, m (`Resolved::wire.supports`), and per carrier
    /// its statistics over each span between them (empty without).
    supports: Vec<f64>,
    spans: Vec<Vec<SpanAccumulator>>,
    /// Per carrier, its steps in the analysis section (`[analysis]`).
    section: [f64; 2],
    in_section: Vec<SectionCount>,
}

/// What [`Recorder`] records of the wire along the span
/// ([`crate::resolve::wire`]): point vectors made once, rows stored into
/// room reserved before the first step.
struct WireRecorder {
    /// (step, requested time) of each snapshot.
    snapshots: Vec<(usize, f64)>,
    snapshot_pvs: Vec<crate::model::beam::PointVector>,
    field_every: usize,
    field_pvs: Vec<crate::model::beam::PointVector>,
    /// Point vectors at the supports and at the envelope's nodes (empty
    /// when none asked for).
    support_pvs: Vec<crate::model::beam::PointVector>,
    envelope_pvs: Vec<crate::model::beam::PointVector>,
    /// The messenger's point vectors at the envelope's nodes (empty without
    /// an envelope or a messenger): its start shape for `line.svg`.
    messenger_envelope_pvs: Vec<crate::model::beam::PointVector>,
}

impl WireRecorder {
    fn new(sc: &Resolved, beam: &crate::model::beam::BeamModel, h: &mut History) -> Self {
        let w = &sc.wire;
        if !w.snapshots.is_empty() {
            h.snapshots = WireSeries::with_capacity(w.snapshot_x.clone(), w.snapshots.len());
        }
        if w.field_every > 0 {
            h.field = WireSeries::with_capacity(w.field_x.clone(), w.field_rows(sc.steps));
        }
        h.supports = w.supports.iter().map(|&x| SupportUplift::new(x)).collect();
        for (s, v) in h
            .supports
            .iter_mut()
            .zip(static_positions(beam, &w.supports))
        {
            s.v_static = v;
        }
        if !w.envelope_x.is_empty() {
            h.envelope = Envelope::new(w.envelope_x.clone());
        }
        let pvs = |x: &[f64]| x.iter().map(|&x| beam.point_vector(x)).collect();
        WireRecorder {
            snapshots: w.snapshots.clone(),
            snapshot_pvs: pvs(&w.snapshot_x),
            field_every: w.field_every,
            field_pvs: pvs(&w.field_x),
            support_pvs: pvs(&w.supports),
            envelope_pvs: pvs(&w.envelope_x),
            messenger_envelope_pvs: if beam.has_messenger() {
                w.envelope_x
                    .iter()
                    .map(|&x| beam.messenger_point_vector(x))
                    .collect()
            } else {
                Vec::new()
            },
        }
    }

    /// Record step n (time t): the snapshots asked at it (in the scene's
    /// order; several may share a step) and a field row every K-th step.
    fn observe(
        &self,
        h: &mut History,
        n: usize,
        t: f64,
        displacement: impl Fn(&crate::model::beam::PointVector) -> f64,
    ) {
        for &(step, requested) in &self.snapshots {
            if step == n {
                record_row(
                    &mut h.snapshots,
                    requested,
                    t,
                    &self.snapshot_pvs,
                    &displacement,
                );
            }
        }
        if self.field_every > 0 && n.is_multiple_of(self.field_every) {
            record_row(&mut h.field, t, t, &self.field_pvs, &displacement);
        }
        // uplift at the supports: O(#supports), into values made up front
        for (pv, s) in self.support_pvs.iter().zip(h.supports.iter_mut()) {
            s.push(t, displacement(pv));
        }
        // the envelope: O(n), only when asked; both wires' start shapes
        // once, at step 0 (before the step loop)
        if n == 0 && !self.envelope_pvs.is_empty() {
            h.envelope.start = self.envelope_pvs.iter().map(&displacement).collect();
            h.envelope.messenger_start = self
                .messenger_envelope_pvs
                .iter()
                .map(&displacement)
                .collect();
        }
        for (i, pv) in self.envelope_pvs.iter().enumerate() {
            h.envelope.push(i, displacement(pv));
        }
    }
}

/// The wire's static position v_static(x) at each of `xs` (m): K d = f
/// with f the model's constant loads (self-weight, the droppers' preloads)
/// and every dropper's spring in K, no carrier (what the standards
/// measure uplift from; `record::SupportUplift`). One banded factor,
/// made only when there are points; `None` where K is singular (a wire
/// not held against rigid motion).
fn static_positions(beam: &crate::model::beam::BeamModel, xs: &[f64]) -> Vec<Option<f64>> {
    if xs.is_empty() {
        return Vec::new();
    }
    let Ok(factor) = crate::model::banded::BandedLdlt::factor(&beam.stiffness) else {
        return vec![None; xs.len()];
    };
    let mut d = beam.load.clone();
    factor.solve(&mut d);
    xs.iter()
        .map(|&x| Some(beam.point_vector(x).dot(&d)).filter(|v| v.is_finite()))
        .collect()
}

/// Append one row of v at the point vectors `pvs`.
fn record_row(
    s: &mut WireSeries,
    requested: f64,
    t: f64,
    pvs: &[crate::model::beam::PointVector],
    displacement: &impl Fn(&crate::model::beam::PointVector) -> f64,
) {
    s.requested.push(requested);
    s.t.push(t);
    for pv in pvs {
        s.v.push(displacement(pv));
    }
}

/// What a recorder reads of a run after a step: an integrator alone, or
/// one lane of a batch ([`LaneView`]).
trait Observed {
    /// Carrier `c`'s values now.
    fn sample(&self, c: usize) -> CarrierSample;
    /// Stop with a diagnosis if carrier `c`'s values `s` are absurd;
    /// `near`: [`Observed::near_support`] at `s.x`.
    fn check(&self, s: &CarrierSample, c: usize, near: bool) -> Result<()>;
    /// True when x lies in the last element before a supported end.
    fn near_support(&self, x: f64) -> bool;
    /// rᵀd of the run's beam displacements.
    fn displacement(&self, pv: &crate::model::beam::PointVector) -> f64;
}

impl Observed for Integrator {
    fn sample(&self, c: usize) -> CarrierSample {
        Integrator::sample(self, c)
    }

    fn check(&self, s: &CarrierSample, c: usize, near: bool) -> Result<()> {
        Integrator::check_near(self, s, c, near)
    }

    fn near_support(&self, x: f64) -> bool {
        Integrator::near_support(self, x)
    }

    fn displacement(&self, pv: &crate::model::beam::PointVector) -> f64 {
        self.displacement_at(pv)
    }
}

/// Lane `l` of a batch `batch` (its `lane`, whose method notes `note`), as
/// a recorder reads it.
struct LaneView<'a> {
    batch: &'a dyn RunBatch,
    l: usize,
    lane: &'a Lane,
    note: Option<&'a str>,
}

impl Observed for LaneView<'_> {
    fn sample(&self, c: usize) -> CarrierSample {
        self.batch.sample(self.l, c)
    }

    fn check(&self, s: &CarrierSample, c: usize, near: bool) -> Result<()> {
        crate::integrate::check_near_lane(&self.lane.sys, &self.lane.st, s, c, self.note, near)
    }

    fn near_support(&self, x: f64) -> bool {
        crate::integrate::near_support_lane(&self.lane.sys, x)
    }

    fn displacement(&self, pv: &crate::model::beam::PointVector) -> f64 {
        self.batch.displacement_at(self.l, pv)
    }
}

impl Recorder {
    fn new(sc: &Resolved, beam: &crate::model::beam::BeamModel, nc: usize) -> Self {
        let every = sc.record_every.max(1);
        let mut h = History::with_capacity(sc.history_rows(), every, nc, &sc.probes);
        h.filter_band_hz = sc.analysis.band_hz;
        h.droppers = sc
            .droppers
            .iter()
            .map(|d| (d.name.clone(), Vec::with_capacity(sc.history_rows())))
            .collect();
        let wire = WireRecorder::new(sc, beam, &mut h);
        Recorder {
            droppers: sc
                .droppers
                .iter()
                .map(|d| DropperAccumulator::new(&d.name, d.x, d.linear))
                .collect(),
            dropper_now: vec![DropperSample::default(); sc.droppers.len()],
            supports: sc.wire.supports.clone(),
            spans: (0..nc)
                .map(|c| SpanAccumulator::for_supports(c, &sc.wire.supports))
                .collect(),
            h,
            wire,
            // statistics over every step, whatever rows the history keeps;
            // the near-support force peak (below) likewise
            acc: (0..nc)
                .map(|c| ContactAccumulator::for_steps(LossGeometry::of(sc, c), sc.steps))
                .collect(),
            support_peak: vec![0.0f64; nc],
            section: sc.analysis.x,
            in_section: vec![SectionCount::default(); nc],
            probes: (0..sc.probes.len())
                .map(|i| sc.probe_vector(beam, i))
                .collect(),
            every,
        }
    }

    /// Record the wire at step n (time t), as [`WireRecorder::observe`].
    fn observe_wire(
        &mut self,
        n: usize,
        t: f64,
        displacement: impl Fn(&crate::model::beam::PointVector) -> f64,
    ) {
        self.wire.observe(&mut self.h, n, t, displacement);
    }

    /// True when step n's row is kept in the history.
    #[inline]
    fn keeps(&self, n: usize, steps: usize) -> bool {
        // every row (the default) without a division a step
        self.every == 1 || n.is_multiple_of(self.every) || n == steps
    }

    /// Record the state of `run` at time t (checking every carrier's
    /// values); `keep`: the row goes into the history, `first`: it is
    /// row 0 (t = 0).
    fn observe(&mut self, t: f64, keep: bool, first: bool, run: &impl Observed) -> Result<()> {
        if keep {
            self.h.t.push(t);
        }
        for c in 0..self.acc.len() {
            let s = run.sample(c);
            // once for the check's force bound and the support peak
            let near = run.near_support(s.x);
            run.check(&s, c, near)?;
            self.acc[c].push(t, &s);
            if !first && near {
                self.support_peak[c] = self.support_peak[c].max(s.force.abs());
            }
            if !first && let Some(k) = span_of(&self.supports, s.x) {
                self.spans[c][k].push(s.force, s.in_contact);
            }
            if !first {
                self.in_section[c].push(self.section, s.x, s.in_contact);
            }
            if keep {
                self.h.carriers[c].push(&s);
            }
        }
        if keep {
            for (pv, (_, col)) in self.probes.iter().zip(self.h.probes.iter_mut()) {
                col.push(run.displacement(pv));
            }
        }
        Ok(())
    }

    /// Record the droppers at time t (after [`Recorder::observe`] of the
    /// same row): `samples` fills their forces and slack states. No-op
    /// without droppers.
    fn observe_droppers(&mut self, t: f64, keep: bool, samples: impl Fn(&mut [DropperSample])) {
        if self.droppers.is_empty() {
            return;
        }
        samples(&mut self.dropper_now);
        for ((acc, s), (_, col)) in self
            .droppers
            .iter_mut()
            .zip(&self.dropper_now)
            .zip(self.h.droppers.iter_mut())
        {
            acc.push(t, *s);
            if keep {
                col.push(s.force);
            }
        }
    }

    /// Statistics and warnings of the finished run.
    fn finish(mut self, sc: &Resolved, f: Finish) -> RunOutput {
        self.h.filter_forces(sc.dt);
        for s in &mut self.h.supports {
            let v = s.v_static;
            s.set_static(v);
        }
        let standard = self
            .h
            .carriers
            .iter()
            .zip(&self.in_section)
            .enumerate()
            .map(|(c, (tr, &count))| {
                let sec = Section {
                    x: sc.analysis.x,
                    band_hz: sc.analysis.band_hz,
                    speed: sc.carriers[c].motion.profile.cruise_speed(),
                };
                standard_stats(c, sec, tr, count, &self.h.supports)
            })
            .collect();
        let max_abs_w: Vec<f64> = self.acc.iter().map(ContactAccumulator::max_abs_w).collect();
        let window_end = if f.steps == sc.steps {
            sc.t_end
        } else {
            f.steps as f64 * sc.dt
        };
        let stats = self
            .acc
            .into_iter()
            .map(|a| a.with_window_end(window_end).finish())
            .collect::<Vec<ContactStats>>();
        let mut warnings: Vec<String> = stats
            .iter()
            .enumerate()
            .filter(|(_, st)| st.contact_switches as f64 > CHATTER_FRACTION * sc.steps as f64)
            .map(|(i, st)| {
                let cause = f.damping_note.as_ref().map_or(String::new(), |w| {
                    format!("; likely cause: {w}")
                });
                format!(
                    "carrier {i}: contact switched {} times in {} steps: {CHATTER}, a numerical oscillation (integrator.method = {}, contact.placement = {:?}; MODEL §5); these contact statistics are not a converged answer{cause}",
                    st.contact_switches,
                    sc.steps,
                    f.method,
                    sc.contact.placement
                )
            })
            .collect();
        // arrival at a support: forces beyond the divergence bound, allowed there
        let bound = f.force_bound;
        warnings.extend(crate::warnings::resolution_warnings(sc, &max_abs_w, &stats));
        for (c, &peak) in self.support_peak.iter().enumerate() {
            if peak > bound {
                warnings.push(format!(
                    "carrier {c}: contact force {peak:.3e} N in the last element before a support (beyond the {bound:.1e} N bound applied elsewhere): the mass arrives with the beam under it deflected and is forced to w = 0 within one element, an impact the model has no law for; it grows as the step falls, and force_max includes it"
                ));
            }
        }
        RunOutput {
            spans: self
                .spans
                .iter()
                .flatten()
                .map(SpanAccumulator::finish)
                .collect(),
            window_end,
            force_lag: f.force_lag,
            form: f.form,
            standard,
            warnings,
            dofs: f.dofs,
            steps: f.steps,
            dt: sc.dt,
            history: self.h,
            stats,
            droppers: self
                .droppers
                .into_iter()
                .map(DropperAccumulator::finish)
                .collect(),
            wall_seconds: f.wall_seconds,
        }
    }
}

/// Run several validated scenes, stepping together those that share their
/// effective matrix ([`crate::integrate::batch_key`]) in batches of at most
/// `batch` runs (`integrate::batch`); the others, and all of them when
/// `batch` is 1, run alone. Results in the order of `scenes`, each
/// bit-identical to [`run`] of that scene alone (but `wall_seconds`: a
/// batched run reports the batch's wall time divided by its runs).
/// `done(i)` after scene i finishes.
pub fn run_batch(
    scenes: &[Resolved],
    batch: usize,
    done: &mut dyn FnMut(usize),
) -> Vec<Result<RunOutput>> {
    let mut out: Vec<Option<Result<RunOutput>>> = (0..scenes.len()).map(|_| None).collect();
    let width = batch.clamp(1, MAX_LANES);
    // group by key, in order of first appearance
    let mut groups: Vec<(Option<crate::integrate::BatchKey>, Vec<usize>)> = Vec::new();
    for (i, sc) in scenes.iter().enumerate() {
        let key = if width > 1 { batch_key(sc) } else { None };
        // no wider than the kernels compiled for this run's columns
        let cap = width.min(lanes_cap(sc));
        match groups
            .iter_mut()
            .find(|(k, g)| key.is_some() && *k == key && g.len() < cap)
        {
            Some((_, g)) => g.push(i),
            None => groups.push((key, vec![i])),
        }
    }
    for (key, members) in groups {
        if key.is_none() || members.len() == 1 {
            for i in members {
                out[i] = Some(run(&scenes[i], &mut |_, _| {}));
                done(i);
            }
            continue;
        }
        for (i, r) in drive_batch(scenes, &members) {
            out[i] = Some(r);
            done(i);
        }
    }
    out.into_iter()
        .map(|r| r.expect("every scene is run"))
        .collect()
}

/// Run several scenes, each with its method: those whose method is the
/// scene's own ([`MethodFactory::is_scene_method`]) through [`run_batch`]
/// (batches of at most `batch`), the others alone with [`run_with`].
/// Results in order, each the same as its run alone.
pub(crate) fn run_many(
    jobs: &[(Resolved, &dyn MethodFactory)],
    batch: usize,
    done: &mut dyn FnMut(usize),
) -> Vec<Result<RunOutput>> {
    let mut out: Vec<Option<Result<RunOutput>>> = (0..jobs.len()).map(|_| None).collect();
    let own: Vec<usize> = (0..jobs.len())
        .filter(|&i| jobs[i].1.is_scene_method(&jobs[i].0))
        .collect();
    let scenes: Vec<Resolved> = own.iter().map(|&i| jobs[i].0.clone()).collect();
    for (j, r) in run_batch(&scenes, batch, &mut |j| done(own[j]))
        .into_iter()
        .enumerate()
    {
        out[own[j]] = Some(r);
    }
    for (i, (sc, m)) in jobs.iter().enumerate() {
        if out[i].is_none() {
            out[i] = Some(run_with(sc, *m, &mut |_, _| {}));
            done(i);
        }
    }
    out.into_iter()
        .map(|r| r.expect("every job is run"))
        .collect()
}

/// Step `members` of `scenes` as one batch (equal keys); falls back to
/// running them alone when no kernel fits.
fn drive_batch(scenes: &[Resolved], members: &[usize]) -> Vec<(usize, Result<RunOutput>)> {
    let _memory = crate::budget::reserve(
        members
            .iter()
            .map(|&i| scenes[i].memory_estimate().total())
            .fold(0u64, u64::saturating_add),
    );
    let start = Instant::now();
    let list: Vec<(usize, &Resolved)> = members.iter().map(|&i| (i, &scenes[i])).collect();
    let (batch, errors) = new_batch(&list);
    let mut results: Vec<(usize, Result<RunOutput>)> =
        errors.into_iter().map(|(i, e)| (i, Err(e))).collect();
    let Some(mut b) = batch else {
        return results;
    };
    if !b.supported() {
        for lane in b.lanes() {
            results.push((lane.id, run(&scenes[lane.id], &mut |_, _| {})));
        }
        return results;
    }
    let runs = b.lanes().len() as f64;
    // each run's own method's cause of an instability, for its diagnoses
    let mut notes: Vec<Option<String>> = vec![None; scenes.len()];
    for &i in members {
        let sc = &scenes[i];
        notes[i] = scene_method(sc).constraint_note(sc);
    }
    let mut recs: Vec<Option<Recorder>> = b
        .lanes()
        .iter()
        .map(|lane| {
            Some(Recorder::new(
                &scenes[lane.id],
                lane.sys.beam(),
                lane.sys.physics.carriers.len(),
            ))
        })
        .collect();
    // recorders follow their lanes: index by lane, compacted with the batch
    let observe = |b: &dyn RunBatch, recs: &mut Vec<Option<Recorder>>, first: bool| {
        let mut gone = Vec::new();
        for (l, lane) in b.lanes().iter().enumerate() {
            let sc = &scenes[lane.id];
            let rec = recs[l].as_mut().expect("a recorder per lane");
            let n = lane.st.step;
            let outcome = match &lane.failed {
                Some(_) => Err(None),
                None => rec
                    .observe(
                        lane.st.t,
                        first || rec.keeps(n, sc.steps),
                        first,
                        &LaneView {
                            batch: b,
                            l,
                            lane,
                            note: notes[lane.id].as_deref(),
                        },
                    )
                    .map(|()| rec.observe_wire(n, lane.st.t, |pv| b.displacement_at(l, pv)))
                    .map_err(Some),
            };
            match outcome {
                Ok(()) if n < sc.steps => {}
                other => gone.push((l, other.err())),
            }
        }
        gone
    };
    let mut pending = observe(&*b, &mut recs, true);
    loop {
        // retire finished and stopped runs
        if !pending.is_empty() {
            let idx: Vec<usize> = pending.iter().map(|(l, _)| *l).collect();
            let mut errs: Vec<Option<Option<Error>>> =
                pending.into_iter().map(|(_, e)| e).collect();
            let lanes = b.retire(&idx);
            for (k, (lane, l)) in lanes.into_iter().zip(&idx).enumerate().rev() {
                let rec = recs.remove(*l).expect("a recorder per lane");
                let sc = &scenes[lane.id];
                let result = match (lane.failed, errs[k].take()) {
                    (Some(e), _) | (None, Some(Some(e))) => Err(e),
                    _ => Ok(rec.finish(
                        sc,
                        Finish {
                            wall_seconds: start.elapsed().as_secs_f64() / runs,
                            dofs: lane.sys.beam().n + lane.sys.contacts(),
                            steps: lane.st.step,
                            force_bound: lane.sys.law.force_bound,
                            method: sc.method.name().to_string(),
                            damping_note: crate::integrate::damping_note_of(
                                &lane.sys,
                                notes[lane.id].as_deref(),
                            ),
                            force_lag: lane.sys.force_lag(lane.st.t),
                            form: lane.sys.form_found().cloned(),
                        },
                    )),
                };
                results.push((lane.id, result));
            }
            if b.lanes().is_empty() {
                break;
            }
            if !b.supported() {
                // fewer lanes than any kernel: the rest continue alone, from the start
                for lane in b.lanes() {
                    results.push((lane.id, run(&scenes[lane.id], &mut |_, _| {})));
                }
                break;
            }
        }
        if crate::interrupt::requested() {
            for lane in b.lanes() {
                results.push((lane.id, Err(Error::Interrupted)));
            }
            break;
        }
        b.step();
        pending = observe(&*b, &mut recs, false);
    }
    results
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A whole run whose steps leave their update pending ([`run`],
    /// `modal_exact`'s one pass a step) records the bits of the same run
    /// stepped with each update settled at once (a co-simulation's
    /// [`SteppedRun`]): every history column, a probe's included, and the
    /// statistics.
    #[test]
    fn a_deferred_run_records_the_bits_of_a_settled_one() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/reference.toml");
        // pinned–pinned and clamped–pinned; 170 m/s: contact losses; J a
        // multiple of 8 and not
        for (left, modes) in [("pinned", 203), ("clamped", 203), ("pinned", 200)] {
            let o: Vec<String> = [
                "mesh.kind=galerkin",
                "time.step=1e-4",
                "integrator={ method = \"modal_exact\" }",
                "carrier.speed.cruise=170",
                "probe=[{ name = \"mid\", x = 25.0 }]",
            ]
            .iter()
            .map(|s| s.to_string())
            .chain([
                format!("beam.left=\"{left}\""),
                format!("mesh.modes={modes}"),
            ])
            .collect();
            let sc = crate::load_scene(&path, &o).unwrap();
            let deferred = run(&sc, &mut |_, _| {}).unwrap();
            let it = Integrator::new(&sc).unwrap();
            let mut stepped = SteppedRun::new(&sc, it, Instant::now()).unwrap();
            while !stepped.done(&sc) {
                stepped.step(&sc).unwrap();
            }
            let settled = stepped.finish(&sc);
            assert_eq!(deferred.history.probes.len(), 1);
            assert!(deferred.stats[0].loss_fraction > 0.0, "{left}: losses");
            assert_eq!(
                format!("{:?}", deferred.history),
                format!("{:?}", settled.history),
                "{left}"
            );
            assert_eq!(
                format!("{:?}", deferred.stats),
                format!("{:?}", settled.stats),
                "{left}"
            );
        }
    }
}
