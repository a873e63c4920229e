//! The rows of one job ([`Job`]): every ladder × quantity of its case
//! under its combination.

use super::case::{Combo, Expect, Quantity, Space, Variable};
use super::explicit::fit_explicit;
use super::job::Job;
use super::judge::judge;
use super::level::level;
use super::measure::measure;
use super::row::{Status, VerifyRow};
use crate::error::Result;
use crate::scene::{Scene, Scheme, Support, scene_with_overrides};

/// The support pair's name, `pinned-free`.
pub(super) fn supports_name((l, r): (Support, Support)) -> String {
    format!("{l:?}-{r:?}").to_lowercase()
}

/// The scene of one combination, before its ladder's levels.
pub(super) fn base_scene(j: &Job) -> Result<Scene> {
    let mut o: Vec<String> = Vec::new();
    if let Some((l, r)) = j.supports {
        o.push(format!("beam.left={}", format!("{l:?}").to_lowercase()));
        o.push(format!("beam.right={}", format!("{r:?}").to_lowercase()));
    }
    if let Some(f) = j.formulation {
        o.push(format!("contact.formulation={}", f.name()));
    }
    let mut scene = scene_with_overrides(j.case.text, &o)?;
    if let Some(spec) = j.factory.integrator(&scene.integrator) {
        scene.integrator = spec;
    }
    Ok(scene)
}

/// The rows of one job: every ladder × quantity of its case.
pub(super) fn run_job(j: &Job) -> Result<Vec<VerifyRow>> {
    let scene = base_scene(j);
    let name_of_space = |sc: Option<&Scene>| {
        let string = sc.is_some_and(|s| s.beam.bending_stiffness == Some(0.0));
        if string && j.space == Space::Hermite {
            "string".to_string()
        } else {
            j.space.name().to_string()
        }
    };
    let supports = j.supports.map_or_else(
        || {
            scene.as_ref().map_or_else(
                |_| String::new(),
                |s| supports_name((s.beam.left, s.beam.right)),
            )
        },
        supports_name,
    );
    let formulation = j
        .formulation
        .map_or_else(|| "none".to_string(), |f| f.name().to_string());
    let discretization = name_of_space(scene.as_ref().ok());
    let blank = |variable: Variable, quantity: Quantity, status: Status, note: String| {
        VerifyRow::unmeasured(
            [
                j.case.name.to_string(),
                j.factory.name(),
                discretization.clone(),
                formulation.clone(),
                supports.clone(),
                variable.name().to_string(),
                quantity.name().to_string(),
            ],
            status,
            note,
        )
    };
    // the case's own ladder variables (a combination that cannot be made
    // is a `cannot` in each)
    let name = j.factory.name();
    let placeholder = Combo {
        method: &name,
        family: super::case::family(&name),
        alphas: None,
        time_order: None,
        space: j.space,
        formulation: j.formulation.unwrap_or_default(),
        supports: j.supports.unwrap_or((Support::Pinned, Support::Pinned)),
    };
    let variables: Vec<Variable> = (j.case.ladders)(j.space, &placeholder)
        .iter()
        .map(|l| l.variable)
        .collect();
    // a scene this combination cannot make (a formulation the method
    // refuses, a basis without free ends) is a `cannot` in every variable
    let probe = scene.and_then(|scene| {
        let resolved = level(&scene, j.space, scene.mesh.elements, scene.time.step, 8)?;
        Ok((scene, resolved))
    });
    let (scene, resolved) = match probe {
        Ok(p) => p,
        Err(e) => {
            return Ok(variables
                .iter()
                .flat_map(|&v| j.case.quantities.iter().map(move |&q| (v, q)))
                .map(|(v, q)| blank(v, q, Status::Cannot, format!("refused: {e}")))
                .collect());
        }
    };
    let alphas = crate::scene::Method::from_name(super::case::family(&name))
        .and_then(|m| m.scheme_for(&resolved).ok())
        .and_then(|s| match s {
            Scheme::GenAlpha(p) => Some((p.alpha_m, p.alpha_f)),
            _ => None,
        });
    let combo = Combo {
        method: &name,
        family: super::case::family(&name),
        alphas,
        time_order: j.factory.time_order(&resolved),
        space: j.space,
        formulation: resolved.contact.formulation,
        supports: (resolved.beam.left, resolved.beam.right),
    };
    let explicit = matches!(resolved.method.scheme, Scheme::CentralDifference);
    let mut rows = Vec::new();
    for ladder in (j.case.ladders)(j.space, &combo) {
        let ladder = if explicit {
            match fit_explicit(&scene, j.space, ladder) {
                Ok(l) => l,
                Err(why) => {
                    for &q in j.case.quantities {
                        rows.push(blank(
                            ladder.variable,
                            q,
                            Status::Cannot,
                            format!("refused: {why}"),
                        ));
                    }
                    continue;
                }
            }
        } else {
            ladder
        };
        // a κ ladder measures the penalty force (its penetration is far
        // below the displacement's other errors)
        let expects: Vec<(Quantity, Expect)> = j
            .case
            .quantities
            .iter()
            .filter(|&&q| ladder.variable != Variable::Kappa || q == Quantity::Force)
            .map(|&q| (q, (j.case.expect)(&combo, ladder.variable, q)))
            .collect();
        let started = std::time::Instant::now();
        let measured = measure(&scene, j, &ladder);
        let wall = started.elapsed().as_secs_f64();
        for (q, e) in expects {
            let mut row = blank(ladder.variable, q, Status::Fail, String::new());
            row.wall_seconds = wall;
            judge(&mut row, &measured, q, e, &ladder);
            rows.push(row);
        }
    }
    Ok(rows)
}
