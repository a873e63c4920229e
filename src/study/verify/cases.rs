//! The declared verification cases (`taut verify`): each a bundled scene
//! that names its reference, its ladders and its expected orders.

use super::case::{Case, Combo, Expect, Ladder, Quantity, Space, Variable};
use crate::scene::{Formulation, Support};

/// Allowed |observed − formal| for a smooth case: the ladders are chosen
/// in the asymptotic range, where successive orders agree to ±0.1; 0.3
/// leaves room for the ladder's first level and still separates order 2
/// from 1.5 (unresolved modes) and 4 from 3.
pub(crate) const ORDER_TOL: f64 = 0.3;

use Support::{Clamped, Free, Pinned};

/// Every support pair a beam case runs under (mirror images behave alike).
const BEAM_SUPPORTS: [(Support, Support); 6] = [
    (Pinned, Pinned),
    (Clamped, Pinned),
    (Clamped, Clamped),
    (Clamped, Free),
    (Pinned, Free),
    (Free, Free),
];

/// Allowed |observed − tail order| of a J ladder: the discrete solution
/// also carries the moving contact's coupling of the modes (as
/// [`MOVING_CONTACT_TOL`]), which moves the pre-asymptotic constant.
pub(crate) const TAIL_TOL: f64 = 0.5;

/// Allowed |observed − formal| of an h or J ladder with a moving contact:
/// the mass's path has a curvature jump at every node of C¹ elements (and
/// a truncated basis's ripple in J), a zero-mean force oscillation at V/h
/// whose effect on the error depends on where the nodes fall, so
/// successive orders scatter by about ±0.6 around the formal one (measured
/// 3.2–4.4 for the displacement's 4, 2.1–2.7 for the force's 2).
pub(crate) const MOVING_CONTACT_TOL: f64 = 0.5;

/// Methods that leave a moving contact's constraint oscillation undamped
/// (trapezoidal at the contact point, α_f = 0): measured on `mms_beam_time`.
fn undamped_constraint(method: &str) -> bool {
    matches!(method, "newmark" | "wbz")
}

/// No formal order: a method of one's own that declares none.
fn undeclared() -> Expect {
    Expect::Report("the method declares no formal order in Δt".into())
}

/// The expected orders of the manufactured beam cases with a moving mass
/// (`docs/verification.md` gives the measurements behind each exception).
fn expect_moving_mass(c: &Combo, v: Variable, q: Quantity) -> Expect {
    let f = c.formulation;
    if undamped_constraint(c.method) && f != Formulation::Impact {
        return Expect::Cannot(format!(
            "{}: α_f = 0 imposes the gap and the force at t_{{n+1}} with no dissipation, so the moving contact excites an undamped constraint oscillation that grows as Δt falls (measured: errors rise 10⁴× over the ladder; the run warns, MODEL §5); with contact.formulation = impact it converges",
            c.method
        ));
    }
    let formal = match v {
        Variable::Dt => c.time_order.unwrap_or(f64::NAN),
        Variable::H if q == Quantity::Displacement => 4.0,
        _ => 2.0,
    };
    if c.method == "central_difference" && c.space == Space::Graded && v == Variable::Dt {
        return Expect::Cannot(
            "central difference on a graded mesh: the stable step of its shortest element makes the time error negligible next to the space error of its longest".into(),
        );
    }
    if c.method == "central_difference" && f == Formulation::Impact {
        return Expect::Known {
            order: formal,
            why: "central difference with the impact law: ġ = 0 is imposed on its half-step velocity v_{n+1/2} at x_m(t_{n+1}), an O(Δt) mismatch, so it is first order in Δt (measured 1.00 on mms_beam_time at N = 32: `taut converge scenes/verify/mms_beam_time.toml --refine step --levels 4 --set time.step=4e-5 --set 'integrator={method=\"central_difference\"}' --set contact.formulation=impact`; on the 200 Hz case its second-order term still dominates) and that error swamps h and J ladders".into(),
        };
    }
    match (v, q) {
        (Variable::Dt, _) if c.time_order.is_none() => undeclared(),
        (Variable::Dt, Quantity::Force) if f == Formulation::Penalty => Expect::Cannot(
            "penalty: the contact starts unloaded (λ = 0 until it penetrates) while λ*(0) = kδ0 + mg, a jump that rings the stiff penalty spring with no dissipation at the contact: the force error (≈ 2e-2 N here) does not fall with Δt; the displacement converges".into(),
        ),
        (Variable::Dt, Quantity::Force) if c.method == "central_difference" => Expect::Cannot(
            "central difference: at its stable steps Δt² ∝ h⁴, while the contact force's space error ∝ h² (the mass's path has a curvature jump at every node): the force's time error is below its space error on every mesh".into(),
        ),
        (Variable::Dt, Quantity::Force) if c.method == "bathe" && f != Formulation::Impact => {
            Expect::Known {
                order: formal,
                why: "Bathe's contact force at force level converges at 1.15–1.53 in Δt with a moving contact (mms_beam_time, quick matrix: hermite 1.35/1.39, graded 1.51/1.53, galerkin 1.19/1.24, modal 1.15/1.22 pinned–pinned/clamped–pinned); second order with a standing contact and with the impact law, and its displacement is second order. The error is smooth in time (no step-to-step oscillation); its cause is not found: a documented deviation, not failed".into(),
            }
        }
        (Variable::Dt, _) => Expect::Order {
            order: formal,
            tol: ORDER_TOL,
        },
        (Variable::H | Variable::J, _) if f == Formulation::Penalty => Expect::Cannot(
            "penalty: the penetration λ/κ (κ = relative/W, W ∝ Δt²) does not fall with h or J: the error floor is set by κ and Δt".into(),
        ),
        (Variable::H, _) => Expect::Order {
            order: formal,
            tol: MOVING_CONTACT_TOL,
        },
        (Variable::J, Quantity::Displacement) => Expect::ModalTail { tol: TAIL_TOL },
        (Variable::J, Quantity::Force) => Expect::Report(
            "the force's order in J follows the modal decay of v*'s curvature along the carrier's path (V²w_xx, m ẅ): a property of the solution, not of the basis".into(),
        ),
    }
}

fn beam_time_ladders(space: Space, c: &Combo) -> Vec<Ladder> {
    // a graded mesh's longest element is about twice the uniform one's
    let (elements, modes) = match space {
        Space::Hermite => (64, 0),
        Space::Graded => (128, 0),
        Space::Galerkin => (1, 64),
        Space::Modal => (64, 64),
    };
    // modal_exact's force error at a Δt is far below the others' (no
    // phase error in any mode): from 1e-3 s its finest force error was
    // within 3× of the basis's own (J = 64 → 128 moved it by a third,
    // measured), so its ladder starts one level coarser and stops at
    // 5e-4 s (at 2.5e-4 s the clamped–pinned modal basis still made 26 %)
    let (dt, levels) = if c.method == "modal_exact" {
        (2e-3, 3)
    } else {
        (1e-3, 4)
    };
    vec![Ladder {
        variable: Variable::Dt,
        levels,
        elements,
        dt,
        modes,
        end: None,
        fixed_exact: false,
    }]
}

/// The explicit case's Δt ladders: N = 16 (J = 16), from below the stable
/// step ([`super::fit_explicit`]).
fn explicit_ladders(space: Space, _: &Combo) -> Vec<Ladder> {
    let (elements, modes) = match space {
        Space::Galerkin => (1, 16),
        Space::Modal => (16, 16),
        _ => (16, 0),
    };
    vec![Ladder {
        variable: Variable::Dt,
        levels: 3,
        elements,
        dt: 1e-3,
        modes,
        end: None,
        fixed_exact: false,
    }]
}

/// The string case: a Δt ladder on a fine mesh and a space ladder at a
/// fine step (string elements: a mesh of N has N − 1 unknowns).
fn string_ladders(space: Space, _: &Combo) -> Vec<Ladder> {
    // string elements are second order in h: a fine mesh for the Δt ladder
    let (elements, modes) = match space {
        Space::Galerkin => (1, 64),
        Space::Modal => (512, 64),
        _ => (512, 0),
    };
    let time = Ladder {
        variable: Variable::Dt,
        levels: 4,
        elements,
        dt: 1e-3,
        modes,
        end: None,
        fixed_exact: false,
    };
    let space_ladder = match space {
        Space::Galerkin | Space::Modal => Ladder {
            variable: Variable::J,
            levels: 4,
            elements: 256,
            dt: 5e-5,
            modes: 4,
            end: None,
            fixed_exact: false,
        },
        _ => Ladder {
            variable: Variable::H,
            levels: 4,
            elements: 8,
            dt: 5e-5,
            modes: 0,
            end: None,
            fixed_exact: false,
        },
    };
    vec![time, space_ladder]
}

/// The two-wire case's expected orders: those of the moving-mass beam
/// cases, but the contact force's h order is reported, not judged: it
/// converged at 2.84 over N = 8 → 64 (every law, generalized-α and HHT),
/// above the formal 2 that the node kicks set as a bound, so neither
/// `MOVING_CONTACT_TOL` around 2 nor a claim of 3 would be honest.
fn expect_two_wires(c: &Combo, v: Variable, q: Quantity) -> Expect {
    if c.method == "central_difference" && v == Variable::Dt && q == Quantity::Displacement {
        return Expect::Cannot(
            "central difference on mms_two_wires: at its stable steps Δt² ∝ h⁴, and this smooth motion's time error stays about the mesh's (2.3e-9 against 4.2e-8 m at N = 32, Δt = 2e-5 s), so a Δt ladder against the exact solution measures the mesh; its order is measured by differences of runs on one mesh instead, 2.00 on both wires (`cargo test --release --test numerics mms_two_wires::central_difference`)".into(),
        );
    }
    force_in_h_reported(
        expect_moving_mass(c, v, q),
        (v, q),
        "2.84 over N = 8 → 64 on mms_two_wires",
    )
}

/// `base` (a moving-mass case's expectation), except that a judged order
/// of the contact force in h becomes a report of the `measured` one: the
/// node kicks under a moving contact set the formal 2 only as a bound. A
/// combination that cannot converge (penalty's floor, α_f = 0 with a
/// force-level law) keeps its `cannot`.
fn force_in_h_reported(base: Expect, (v, q): (Variable, Quantity), measured: &str) -> Expect {
    match (v, q, &base) {
        (Variable::H, Quantity::Force, Expect::Order { .. }) => Expect::Report(format!(
            "the contact force in h: measured {measured} (the formal 2 is the bound of the node kicks under a moving contact; the displacement's 4 is the judged order)"
        )),
        _ => base,
    }
}

/// The two-wire case (`mms_two_wires`): a Δt ladder at N = 64 and an h
/// ladder N = 8 → 64 at Δt = 5e-6 s, Hermite only (the messenger is
/// carried on `hermite` alone, `resolve::messenger`); N stays even, so the
/// messenger's interior support at L/2 is a node on every level. At
/// Δt = 2.5e-5 s (the beam cases' step) the time error (≈ 2e-9 m) was most
/// of the N = 64 level's (measured: orders 4.7, 3.5, 2.9 per halving); at
/// 5e-6 s 4.7, 3.4, 4.0 (8 → 64: 4.0).
fn two_wire_ladders(space: Space, _: &Combo) -> Vec<Ladder> {
    if space == Space::Modal {
        // the modes of the two-line model: a J ladder 8 → 64 on N = 32
        // (127 unknowns) at the h ladder's step, and the Δt ladder on the
        // Hermite ladder's N = 64 with all its 255 modes (the element model
        // in its eigenbasis: at J = 64 on N = 32 the truncation made 72 % of
        // the finest error, measured orders 1.49 / 1.12)
        return vec![
            Ladder {
                variable: Variable::J,
                levels: 4,
                elements: 32,
                dt: 5e-6,
                modes: 8,
                end: None,
                fixed_exact: false,
            },
            Ladder {
                variable: Variable::Dt,
                levels: 4,
                elements: 64,
                dt: 1e-3,
                modes: 255,
                end: None,
                fixed_exact: false,
            },
        ];
    }
    vec![
        // at N = 32 the mesh made 29–32 % of the finest force error
        Ladder {
            variable: Variable::Dt,
            levels: 4,
            elements: 64,
            dt: 1e-3,
            modes: 0,
            end: None,
            fixed_exact: false,
        },
        Ladder {
            variable: Variable::H,
            levels: 4,
            elements: 8,
            dt: 5e-6,
            modes: 0,
            end: None,
            fixed_exact: false,
        },
    ]
}

/// The attachment case's expected orders: those of the moving-mass beam
/// cases, but where those judge the contact force's h order it is
/// reported, as on the two wires: it converged at 2.62–2.65 over
/// N = 8 → 64 (every method and law whose force converges here), above the
/// formal 2 that the node kicks set as a bound.
fn expect_attachments(c: &Combo, v: Variable, q: Quantity) -> Expect {
    force_in_h_reported(
        expect_moving_mass(c, v, q),
        (v, q),
        "2.62–2.65 over N = 8 → 64 on mms_attachments",
    )
}

/// The attachment case (`mms_attachments`): a Δt ladder of 3 levels at
/// N = 128 and an h ladder N = 8 → 64 at Δt = 5e-6 s, Hermite only. At
/// N = 64 the contact force's space error (1.8e-5 N, order 2 in h) was
/// most of the Δt ladder's finest force error (measured Δt orders 1.91,
/// 1.56, 1.26), so the Δt ladder runs at N = 128 and stops at 2.5e-4 s.
fn attachment_ladders(_: Space, _: &Combo) -> Vec<Ladder> {
    vec![
        Ladder {
            variable: Variable::Dt,
            levels: 3,
            elements: 128,
            dt: 1e-3,
            modes: 0,
            end: None,
            fixed_exact: false,
        },
        Ladder {
            variable: Variable::H,
            levels: 4,
            elements: 8,
            dt: 5e-6,
            modes: 0,
            end: None,
            fixed_exact: false,
        },
    ]
}

/// The loss case: a Δt ladder at N = 64 and an h ladder at Δt = 2.5e-5 s.
fn loss_ladders(space: Space, c: &Combo) -> Vec<Ladder> {
    let mut l = beam_time_ladders(space, c);
    l.extend(beam_space_ladders(space, c));
    l
}

/// The expected orders of the loss case: those of the moving mass for the
/// displacement in Δt; the force and the space ladders are reported, since
/// the contact bounces at reattachment (`docs/verification.md`).
fn expect_loss(c: &Combo, v: Variable, q: Quantity) -> Expect {
    let base = expect_moving_mass(c, v, q);
    if !matches!(base, Expect::Order { .. } | Expect::ModalTail { .. }) {
        return base;
    }
    let bounce = "with no impact law (MODEL §6) the discrete contact reattaches with the small approach velocity its free flight left and bounces, more often as Δt falls (gen-α on galerkin: 1, 1, 2 loss intervals at Δt = 5e-4 … 1.25e-4 s; HHT 3, 2, 15; Bathe 2, 2, 6) although the exact reattachment is smooth";
    match (v, q) {
        (Variable::Dt, Quantity::Displacement) if c.formulation == Formulation::Penalty => {
            Expect::Cannot(format!(
                "penalty with a loss: release and reattachment lag by the penetration λ/κ, and {bounce}: measured orders 1.4–1.8"
            ))
        }
        (Variable::Dt, Quantity::Displacement) if c.method == "hht" => Expect::Known {
            order: c.time_order.unwrap_or(f64::NAN),
            why: format!(
                "HHT: {bounce}; at its finest step on galerkin pinned–pinned the bounces raise the error (order 0.9 there, 2.0 elsewhere)"
            ),
        },
        (Variable::Dt, Quantity::Displacement) => base,
        _ => Expect::Report(format!(
            "the error is set by the bounces at reattachment, not by the refined variable: {bounce}"
        )),
    }
}

/// The expected orders of the string case: a standing contact (no node
/// kicks), string elements second order in h.
fn expect_standing_string(c: &Combo, v: Variable, q: Quantity) -> Expect {
    let f = c.formulation;
    if f == Formulation::Penalty && undamped_constraint(c.method) {
        return Expect::Cannot(format!(
            "{} with penalty: the contact starts unloaded (λ = 0 until it penetrates) while λ*(0) = kδ0 + mg, and the jump rings the stiff penalty spring with no dissipation at all (α_f = 0): the displacement error does not fall with Δt (measured orders −0.1 … −0.2)",
            c.method
        ));
    }
    match (v, q) {
        (Variable::Dt, _) if c.time_order.is_none() => undeclared(),
        (Variable::Dt, Quantity::Force) if f == Formulation::Penalty => Expect::Cannot(
            "penalty: the contact starts unloaded (λ = 0 until it penetrates) while λ*(0) = kδ0 + mg, a jump that rings the stiff penalty spring with no dissipation at the contact: the force error does not fall with Δt".into(),
        ),
        (Variable::Dt, Quantity::Displacement) if f == Formulation::Penalty => Expect::Cannot(
            "penalty on string elements: the penetration λ/κ, κ = relative/W, depends on the mesh through W ∝ Δt² rᵀA⁻¹r (rᵀM⁻¹r ∝ 1/(ρA h)), so no mesh leaves the Δt ladder its own error (measured: doubling N changes the finest error by 74 %)".into(),
        ),
        (Variable::Dt, _) => Expect::Order {
            order: c.time_order.unwrap_or(f64::NAN),
            tol: ORDER_TOL,
        },
        (Variable::H | Variable::J, _) if f == Formulation::Penalty => Expect::Cannot(
            "penalty: the penetration λ/κ (κ = relative/W, W ∝ Δt²) does not fall with h or J: the error floor is set by κ and Δt".into(),
        ),
        (Variable::H, _) => Expect::Order {
            order: 2.0,
            tol: ORDER_TOL,
        },
        (Variable::J, Quantity::Displacement) => Expect::ModalTail { tol: TAIL_TOL },
        (Variable::J, Quantity::Force) => Expect::Report(
            "the force's order in J follows the modal decay of v* at the contact point: a property of the solution, not of the basis".into(),
        ),
    }
}

/// Δt of the space ladders, s: fine enough that every second-order
/// method's time error is below the finest space error. modal_exact's
/// force held over the step leaves a larger time error in w than the
/// others' at 2.5e-5 s (a J = 32 modal basis with a free end: 1.42e-10 m
/// against their 0.95–1.06e-10 m, its order 4.50 against a tail of 5.02),
/// and its steps are cheap: half that.
fn space_dt(c: &Combo) -> f64 {
    if c.method == "modal_exact" {
        1.25e-5
    } else {
        2.5e-5
    }
}

/// Levels of a J ladder: 4 (J = 4 … 32), 3 on a free–free modal basis,
/// whose J = 32 level reaches 2.8e-11 m, where the time error at the
/// ladder's Δt made 45 % of it (measured, generalized-α) once the basis's
/// modes were refined (issue 22): its order is that of J = 4 … 16.
fn free_free_modal_levels(space: Space, c: &Combo) -> usize {
    if space == Space::Modal && c.supports == (Support::Free, Support::Free) {
        3
    } else {
        4
    }
}

fn beam_space_ladders(space: Space, c: &Combo) -> Vec<Ladder> {
    let dt = space_dt(c);
    vec![match space {
        Space::Hermite | Space::Graded => Ladder {
            variable: Variable::H,
            levels: 4,
            elements: 8,
            dt,
            modes: 0,
            end: None,
            fixed_exact: false,
        },
        // the FE mesh of a modal basis: 256 unknowns, so J ≤ 32 is a truncation
        Space::Galerkin | Space::Modal => Ladder {
            variable: Variable::J,
            levels: free_free_modal_levels(space, c),
            elements: 128,
            dt,
            modes: 4,
            end: None,
            fixed_exact: false,
        },
    }]
}

/// The one-dof oscillator's step response: time orders alone.
fn expect_oscillator(c: &Combo, v: Variable, _: Quantity) -> Expect {
    match (v, c.time_order) {
        (Variable::Dt, Some(p)) => Expect::Order {
            order: p,
            tol: ORDER_TOL,
        },
        (Variable::Dt, None) => undeclared(),
        _ => Expect::Cannot("one unknown: nothing to refine in space".into()),
    }
}

/// 0.2 s from Δt = 5e-4 s (ωΔt = 0.03): a first-order method's numerical
/// damping e^{−ω²Δt t/2} stays small over it, so its order is its own.
fn oscillator_ladders(_: Space, _: &Combo) -> Vec<Ladder> {
    vec![Ladder {
        variable: Variable::Dt,
        levels: 4,
        elements: 2,
        dt: 5e-4,
        modes: 0,
        end: Some(0.2),
        fixed_exact: true,
    }]
}

/// The moving force on the taut string against the series of MODEL §8:
/// string elements under a point load between nodes, first order in h.
fn expect_moving_force_string(c: &Combo, v: Variable, _: Quantity) -> Expect {
    match v {
        Variable::H => Expect::Order {
            order: 1.0,
            tol: ORDER_TOL,
        },
        _ => Expect::Cannot(format!(
            "{}: only an h ladder is declared for this case",
            c.method
        )),
    }
}

/// h from L/50 to L/400 at Δt = 5e-5 s (the error under the load is
/// first order in h and Δt's share stays below 1 %).
fn moving_force_string_ladders(_: Space, _: &Combo) -> Vec<Ladder> {
    vec![Ladder {
        variable: Variable::H,
        levels: 4,
        elements: 50,
        dt: 5e-5,
        modes: 0,
        end: None,
        fixed_exact: false,
    }]
}

/// Methods the moving-mass time cases leave to `mms_beam_explicit`.
const IMPLICIT: [&str; 1] = ["central_difference"];

/// The declared cases, in table order.
pub const CASES: [Case; 9] = [
    Case {
        name: "oscillator",
        file: "scenes/oscillator_one_dof.toml",
        text: include_str!("../../../scenes/oscillator_one_dof.toml"),
        about: "one-dof step response against the model's exact modal solution: Δt order alone",
        supports: &[],
        spaces: &[Space::Hermite],
        contact: false,
        ladders: oscillator_ladders,
        expect: expect_oscillator,
        quantities: &[Quantity::Displacement],
        quick: true,
        only: &[],
        skip: &[],
    },
    Case {
        name: "moving_force_string",
        file: "scenes/moving_force_string.toml",
        text: include_str!("../../../scenes/moving_force_string.toml"),
        about: "a force crossing a taut string against the modal series (MODEL §8): string elements under a moving point load",
        supports: &[],
        spaces: &[Space::Hermite],
        contact: false,
        ladders: moving_force_string_ladders,
        expect: expect_moving_force_string,
        quantities: &[Quantity::Displacement],
        quick: false,
        only: &[],
        skip: &[],
    },
    Case {
        name: "mms_beam_time",
        file: "scenes/verify/mms_beam_time.toml",
        text: include_str!("../../../scenes/verify/mms_beam_time.toml"),
        about: "manufactured beam motion, fast in time, with a mass–spring moving over it: Δt orders",
        supports: &BEAM_SUPPORTS,
        spaces: &Space::ALL,
        contact: true,
        ladders: beam_time_ladders,
        expect: expect_moving_mass,
        quantities: &[Quantity::Displacement, Quantity::Force],
        quick: true,
        only: &[],
        skip: &IMPLICIT,
    },
    Case {
        name: "mms_beam_explicit",
        file: "scenes/verify/mms_beam_explicit.toml",
        text: include_str!("../../../scenes/verify/mms_beam_explicit.toml"),
        about: "manufactured beam motion at 200 Hz for central difference's stable steps: its Δt orders",
        supports: &BEAM_SUPPORTS,
        spaces: &Space::ALL,
        contact: true,
        ladders: explicit_ladders,
        expect: expect_moving_mass,
        quantities: &[Quantity::Displacement, Quantity::Force],
        quick: false,
        only: &IMPLICIT,
        skip: &[],
    },
    Case {
        name: "mms_beam_space",
        file: "scenes/verify/mms_beam_space.toml",
        text: include_str!("../../../scenes/verify/mms_beam_space.toml"),
        about: "manufactured beam motion, rich in space, with a mass–spring moving over it: h and J orders",
        supports: &BEAM_SUPPORTS,
        spaces: &Space::ALL,
        contact: true,
        ladders: beam_space_ladders,
        expect: expect_moving_mass,
        quantities: &[Quantity::Displacement, Quantity::Force],
        quick: true,
        only: &[],
        skip: &[],
    },
    Case {
        name: "mms_loss",
        file: "scenes/verify/mms_loss.toml",
        text: include_str!("../../../scenes/verify/mms_loss.toml"),
        about: "manufactured motion with a prescribed loss of contact and reattachment: Δt and h orders",
        supports: &[(Pinned, Pinned), (Clamped, Pinned)],
        spaces: &[Space::Hermite, Space::Galerkin],
        contact: true,
        ladders: loss_ladders,
        expect: expect_loss,
        quantities: &[Quantity::Displacement, Quantity::Force],
        quick: false,
        only: &[],
        skip: &IMPLICIT,
    },
    Case {
        name: "mms_string",
        file: "scenes/verify/mms_string.toml",
        text: include_str!("../../../scenes/verify/mms_string.toml"),
        about: "manufactured motion of a taut string (string elements) with a standing mass–spring: Δt, h and J orders",
        supports: &[],
        spaces: &[Space::Hermite, Space::Galerkin, Space::Modal],
        contact: true,
        ladders: string_ladders,
        expect: expect_standing_string,
        quantities: &[Quantity::Displacement, Quantity::Force],
        quick: false,
        only: &[],
        skip: &[],
    },
    Case {
        name: "mms_two_wires",
        file: "scenes/verify/mms_two_wires.toml",
        text: include_str!("../../../scenes/verify/mms_two_wires.toml"),
        about: "manufactured motions of a contact wire and a messenger on an interior support coupled by four linear droppers, a mass–spring moving under the contact wire: Δt and h orders on both wires",
        supports: &[],
        spaces: &[Space::Hermite, Space::Modal],
        contact: true,
        ladders: two_wire_ladders,
        expect: expect_two_wires,
        quantities: &[Quantity::Displacement, Quantity::Force],
        quick: false,
        only: &[
            "generalized_alpha",
            "newmark",
            "hht",
            "wbz",
            "bathe",
            "moreau_jean",
            "central_difference",
        ],
        skip: &[],
    },
    Case {
        name: "mms_attachments",
        file: "scenes/verify/mms_attachments.toml",
        text: include_str!("../../../scenes/verify/mms_attachments.toml"),
        about: "manufactured motion carrying two spring + dashpot + mass attachments, one between nodes and one at a node, a mass–spring moving over the wire: Δt and h orders",
        supports: &[],
        spaces: &[Space::Hermite],
        contact: true,
        ladders: attachment_ladders,
        expect: expect_attachments,
        quantities: &[Quantity::Displacement, Quantity::Force],
        quick: false,
        // the methods that carry a damping matrix (`resolve::damping`):
        // central difference refuses it, modal_exact needs a diagonal basis
        only: &[],
        skip: &["central_difference", "modal_exact"],
    },
];
