//! The bundled form-found catenary from the command line
//! (`scenes/catenary_designed.toml`, docs/lines.md "Form-finding"): `taut
//! line expand` prints the found lengths and its text runs bit for bit as
//! the `[line]` scene does; the run writes the static height profile
//! against the design and the droppers at rest; a design no dropper can
//! hold is refused by name.

use crate::common;

use std::path::Path;

use common::{out_dir, scene_path, summary_json as summary, taut_ok as ok};

/// Two spans, the first 0.3 s.
const CUT: [&str; 4] = ["--set", "line.spans=2", "--set", "time.end=0.3"];

fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut rows = text
        .lines()
        .map(|l| l.split(',').map(String::from).collect());
    (rows.next().unwrap(), rows.collect())
}

#[test]
fn the_expanded_catenary_carries_the_found_lengths_and_runs_bit_for_bit() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = scene_path("catenary_designed.toml");
    let mut args = vec!["line", "expand", scene.as_str()];
    args.extend(CUT);
    let text = ok(&args);
    assert!(
        !text.contains("[line]") && text.contains("design_height"),
        "{text}"
    );
    let expanded = tmp.path().join("expanded.toml");
    std::fs::write(&expanded, &text).unwrap();
    let expanded = expanded.to_str().unwrap();
    // expanding the expanded scene changes nothing (its lengths are found)
    assert_eq!(ok(&["line", "expand", expanded]), text);
    let (a, b) = (out_dir(&tmp, "line"), out_dir(&tmp, "expanded"));
    let mut run_a = vec![
        "run",
        scene.as_str(),
        "--out",
        a.to_str().unwrap(),
        "--quiet",
    ];
    run_a.extend(CUT);
    ok(&run_a);
    ok(&["run", expanded, "--out", b.to_str().unwrap(), "--quiet"]);
    for f in ["history.csv", "static_heights.csv", "droppers_static.csv"] {
        let (fa, fb) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(fa == fb, "{f} differs");
    }
    // the same but for how form-finding got there: the expanded text's
    // lengths already meet the design (no step; its start error is the
    // line's final one)
    let (mut sa, mut sb) = (summary(&a), summary(&b));
    let (fa, fb) = (sa["form_finding"].take(), sb["form_finding"].take());
    assert_eq!(sa, sb);
    assert_eq!(
        (fa["steps"].as_u64(), fb["steps"].as_u64()),
        (Some(1), Some(0))
    );
    assert_eq!(fa["error"], fb["error"]);
    assert_eq!(fb["start_error"], fb["error"]);
    // the lengths in the text are the run's (droppers_static.csv)
    let (head, rows) = csv(&a.join("droppers_static.csv"));
    assert_eq!(head, ["name", "x", "length", "force", "height"]);
    assert_eq!(rows.len(), 18);
    for r in &rows {
        assert!(text.contains(&format!("length = {}", r[2])), "{r:?}");
    }
    // the static heights meet the design, and the summary says so
    let (head, rows) = csv(&a.join("static_heights.csv"));
    assert_eq!(head, ["name", "x", "design", "static", "difference"]);
    for r in &rows {
        let diff: f64 = r[4].parse().unwrap();
        assert!(diff.abs() <= taut::integrate::FORM_TOLERANCE, "{r:?}");
    }
    let s = summary(&a);
    let f = &s["form_finding"];
    assert!(f["error"].as_f64().unwrap() <= f["tolerance"].as_f64().unwrap());
    assert!(f["start_error"].as_f64().unwrap() > 1e-3, "{f}");
    // and the contact-force statistics per span
    assert!(a.join("spans.csv").exists());
}

#[test]
fn a_design_no_dropper_can_hold_is_refused_by_name() {
    let tmp = tempfile::tempdir().unwrap();
    let e = common::run_fails(
        &scene_path("catenary_designed.toml"),
        &out_dir(&tmp, "run"),
        &["--set", "line.spans=1", "--set", "line.presag=0.3"],
    );
    assert!(e.contains("line.presag") && e.contains("0.3"), "{e}");
    // more droppers than form-finding's dense Jacobian takes
    let e = common::run_fails(
        &scene_path("catenary_designed.toml"),
        &out_dir(&tmp, "run"),
        &["--set", "line.spans=223", "--set", "time.end=0.01"],
    );
    assert!(
        e.contains("line.form_finding") && e.contains("2007") && e.contains("2000"),
        "{e}"
    );
}
