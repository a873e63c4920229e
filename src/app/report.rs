//! `taut report DIR… [--out FILE]` / `taut.report`: one self-contained
//! `report.html` from the outputs taut wrote into the folders
//! (`crate::report::write_report`).

use std::path::PathBuf;

use crate::error::Result;
use crate::report::ReportSummary;

/// A report of one or more output folders.
#[derive(Debug, Clone)]
pub struct ReportRequest {
    /// The folders, in the order the page shows them.
    pub dirs: Vec<PathBuf>,
    /// The page (default [`ReportRequest::default_out`]).
    pub out: Option<PathBuf>,
}

impl ReportRequest {
    /// Where the page goes without `--out`: `report.html` in the folder
    /// when there is one, else `out/report.html`.
    pub fn default_out(&self) -> PathBuf {
        match self.dirs.as_slice() {
            [one] => one.join("report.html"),
            _ => PathBuf::from("out").join("report.html"),
        }
    }
}

/// Write the report.
pub fn report(req: &ReportRequest) -> Result<ReportSummary> {
    let out = req.out.clone().unwrap_or_else(|| req.default_out());
    crate::report::write_report(&req.dirs, &out, &declared())
}

/// The outputs of the studies of [`super::each_study`] that declare their
/// files ([`crate::report::Outputs::Declared`]), so that the page shows
/// them as it shows the built-in ones.
#[cfg(feature = "clap")]
fn declared() -> Vec<crate::report::Outputs> {
    struct Kinds(Vec<crate::report::Outputs>);
    impl super::StudyVisitor for Kinds {
        fn visit<S: super::StudyCommand>(&mut self)
        where
            S::Outcome: Send,
        {
            self.0.push(<S as super::Study>::OUTPUTS);
        }
    }
    let mut kinds = Kinds(Vec::new());
    super::each_study(&mut kinds);
    kinds.0
}

/// Without the command schema there is no list of studies: the built-in
/// kinds only.
#[cfg(not(feature = "clap"))]
fn declared() -> Vec<crate::report::Outputs> {
    Vec::new()
}
