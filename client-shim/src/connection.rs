//! A connection to the daemon: handshake over the control socket, then commands through the
//! segment's command ring and replies through its reply ring.
//!
//! Fire-and-forget commands are encoded in place into the ring and published in batches: at a
//! synchronous call, at `flush`, or once the batch limit is pending.

use std::os::fd::AsRawFd;
use std::os::unix::net::UnixStream;
use std::path::PathBuf;
use std::time::Duration;

use strata_protocol::codec::{self, MAX_MESSAGE_LEN};
use strata_protocol::handshake::{
    self, ClientMessage, HandshakeError, Hello, Placement, Purpose, ServerMessage, VertexWire, PROTOCOL_VERSION,
};
use strata_protocol::input::InputEvent;

use crate::error::ClientError;
use crate::input::InputReader;
use strata_protocol::ring::{Reader, Writer, STREAM_FROM};
use strata_protocol::segment::{FenceWord, Segment};
use strata_protocol::tally::Tally;
use strata_protocol::{Calls, Command, Reply, StreamTally};

/// How a client introduces itself.
#[derive(Debug, Clone)]
pub struct ConnectOptions {
    /// Daemon socket.
    pub socket: PathBuf,
    /// Client name.
    pub name: String,
    /// Role, e.g. `ic` or `hu`.
    pub role: String,
    /// Requested placement.
    pub placement: Option<Placement>,
    /// Keep a count and CRC-32 of sent messages on both ends, for [`Connection::verify`].
    pub tally: bool,
    /// Bytes pending before the batch is published without an explicit flush.
    pub batch_bytes: u32,
    /// Protocol version to announce (tests set a wrong one on purpose).
    pub version: u32,
}

impl Default for ConnectOptions {
    fn default() -> Self {
        let name = std::env::current_exe()
            .ok()
            .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| "client".into());
        ConnectOptions {
            socket: handshake::default_socket_path(),
            name,
            role: "app".into(),
            placement: None,
            tally: false,
            batch_bytes: 64 << 10,
            version: PROTOCOL_VERSION,
        }
    }
}

/// A live connection to `stratad`.
pub struct Connection {
    stream: UnixStream,
    commands: Writer,
    replies: Reader,
    tally: Option<Tally>,
    client_id: u64,
    vertex_wire: VertexWire,
    _segment: Segment,
    /// The segment's word for the newest completed fence mark.
    fence_word: FenceWord,
    /// Reads the input events the daemon sends on the socket.
    input: Option<InputReader>,
}

/// Whether the daemon's end of the client socket is still open (input events it sent and
/// nobody read yet do not make a closed socket look open).
fn socket_alive(fd: i32) -> bool {
    let mut p = libc::pollfd { fd, events: libc::POLLRDHUP, revents: 0 };
    // SAFETY: polls one descriptor the connection owns, without waiting.
    let n = unsafe { libc::poll(&mut p, 1, 0) };
    n == 0 || (n > 0 && p.revents & (libc::POLLRDHUP | libc::POLLHUP | libc::POLLERR) == 0)
}

impl Connection {
    /// Connects, performs the handshake and maps the segment.
    pub fn connect(opts: &ConnectOptions) -> Result<Connection, ClientError> {
        let stream = UnixStream::connect(&opts.socket)
            .map_err(|source| ClientError::Connect { socket: opts.socket.clone(), source })?;
        Connection::connect_over(stream, opts)
    }

    /// Performs the handshake over `stream`, already connected to the daemon's client socket
    /// (by a launcher or a parent process that passed it on; `opts.socket` is not used). The
    /// daemon knows the client by the credentials of the process that connected it.
    pub fn connect_over(mut stream: UnixStream, opts: &ConnectOptions) -> Result<Connection, ClientError> {
        stream.set_read_timeout(Some(Duration::from_secs(10))).map_err(HandshakeError::Io)?;
        use std::io::Write;
        let hello = Hello {
            name: opts.name.clone(),
            role: opts.role.clone(),
            placement: opts.placement,
            tally: opts.tally,
            purpose: Purpose::Render,
        };
        let mut opening = handshake::preamble(opts.version).to_vec();
        opening.extend_from_slice(&handshake::frame(&hello)?);
        // The daemon may refuse after the preamble and close before the hello arrives; its
        // reason is then waiting to be read, and it explains more than a broken pipe.
        let sent = stream.write_all(&opening);
        let reply = handshake::read_message_with_fds(&stream, "welcome");
        if let Err(e) = sent {
            return match reply {
                Ok((ServerMessage::Refused { reason }, _)) => Err(HandshakeError::Refused(reason).into()),
                _ => Err(HandshakeError::Io(e).into()),
            };
        }
        let (reply, fds) = reply?;
        let (client_id, cmd_capacity, reply_capacity, vertex_wire) = match reply {
            ServerMessage::Welcome { client_id, cmd_capacity, reply_capacity, vertex_wire } => {
                (client_id, cmd_capacity, reply_capacity, vertex_wire)
            }
            ServerMessage::Refused { reason } => return Err(HandshakeError::Refused(reason).into()),
            ServerMessage::ControlReady | ServerMessage::Input(_) => {
                return Err(ClientError::Unexpected("a message other than the welcome on a render connection".into()))
            }
        };
        let Ok::<[_; 1], _>([fd]) = fds.try_into() else {
            return Err(ClientError::Unexpected("the welcome did not carry exactly one segment descriptor".into()));
        };
        let segment = Segment::open(fd, cmd_capacity, reply_capacity)?;
        handshake::write_message(&mut stream, &ClientMessage::Mapped)?;
        stream.set_read_timeout(None).map_err(HandshakeError::Io)?;
        let input = Some(InputReader::new(&stream)?);
        Ok(Connection {
            input,
            commands: Writer::new(segment.command_ring()?, opts.batch_bytes),
            replies: Reader::new(segment.reply_ring()?, MAX_MESSAGE_LEN),
            stream,
            tally: opts.tally.then(Tally::default),
            client_id,
            vertex_wire,
            fence_word: segment.fence_word(),
            _segment: segment,
        })
    }

    /// The daemon's number for this client.
    pub fn client_id(&self) -> u64 {
        self.client_id
    }

    /// How the daemon asked for `GL_FLOAT` client-side vertex arrays to be sent.
    pub fn vertex_wire(&self) -> VertexWire {
        self.vertex_wire
    }

    /// The newest fence mark (`strataFence`'s reply) whose commands have completed, as the daemon
    /// publishes it in the segment: reading it costs no round trip.
    pub fn fences_reached(&self) -> u64 {
        self.fence_word.get()
    }

    /// Whether the daemon's end of the connection is still open (one `poll` of the socket, no
    /// round trip): a fence whose mark has not come is waited on only while it is.
    pub fn daemon_alive(&self) -> bool {
        socket_alive(self.stream.as_raw_fd())
    }

    /// Publishes every queued command.
    pub fn flush(&mut self) {
        self.commands.publish();
    }

    /// Asks the daemon to compare its count and CRC-32 of this stream with ours.
    /// Requires [`ConnectOptions::tally`].
    pub fn verify(&mut self) -> Result<StreamTally, ClientError> {
        let (commands, crc32) = self.tally.as_ref().map(|t| (t.commands(), t.crc32())).unwrap_or((0, 0));
        self.strataVerify(commands, crc32)
    }

    /// Messages sent so far, if tallying.
    pub fn sent(&self) -> Option<u64> {
        self.tally.as_ref().map(Tally::commands)
    }

    /// The next input event the daemon sent for this client's surfaces, waiting at most
    /// `timeout` for one (`None`: none came). Events must be read: the daemon disconnects a
    /// client that lets 1,024 of them pile up beyond what its socket holds. An error once the
    /// reader was handed off ([`Connection::take_input_reader`]).
    pub fn next_input(&mut self, timeout: Duration) -> Result<Option<InputEvent>, ClientError> {
        match &mut self.input {
            Some(r) => r.next(timeout),
            None => Err(ClientError::Unexpected("this connection's input reader was handed off".into())),
        }
    }

    /// Hands off the reading of input events, for a thread of their own (`None` if already
    /// handed off).
    pub fn take_input_reader(&mut self) -> Option<InputReader> {
        self.input.take()
    }

    /// Writes `cmd`, `len` bytes encoded, as one message.
    fn write_message(&mut self, cmd: &Command<'_>, len: usize, alive: &dyn Fn() -> bool) -> Result<(), ClientError> {
        let tally = &mut self.tally;
        self.commands.write::<ClientError>(len, alive, |buf| {
            codec::encode_into(cmd, buf)?;
            if let Some(t) = tally {
                t.add(buf);
            }
            Ok(())
        })
    }
}

impl Calls for Connection {
    type Error = ClientError;

    fn send(&mut self, cmd: &Command<'_>) -> Result<(), ClientError> {
        let fd = self.stream.as_raw_fd();
        let alive = move || socket_alive(fd);
        let len = codec::encoded_len(cmd)?;
        if len >= STREAM_FROM {
            // A large blob follows its command in pieces, read straight to where it goes.
            if let Some((head, bytes)) = cmd.split_bulk(STREAM_FROM) {
                self.write_message(&head, codec::encoded_len(&head)?, &alive)?;
                return Ok(self.commands.write_bulk(bytes, &alive)?);
            }
        }
        self.write_message(cmd, len, &alive)
    }

    fn call(&mut self, cmd: &Command<'_>) -> Result<Reply, ClientError> {
        self.send(cmd)?;
        self.commands.publish();
        let fd = self.stream.as_raw_fd();
        let alive = move || socket_alive(fd);
        let mut reply = None;
        while reply.is_none() {
            self.replies.recv_batch::<ClientError>(&alive, |bytes| {
                reply = Some(codec::decode_reply(bytes)?);
                Ok(())
            })?;
        }
        match reply {
            Some(Reply::Unsupported(why)) => Err(ClientError::Unsupported(why)),
            Some(r) => Ok(r),
            None => Err(ClientError::Unexpected("no reply".into())),
        }
    }
}
