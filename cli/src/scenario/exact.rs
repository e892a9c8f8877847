//! Arrays of a fixed length, read whole. serde reads `[T; N]` as a tuple
//! of `N` elements and the TOML reader does not refuse the elements left
//! over, so `velocity = [1, 0, 7]` would be read as `[1, 0]` and the `7`
//! lost without a word. The fields of the schema that hold a point, a
//! vector or a pair read through these functions instead, which refuse an
//! array of any other length at its place in the file ("invalid length 3,
//! expected an array of length 2").

use std::fmt;
use std::marker::PhantomData;

use serde::de::{Error, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};

/// An array of exactly `N` elements.
struct Exact<T, const N: usize>([T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Elements<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for Elements<T, N> {
            type Value = Exact<T, N>;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an array of length {N}")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut items = Vec::with_capacity(N);
                while let Some(item) = seq.next_element::<T>()? {
                    items.push(item);
                }
                let length = items.len();
                <[T; N]>::try_from(items)
                    .map(Exact)
                    .map_err(|_| A::Error::invalid_length(length, &self))
            }
        }
        deserializer.deserialize_seq(Elements(PhantomData))
    }
}

/// `[T; N]`, refusing an array of another length.
///
/// # Errors
/// The deserializer's error for an array of another length or an element
/// of the wrong type.
pub fn array<'de, D, T, const N: usize>(deserializer: D) -> Result<[T; N], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Exact::<T, N>::deserialize(deserializer).map(|exact| exact.0)
}

/// `Option<[T; N]>` (with `#[serde(default)]`, absent is `None`), refusing
/// an array of another length.
///
/// # Errors
/// As [`array`].
pub fn optional<'de, D, T, const N: usize>(deserializer: D) -> Result<Option<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<Exact<T, N>>::deserialize(deserializer).map(|exact| exact.map(|e| e.0))
}

/// `Vec<[T; N]>`, refusing any element array of another length.
///
/// # Errors
/// As [`array`].
pub fn each<'de, D, T, const N: usize>(deserializer: D) -> Result<Vec<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Vec::<Exact<T, N>>::deserialize(deserializer).map(|v| v.into_iter().map(|e| e.0).collect())
}
