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
    fn partial(c: &Comparison, dir: &Path) -> Option<crate::error::Error> {
        partial(c, dir)
    }
    fn write(dir: &Path, c: &Comparison) -> Result<()> {
        crate::report::write_compare(dir, c)
    }
}

/// A comparison some of whose runs stopped, refused before its tables
/// are written: they would replace a folder's whole tables with a part
/// (every stopped run is named with why it stopped).
fn partial(c: &Comparison, dir: &Path) -> Option<crate::error::Error> {
    if c.failed.is_empty() {
        return None;
    }
    // each reason names its run (method/formulation)
    let runs: Vec<String> = c.failed.iter().map(|n| n.reason.to_string()).collect();
    Some(crate::error::Error::Output {
        path: dir.join("compare.csv"),
        reason: format!(
            "the comparison is incomplete: {} of its {} runs stopped, so no tables were written ({}); change or leave out what stopped them and run it again",
            c.failed.len(),
            c.failed.len() + c.rows.len(),
            runs.join("; ")
        ),
    })
}

/// Run the comparison and write its outputs. With an output folder, a
/// comparison some of whose runs stopped fails naming them, the folder
/// untouched; without one, the stopped runs are in the outcome's `failed`
/// (the tables hold the others).
pub fn compare(req: &CompareRequest, fe: &dyn Frontend) -> Result<Comparison> {
    run_study(req, fe)
}

super::args::command_args!("compare": super::CompareArgs => request::CompareStudy, super::CompareArgs::study);

#[cfg(feature = "clap")]
impl super::StudyCommand for request::CompareStudy {
    type Args = super::CompareArgs;
    const ABOUT: &'static str = "Run one scene under several contact formulations and time integrators and compare them (compare.csv, compare.json, compare.svg)";
    const SUFFIX: &'static str = "-compare";
    fn terminal(&self, c: &Comparison) -> (String, String) {
        ("compare".into(), crate::report::compare_table(c))
    }
    /// A run that stopped: its table is written for the others.
    fn whole(c: &Comparison) -> bool {
        c.failed.is_empty()
    }
    fn tables(c: &Comparison) -> Vec<(&'static str, crate::report::Table)> {
        vec![("compare.csv", crate::report::compare_rows(c))]
    }
}
