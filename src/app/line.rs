//! `taut line expand SCENE`: a scene's `[line]` written out as the plain
//! keys it stands for (docs/lines.md#the-line-generator-g1g7), as TOML text
//! that runs identically when given back.

use crate::error::{Error, Result, one_line};
use crate::scene::expand_line;

use super::SceneSource;
use super::scene::scene_tree;

/// The scene after `set` (in order, as every command applies them) with
/// its `[line]` expanded, as TOML text. A scene without `[line]` is written
/// as its tree (the same keys, TOML's layout). The text is not checked
/// beyond the expansion: the command it is given to validates it.
pub fn expand(scene: &SceneSource, set: &[String]) -> Result<String> {
    let tree = expand_line(scene_tree(scene, set)?).map_err(|e| scene.name(e))?;
    toml::to_string(&tree).map_err(|e| {
        Error::invalid(
            "line",
            one_line(&e.to_string()),
            "tables TOML can hold (finite numbers)",
        )
    })
}
