//! The values replies carry besides scalars and strings: active variables, stream tallies,
//! executor counters, debug messages and raw bytes, with the limits that bound them.

use serde::{Deserialize, Serialize};

use crate::wire::*;

/// What `glGetActiveAttrib` / `glGetActiveUniform` report about one variable.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ActiveVariable {
    /// Array size (1 for non-arrays).
    pub size: GLint,
    /// GL type enum, e.g. `GL_FLOAT_VEC4`.
    pub ty: GLenum,
    /// The name as the application sees it.
    pub name: String,
}

/// The daemon's count and CRC-32 of the messages it has decoded from one client.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct StreamTally {
    /// Messages decoded before the verify call.
    pub commands: u64,
    /// CRC-32 over the encoded bytes of those messages, in order.
    pub crc32: u32,
    /// Whether they equal what the client said it sent.
    pub matches: bool,
}

/// Counters an executor keeps about one client, for benchmarks and diagnostics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct ExecStats {
    /// Render pipelines created because none in the cache matched.
    pub pipeline_cache_misses: u64,
    /// Render passes submitted.
    pub render_passes: u64,
    /// Draw calls recorded.
    pub draws: u64,
}

/// One `GL_KHR_debug` message, as `glGetDebugMessageLogKHR` and the debug callback report it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DebugMessage {
    /// `GL_DEBUG_SOURCE_*_KHR`.
    pub source: GLenum,
    /// `GL_DEBUG_TYPE_*_KHR`.
    pub ty: GLenum,
    /// The message's id within its source and type.
    pub id: GLuint,
    /// `GL_DEBUG_SEVERITY_*_KHR`.
    pub severity: GLenum,
    /// The text, without a terminating NUL.
    pub text: Bytes,
}

/// `GL_MAX_LABEL_LENGTH_KHR`: a label must be shorter than this (in bytes).
pub const MAX_LABEL_LENGTH: GLsizei = 256;
/// `GL_MAX_DEBUG_MESSAGE_LENGTH_KHR`: a message must be shorter than this (in bytes).
pub const MAX_DEBUG_MESSAGE_LENGTH: GLsizei = 4096;
/// `GL_MAX_DRAW_BUFFERS_EXT` and `GL_MAX_COLOR_ATTACHMENTS_EXT`: the colour buffers one draw
/// writes (`GL_EXT_draw_buffers`).
pub const MAX_DRAW_BUFFERS: GLsizei = 8;

/// Owned raw bytes in a reply (e.g. `glReadPixels`), encoded without per-element framing.
#[derive(Clone, PartialEq, Eq, Default)]
pub struct Bytes(pub Vec<u8>);

impl std::fmt::Debug for Bytes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Bytes({} bytes)", self.0.len())
    }
}

/// In a human-readable format (the JSON control protocol) the bytes are one base64 string;
/// in the binary codec, raw.
impl Serialize for Bytes {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if s.is_human_readable() {
            s.serialize_str(&data_encoding::BASE64.encode(&self.0))
        } else {
            s.serialize_bytes(&self.0)
        }
    }
}

impl<'de> Deserialize<'de> for Bytes {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        if d.is_human_readable() {
            let text = String::deserialize(d)?;
            data_encoding::BASE64.decode(text.as_bytes()).map(Bytes).map_err(serde::de::Error::custom)
        } else {
            d.deserialize_bytes(crate::wire::BytesVisitor).map(|b| Bytes(b.into_owned()))
        }
    }
}

/// Proptest strategies for the reply types (the command strategies are `Opcode::strategy`).
#[cfg(feature = "arbitrary")]
mod strategies {
    use super::*;
    use proptest::prelude::*;

    impl Arbitrary for ActiveVariable {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            (any::<GLint>(), any::<GLenum>(), any::<String>())
                .prop_map(|(size, ty, name)| ActiveVariable { size, ty, name })
                .boxed()
        }
    }

    impl Arbitrary for StreamTally {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            (any::<u64>(), any::<u32>(), any::<bool>())
                .prop_map(|(commands, crc32, matches)| StreamTally { commands, crc32, matches })
                .boxed()
        }
    }

    impl Arbitrary for ExecStats {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            (any::<u64>(), any::<u64>(), any::<u64>())
                .prop_map(|(pipeline_cache_misses, render_passes, draws)| ExecStats {
                    pipeline_cache_misses,
                    render_passes,
                    draws,
                })
                .boxed()
        }
    }

    impl Arbitrary for DebugMessage {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            (any::<GLenum>(), any::<GLenum>(), any::<GLuint>(), any::<GLenum>(), any::<Bytes>())
                .prop_map(|(source, ty, id, severity, text)| DebugMessage { source, ty, id, severity, text })
                .boxed()
        }
    }

    impl Arbitrary for Bytes {
        type Parameters = ();
        type Strategy = BoxedStrategy<Self>;
        fn arbitrary_with(_: ()) -> Self::Strategy {
            proptest::collection::vec(any::<u8>(), 0..300).prop_map(Bytes).boxed()
        }
    }
}
