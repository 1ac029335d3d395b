//! Field types that carry bulk data on the wire as raw bytes, borrowed from the reader's
//! private copy on decode.

mod blob;

pub(crate) use blob::BytesVisitor;
pub use blob::{Blob, BulkProbe, BulkProbeAny, BulkProbeMut, BulkProbeMutAny, BulkSource};

use std::borrow::Cow;
use std::fmt;
use std::marker::PhantomData;

use bytemuck::Pod;
use serde::de::{Error as _, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// GL enumerant.
pub type GLenum = u32;
/// GL object name (client-allocated).
pub type GLuint = u32;
/// GL signed integer.
pub type GLint = i32;
/// GL size or count.
pub type GLsizei = i32;
/// GL single-precision float.
pub type GLfloat = f32;
/// GL bitfield of flags.
pub type GLbitfield = u32;
/// EGL handle (display, config, surface or context) as the daemon numbers it.
pub type EglHandle = u32;
/// EGL attribute or integer value.
pub type EGLint = i32;

/// UTF-8 text (shader sources, identifiers, logs), borrowed from the ring on decode.
#[derive(Clone, PartialEq, Eq, Default)]
pub struct Text<'a>(pub Cow<'a, str>);

impl<'a> Text<'a> {
    /// Wraps a borrowed string without copying.
    pub fn borrowed(s: &'a str) -> Self {
        Text(Cow::Borrowed(s))
    }
    /// Wraps an owned string.
    pub fn owned(s: String) -> Text<'static> {
        Text(Cow::Owned(s))
    }
    /// The string.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl fmt::Debug for Text<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&*self.0, f)
    }
}

impl Serialize for Text<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.0)
    }
}

struct StrVisitor;

impl<'de> Visitor<'de> for StrVisitor {
    type Value = Cow<'de, str>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a UTF-8 string")
    }
    fn visit_borrowed_str<E: serde::de::Error>(self, v: &'de str) -> Result<Self::Value, E> {
        Ok(Cow::Borrowed(v))
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Self::Value, E> {
        Ok(Cow::Owned(v.to_owned()))
    }
    fn visit_string<E: serde::de::Error>(self, v: String) -> Result<Self::Value, E> {
        Ok(Cow::Owned(v))
    }
}

impl<'de: 'a, 'a> Deserialize<'de> for Text<'a> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_str(StrVisitor).map(Text)
    }
}

/// A typed array (names, floats, ints) carried as its native-endian bytes, so that decoding
/// borrows instead of allocating. Client and daemon share one host, hence one byte order.
#[derive(Clone, PartialEq, Eq)]
pub struct Slice<'a, T: Pod> {
    bytes: Cow<'a, [u8]>,
    _ty: PhantomData<T>,
}

impl<'a, T: Pod> Slice<'a, T> {
    /// Borrows a typed slice as bytes without copying.
    pub fn new(values: &'a [T]) -> Self {
        Slice { bytes: Cow::Borrowed(bytemuck::cast_slice(values)), _ty: PhantomData }
    }
    /// Takes ownership of a vector of values.
    pub fn from_vec(values: Vec<T>) -> Slice<'static, T> {
        Slice { bytes: Cow::Owned(bytemuck::cast_slice(&values).to_vec()), _ty: PhantomData }
    }
    /// Number of elements.
    pub fn len(&self) -> usize {
        self.bytes.len() / std::mem::size_of::<T>()
    }
    /// Whether the array is empty.
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }
    /// Element `i`, read without any alignment requirement.
    pub fn get(&self, i: usize) -> Option<T> {
        let n = std::mem::size_of::<T>();
        self.bytes.get(i * n..(i + 1) * n).map(bytemuck::pod_read_unaligned)
    }
    /// Iterates over the elements.
    pub fn iter(&self) -> impl Iterator<Item = T> + '_ {
        self.bytes.chunks_exact(std::mem::size_of::<T>()).map(bytemuck::pod_read_unaligned)
    }
    /// The raw native-endian bytes.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes
    }
    /// Copies the elements into a vector.
    pub fn to_vec(&self) -> Vec<T> {
        self.iter().collect()
    }
}

impl<T: Pod + fmt::Debug> fmt::Debug for Slice<'_, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<T: Pod> Serialize for Slice<'_, T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_bytes(&self.bytes)
    }
}

impl<'de: 'a, 'a, T: Pod> Deserialize<'de> for Slice<'a, T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let bytes = d.deserialize_bytes(BytesVisitor)?;
        if bytes.len() % std::mem::size_of::<T>() != 0 {
            return Err(D::Error::custom(format_args!(
                "array of {} bytes is not a whole number of {}-byte elements",
                bytes.len(),
                std::mem::size_of::<T>()
            )));
        }
        Ok(Slice { bytes, _ty: PhantomData })
    }
}

/// Proptest strategies for the bulk field types.
#[cfg(feature = "arbitrary")]
mod strategies {
    use super::*;
    use proptest::prelude::*;

    impl Arbitrary for Blob<'static> {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            proptest::collection::vec(any::<u8>(), 0..300).prop_map(Blob::owned).boxed()
        }
    }

    impl Arbitrary for Text<'static> {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            any::<String>().prop_map(Text::owned).boxed()
        }
    }

    impl<T: Pod + Arbitrary + fmt::Debug> Arbitrary for Slice<'static, T> {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            proptest::collection::vec(any::<T>(), 0..40).prop_map(Slice::from_vec).boxed()
        }
    }
}

/// `arbitrary::Arbitrary` for the bulk field types, borrowing from the fuzzer's input as a
/// decoded command borrows from the ring.
#[cfg(feature = "arbitrary")]
mod fuzzing {
    use super::*;
    use ::arbitrary::{Arbitrary, Result, Unstructured};

    impl<'a> Arbitrary<'a> for Blob<'a> {
        fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
            Ok(Blob::borrowed(<&[u8]>::arbitrary(u)?))
        }
    }

    impl<'a> Arbitrary<'a> for Text<'a> {
        fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
            Ok(Text::borrowed(<&str>::arbitrary(u)?))
        }
    }

    impl<'a, T: Pod> Arbitrary<'a> for Slice<'a, T> {
        fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
            // A whole number of elements, as decoding requires.
            let len = u.arbitrary_len::<u8>()?;
            let bytes = u.bytes(len - len % std::mem::size_of::<T>().max(1))?;
            Ok(Slice { bytes: Cow::Borrowed(bytes), _ty: PhantomData })
        }
    }
}
