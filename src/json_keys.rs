//! Duplicate keys in JSON files read back (gate cases, replayed contact
//! problems). serde_json keeps the last copy of a repeated key and drops the
//! first without a word, so a tampered or badly merged file can say one
//! thing to a reader and another to taut; [`reject_duplicate_keys`] makes a
//! repeated key, at any nesting level, an error naming the key and the file.

use std::cell::RefCell;
use std::collections::HashSet;
use std::fmt;
use std::path::Path;

use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};

use crate::error::{Error, Result};

/// Walks any JSON value and stops at the first key repeated in one object,
/// recording its dotted path (`quantities.force_mean`, array entries by
/// index).
struct Walk<'a> {
    path: String,
    duplicate: &'a RefCell<Option<String>>,
}

impl Walk<'_> {
    fn child(&self, segment: &str) -> String {
        if self.path.is_empty() {
            segment.to_string()
        } else {
            format!("{}.{segment}", self.path)
        }
    }
}

impl<'de> DeserializeSeed<'de> for Walk<'_> {
    type Value = ();
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Walk<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }
    fn visit_bool<E>(self, _: bool) -> std::result::Result<(), E> {
        Ok(())
    }
    fn visit_i64<E>(self, _: i64) -> std::result::Result<(), E> {
        Ok(())
    }
    fn visit_u64<E>(self, _: u64) -> std::result::Result<(), E> {
        Ok(())
    }
    fn visit_f64<E>(self, _: f64) -> std::result::Result<(), E> {
        Ok(())
    }
    fn visit_str<E>(self, _: &str) -> std::result::Result<(), E> {
        Ok(())
    }
    fn visit_unit<E>(self) -> std::result::Result<(), E> {
        Ok(())
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> std::result::Result<(), A::Error> {
        let mut i = 0usize;
        while seq
            .next_element_seed(Walk {
                path: self.child(&i.to_string()),
                duplicate: self.duplicate,
            })?
            .is_some()
        {
            i += 1;
        }
        Ok(())
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> std::result::Result<(), A::Error> {
        let mut seen = HashSet::new();
        while let Some(key) = map.next_key::<String>()? {
            let path = self.child(&key);
            if !seen.insert(key) {
                *self.duplicate.borrow_mut() = Some(path.clone());
                return Err(de::Error::custom(format!("duplicate key `{path}`")));
            }
            map.next_value_seed(Walk {
                path,
                duplicate: self.duplicate,
            })?;
        }
        Ok(())
    }
}

/// Refuse JSON `text` (read from `file`) in which an object repeats a key,
/// at any nesting level: an [`Error::Invalid`] naming the file, the key's
/// dotted path and where the second copy is. Text that is not JSON passes:
/// the typed parse that follows reports it.
pub fn reject_duplicate_keys(text: &str, file: &Path) -> Result<()> {
    let duplicate = RefCell::new(None);
    let mut de = serde_json::Deserializer::from_str(text);
    let walked = Walk {
        path: String::new(),
        duplicate: &duplicate,
    }
    .deserialize(&mut de);
    match (walked, duplicate.into_inner()) {
        (Err(e), Some(key)) => Err(Error::invalid(
            format!("{}: {key}", file.display()),
            format!("a second copy (line {}, column {})", e.line(), e.column()),
            "a key may appear once in an object: a JSON reader keeps the last copy and silently drops the first",
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_repeated_key_at_any_depth_is_named_with_its_file() {
        let file = Path::new("suite/case.json");
        let top = r#"{"a": 1, "b": [1, {"c": 2}], "a": 3}"#;
        let e = reject_duplicate_keys(top, file).unwrap_err().to_string();
        assert!(
            e.contains("`suite/case.json: a`") && e.contains("line 1"),
            "{e}"
        );
        let deep = r#"{"q": {"force_mean": {"value": 1, "value": 2}}, "l": [{"x": 1, "x": 1}]}"#;
        let e = reject_duplicate_keys(deep, file).unwrap_err().to_string();
        assert!(e.contains("q.force_mean.value"), "{e}");
        let in_array = r#"{"l": [{"x": 1}, {"x": 1, "x": 2}]}"#;
        let e = reject_duplicate_keys(in_array, file)
            .unwrap_err()
            .to_string();
        assert!(e.contains("l.1.x"), "{e}");
    }

    #[test]
    fn distinct_keys_and_non_json_pass() {
        let file = Path::new("f.json");
        let ok = r#"{"a": {"x": 1}, "b": {"x": [null, true, -1, 2.5e3, "s"]}, "c": []}"#;
        assert!(reject_duplicate_keys(ok, file).is_ok());
        // escapes are compared decoded: "a" and "\u0061" are the same key
        assert!(reject_duplicate_keys(r#"{"a": 1, "\u0061": 2}"#, file).is_err());
        assert!(reject_duplicate_keys("not json {", file).is_ok());
    }
}
