//! One value per key: the scene values an axis sets, so that two axes (of
//! a grid, or two columns of a list of points) that set one value are
//! refused rather than one silently winning while a row records the
//! other's value.
//!
//! An axis's key is read as `--set` reads it, against the scene's tree
//! (the text with the fixed overrides): an array of one entry may be
//! walked without its index, so `carrier.mass` is `carrier.0.mass` there.
//! A dimensionless axis sets what its ratio fixes: `speed_ratio` every
//! carrier's speed, `tension_ratio` the beam's tension, `mass_ratio` and
//! `stiffness_ratio` every carrier's mass or stiffness. Two axes clash when
//! one's value is the other's or lies inside it (`carrier.0.speed` and
//! `carrier.0.speed.cruise`).

use std::collections::HashMap;

use toml::{Table, Value};

use super::axis::{Axis, AxisTarget, Ratio};
use crate::error::{Error, Result};

/// The scene values (dotted paths, every array index written) that `axis`
/// sets on `base`.
pub fn targets(axis: &Axis, base: &Table) -> Vec<String> {
    let carriers = match base.get("carrier") {
        Some(Value::Array(a)) => a.len(),
        _ => 1,
    };
    let every_carrier = |key: &str| {
        (0..carriers)
            .map(|i| format!("carrier.{i}.{key}"))
            .collect()
    };
    match axis.target() {
        AxisTarget::Ratio(Ratio::Tension) => vec!["beam.tension".into()],
        AxisTarget::Ratio(Ratio::Speed) => every_carrier("speed"),
        AxisTarget::Ratio(Ratio::Mass) => every_carrier("mass"),
        AxisTarget::Ratio(Ratio::Stiffness) => every_carrier("stiffness"),
        AxisTarget::Path(path) => vec![canonical(path, base)],
    }
}

/// `path` with the index of every one-entry array it walks without one
/// written in (the walk of `--set`); segments past the tree kept as given.
fn canonical(path: &str, base: &Table) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut node: Option<&Value> = None;
    let mut table = Some(base);
    for seg in path.trim().split('.') {
        loop {
            match node {
                Some(Value::Array(a)) if seg.parse::<usize>().is_err() && a.len() == 1 => {
                    out.push("0".into());
                    node = a.first();
                    table = node.and_then(Value::as_table);
                }
                _ => break,
            }
        }
        out.push(seg.to_string());
        node = match node {
            Some(Value::Array(a)) => seg.parse::<usize>().ok().and_then(|i| a.get(i)),
            _ => table.and_then(|t| t.get(seg)),
        };
        table = node.and_then(Value::as_table);
    }
    out.join(".")
}

/// Whether setting `a` and setting `b` touch one value: equal, or one
/// inside the other.
fn clash(a: &str, b: &str) -> bool {
    let inside =
        |x: &str, y: &str| x.len() > y.len() && x.starts_with(y) && x.as_bytes()[y.len()] == b'.';
    a == b || inside(a, b) || inside(b, a)
}

/// Refuse two axes that set one scene value (module docs), naming both
/// keys and the value; `flag` names the option (`--vary`, `--points`).
pub fn check_one_value_per_key(axes: &[Axis], base: &Table, flag: &str) -> Result<()> {
    // every target of every axis, with the axis it belongs to; a clash is
    // found between targets that share their first two segments, so the
    // comparison stays near-linear in the keys
    let mut groups: HashMap<String, Vec<(usize, String)>> = HashMap::new();
    for (k, axis) in axes.iter().enumerate() {
        for t in targets(axis, base) {
            let head: Vec<&str> = t.splitn(3, '.').take(2).collect();
            groups.entry(head.join(".")).or_default().push((k, t));
        }
    }
    let mut found: Option<(usize, usize, String)> = None;
    for members in groups.values() {
        for (i, (ka, ta)) in members.iter().enumerate() {
            for (kb, tb) in &members[i + 1..] {
                if ka != kb && clash(ta, tb) {
                    let (a, b) = ((*ka).min(*kb), (*ka).max(*kb));
                    if found.as_ref().is_none_or(|f| (a, b) < (f.0, f.1)) {
                        found = Some((
                            a,
                            b,
                            if ta.len() <= tb.len() {
                                ta.clone()
                            } else {
                                tb.clone()
                            },
                        ));
                    }
                }
            }
        }
    }
    match found {
        None => Ok(()),
        Some((a, b, value)) => Err(Error::invalid(
            flag,
            format!("{}, {}", axes[a].key, axes[b].key),
            format!(
                "both set `{value}`: one would silently win while the other's values are recorded; give each scene value once (keys are read as --set reads them: `carrier.mass` is `carrier.0.mass` with one carrier; speed_ratio sets every carrier's speed, tension_ratio beam.tension, mass_ratio and stiffness_ratio every carrier's mass and stiffness)"
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> Table {
        include_str!("../../../scenes/reference.toml")
            .parse()
            .unwrap()
    }

    fn axis(key: &str) -> Axis {
        Axis::list(key, vec![1.0, 2.0], false).unwrap()
    }

    fn check(keys: &[&str]) -> Result<()> {
        let axes: Vec<Axis> = keys.iter().map(|k| axis(k)).collect();
        check_one_value_per_key(&axes, &base(), "--points")
    }

    #[test]
    fn aliases_of_one_value_are_refused_naming_both() {
        for pair in [
            ["carrier.mass", "carrier.0.mass"],
            ["carrier.speed.cruise", "speed_ratio"],
            ["carrier.0.speed", "carrier.speed.cruise"],
            ["beam.tension", "tension_ratio"],
            ["mass_ratio", "carrier.0.mass"],
        ] {
            let e = check(&pair).unwrap_err().to_string();
            assert!(
                e.contains(pair[0]) && e.contains(pair[1]) && e.contains("both set"),
                "{e}"
            );
        }
        assert!(
            check(&[
                "carrier.mass",
                "carrier.stiffness",
                "beam.tension",
                "speed_ratio"
            ])
            .is_ok()
        );
        assert!(check(&["beam.tension", "beam.tensions"]).is_ok());
    }
}
