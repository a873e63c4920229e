//! The bundled scenes (`scenes/*.toml` of the repository), compiled into
//! the extension so that every wheel carries them: `taut.run("reference")`
//! works in a notebook outside the repository. `python/tests/test_scenes.py`
//! checks that this list is the folder's, text for text.

use pyo3::prelude::*;

/// `(name, TOML text)` of every bundled scene, by name.
pub const BUNDLED: [(&str, &str); 17] = [
    (
        "catenary_designed",
        include_str!("../../scenes/catenary_designed.toml"),
    ),
    (
        "line_10_spans",
        include_str!("../../scenes/line_10_spans.toml"),
    ),
    (
        "line_10_spans_linear",
        include_str!("../../scenes/line_10_spans_linear.toml"),
    ),
    (
        "moving_force_beam",
        include_str!("../../scenes/moving_force_beam.toml"),
    ),
    (
        "moving_force_string",
        include_str!("../../scenes/moving_force_string.toml"),
    ),
    (
        "oscillator_one_dof",
        include_str!("../../scenes/oscillator_one_dof.toml"),
    ),
    (
        "pantograph_3mass",
        include_str!("../../scenes/pantograph_3mass.toml"),
    ),
    ("reference", include_str!("../../scenes/reference.toml")),
    (
        "reference_below",
        include_str!("../../scenes/reference_below.toml"),
    ),
    (
        "riding_mass_pinned",
        include_str!("../../scenes/riding_mass_pinned.toml"),
    ),
    (
        "span_droppers",
        include_str!("../../scenes/span_droppers.toml"),
    ),
    (
        "span_droppers_linear",
        include_str!("../../scenes/span_droppers_linear.toml"),
    ),
    (
        "span_messenger",
        include_str!("../../scenes/span_messenger.toml"),
    ),
    (
        "t1_cantilever_riding_mass",
        include_str!("../../scenes/t1_cantilever_riding_mass.toml"),
    ),
    (
        "t2_stationary_mass",
        include_str!("../../scenes/t2_stationary_mass.toml"),
    ),
    (
        "t2_stationary_mass_string",
        include_str!("../../scenes/t2_stationary_mass_string.toml"),
    ),
    (
        "two_pantographs",
        include_str!("../../scenes/two_pantographs.toml"),
    ),
];

/// The bundled scenes as `[(name, text)]`, by name.
#[pyfunction]
pub fn bundled_scenes() -> Vec<(&'static str, &'static str)> {
    BUNDLED.to_vec()
}
