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
