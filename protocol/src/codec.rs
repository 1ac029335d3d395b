//! The one place that knows the byte encoding of commands, replies and handshake messages
//! (bincode 2, varint integers). Swapping the codec means changing only this module.

use bincode::config::{Configuration, Limit, LittleEndian, Varint};
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::commands::{Command, Opcode, Reply};

/// The largest message (command, reply or handshake) either side accepts: 512 MiB.
pub const MAX_MESSAGE_LEN: usize = 512 << 20;

type Config = Configuration<LittleEndian, Varint, Limit<MAX_MESSAGE_LEN>>;

fn config() -> Config {
    bincode::config::standard().with_limit::<MAX_MESSAGE_LEN>()
}

/// Why a message could not be encoded or decoded.
#[derive(Debug, thiserror::Error)]
pub enum CodecError {
    /// The opcode is outside the command set.
    #[error("unknown command opcode {opcode} (this daemon knows {known})")]
    UnknownCommand {
        /// The opcode the client sent.
        opcode: u64,
        /// How many opcodes the protocol defines.
        known: usize,
    },
    /// The message is empty, truncated or otherwise not a valid encoding.
    #[error("malformed {what}: {reason}")]
    Malformed {
        /// What was being decoded, e.g. `glBufferData`.
        what: String,
        /// The decoder's complaint.
        reason: String,
    },
    /// The message decoded but left bytes over.
    #[error("{what} decoded from {used} of {len} bytes; trailing bytes are not allowed")]
    TrailingBytes {
        /// What was decoded.
        what: &'static str,
        /// Bytes the value used.
        used: usize,
        /// Bytes the message had.
        len: usize,
    },
    /// The value could not be encoded.
    #[error("encode failed: {0}")]
    Encode(#[from] bincode::error::EncodeError),
}

/// Bytes `value` takes when encoded.
pub fn encoded_len<T: Serialize + ?Sized>(value: &T) -> Result<usize, CodecError> {
    let mut w = bincode::enc::write::SizeWriter::default();
    bincode::serde::encode_into_writer(value, &mut w, config())?;
    Ok(w.bytes_written)
}

/// Encodes `value` into the front of `dst`, returning the bytes written.
pub fn encode_into<T: Serialize + ?Sized>(value: &T, dst: &mut [u8]) -> Result<usize, CodecError> {
    Ok(bincode::serde::encode_into_slice(value, dst, config())?)
}

/// Encodes `value` into a new vector.
pub fn encode_to_vec<T: Serialize + ?Sized>(value: &T) -> Result<Vec<u8>, CodecError> {
    Ok(bincode::serde::encode_to_vec(value, config())?)
}

/// Reads the leading variant index (a bincode varint) without decoding the rest.
fn peek_variant(bytes: &[u8]) -> Option<u64> {
    let (&tag, rest) = bytes.split_first()?;
    let take = |n: usize| -> Option<u64> {
        let b = rest.get(..n)?;
        let mut v = [0u8; 8];
        v[..n].copy_from_slice(b);
        Some(u64::from_le_bytes(v))
    };
    match tag {
        0..=250 => Some(u64::from(tag)),
        251 => take(2),
        252 => take(4),
        253 => take(8),
        _ => None,
    }
}

/// The opcode at the start of an encoded command, without decoding the rest (for a command
/// the daemon refuses unread, such as one beyond the client's size limit).
pub fn peek_opcode(bytes: &[u8]) -> Option<Opcode> {
    peek_variant(bytes).and_then(|i| u32::try_from(i).ok()).and_then(Opcode::from_index)
}

/// Decodes one command, borrowing bulk data from `bytes`. Every byte must be used.
pub fn decode_command(bytes: &[u8]) -> Result<Command<'_>, CodecError> {
    let index = peek_variant(bytes).ok_or_else(|| CodecError::Malformed {
        what: "command".into(),
        reason: format!("no valid opcode at the start of a {}-byte message", bytes.len()),
    })?;
    let opcode = u32::try_from(index)
        .ok()
        .and_then(Opcode::from_index)
        .ok_or(CodecError::UnknownCommand { opcode: index, known: Opcode::COUNT })?;
    let (cmd, used) = bincode::serde::borrow_decode_from_slice::<Command<'_>, _>(bytes, config())
        .map_err(|e| CodecError::Malformed { what: opcode.name().into(), reason: e.to_string() })?;
    if used != bytes.len() {
        return Err(CodecError::TrailingBytes { what: opcode.name(), used, len: bytes.len() });
    }
    Ok(cmd)
}

/// Decodes one reply. Every byte must be used. The client trusts the daemon, and a reply's
/// decoded size may be many times its encoded size (a list of many small items), so replies
/// get the whole limit rather than one that follows their size.
pub fn decode_reply(bytes: &[u8]) -> Result<Reply, CodecError> {
    decode_owned_within::<Reply, MAX_MESSAGE_LEN>(bytes, "reply")
}

/// Decodes an owned value (handshake messages, replies). Every byte must be used.
///
/// bincode allocates an owned string or byte array at its announced length before reading it,
/// within the configured limit. A valid message announces at most its own length in all, so the
/// limit follows the message's size: a forged length costs at most 16 times the bytes that
/// carried it (and never more than [`MAX_MESSAGE_LEN`]), not the whole limit.
pub fn decode_owned<T: DeserializeOwned>(bytes: &[u8], what: &'static str) -> Result<T, CodecError> {
    let n = bytes.len();
    if n <= 4 << 10 {
        decode_owned_within::<T, { 4 << 10 }>(bytes, what)
    } else if n <= 64 << 10 {
        decode_owned_within::<T, { 64 << 10 }>(bytes, what)
    } else if n <= 1 << 20 {
        decode_owned_within::<T, { 1 << 20 }>(bytes, what)
    } else if n <= 16 << 20 {
        decode_owned_within::<T, { 16 << 20 }>(bytes, what)
    } else if n <= 256 << 20 {
        decode_owned_within::<T, { 256 << 20 }>(bytes, what)
    } else {
        decode_owned_within::<T, MAX_MESSAGE_LEN>(bytes, what)
    }
}

/// Decodes an owned value from a peer the reader trusts (the daemon, for a client), within the
/// whole message limit. Every byte must be used.
pub fn decode_trusted<T: DeserializeOwned>(bytes: &[u8], what: &'static str) -> Result<T, CodecError> {
    decode_owned_within::<T, MAX_MESSAGE_LEN>(bytes, what)
}

/// [`decode_owned`] with at most `LIMIT` bytes of owned strings and byte arrays.
fn decode_owned_within<T: DeserializeOwned, const LIMIT: usize>(
    bytes: &[u8],
    what: &'static str,
) -> Result<T, CodecError> {
    let config = bincode::config::standard().with_limit::<LIMIT>();
    let (v, used) = bincode::serde::decode_from_slice::<T, _>(bytes, config)
        .map_err(|e| CodecError::Malformed { what: what.into(), reason: e.to_string() })?;
    if used != bytes.len() {
        return Err(CodecError::TrailingBytes { what, used, len: bytes.len() });
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use proptest::test_runner::{Config as PtConfig, TestRunner};

    /// Every variant, not just a random sample: each opcode gets its own proptest run.
    #[test]
    fn every_command_round_trips() {
        for &op in Opcode::ALL {
            let mut runner = TestRunner::new(PtConfig { cases: 48, ..PtConfig::default() });
            runner
                .run(&op.strategy(), |cmd| {
                    prop_assert_eq!(cmd.opcode(), op);
                    let bytes = encode_to_vec(&cmd).expect("encode");
                    prop_assert_eq!(encoded_len(&cmd).expect("len"), bytes.len());
                    let back = decode_command(&bytes).expect("decode");
                    // Byte equality after re-encoding also covers NaN fields.
                    prop_assert_eq!(encode_to_vec(&back).expect("re-encode"), bytes.clone());
                    prop_assert_eq!(format!("{back:?}"), format!("{cmd:?}"));
                    Ok(())
                })
                .unwrap_or_else(|e| panic!("{}: {e}", op.name()));
        }
    }

    #[test]
    fn every_reply_round_trips() {
        for &op in Opcode::ALL {
            let Some(strategy) = op.reply_strategy() else { continue };
            let mut runner = TestRunner::new(PtConfig { cases: 48, ..PtConfig::default() });
            runner
                .run(&strategy, |reply| {
                    prop_assert_eq!(reply.opcode(), Some(op));
                    let bytes = encode_to_vec(&reply).expect("encode");
                    let back = decode_reply(&bytes).expect("decode");
                    prop_assert_eq!(encode_to_vec(&back).expect("re-encode"), bytes);
                    Ok(())
                })
                .unwrap_or_else(|e| panic!("{}: {e}", op.name()));
        }
    }

    #[test]
    fn unknown_opcode_is_named() {
        let bytes = [251u8, 0x60, 0xEA]; // varint 60000
        match decode_command(&bytes) {
            Err(CodecError::UnknownCommand { opcode: 60000, .. }) => {}
            other => panic!("expected UnknownCommand, got {other:?}"),
        }
    }

    /// A forged length in a short message fails on the limit, before bincode allocates the
    /// announced bytes: a 7-byte hello may not cost the daemon 256 MiB.
    #[test]
    fn forged_string_length_is_refused_before_allocating() {
        // `Hello::name`: a string announcing 256 MiB (varint 253 + u64), then nothing.
        let mut bytes = vec![253u8];
        bytes.extend_from_slice(&(256u64 << 20).to_le_bytes());
        match decode_owned::<crate::handshake::Hello>(&bytes, "hello") {
            Err(CodecError::Malformed { reason, .. }) => {
                assert!(reason.contains("LimitExceeded"), "refused only after allocating: {reason}")
            }
            other => panic!("expected a malformed hello, got {other:?}"),
        }
    }

    proptest! {
        /// Garbage never panics the decoder; it is either a command or an error.
        #[test]
        fn garbage_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
            let _ = decode_command(&bytes);
        }

        /// Every strict prefix of a valid encoding is rejected, never misread.
        #[test]
        fn truncation_is_rejected(op in 0..Opcode::COUNT, seed in any::<u64>()) {
            let op = Opcode::ALL[op];
            let mut runner = TestRunner::new_with_rng(
                PtConfig::default(),
                proptest::test_runner::TestRng::from_seed(
                    proptest::test_runner::RngAlgorithm::ChaCha, &[seed as u8; 32]));
            let cmd = op.strategy().new_tree(&mut runner).expect("tree").current();
            let bytes = encode_to_vec(&cmd).expect("encode");
            for cut in 0..bytes.len() {
                prop_assert!(decode_command(&bytes[..cut]).is_err(), "{} cut at {cut}", op.name());
            }
        }
    }
}
