//! `taut line expand SCENE`: a scene's `[line]` written out as the plain
//! keys it stands for (docs/lines.md#the-line-generator-g1g7), as TOML text
//! that runs identically when given back. With form-finding (a dropper's
//! `design_height`, docs/lines.md eq. F1–F5) the lengths written are the
//! found ones: given back, the text's form-finding starts within its
//! tolerance, takes no step, and runs the same bytes.

use crate::error::{Error, Result, one_line};
use crate::scene::{expand_line, scene_from_tree};
use toml::Value;

use super::SceneSource;
use super::scene::scene_tree;

/// The scene after `set` (in order, as every command applies them) with
/// its `[line]` expanded, as TOML text. A scene without `[line]` is written
/// as its tree (the same keys, TOML's layout). The text is not checked
/// beyond the expansion: the command it is given to validates it.
pub fn expand(scene: &SceneSource, set: &[String]) -> Result<String> {
    let given = scene_tree(scene, set)?;
    let mut tree = expand_line(given.clone()).map_err(|e| scene.name(e))?;
    write_found_lengths(given, &mut tree).map_err(|e| scene.name(e))?;
    toml::to_string(&tree).map_err(|e| {
        Error::invalid(
            "line",
            one_line(&e.to_string()),
            "tables TOML can hold (finite numbers)",
        )
    })
}

/// With a dropper `design_height` in the expanded `tree`, the lengths
/// form-finding finds (the scene `given` resolved and its line built, as a
/// run builds it) written into each dropper's `length`.
fn write_found_lengths(given: toml::Table, tree: &mut toml::Table) -> Result<()> {
    let wanted = tree
        .get("dropper")
        .and_then(Value::as_array)
        .is_some_and(|ds| ds.iter().any(|d| d.get("design_height").is_some()));
    if !wanted {
        return Ok(());
    }
    let sc = scene_from_tree(given)?.validate()?;
    let sys = crate::integrate::System::new(&sc)?;
    let Some(found) = sys.form_found() else {
        return Ok(());
    };
    if let Some(Value::Array(ds)) = tree.get_mut("dropper") {
        for (d, f) in ds.iter_mut().zip(&found.droppers) {
            if let Value::Table(t) = d {
                t.insert("length".into(), Value::Float(f.length));
            }
        }
    }
    Ok(())
}
