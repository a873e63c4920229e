//! `[messenger] support`: elastic supports of the messenger wire
//! (`docs/lines.md` eq. E1). Without the key every support is pinned
//! (v_m = 0, eq. W3). With it a support is a spring k_s (N/m), a dashpot
//! c_s (N·s/m) and a point mass m_s (kg) to the ground at x_s, the three
//! assembled as a point attachment on the messenger (`k_s r_m r_mᵀ` in K,
//! `c_s r_m r_mᵀ` in C, `m_s r_m r_mᵀ` in M, r_m = r_m(x_s), A0) and the
//! node's messenger w kept as an unknown.
//!
//! Spellings:
//!
//! ```toml
//! support = { stiffness = 5e5, damping = 200.0, mass = 10.0 }   # every support
//! support = ["pinned", { stiffness = 5e5 }, "pinned"]            # one entry per support
//! ```
//!
//! An elastic support needs k_s > 0: a support with only a mass or a dashpot
//! holds nothing at rest, and a messenger held by no spring and no pin is
//! singular (it would hang on the droppers alone). A free end beyond the
//! outermost support is free as before; an elastic support at an end is a
//! free end on a spring.

use toml::Value;

use super::range::{non_negative, positive};
use crate::error::{Error, Result, one_line};

/// One elastic support, resolved (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticSupport {
    /// Spring k_s to the ground, N/m (> 0).
    pub stiffness: f64,
    /// Dashpot c_s to the ground, N·s/m (≥ 0).
    pub damping: f64,
    /// Point mass m_s, kg (≥ 0; carries no weight, as an attachment's).
    pub mass: f64,
}

/// The supports' kinds from `support` (`None`: every one pinned), one
/// entry per support (`None`: pinned), for `count` supports.
pub(crate) fn resolve_support(
    field: &str,
    v: Option<&Value>,
    count: usize,
) -> Result<Vec<Option<ElasticSupport>>> {
    match v {
        None => Ok(vec![None; count]),
        Some(Value::Table(_)) => {
            let s = elastic(field, v.expect("matched Some"))?;
            Ok(vec![Some(s); count])
        }
        Some(Value::Array(list)) => {
            if list.len() != count {
                return Err(Error::invalid(
                    field,
                    format!("a list of {}", list.len()),
                    format!(
                        "must give one entry per support ({count}), each \"pinned\" or {{ stiffness, damping, mass }}; or one table for every support"
                    ),
                ));
            }
            list.iter()
                .enumerate()
                .map(|(i, e)| match e {
                    Value::String(s) if s == "pinned" => Ok(None),
                    Value::Table(_) => elastic(&format!("{field}.{i}"), e).map(Some),
                    other => Err(Error::invalid(
                        format!("{field}.{i}"),
                        one_line(&other.to_string()),
                        "must be \"pinned\" or { stiffness = k_s (N/m, > 0), damping = c_s (N·s/m, ≥ 0), mass = m_s (kg, ≥ 0) }",
                    )),
                })
                .collect()
        }
        Some(other) => Err(Error::invalid(
            field,
            one_line(&other.to_string()),
            "must be { stiffness, damping, mass } (every support) or a list with one \"pinned\" or { … } per support",
        )),
    }
}

/// `{ stiffness, damping, mass }` at `field`: unknown keys refused, k_s > 0,
/// c_s and m_s ≥ 0 (default 0).
fn elastic(field: &str, v: &Value) -> Result<ElasticSupport> {
    let Value::Table(t) = v else {
        unreachable!("called on tables")
    };
    for k in t.keys() {
        if !["stiffness", "damping", "mass"].contains(&k.as_str()) {
            return Err(Error::invalid(
                format!("{field}.{k}"),
                one_line(&t[k].to_string()),
                "is not a key of an elastic support: use stiffness (N/m), damping (N·s/m) and mass (kg)",
            ));
        }
    }
    let number = |k: &str| -> Result<Option<f64>> {
        match t.get(k) {
            None => Ok(None),
            Some(Value::Float(f)) => Ok(Some(*f)),
            Some(Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(other) => Err(Error::invalid(
                format!("{field}.{k}"),
                one_line(&other.to_string()),
                "must be a number",
            )),
        }
    };
    let Some(k) = number("stiffness")? else {
        return Err(Error::invalid(
            format!("{field}.stiffness"),
            "missing",
            "is required (N/m, > 0): a support with no spring and no pin leaves the messenger free (singular); write \"pinned\" for a rigid one",
        ));
    };
    Ok(ElasticSupport {
        stiffness: positive(
            &format!("{field}.stiffness"),
            k,
            "N/m; a support with no spring and no pin leaves the messenger free",
        )?,
        damping: non_negative(
            &format!("{field}.damping"),
            number("damping")?.unwrap_or(0.0),
            "N·s/m",
        )?,
        mass: non_negative(
            &format!("{field}.mass"),
            number("mass")?.unwrap_or(0.0),
            "kg",
        )?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const F: &str = "messenger.support";

    fn parse(text: &str) -> Value {
        let t: toml::Table = toml::from_str(&format!("support = {text}")).unwrap();
        t["support"].clone()
    }

    #[test]
    fn every_support_one_each_or_none() {
        assert_eq!(resolve_support(F, None, 3).unwrap(), vec![None; 3]);
        let all = resolve_support(F, Some(&parse("{ stiffness = 5e5, mass = 2 }")), 2).unwrap();
        let s = ElasticSupport {
            stiffness: 5e5,
            damping: 0.0,
            mass: 2.0,
        };
        assert_eq!(all, vec![Some(s); 2]);
        let each = resolve_support(
            F,
            Some(&parse(
                "[\"pinned\", { stiffness = 5e5, damping = 3.0, mass = 2 }, \"pinned\"]",
            )),
            3,
        )
        .unwrap();
        assert_eq!(each[0], None);
        assert_eq!(each[1].unwrap().damping, 3.0);
        assert_eq!(each[2], None);
    }

    #[test]
    fn bad_values_name_the_field_the_value_and_the_range() {
        for (text, count, want) in [
            (
                "{ stiffness = 0 }",
                2,
                &["messenger.support.stiffness", "0", "> 0"][..],
            ),
            (
                "{ mass = 1 }",
                2,
                &["messenger.support.stiffness", "missing", "singular"],
            ),
            (
                "{ stiffness = 1e5, damping = -1 }",
                2,
                &["messenger.support.damping", "-1", "≥ 0"],
            ),
            (
                "{ stiffness = 1e5, mass = nan }",
                2,
                &["messenger.support.mass", "NaN", "finite"],
            ),
            (
                "{ stiffness = 1e5, stifness = 1 }",
                2,
                &["messenger.support.stifness", "not a key"],
            ),
            (
                "[\"pinned\"]",
                2,
                &[
                    "messenger.support",
                    "a list of 1",
                    "one entry per support (2)",
                ],
            ),
            (
                "[\"pinned\", \"rigid\"]",
                2,
                &["messenger.support.1", "rigid", "\"pinned\""],
            ),
            (
                "[\"pinned\", { stiffness = -3 }]",
                2,
                &["messenger.support.1.stiffness", "-3"],
            ),
            ("3.0", 2, &["messenger.support", "3.0", "every support"]),
        ] {
            let e = resolve_support(F, Some(&parse(text)), count)
                .unwrap_err()
                .to_string();
            for w in want {
                assert!(e.contains(w), "{text}: {e} (wanted {w})");
            }
        }
    }
}
