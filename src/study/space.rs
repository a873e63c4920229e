//! The space discretizations a study runs a scene under
//! (`--discretizations hermite,galerkin:40,modal:40`, MODEL §9.2), as typed
//! choices applied to the resolved scene, not override strings.
//!
//! A choice sets `mesh.kind` and `mesh.modes` on the scene and validates it
//! again, so every range check of a scene file applies (J above the FE
//! unknowns, a galerkin basis on a free end, …) and a study reports the
//! same error a scene would. Refinement in a study is the choice's own
//! level parameter: the number of elements N for `hermite`, the number of
//! modes J for `galerkin` and `modal` (whose FE mesh stays the scene's).

use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::scene::{GradingKind, MeshKind, Scene};

/// A space discretization of a study (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpaceChoice {
    /// `mesh.kind`.
    pub kind: MeshKind,
    /// J for the modal kinds; `None`: the scene's `mesh.modes`.
    pub modes: Option<usize>,
}

impl SpaceChoice {
    /// Parse `hermite,galerkin:40,modal:40` (J after a colon; without it a
    /// modal kind takes the scene's `mesh.modes`).
    pub fn parse_list(list: &str) -> Result<Vec<SpaceChoice>> {
        let field = "--discretizations";
        let mut out: Vec<SpaceChoice> = Vec::new();
        for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (name, j) = match item.split_once(':') {
                Some((n, j)) => (n.trim(), Some(j.trim())),
                None => (item, None),
            };
            let kind = match name {
                "hermite" => MeshKind::Hermite,
                "galerkin" => MeshKind::Galerkin,
                "modal" => MeshKind::Modal,
                _ => {
                    return Err(Error::invalid(
                        field,
                        item,
                        "each item must be hermite, galerkin[:J] or modal[:J]",
                    ));
                }
            };
            let modes = match (kind, j) {
                (_, None) => None,
                (MeshKind::Hermite, Some(_)) => {
                    return Err(Error::invalid(
                        field,
                        item,
                        "hermite takes no mode count (its level parameter is mesh.elements)",
                    ));
                }
                (_, Some(j)) => {
                    Some(j.parse::<usize>().ok().filter(|&j| j >= 1).ok_or_else(|| {
                        Error::invalid(field, item, "J after the colon must be an integer ≥ 1")
                    })?)
                }
            };
            let c = SpaceChoice { kind, modes };
            if out.contains(&c) {
                return Err(Error::invalid(field, item, "is listed twice"));
            }
            out.push(c);
        }
        if out.is_empty() {
            return Err(Error::invalid(
                field,
                list,
                "name at least one of hermite, galerkin[:J], modal[:J]",
            ));
        }
        Ok(out)
    }

    /// `hermite`, `galerkin`, `modal` (J is a level parameter, shown in
    /// the tables' own columns).
    pub fn name(&self) -> &'static str {
        self.kind.name()
    }

    /// True for `galerkin` and `modal`: refined in J, not in N.
    pub fn is_modal(&self) -> bool {
        self.kind != MeshKind::Hermite
    }

    /// `sc` under this discretization, its level parameter scaled by
    /// `factor` (N for hermite, J for the modal kinds; 1 keeps it).
    pub fn apply(&self, sc: &Resolved, factor: f64) -> Result<Resolved> {
        let mut scene = sc.scene.clone();
        self.set(&mut scene, factor)?;
        scene.validate()
    }

    /// Set this discretization's `[mesh]` fields on `scene`, its level
    /// parameter scaled by `factor` ([`SpaceChoice::apply`] without the
    /// validation, for `super::variant::RunVariant`).
    pub fn set(&self, scene: &mut Scene, factor: f64) -> Result<()> {
        let mesh = &mut scene.mesh;
        mesh.kind = self.kind;
        match self.kind {
            MeshKind::Hermite => {
                mesh.modes = None;
                mesh.elements = (mesh.elements as f64 * factor).round() as usize;
            }
            MeshKind::Galerkin | MeshKind::Modal => {
                let j0 = self.modes.or(mesh.modes).ok_or_else(|| {
                    Error::invalid(
                        "--discretizations",
                        self.name(),
                        format!(
                            "the scene has no mesh.modes: give J as {}:J (e.g. {}:40)",
                            self.name(),
                            self.name()
                        ),
                    )
                })?;
                mesh.modes = Some((j0 as f64 * factor).round() as usize);
                if self.kind == MeshKind::Galerkin {
                    // no mesh to grade: the same scene under a basis without one
                    mesh.grading = GradingKind::Uniform;
                    mesh.grading_ratio = None;
                    mesh.grading_at = None;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_are_parsed_and_checked() {
        let l = SpaceChoice::parse_list("hermite, galerkin:40,modal").unwrap();
        assert_eq!(
            l,
            vec![
                SpaceChoice {
                    kind: MeshKind::Hermite,
                    modes: None
                },
                SpaceChoice {
                    kind: MeshKind::Galerkin,
                    modes: Some(40)
                },
                SpaceChoice {
                    kind: MeshKind::Modal,
                    modes: None
                },
            ]
        );
        for bad in [
            "fourier",
            "hermite:3",
            "modal:0",
            "modal:x",
            "modal,modal",
            " , ",
        ] {
            let e = SpaceChoice::parse_list(bad).unwrap_err().to_string();
            assert!(e.contains("--discretizations"), "{bad}: {e}");
        }
    }
}
