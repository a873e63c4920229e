//! `taut modes` / `taut.modes`: the natural frequencies and mode shapes of
//! a scene's beam ([`crate::study::modes`]), written as `modes.csv` and
//! `mode_shapes.csv`.

use std::path::PathBuf;

use crate::error::Result;
use crate::report::Outputs;
use crate::study::modes::Modes;

use super::{Frontend, SceneSource, Writing, kept};

/// The modes of one scene.
#[derive(Debug, Clone)]
pub struct ModesRequest {
    /// The scene.
    pub scene: SceneSource,
    /// Scene overrides, `key.path=value` (`--set`).
    pub set: Vec<String>,
    /// How many modes (`--count`; default `crate::study::modes::DEFAULT_COUNT`).
    pub count: Option<usize>,
    /// Output folder (none: nothing written).
    pub out: Option<PathBuf>,
}

/// Compute the scene's modes and write them. The output folder is claimed
/// (and so known writable) before the modes are computed; a command that
/// stops leaves its earlier outputs as they were.
pub fn modes(req: &ModesRequest, fe: &dyn Frontend) -> Result<Modes> {
    let dir = req.out.as_deref();
    modes_in(req, fe).map_err(|e| kept(dir, Outputs::Modes, e, fe))
}

/// [`modes`] but for the note of a command that stopped.
fn modes_in(req: &ModesRequest, fe: &dyn Frontend) -> Result<Modes> {
    let dir = req.out.as_deref();
    if let Some(d) = dir {
        crate::report::check_out_dir(d)?;
    }
    let text = req.scene.read()?;
    let sc = crate::resolve::resolve_scene(&text, &req.set).map_err(|e| req.scene.name(e))?;
    let writing = Writing::open_some(dir, Outputs::Modes, "taut modes")?;
    let m = crate::study::modes::modes(&sc, req.count)?;
    if let Some(w) = writing {
        crate::report::write_modes(w.stage(), &m)?;
        w.finish(fe)?;
    }
    Ok(m)
}

/// The scene's mesh nodes, m (`taut.mesh`): where snapshots, the field and
/// mode shapes are sampled by default (`crate::resolve::wire::nodes`).
pub fn mesh_nodes(scene: &SceneSource, set: &[String]) -> Result<Vec<f64>> {
    let text = scene.read()?;
    let sc = crate::resolve::resolve_scene(&text, set).map_err(|e| scene.name(e))?;
    crate::resolve::wire::nodes(&crate::resolve::wire::Grid {
        length: sc.beam.length,
        elements: sc.elements,
        grading: sc.grading,
        discretization: sc.discretization,
        dt: sc.dt,
        steps: sc.steps,
        t_end: sc.t_end,
    })
}
