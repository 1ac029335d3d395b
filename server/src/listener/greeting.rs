//! A connection's first steps: its first byte, the preamble and hello, replies framed for the
//! handshake, and the kernel's credentials of the peer.

use std::time::Duration;

use strata_protocol::handshake::{self, HandshakeError, Hello, ServerMessage};
use tokio::io::AsyncWriteExt;
use tokio::net::UnixStream;

use super::doors;

/// How long a client may take over each handshake step.
const HANDSHAKE_TIMEOUT: Duration = Duration::from_secs(5);

pub(crate) async fn send(stream: &mut UnixStream, msg: &ServerMessage) -> Result<(), HandshakeError> {
    stream.write_all(&handshake::frame(msg)?).await?;
    Ok(())
}

pub(crate) async fn recv<T: serde::de::DeserializeOwned>(
    stream: &mut UnixStream,
    what: &'static str,
) -> Result<T, HandshakeError> {
    let mut prefix = [0u8; 4];
    doors::read_plain(stream, &mut prefix).await?;
    let mut body = vec![0u8; handshake::frame_len(prefix)?];
    doors::read_plain(stream, &mut body).await?;
    Ok(strata_protocol::codec::decode_owned(&body, what)?)
}

pub(crate) async fn timed<T>(
    f: impl std::future::Future<Output = Result<T, HandshakeError>>,
) -> Result<T, HandshakeError> {
    tokio::time::timeout(HANDSHAKE_TIMEOUT, f).await.unwrap_or_else(|_| {
        Err(HandshakeError::Io(std::io::Error::new(std::io::ErrorKind::TimedOut, "handshake timed out")))
    })
}

/// Reads the rest of the preamble (its first byte is `first`) and the hello; refusals are sent
/// to the client before the error returns.
pub(crate) async fn greet(stream: &mut UnixStream, first: u8) -> Result<Hello, HandshakeError> {
    let mut pre = [first, 0, 0, 0, 0, 0, 0, 0];
    let read = timed(async { Ok(doors::read_plain(stream, &mut pre[1..]).await?) }).await;
    let checked = read.and_then(|()| handshake::check_preamble(pre));
    let hello = match checked {
        Ok(()) => timed(recv::<Hello>(stream, "hello")).await,
        Err(e) => Err(e),
    };
    if let Err(e) = &hello {
        if !matches!(e, HandshakeError::Io(io) if io.kind() != std::io::ErrorKind::InvalidData) {
            let _ = send(stream, &ServerMessage::Refused { reason: e.to_string() }).await;
        }
    }
    hello
}

/// Reads a connection's first byte (refusing descriptors sent with it).
pub(crate) async fn first_byte(stream: &UnixStream) -> Result<u8, HandshakeError> {
    let mut first = [0u8; 1];
    timed(async { Ok(doors::read_plain(stream, &mut first).await?) }).await?;
    Ok(first[0])
}

/// The kernel's credentials of the process that connected.
pub(crate) fn peer_of(stream: &UnixStream) -> std::io::Result<strata_protocol::control::Peer> {
    let c = stream.peer_cred()?;
    Ok(strata_protocol::control::Peer {
        pid: c.pid().map_or(0, |p| p.unsigned_abs()),
        uid: c.uid(),
        gid: c.gid(),
        unverified: false,
    })
}
