//! The daemon's control protocol for Rust programs (an HMI controller, `stratad ctl`): JSON
//! lines on the daemon's control socket, as docs/control.md specifies. Every request gets one reply;
//! [`ControlConnection::watch`] turns the connection into a stream of events.
//!
//! ```no_run
//! use strata_client::control::{ControlConnection, ControlReply, ControlRequest};
//! use strata_protocol::properties::Change;
//!
//! let mut c = ControlConnection::connect(std::path::Path::new("/run/strata/strata-control.sock"))?;
//! let hide = Change::Visibility { surface: 2000, visible: false };
//! match c.request(&ControlRequest::Apply { changes: vec![hide] })? {
//!     ControlReply::Error(e) => eprintln!("refused: {e}"),
//!     _ => println!("done"),
//! }
//! # Ok::<(), strata_client::control::ControlError>(())
//! ```

use std::io::{BufRead, BufReader, Read, Write};
use std::os::unix::net::UnixStream;
use std::path::{Path, PathBuf};

pub use strata_protocol::events::{Analysis, Event, Reason};
use strata_protocol::json_control::{self, Greeting, LineError, Opening, MAX_LINE};
pub use strata_protocol::json_control::{ControlReply, ControlRequest, CONTROL_VERSION};

/// A control conversation that failed.
#[derive(Debug, thiserror::Error)]
pub enum ControlError {
    /// The socket could not be reached.
    #[error("cannot connect to stratad at {socket}: {source}")]
    Connect {
        /// The socket.
        socket: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// Reading or writing failed.
    #[error("control connection: {0}")]
    Io(#[from] std::io::Error),
    /// A line was not what the protocol says.
    #[error(transparent)]
    Line(#[from] LineError),
    /// The daemon refused the connection.
    #[error("stratad refused the control connection: {0}")]
    Refused(String),
    /// The daemon closed the connection.
    #[error("stratad closed the control connection")]
    Closed,
}

/// A control connection to the daemon.
pub struct ControlConnection {
    reader: BufReader<UnixStream>,
    writer: UnixStream,
}

impl ControlConnection {
    /// Connects to the daemon's control socket `socket` as `stratad-ctl`.
    pub fn connect(socket: &Path) -> Result<ControlConnection, ControlError> {
        ControlConnection::connect_as(socket, "stratad-ctl")
    }

    /// Connects to the control socket of the daemon whose client socket is `client_socket`,
    /// where it is by default (beside it, `NAME-control.sock`).
    pub fn connect_beside(client_socket: &Path) -> Result<ControlConnection, ControlError> {
        ControlConnection::connect(&strata_protocol::handshake::control_socket_for(client_socket))
    }

    /// Connects to the daemon's control socket `socket`, named `name` in its log.
    pub fn connect_as(socket: &Path, name: &str) -> Result<ControlConnection, ControlError> {
        let writer = UnixStream::connect(socket)
            .map_err(|source| ControlError::Connect { socket: socket.to_path_buf(), source })?;
        let mut c = ControlConnection { reader: BufReader::new(writer.try_clone()?), writer };
        c.send(&Opening::Hello { version: CONTROL_VERSION, name: name.to_string() })?;
        match c.read::<Greeting>("greeting")? {
            Greeting::Ready { .. } => Ok(c),
            Greeting::Refused { reason } => Err(ControlError::Refused(reason)),
        }
    }

    fn send<T: serde::Serialize>(&mut self, v: &T) -> Result<(), ControlError> {
        self.writer.write_all(&json_control::line(v)?)?;
        Ok(())
    }

    fn read<T: serde::de::DeserializeOwned>(&mut self, what: &'static str) -> Result<T, ControlError> {
        let mut line = Vec::new();
        let n = (&mut self.reader).take(MAX_LINE as u64 + 1).read_until(b'\n', &mut line)?;
        if n == 0 {
            return Err(ControlError::Closed);
        }
        if line.len() > MAX_LINE {
            return Err(LineError::TooLong { what, limit: MAX_LINE }.into());
        }
        Ok(json_control::parse(&line, what)?)
    }

    /// Sends one request and waits for its reply.
    pub fn request(&mut self, req: &ControlRequest) -> Result<ControlReply, ControlError> {
        self.send(req)?;
        self.read("control reply")
    }

    /// Turns the connection into the daemon's event stream: each item is one event, until the
    /// daemon closes it (the last item of a watcher that fell behind is `Event::Dropped`).
    pub fn watch(mut self) -> Result<impl Iterator<Item = Result<Event, ControlError>>, ControlError> {
        self.send(&ControlRequest::Watch)?;
        Ok(std::iter::from_fn(move || match self.read::<ControlReply>("event") {
            Ok(ControlReply::Event(e)) => Some(Ok(e)),
            Ok(ControlReply::Error(e)) => Some(Err(ControlError::Refused(e))),
            Ok(other) => Some(Err(ControlError::Refused(format!("not an event: {other:?}")))),
            Err(ControlError::Closed) => None,
            Err(e) => Some(Err(e)),
        }))
    }
}
