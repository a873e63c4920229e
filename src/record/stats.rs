//! A carrier's contact statistics (MODEL §7), accumulated over every step:
//! P_l and its split at the supports, loss intervals, force statistics, the
//! re-contacts with their peaks and impulses, and which losses a resolution
//! artefact may explain.

use serde::Serialize;

use super::CarrierTrace;
use super::window::TimeAverage;
use super::zone::LossGeometry;
use crate::integrate::CarrierSample;
use crate::resolve::memory::{EVENT_BYTES, MAX_STORED_EVENTS, event_capacity};

/// Mean, standard deviation, min and max of the contact force, N.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct ForceStats {
    /// Mean, N.
    pub mean: f64,
    /// Standard deviation (population), N.
    pub std: f64,
    /// Minimum, N.
    pub min: f64,
    /// Maximum, N.
    pub max: f64,
}

/// The filtered contact force's statistics over the steps
/// (docs/output.md#filtered-force): the filter's band, [`ForceStats`] of
/// the filtered force and its statistical max and min.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct FilteredForce {
    /// The band's upper edge, Hz (the filter is −3 dB there).
    pub cutoff_hz: f64,
    /// Mean, N.
    pub mean: f64,
    /// Standard deviation (population), N.
    pub std: f64,
    /// Maximum, N.
    pub max: f64,
    /// Minimum, N.
    pub min: f64,
    /// The statistical maximum mean + 3σ, N (EN 50367's F_m + 3σ).
    pub statistical_max: f64,
    /// The statistical minimum mean − 3σ, N.
    pub statistical_min: f64,
}

/// Whether a [`ContactStats`] carries the filtered force's statistics.
#[derive(Debug, Clone, Copy, Serialize, PartialEq, Default)]
#[serde(untagged)]
pub enum Filtered {
    /// Not computed (not a run's summary): the key is left out.
    #[default]
    Absent,
    /// Not computable: the history keeps only every K-th step, or has no
    /// rows (`null`).
    Unavailable,
    /// The statistics.
    Stats(FilteredForce),
}

impl Filtered {
    /// True when the key is left out.
    pub fn is_absent(&self) -> bool {
        matches!(self, Filtered::Absent)
    }
}

/// The window a re-contact's impulse ∫λ dt is summed over, s, from the
/// re-contact step, bounces included. A rigid contact on the reference wire
/// relaxes over m/Z ≈ 2.5 ms (Z = 2·sqrt(T·ρA) ≈ 400 N·s/m, the string's
/// drive-point impedance, m = 1 kg). Measured on the reference case, this
/// impulse converges in Δt (changes of 0.01–0.6 % between the finest steps)
/// where the peak grows like Δt^−½ (`docs/contact_loss.md` §2).
pub const RECONTACT_WINDOW: f64 = 2e-3;

/// A re-contact's peak is the largest λ over its first this-many steps: the
/// rigid-impact spike sits in the first step or two.
pub(crate) const PEAK_STEPS: usize = 3;

/// The memory plan's count of one stored event ([`EVENT_BYTES`]: a loss
/// interval in x/L and in t, its class and a re-contact) is what these
/// types take: a change to them that the plan does not follow fails to
/// compile here.
const _: () = assert!(
    EVENT_BYTES
        == (2 * std::mem::size_of::<[f64; 2]>()
            + std::mem::size_of::<LossClass>()
            + std::mem::size_of::<Recontact>()) as u64
);

/// A re-contact after a loss at least this long starts a new event; a
/// shorter loss inside an event's window is a bounce of that event (the
/// number of bounces grows as Δt falls), and only losses at least this
/// long count in `loss_fraction_span_sustained` (there measured between
/// the located instants, here in whole steps). 0.2 ms = 2 steps at
/// Δt = 1e-4 s.
pub const MIN_LOSS_TIME: f64 = 2e-4;

/// Relative slack on [`MIN_LOSS_TIME`] for a loss's summed pieces: a loss
/// whose instants fall at step starts lasts a whole number of steps, and
/// one of exactly 0.2 ms (2 steps of 1e-4 s, 4 of 5e-5 s, …) sums to
/// within round-off either side of it (measured 2.00000000000089e-4 on the
/// reference scene); it counts.
const SUSTAINED_SLACK: f64 = 1e-9;

/// Relative slack on the window's end, so that round-off in summed steps
/// does not drop the step that ends exactly at the window.
const WINDOW_SLACK: f64 = 1e-9;

/// One re-contact: contact closing after being lost (bounces inside its
/// window belong to it; `docs/contact_loss.md` §2).
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct Recontact {
    /// Time of the first closed step, s.
    pub time: f64,
    /// x_m/L there.
    pub position: f64,
    /// Whether it lies in a support zone ([`LossGeometry`]).
    pub at_support: bool,
    /// How long the contact was lost before it, s (below [`MIN_LOSS_TIME`]:
    /// a short bounce rather than a separation).
    pub loss_before: f64,
    /// Closing speed Δv = −dg/dt over the last open step, m/s (null when
    /// the loss lasted one step).
    pub closing_speed: Option<f64>,
    /// Largest λ over its first `PEAK_STEPS` steps, N: grows like Δt^−½
    /// (an impact on a beam); not a number to quote.
    pub peak: f64,
    /// Contact impulse ∫λ dt over [`RECONTACT_WINDOW`] from the re-contact
    /// step, bounces included, N·s: what converges where the peak does not.
    pub impulse: f64,
    /// The part of the window the run covered, s (less than the window
    /// when the run ends inside it).
    pub window: f64,
    /// Re-contacts after shorter losses inside the window.
    pub bounces: usize,
}

/// Where a loss interval lies, and whether the run resolves it.
#[derive(Debug, Clone, Copy, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LossClass {
    /// In the span, resolved: part of the P_l to quote.
    Span,
    /// In the span, shorter than the run resolves: a likely artefact.
    Unresolved,
    /// Touching a support zone (the carrier's arrival or start).
    Support,
}

/// A carrier's contact statistics over the steps of a run.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ContactStats {
    /// P_l: the time with the contact open over the window [0, T] (MODEL
    /// §7): each loss from its instant located within its step to the
    /// re-contact's (`ContactAccumulator`), so that it does not move in
    /// whole steps as Δt changes.
    pub loss_fraction: f64,
    /// The part of P_l in the span, outside the support zones: the number
    /// to quote, with its h and Δt (the support part does not converge in
    /// Δt; the bounces after a re-contact add to this one as Δt falls).
    pub loss_fraction_span: f64,
    /// The part of P_l in the support zones (the carrier's arrival at a
    /// support; does not converge in Δt). Span + support = P_l.
    pub loss_fraction_support: f64,
    /// The part of `loss_fraction_span` from losses lasting at least
    /// [`MIN_LOSS_TIME`] (each from its located loss instant to its located
    /// re-contact): the bounces after a re-contact, whose number and total
    /// time grow as Δt falls, left out, so that it settles in Δt where
    /// `loss_fraction_span` keeps rising (docs/contact_loss.md §3).
    pub loss_fraction_span_sustained: f64,
    /// P_l as the source study counts it: the steps with the contact open
    /// over all steps (moves in whole steps as Δt changes).
    pub loss_fraction_steps: f64,
    /// Width z of the support zone at each held end, m ([`LossGeometry`]).
    pub support_zone: f64,
    /// Loss intervals as [x_start/L, x_end/L]: a lost step covers
    /// [x_{i−1}, x_i], and adjacent lost steps merge. At most
    /// `MAX_STORED_EVENTS` are listed.
    pub loss_intervals: Vec<[f64; 2]>,
    /// The same intervals in time, [t_start, t_end], s.
    pub loss_intervals_time: Vec<[f64; 2]>,
    /// What each listed interval is: `span`, `unresolved` (in the span,
    /// shorter than 3 steps or h/V) or `support`.
    pub loss_interval_class: Vec<LossClass>,
    /// Number of loss intervals (all of them, listed or not).
    pub loss_interval_count: usize,
    /// Loss intervals in the span shorter than the run resolves (fewer than
    /// 3 steps, or shorter than h/V): likely resolution artefacts.
    pub suspect_loss_intervals: usize,
    /// Their share of the steps (a part of `loss_fraction_span`).
    pub suspect_loss_fraction: f64,
    /// Re-contacts, with peak and impulse (at most `MAX_STORED_EVENTS`).
    pub recontacts: Vec<Recontact>,
    /// Number of re-contacts (all of them).
    pub recontact_count: usize,
    /// x_m/L where contact is first lost (null if never).
    pub first_loss_position: Option<f64>,
    /// Number of contact state changes (closed → open and open → closed).
    pub contact_switches: usize,
    /// Force statistics, N (λ = 0 counts where contact is lost): the mean
    /// and σ over the window [0, T] (`super::window`), the min and max over
    /// the steps.
    pub force: ForceStats,
    /// Statistics of the 0–20 Hz force (EN 50317/50318/50367 style), in a
    /// run's summary only (the filter is a study's: `report::Summary` fills
    /// it); absent elsewhere, and written `null` when the history does not
    /// hold every step (`output.record_every` > 1).
    #[serde(skip_serializing_if = "Filtered::is_absent")]
    pub force_filtered: Filtered,
    /// Largest |gap| while in contact, m (round-off for the `end` placement).
    pub max_gap_in_contact: f64,
    /// Largest penetration max(0, −g), m (round-off for Lagrange; ≈ λ/κ for penalty).
    pub max_penetration: f64,
    /// Smallest gap over the steps, m.
    pub min_gap: f64,
    /// Largest |g·λ| over the steps, N·m (complementarity residual; 0 for exact Signorini).
    pub max_gap_force_product: f64,
}

impl ContactStats {
    /// Statistics of one trace over `geometry` (the span and its support
    /// zones). The same numbers, bit for bit, as `ContactAccumulator` fed
    /// row by row. Rows beyond the shortest column are ignored.
    pub fn from_trace(t: &[f64], tr: &CarrierTrace, geometry: LossGeometry) -> Self {
        Self::from_trace_into(ContactAccumulator::new(geometry), t, tr)
    }

    /// [`ContactStats::from_trace`] into accumulator `acc` (its window's
    /// end set, say).
    pub(crate) fn from_trace_into(
        mut acc: ContactAccumulator,
        t: &[f64],
        tr: &CarrierTrace,
    ) -> Self {
        let n = [
            t.len(),
            tr.x.len(),
            tr.w.len(),
            tr.q.len(),
            tr.gap.len(),
            tr.force.len(),
            tr.in_contact.len(),
        ]
        .into_iter()
        .min()
        .unwrap_or(0);
        for i in 0..n {
            acc.push(
                t[i],
                &CarrierSample {
                    x: tr.x[i],
                    w: tr.w[i],
                    q: tr.q[i],
                    gap: tr.gap[i],
                    force: tr.force[i],
                    in_contact: tr.in_contact[i],
                },
            );
        }
        acc.finish()
    }
}

/// One carrier's contact statistics, accumulated a sample at a time over
/// every step, so that they do not depend on which rows the history keeps
/// (`output.record_every`). Row 0 (t = 0) is the initial state.
///
/// Every time statistic is over the window [0, T], T the scene's end time
/// ([`Self::with_window_end`]), whatever Δt (`super::window`): the force's
/// mean and σ are time averages (trapezoids, West's weighted update), and
/// P_l is a time. A loss starts where λ, extrapolated along its last two
/// closed rows, reaches 0 within the first open step; contact returns
/// where the gap, extrapolated along its last two open rows, closes within
/// the re-contact step (linear event location, as an ODE solver's). Where
/// the two rows are not there or do not head to zero (a loss after one
/// step, λ not falling), the step's start stands for the instant: the
/// step count's convention. The step count itself is kept
/// (`loss_fraction_steps`).
#[derive(Debug, Clone)]
pub(crate) struct ContactAccumulator {
    geometry: LossGeometry,
    length: f64,
    /// Samples seen (row 0 included).
    rows: usize,
    prev_contact: bool,
    prev_x: f64,
    prev_t: f64,
    /// The gap at the previous two rows (for the closing speed), m.
    prev_gap: [f64; 2],
    lost: usize,
    /// Lost steps in a support zone.
    /// (x, t) at the row before the first lost step of the open interval.
    open: Option<(f64, f64)>,
    /// Steps of the open interval, and whether one lay in a support zone.
    open_steps: usize,
    open_at_support: bool,
    intervals: Vec<[f64; 2]>,
    intervals_t: Vec<[f64; 2]>,
    classes: Vec<LossClass>,
    interval_count: usize,
    suspect_intervals: usize,
    suspect_steps: usize,
    recontacts: Vec<Recontact>,
    recontact_count: usize,
    /// The re-contact whose window is open, and its steps so far.
    window: Option<(Recontact, usize)>,
    switches: usize,
    max_gap: f64,
    min_gap: f64,
    max_gap_force: f64,
    min: f64,
    max: f64,
    /// Row 0's force, used only when no step follows it.
    force0: f64,
    /// The window's end T, s (NaN: the last row's time).
    window_end: f64,
    /// Row 0's time, s: the window's start.
    t_first: f64,
    /// The force's time average so far.
    force_time: TimeAverage,
    /// λ at the previous row and the one before, N.
    prev_force: [f64; 2],
    /// The time and contact state of the row before the previous one.
    prev2_t: f64,
    prev2_contact: bool,
    /// Time with the contact open, s, and its part in a support zone.
    lost_time: f64,
    lost_time_support: f64,
    /// The open loss's located time so far, s, and its part in the span.
    open_lost: f64,
    open_lost_span: f64,
    /// Time in span of the losses closed so far that lasted at least
    /// [`MIN_LOSS_TIME`], s.
    sustained_span: f64,
    /// Largest |w| over every row (row 0 included), m.
    max_abs_w: f64,
}

impl ContactAccumulator {
    /// Empty statistics over `geometry` (the span and its support zones).
    pub fn new(geometry: LossGeometry) -> Self {
        ContactAccumulator {
            geometry,
            length: geometry.length,
            rows: 0,
            prev_contact: false,
            prev_x: 0.0,
            prev_t: 0.0,
            prev_gap: [0.0; 2],
            lost: 0,
            open: None,
            open_steps: 0,
            open_at_support: false,
            intervals: Vec::new(),
            intervals_t: Vec::new(),
            classes: Vec::new(),
            interval_count: 0,
            suspect_intervals: 0,
            suspect_steps: 0,
            recontacts: Vec::new(),
            recontact_count: 0,
            window: None,
            switches: 0,
            max_gap: 0.0,
            min_gap: f64::INFINITY,
            max_gap_force: 0.0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            force0: 0.0,
            max_abs_w: 0.0,
            window_end: f64::NAN,
            t_first: 0.0,
            force_time: TimeAverage::default(),
            prev_force: [0.0; 2],
            prev2_t: 0.0,
            prev2_contact: false,
            lost_time: 0.0,
            lost_time_support: 0.0,
            open_lost: 0.0,
            open_lost_span: 0.0,
            sustained_span: 0.0,
        }
    }

    /// The same statistics over the window [t₀, `t_end`] (the scene's end
    /// time; the run's last row may fall short of it by less than a step).
    pub fn with_window_end(mut self, t_end: f64) -> Self {
        self.window_end = t_end;
        self
    }

    /// The instant within the step ending at `t` where contact was lost
    /// (struct docs): λ's line through the two closed rows before it, at 0.
    fn loss_instant(&self, t: f64) -> f64 {
        let t0 = self.prev_t;
        let [l2, l1] = self.prev_force;
        if self.rows >= 2 && self.prev2_contact && l2 > l1 && l1 >= 0.0 {
            return (t0 + l1 / (l2 - l1) * (t0 - self.prev2_t)).clamp(t0, t);
        }
        t0
    }

    /// The instant within the step ending at `t` where contact returned
    /// (struct docs): the gap's line through the two open rows before it,
    /// at 0.
    fn recontact_instant(&self, t: f64) -> f64 {
        let t0 = self.prev_t;
        let [g2, g1] = self.prev_gap;
        if self.rows >= 2 && !self.prev2_contact && g2 > g1 && g1 >= 0.0 {
            return (t0 + g1 / (g2 - g1) * (t0 - self.prev2_t)).clamp(t0, t);
        }
        t0
    }

    /// Add the step ending at `t` (contact `c`, position `x`)'s time with
    /// the contact open.
    fn add_lost_time(&mut self, t: f64, c: bool, x: f64) {
        let (piece, at) = match (self.prev_contact, c) {
            (true, true) => return,
            (false, false) => (t - self.prev_t, x),
            (true, false) => (t - self.loss_instant(t), x),
            (false, true) => (self.recontact_instant(t) - self.prev_t, self.prev_x),
        };
        self.add_open_piece(piece, at);
    }

    /// Add `piece` (s) of lost time, the carrier at `at` (m), to P_l, its
    /// support part and the open loss's own time.
    fn add_open_piece(&mut self, piece: f64, at: f64) {
        self.lost_time += piece;
        self.open_lost += piece;
        if self.geometry.in_support_zone(at) {
            self.lost_time_support += piece;
        } else {
            self.open_lost_span += piece;
        }
    }

    /// The open loss has ended (a re-contact, or the window's end): its
    /// time in span counts as sustained when the whole loss lasted at
    /// least [`MIN_LOSS_TIME`].
    fn end_loss(&mut self) {
        if self.open_lost >= MIN_LOSS_TIME * (1.0 - SUSTAINED_SLACK) {
            self.sustained_span += self.open_lost_span;
        }
        self.open_lost = 0.0;
        self.open_lost_span = 0.0;
    }

    /// Empty statistics with room for the events a run of `steps` steps can
    /// store ([`event_capacity`]), reserved now: the
    /// run allocates nothing for them while it steps, and holds no more
    /// than the memory estimate counts (a list grown by doubling holds up
    /// to twice its events).
    pub fn for_steps(geometry: LossGeometry, steps: usize) -> Self {
        let n = event_capacity(steps);
        let mut acc = Self::new(geometry);
        acc.intervals.reserve_exact(n);
        acc.intervals_t.reserve_exact(n);
        acc.classes.reserve_exact(n);
        acc.recontacts.reserve_exact(n);
        acc
    }

    /// Add the sample of the next row (row 0 first) at time `t`. Allocates
    /// only when a loss interval closes beyond the intervals' capacity
    /// (never for one made by [`Self::for_steps`] and fed that many steps).
    pub fn push(&mut self, t: f64, s: &CarrierSample) {
        self.max_abs_w = self.max_abs_w.max(s.w.abs());
        if self.rows == 0 {
            self.force0 = s.force;
            self.t_first = t;
        } else {
            let c = s.in_contact;
            if c != self.prev_contact {
                self.switches += 1;
            }
            let dt = t - self.prev_t;
            self.force_time.add_step(self.prev_force[1], s.force, dt);
            self.add_lost_time(t, c, s.x);
            if c && !self.prev_contact {
                self.end_loss();
            }
            if c && self.open.is_some() {
                self.recontact(t, dt, s);
            }
            if let Some((w, steps)) = &mut self.window {
                if w.window + dt <= RECONTACT_WINDOW * (1.0 + WINDOW_SLACK) {
                    w.window += dt;
                    w.impulse += s.force * dt;
                    *steps += 1;
                    if *steps <= PEAK_STEPS && c {
                        w.peak = w.peak.max(s.force);
                    }
                } else {
                    self.close_window();
                }
            }
            if c {
                self.max_gap = self.max_gap.max(s.gap.abs());
            } else {
                self.lost += 1;
                let at_support = self.geometry.in_support_zone(s.x);
                if self.open.is_none() {
                    self.open = Some((self.prev_x, self.prev_t));
                    self.open_steps = 0;
                    self.open_at_support = false;
                }
                self.open_steps += 1;
                self.open_at_support |= at_support;
            }
            self.min_gap = self.min_gap.min(s.gap);
            self.max_gap_force = self.max_gap_force.max((s.gap * s.force).abs());
            let f = s.force;
            self.min = self.min.min(f);
            self.max = self.max.max(f);
        }
        self.prev2_contact = self.prev_contact;
        self.prev2_t = self.prev_t;
        self.prev_contact = s.in_contact;
        self.prev_x = s.x;
        self.prev_t = t;
        self.prev_gap = [self.prev_gap[1], s.gap];
        self.prev_force = [self.prev_force[1], s.force];
        self.rows += 1;
    }

    /// Store the open loss interval (ending at the previous row) and judge
    /// whether the run resolves it.
    fn close_interval(&mut self) {
        let Some((x0, t0)) = self.open.take() else {
            return;
        };
        self.interval_count += 1;
        let class = if self.open_at_support {
            LossClass::Support
        } else if self.geometry.unresolved(self.open_steps, self.prev_t - t0) {
            self.suspect_intervals += 1;
            self.suspect_steps += self.open_steps;
            LossClass::Unresolved
        } else {
            LossClass::Span
        };
        if self.intervals.len() < MAX_STORED_EVENTS {
            self.intervals
                .push([x0 / self.length, self.prev_x / self.length]);
            self.intervals_t.push([t0, self.prev_t]);
            self.classes.push(class);
        }
    }

    /// Contact closes at row time `t` (step `dt`) after the open interval:
    /// a bounce of the open event, or a new event.
    fn recontact(&mut self, t: f64, dt: f64, s: &CarrierSample) {
        let Some((_, t0)) = self.open else {
            return;
        };
        let loss_before = self.prev_t - t0;
        let open_steps = self.open_steps;
        self.close_interval();
        if let Some((w, _)) = &mut self.window
            && loss_before < MIN_LOSS_TIME
        {
            w.bounces += 1;
            return;
        }
        self.close_window();
        self.window = Some((
            Recontact {
                time: t,
                position: s.x / self.length,
                at_support: self.geometry.in_support_zone(s.x),
                loss_before,
                closing_speed: (open_steps >= 2 && dt > 0.0)
                    .then(|| -(self.prev_gap[1] - self.prev_gap[0]) / dt),
                peak: f64::NEG_INFINITY,
                impulse: 0.0,
                window: 0.0,
                bounces: 0,
            },
            0,
        ));
    }

    /// Store the re-contact whose window is open.
    fn close_window(&mut self) {
        if let Some((w, _)) = self.window.take() {
            self.recontact_count += 1;
            if self.recontacts.len() < MAX_STORED_EVENTS {
                self.recontacts.push(w);
            }
        }
    }

    /// Largest |w| seen (row 0 included), m.
    pub fn max_abs_w(&self) -> f64 {
        self.max_abs_w
    }

    /// The statistics of every sample pushed.
    pub fn finish(mut self) -> ContactStats {
        self.close_interval();
        self.close_window();
        // give back the room reserved for events that did not happen (a
        // study may keep many runs' statistics)
        self.intervals.shrink_to_fit();
        self.intervals_t.shrink_to_fit();
        self.classes.shrink_to_fit();
        self.recontacts.shrink_to_fit();
        let steps = self.rows.saturating_sub(1);
        let per_step = 1.0 / steps.max(1) as f64;
        // the window's end: the last row's step carried on to T (less
        // than a step), the contact as it last was
        let t_end = if self.window_end.is_finite() {
            self.window_end.max(self.prev_t)
        } else {
            self.prev_t
        };
        let rest = t_end - self.prev_t;
        if steps > 0 && rest > 0.0 {
            let [f2, f1] = self.prev_force;
            let dt = self.prev_t - self.prev2_t;
            let at_end = if dt > 0.0 {
                f1 + rest / dt * (f1 - f2)
            } else {
                f1
            };
            self.force_time.add_step(f1, at_end, rest);
            if !self.prev_contact {
                self.add_open_piece(rest, self.prev_x);
            }
        }
        // a loss still open at the window's end, by its time within it
        self.end_loss();
        let window = t_end - self.t_first;
        let per_time = if window > 0.0 { 1.0 / window } else { 0.0 };
        let span_time = self.lost_time - self.lost_time_support;
        let min_gap = if self.min_gap.is_finite() {
            self.min_gap
        } else {
            0.0
        };
        let force = if steps == 0 {
            // no step: the initial state's force alone (or nothing)
            let f = if self.rows == 0 { 0.0 } else { self.force0 };
            let (min, max) = if self.rows == 0 {
                (f64::INFINITY, f64::NEG_INFINITY)
            } else {
                (f, f)
            };
            ForceStats {
                mean: f,
                std: 0.0,
                min,
                max,
            }
        } else {
            ForceStats {
                mean: self.force_time.mean(),
                std: self.force_time.std(),
                min: self.min,
                max: self.max,
            }
        };
        ContactStats {
            loss_fraction: self.lost_time * per_time,
            loss_fraction_span: span_time * per_time,
            loss_fraction_support: self.lost_time_support * per_time,
            // a sum of its losses' span parts: at most the span part,
            // which is P_l less the support part, up to round-off
            loss_fraction_span_sustained: self.sustained_span.min(span_time) * per_time,
            loss_fraction_steps: self.lost as f64 * per_step,
            support_zone: self.geometry.support_zone,
            first_loss_position: self.intervals.first().map(|iv| iv[0]),
            loss_intervals: self.intervals,
            loss_intervals_time: self.intervals_t,
            loss_interval_class: self.classes,
            loss_interval_count: self.interval_count,
            suspect_loss_intervals: self.suspect_intervals,
            suspect_loss_fraction: self.suspect_steps as f64 * per_step,
            recontacts: self.recontacts,
            recontact_count: self.recontact_count,
            contact_switches: self.switches,
            force,
            max_gap_in_contact: self.max_gap,
            max_penetration: (-min_gap).max(0.0),
            min_gap,
            max_gap_force_product: self.max_gap_force,
            force_filtered: Filtered::Absent,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::CarrierTrace;

    fn trace(contact: &[bool]) -> (Vec<f64>, CarrierTrace) {
        let n = contact.len();
        let t: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let tr = CarrierTrace {
            x: t.clone(),
            w: vec![0.0; n],
            q: vec![0.0; n],
            gap: vec![0.0; n],
            force: contact.iter().map(|&c| if c { 2.0 } else { 0.0 }).collect(),
            in_contact: contact.to_vec(),
            force_filtered: vec![],
        };
        (t, tr)
    }

    #[test]
    fn loss_fraction_and_intervals_agree() {
        // steps 1..=8; lost at steps 3,4 and 8
        let (t, tr) = trace(&[true, true, true, false, false, true, true, true, false]);
        let s = ContactStats::from_trace(&t, &tr, LossGeometry::span_only(8.0));
        assert_eq!(s.loss_fraction, 3.0 / 8.0);
        assert_eq!(
            s.loss_intervals,
            vec![[2.0 / 8.0, 4.0 / 8.0], [7.0 / 8.0, 1.0]]
        );
        let measure: f64 = s.loss_intervals_time.iter().map(|iv| iv[1] - iv[0]).sum();
        assert_eq!(measure / 8.0, s.loss_fraction);
        assert_eq!(s.contact_switches, 3);
        assert_eq!(s.first_loss_position, Some(0.25));
        assert_eq!(s.force.min, 0.0);
        assert_eq!(s.force.max, 2.0);
    }

    /// `trace` at steps of 0.1 ms, the carrier moving 1 m a step.
    fn fast_trace(contact: &[bool]) -> (Vec<f64>, CarrierTrace) {
        let (t, tr) = trace(contact);
        (t.iter().map(|t| t * 1e-4).collect(), tr)
    }

    /// Round-off of ten summed steps of 0.1 ms, relative to the window.
    const SUMMED_STEPS: f64 = 1e-12;

    /// Only losses lasting at least `MIN_LOSS_TIME` count as sustained: a
    /// one-step bounce (0.1 ms) does not, a three-step loss (0.3 ms) does,
    /// and so does one still open at the window's end once it has lasted
    /// that long; their part in a support zone counts in neither span sum.
    #[test]
    fn sustained_losses_leave_out_the_bounces() {
        let (f, o) = (false, true);
        // lost: row 2 (a bounce), rows 4–6 (0.3 ms), row 9 (open at the end)
        let (t, tr) = fast_trace(&[o, o, f, o, f, f, f, o, o, f]);
        let s = ContactStats::from_trace(&t, &tr, LossGeometry::span_only(9.0));
        assert!((s.loss_fraction - 5.0 / 9.0).abs() < SUMMED_STEPS);
        assert!((s.loss_fraction_span_sustained - 3.0 / 9.0).abs() < SUMMED_STEPS);
        // the last loss lasts 3 steps too: it counts
        let (t, tr) = fast_trace(&[o, o, f, o, f, f, f, o, f, f, f]);
        let s = ContactStats::from_trace(&t, &tr, LossGeometry::span_only(10.0));
        assert!((s.loss_fraction_span_sustained - 6.0 / 10.0).abs() < SUMMED_STEPS);
        // a support zone of 1.5 m at the held left end: the sustained
        // loss's steps at x = 1 (in the zone) count at the support only
        let zoned = LossGeometry {
            support_zone: 1.5,
            held: (true, false),
            ..LossGeometry::span_only(10.0)
        };
        let (t, tr) = fast_trace(&[o, f, f, f, o, o, o, o, o, o, o]);
        let s = ContactStats::from_trace(&t, &tr, zoned);
        assert!((s.loss_fraction - 3.0 / 10.0).abs() < SUMMED_STEPS);
        assert!((s.loss_fraction_support - 1.0 / 10.0).abs() < SUMMED_STEPS);
        assert!((s.loss_fraction_span_sustained - 2.0 / 10.0).abs() < SUMMED_STEPS);
        assert!(s.loss_fraction_span_sustained <= s.loss_fraction_span);
    }

    /// A trace at steps of 0.1 ms with λ and the gap given row by row, so
    /// that the located instants fall within their steps.
    fn located_trace(force: &[f64], gap: &[f64]) -> (Vec<f64>, CarrierTrace) {
        let contact: Vec<bool> = force.iter().map(|&f| f > 0.0).collect();
        let (t, mut tr) = fast_trace(&contact);
        tr.force = force.to_vec();
        tr.gap = gap.to_vec();
        (t, tr)
    }

    /// The pieces of a loss are its located parts: λ falling 3 → 1 N puts
    /// the loss half a step into its first open step, and the gap closing
    /// 5 → 3 → 1 mm puts the re-contact half a step into its step. One open
    /// row (no two open rows to locate the re-contact on: the step's start)
    /// makes a loss of half a step, a bounce; three make 0.5 + 1 + 1 + 0.5
    /// steps, 0.3 ms, sustained; and a loss open at the window's end, 0.8
    /// of a step after the last row, counts that part too (1.5 + 0.8 steps,
    /// where the rows alone hold 1.5).
    #[test]
    fn a_sustained_loss_is_timed_by_its_located_instants() {
        let close = |s: &ContactStats, want: f64| {
            assert!(
                (s.loss_fraction_span_sustained - want).abs() < SUMMED_STEPS,
                "{} against {want}",
                s.loss_fraction_span_sustained
            )
        };
        let g = |mm: f64| mm * 1e-3;
        let (t, tr) = located_trace(&[4.0, 3.0, 1.0, 0.0, 2.0], &[0.0, 0.0, 0.0, g(1.0), 0.0]);
        let s = ContactStats::from_trace(&t, &tr, LossGeometry::span_only(4.0));
        assert!(
            (s.loss_fraction - 0.5 / 4.0).abs() < SUMMED_STEPS,
            "{}",
            s.loss_fraction
        );
        close(&s, 0.0);
        let (t, tr) = located_trace(
            &[4.0, 3.0, 1.0, 0.0, 0.0, 0.0, 2.0],
            &[0.0, 0.0, 0.0, g(5.0), g(3.0), g(1.0), 0.0],
        );
        let s = ContactStats::from_trace(&t, &tr, LossGeometry::span_only(6.0));
        assert!((s.loss_fraction - 3.0 / 6.0).abs() < SUMMED_STEPS);
        close(&s, 3.0 / 6.0);
        let (t, tr) = located_trace(&[4.0, 3.0, 1.0, 0.0, 0.0], &[0.0, 0.0, 0.0, g(1.0), g(2.0)]);
        let acc = ContactAccumulator::new(LossGeometry::span_only(4.8)).with_window_end(4.8e-4);
        close(&ContactStats::from_trace_into(acc, &t, &tr), 2.3 / 4.8);
        // a loss of exactly two steps of 0.1 ms (instants at step starts)
        // is 0.2 ms: it counts, whatever the round-off of its sum
        let (f, o) = (false, true);
        let (t, tr) = fast_trace(&[o, o, f, f, o, o]);
        let s = ContactStats::from_trace(&t, &tr, LossGeometry::span_only(5.0));
        close(&s, 2.0 / 5.0);
    }

    #[test]
    fn the_reserved_events_hold_the_most_a_run_can_store() {
        // contact lost on every other step (row 0 in contact, or not): the
        // most intervals and re-contacts `steps` steps can hold, which the
        // room reserved up front (and the memory estimate) must take without
        // growing; past MAX_STORED_EVENTS the lists stop growing
        for steps in (1..=9).chain([2 * MAX_STORED_EVENTS + 7]) {
            for lost_first in [true, false] {
                let mut acc = ContactAccumulator::for_steps(LossGeometry::span_only(1.0), steps);
                let room = [
                    acc.intervals.capacity(),
                    acc.intervals_t.capacity(),
                    acc.classes.capacity(),
                    acc.recontacts.capacity(),
                ];
                assert!(room.iter().all(|&r| r == event_capacity(steps)));
                for row in 0..=steps {
                    let c = (row % 2 == 1) != lost_first;
                    let sample = CarrierSample {
                        x: row as f64 / steps as f64,
                        w: 0.0,
                        q: 0.0,
                        gap: 0.0,
                        force: if c { 1.0 } else { 0.0 },
                        in_contact: c,
                    };
                    // far apart: every re-contact its own (no bounces)
                    acc.push(row as f64, &sample);
                }
                let [i, it, c, r] = room;
                assert_eq!(acc.intervals.capacity(), i, "{steps} steps");
                assert_eq!(acc.intervals_t.capacity(), it);
                assert_eq!(acc.classes.capacity(), c);
                assert_eq!(acc.recontacts.capacity(), r);
                let s = acc.finish();
                if lost_first {
                    // steps 1, 3, 5, …: ⌈steps/2⌉ intervals, the bound met
                    assert_eq!(s.loss_interval_count, steps.div_ceil(2), "{steps} steps");
                    assert_eq!(
                        s.loss_intervals.len(),
                        steps.div_ceil(2).min(MAX_STORED_EVENTS)
                    );
                }
            }
        }
    }

    #[test]
    fn no_loss_gives_no_interval() {
        let (t, tr) = trace(&[true; 5]);
        let s = ContactStats::from_trace(&t, &tr, LossGeometry::span_only(4.0));
        assert_eq!(s.loss_fraction, 0.0);
        assert!(s.loss_intervals.is_empty());
        assert_eq!(s.first_loss_position, None);
        assert_eq!(s.force.std, 0.0);
    }
}
