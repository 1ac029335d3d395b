//! Raw bytes on the wire: inline in a message, or streamed after it in `BULK` frames and read
//! by the executor straight into their destination.

use std::borrow::Cow;
use std::fmt;

use serde::de::{DeserializeSeed, EnumAccess, Error as _, VariantAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::ring::RingError;

/// Takes a byte string, borrowed where the input allows.
pub(crate) struct BytesVisitor;

impl<'de> Visitor<'de> for BytesVisitor {
    type Value = Cow<'de, [u8]>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a byte string")
    }
    fn visit_borrowed_bytes<E: serde::de::Error>(self, v: &'de [u8]) -> Result<Self::Value, E> {
        Ok(Cow::Borrowed(v))
    }
    fn visit_bytes<E: serde::de::Error>(self, v: &[u8]) -> Result<Self::Value, E> {
        Ok(Cow::Owned(v.to_vec()))
    }
    fn visit_byte_buf<E: serde::de::Error>(self, v: Vec<u8>) -> Result<Self::Value, E> {
        Ok(Cow::Owned(v))
    }
}

/// Where a streamed blob's bytes come from: the frames after its message ([`crate::ring::Bulk`]).
pub trait BulkSource {
    /// Copies the blob's next `dst.len()` bytes into `dst`.
    fn read(&self, dst: &mut [u8]) -> Result<(), RingError>;
    /// The blob's next `len` bytes, in memory charged to the reader's holdings first.
    fn read_owned(&self, len: usize) -> Result<Vec<u8>, RingError>;
}

impl BulkSource for crate::ring::Bulk<'_> {
    fn read(&self, dst: &mut [u8]) -> Result<(), RingError> {
        crate::ring::Bulk::read(self, dst)
    }
    fn read_owned(&self, len: usize) -> Result<Vec<u8>, RingError> {
        crate::ring::Bulk::read_owned(self, len)
    }
}

/// Raw bytes (vertex data, pixels, shader binaries) sent without per-element encoding: inline
/// in the message, or (a large one a client sends) streamed after it, in which case the
/// daemon reads them once, from the ring into wherever they go.
#[derive(Clone, Default)]
pub struct Blob<'a>(Repr<'a>);

#[derive(Clone)]
enum Repr<'a> {
    /// The bytes themselves.
    Bytes(Cow<'a, [u8]>),
    /// `len` bytes that follow the message, and once attached, where to read them.
    Streamed { len: u64, from: Option<&'a dyn BulkSource> },
}

impl Default for Repr<'_> {
    fn default() -> Self {
        Repr::Bytes(Cow::Borrowed(&[]))
    }
}

impl<'a> Blob<'a> {
    /// Wraps borrowed bytes without copying.
    pub fn borrowed(bytes: &'a [u8]) -> Self {
        Blob(Repr::Bytes(Cow::Borrowed(bytes)))
    }
    /// Wraps owned bytes.
    pub fn owned(bytes: Vec<u8>) -> Blob<'static> {
        Blob(Repr::Bytes(Cow::Owned(bytes)))
    }
    /// The announcement of `len` bytes streamed after the message.
    pub fn streamed(len: u64) -> Self {
        Blob(Repr::Streamed { len, from: None })
    }
    /// The bytes, when they are in the message: a streamed blob has none here until it is
    /// read ([`Blob::read_into`], [`Blob::materialize`]); the daemon hands an executor
    /// streamed blobs only in the commands it says it streams.
    pub fn as_bytes(&self) -> &[u8] {
        match &self.0 {
            Repr::Bytes(b) => b,
            Repr::Streamed { .. } => &[],
        }
    }
    /// Number of bytes (of a streamed blob, as announced).
    pub fn len(&self) -> usize {
        match &self.0 {
            Repr::Bytes(b) => b.len(),
            Repr::Streamed { len, .. } => usize::try_from(*len).unwrap_or(usize::MAX),
        }
    }
    /// Whether there are no bytes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The announced length of a streamed blob.
    pub fn streamed_len(&self) -> Option<u64> {
        match &self.0 {
            Repr::Streamed { len, .. } => Some(*len),
            Repr::Bytes(_) => None,
        }
    }
    /// Names where a streamed blob's bytes are read from.
    pub fn attach(&mut self, source: &'a dyn BulkSource) {
        if let Repr::Streamed { from, .. } = &mut self.0 {
            *from = Some(source);
        }
    }
    /// Copies all the bytes into `dst`, which must be exactly as long; a streamed blob's are
    /// read from its source, once.
    pub fn read_into(&self, dst: &mut [u8]) -> Result<(), RingError> {
        if dst.len() != self.len() {
            return Err(RingError::BadChunk("a blob read into a destination of another length"));
        }
        match &self.0 {
            Repr::Bytes(b) => {
                dst.copy_from_slice(b);
                Ok(())
            }
            Repr::Streamed { from: Some(src), .. } => src.read(dst),
            Repr::Streamed { from: None, .. } => Err(RingError::BadChunk("a streamed blob with no stream")),
        }
    }
    /// Reads a streamed blob's bytes into memory of the daemon's own, so that it can be read
    /// as bytes like any other.
    pub fn materialize(&mut self) -> Result<(), RingError> {
        if let Repr::Streamed { len, from } = &self.0 {
            let src = from.ok_or(RingError::BadChunk("a streamed blob with no stream"))?;
            let len = usize::try_from(*len).map_err(|_| RingError::TooLarge { len: *len, limit: usize::MAX })?;
            self.0 = Repr::Bytes(Cow::Owned(src.read_owned(len)?));
        }
        Ok(())
    }
    /// Detaches the bytes from the buffer they were decoded from (a streamed blob from its
    /// stream).
    pub fn into_owned(self) -> Blob<'static> {
        Blob(match self.0 {
            Repr::Bytes(b) => Repr::Bytes(Cow::Owned(b.into_owned())),
            Repr::Streamed { len, .. } => Repr::Streamed { len, from: None },
        })
    }
}

impl PartialEq for Blob<'_> {
    fn eq(&self, other: &Self) -> bool {
        match (&self.0, &other.0) {
            (Repr::Bytes(a), Repr::Bytes(b)) => a == b,
            (Repr::Streamed { len: a, .. }, Repr::Streamed { len: b, .. }) => a == b,
            _ => false,
        }
    }
}

impl Eq for Blob<'_> {}

impl fmt::Debug for Blob<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Bytes(b) => write!(f, "Blob({} bytes, crc32 {:08x})", b.len(), crc32fast::hash(b)),
            Repr::Streamed { len, .. } => write!(f, "Blob({len} bytes, streamed)"),
        }
    }
}

/// Serializes a byte string as one.
struct ByteStr<'r>(&'r [u8]);

impl Serialize for ByteStr<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_bytes(self.0)
    }
}

const VARIANTS: &[&str] = &["Bytes", "Streamed"];

impl Serialize for Blob<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match &self.0 {
            Repr::Bytes(b) => s.serialize_newtype_variant("Blob", 0, VARIANTS[0], &ByteStr(b)),
            Repr::Streamed { len, .. } => s.serialize_newtype_variant("Blob", 1, VARIANTS[1], len),
        }
    }
}

/// Deserializes a byte string, borrowed where the input allows.
struct BytesSeed;

impl<'de> DeserializeSeed<'de> for BytesSeed {
    type Value = Cow<'de, [u8]>;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_bytes(BytesVisitor)
    }
}

struct BlobVisitor;

impl<'de> Visitor<'de> for BlobVisitor {
    type Value = Blob<'de>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a blob: bytes, or the length of bytes streamed after the message")
    }
    fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<Self::Value, A::Error> {
        let (variant, access): (u32, _) = data.variant()?;
        match variant {
            0 => access.newtype_variant_seed(BytesSeed).map(|b| Blob(Repr::Bytes(b))),
            1 => access.newtype_variant::<u64>().map(Blob::streamed),
            other => Err(A::Error::custom(format_args!("blob variant {other} is neither bytes nor streamed"))),
        }
    }
}

impl<'de: 'a, 'a> Deserialize<'de> for Blob<'a> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_enum("Blob", VARIANTS, BlobVisitor)
    }
}

/// A command field as the command table's generated `split_bulk` and `bulk_mut` see it: a
/// blob (or an optional one) answers for itself; any other field through [`BulkProbeAny`].
#[doc(hidden)]
pub struct BulkProbe<'r, T>(pub &'r T);

impl<'r> BulkProbe<'r, Blob<'_>> {
    /// This blob, or if it holds at least `min` bytes and `out` is still empty, the
    /// announcement of it streamed, its bytes put in `out`.
    pub fn split(&self, min: usize, out: &mut Option<&'r [u8]>) -> Blob<'r> {
        match &self.0 .0 {
            Repr::Bytes(b) if b.len() >= min && out.is_none() => {
                *out = Some(b);
                Blob::streamed(b.len() as u64)
            }
            _ => self.0.clone(),
        }
    }
}

impl<'r> BulkProbe<'r, Option<Blob<'_>>> {
    /// As for a blob, when there is one.
    pub fn split(&self, min: usize, out: &mut Option<&'r [u8]>) -> Option<Blob<'r>> {
        self.0.as_ref().map(|b| BulkProbe(b).split(min, out))
    }
}

/// Any field but a blob: kept as it is.
#[doc(hidden)]
pub trait BulkProbeAny<T> {
    /// A copy of the field.
    fn split(&self, min: usize, out: &mut Option<&[u8]>) -> T;
}

impl<T: Clone> BulkProbeAny<T> for BulkProbe<'_, T> {
    fn split(&self, _: usize, _: &mut Option<&[u8]>) -> T {
        self.0.clone()
    }
}

/// A command field as the generated `bulk_mut` sees it.
#[doc(hidden)]
pub struct BulkProbeMut<'r, T>(pub &'r mut T);

impl<'r, 'a> BulkProbeMut<'r, Blob<'a>> {
    /// This blob, if it is streamed and not yet attached to its stream.
    pub fn streamed(self) -> Option<&'r mut Blob<'a>> {
        matches!(self.0 .0, Repr::Streamed { from: None, .. }).then_some(self.0)
    }
}

impl<'r, 'a> BulkProbeMut<'r, Option<Blob<'a>>> {
    /// The blob, if there is one and it is streamed and not yet attached.
    pub fn streamed(self) -> Option<&'r mut Blob<'a>> {
        self.0.as_mut().and_then(|b| BulkProbeMut(b).streamed())
    }
}

/// Any field but a blob: never streamed.
#[doc(hidden)]
pub trait BulkProbeMutAny<'r> {
    /// Always `None`.
    fn streamed<'a>(self) -> Option<&'r mut Blob<'a>>;
}

impl<'r, T> BulkProbeMutAny<'r> for BulkProbeMut<'r, T> {
    fn streamed<'a>(self) -> Option<&'r mut Blob<'a>> {
        None
    }
}
