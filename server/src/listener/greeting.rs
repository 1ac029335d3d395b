//! A connection's first steps: its first byte, the preamble and hello, replies framed for the
//! handshake, and the kernel's credentials of the peer.

use std::time::Duration;

use strata_protocol::handshake::{self, HandshakeError, Hello, ServerMessage};
use tokio::io::AsyncWriteExt;
use tokio::net::UnixStream;

use super::doors;

/// How long a client may take over each handshake step.
pub(crate) const HANDSHAKE_TIMEOUT: Duration = Duration::from_secs(5);

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

/// Most characters of a client's name or role that a log line shows.
const SHOWN_CHARS: usize = 64;

/// A client's name or role as log lines show it: control and other non-printing characters
/// escaped, so that a name cannot forge a line of its own, and cut to [`SHOWN_CHARS`]
/// characters, with the length it had. Entries still match the whole name.
pub(crate) fn shown(text: &str) -> String {
    let mut out: String = text.chars().take(SHOWN_CHARS).flat_map(char::escape_debug).collect();
    let n = text.chars().count();
    if n > SHOWN_CHARS {
        out.push_str(&format!("…({n} characters)"));
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn names_are_escaped_and_cut_for_the_log() {
        assert_eq!(super::shown("ic-cluster"), "ic-cluster");
        assert_eq!(super::shown("a\nb\u{1b}[31m"), "a\\nb\\u{1b}[31m");
        let long = "x".repeat(300);
        assert_eq!(super::shown(&long), format!("{}…(300 characters)", "x".repeat(64)));
    }
}
