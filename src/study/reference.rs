//! The reference a scene declares (`[reference]`, or `[manufactured]`;
//! MODEL §8, §11), built for a study: nothing is recognized from the
//! scene's shape. The scene says what its reference is, and validation has
//! checked that the scene meets that reference's assumptions
//! ([`crate::scene::Declared`], `docs/scene.md`):
//!
//! * `manufactured` — the manufactured solution, exact everywhere:
//!   v*(x, t), and for every carrier w*, λ*, q* (`crate::manufactured`);
//! * `moving_force_series` — the modal series of MODEL §8
//!   ([`MovingForceString`], [`MovingForceBeam`]);
//! * `riding_mass_galerkin` — the Galerkin solution in the exact modes with
//!   the convective terms ([`RidingMassBeam`]), integrated once on the
//!   finest level's time grid with J from `reference.modes` or
//!   [`riding_mass_modes`];
//! * `standing_force_modes` — the exact time history of the discretized
//!   model under standing forces (`StandingForce`): no space error;
//! * `richardson` (no `[reference]`) — none here: a study extrapolates its
//!   own finest levels.

use super::standing_force::StandingForce;
use crate::analytic::{MovingForceBeam, MovingForceString, Rider, RidingMassBeam};
use crate::error::{Error, Result};
use crate::manufactured::Manufactured;
use crate::resolve::Resolved;
use crate::scene::{CarrierKind, Declared, SpeedProfile};

/// A reference solution for the displacement under the carrier,
/// w(x_m(t), t) as a function of t (m), when the scene has one.
pub(crate) type AnalyticW = Box<dyn Fn(f64) -> f64 + Sync>;

/// v(x, t) of a reference that has it everywhere, m (positive up).
pub(crate) type ExactField = Box<dyn Fn(f64, f64) -> f64 + Send + Sync>;

/// What a declared reference gives for a scene: the histories a run
/// records, as functions of time (carrier 0), and v(x, t) where known.
pub struct Exact {
    /// The declared kind.
    pub kind: Declared,
    /// w(t) = s·v(x_m(t), t) under carrier 0, m.
    pub w: AnalyticW,
    /// λ(t) of carrier 0, N, when the reference has it.
    pub force: Option<AnalyticW>,
    /// q(t) of carrier 0's mass, m, when it has one.
    pub mass: Option<AnalyticW>,
    /// v(x, t), when the reference has it everywhere (probes).
    pub field: Option<ExactField>,
    /// The manufactured solution itself (every carrier), for `manufactured`.
    pub manufactured: Option<Manufactured>,
}

/// The exact reference of `sc` (`None` for Richardson), built for the
/// scene's own time grid (a riding mass is integrated up to its end).
pub fn exact(sc: &Resolved) -> Result<Option<Exact>> {
    match sc.reference {
        Declared::Richardson => Ok(None),
        Declared::Manufactured => {
            let m = sc
                .manufactured
                .clone()
                .expect("a manufactured scene carries its solution");
            let (a, b, c, d) = (m.clone(), m.clone(), m.clone(), m.clone());
            let mass = matches!(sc.carriers[0].kind, CarrierKind::MassSpring { .. });
            Ok(Some(Exact {
                kind: sc.reference,
                w: Box::new(move |t| a.w(0, t)[0]),
                force: Some(Box::new(move |t| b.lambda(0, t))),
                mass: mass.then(|| Box::new(move |t| c.q(0, t)) as AnalyticW),
                field: Some(Box::new(move |x, t| d.v(x, t))),
                manufactured: Some(m),
            }))
        }
        Declared::MovingForceSeries => {
            let c = &sc.carriers[0];
            let (CarrierKind::Force { force }, SpeedProfile::Constant { value: speed }) =
                (c.kind, c.motion.profile.clone())
            else {
                unreachable!("validation checked a constant-speed force")
            };
            let (b, s) = (&sc.beam, c.side.sign());
            let f: ExactField = if b.is_string() {
                let m = MovingForceString::new(b.tension, b.rho_a, b.length, force, speed)?;
                Box::new(move |x, t| s * m.deflection(x, t))
            } else {
                let m = MovingForceBeam::new(b.ei, b.tension, b.rho_a, b.length, force, speed)?;
                Box::new(move |x, t| s * m.deflection(x, t))
            };
            let field = std::sync::Arc::new(f);
            let under = field.clone();
            // w = s·v under the force = the response to F in +v
            Ok(Some(Exact {
                kind: sc.reference,
                w: Box::new(move |t| s * under(speed * t, t)),
                force: Some(Box::new(move |_| force)),
                mass: None,
                field: Some(Box::new(move |x, t| field(x, t))),
                manufactured: None,
            }))
        }
        Declared::RidingMassGalerkin { modes } => {
            let r = riding_mass_beam(sc).ok_or_else(|| {
                Error::invalid(
                    "reference.kind",
                    "\"riding_mass_galerkin\"",
                    "the scene's beam and carrier give no riding-mass reference",
                )
            })?;
            let j = modes.unwrap_or_else(|| riding_mass_modes(sc.elements));
            let h = r.solve(j, r.max_step(j), sc.dt, sc.steps as f64 * sc.dt)?;
            Ok(Some(Exact {
                kind: sc.reference,
                w: Box::new(move |t| h.w_at(t)),
                force: None,
                mass: None,
                field: None,
                manufactured: None,
            }))
        }
        Declared::StandingForceModes => {
            let m = std::sync::Arc::new(StandingForce::new(sc)?);
            let (c, u) = (sc.carriers[0].clone(), m.clone());
            let (x, s) = (c.motion.position(0.0), c.side.sign());
            let force = match c.kind {
                CarrierKind::Force { force } => force,
                CarrierKind::MassSpring { .. } => unreachable!("validation checked forces"),
            };
            Ok(Some(Exact {
                kind: sc.reference,
                w: Box::new(move |t| s * u.v(x, t)),
                force: Some(Box::new(move |_| force)),
                mass: None,
                field: Some(Box::new(move |x, t| m.v(x, t))),
                manufactured: None,
            }))
        }
    }
}

/// The exact w(t) under carrier 0 of the scene's declared reference
/// ([`exact`]), for a study's displacement errors; `None` for Richardson
/// (or a reference that cannot be built, e.g. a model too large for the
/// standing-force eigenproblem).
pub fn analytic_w(sc: &Resolved) -> Option<AnalyticW> {
    exact(sc).ok().flatten().map(|e| e.w)
}

/// Fewest Galerkin modes for a riding-mass reference: measured on
/// `scenes/riding_mass_pinned.toml`, w changes by 1.8e-5 m from J = 800 to
/// 1600 (about J^-2.3), so J = 800 is within ≈ 5e-6 m (2.5e-5 of max |w|),
/// ten times below the FE error at N = 200 (4.7e-5 m).
pub(crate) const RIDING_MASS_MIN_MODES: usize = 800;

/// Modes per element of the finest mesh: the Hermite model has 2N unknowns,
/// and J = 4N keeps the Galerkin truncation about ten times below the FE
/// error at every N measured (N = 200: 4.7e-5 vs 5e-6 m; N = 400: 8.7e-6
/// vs ≈ 1e-6 m at J = 1600).
pub(crate) const RIDING_MASS_MODES_PER_ELEMENT: usize = 4;

/// Cap on J: the RK4 step falls like 1/ω_J ∝ J⁻² in the bending range, so
/// the cost grows like J³ (J = 1600: a few seconds for 0.4 s of motion); beyond
/// this the reference would cost more than the FE ladder it checks.
pub(crate) const RIDING_MASS_MAX_MODES: usize = 3200;

/// J for a riding-mass reference against a mesh of `elements` elements:
/// `clamp(4N, 800, 3200)`.
pub fn riding_mass_modes(elements: usize) -> usize {
    (RIDING_MASS_MODES_PER_ELEMENT * elements).clamp(RIDING_MASS_MIN_MODES, RIDING_MASS_MAX_MODES)
}

/// The Galerkin riding mass of a scene that declares
/// `reference.kind = "riding_mass_galerkin"` (validation checked its
/// assumptions); `None` for any other scene.
pub fn riding_mass_beam(sc: &Resolved) -> Option<RidingMassBeam> {
    if !matches!(sc.reference, Declared::RidingMassGalerkin { .. }) {
        return None;
    }
    let c = &sc.carriers[0];
    let (CarrierKind::MassSpring { mass, .. }, SpeedProfile::Constant { value: speed }) =
        (c.kind, c.motion.profile.clone())
    else {
        return None;
    };
    let b = &sc.beam;
    let rider = Rider {
        mass,
        gravity: sc.g,
        side: c.side,
        start: c.motion.start,
        speed,
    };
    RidingMassBeam::new(b.ei, b.tension, b.rho_a, b.length, rider).ok()
}
