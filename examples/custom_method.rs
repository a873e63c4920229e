//! Adding a time integrator outside the crate: first-order backward Euler
//! against taut's public [`Stepper`] trait, run through the same studies as
//! the built-in methods (docs/methods.md, "Adding a method", walks through it).
//!
//! ```text
//!   M (v_{n+1} − v_n)/Δt + K d_{n+1} = f_{n+1} + Σ λ_c r_c,   d_{n+1} = d_n + Δt v_{n+1}
//! ```
//!
//! Solved for u = d_{n+1}: `(M/Δt² + K) d_{n+1} = M(d_n + Δt v_n)/Δt² + f + Σ λ r`,
//! one constant matrix factored once. For the contact problem the step is
//! `d_{n+1} = 0 + 1·u`, `v_{n+1} = −d_n/Δt + (1/Δt)·u` ([`StepMap`] with
//! c_d = 1, c_v = 1/Δt); the [`System`] does the rest (free gaps, Delassus
//! matrix, whichever contact law the scene asks for).
//!
//! Run: `cargo run --release --example custom_method` — it prints the
//! observed time order of backward Euler beside generalized-α's on the
//! one-dof oscillator's step response (its declared reference,
//! `standing_force_modes`: first and second order), runs both through the
//! verification harness (`taut verify`'s cases; backward Euler declares
//! its formal order 1 with [`MethodFactory::time_order`]) and through
//! `taut converge`'s study on the moving-force case, then compares both on
//! the reference case, and writes `out/custom_method/{converge,compare}/`.
//! `tests/methods.rs` runs the oscillator check.

use taut::integrate::{
    Initial, MassPrediction, MethodFactory, State, StepMap, Stepper, System, VelocityPrediction,
    combine,
};
use taut::model::banded::BandedLdlt;
use taut::scene::{Method, MethodInfo};
use taut::{Resolved, Result};

/// Backward Euler for one run.
pub struct BackwardEuler {
    dt: f64,
    /// The factor of M/Δt² + K.
    ldlt: BandedLdlt,
    /// A_q = m/Δt² + c/Δt + k per contact.
    a_eff: Vec<f64>,
    mass_pred: Vec<MassPrediction>,
    /// ṽ = −d_n/Δt, d̃ = 0, and scratch.
    v_pred: Vec<f64>,
    zeros: Vec<f64>,
    w: Vec<f64>,
    y: Vec<f64>,
    rhs: Vec<f64>,
}

impl Stepper for BackwardEuler {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let dt = self.dt;
        let k = sys.columns();
        let t1 = st.next_time(dt);
        // loads, force directions and gap rows all at t_{n+1}
        sys.place(t1, t1, t1);
        let beam = sys.beam();
        // column 0: f + M(d_n + Δt v_n)/Δt²; columns 1 + c: the contact directions
        for i in 0..st.d.len() {
            self.w[i] = (st.d[i] + dt * st.v[i]) / (dt * dt);
            self.v_pred[i] = -st.d[i] / dt;
        }
        self.y.copy_from_slice(&beam.load);
        beam.mass.mul_acc(&self.w, 1.0, &mut self.y);
        self.rhs.fill(0.0);
        for (row, y) in self.rhs.chunks_exact_mut(k).zip(&self.y) {
            row[0] = *y;
        }
        sys.scatter_loads(&mut self.rhs, k, 1.0);
        self.ldlt.solve_many(&mut self.rhs, k);
        // the mass dofs by the same rule
        for (j, m) in sys.masses().iter().enumerate() {
            let (q, qd) = (st.q[j], st.q_dot[j]);
            let b = m.f0 + m.m * (q + dt * qd) / (dt * dt) + m.c * q / dt;
            self.mass_pred[j] = MassPrediction {
                q: 0.0,
                q_dot: -q / dt,
                u: b / self.a_eff[j],
                a_eff: self.a_eff[j],
            };
        }
        // the contact problem: the system forms (g_free, W) and calls the law
        let map = StepMap {
            solved: &self.rhs,
            c_d: 1.0,
            c_v: 1.0 / dt,
            d_pred: &self.zeros,
            v_pred: VelocityPrediction::Vector(&self.v_pred),
            alpha_weight: 0.0,
            masses: &self.mass_pred,
        };
        sys.solve_contact(&map, st)?;
        // the update with the multipliers
        let lambda = sys.multipliers();
        for (i, d) in combine(&self.rhs, k, lambda).enumerate() {
            st.v[i] = (d - st.d[i]) / dt;
            st.d[i] = d;
        }
        for (j, m) in self.mass_pred.iter().enumerate() {
            let q = m.unknown(lambda[j]);
            st.q_dot[j] = (q - st.q[j]) / dt;
            st.q[j] = q;
        }
        Ok(())
    }
}

/// Builds [`BackwardEuler`] for a run: what the studies take.
pub struct BackwardEulerFactory;

/// The one factory, registered by name ([`register`]).
pub static BACKWARD_EULER: BackwardEulerFactory = BackwardEulerFactory;

/// What a scene, `--methods` and the tables call it.
impl MethodInfo for BackwardEulerFactory {
    fn name(&self) -> String {
        "backward_euler".into()
    }
}

/// Register [`BACKWARD_EULER`] as `"backward_euler"` (once per process;
/// later calls do nothing): from then on `integrator.method =
/// "backward_euler"` in a scene and `--methods backward_euler` reach it
/// as they reach a built-in method.
pub fn register() -> Result<()> {
    static ONCE: std::sync::OnceLock<std::result::Result<(), String>> = std::sync::OnceLock::new();
    ONCE.get_or_init(|| taut::integrate::register(&BACKWARD_EULER).map_err(|e| e.to_string()))
        .clone()
        .map_err(|e| taut::Error::invalid("method name", "backward_euler", e))
}

impl MethodFactory for BackwardEulerFactory {
    /// Backward Euler is first order in Δt: what `taut verify` holds it to.
    fn time_order(&self, _sc: &Resolved) -> Option<f64> {
        Some(1.0)
    }

    fn build(
        &self,
        _sc: &Resolved,
        sys: &mut System,
        _st: &mut State,
        _init: Initial,
    ) -> Result<Box<dyn Stepper>> {
        let dt = sys.dt();
        let beam = sys.beam();
        let n = beam.n;
        let a = beam.stiffness.combine(1.0, &beam.mass, 1.0 / (dt * dt));
        let nc = sys.contacts();
        Ok(Box::new(BackwardEuler {
            dt,
            ldlt: BandedLdlt::factor(&a)?,
            a_eff: sys
                .masses()
                .iter()
                .map(|m| m.m / (dt * dt) + m.c / dt + m.k)
                .collect(),
            mass_pred: vec![MassPrediction::default(); nc],
            v_pred: vec![0.0; n],
            zeros: vec![0.0; n],
            w: vec![0.0; n],
            y: vec![0.0; n],
            rhs: vec![0.0; n * sys.columns()],
        }))
    }
}

/// Observed time order of `method` on the one-dof oscillator's step
/// response (`scenes/oscillator_one_dof.toml`, whose declared reference is
/// the model's exact d_s(1 − cos ωt)): the max error over 0.2 s at
/// Δt = 5e-4 and 2.5e-4 s, through the one observed order of the studies.
pub fn oscillator_order(method: &dyn MethodFactory) -> Result<f64> {
    let text = include_str!("../scenes/oscillator_one_dof.toml");
    let mut errors = Vec::new();
    for dt in [5e-4, 2.5e-4] {
        let set = [format!("time.step={dt:e}"), "time.end=0.2".to_string()];
        let sc = taut::resolve_scene(text, &set)?;
        let exact = taut::study::reference::exact(&sc)?
            .and_then(|e| e.field)
            .expect("the oscillator declares an exact reference");
        let out = taut::run_with(&sc, method, &mut |_, _| {})?;
        let h = &out.history;
        let x = sc.probes[0].1;
        let err =
            h.t.iter()
                .zip(&h.probes[0].1)
                .map(|(&t, v)| (v - exact(x, t)).abs())
                .fold(0.0, f64::max);
        errors.push(err);
    }
    Ok(taut::study::uncertainty::observed_order(
        errors[0], errors[1], 2.0,
    ))
}

#[allow(dead_code)]
fn main() -> Result<()> {
    use taut::study::converge::{Ladder, Refine, converge_methods};
    let out = std::path::Path::new("out/custom_method");
    // from here on "backward_euler" is a method name like the built-in ones
    register()?;
    let methods: [&dyn MethodFactory; 2] = [&BACKWARD_EULER, &Method::GeneralizedAlpha];

    // observed time order on an exact one-dof case
    for m in methods {
        println!(
            "{:18} observed time order {:.2} (oscillator step response)",
            m.name(),
            oscillator_order(m)?
        );
    }

    // the same through the verification harness (`taut verify`'s cases),
    // each method against the order it declares; the selection is parsed
    // from names, as `taut verify --methods` does
    let sel = taut::study::verify::selection(
        Some("generalized_alpha,backward_euler"),
        Some("hermite"),
        Some("lagrange"),
        true,
    )?;
    let rows =
        taut::study::verify::verify(&taut::study::verify::cases::CASES[..1], &sel, &|_, _| {})?;
    print!("{}", taut::report::verify_table(&rows));

    // the same through `taut converge` on the moving-force case, which
    // declares its exact series: on this 50-element mesh the error against
    // the series is the mesh's and does not move with Δt, and converge says
    // so (`regime`: limited by the mesh). The order of successive
    // differences (`observed_order`) is then the discrete model's, not the
    // error's: print both, never the one without the other
    let moving_force = include_str!("../scenes/moving_force_beam.toml");
    let (studies, skipped) = converge_methods(
        moving_force,
        &[],
        &methods,
        Ladder {
            refine: Refine::Step,
            levels: 4,
            ratio: 2.0,
        },
        &taut::study::reference::analytic_w,
        &mut |_, _| {},
    )?;
    for s in &studies {
        if let Some(r) = s
            .study
            .rows
            .iter()
            .rfind(|r| r.quantity == "displacement_history_l2")
        {
            println!(
                "{:18} moving force, taut converge: error against the series {:.3e} (order {:.2}), successive differences' order {:.2}: {}",
                s.method, r.error, r.error_order, r.observed_order, r.regime
            );
        }
    }
    taut::report::write_converge_methods(&out.join("converge"), &studies, &skipped)?;

    // a scene that names it (the reference scene sets rho_inf, so its whole
    // `[integrator]` is replaced): `integrator.method = "backward_euler"`, run as
    // `taut run` runs a scene (its own method, found by name)
    let reference = include_str!("../scenes/reference.toml");
    let set = [
        "integrator={ method = \"backward_euler\" }".to_string(),
        "time.end=0.05".to_string(),
    ];
    let sc = taut::resolve_scene(reference, &set)?;
    let run = taut::run(&sc, &mut |_, _| {})?;
    println!(
        "{:18} reference case to t = {} s: largest contact force {:.2} N (the scene names it)",
        sc.method.name(),
        sc.t_end,
        run.stats[0].force.max
    );

    // side by side on the study's reference case, as `taut compare
    // --methods backward_euler,generalized_alpha --formulations lagrange
    // --batch 1` asks for it: the same typed request, made from the same
    // words by the same edge (`taut::app::words`)
    let request = taut::app::words::compare(
        "lagrange",
        (Some("backward_euler,generalized_alpha"), None),
        ("lagrange", Some("generalized_alpha")),
        Some(1),
        false,
    )?;
    let c = request.run(reference, &[], &mut |_, _| {})?;
    print!("{}", taut::report::compare_table(&c));
    taut::report::write_compare(&out.join("compare"), &c)?;
    println!("wrote {}/{{converge,compare}}/", out.display());
    Ok(())
}
