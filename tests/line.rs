//! The `[line]` generator from the command line (docs/lines.md,
//! "The line generator"): `taut line expand` prints a scene that runs
//! bit for bit as the `[line]` scene does, a fixed-anchor line runs end to
//! end, `--set line.*` regenerates it, and a bad key is refused by name.

use crate::common;

use std::path::Path;

use common::{out_dir, taut_bin};

/// Two 27 m spans of contact wire (the bundled span's wire) on fixed
/// anchors, three droppers a span, no pre-sag (the run starts from the
/// straight wire, which with p = 0 is the design shape: the droppers'
/// pre-tensions carry its weight), a steady arm mass at the middle support,
/// one pantograph crossing the first span.
const LINE: &str = r#"
[beam]
mass_per_length = 1.35
bending_stiffness = 150.0
tension = 2.0e4

[mesh]

[[carrier]]
mass = 8.0
stiffness = 5000.0
preload = 0.0357
side = "below"
start = 0.0
speed = { profile = "constant", value = 55.6 }

[contact]
kind = "unilateral"
formulation = "lagrange"

[time]
step = 4.0e-4
end = 0.45

[gravity]
g = 9.81
beam_self_weight = true

[line]
spans = 2
span_length = 27.0
droppers = { count = 3, end_distance = 4.5 }
dropper_stiffness = 1.0e5
element_length = 0.5
anchor = "fixed"
messenger = { tension = 1.6e4, mass_per_length = 1.07, height = 1.2 }
steady_arm = { mass = 1.0 }
"#;

fn write(dir: &Path, name: &str, text: &str) -> String {
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

use common::{summary_json as summary, taut_ok as ok};

/// `LINE` hung from a messenger on elastic interior supports, with
/// per-dropper stiffnesses (one list a span), dashpots (a pattern of two
/// spans), the droppers' own and clamp masses on both wires, and a damped
/// steady arm spring (docs/lines.md E2, E3).
fn line_with_properties() -> String {
    LINE.replace(
        "dropper_stiffness = 1.0e5",
        "dropper_stiffness = [2.0e5, 1.0e5, 2.0e5]\ndropper_damping = [[10.0, 0.0, 10.0], [0.0, 5.0, 0.0]]\ndropper_mass = 0.4\nclamp_mass = { contact = 0.2, messenger = [0.15, 0.1, 0.15] }",
    )
    .replace("anchor = \"fixed\"", "anchor = \"messenger\"")
    .replace(
        "height = 1.2 }",
        "bending_stiffness = 130.0, height = 1.2, support = { stiffness = 5.0e5, damping = 100.0, mass = 10.0 } }",
    )
    .replace(
        "steady_arm = { mass = 1.0 }",
        "steady_arm = { stiffness = 2000.0, mass = 1.0, damping = 20.0 }",
    )
}

/// The expanded scene runs bit for bit as the `[line]` scene: the same
/// history.csv bytes and the same summary (wall time aside). The expansion
/// is the run's own (one function, where every scene tree becomes a scene).
#[test]
fn the_expanded_scene_runs_bit_for_bit_as_the_line() {
    bit_for_bit(LINE);
}

/// The same with the per-dropper properties, clamp masses and elastic
/// messenger supports: each is written out as plain keys.
#[test]
fn the_expanded_properties_run_bit_for_bit_as_the_line() {
    let text = bit_for_bit(&line_with_properties());
    for key in [
        "stiffness = 200000.0",
        "damping = 5.0",
        "wire = \"messenger\"",
        "name = \"messenger_clamp_s2d2\"",
        "support = [\"pinned\", { damping = 100.0, mass = 10.0, stiffness = 500000.0 }, \"pinned\"]",
    ] {
        assert!(text.contains(key), "{key}: {text}");
    }
    // 6 droppers: lower ends 0.2 + 0.4/2 kg, upper ends 0.15/0.1 + 0.2 kg
    assert_eq!(text.matches("mass = 0.4").count(), 6, "{text}");
    assert_eq!(text.matches("mass = 0.35").count(), 4, "{text}");
    assert_eq!(
        text.matches("mass = 0.30000000000000004").count(),
        2,
        "{text}"
    );
}

/// Run `scene` and its `taut line expand` text; both histories and
/// summaries agree, and expanding again changes nothing. The expanded text.
fn bit_for_bit(scene: &str) -> String {
    let tmp = tempfile::tempdir().unwrap();
    let line = write(tmp.path(), "line.toml", scene);
    let text = ok(&["line", "expand", &line]);
    assert!(!text.contains("[line]"), "{text}");
    assert!(
        text.contains("[[dropper]]") && text.contains("s2d3"),
        "{text}"
    );
    let expanded = write(tmp.path(), "expanded.toml", &text);
    // expanding the expanded scene changes nothing
    assert_eq!(ok(&["line", "expand", &expanded]), text);
    let (a, b) = (out_dir(&tmp, "line"), out_dir(&tmp, "expanded"));
    ok(&["run", &line, "--out", a.to_str().unwrap(), "--quiet"]);
    ok(&["run", &expanded, "--out", b.to_str().unwrap(), "--quiet"]);
    let ha = std::fs::read(a.join("history.csv")).unwrap();
    let hb = std::fs::read(b.join("history.csv")).unwrap();
    assert!(ha == hb, "history.csv differs");
    assert_eq!(summary(&a), summary(&b));
    // the pantograph passed droppers: they carry forces in the history
    let header = String::from_utf8_lossy(&ha);
    let header = header.lines().next().unwrap();
    assert!(header.contains("dropper_s1d1_force"), "{header}");
    text
}

/// A fixed-anchor line starts at its design state: with no pre-sag and no
/// steady arm spring (G3 with s = 0, F = 0) each dropper's force in row 0
/// (the straight wire, t = 0) is the wire's weight over its tributary
/// length — 6.75 m for the end droppers (4.5 m to the pinned end, 9 m to
/// the next), 9 m for the others, across the middle support too — and the
/// run goes to its end.
#[test]
fn a_fixed_anchor_line_starts_from_its_design_forces() {
    let tmp = tempfile::tempdir().unwrap();
    let line = write(tmp.path(), "line.toml", LINE);
    let out = out_dir(&tmp, "run");
    ok(&["run", &line, "--out", out.to_str().unwrap(), "--quiet"]);
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let mut rows = history.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    let row0: Vec<f64> = rows
        .next()
        .unwrap()
        .split(',')
        .map(|c| c.parse().unwrap())
        .collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    // k_d (z_a − ℓ_0) with z_a ≈ 1.2 m and z_a − ℓ_0 ≈ 1.2 mm: the
    // subtraction loses 1e3 ulps of the force
    const ROUND_OFF: f64 = 1e-12;
    let w = 1.35 * 9.81;
    for (name, tributary) in [
        ("s1d1", 6.75),
        ("s1d2", 9.0),
        ("s1d3", 9.0),
        ("s2d1", 9.0),
        ("s2d2", 9.0),
        ("s2d3", 6.75),
    ] {
        let got = row0[col(&format!("dropper_{name}_force"))];
        let want = w * tributary;
        assert!(
            ((got - want) / want).abs() < ROUND_OFF,
            "{name}: {got} vs {want}"
        );
    }
    let last: f64 = history
        .lines()
        .last()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((last - 0.45).abs() < 1e-9, "{last}");
}

/// `--set line.*` regenerates the line: three spans give a longer beam and
/// nine droppers; a bad key is refused naming it.
#[test]
fn set_regenerates_the_line_and_bad_keys_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    let line = write(tmp.path(), "line.toml", LINE);
    let text = ok(&["line", "expand", &line, "--set", "line.spans=3"]);
    assert!(text.contains("length = 81.0"), "{text}");
    assert!(text.contains("s3d3") && !text.contains("s4d1"), "{text}");
    let o = taut_bin(&["line", "expand", &line, "--set", "line.spans=0"]);
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("line.spans") && e.contains("1 ..= 1000"), "{e}");
    let out = out_dir(&tmp, "bad");
    let e = common::run_fails(&line, &out, &["--set", "line.dropper_stifness=3"]);
    assert!(e.contains("dropper_stifness"), "{e}");
}
