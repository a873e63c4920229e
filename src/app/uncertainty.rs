//! `taut uncertainty` / `taut.uncertainty`: the numerical uncertainty of
//! every reported quantity of one scene (uncertainty.csv, uncertainty.json,
//! uncertainty.svg).

use std::path::Path;

use crate::error::{Error, Result};
use crate::report::Outputs;
use crate::study::cost::Estimate;
use crate::study::request;
use crate::study::uncertainty::Uncertainty;

use super::{Frontend, Study, StudyRequest, run_study};

/// A solution verification of one scene.
pub type UncertaintyRequest = StudyRequest<request::UncertaintyStudy>;

impl Study for request::UncertaintyStudy {
    type Outcome = Uncertainty;
    const OUTPUTS: Outputs = Outputs::Uncertainty;
    const COMMAND: &'static str = "taut uncertainty";
    fn yes(&self) -> bool {
        self.yes
    }
    fn estimate(&self, text: &str, set: &[String]) -> Result<Estimate> {
        request::UncertaintyStudy::estimate(self, text, set)
    }
    fn run(
        &self,
        text: &str,
        set: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Uncertainty> {
        request::UncertaintyStudy::run(self, text, set, progress)
    }
    /// A run of the family that diverged: nothing is estimated.
    fn nothing(outcome: &mut Uncertainty) -> Option<Error> {
        let e = outcome.stopped.take()?;
        Some(std::sync::Arc::try_unwrap(e).unwrap_or_else(|e| Error::parse(e.to_string())))
    }
    fn write(dir: &Path, outcome: &Uncertainty) -> Result<()> {
        crate::report::write_uncertainty(dir, outcome)
    }
}

/// Run the family and write its outputs. A family with a run that
/// diverged estimates nothing: the command fails with that run's
/// divergence, its output folder untouched.
pub fn uncertainty(req: &UncertaintyRequest, fe: &dyn Frontend) -> Result<Uncertainty> {
    run_study(req, fe)
}

super::args::command_args!("uncertainty": super::UncertaintyArgs => request::UncertaintyStudy, super::UncertaintyArgs::study);

#[cfg(feature = "clap")]
impl super::StudyCommand for request::UncertaintyStudy {
    type Args = super::UncertaintyArgs;
    const ABOUT: &'static str = "Solution verification: run a small family of the scene refined in space and time, together and apart, and give every reported quantity its numerical uncertainty u_num (GCI, Eça–Hoekstra least squares), observed orders and the space/time split (uncertainty.csv, uncertainty.json, uncertainty.svg; docs/verification.md)";
    const SUFFIX: &'static str = "-uncertainty";
    fn terminal(&self, u: &Uncertainty) -> (String, String) {
        let added = match u.levels_added {
            0 => String::new(),
            n => format!(" ({n} added: level 0 pre-asymptotic)"),
        };
        let kind = format!(
            "uncertainty ({} levels{added}, {} runs in {:.2} s wall)",
            u.levels,
            u.family.len(),
            u.wall_seconds
        );
        (kind, family_text(u))
    }
    fn tables(u: &Uncertainty) -> Vec<(&'static str, crate::report::Table)> {
        vec![
            ("uncertainty.csv", crate::report::uncertainty_table(u)),
            ("family", crate::report::family_table(u)),
        ]
    }
}

/// The family of `taut uncertainty` (each diagonal level's N or J and Δt)
/// and its table of value ± u_num, as the terminal prints them.
#[cfg(feature = "clap")]
fn family_text(u: &Uncertainty) -> String {
    use crate::study::uncertainty::Role;
    use std::fmt::Write as _;
    let mut s = String::from("  family  ");
    let levels: Vec<String> = u
        .family
        .iter()
        .filter(|m| m.role == Role::Diagonal)
        .map(|m| {
            format!(
                "{} = {} × Δt = {:e} s",
                u.level_symbol,
                m.modes.unwrap_or(m.elements),
                m.dt
            )
        })
        .collect();
    let _ = writeln!(
        s,
        "{} (diagonal), and each level's {} at the previous Δt",
        levels.join(", "),
        u.level_symbol
    );
    s.push_str(&crate::report::uncertainty_lines(u));
    s
}
