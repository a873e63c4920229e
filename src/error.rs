//! One error type for the whole crate.
//!
//! Every variant carries enough structure to tell the user what went wrong
//! and what is allowed: bad input names the field, the value and the allowed
//! range; a run that goes unstable names the step, the time and the quantity.

use std::path::PathBuf;

/// A typed failure of a layer above this one, carried whole by an [`Error`]
/// variant: boxed behind std's error trait so that the ground floor depends
/// on no higher floor (a contact law's failure with the problem it was
/// given is `contact::ContactFailed`). Its message is the variant's;
/// [`Error::payload`] gets the typed value back.
pub(crate) type Payload = Box<dyn std::error::Error + Send + Sync>;

/// Everything that can go wrong in taut.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scene value outside its allowed range, or a command-line option's
    /// (a `field` that starts with `--`: `invalid option: …`).
    #[error("invalid {}: `{field}` = {value}: {allowed}", invalid_what(field))]
    Invalid {
        /// Dotted path of the offending key, e.g. `beam.length`.
        field: String,
        /// The value as given.
        value: String,
        /// What is allowed, e.g. `must be > 0 (m)`.
        allowed: String,
    },

    /// The scene file could not be parsed (syntax, unknown key, wrong type).
    #[error("cannot read scene: {reason}")]
    Parse {
        /// What is wrong, with the line and column or the key path.
        reason: String,
        /// Dotted path of the table or key at fault (`beam`, `carrier.0.speed`)
        /// when the fault is in one (an unknown key, a wrong type); `None`
        /// for a syntax error or a file that is not a scene.
        field: Option<String>,
    },

    /// Work stopped because it was asked to ([`crate::interrupt`]): Ctrl-C
    /// in the Python module. Not a failure of the run: a sweep keeps no
    /// record of it, so a resumed sweep runs the point again.
    #[error("interrupted on request")]
    Interrupted,

    /// A `--set key.path=value` override that cannot be applied.
    #[error("invalid override `{spec}`: {reason}")]
    Override {
        /// The override as typed.
        spec: String,
        /// Why it was rejected.
        reason: String,
    },

    /// The integration went unstable: non-finite or absurd values.
    #[error(
        "run diverged at step {step} (t = {time:.6} s): {quantity} = {value:e}. Likely cause: {cause}"
    )]
    Diverged {
        /// Step index (1-based: step 1 goes from t = 0 to t = dt).
        step: usize,
        /// Time at the end of the step, s.
        time: f64,
        /// The quantity that left its sane range.
        quantity: String,
        /// Its value.
        value: f64,
        /// A short diagnosis.
        cause: String,
    },

    /// The contact law failed to find forces (e.g. an active set that cycles).
    #[error("contact solve failed at step {step} (t = {time:.6} s): {run}{failure}")]
    Contact {
        /// Step index.
        step: usize,
        /// Time at the end of the step, s.
        time: f64,
        /// Which run of a study it was (`"formulation penalty: "`), or empty.
        run: String,
        /// Why the law failed, with the problem it was given (to save and
        /// replay): a `contact::ContactFailed`, read back by
        /// [`Error::payload`].
        failure: Payload,
    },

    /// A replayed contact problem (`taut replay`) that its law cannot solve,
    /// or whose answer violates the contact conditions.
    #[error("replay of {path}: {reason}")]
    Replay {
        /// The saved problem.
        path: PathBuf,
        /// What failed.
        reason: String,
    },

    /// File system trouble, with the path involved.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },

    /// An accuracy-targeted run (`taut run --tolerance`) that cannot be made
    /// honestly: the quantity does not converge on the pilot runs, or the
    /// resolution it needs is beyond the cost limit.
    #[error("--tolerance {tolerance:e} on --quantity {quantity}: {reason}")]
    Tolerance {
        /// The quantity the tolerance is on (`force`, `force_raw`, …).
        quantity: String,
        /// The requested tolerance.
        tolerance: f64,
        /// What was measured and what to do instead.
        reason: String,
    },

    /// Writing an output (plot, JSON) failed.
    #[error("cannot write output {path}: {reason}")]
    Output {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
}

impl Error {
    /// Name the run a failure happened in, for studies that make several
    /// runs: a divergence or a contact failure gives its step and time, which
    /// alone do not tell one run of a study from another. `run` is prefixed
    /// to the diverged quantity or the contact failure's reason; other
    /// errors are returned as they are.
    pub fn in_run(self, run: &str) -> Self {
        match self {
            Error::Diverged {
                step,
                time,
                quantity,
                value,
                cause,
            } => Error::Diverged {
                step,
                time,
                quantity: format!("{run}: {quantity}"),
                value,
                cause,
            },
            Error::Contact {
                step,
                time,
                run: inner,
                failure,
            } => Error::Contact {
                step,
                time,
                run: format!("{run}: {inner}"),
                failure,
            },
            other => other,
        }
    }

    /// An input error with its key path made another by `path`: an
    /// invalid value's field, and a read error's field and the path its
    /// reason quotes; other errors as they are.
    pub fn map_field(self, path: impl Fn(&str) -> String) -> Self {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
            } => Error::Invalid {
                field: path(&field),
                value,
                allowed,
            },
            Error::Parse {
                reason,
                field: Some(field),
            } => {
                let to = path(&field);
                Error::Parse {
                    reason: reason.replace(&format!("`{field}`"), &format!("`{to}`")),
                    field: Some(to),
                }
            }
            other => other,
        }
    }

    /// An input error (an invalid value, a read error, an override) with
    /// `more` appended to what it says is allowed or wrong (where it
    /// happened: a sweep's point, a refined run); other errors as they are.
    pub fn explained(self, more: &str) -> Self {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
            } => Error::Invalid {
                field,
                value,
                allowed: format!("{allowed}{more}"),
            },
            Error::Parse { reason, field } => Error::Parse {
                reason: format!("{reason}{more}"),
                field,
            },
            Error::Override { spec, reason } => Error::Override {
                spec,
                reason: format!("{reason}{more}"),
            },
            other => other,
        }
    }

    /// Shorthand for an [`Error::Parse`] not tied to a key.
    pub fn parse(reason: impl Into<String>) -> Self {
        Error::Parse {
            reason: reason.into(),
            field: None,
        }
    }

    /// Shorthand for [`Error::Invalid`]. The value is shown as a person
    /// reads it (`for_message`: numbers compact, a huge value clipped),
    /// and so are the numbers in `allowed`.
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        allowed: impl Into<String>,
    ) -> Self {
        Error::Invalid {
            field: clip(&field.into(), MAX_FIELD_CHARS),
            value: for_message(&value.to_string(), MAX_VALUE_CHARS),
            allowed: for_message(&allowed.into(), MAX_MESSAGE_CHARS),
        }
    }

    /// The typed failure a variant carries from a higher layer
    /// (`Payload`), when it is a `T`: `e.payload::<contact::ContactFailed>()`
    /// gives a failed contact solve's problem back.
    pub fn payload<T: std::error::Error + 'static>(&self) -> Option<&T> {
        match self {
            Error::Contact { failure, .. } => failure.downcast_ref::<T>(),
            _ => None,
        }
    }

    /// Attach a path to an I/O error.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// Text for a one-line error message: line breaks become `; ` (a TOML
/// parser's multi-line report, or a key or value that itself holds a line
/// break) and other control characters are escaped, so that every error is
/// one line whatever the input (`taut` prints `error: …` on one line).
pub(crate) fn one_line(text: &str) -> String {
    let text = &for_message(text, MAX_MESSAGE_CHARS);
    let mut out = String::with_capacity(text.len());
    for (i, line) in text
        .split('\n')
        .map(str::trim_end)
        .filter(|l| !l.trim().is_empty())
        .enumerate()
    {
        if i > 0 {
            out.push_str("; ");
        }
        for c in line.chars() {
            if c.is_control() {
                out.extend(c.escape_default());
            } else {
                out.push(c);
            }
        }
    }
    out
}

/// Most characters of a value shown in a message: enough for any number,
/// path or key; a 10 MB string value is shown by its start and its length.
pub(crate) const MAX_VALUE_CHARS: usize = 200;

/// Most characters of a field name (a key path) shown in a message.
pub(crate) const MAX_FIELD_CHARS: usize = 200;

/// Most characters of any one part of a message (a reason, an allowed
/// range): the longest real ones (a divergence's likely cause) are under
/// 1 000.
pub(crate) const MAX_MESSAGE_CHARS: usize = 2000;

/// `text` cut to `max` characters, the cut said with the full length.
pub fn clip(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        None => text.to_string(),
        Some((at, _)) => format!("{}… ({} bytes in all)", &text[..at], text.len()),
    }
}

/// Text for a message: every number written with more than 20 characters
/// (`1e308` as `{}` prints 309 digits, `-1e-300` 302) rewritten compactly
/// ([`compact_number`]), then [`clip`]ped to `max` characters.
pub(crate) fn for_message(text: &str, max: usize) -> String {
    /// A number longer than this is rewritten.
    const LONG_NUMBER: usize = 20;
    let mut out = String::with_capacity(text.len().min(max + 64));
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit()
            || ((b[i] == b'-' || b[i] == b'.') && b.get(i + 1).is_some_and(u8::is_ascii_digit));
        let after_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        if starts && !after_word {
            let mut j = i + 1;
            while j < b.len()
                && (b[j].is_ascii_digit()
                    || b[j] == b'.'
                    || ((b[j] == b'e' || b[j] == b'E') && j + 1 < b.len())
                    || ((b[j] == b'-' || b[j] == b'+') && (b[j - 1] == b'e' || b[j - 1] == b'E')))
            {
                j += 1;
            }
            let run = &text[i..j];
            match run.parse::<f64>() {
                Ok(v) if run.len() > LONG_NUMBER => out.push_str(&compact_number(v)),
                _ => out.push_str(run),
            }
            i = j;
        } else {
            let c = text[i..].chars().next().expect("in bounds");
            out.push(c);
            i += c.len_utf8();
        }
        if out.len() > 4 * max + 64 {
            break;
        }
    }
    match out.char_indices().nth(max) {
        None => out,
        Some((at, _)) => format!("{}… ({} bytes in all)", &out[..at], text.len()),
    }
}

/// A number for a message, compact whatever its size: Rust's shortest
/// round-trip form, plain between 10⁻⁴ and 10¹⁵ (`0.25`, `120`), in
/// exponent form outside (`1e308`, `-1e-300`, where `{}` would print 300
/// digits), `NaN`, `inf` and `-inf` as they are.
pub(crate) fn compact_number(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() || a == 0.0 || (1e-4..1e15).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// What an [`Error::Invalid`] is of: a command-line option (its field a
/// flag, `--threads`) or the scene (a key path, `beam.length`).
/// What an invalid value belongs to, for the message's head: a flag
/// (`--threads`), a shard folder `taut merge` was given (`merge`), a run
/// record of a sweep's folder (`runs`), or else a scene key.
fn invalid_what(field: &str) -> &'static str {
    if field.starts_with("--") {
        "option"
    } else if field == "merge" {
        "merge input"
    } else if field == "runs" || field.starts_with("runs.") {
        "run record"
    } else {
        "scene"
    }
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_numbers_are_compact_and_long_values_clipped() {
        let e = Error::invalid("beam.length", -1e-300, "must be > 0 (m)").to_string();
        assert_eq!(e, "invalid scene: `beam.length` = -1e-300: must be > 0 (m)");
        let e = Error::invalid(
            "beam.length",
            format!("{} m", 1e308),
            format!("in (0, {}] m", 1e308),
        )
        .to_string();
        assert_eq!(e, "invalid scene: `beam.length` = 1e308 m: in (0, 1e308] m");
        // short numbers, keys with digits and words are as they were
        assert_eq!(
            for_message("carrier.0.speed = 120.5, pivot 1e-3, x2 = 3", 100),
            "carrier.0.speed = 120.5, pivot 1e-3, x2 = 3"
        );
        let huge = "a".repeat(10 << 20);
        let e = Error::invalid("beam.left", &huge, "pinned or clamped").to_string();
        assert!(
            e.len() < 400 && e.contains("(10485760 bytes in all)"),
            "{}",
            e.len()
        );
        assert!(one_line(&huge).len() < 2100);
    }

    #[test]
    fn in_run_names_the_run_of_a_divergence_or_contact_failure_only() {
        let diverged = Error::Diverged {
            step: 3,
            time: 0.3,
            quantity: "λ".into(),
            value: 1e9,
            cause: "too large a step".into(),
        }
        .in_run("pilot `base`");
        assert!(
            diverged.to_string().contains("pilot `base`: λ = 1e9"),
            "{diverged}"
        );
        /// A higher layer's failure, as [`Payload`] carries one.
        #[derive(Debug, thiserror::Error)]
        #[error("the active set did not settle")]
        struct Cycling;
        let contact = Error::Contact {
            step: 3,
            time: 0.3,
            run: String::new(),
            failure: Box::new(Cycling),
        }
        .in_run("formulation penalty");
        assert!(
            contact
                .to_string()
                .contains("formulation penalty: the active set did not settle"),
            "{contact}"
        );
        assert!(contact.payload::<Cycling>().is_some());
        let invalid = Error::invalid("mesh.elements", 0, "≥ 1");
        assert_eq!(
            invalid.in_run("pilot `base`").to_string(),
            Error::invalid("mesh.elements", 0, "≥ 1").to_string()
        );
    }
}
