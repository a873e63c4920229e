//! What `[line]` generated in a scene, so that an error found in the
//! expanded scene names the key a user wrote. Its own file: the
//! scene file's [`super::Scene`] keeps it, and the expansion in `line.rs`
//! fills it.

use crate::error::Error;

/// What `[line]` generated in a scene (`super::expand_line_with_origin`): the
/// generated droppers come first in `[[dropper]]` and the steady arms
/// first in `[[attachment]]`, the scene's own tables after them. An error
/// found in the expanded scene names the key a user can give back to
/// `--set` (and Python's `set=`): [`Generated::user_path`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Generated {
    /// The scene had a `[line]` table.
    pub line: bool,
    /// Droppers generated (`dropper.0` … `dropper.{droppers − 1}`).
    pub droppers: usize,
    /// Attachments generated (`attachment.0` …): the steady arms, then the
    /// droppers' clamp masses (E3).
    pub attachments: usize,
    /// Steady arms among them (the first ones).
    pub steady_arms: usize,
    /// Clamp masses on the contact wire among them (after the steady
    /// arms; those on the messenger follow).
    pub contact_clamps: usize,
    /// The `[messenger]` table was generated (`anchor = "messenger"`).
    pub messenger: bool,
    /// `mesh.elements` was generated (from `line.element_length`).
    pub elements: bool,
}

impl Generated {
    /// The path a user gives back to `--set` for `path`, a key of the
    /// expanded scene: a generated dropper's key is the `[line]` key that
    /// made it, an explicit dropper's index counts from the scene's own
    /// first `[[dropper]]` (likewise attachments and steady arms); other
    /// paths are their own.
    pub fn user_path(&self, path: &str) -> String {
        if !self.line {
            return path.to_string();
        }
        let (head, rest) = path.split_once('.').unwrap_or((path, ""));
        let (index, key) = rest.split_once('.').unwrap_or((rest, ""));
        let index = index.parse::<usize>().ok();
        let tail = |i: usize| {
            if key.is_empty() {
                format!("{head}.{i}")
            } else {
                format!("{head}.{i}.{key}")
            }
        };
        let top = key.split('.').next().unwrap_or("");
        match (head, index) {
            ("dropper", Some(i)) if i < self.droppers => match top {
                "stiffness" => "line.dropper_stiffness",
                "damping" => "line.dropper_damping",
                "linear" => "line.linear_droppers",
                "x" => "line.droppers",
                "anchor" => "line.anchor",
                "length" | "anchor_height" | "design_height" => "line.presag",
                _ => "line",
            }
            .to_string(),
            ("dropper", Some(i)) => tail(i - self.droppers),
            ("attachment", Some(i)) if i < self.steady_arms => match top {
                "stiffness" => "line.steady_arm.stiffness",
                "mass" => "line.steady_arm.mass",
                "damping" => "line.steady_arm.damping",
                _ => "line.steady_arm",
            }
            .to_string(),
            ("attachment", Some(i)) if i < self.steady_arms + self.contact_clamps => {
                "line.clamp_mass.contact".to_string()
            }
            ("attachment", Some(i)) if i < self.attachments => {
                "line.clamp_mass.messenger".to_string()
            }
            ("attachment", Some(i)) => tail(i - self.attachments),
            ("messenger", _) if self.messenger => match top_of(rest) {
                k @ ("tension" | "mass_per_length" | "bending_stiffness" | "height") => {
                    format!("line.messenger.{k}")
                }
                "supports" => "line.spans".to_string(),
                // the expansion writes a list with the end supports
                // pinned: its index is no index of the user's
                // `line.messenger.support`, its leaf key is
                "support" => match rest.rsplit('.').next() {
                    Some(k @ ("stiffness" | "mass" | "damping")) => {
                        format!("line.messenger.support.{k}")
                    }
                    _ => "line.messenger.support".to_string(),
                },
                _ => "line.messenger".to_string(),
            },
            ("beam", _) if rest == "length" => "line.span_length".to_string(),
            ("mesh", _) if rest == "elements" && self.elements => "line.element_length".to_string(),
            _ => path.to_string(),
        }
    }

    /// `e` with every key path it names made a user's ([`Generated::user_path`]):
    /// the field of an invalid value or a read error, and the path quoted in
    /// a read error's reason.
    pub fn user_error(&self, e: Error) -> Error {
        if !self.line {
            return e;
        }
        e.map_field(|path| self.user_path(path))
    }
}

/// The first segment of a dotted path.
fn top_of(path: &str) -> &str {
    path.split('.').next().unwrap_or("")
}
