//! `taut.load_scene`: a scene as its TOML tree, with `--set` / `--unset`
//! overrides applied, for a front end that edits scenes as data (Python
//! dicts) and hands them back as TOML text.

use crate::error::Result;
use crate::scene::{apply_override, check_is_scene, parse_scene};

use super::SceneSource;

/// The scene's TOML tree after `set` (in order; `unset KEY` entries
/// remove keys): read and parsed as every command reads it (a syntax
/// error by line and column, a file that is not a scene refused without
/// its keys), not deserialized (a tree with an unknown key is handed back
/// as it is; the command it is given to names the key).
pub fn scene_tree(scene: &SceneSource, set: &[String]) -> Result<toml::Table> {
    let text = scene.read()?;
    let mut tree = parse_scene(&text).map_err(|e| scene.name(e))?;
    check_is_scene(&tree).map_err(|e| scene.name(e))?;
    for spec in set {
        apply_override(&mut tree, spec)?;
    }
    Ok(tree)
}
