//! `gate.json`, `junit.xml` and the terminal table of `taut gate`.

use std::path::Path;

use crate::error::{Error, Result};
use crate::study::gate::GateReport;

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// JUnit XML: one `testsuite` per case, one `testcase` per quantity.
pub(crate) fn junit_xml(r: &GateReport) -> String {
    let mut cases: Vec<&str> = r.checks.iter().map(|c| c.case.as_str()).collect();
    cases.extend(r.errors.iter().map(|e| e.case.as_str()));
    cases.sort();
    cases.dedup();
    let failures = r.checks.iter().filter(|c| !c.pass).count();
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    x.push_str(&format!(
        "<testsuites name=\"taut gate\" tests=\"{}\" failures=\"{failures}\" errors=\"{}\">\n",
        r.checks.len() + r.errors.len(),
        r.errors.len()
    ));
    for case in cases {
        let checks: Vec<_> = r.checks.iter().filter(|c| c.case == case).collect();
        let errors: Vec<_> = r.errors.iter().filter(|e| e.case == case).collect();
        let time = r.wall_seconds.get(case).copied().unwrap_or(0.0);
        x.push_str(&format!(
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"{}\" time=\"{time:.3}\">\n",
            xml_escape(case),
            checks.len() + errors.len(),
            checks.iter().filter(|c| !c.pass).count(),
            errors.len()
        ));
        for c in checks {
            x.push_str(&format!(
                "    <testcase classname=\"taut.gate.{}\" name=\"{}\">",
                xml_escape(case),
                xml_escape(&c.quantity)
            ));
            if !c.pass {
                x.push_str(&format!(
                    "<failure message=\"{}\"/>",
                    xml_escape(&format!(
                        "value {:e}, reference {:e}, |difference| {:e} > tolerance {:e} ({})",
                        c.value, c.reference, c.difference, c.tolerance, c.reason
                    ))
                ));
            }
            x.push_str("</testcase>\n");
        }
        for e in errors {
            x.push_str(&format!(
                "    <testcase classname=\"taut.gate.{0}\" name=\"run\"><error message=\"{1}\"/></testcase>\n",
                xml_escape(case),
                xml_escape(&e.error)
            ));
        }
        x.push_str("  </testsuite>\n");
    }
    x.push_str("</testsuites>\n");
    x
}

/// Write `gate.json` and `junit.xml` into `dir`.
pub(crate) fn write_gate(dir: &Path, r: &GateReport) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let json = dir.join("gate.json");
    super::write_json(
        &json,
        &serde_json::json!({
            "taut_version": env!("CARGO_PKG_VERSION"),
            "passed": r.passed(),
            "checks": r.checks,
            "errors": r.errors,
            "wall_seconds": r.wall_seconds,
        }),
    )?;
    let xml = dir.join("junit.xml");
    std::fs::write(&xml, junit_xml(r)).map_err(|e| Error::io(&xml, e))
}

/// The terminal table; with `updated`, the changes written.
pub fn gate_table(r: &GateReport, updated: bool) -> String {
    let mut s = format!(
        "{:<24} {:<22} {:>15} {:>15} {:>11} {}\n",
        "case",
        "quantity",
        "value",
        "reference",
        "tolerance",
        if updated { "change" } else { "result" }
    );
    for c in &r.checks {
        let verdict = match (updated, c.pass) {
            (true, true) => "unchanged within tolerance".to_string(),
            (true, false) => format!("UPDATED (was {:e})", c.reference),
            (false, true) => "pass".to_string(),
            (false, false) => "FAIL".to_string(),
        };
        s.push_str(&format!(
            "{:<24} {:<22} {:>15.8e} {:>15.8e} {:>11.3e} {verdict}\n",
            c.case, c.quantity, c.value, c.reference, c.tolerance
        ));
    }
    for e in &r.errors {
        s.push_str(&format!("{:<24} ERROR: {}\n", e.case, e.error));
    }
    if r.checks.is_empty() {
        s.push_str("no quantity was checked: a gate that checks nothing fails\n");
    }
    let failed = r.checks.iter().filter(|c| !c.pass).count();
    s.push_str(&format!(
        "{} checks, {} passed, {} failed, {} cases with errors\n",
        r.checks.len(),
        r.checks.len() - failed,
        failed,
        r.errors.len()
    ));
    s
}
