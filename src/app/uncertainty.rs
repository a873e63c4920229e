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
