//! The cases of the stability report (`out/xtask/stability.md`), section by section (their scenes,
//! settings, references and expected verdicts).

use super::score::*;
// ---------------------------------------------------------------------------
// The cases
// ---------------------------------------------------------------------------

/// The reference wire's second moment of area (9.64e-10 m⁴) × 1e-6 and × 1e4,
/// as override values.
pub(super) const I_SMALL: &str = "beam.second_moment=9.64e-16";
pub(super) const I_BIG: &str = "beam.second_moment=9.64e-6";
/// Tension of the reference wire, N.
pub(super) const T_REF: f64 = 3.0e4;
/// Spring stiffness and preload of the reference carrier.
pub(super) const K_REF: f64 = 987.0;
pub(super) const PRELOAD_REF: f64 = 0.05;

pub(super) fn sets(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

pub(super) fn with(base: &[String], more: &[&str]) -> Vec<String> {
    let mut v = base.to_vec();
    v.extend(more.iter().map(|s| s.to_string()));
    v
}

/// g changed by 1e-6 of itself: a perturbation far below any physical
/// meaning, to see whether a case's figures are determined at all.
pub(super) const PERTURBED_G: &str = "gravity.g=9.81000981";

/// A Lagrange reference run with `resolution` on top of `physics`; its
/// spread is measured against `coarser` and against a 1e-6 change of g.
pub(super) fn reference_run(
    scene: &'static str,
    physics: &[String],
    resolution: &[&str],
    coarser: Option<(&'static str, &[&str])>,
    name: String,
) -> Check {
    let base = with(physics, &["contact.formulation=lagrange"]);
    let sets = with(&base, resolution);
    let mut also = vec![("under a 1e-6 change of g", with(&sets, &[PERTURBED_G]))];
    if let Some((label, c)) = coarser {
        also.push((label, with(&base, c)));
    }
    Check::Run {
        scene,
        sets,
        name,
        also,
    }
}

/// Lagrange, two refinements finer than the bundled resolution; spread
/// against one refinement finer and against a perturbation.
pub(super) fn finest(scene: &'static str, physics: &[String]) -> Check {
    reference_run(
        scene,
        physics,
        &["mesh.elements=1600", "time.step=2.5e-5"],
        Some((
            "at N = 800, Δt = 5e-5 s",
            &["mesh.elements=800", "time.step=5e-5"],
        )),
        "Lagrange at N = 1600, Δt = 2.5e-5 s".into(),
    )
}

/// Lagrange with a step that resolves the carrier's 0.2 ms period; spread
/// against twice that step and against a perturbation.
pub(super) fn fine_step(scene: &'static str, physics: &[String]) -> Check {
    reference_run(
        scene,
        physics,
        &["time.step=1e-5"],
        Some(("at Δt = 2e-5 s", &["time.step=2e-5"])),
        "Lagrange at N = 400, Δt = 1e-5 s".into(),
    )
}

/// Lagrange at the bundled resolution (N = 400, Δt = 1e-4 s); spread
/// against a perturbation (its convergence is the baseline section's).
pub(super) fn bundled(scene: &'static str, physics: &[String], what: &str) -> Check {
    reference_run(
        scene,
        physics,
        &[],
        None,
        format!("the bundled Lagrange run (N = 400, Δt = 1e-4 s{what})"),
    )
}

/// Rows for every formulation: scene, physics, reference, expected verdicts
/// and explanations per formulation.
pub(super) fn all_forms(
    label: &str,
    scene: &'static str,
    physics: &[String],
    check: &Check,
    expect: [Verdict; 4],
    why: [&str; 4],
) -> Vec<Case> {
    FORMULATIONS
        .iter()
        .zip(expect)
        .zip(why)
        .map(|((&form, expect), why)| Case {
            label: label.into(),
            form,
            scene,
            sets: with(physics, &[&format!("contact.formulation={form}")]),
            check: check.clone(),
            expect,
            why: why.into(),
        })
        .collect()
}

pub(super) fn one(
    label: &str,
    form: &'static str,
    scene: &'static str,
    sets: Vec<String>,
    check: Check,
    expect: Verdict,
    why: &str,
) -> Case {
    Case {
        label: label.into(),
        form,
        scene,
        sets,
        check,
        expect,
        why: why.into(),
    }
}

pub(super) fn force_case(
    label: &str,
    scene: &'static str,
    s: &[&str],
    expect: Verdict,
    why: &str,
) -> Case {
    one(label, "—", scene, sets(s), Check::Analytic, expect, why)
}

pub(super) use Verdict::*;

pub(super) fn sections() -> Vec<Section> {
    let reference = resolve_scene(&scene_text("reference"), &[]).expect("bundled scene");
    let c = reference.beam.wave_speed();
    let ea = reference.beam.ea.unwrap_or(f64::NAN);
    let none: Vec<String> = vec![];
    let mut out = Vec::new();

    // 0. Baseline
    let mut cases = all_forms(
        "bundled",
        "reference",
        &none,
        &finest("reference", &none),
        [Accurate; 4],
        [
            "the study's scheme at the bundled resolution already has P_l and the mean force; only the re-contact peaks near the far support are unconverged",
            "the default relative stiffness ρ = 1000 makes each step's force 0.1 % softer than Lagrange's, which barely moves P_l or the mean",
            "the QP solves Lagrange's per-step problem to solver tolerance",
            "the velocity-level law lets the gap drift by micrometres and softens re-contact, which loses a few loss steps but not the mean",
        ],
    );
    cases.push(force_case(
        "moving force on a beam, bundled",
        "moving_force_beam",
        &[],
        Accurate,
        "50 Hermite elements resolve the nearly quasi-static deflection of the tensioned beam",
    ));
    cases.push(force_case(
        "moving force on a string, bundled",
        "moving_force_string",
        &[],
        Accurate,
        "linear string elements smear the kink under the load over one 1 m element, a first-order error that is still small",
    ));
    out.push(Section {
        title: "Baseline: the bundled scenes",
        intro: "The rows every extreme is measured against: the reference case under each formulation, scored against Lagrange two refinements finer, and the two moving-force scenes scored against their analytic solutions.".into(),
        cases,
    });

    // 1. EI → 0
    let ei_small = sets(&[I_SMALL]);
    let string = sets(&["beam.second_moment=0", "beam.left=pinned"]);
    let chatter_why = "a mass on an almost bendless wire chatters on and off contact, its force alternating from step to step (osc ≈ 0.5), and P_l and the mean move with refinement; the chatter warning says so";
    let mut cases = all_forms(
        "EI × 1e-6",
        "reference",
        &ei_small,
        &finest("reference", &ei_small),
        [Flagged, Flagged, Flagged, Stopped],
        [
            chatter_why,
            chatter_why,
            chatter_why,
            "the velocity-level Delassus number turns negative on the very last step, as the carrier arrives at the far support over the wire's steep slope there (V·Δt is only 0.08 h; with Δt = 1e-5 s the run completes)",
        ],
    );
    cases.push(one(
        "EI = 0, clamped left end",
        "lagrange",
        "reference",
        sets(&["beam.second_moment=0", "contact.formulation=lagrange"]),
        Check::None,
        Rejected,
        "a string has no rotational dof, so it cannot be clamped, and taut names the field",
    ));
    let string_why = "on linear string elements the mass switches contact on about a fifth of the steps at every resolution, a numerical on/off oscillation rather than physical loss, and the chatter warning says so";
    cases.extend(all_forms(
        "EI = 0, string elements (pinned–pinned)",
        "reference",
        &string,
        &finest("reference", &string),
        [Flagged; 4],
        [string_why; 4],
    ));
    cases.push(force_case(
        "moving force, EI × 1e-6",
        "moving_force_beam",
        &[I_SMALL],
        Accurate,
        "with the tension carrying the load the C¹ Hermite elements still match the analytic series; without a mass there is nothing to chatter",
    ));
    cases.push(force_case(
        "moving force, EI = 0 (string elements)",
        "moving_force_string",
        &[],
        Accurate,
        "this is the bundled string scene: the first-order kink error of linear elements, a few per cent at 1 m elements",
    ));
    out.push(Section {
        title: "Bending stiffness EI → 0",
        intro: "EI × 1e-6 keeps Hermite beam elements and the clamped–pinned supports; EI = 0 switches to linear string elements, which need pinned ends. The moving-force rows isolate the wire from the contact.".into(),
        cases,
    });

    // 2. EI large
    let ei_big = sets(&[I_BIG]);
    let stiff_why = "the 1e4 times stiffer beam barely deflects under the carrier, so the force stays near its preload, contact is never lost and every law gives the same smooth force";
    let mut cases = all_forms(
        "EI × 1e4",
        "reference",
        &ei_big,
        &finest("reference", &ei_big),
        [Accurate; 4],
        [stiff_why; 4],
    );
    cases.push(force_case(
        "moving force, EI × 1e4",
        "moving_force_beam",
        &[I_BIG],
        Accurate,
        "a stiff beam's response is quasi-static and easily resolved",
    ));
    out.push(Section {
        title: "Bending stiffness EI large (× 1e4)",
        intro: String::new(),
        cases,
    });

    // 3. T → 0
    let t0 = sets(&["beam.tension=0"]);
    let t0_scene = resolve_scene(&scene_text("reference"), &t0).expect("T = 0 is valid");
    let c0 = t0_scene.beam.wave_speed();
    let ell =
        |v: f64| 2.0 * std::f64::consts::PI * (reference.beam.ei / reference.beam.rho_a).sqrt() / v;
    let mut cases = all_forms(
        "T = 0 (pure beam)",
        "reference",
        &t0,
        &finest("reference", &t0),
        [Accurate, SilentlyWrong, Marginal, Accurate],
        [
            "the untensioned wire is so soft that the mass bounces (P_l ≈ 0.69, re-contact peaks of 10⁴ N), yet P_l and the mean converge within a few per cent; the peaks do not",
            "with the default relative stiffness ρ = 1000 every one of the many re-contacts is slightly cushioned, which lowers the mean force by about a tenth (ρ = 1e9 brings it within 2 % of the bundled Lagrange run); nothing warns",
            "the bouncing amplifies round-off-level differences (a 1e-12 m change of preload moves the bundled Lagrange mean by almost 1 %), and the QP lands a few per cent from Lagrange",
            "the velocity-level law softens the re-contacts but keeps the mean and P_l of this bouncing regime",
        ],
    );
    cases.push(one(
        "T = 0 on a string (EI = 0)",
        "lagrange",
        "reference",
        sets(&[
            "beam.second_moment=0",
            "beam.left=pinned",
            "beam.tension=0",
            "contact.formulation=lagrange",
        ]),
        Check::None,
        Rejected,
        "a string without tension has no stiffness, and taut names the field",
    ));
    cases.push(force_case(
        "moving force, T = 0 (pure beam), bundled N = 50",
        "moving_force_beam",
        &["beam.tension=0"],
        SilentlyWrong,
        &format!(
            "without tension the load excites the flexural wave whose phase speed equals V, of length ℓ* = 2π·sqrt(EI/ρA)/V = {:.2} m, which 1 m elements cannot carry; nothing in the run notices",
            ell(75.0)
        ),
    ));
    cases.push(force_case(
        "moving force, T = 0, N = 800, Δt = 2.5e-5 s",
        "moving_force_beam",
        &["beam.tension=0", "mesh.elements=800", "time.step=2.5e-5"],
        Accurate,
        "with 6.25 cm elements (ℓ*/13) the same case converges to the analytic solution, so the bundled mesh, not the scheme, was at fault",
    ));
    out.push(Section {
        title: "Tension T → 0",
        intro: format!(
            "With T = 0 the string wave speed c = sqrt(T/ρA) is {c0} m/s, so V0/c is undefined: `summary.json` writes `speed_ratio: null` and the terminal `V0/c = n/a`. A pure beam's flexural waves are dispersive, with phase speeds from 0 upwards, so every moving load meets a wave of its own speed, of length ℓ* = 2π·sqrt(EI/ρA)/V ({:.2} m at the reference's 100 m/s, five elements of the bundled mesh).",
            ell(100.0)
        ),
        cases,
    });

    // 4. T large
    let t_big = vec![format!("beam.tension={:e}", T_REF * 1e3)];
    let taut_why = "the wire becomes a very stiff string (V0/c = 0.02), so the force stays within a few newtons of its static 59 N; no warning either that T/EA > 1, a strain beyond the model's small-strain premise";
    let mut cases = all_forms(
        "T × 1e3",
        "reference",
        &t_big,
        &finest("reference", &t_big),
        [Accurate; 4],
        [taut_why; 4],
    );
    cases.push(force_case(
        "moving force, T × 1e3",
        "moving_force_beam",
        &[&format!("beam.tension={:e}", T_REF * 1e3)],
        Accurate,
        "the deflection is quasi-static and small",
    ));
    out.push(Section {
        title: "Tension T very large (× 1e3)",
        intro: format!(
            "T = 3e7 N gives c = {:.0} m/s and V0/c = {:.3}. It is also T/EA = {:.2} (EA = {ea:.3e} N): the axial strain the model assumes small is 149 %, a physical absurdity that taut reports in `summary.json` (`tension_ratio`) but does not warn about; the numerics are unaffected.",
            c * (1e3f64).sqrt(),
            100.0 / (c * (1e3f64).sqrt()),
            T_REF * 1e3 / ea
        ),
        cases,
    });

    // 5. m → 0
    let m0 = sets(&["carrier.mass=1e-6"]);
    let m0_why = "with no inertia the contact point follows the wire, the force is k(δ0 − w) every step and is smoother (osc ≈ 0) than the bundled 1 kg mass's (0.18): the unresolved 0.2 ms mass–spring mode is never excited and no multiplier oscillates";
    let m0_pen = "as for Lagrange, with W dominated by the spring (1/A_q), so the relative κ = 1000/W is only about 5e5 N/m and the penetration is 0.07 mm";
    let mut cases = all_forms(
        "m = 1e-6 kg",
        "reference",
        &m0,
        &fine_step("reference", &m0),
        [Accurate; 4],
        [m0_why, m0_pen, m0_why, m0_why],
    );
    let m0_t2 = sets(&["carrier.mass=1e-6", "time.end=1.0"]);
    let t2_why = "the standing massless contact point feels the returning waves as a smooth change of k(δ0 − w), with no step-to-step oscillation";
    cases.extend(all_forms(
        "m = 1e-6 kg, stationary (T2, 1 s)",
        "t2_stationary_mass",
        &m0_t2,
        &fine_step("t2_stationary_mass", &m0_t2),
        [Accurate; 4],
        [t2_why, m0_pen, t2_why, t2_why],
    ));
    out.push(Section {
        title: "Carrier mass m → 0 (1e-6 kg)",
        intro: "A massless contact point: the mass–spring's own period 2π·sqrt(m/k) is 0.2 ms, two steps of 1e-4 s, so its mode is not resolved and a Lagrange multiplier might ring from step to step. The `osc` column measures that: Σ|λ_{n+1} − λ_n| / Σ|λ_n| is 0.18 for the bundled 1 kg case (its force is rough at re-contacts) and would exceed 1 for a multiplier alternating in sign. The reference is Lagrange at Δt = 1e-5 s, which resolves the 0.2 ms period.".into(),
        cases,
    });

    // 6. k → ∞
    let k_big = sets(&["carrier.stiffness=1e9"]);
    let k_same_force = vec![
        "carrier.stiffness=1e9".to_string(),
        format!("carrier.preload={:e}", K_REF * PRELOAD_REF / 1e9),
    ];
    let k_why = "the carrier starts at the clamped end, where the support takes the whole 5e7 N preload force k·δ0 (that dominates the mean); off the support the spring punches the wire almost a metre deep and the mass then bounces, out of contact 41 % of the time; the figures hold as Δt falls tenfold to resolve the 0.2 ms spring";
    let k_imp = "the velocity-level Delassus number turns negative on the last step, at the far support; the advice works (with Δt = 1e-5 s the run completes)";
    let k_rigid = "a rigid carrier whose 49 N preload is relieved by a 5e-8 m deflection keeps only 2.9 N on average and loses contact 41 % of the time, converged in Δt";
    let mut cases = all_forms(
        "k = 1e9 N/m, δ0 = 0.05 m",
        "reference",
        &k_big,
        &fine_step("reference", &k_big),
        [Accurate, Accurate, Accurate, Stopped],
        [k_why, k_why, k_why, k_imp],
    );
    cases.extend(all_forms(
        "k = 1e9 N/m, k·δ0 = 49.35 N",
        "reference",
        &k_same_force,
        &fine_step("reference", &k_same_force),
        [Accurate, Accurate, Accurate, Stopped],
        [k_rigid, k_rigid, k_rigid, k_imp],
    ));
    out.push(Section {
        title: "Spring stiffness k → ∞ (1e9 N/m)",
        intro: "Two readings: the bundled preload δ0 = 0.05 m (so the preload force k·δ0 is 5e7 N), and the bundled preload force k·δ0 = 49.35 N (δ0 = 4.9e-8 m), the limit of a rigid carrier. Either way the mass–spring period is 0.2 ms (two steps), so the reference is Lagrange at Δt = 1e-5 s.".into(),
        cases,
    });

    // 7. V0 > c
    let mut cases = Vec::new();
    let supersonic_uni = "above c the mass outruns its own waves and bounces (P_l ≈ 0.13); P_l and the mean agree with the finest run, the peaks do not";
    let bil_12 = "a mass held on the wire above c is physically unstable (anomalous Doppler waves), and at 1.2c the growth is slow enough to reach the far support before the 1e3 × force bound would stop the run: the force grows from 60 N to 10⁴ N over the last fifth of the span, alternates sign from step to step there (osc > 1.5), and its mean changes by 15 % between N = 800 and 1600; the instability the 2c run diagnoses goes unmentioned here";
    let bil_12_imp = "the velocity-level law lets the held mass drift (0.7 mm) and keeps the force smoother, but the case is the same undiagnosed, unconverged instability as for Lagrange, and the agreement of the mean is a coincidence (at N = 800, Δt = 5e-5 s impact gives 51 N)";
    let fast_uni = "at 2c the mass is airborne 70 % of the time and its bouncing is sensitive to tiny changes (changing V0 by 7e-7 of itself moves the bundled Lagrange mean from 60.5 N to 69.3 N), so P_l and the mean are meaningful only to about 10 %, which nothing reports";
    let bil_2 = "a held mass at 2c is unstable and its force reaches the 1e3 × bound within 0.08 s; the message names the physical instability";
    for (factor, name) in [(1.2, "1.2c"), (2.0, "2c")] {
        for kind in ["unilateral", "bilateral"] {
            let physics = vec![
                format!("carrier.speed.cruise={:.4}", factor * c),
                format!("contact.kind={kind}"),
            ];
            let (expect, why) = match (name, kind) {
                ("1.2c", "unilateral") => ([Accurate; 4], [supersonic_uni; 4]),
                ("1.2c", _) => ([IllDetermined; 4], [bil_12, bil_12, bil_12, bil_12_imp]),
                ("2c", "unilateral") => ([IllDetermined; 4], [fast_uni; 4]),
                _ => ([Stopped; 4], [bil_2; 4]),
            };
            cases.extend(all_forms(
                &format!("V0 = {name}, {kind}"),
                "reference",
                &physics,
                &finest("reference", &physics),
                expect,
                why,
            ));
        }
    }
    for (factor, name) in [(1.2, "1.2c"), (2.0, "2c")] {
        for n in [50, 400] {
            let (expect, why) = match (name, n) {
                ("1.2c", 50) => (
                    SilentlyWrong,
                    "under a supersonic force the exact deflection under the load is zero (the wake trails behind with slope F/(ρA(V² − c²))), and 1 m linear elements smear that kink into millimetres of error; it shrinks with h, but nothing warns at this mesh",
                ),
                (_, 50) => (
                    Accurate,
                    "at 2c the wake's slope F/(ρA(V² − c²)) is seven times smaller than at 1.2c, and the kink error of 1 m elements smaller still",
                ),
                _ => (
                    Accurate,
                    "with elements eight times shorter the kink error all but vanishes",
                ),
            };
            cases.push(force_case(
                &format!("moving force on a string, V = {name}, N = {n}"),
                "moving_force_string",
                &[
                    &format!("carrier.speed.value={:.4}", factor * c),
                    "time.end=carrier_leaves",
                    &format!("mesh.elements={n}"),
                ],
                expect,
                why,
            ));
        }
    }
    out.push(Section {
        title: "Carrier speed above the wave speed (V0 > c)",
        intro: format!(
            "c = sqrt(T/ρA) = {c:.2} m/s for the reference wire; V0 = 1.2c = {:.2} m/s and 2c = {:.2} m/s (the runs end sooner, as the carrier leaves sooner). A mass held on the wire (bilateral) above c can be physically unstable; a moving force cannot.",
            1.2 * c,
            2.0 * c
        ),
        cases,
    });

    // 8. Δt
    let mut cases = Vec::new();
    let dt2 = "steps that move the carrier 1 m (8 elements), twelve times the time a wave takes to cross an element, filter out the wire's waves: the force is smooth, the 9 loss intervals of the bundled run are all missed, and nothing warns that the step is far above the element-crossing time";
    let dt3 = "10 cm steps (0.8 element) still miss the reflected waves that lift the wire off the mass near the far support: no loss at all, and nothing warns";
    let dt3_imp = "with V·Δt = 0.8 h the convective term outweighs the velocity-level Delassus number and the law stops, telling the user to reduce Δt";
    let dt6 =
        "over the ramp (no loss) every law agrees with the bundled step to four digits in the mean";
    for (dt, expect, why) in [
        ("1e-2", [SilentlyWrong; 4], [dt2; 4]),
        (
            "1e-3",
            [SilentlyWrong, SilentlyWrong, SilentlyWrong, Stopped],
            [dt3, dt3, dt3, dt3_imp],
        ),
    ] {
        cases.extend(all_forms(
            &format!("Δt = {dt} s"),
            "reference",
            &[format!("time.step={dt}")],
            &bundled("reference", &none, ""),
            expect,
            why,
        ));
    }
    let short = sets(&["time.end=0.05"]);
    cases.extend(all_forms(
        "Δt = 1e-6 s, t_end = 0.05 s",
        "reference",
        &with(&short, &["time.step=1e-6"]),
        &bundled("reference", &short, ", t_end = 0.05 s"),
        [Accurate; 4],
        [dt6; 4],
    ));
    cases.push(one(
        "Δt = 1e-6 s, whole run",
        "lagrange",
        "reference",
        sets(&["time.step=1e-6", "contact.formulation=lagrange"]),
        bundled("reference", &none, ""),
        Accurate,
        "P_l and the mean hold at a hundredth of the bundled step, while the re-contact peak near the far support grows to about 4.5e4 N, the documented Δt-dependence of the study's model (formulations.md)",
    ));
    for (dt, why) in [
        (
            "1e-2",
            "the deflection under a force at half the wave speed is nearly quasi-static, so even 60 steps follow it",
        ),
        ("1e-3", "a quasi-static response, well followed"),
        (
            "1e-6",
            "the time error vanishes and the small mesh error remains",
        ),
    ] {
        cases.push(force_case(
            &format!("moving force on a beam, Δt = {dt} s"),
            "moving_force_beam",
            &[&format!("time.step={dt}")],
            Accurate,
            why,
        ));
    }
    out.push(Section {
        title: "Time step Δt far above and below the accuracy and stability scales",
        intro: "The bundled Δt = 1e-4 s moves the carrier 1 cm (0.08 element) per step at cruise, and a wave crosses an element in 0.83 ms. Δt = 1e-2 s moves the carrier 1 m (8 elements) per step, though it still resolves the 0.2 s mass–spring period; Δt = 1e-3 s moves it 0.8 element per step. Generalized-α with ρ∞ = 1 is unconditionally stable, so nothing can blow up from the step alone; the question is whether a too-coarse step is noticed. Δt = 1e-6 s is run over the ramp (0.05 s) for every law, and once over the whole run with Lagrange.".into(),
        cases,
    });

    // 9. Mesh
    let mut cases = Vec::new();
    let n4 = "12.5 m elements cannot carry the short waves that lift the wire off the mass: the force is smooth, no loss is found, and nothing warns";
    let n40 = "1.25 m elements distort the reflected waves and add a spurious excitation at each node crossing: P_l is two to four times the converged value, and nothing warns";
    let n1e4 = "5 mm elements and 20 000 unknowns raise no difficulty over the ramp (no loss), and agree with the bundled mesh";
    for (n, expect, why) in [
        ("4", [SilentlyWrong; 4], [n4; 4]),
        (
            "40",
            [SilentlyWrong, SilentlyWrong, SilentlyWrong, Marginal],
            [
                n40,
                n40,
                n40,
                "the velocity-level law softens the spurious re-contacts, so P_l is less than twice the converged value; nothing warns",
            ],
        ),
    ] {
        cases.extend(all_forms(
            &format!("N = {n}"),
            "reference",
            &[format!("mesh.elements={n}")],
            &bundled("reference", &none, ""),
            expect,
            why,
        ));
    }
    cases.extend(all_forms(
        "N = 10⁴, t_end = 0.05 s",
        "reference",
        &with(&short, &["mesh.elements=10000"]),
        &bundled("reference", &short, ", t_end = 0.05 s"),
        [Accurate; 4],
        [n1e4; 4],
    ));
    cases.push(one(
        "N = 10⁴, whole run",
        "lagrange",
        "reference",
        sets(&["mesh.elements=10000", "contact.formulation=lagrange"]),
        bundled("reference", &none, ""),
        Accurate,
        "over the whole run the fine mesh confirms the bundled P_l and mean",
    ));
    cases.push(force_case(
        "moving force on a beam, N = 4",
        "moving_force_beam",
        &["mesh.elements=4"],
        Marginal,
        "four cubic elements still carry the quasi-static bulge under the load, to several per cent",
    ));
    cases.push(force_case(
        "moving force on a beam, N = 10⁴",
        "moving_force_beam",
        &["mesh.elements=10000"],
        Accurate,
        "the mesh error vanishes; what remains is the time error of Δt = 4e-4 s",
    ));
    out.push(Section {
        title: "Meshes from 4 to 10⁴ elements",
        intro: "N = 4 gives 12.5 m elements on the 50 m span; N = 10⁴ gives 5 mm elements and 20 000 unknowns. 10⁴ elements are run over the ramp (0.05 s) for every law, and once over the whole run with Lagrange.".into(),
        cases,
    });

    // 10. Penalty κ
    let mut cases = Vec::new();
    let kappas = [
        (
            "stiffness=1e2",
            "κ = 1e2 N/m",
            SilentlyWrong,
            "a penalty spring softer than the carrier spring (k = 987 N/m) lets the mass sink 11 cm into the wire, more than the preload, so the force is that of two springs in series, a tenth of the true one; only the reported max penetration betrays it",
        ),
        (
            "stiffness=1e4",
            "κ = 1e4 N/m",
            SilentlyWrong,
            "1 cm of penetration (a fifth of the preload) cushions every re-contact, removes all contact loss and lowers the mean; only the max penetration betrays it",
        ),
        (
            "stiffness=1e8",
            "κ = 1e8 N/m",
            Accurate,
            "κ is five times the contact's own stiffness 1/W ≈ 2e7 N/m, so the peaks soften but P_l and the mean hold",
        ),
        (
            "stiffness=1e12",
            "κ = 1e12 N/m",
            Accurate,
            "the penetration is 0.6 nm and the force Lagrange's to four digits",
        ),
        (
            "stiffness=1e16",
            "κ = 1e16 N/m",
            Accurate,
            "no ill-conditioning appears: for one contact the law only adds 1/κ = 1e-16 m/N to the scalar W ≈ 5e-8 m/N, and the penetration is λ/κ",
        ),
        (
            "relative=1e14",
            "relative ρ = 1e14 (κ = ρ/W)",
            Accurate,
            "1/κ = W/ρ changes W by 1e-14 of itself, so the run is Lagrange's to the digits shown",
        ),
    ];
    for (set, label, expect, why) in kappas {
        cases.push(one(
            label,
            "penalty",
            "reference",
            sets(&[
                "contact.formulation=penalty",
                &format!("contact.penalty.{set}"),
            ]),
            bundled("reference", &none, ""),
            expect,
            why,
        ));
    }
    out.push(Section {
        title: "Penalty stiffness κ from soft to ill-conditioned",
        intro: "W_cc ≈ 5e-8 m/N at the bundled resolution, so the contact's own stiffness 1/W is about 2e7 N/m. κ = 1e16 N/m and ρ = 1e14 are 1e9 and 1e14 times stiffer than that; κ = 1e2 N/m is softer than the carrier spring (k = 987 N/m).".into(),
        cases,
    });

    // 11. alpha placement
    let mut cases = Vec::new();
    let a_uni = "the α-level constraint leaves an undamped step-to-step gap mode that the moving contact point feeds, so the contact chatters (P_l ≈ 0.66–0.69 instead of 0.006), and the chatter warning says so";
    let a_imp = "the velocity-level law imposes ġ at t_{n+1}; `alpha` changes only its index set, so the answer stays that of `end`";
    let a_bil = "the undamped step-to-step mode grows without bound, and the message names the placement as the cause";
    for kind in ["unilateral", "bilateral"] {
        let physics = vec![format!("contact.kind={kind}")];
        let (expect, why) = if kind == "unilateral" {
            (
                [Flagged, Flagged, Flagged, Accurate],
                [a_uni, a_uni, a_uni, a_imp],
            )
        } else {
            (
                [Stopped, Stopped, Stopped, Accurate],
                [a_bil, a_bil, a_bil, a_imp],
            )
        };
        for ((form, expect), why) in FORMULATIONS.iter().zip(expect).zip(why) {
            let base = with(&physics, &[&format!("contact.formulation={form}")]);
            cases.push(one(
                &format!("alpha, {kind}, moving"),
                form,
                "reference",
                with(&base, &["contact.placement=alpha"]),
                Check::Run {
                    scene: "reference",
                    sets: base.clone(),
                    name: format!("the same {form} run with placement `end`"),
                    also: vec![("under a 1e-6 change of g", with(&base, &[PERTURBED_G]))],
                },
                expect,
                why,
            ));
        }
    }
    let t2 = sets(&["time.end=1.0", "contact.formulation=lagrange"]);
    cases.push(one(
        "alpha, unilateral, stationary (T2, 1 s)",
        "lagrange",
        "t2_stationary_mass",
        with(&t2, &["contact.placement=alpha"]),
        Check::Run {
            scene: "t2_stationary_mass",
            sets: t2.clone(),
            name: "the same run with placement `end`".into(),
            also: vec![("under a 1e-6 change of g", with(&t2, &[PERTURBED_G]))],
        },
        Accurate,
        "a standing carrier has r_f = r_g, so both placements impose the same condition",
    ));
    out.push(Section {
        title: "The `alpha` constraint placement with a moving carrier",
        intro: "`alpha` imposes the gap at t_{n+1−α_f}; with ρ∞ = 1 any gap error alternates in sign undamped, and a moving contact point feeds it ([numerics.md](numerics.md) §4). Each row is scored against the same formulation with placement `end`, so the column isolates the placement.".into(),
        cases,
    });
    out
}
