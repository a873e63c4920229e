//! `taut compare` / `taut.compare`: one scene under several formulations,
//! methods and discretizations (compare.csv, compare.json, compare.svg).

use std::path::Path;

use crate::error::Result;
use crate::report::Outputs;
use crate::study::compare::Comparison;
use crate::study::cost::Estimate;
use crate::study::request;

use super::{Frontend, Study, StudyRequest, run_study};

/// A comparison of one scene.
pub type CompareRequest = StudyRequest<request::CompareStudy>;

impl Study for request::CompareStudy {
    type Outcome = Comparison;
    const OUTPUTS: Outputs = Outputs::Compare;
    const COMMAND: &'static str = "taut compare";
    fn yes(&self) -> bool {
        self.yes
    }
    fn estimate(&self, text: &str, set: &[String]) -> Result<Estimate> {
        request::CompareStudy::estimate(self, text, set)
    }
    fn run(
        &self,
        text: &str,
        set: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Comparison> {
        request::CompareStudy::run(self, text, set, progress)
    }
    fn write(dir: &Path, c: &Comparison) -> Result<()> {
        crate::report::write_compare(dir, c)
    }
}

/// Run the comparison and write its outputs; the runs that stopped are in
/// the outcome's `failed` (the tables hold the others).
pub fn compare(req: &CompareRequest, fe: &dyn Frontend) -> Result<Comparison> {
    run_study(req, fe)
}
