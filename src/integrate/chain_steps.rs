//! The multi-mass pantograph stepped by each method that carries it
//! (`mass_step.rs` with each method's stage: generalized-α, Bathe's two
//! sub-steps, Moreau–Jean, central difference) against the closed-form
//! held pantograph (docs/lines.md L9–L11): the head held on a rigid
//! surface (the wire replaced by a rigid support), the contact force
//! found each step as the contact problem finds it with a rigid beam
//! (`end` placement: q_{n+1} = q̃ + c_d u = 0 with u = u★ − λ/A_q, so
//! λ = A_q (u★ + q̃/c_d)).

use crate::analytic::PantographStep;
use crate::scene::{ChainProps, GenAlphaParams, MAX_CHAIN};

use super::bathe::{BatheDof, FirstSubStep, SecondSubStep};
use super::central_difference::CentralMass;
use super::chain::Chain;
use super::chain::tests::{ROUND_OFF, chains, held, props};
use super::gen_alpha_kernel::GenAlphaMass;
use super::mass_dofs::{MassDof, MassDofs};
use super::mass_step::{Dof, Effective, Kinematics, MassSteps, Stage};
use super::moreau_jean::MoreauJeanMass;

/// Newmark's (trapezoidal) error is second order: the measured order of
/// the max error on Δt halvings is within this of 2 (measured 1.99–2.00
/// in the asymptotic range used).
const ORDER_BAND: f64 = 0.05;

fn newmark() -> GenAlphaParams {
    GenAlphaParams::newmark()
}

/// Chung–Hulbert generalized-α at ρ∞ = 0.8.
fn gen_alpha_08() -> GenAlphaParams {
    GenAlphaParams::from_rho_inf(0.8)
}

/// A held run's samples: (t_{n+1}, every mass's z, λ_{n+1}).
type Run = Vec<(f64, [f64; MAX_CHAIN], f64)>;

/// The chain of `p` (no gravity) after an uplift step ΔF on its last
/// mass at t = 0, as a run's mass dofs.
fn stepped(p: &ChainProps, df: f64) -> MassDofs {
    let mut chain = Chain::new(p, 1.0, 0.0);
    chain.f0[p.n - 1] += df;
    MassDofs::of_chain(chain)
}

/// Every mass's z of contact 0.
fn z_of<D: Dof>(steps: &MassSteps<D>, n: usize, z: impl Fn(&D) -> f64) -> [f64; MAX_CHAIN] {
    let mut out = [0.0; MAX_CHAIN];
    for (i, o) in out.iter_mut().enumerate().take(n) {
        *o = z(steps.dof(0, i));
    }
    out
}

/// A held run: the uplift step ΔF (N), Δt and the end time (s).
#[derive(Debug, Clone, Copy)]
struct HeldRun {
    df: f64,
    dt: f64,
    t_end: f64,
}

/// A held run of a one-stage method: `lambda(u★, q̃, A_q)` is its held
/// head's multiplier, `force` the force it records of it.
fn held_one_stage<S: Stage<Dof = Kinematics>>(
    p: &ChainProps,
    stage: S,
    run: HeldRun,
    start: impl Fn(&mut MassSteps<Kinematics>),
    lambda: impl Fn(f64, f64, f64) -> f64,
) -> Run {
    let HeldRun { df, dt, t_end } = run;
    let masses = stepped(p, df);
    let effective = MassSteps::effective(&stage, &masses);
    let mut steps = MassSteps::<Kinematics>::new(&masses);
    start(&mut steps);
    let steps_n = (t_end / dt).round() as usize;
    (0..steps_n)
        .map(|s| {
            steps.predict(&stage, &effective, &masses);
            let pred = steps.predictions()[0];
            let l = lambda(pred.u, pred.q, pred.a_eff);
            steps.finish(&stage, &effective, &masses, &[l]);
            ((s + 1) as f64 * dt, z_of(&steps, p.n, |d| d.z), l)
        })
        .collect()
}

/// Generalized-α's held run (its λ at t_{n+1−α_f}).
fn held_run(p: &ChainProps, params: GenAlphaParams, df: f64, dt: f64, t_end: f64) -> Run {
    let n = p.n;
    let c_d = params.beta * dt * dt;
    held_one_stage(
        p,
        GenAlphaMass { p: params, dt },
        HeldRun { df, dt, t_end },
        |steps| steps.dof_mut(0, n - 1).za = df / p.masses[n - 1],
        // rigid surface: g = 0 − q_{n+1}, g_free = −(q̃ + c_d u★), W = c_d/A_q
        |u, q, a_q| {
            let (g_free, w) = (-(q + c_d * u), c_d / a_q);
            -g_free / w
        },
    )
}

fn held_bathe(p: &ChainProps, df: f64, dt: f64, t_end: f64) -> Run {
    let n = p.n;
    let gamma = 0.5;
    let (h1, c0) = (gamma * dt, 2.0 / (gamma * dt));
    let first = FirstSubStep { h1, c0 };
    let second = SecondSubStep {
        c1: (1.0 - gamma) / (gamma * dt),
        c2: -1.0 / ((1.0 - gamma) * gamma * dt),
        c3: (2.0 - gamma) / ((1.0 - gamma) * dt),
    };
    let masses = stepped(p, df);
    let (e1, e2) = (
        MassSteps::effective(&first, &masses),
        MassSteps::effective(&second, &masses),
    );
    let mut steps = MassSteps::<BatheDof>::new(&masses);
    steps.dof_mut(0, n - 1).za = df / p.masses[n - 1];
    let steps_n = (t_end / dt).round() as usize;
    (0..steps_n)
        .map(|s| {
            // each sub-step's gap row: q = q̃ + e = 0
            steps.predict(&first, &e1, &masses);
            let pred = steps.predictions()[0];
            steps.finish(&first, &e1, &masses, &[pred.a_eff * (pred.u + pred.q)]);
            steps.predict(&second, &e2, &masses);
            let pred = steps.predictions()[0];
            let lambda = pred.a_eff * (pred.u + pred.q);
            steps.finish(&second, &e2, &masses, &[lambda]);
            let z = z_of(&steps, n, |d| d.head().0);
            ((s + 1) as f64 * dt, z, lambda)
        })
        .collect()
}

fn held_moreau_jean(p: &ChainProps, df: f64, dt: f64, t_end: f64) -> Run {
    let theta = 0.5;
    let run = held_one_stage(
        p,
        MoreauJeanMass { theta, dt },
        HeldRun { df, dt, t_end },
        |_| {},
        |u, q, a_q| a_q * (u + q / (theta * dt)),
    );
    // the impulse P recorded as the step's mean force P/Δt
    run.into_iter()
        .map(|(t, z, impulse)| (t, z, impulse / dt))
        .collect()
}

fn held_central(p: &ChainProps, df: f64, dt: f64, t_end: f64) -> Run {
    let n = p.n;
    held_one_stage(
        p,
        CentralMass { dt },
        HeldRun { df, dt, t_end },
        // ż_{−1/2} = ż₀ − (Δt/2) z̈₀
        |steps| steps.dof_mut(0, n - 1).zd = -0.5 * dt * df / p.masses[n - 1],
        |u, q, a_q| a_q * (u + q / (dt * dt)),
    )
}

/// Max errors of a held run against L11 (state-space exponential): in
/// the lower masses' z relative to the static change, and in λ (at
/// t − lag·Δt, where the method's balance puts it) relative to ΔF.
fn errors_of(p: &ChainProps, df: f64, dt: f64, lag: f64, run: Run) -> (f64, f64) {
    let panto = held(p);
    let resp = panto.step(PantographStep::Uplift(df)).unwrap();
    let (z0, _) = resp.initial();
    let scale = (&resp.z_static - &z0).amax();
    let (mut ez, mut ef) = (0.0_f64, 0.0_f64);
    for (t, z, lambda) in run {
        let (zr, _) = resp.state_space(t);
        for i in 1..p.n {
            ez = ez.max((z[i] - (zr[i - 1] - z0[i - 1])).abs() / scale);
        }
        let (zf, vf) = resp.state_space(t - lag * dt);
        ef = ef.max((lambda - resp.contact_force(&zf, &vf)).abs() / df.abs());
    }
    (ez, ef)
}

fn errors(p: &ChainProps, params: GenAlphaParams, df: f64, dt: f64, t_end: f64) -> (f64, f64) {
    errors_of(
        p,
        df,
        dt,
        params.alpha_f,
        held_run(p, params, df, dt, t_end),
    )
}

#[test]
fn the_head_sees_the_chains_dynamic_stiffness() {
    // A_q = 1/(A⁻¹)₁₁ against the Schur complement of the lower block
    // for two masses: A₁₁ − A₁₂²/A₂₂
    let p = props(&[6.0, 11.0], &[7000.0, 60.0], &[15.0, 40.0], 100.0);
    let (params, dt) = (gen_alpha_08(), 1e-3);
    let chain = Chain::new(&p, 1.0, 0.0);
    let stage = GenAlphaMass { p: params, dt };
    let head = MassDof {
        m: chain.m[0],
        k: 0.0,
        c: 0.0,
        f0: chain.f0[0],
    };
    let a_q = Effective::new(stage.matrix(), &head, Some(&chain)).a_q();
    let entry = |i: usize, j: usize, c: &Chain| {
        (1.0 - params.alpha_f) * (params.gamma * dt * c.c[i][j] + params.beta * dt * dt * c.k[i][j])
            + if i == j {
                (1.0 - params.alpha_m) * c.m[i]
            } else {
                0.0
            }
    };
    let c = &chain;
    let schur = entry(0, 0, c) - entry(0, 1, c) * entry(1, 0, c) / entry(1, 1, c);
    assert!((a_q - schur).abs() <= ROUND_OFF * schur);
}

#[test]
fn held_uplift_steps_match_the_closed_form_at_second_order() {
    let df = 20.0;
    for (name, p) in chains() {
        let modes = held(&p).modes().unwrap();
        let t_min = 2.0 * std::f64::consts::PI / modes.omega.last().unwrap();
        let t_end = 3.0 * 2.0 * std::f64::consts::PI / modes.omega[0];
        type Errors = Box<dyn Fn(f64) -> (f64, f64)>;
        let schemes: [(&str, Errors); 5] = [
            (
                "newmark",
                Box::new(move |dt| errors(&p, newmark(), df, dt, t_end)),
            ),
            (
                "gen-α ρ∞ = 0.8",
                Box::new(move |dt| errors(&p, gen_alpha_08(), df, dt, t_end)),
            ),
            (
                "bathe",
                Box::new(move |dt| errors_of(&p, df, dt, 0.0, held_bathe(&p, df, dt, t_end))),
            ),
            (
                "moreau_jean θ = ½",
                Box::new(move |dt| errors_of(&p, df, dt, 0.5, held_moreau_jean(&p, df, dt, t_end))),
            ),
            (
                "central_difference",
                Box::new(move |dt| errors_of(&p, df, dt, 1.0, held_central(&p, df, dt, t_end))),
            ),
        ];
        for (scheme, errors) in schemes {
            let e: Vec<(f64, f64)> = [40.0, 80.0, 160.0]
                .iter()
                .map(|per| errors(t_min / per))
                .collect();
            let order_z = (e[1].0 / e[2].0).log2();
            let order_f = (e[1].1 / e[2].1).log2();
            println!(
                "{name}, {scheme}: z errors {:.3e} {:.3e} {:.3e} (order {order_z:.3}), \
                 λ errors {:.3e} {:.3e} {:.3e} (order {order_f:.3})",
                e[0].0, e[1].0, e[2].0, e[0].1, e[1].1, e[2].1
            );
            assert!(
                (order_z - 2.0).abs() <= ORDER_BAND,
                "{name} {scheme}: z order {order_z}"
            );
            assert!(
                (order_f - 2.0).abs() <= ORDER_BAND,
                "{name} {scheme}: λ order {order_f}"
            );
        }
    }
}

#[test]
fn the_held_two_mass_chain_rings_at_its_natural_frequency() {
    // one degree of freedom once held: ω² = (k₁ + k₂)/m₂ (L10); the
    // trapezoidal rule rings at ω_h = (2/Δt) atan(ωΔt/2) exactly
    let p = props(&[6.0, 11.0], &[7000.0, 60.0], &[0.0, 0.0], 100.0);
    let omega = held(&p).modes().unwrap().omega[0];
    assert!((omega - ((7000.0_f64 + 60.0) / 11.0).sqrt()).abs() <= ROUND_OFF * omega);
    let dt = 2.0 * std::f64::consts::PI / omega / 100.0;
    let df = 20.0;
    let z_after = df / (7000.0 + 60.0);
    let run = held_run(
        &p,
        newmark(),
        df,
        dt,
        40.0 * 2.0 * std::f64::consts::PI / omega,
    );
    // upward crossings of z₂ − z_s by linear interpolation
    let mut crossings = Vec::new();
    let mut prev = (0.0, -z_after);
    for (t, z, _) in &run {
        let y = z[1] - z_after;
        if prev.1 < 0.0 && y >= 0.0 {
            crossings.push(prev.0 + (t - prev.0) * (-prev.1) / (y - prev.1));
        }
        prev = (*t, y);
    }
    let periods = (crossings.len() - 1) as f64;
    let measured =
        2.0 * std::f64::consts::PI * periods / (crossings.last().unwrap() - crossings[0]);
    let discrete = 2.0 / dt * (omega * dt / 2.0).atan();
    println!(
        "ω = {omega:.9} rad/s, measured {measured:.9}, trapezoidal {discrete:.9} \
         ({:.2e}, {:.2e})",
        measured / omega - 1.0,
        measured / discrete - 1.0
    );
    // the measured frequency is the scheme's to the crossing interpolation
    // (O((ωΔt)³) per crossing over 40 periods: below 1e-6), and it is ω
    // to the scheme's period error (ωΔt)²/12 = 3.3e-4 at 100 steps per period
    assert!((measured / discrete - 1.0).abs() <= 1e-6);
    let period_error = (omega * dt).powi(2) / 12.0;
    assert!((measured / omega - 1.0).abs() <= 1.05 * period_error);
}
