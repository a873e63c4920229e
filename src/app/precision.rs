//! `taut precision` / `taut.precision`: error against cost for each
//! formulation over a (mesh, Δt) grid (precision.csv, precision.svg).

use std::path::Path;

use crate::error::Result;
use crate::report::Outputs;
use crate::study::cost::Estimate;
use crate::study::precision::Precision;
use crate::study::request;

use super::{Frontend, Study, StudyRequest, run_study};

/// A work–precision study of one scene.
pub type PrecisionRequest = StudyRequest<request::PrecisionStudy>;

impl Study for request::PrecisionStudy {
    type Outcome = Precision;
    const OUTPUTS: Outputs = Outputs::Precision;
    const COMMAND: &'static str = "taut precision";
    fn yes(&self) -> bool {
        self.yes
    }
    fn estimate(&self, text: &str, set: &[String]) -> Result<Estimate> {
        request::PrecisionStudy::estimate(self, text, set)
    }
    fn run(
        &self,
        text: &str,
        set: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Precision> {
        request::PrecisionStudy::run(self, text, set, progress)
    }
    fn write(dir: &Path, p: &Precision) -> Result<()> {
        crate::report::write_precision(dir, p)
    }
}

/// Run the study and write its outputs.
pub fn precision(req: &PrecisionRequest, fe: &dyn Frontend) -> Result<Precision> {
    run_study(req, fe)
}

super::args::command_args!("precision": super::PrecisionArgs => request::PrecisionStudy, super::PrecisionArgs::study);

#[cfg(feature = "clap")]
impl super::StudyCommand for request::PrecisionStudy {
    type Args = super::PrecisionArgs;
    const ABOUT: &'static str = "Work–precision: error against cost for each formulation over a (mesh, Δt) grid, with the Pareto front (precision.csv, precision.svg)";
    const SUFFIX: &'static str = "-precision";
    fn terminal(&self, p: &Precision) -> (String, String) {
        ("precision".into(), crate::report::precision_table(p))
    }
    fn tables(p: &Precision) -> Vec<(&'static str, crate::report::Table)> {
        vec![("precision.csv", crate::report::precision_rows(p))]
    }
}
