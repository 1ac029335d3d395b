//! Reading the input events the daemon sends on a client's socket (`ServerMessage::Input`
//! frames), on the connection's thread or on one of their own.

use std::os::fd::AsRawFd;
use std::os::unix::net::UnixStream;
use std::time::{Duration, Instant};

use strata_protocol::codec;
use strata_protocol::handshake::{self, HandshakeError, ServerMessage};
use strata_protocol::input::InputEvent;

use crate::ClientError;

/// Reads input events from (its own handle on) a connection's socket.
pub struct InputReader {
    stream: UnixStream,
    /// Bytes read but not yet a whole frame.
    buf: Vec<u8>,
}

impl InputReader {
    /// A reader on `stream`'s socket.
    pub(crate) fn new(stream: &UnixStream) -> Result<InputReader, ClientError> {
        Ok(InputReader { stream: stream.try_clone().map_err(HandshakeError::Io)?, buf: Vec::new() })
    }

    /// The next event, waiting at most `timeout` (`None`: none came); an error once the daemon
    /// has closed the connection.
    pub fn next(&mut self, timeout: Duration) -> Result<Option<InputEvent>, ClientError> {
        let deadline = Instant::now() + timeout;
        loop {
            if let Some(e) = self.take()? {
                return Ok(Some(e));
            }
            let left = deadline.saturating_duration_since(Instant::now());
            let mut p = libc::pollfd { fd: self.stream.as_raw_fd(), events: libc::POLLIN, revents: 0 };
            let ms = i32::try_from(left.as_millis()).unwrap_or(i32::MAX);
            // SAFETY: polls one descriptor the reader owns.
            let n = unsafe { libc::poll(&mut p, 1, ms) };
            if n == 0 {
                return Ok(None);
            }
            if n < 0 {
                let e = std::io::Error::last_os_error();
                if e.kind() == std::io::ErrorKind::Interrupted {
                    continue;
                }
                return Err(HandshakeError::Io(e).into());
            }
            let mut chunk = [0u8; 4096];
            // SAFETY: reads into a local buffer of its length, without waiting.
            let got = unsafe { libc::recv(p.fd, chunk.as_mut_ptr().cast(), chunk.len(), libc::MSG_DONTWAIT) };
            match got {
                0 => return Err(HandshakeError::Io(std::io::ErrorKind::UnexpectedEof.into()).into()),
                n if n > 0 => self.buf.extend_from_slice(&chunk[..n as usize]),
                _ => {
                    let e = std::io::Error::last_os_error();
                    if !matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::Interrupted) {
                        return Err(HandshakeError::Io(e).into());
                    }
                }
            }
        }
    }

    /// A whole event from what was read, if there is one.
    fn take(&mut self) -> Result<Option<InputEvent>, ClientError> {
        let Some(prefix) = self.buf.first_chunk::<4>() else { return Ok(None) };
        let len = handshake::frame_len(*prefix)?;
        if self.buf.len() < 4 + len {
            return Ok(None);
        }
        let msg: ServerMessage = codec::decode_trusted(&self.buf[4..4 + len], "input event")?;
        self.buf.drain(..4 + len);
        match msg {
            ServerMessage::Input(e) => Ok(Some(e)),
            other => Err(ClientError::Unexpected(format!("{other:?} after the welcome"))),
        }
    }
}
