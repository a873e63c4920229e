//! A ladder's measurements: each level's error against the exact solution
//! on the coarsest level's time grid, the dominance run, and the exact
//! solution's modal tail.

use super::case::{Ladder, Space, Variable};
use super::job::Job;
use super::level::level;
use crate::error::Result;
use crate::integrate::central_difference_limit;
use crate::resolve::Resolved;
use crate::run::{RunOutput, run_with};
use crate::scene::{CarrierKind, Scene};
use crate::study::grid::{Reach, nest};
use crate::study::reference::{Exact, exact};
/// Which times an error is the max over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Window {
    /// Every recorded time t > 0.
    Whole = 0,
    /// t > [`super::START_WINDOW`].
    AfterStart = 1,
    /// Before a prescribed loss's window ([`crate::manufactured::Manufactured::loss_window`]);
    /// the whole run without one.
    BeforeLoss = 2,
    /// After the start and before the loss: the share the loss makes of an
    /// error judged after the start (the start's ringing would hide it in
    /// the whole run's max).
    AfterStartBeforeLoss = 3,
}

/// How many [`Window`]s a run's errors are measured over.
pub(super) const WINDOWS: usize = 4;

/// A ladder's errors over one [`Window`].
#[derive(Debug, Clone, Default)]
pub(super) struct View {
    /// Displacement and force errors per level.
    pub(super) displacement: Vec<f64>,
    pub(super) force: Vec<f64>,
    /// The dominance run's errors (NaN when it could not run).
    pub(super) refined: (f64, f64),
    /// Penalty only: the finest level's errors with κ stiffened
    /// [`super::PENALTY_STIFFEN`] times; `None` where the law has no
    /// compliance to measure, NaN where the run that measures it failed.
    pub(super) stiffened: Option<(f64, f64)>,
}

/// A ladder's measurements.
pub(super) struct Measured {
    /// The refined variable per level.
    pub(super) levels: Vec<f64>,
    /// The errors over each [`Window`], indexed by it.
    pub(super) views: [View; WINDOWS],
    /// The exact solution's largest displacement and force.
    pub(super) scale: (f64, f64),
    /// Loss intervals of each level's run.
    pub(super) loss_intervals: Vec<usize>,
    pub(super) omega_max_dt: f64,
    pub(super) runs: usize,
    /// A run that failed, and why.
    pub(super) failed: Option<String>,
    /// The exact solution's modal tail per J level (J ladders).
    pub(super) tail: Option<Vec<f64>>,
    /// A penalty ladder in h, Δt or J whose levels are the κ → ∞ values
    /// ([`richardson`]): its `stiffened` view is then the extrapolation's
    /// check ([`PENALTY_CHECK`]), not a stiffer run.
    pub(super) extrapolated: bool,
}

/// The κ of the extrapolation's check, times the level's: the κ → ∞ value
/// extrapolated from κ and 4κ differs from the one from κ and 16κ by three
/// times the latter's remainder where the compliance's error is c₁/κ +
/// c₂/κ² (−c₂/(16κ²) against −3c₂/(16κ²)), so the check's difference
/// bounds the remainder three times over.
pub(crate) const PENALTY_CHECK: f64 = 4.0;

/// The κ → ∞ value of a penalty run from runs at κ (`a`) and `factor`·κ
/// (`b`, same steps and probes): Richardson in 1/κ, x∞ = (f·x_b − x_a)/(f − 1)
/// row by row, for every carrier's w, q and force and every probe (the
/// compliance's error ∝ 1/κ removed, its c₂/κ² part left at −c₂/(f κ²)).
/// The contact statistics stay `a`'s (the run at the scene's κ).
fn richardson(a: &RunOutput, mut b: RunOutput, factor: f64) -> RunOutput {
    let mix = |xb: &mut [f64], xa: &[f64]| {
        for (y, x) in xb.iter_mut().zip(xa) {
            *y = (factor * *y - x) / (factor - 1.0);
        }
    };
    for (cb, ca) in b.history.carriers.iter_mut().zip(&a.history.carriers) {
        mix(&mut cb.w, &ca.w);
        mix(&mut cb.q, &ca.q);
        mix(&mut cb.force, &ca.force);
    }
    for ((_, pb), (_, pa)) in b.history.probes.iter_mut().zip(&a.history.probes) {
        mix(pb, pa);
    }
    b.stats = a.stats.clone();
    b
}

/// The per-level value of the refined variable, and the level's (N, Δt, J).
pub(super) fn level_params(l: &Ladder, k: usize) -> (f64, usize, f64, usize) {
    let f = 1usize << k;
    match l.variable {
        Variable::H => (f64::NAN, l.elements * f, l.dt, l.modes),
        Variable::Dt => (l.dt / f as f64, l.elements, l.dt / f as f64, l.modes),
        Variable::J => ((l.modes * f) as f64, l.elements, l.dt, l.modes * f),
        Variable::Kappa => (f64::NAN, l.elements, l.dt, l.modes),
    }
}

/// The penalty's relative stiffness ρ of `scene` (κ = ρ/W; MODEL §6), or
/// `None` when it gives an absolute κ.
fn penalty_relative(scene: &Scene) -> Option<f64> {
    let p = &scene.contact.penalty;
    match (p.stiffness, p.relative) {
        (Some(_), _) => None,
        (None, r) => Some(r.unwrap_or(crate::scene::DEFAULT_PENALTY_RELATIVE)),
    }
}

/// `scene` with its penalty stiffened `factor` times (κ or ρ).
fn stiffened(scene: &Scene, factor: f64) -> Scene {
    let mut s = scene.clone();
    let p = &mut s.contact.penalty;
    match (p.stiffness, penalty_relative(scene)) {
        (Some(k), _) => p.stiffness = Some(k * factor),
        (None, Some(r)) => p.relative = Some(r * factor),
        (None, None) => {}
    }
    s
}

/// A κ ladder's first level: the scene's penalty times this (ρ = 250 for
/// the default 1000), so that its finest level, 8 × that, leaves the fixed
/// Δt and mesh a small share (at 8000 they made 29 % of the finest force
/// error of generalized-α, measured).
pub(crate) const PENALTY_LADDER_START: f64 = 0.25;

/// `scene` at level `k` of a κ ladder: ρ₀·2^k (the identity otherwise).
fn at_level<'a>(scene: &'a Scene, ladder: &Ladder, k: usize) -> std::borrow::Cow<'a, Scene> {
    if ladder.variable == Variable::Kappa {
        std::borrow::Cow::Owned(stiffened(
            scene,
            PENALTY_LADDER_START * (1usize << k) as f64,
        ))
    } else {
        std::borrow::Cow::Borrowed(scene)
    }
}

/// Run a ladder and its dominance run; errors against the exact solution.
pub(super) fn measure(scene: &Scene, j: &Job, ladder: &Ladder) -> Measured {
    let blank = View {
        refined: (f64::NAN, f64::NAN),
        stiffened: None,
        ..View::default()
    };
    let mut m = Measured {
        levels: Vec::new(),
        views: [blank.clone(), blank.clone(), blank.clone(), blank],
        scale: (0.0, 0.0),
        loss_intervals: Vec::new(),
        omega_max_dt: f64::NAN,
        runs: 0,
        failed: None,
        tail: None,
        extrapolated: false,
    };
    let owned;
    let scene = match ladder.end {
        None => scene,
        Some(t) => {
            let mut s = scene.clone();
            s.time.end = crate::scene::EndTime::Seconds(t);
            owned = s;
            &owned
        }
    };
    let mut scenes = Vec::with_capacity(ladder.levels);
    for k in 0..ladder.levels {
        let (_, n, dt, jm) = level_params(ladder, k);
        match level(&at_level(scene, ladder, k), j.space, n, dt, jm) {
            Ok(s) => scenes.push(s),
            Err(e) => {
                m.failed = Some(e.to_string());
                return m;
            }
        }
    }
    let finest = scenes.last().expect("a ladder has levels");
    let ex = match exact(finest) {
        Ok(Some(e)) => e,
        Ok(None) => {
            m.failed = Some("the case's scene declares no exact reference".into());
            return m;
        }
        Err(e) => {
            m.failed = Some(e.to_string());
            return m;
        }
    };
    m.omega_max_dt = central_difference_limit(finest).map_or(f64::NAN, |l| l.omega_max * finest.dt);
    let coarse = (scenes[0].steps, scenes[0].dt);
    // a penalty ladder in h, Δt or J judges the κ → ∞ value: each level run
    // at κ and PENALTY_STIFFEN·κ, extrapolated in 1/κ ([`richardson`])
    // (not an explicit method: its stable step falls as 1/√κ, so at a
    // fixed Δt it has no κ → ∞ value; its κ × 16 rerun measures the share)
    m.extrapolated = ladder.variable != Variable::Kappa
        && finest.contact.formulation == crate::scene::Formulation::Penalty
        && !matches!(
            finest.method.scheme,
            crate::scene::Scheme::CentralDifference
        );
    let stiff_run = |base: &Scene, factor: f64, n: usize, dt: f64, jm: usize| {
        level(&stiffened(base, factor), j.space, n, dt, jm)
            .and_then(|sc| run_with(&sc, j.factory, &mut |_, _| {}))
    };
    let mut finest_plain = None;
    for (k, sc) in scenes.iter().enumerate() {
        m.levels.push(match ladder.variable {
            Variable::H => sc.resolution(),
            Variable::Dt => sc.dt,
            Variable::J => sc.discretization.modes().unwrap_or(0) as f64,
            Variable::Kappa => 1.0 / sc.contact.penalty.relative.unwrap_or(f64::NAN),
        });
        let out = match run_with(sc, j.factory, &mut |_, _| {}) {
            Ok(o) => o,
            Err(e) => {
                m.failed = Some(format!("level {k}: {e}"));
                return m;
            }
        };
        m.runs += 1;
        m.loss_intervals
            .push(out.stats.first().map_or(0, |s| s.loss_interval_count));
        let out = if m.extrapolated {
            let (_, n, dt, jm) = level_params(ladder, k);
            let stiff = match stiff_run(
                &at_level(scene, ladder, k),
                super::PENALTY_STIFFEN,
                n,
                dt,
                jm,
            ) {
                Ok(o) => o,
                Err(e) => {
                    m.failed = Some(format!(
                        "level {k} with κ × {} (the κ → ∞ extrapolation): {e}",
                        super::PENALTY_STIFFEN
                    ));
                    return m;
                }
            };
            m.runs += 1;
            let x = richardson(&out, stiff, super::PENALTY_STIFFEN);
            if k + 1 == ladder.levels {
                finest_plain = Some(out);
            }
            x
        } else {
            out
        };
        let Ok(stride) = nest(coarse, (sc.steps, sc.dt), Reach::SameEnd) else {
            m.failed = Some("the levels' time grids do not nest".into());
            return m;
        };
        let e = errors(sc, &out, &ex, stride, coarse.0);
        for (v, (d, f)) in m.views.iter_mut().zip(e.d.iter().zip(&e.f)) {
            v.displacement.push(*d);
            v.force.push(*f);
        }
        m.scale = e.scale;
    }
    if ladder.variable == Variable::J
        && let Some(mf) = &finest.manufactured
    {
        m.tail = modal_tail(&scenes, mf, j.space).ok();
    }
    // penalty: the finest level with κ stiffened, for the compliance's
    // share; an extrapolated ladder's check instead: the κ → ∞ value from κ
    // and PENALTY_CHECK·κ, whose difference from the ladder's bounds the
    // extrapolation's remainder ([`PENALTY_CHECK`])
    let last = &at_level(scene, ladder, ladder.levels - 1);
    if finest.contact.formulation == crate::scene::Formulation::Penalty {
        // measured from here on: NaN until its run succeeds
        for v in &mut m.views {
            v.stiffened = Some((f64::NAN, f64::NAN));
        }
        let (_, n, dt, jm) = level_params(ladder, ladder.levels - 1);
        let checked = match &finest_plain {
            Some(plain) => stiff_run(last, PENALTY_CHECK, n, dt, jm)
                .map(|o| richardson(plain, o, PENALTY_CHECK)),
            None => stiff_run(last, super::PENALTY_STIFFEN, n, dt, jm),
        };
        if let Ok(out) = checked
            && let Ok(stride) = nest(coarse, (finest.steps, finest.dt), Reach::SameEnd)
        {
            m.runs += 1;
            let e = errors(finest, &out, &ex, stride, coarse.0);
            for (v, (d, f)) in m.views.iter_mut().zip(e.d.iter().zip(&e.f)) {
                v.stiffened = Some((*d, *f));
            }
        }
    }
    if ladder.fixed_exact {
        for v in &mut m.views {
            v.refined = (
                v.displacement[ladder.levels - 1],
                v.force[ladder.levels - 1],
            );
        }
        return m;
    }
    // the dominance run: the finest level with the fixed variables refined
    // (a modal basis's FE mesh stays in a Δt ladder: its error is the
    // hermite ladder's at that N, which that ladder shows)
    let (_, n, dt, jm) = level_params(ladder, ladder.levels - 1);
    // a modal basis with every mode of its mesh is the element model in
    // its eigenbasis: its fixed variable is then the mesh (N×2, every mode)
    let all_modes =
        |n: usize| level(last, Space::Hermite, n, dt, 0).map_or(jm, |s| s.beam_unknowns());
    let (n2, dt2, j2) = match ladder.variable {
        Variable::Dt => match j.space {
            Space::Galerkin => (n, dt, jm * 2),
            Space::Modal if jm >= finest.beam_unknowns() => (n * 2, dt, all_modes(n * 2)),
            Space::Modal => (n, dt, (jm * 2).min(finest.beam_unknowns())),
            _ => (n * 2, dt, jm),
        },
        // a modal basis's FE mesh stays in its J ladder too: refining it
        // makes the dense eigenvectors less accurate (ε·ω_max²/Δω²), which
        // docs/verification.md shows on its own
        Variable::H | Variable::J => (n, dt / 2.0, jm),
        // a κ ladder: both fixed variables at once, Δt/2 and N×2 (J×2)
        Variable::Kappa => match j.space {
            Space::Galerkin => (n, dt / 2.0, jm * 2),
            Space::Modal => (n, dt / 2.0, (jm * 2).min(finest.beam_unknowns())),
            _ => (n * 2, dt / 2.0, jm),
        },
    };
    // an extrapolated ladder's dominance run is extrapolated too
    let refined_run = |sc: &Resolved| -> Result<RunOutput> {
        let out = run_with(sc, j.factory, &mut |_, _| {})?;
        if m.extrapolated {
            let stiff = stiff_run(last, super::PENALTY_STIFFEN, n2, dt2, j2)?;
            Ok(richardson(&out, stiff, super::PENALTY_STIFFEN))
        } else {
            Ok(out)
        }
    };
    if let Ok(sc) = level(last, j.space, n2, dt2, j2)
        && let Ok(out) = refined_run(&sc)
        && let Ok(stride) = nest(coarse, (sc.steps, sc.dt), Reach::SameEnd)
    {
        m.runs += if m.extrapolated { 2 } else { 1 };
        let e = errors(&sc, &out, &ex, stride, coarse.0);
        for (v, (d, f)) in m.views.iter_mut().zip(e.d.iter().zip(&e.f)) {
            v.refined = (*d, *f);
        }
    }
    m
}

/// Times at which a modal tail is sampled (evenly over the run, t > 0).
pub(crate) const TAIL_TIMES: usize = 8;

/// The exact solution's own modal tail at each J level of a ladder: the
/// largest |v* − Σ_{j ≤ J} c_j φ_j| over the probes and the carrier's
/// position at [`TAIL_TIMES`] times, with c_j = ∫ρA φ_j v* dx the exact
/// modal coefficients (galerkin: the exact modes, by their own quadrature;
/// modal: the FE modes of the level's mesh, applied to the nodal
/// interpolant of v*, so the FE interpolation error is left out; with a
/// `[messenger]` the modes of the two-line model, applied to both lines'
/// interpolants, at the probes of each line).
pub(super) fn modal_tail(
    scenes: &[Resolved],
    mf: &crate::manufactured::Manufactured,
    space: Space,
) -> Result<Vec<f64>> {
    let finest = scenes.last().expect("levels");
    let js: Vec<usize> = scenes
        .iter()
        .map(|s| s.discretization.modes().unwrap_or(0))
        .collect();
    let jmax = *js.last().unwrap_or(&0);
    let t_end = finest.steps as f64 * finest.dt;
    let times: Vec<f64> = (1..=TAIL_TIMES)
        .map(|k| t_end * k as f64 / TAIL_TIMES as f64)
        .collect();
    // the probes and the carriers' positions, each with whether it lies on
    // the messenger
    let points = |t: f64| -> Vec<(f64, bool)> {
        let mut p: Vec<(f64, bool)> = finest
            .probes
            .iter()
            .enumerate()
            .map(|(k, (_, x))| {
                let wire = finest.scene.probes.get(k).and_then(|p| p.wire);
                (*x, wire == Some(crate::scene::Wire::Messenger))
            })
            .collect();
        p.extend((0..mf.carriers()).map(|c| (mf.position(c, t), false)));
        p
    };
    let mut tail = vec![0.0f64; js.len()];
    match space {
        Space::Galerkin => {
            let shapes = crate::analytic::ModeShapes::new(&finest.beam, jmax)?;
            let quad = shapes.quadrature(finest.beam.length / 400.0);
            let mut phi = vec![0.0; jmax];
            for &t in &times {
                let mut c = vec![0.0; jmax];
                for &(x, w) in &quad {
                    shapes.values_into(x, &mut phi);
                    let v = finest.beam.rho_a * mf.v(x, t) * w;
                    for (cj, p) in c.iter_mut().zip(&phi) {
                        *cj += v * p;
                    }
                }
                for (x, _) in points(t) {
                    shapes.values_into(x, &mut phi);
                    let exact = mf.v(x, t);
                    for (k, &j) in js.iter().enumerate() {
                        let sum: f64 = c[..j].iter().zip(&phi[..j]).map(|(a, b)| a * b).sum();
                        tail[k] = tail[k].max((exact - sum).abs());
                    }
                }
            }
        }
        Space::Modal => {
            use crate::model::beam::BeamModel;
            let mesh =
                crate::model::mesh::Mesh::new(finest.beam.length, finest.elements, finest.grading)?;
            let fe = BeamModel::on_mesh(&finest.beam, mesh);
            let pairs = crate::model::eigen::lowest_eigenpairs(&fe.mass, &fe.stiffness, jmax)?;
            let n = fe.n;
            for &t in &times {
                // the nodal interpolant d* of v*(·, t)
                let mut d = vec![0.0; n];
                let per_node = if finest.beam.is_string() { 1 } else { 2 };
                for node in 0..=fe.mesh.elements() {
                    let x = fe.mesh.node(node);
                    let f = mf.fields(x, t);
                    if let Some(i) = fe.dof_of[per_node * node] {
                        d[i] = f.v;
                    }
                    if per_node == 2
                        && let Some(i) = fe.dof_of[2 * node + 1]
                    {
                        d[i] = f.v_x;
                    }
                    // the messenger's nodes (eq. W1), v_m* and its slope
                    if let Some(&Some(i)) = fe.messenger_dof_of.get(per_node * node) {
                        d[i] = mf.v_m(x, t);
                    }
                    if per_node == 2
                        && let Some(&Some(i)) = fe.messenger_dof_of.get(2 * node + 1)
                    {
                        d[i] = mf.v_m_x(x, t);
                    }
                }
                let mut md = vec![0.0; n];
                fe.mass.mul_acc(&d, 1.0, &mut md);
                let c: Vec<f64> = (0..jmax)
                    .map(|j| pairs.shape(j).iter().zip(&md).map(|(a, b)| a * b).sum())
                    .collect();
                for (x, on_messenger) in points(t) {
                    let r = if on_messenger {
                        fe.messenger_point_vector(x)
                    } else {
                        fe.point_vector(x)
                    };
                    let full = r.dot(&d);
                    let modes: Vec<f64> = (0..jmax).map(|j| r.dot(pairs.shape(j))).collect();
                    for (k, &j) in js.iter().enumerate() {
                        let sum: f64 = c[..j].iter().zip(&modes[..j]).map(|(a, b)| a * b).sum();
                        tail[k] = tail[k].max((full - sum).abs());
                    }
                }
            }
        }
        _ => {}
    }
    Ok(tail)
}

/// A run's errors over each [`Window`] (indexed by it), and the exact
/// solution's largest values.
pub(super) struct Errors {
    /// Displacement errors, m.
    pub(super) d: [f64; WINDOWS],
    /// Force errors, N (NaN without a force reference).
    pub(super) f: [f64; WINDOWS],
    /// The exact solution's largest displacement and force over the run.
    pub(super) scale: (f64, f64),
}

/// Max errors over the coarse grid's rows 1 ..= `rows` of a run, over each
/// [`Window`]: the displacement (under carrier 0, at the probes on their
/// own wire, of its mass) and the force (at the time the multiplier acts);
/// and the exact solution's largest values there.
pub(super) fn errors(
    sc: &Resolved,
    out: &RunOutput,
    ex: &Exact,
    stride: usize,
    rows: usize,
) -> Errors {
    let h = &out.history;
    let c = &h.carriers[0];
    let lag = out.force_lag * sc.dt;
    let has_force =
        ex.force.is_some() && matches!(sc.carriers[0].kind, CarrierKind::MassSpring { .. });
    let loss_from = ex
        .manufactured
        .as_ref()
        .and_then(|m| m.loss_window())
        .map_or(f64::INFINITY, |(a, _)| a);
    let (mut ed, mut ef, mut sd, mut sf) = ([0.0f64; WINDOWS], [0.0f64; WINDOWS], 0.0f64, 0.0f64);
    let on_messenger = |p: usize| {
        sc.scene.probes.get(p).and_then(|p| p.wire) == Some(crate::scene::Wire::Messenger)
    };
    for k in 1..=rows {
        let i = k * stride;
        let t = h.t[i];
        let after = t > super::START_WINDOW;
        let within = [true, after, t < loss_from, after && t < loss_from];
        let w = (ex.w)(t);
        sd = sd.max(w.abs());
        let mut e = (c.w[i] - w).abs();
        if let Some(q) = &ex.mass {
            e = e.max((c.q[i] - q(t)).abs());
        }
        if let Some(field) = &ex.field {
            for (p, ((_, x), (_, col))) in sc.probes.iter().zip(&h.probes).enumerate() {
                // a messenger probe reads v_m* (`docs/lines.md` W1)
                let v = match (on_messenger(p), &ex.manufactured) {
                    (true, Some(m)) => m.v_m(*x, t),
                    _ => field(*x, t),
                };
                sd = sd.max(v.abs());
                e = e.max((col[i] - v).abs());
            }
        }
        let mut g = f64::NAN;
        if has_force && let Some(f) = &ex.force {
            let l = f(t - lag);
            sf = sf.max(l.abs());
            g = (c.force[i] - l).abs();
        }
        for w in 0..WINDOWS {
            if within[w] {
                ed[w] = ed[w].max(e);
                ef[w] = ef[w].max(g);
            }
        }
    }
    if !has_force {
        ef = [f64::NAN; WINDOWS];
    }
    Errors {
        d: ed,
        f: ef,
        scale: (sd, sf),
    }
}
