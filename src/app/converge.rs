//! `taut converge` / `taut.converge`: a refinement ladder with errors,
//! observed orders and GCI (converge.csv, converge.json, converge.svg).

use std::path::Path;

use crate::error::Result;
use crate::report::Outputs;
use crate::study::cost::Estimate;
use crate::study::request::{self, ConvergeOutcome};

use super::{Frontend, Study, StudyRequest, run_study};

/// A convergence study of one scene.
pub type ConvergeRequest = StudyRequest<request::ConvergeStudy>;

impl Study for request::ConvergeStudy {
    type Outcome = ConvergeOutcome;
    const OUTPUTS: Outputs = Outputs::Converge;
    const COMMAND: &'static str = "taut converge";
    fn yes(&self) -> bool {
        self.yes
    }
    fn estimate(&self, text: &str, set: &[String]) -> Result<Estimate> {
        request::ConvergeStudy::estimate(self, text, set)
    }
    fn run(
        &self,
        text: &str,
        set: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<ConvergeOutcome> {
        request::ConvergeStudy::run(self, text, set, progress)
    }
    fn write(dir: &Path, outcome: &ConvergeOutcome) -> Result<()> {
        match outcome {
            ConvergeOutcome::One(c) => crate::report::write_converge(dir, c),
            ConvergeOutcome::Variants { studies, skipped } => {
                crate::report::write_converge_methods(dir, studies, skipped)
            }
        }
    }
}

/// Run the study and write its outputs.
pub fn converge(req: &ConvergeRequest, fe: &dyn Frontend) -> Result<ConvergeOutcome> {
    run_study(req, fe)
}

super::args::command_args!("converge": super::ConvergeArgs => request::ConvergeStudy, super::ConvergeArgs::study);

#[cfg(feature = "clap")]
impl super::StudyCommand for request::ConvergeStudy {
    type Args = super::ConvergeArgs;
    const ABOUT: &'static str = "Refine mesh, step or both and report errors, observed orders and GCI (converge.csv, converge.json, converge.svg)";
    const SUFFIX: &'static str = "-converge";
    fn terminal(&self, outcome: &ConvergeOutcome) -> (String, String) {
        let kind = format!("converge ({:?}, r = {})", self.refine, self.ratio);
        let table = match outcome {
            ConvergeOutcome::One(c) => crate::report::converge_table(c),
            ConvergeOutcome::Variants { studies, skipped } => {
                crate::report::converge_methods_table(studies, skipped)
            }
        };
        (kind, table)
    }
    fn tables(outcome: &ConvergeOutcome) -> Vec<(&'static str, crate::report::Table)> {
        vec![(
            "converge.csv",
            crate::report::converge_rows(&outcome.rows()),
        )]
    }
}
