//! Per-dropper properties and clamp masses of a generated line (`[line]`,
//! `docs/lines.md` "Per-dropper properties and clamp masses", E3): the
//! spellings that give each dropper of a span its own stiffness, dashpot
//! and mass, and the masses of the clamps that hold it on each wire.
//!
//! A per-dropper key is one of
//!
//! ```toml
//! dropper_stiffness = 1e5                                  # every dropper
//! dropper_stiffness = [2e5, 1e5, 1e5, 1e5, 2e5]            # one per dropper of a span, every span
//! dropper_stiffness = [[2e5, 1e5, 2e5], [1e5, 1e5, 1e5]]   # a pattern of spans: span k takes row k mod 2
//! ```
//!
//! and is expanded into one value per generated dropper, span by span.
//! Nothing here is physics: the expansion writes plain `[[dropper]]` and
//! `[[attachment]]` keys, whose meaning is D1–D12 and A0/E1.

use toml::Value;

use super::range::{non_negative, positive};
use crate::error::{Error, Result, one_line};

/// A per-dropper key's allowed values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Range {
    /// Finite and > 0.
    Positive,
    /// Finite and ≥ 0.
    NonNegative,
}

/// One value per dropper of the line (`spans` spans of `per_span`
/// droppers, span by span) from the key `field` (module docs); `None`
/// gives `default` everywhere.
pub(crate) fn per_dropper(
    field: &str,
    v: Option<&Value>,
    default: f64,
    (spans, per_span): (usize, usize),
    range: Range,
    unit: &str,
) -> Result<Vec<f64>> {
    let check = |f: &str, x: f64| match range {
        Range::Positive => positive(f, x, unit),
        Range::NonNegative => non_negative(f, x, unit),
    };
    let number = |f: &str, v: &Value| -> Result<f64> {
        match v {
            Value::Float(x) => check(f, *x),
            Value::Integer(i) => check(f, *i as f64),
            other => Err(Error::invalid(
                f,
                one_line(&other.to_string()),
                format!("must be a number ({unit})"),
            )),
        }
    };
    let row = |f: &str, list: &[Value]| -> Result<Vec<f64>> {
        if list.len() != per_span {
            return Err(Error::invalid(
                f,
                format!("a list of {}", list.len()),
                format!(
                    "must give one value per dropper of a span ({per_span}, as line.droppers), a list of such lists (a pattern of spans), or one number ({unit})"
                ),
            ));
        }
        list.iter()
            .enumerate()
            .map(|(i, x)| number(&format!("{f}.{i}"), x))
            .collect()
    };
    let pattern: Vec<Vec<f64>> = match v {
        None => vec![vec![default; per_span]],
        Some(Value::Array(list)) if list.iter().all(|x| matches!(x, Value::Array(_))) => {
            if list.is_empty() || list.len() > spans {
                return Err(Error::invalid(
                    field,
                    format!("a pattern of {} spans", list.len()),
                    format!(
                        "must have 1 ..= {spans} rows (line.spans): span k takes row k mod rows"
                    ),
                ));
            }
            list.iter()
                .enumerate()
                .map(|(r, x)| {
                    let Value::Array(x) = x else {
                        unreachable!("rows checked above")
                    };
                    row(&format!("{field}.{r}"), x)
                })
                .collect::<Result<_>>()?
        }
        Some(Value::Array(list)) => vec![row(field, list)?],
        Some(x) => vec![vec![number(field, x)?; per_span]],
    };
    Ok((0..spans)
        .flat_map(|k| pattern[k % pattern.len()].iter().copied())
        .collect())
}

/// Every dropper's properties (span by span) from `[line]`.
pub(crate) struct DropperProps {
    /// k_d, N/m.
    pub stiffness: Vec<f64>,
    /// c_d, N·s/m.
    pub damping: Vec<f64>,
    /// The point masses at the droppers' ends.
    pub end_mass: EndMasses,
    /// Each dropper's own mass as written (`line.dropper_mass`), kg.
    pub own_mass: Vec<f64>,
    /// Each dropper's clamps as written (`line.clamp_mass`): (contact,
    /// messenger), kg.
    pub clamp_mass: (Vec<f64>, Vec<f64>),
}

/// The point masses at each dropper's two ends (E3), kg.
pub(crate) struct EndMasses {
    /// At the lower end (contact wire): its clamp plus half the dropper's
    /// own mass.
    lower: Vec<f64>,
    /// The same at the upper end (messenger); 0 on a fixed anchor, which
    /// holds the upper half.
    upper: Vec<f64>,
}

impl EndMasses {
    /// The `[[attachment]]` tables of the droppers `(name, x_d)`: on the
    /// contact wire (`clamp_<name>`), then on the messenger
    /// (`messenger_clamp_<name>`, `wire = "messenger"`); none where the
    /// mass is 0.
    pub(crate) fn tables<'a>(
        &self,
        droppers: impl Iterator<Item = (&'a str, f64)> + Clone,
    ) -> Vec<Value> {
        let at = |side: &str, wire: Option<&str>, masses: &[f64]| -> Vec<Value> {
            droppers
                .clone()
                .zip(masses)
                .filter(|(_, m)| **m != 0.0)
                .map(|((name, x), m)| {
                    let mut t = toml::Table::new();
                    t.insert("name".into(), Value::String(format!("{side}_{name}")));
                    t.insert("x".into(), Value::Float(x));
                    t.insert("mass".into(), Value::Float(*m));
                    if let Some(w) = wire {
                        t.insert("wire".into(), Value::String(w.into()));
                    }
                    Value::Table(t)
                })
                .collect()
        };
        let mut out = at("clamp", None, &self.lower);
        out.extend(at("messenger_clamp", Some("messenger"), &self.upper));
        out
    }

    /// How many of [`EndMasses::tables`]' tables are on the contact wire
    /// (the first ones).
    pub(crate) fn contact_count(&self) -> usize {
        self.lower.iter().filter(|m| **m != 0.0).count()
    }

    /// How many tables [`EndMasses::tables`] writes.
    pub(crate) fn count(&self) -> usize {
        self.lower
            .iter()
            .chain(&self.upper)
            .filter(|m| **m != 0.0)
            .count()
    }
}

/// `dropper_stiffness`, `dropper_damping`, `dropper_mass` and
/// `clamp_mass` of a line of `shape` = (spans, droppers a span) as each
/// dropper's values (E3); `fixed_anchor`: the upper ends are fixed points
/// (a messenger clamp mass is refused).
pub(crate) fn dropper_props(
    (stiffness, damping, mass, clamp): (&Value, Option<&Value>, Option<&Value>, Option<&Value>),
    shape: (usize, usize),
    fixed_anchor: bool,
) -> Result<DropperProps> {
    let [stiffness, damping, own] = [
        (
            "line.dropper_stiffness",
            Some(stiffness),
            Range::Positive,
            "N/m",
        ),
        ("line.dropper_damping", damping, Range::NonNegative, "N·s/m"),
        ("line.dropper_mass", mass, Range::NonNegative, "kg"),
    ]
    .map(|(field, v, range, unit)| per_dropper(field, v, 0.0, shape, range, unit));
    let own = own?;
    let (clamp_c, clamp_m) = clamp_masses(clamp, shape)?;
    if fixed_anchor && let Some(i) = clamp_m.iter().position(|&m| m != 0.0) {
        return Err(Error::invalid(
            "line.clamp_mass.messenger",
            clamp_m[i],
            "must be 0 (kg) with line.anchor = \"fixed\": the droppers' upper ends are fixed points, which no mass moves; use anchor = \"messenger\"",
        ));
    }
    let ends =
        |clamp: &[f64]| -> Vec<f64> { clamp.iter().zip(&own).map(|(c, m)| c + 0.5 * m).collect() };
    Ok(DropperProps {
        stiffness: stiffness?,
        damping: damping?,
        end_mass: EndMasses {
            lower: ends(&clamp_c),
            upper: if fixed_anchor {
                vec![0.0; own.len()]
            } else {
                ends(&clamp_m)
            },
        },
        own_mass: own,
        clamp_mass: (clamp_c, clamp_m),
    })
}

/// `line.clamp_mass = { contact = …, messenger = … }`: each a per-dropper
/// key (kg, ≥ 0, default 0); (contact side, messenger side), one value per
/// dropper of the line.
pub(crate) fn clamp_masses(
    v: Option<&Value>,
    shape: (usize, usize),
) -> Result<(Vec<f64>, Vec<f64>)> {
    let field = "line.clamp_mass";
    let t = match v {
        None => None,
        Some(Value::Table(t)) => Some(t),
        Some(other) => {
            return Err(Error::invalid(
                field,
                one_line(&other.to_string()),
                "must be { contact = m_c, messenger = m_m } (kg, each a number or a per-dropper list)",
            ));
        }
    };
    if let Some(t) = t
        && let Some(k) = t.keys().find(|k| *k != "contact" && *k != "messenger")
    {
        return Err(Error::invalid(
            format!("{field}.{k}"),
            one_line(&t[k].to_string()),
            "is not a side of a dropper: use contact (the clamp on the contact wire) and messenger (kg)",
        ));
    }
    let side = |s: &str| {
        per_dropper(
            &format!("{field}.{s}"),
            t.and_then(|t| t.get(s)),
            0.0,
            shape,
            Range::NonNegative,
            "kg",
        )
    };
    Ok((side("contact")?, side("messenger")?))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(text: &str) -> Value {
        let t: toml::Table = toml::from_str(&format!("k = {text}")).unwrap();
        t["k"].clone()
    }

    fn expand(text: &str) -> Result<Vec<f64>> {
        per_dropper(
            "line.k",
            Some(&value(text)),
            0.0,
            (3, 2),
            Range::Positive,
            "N/m",
        )
    }

    #[test]
    fn a_number_a_list_and_a_pattern_of_spans() {
        assert_eq!(expand("5").unwrap(), vec![5.0; 6]);
        assert_eq!(
            expand("[1.0, 2.0]").unwrap(),
            [1.0, 2.0, 1.0, 2.0, 1.0, 2.0]
        );
        assert_eq!(
            expand("[[1.0, 2.0], [3.0, 4.0]]").unwrap(),
            [1.0, 2.0, 3.0, 4.0, 1.0, 2.0]
        );
        let none = per_dropper("line.k", None, 7.0, (2, 2), Range::Positive, "N/m").unwrap();
        assert_eq!(none, vec![7.0; 4]);
    }

    #[test]
    fn bad_values_name_the_field_the_value_and_the_range() {
        for (text, want) in [
            ("0", &["line.k", "0", "> 0"][..]),
            (
                "[1.0, 2.0, 3.0]",
                &["line.k", "a list of 3", "(2, as line.droppers)"],
            ),
            ("[1.0, -2.0]", &["line.k.1", "-2", "> 0"]),
            ("[[1.0, 2.0], [3.0]]", &["line.k.1", "a list of 1"]),
            ("[[1.0, 2.0], [3.0, 0.0]]", &["line.k.1.1", "0"]),
            (
                "[[1.0, 2.0], [1.0, 2.0], [1.0, 2.0], [1.0, 2.0]]",
                &["line.k", "4 spans", "1 ..= 3"],
            ),
            ("\"stiff\"", &["line.k", "stiff", "number"]),
        ] {
            let e = expand(text).unwrap_err().to_string();
            for w in want {
                assert!(e.contains(w), "{text}: {e} (wanted {w})");
            }
        }
        let e = clamp_masses(Some(&value("{ contakt = 1.0 }")), (1, 1))
            .unwrap_err()
            .to_string();
        assert!(e.contains("line.clamp_mass.contakt"), "{e}");
        let e = clamp_masses(Some(&value("{ messenger = -1.0 }")), (1, 1))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("line.clamp_mass.messenger") && e.contains("≥ 0"),
            "{e}"
        );
    }
}
