//! What can go wrong on the client's side of a connection.

use std::path::PathBuf;

use strata_protocol::codec::CodecError;
use strata_protocol::handshake::HandshakeError;
use strata_protocol::ring::RingError;
use strata_protocol::segment::SegmentError;
use strata_protocol::ReplyMismatch;

/// A client-side failure.
#[derive(Debug, thiserror::Error)]
pub enum ClientError {
    /// Could not reach the daemon.
    #[error("cannot connect to stratad at {socket}: {source}")]
    Connect {
        /// The socket tried.
        socket: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// The handshake failed or was refused.
    #[error(transparent)]
    Handshake(#[from] HandshakeError),
    /// The segment could not be mapped.
    #[error(transparent)]
    Segment(#[from] SegmentError),
    /// The ring failed; `PeerGone` means the daemon went away.
    #[error(transparent)]
    Ring(#[from] RingError),
    /// Encoding or decoding failed.
    #[error(transparent)]
    Codec(#[from] CodecError),
    /// A reply did not match its call.
    #[error(transparent)]
    Mismatch(#[from] ReplyMismatch),
    /// The daemon does not implement the call.
    #[error("unsupported by stratad: {0}")]
    Unsupported(String),
    /// The daemon sent something out of place in the handshake.
    #[error("unexpected handshake message: {0}")]
    Unexpected(String),
}
