//! Tables are tables: a scene's table is read from a TOML table only.
//!
//! serde reads a struct from a sequence too, by position: with a plain
//! derive, `beam.damping = [1.0, 2.0]` became `{ mass = 1, stiffness = 2 }`,
//! `attachment = [[10.0, 1e4]]` an attachment at x = 10 m of stiffness
//! 1e4 N/m, `integrator = ["newmark"]` the Newmark method — silently, and
//! in an order no document gave. `Strict` wraps a deserializer
//! so that every struct it reads, at any depth, refuses a sequence with the
//! form it expects (its keys); everything else reads as before. The scene
//! (`super::scene_from_tree`) and the `[line]` table are read through it.

use std::fmt;

use serde::de::{
    self, DeserializeSeed, Deserializer, EnumAccess, Error as _, MapAccess, SeqAccess,
    VariantAccess, Visitor,
};

/// A deserializer whose structs are read from maps (tables) only.
pub(crate) struct Strict<D>(pub D);

/// A visitor that refuses a sequence where a struct with `fields` is read
/// (`fields` is `None` for any other type), and passes [`Strict`] down to
/// everything it reads.
struct Visit<V> {
    inner: V,
    fields: Option<&'static [&'static str]>,
}

/// The refusal of a sequence given for a table with `fields`.
fn not_a_table<E: de::Error>(fields: &[&str]) -> E {
    let keys: Vec<String> = fields.iter().map(|f| format!("{f} = …")).collect();
    E::custom(format!(
        "expected a table {{ {} }}, not an array: a table's values are given by key, never by position",
        keys.join(", ")
    ))
}

macro_rules! forward_visits {
    ($($method:ident($ty:ty)),* $(,)?) => {
        $(
            fn $method<E: de::Error>(self, v: $ty) -> Result<Self::Value, E> {
                self.inner.$method(v)
            }
        )*
    };
}

impl<'de, V: Visitor<'de>> Visitor<'de> for Visit<V> {
    type Value = V::Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        self.inner.expecting(f)
    }

    forward_visits!(
        visit_bool(bool),
        visit_i8(i8),
        visit_i16(i16),
        visit_i32(i32),
        visit_i64(i64),
        visit_i128(i128),
        visit_u8(u8),
        visit_u16(u16),
        visit_u32(u32),
        visit_u64(u64),
        visit_u128(u128),
        visit_f32(f32),
        visit_f64(f64),
        visit_char(char),
        visit_str(&str),
        visit_borrowed_str(&'de str),
        visit_string(String),
        visit_bytes(&[u8]),
        visit_borrowed_bytes(&'de [u8]),
        visit_byte_buf(Vec<u8>),
    );

    fn visit_none<E: de::Error>(self) -> Result<Self::Value, E> {
        self.inner.visit_none()
    }

    fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
        self.inner.visit_unit()
    }

    fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        self.inner.visit_some(Strict(d))
    }

    fn visit_newtype_struct<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        self.inner.visit_newtype_struct(Strict(d))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
        match self.fields {
            Some(fields) => Err(not_a_table(fields)),
            // an internally tagged enum (`speed = { profile = … }`, a
            // manufactured factor `{ kind = … }`) is read through
            // `deserialize_any`, and serde takes a sequence's first element
            // as its tag and the rest by position: refused as well, told
            // apart by what its visitor expects
            None if tagged_enum(&self.inner) => Err(A::Error::custom(
                "expected a table whose key names its form (`profile = …`, `kind = …`) and its values, not an array: a table's values are given by key, never by position",
            )),
            None => self.inner.visit_seq(Seq(seq)),
        }
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
        self.inner.visit_map(Map(map))
    }

    fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<Self::Value, A::Error> {
        self.inner.visit_enum(Enum(data))
    }
}

/// What a visitor expects, as text.
struct Expecting<'a, V>(&'a V);

impl<'de, V: Visitor<'de>> fmt::Display for Expecting<'_, V> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        self.0.expecting(f)
    }
}

/// Whether `v` reads an internally tagged enum (serde's visitor of one
/// expects "internally tagged enum NAME").
fn tagged_enum<'de, V: Visitor<'de>>(v: &V) -> bool {
    Expecting(v)
        .to_string()
        .starts_with("internally tagged enum")
}

/// A seed whose value is read through [`Strict`].
struct Seed<S>(S);

impl<'de, S: DeserializeSeed<'de>> DeserializeSeed<'de> for Seed<S> {
    type Value = S::Value;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        self.0.deserialize(Strict(d))
    }
}

struct Seq<A>(A);

impl<'de, A: SeqAccess<'de>> SeqAccess<'de> for Seq<A> {
    type Error = A::Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, A::Error> {
        self.0.next_element_seed(Seed(seed))
    }

    fn size_hint(&self) -> Option<usize> {
        self.0.size_hint()
    }
}

struct Map<A>(A);

impl<'de, A: MapAccess<'de>> MapAccess<'de> for Map<A> {
    type Error = A::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, A::Error> {
        self.0.next_key_seed(Seed(seed))
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, A::Error> {
        self.0.next_value_seed(Seed(seed))
    }

    fn size_hint(&self) -> Option<usize> {
        self.0.size_hint()
    }
}

struct Enum<A>(A);

impl<'de, A: EnumAccess<'de>> EnumAccess<'de> for Enum<A> {
    type Error = A::Error;
    type Variant = Variant<A::Variant>;

    fn variant_seed<V: DeserializeSeed<'de>>(
        self,
        seed: V,
    ) -> Result<(V::Value, Self::Variant), A::Error> {
        self.0
            .variant_seed(Seed(seed))
            .map(|(v, variant)| (v, Variant(variant)))
    }
}

struct Variant<A>(A);

impl<'de, A: VariantAccess<'de>> VariantAccess<'de> for Variant<A> {
    type Error = A::Error;

    fn unit_variant(self) -> Result<(), A::Error> {
        self.0.unit_variant()
    }

    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, A::Error> {
        self.0.newtype_variant_seed(Seed(seed))
    }

    fn tuple_variant<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, A::Error> {
        self.0.tuple_variant(
            len,
            Visit {
                inner: visitor,
                fields: None,
            },
        )
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, A::Error> {
        self.0.struct_variant(
            fields,
            Visit {
                inner: visitor,
                fields: Some(fields),
            },
        )
    }
}

macro_rules! forward_deserialize {
    ($($method:ident),* $(,)?) => {
        $(
            fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, D::Error> {
                self.0.$method(Visit { inner: visitor, fields: None })
            }
        )*
    };
}

impl<'de, D: Deserializer<'de>> Deserializer<'de> for Strict<D> {
    type Error = D::Error;

    forward_deserialize!(
        deserialize_any,
        deserialize_bool,
        deserialize_i8,
        deserialize_i16,
        deserialize_i32,
        deserialize_i64,
        deserialize_i128,
        deserialize_u8,
        deserialize_u16,
        deserialize_u32,
        deserialize_u64,
        deserialize_u128,
        deserialize_f32,
        deserialize_f64,
        deserialize_char,
        deserialize_str,
        deserialize_string,
        deserialize_bytes,
        deserialize_byte_buf,
        deserialize_option,
        deserialize_unit,
        deserialize_seq,
        deserialize_map,
        deserialize_identifier,
        deserialize_ignored_any,
    );

    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_unit_struct(
            name,
            Visit {
                inner: visitor,
                fields: None,
            },
        )
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_newtype_struct(
            name,
            Visit {
                inner: visitor,
                fields: None,
            },
        )
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_tuple(
            len,
            Visit {
                inner: visitor,
                fields: None,
            },
        )
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_tuple_struct(
            name,
            len,
            Visit {
                inner: visitor,
                fields: None,
            },
        )
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_struct(
            name,
            fields,
            Visit {
                inner: visitor,
                fields: Some(fields),
            },
        )
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_enum(
            name,
            variants,
            Visit {
                inner: visitor,
                fields: None,
            },
        )
    }

    fn is_human_readable(&self) -> bool {
        self.0.is_human_readable()
    }
}

/// Read a `T` from a TOML value through `Strict` (a struct from a table
/// only), with the path of an error (`serde_path_to_error`).
pub fn from_value<T: de::DeserializeOwned>(
    value: toml::Value,
) -> Result<T, serde_path_to_error::Error<toml::de::Error>> {
    serde_path_to_error::deserialize(Strict(value))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Inner {
        mass: f64,
        #[serde(default)]
        stiffness: f64,
    }

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Outer {
        #[serde(default)]
        inner: Option<Inner>,
        #[serde(default)]
        list: Vec<Inner>,
        #[serde(default)]
        values: Vec<f64>,
    }

    fn read(text: &str) -> Result<Outer, String> {
        let v: toml::Value = toml::Value::Table(text.parse::<toml::Table>().unwrap());
        from_value::<Outer>(v).map_err(|e| format!("{} at {}", e.inner(), e.path()))
    }

    #[test]
    fn a_struct_given_as_an_array_is_refused_at_any_depth() {
        assert_eq!(
            read("inner = { mass = 1.0 }\nvalues = [1.0, 2.0]").unwrap(),
            Outer {
                inner: Some(Inner {
                    mass: 1.0,
                    stiffness: 0.0
                }),
                list: vec![],
                values: vec![1.0, 2.0],
            }
        );
        let e = read("inner = [1.0, 2.0]").unwrap_err();
        assert!(
            e.contains("expected a table { mass = …, stiffness = … }, not an array"),
            "{e}"
        );
        assert!(e.ends_with("at inner"), "{e}");
        let e = read("list = [[1.0, 2.0]]").unwrap_err();
        assert!(
            e.contains("not an array") && e.ends_with("at list[0]"),
            "{e}"
        );
        // a list of tables is still a list
        assert_eq!(read("list = [{ mass = 2.0 }]").unwrap().list.len(), 1);
    }

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(tag = "profile", rename_all = "snake_case", deny_unknown_fields)]
    enum Speed {
        Constant { value: f64 },
    }

    #[derive(Debug, Deserialize, PartialEq)]
    struct WithSpeed {
        speed: Speed,
    }

    #[test]
    fn an_internally_tagged_table_given_as_an_array_is_refused() {
        let read = |text: &str| {
            let v = toml::Value::Table(text.parse::<toml::Table>().unwrap());
            from_value::<WithSpeed>(v).map_err(|e| e.inner().to_string())
        };
        assert_eq!(
            read("speed = { profile = \"constant\", value = 10.0 }").unwrap(),
            WithSpeed {
                speed: Speed::Constant { value: 10.0 }
            }
        );
        let e = read("speed = [\"constant\", 10.0]").unwrap_err();
        assert!(
            e.contains("names its form") && e.contains("not an array"),
            "{e}"
        );
    }
}
