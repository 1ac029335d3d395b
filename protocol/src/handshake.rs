//! The control-socket conversation: preamble and version check, hello, welcome or refusal,
//! and the client's confirmation that it mapped the segment.
//!
//! Wire: the client first sends 8 raw bytes, `b"STRT"` then its protocol version as `u32` LE,
//! so that any version can be refused by name. After that both sides exchange messages framed
//! as `[len: u32 LE][codec bytes]`, each at most [`MAX_CONTROL_MESSAGE`] bytes. The welcome
//! carries the client's segment as a descriptor attached to its first byte (`SCM_RIGHTS`).

use std::io::{Read, Write};
use std::path::PathBuf;

use serde::{de::DeserializeOwned, Deserialize, Serialize};

use crate::codec::{self, CodecError};
pub use crate::control::{ControlReply, ControlRequest, SurfaceRow};

/// The protocol version this build speaks.
pub const PROTOCOL_VERSION: u32 = 13;
/// The first four bytes a client sends.
pub const PREAMBLE_MAGIC: [u8; 4] = *b"STRT";
/// Largest framed control message the daemon accepts.
pub const MAX_CONTROL_MESSAGE: usize = 1 << 20;
/// Largest framed reply a control client accepts (screenshots are large).
pub const MAX_CONTROL_REPLY: usize = 256 << 20;

/// Where a client's window goes in the output: position, depth layer and size in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Placement {
    /// Left edge in output pixels.
    pub x: i32,
    /// Top edge in output pixels.
    pub y: i32,
    /// Depth layer; groups are drawn far (large z) to near.
    pub z: f32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

/// What a connection is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Purpose {
    /// A rendering client that streams commands through a segment.
    Render,
    /// An administrative connection (`stratad ctl`).
    Control,
}

/// The client's introduction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Hello {
    /// Client name, by default the process name.
    pub name: String,
    /// Role, e.g. `ic` or `hu`.
    pub role: String,
    /// Requested placement, if the client has one.
    pub placement: Option<Placement>,
    /// Whether the daemon should keep a count and CRC-32 of decoded messages for `strataVerify`.
    pub tally: bool,
    /// What the connection is for.
    pub purpose: Purpose,
}

/// The daemon's messages on the control socket.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ServerMessage {
    /// Accepted: map the segment that came with this message, then answer `Mapped`.
    Welcome {
        /// The daemon's number for this client.
        client_id: u64,
        /// Command ring capacity in bytes.
        cmd_capacity: u32,
        /// Reply ring capacity in bytes.
        reply_capacity: u32,
        /// How the client sends the `GL_FLOAT` client-side vertex arrays its draws read.
        vertex_wire: VertexWire,
    },
    /// Refused, with the reason.
    Refused {
        /// Why.
        reason: String,
    },
    /// A control connection is accepted; send `ControlRequest`s.
    ControlReady,
    /// An input event for one of the client's surfaces (after the welcome, unasked).
    Input(crate::input::InputEvent),
}

/// The number format of `GL_FLOAT` client-side vertex arrays on the wire (`stratad serve
/// --vertex-wire`). Buffer objects and arrays of other types travel as the application gave them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum VertexWire {
    /// IEEE binary32, as the application gave them (4 bytes a component).
    #[default]
    Float,
    /// IEEE binary16, rounded to nearest even (2 bytes a component, `GL_HALF_FLOAT_OES`).
    Half,
    /// Signed 16.16 fixed point, rounded to nearest and saturated (4 bytes, `GL_FIXED`).
    Fixed,
}

impl VertexWire {
    /// Every format, in the order the benchmark reports them.
    pub const ALL: [VertexWire; 3] = [VertexWire::Float, VertexWire::Half, VertexWire::Fixed];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            VertexWire::Float => "float",
            VertexWire::Half => "half",
            VertexWire::Fixed => "fixed",
        }
    }

    /// The GL component type the client sends (`GL_FLOAT`, `GL_HALF_FLOAT_OES`, `GL_FIXED`).
    pub fn gl_type(self) -> u32 {
        match self {
            VertexWire::Float => 0x1406,
            VertexWire::Half => 0x8D61,
            VertexWire::Fixed => 0x140C,
        }
    }

    /// Bytes per component on the wire.
    pub fn component_bytes(self) -> usize {
        match self {
            VertexWire::Half => 2,
            VertexWire::Float | VertexWire::Fixed => 4,
        }
    }
}

impl std::fmt::Display for VertexWire {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A `--vertex-wire` value that names no format.
#[derive(Debug, thiserror::Error)]
#[error("unknown vertex wire format {0:?} (expected float, half or fixed)")]
pub struct UnknownVertexWire(pub String);

impl std::str::FromStr for VertexWire {
    type Err = UnknownVertexWire;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        VertexWire::ALL.into_iter().find(|w| w.name() == s).ok_or_else(|| UnknownVertexWire(s.to_string()))
    }
}

/// The client's messages on the control socket after the hello.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ClientMessage {
    /// The segment is mapped; the daemon may unlink it.
    Mapped,
}

/// A handshake failure.
#[derive(Debug, thiserror::Error)]
pub enum HandshakeError {
    /// The peer is not speaking this protocol at all.
    #[error("not a Strata client: preamble {0:02x?}")]
    NotStrata([u8; 4]),
    /// Versions differ.
    #[error("protocol version mismatch: client speaks version {client}, daemon speaks version {daemon}")]
    VersionMismatch {
        /// The client's version.
        client: u32,
        /// The daemon's version.
        daemon: u32,
    },
    /// A control message announced an absurd size.
    #[error("control message of {0} bytes exceeds the {MAX_CONTROL_MESSAGE}-byte limit")]
    TooLarge(usize),
    /// The daemon said no.
    #[error("refused by daemon: {0}")]
    Refused(String),
    /// The message did not decode.
    #[error(transparent)]
    Codec(#[from] CodecError),
    /// The socket failed.
    #[error("control socket: {0}")]
    Io(#[from] std::io::Error),
}

/// The 8 bytes a client opens with.
pub fn preamble(version: u32) -> [u8; 8] {
    let mut p = [0u8; 8];
    p[..4].copy_from_slice(&PREAMBLE_MAGIC);
    p[4..].copy_from_slice(&version.to_le_bytes());
    p
}

/// Checks a client's preamble against this build's version.
pub fn check_preamble(p: [u8; 8]) -> Result<(), HandshakeError> {
    let mut magic = [0u8; 4];
    magic.copy_from_slice(&p[..4]);
    if magic != PREAMBLE_MAGIC {
        return Err(HandshakeError::NotStrata(magic));
    }
    let client = u32::from_le_bytes([p[4], p[5], p[6], p[7]]);
    if client != PROTOCOL_VERSION {
        return Err(HandshakeError::VersionMismatch { client, daemon: PROTOCOL_VERSION });
    }
    Ok(())
}

/// Frames a control message: `[len: u32 LE][bytes]`.
pub fn frame<T: Serialize>(msg: &T) -> Result<Vec<u8>, HandshakeError> {
    frame_limited(msg, MAX_CONTROL_MESSAGE)
}

/// Frames a control message of at most `limit` bytes.
pub fn frame_limited<T: Serialize>(msg: &T, limit: usize) -> Result<Vec<u8>, HandshakeError> {
    let body = codec::encode_to_vec(msg)?;
    if body.len() > limit {
        return Err(HandshakeError::TooLarge(body.len()));
    }
    let mut out = Vec::with_capacity(4 + body.len());
    out.extend_from_slice(&(body.len() as u32).to_le_bytes());
    out.extend_from_slice(&body);
    Ok(out)
}

/// Validates a frame's length prefix.
pub fn frame_len(prefix: [u8; 4]) -> Result<usize, HandshakeError> {
    let len = u32::from_le_bytes(prefix) as usize;
    if len > MAX_CONTROL_MESSAGE {
        return Err(HandshakeError::TooLarge(len));
    }
    Ok(len)
}

/// Writes one framed message to a blocking stream.
pub fn write_message<T: Serialize>(w: &mut impl Write, msg: &T) -> Result<(), HandshakeError> {
    w.write_all(&frame(msg)?)?;
    Ok(())
}

/// Reads one framed message from a blocking stream.
pub fn read_message<T: DeserializeOwned>(r: &mut impl Read, what: &'static str) -> Result<T, HandshakeError> {
    read_message_limited(r, what, MAX_CONTROL_MESSAGE)
}

/// Reads one framed message of at most `limit` bytes from a blocking stream. The client reads
/// the daemon's messages with it and trusts them: a control reply's decoded size may be many
/// times its encoded size (`ctl stats` lists many small items), so it decodes within the whole
/// message limit rather than one that follows its size.
pub fn read_message_limited<T: DeserializeOwned>(
    r: &mut impl Read,
    what: &'static str,
    limit: usize,
) -> Result<T, HandshakeError> {
    let mut prefix = [0u8; 4];
    r.read_exact(&mut prefix)?;
    let len = u32::from_le_bytes(prefix) as usize;
    if len > limit {
        return Err(HandshakeError::TooLarge(len));
    }
    let mut body = vec![0u8; len];
    r.read_exact(&mut body)?;
    Ok(codec::decode_trusted(&body, what)?)
}

/// Reads one framed message from a blocking Unix stream, with the descriptors attached to its
/// bytes (the welcome's segment).
pub fn read_message_with_fds<T: DeserializeOwned>(
    stream: &std::os::unix::net::UnixStream,
    what: &'static str,
) -> Result<(T, Vec<std::os::fd::OwnedFd>), HandshakeError> {
    use std::os::fd::AsFd;
    let mut prefix = [0u8; 4];
    let mut fds = Vec::new();
    let mut have = 0;
    while have < prefix.len() {
        let got = match crate::fd_passing::recv(stream.as_fd(), &mut prefix[have..]) {
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            r => r?,
        };
        if got.bytes == 0 {
            return Err(HandshakeError::Io(std::io::ErrorKind::UnexpectedEof.into()));
        }
        have += got.bytes;
        fds.extend(got.fds);
    }
    let len = u32::from_le_bytes(prefix) as usize;
    if len > MAX_CONTROL_MESSAGE {
        return Err(HandshakeError::TooLarge(len));
    }
    let mut body = vec![0u8; len];
    (&mut &*stream).read_exact(&mut body)?;
    Ok((codec::decode_trusted(&body, what)?, fds))
}

/// The control socket that belongs to client socket `client` when none is named: beside it,
/// `NAME-control.EXT` (`strata.sock` → `strata-control.sock`).
pub fn control_socket_for(client: &std::path::Path) -> PathBuf {
    let stem = client.file_stem().map_or_else(|| "strata".into(), |s| s.to_string_lossy().into_owned());
    let name = match client.extension() {
        Some(ext) => format!("{stem}-control.{}", ext.to_string_lossy()),
        None => format!("{stem}-control"),
    };
    client.with_file_name(name)
}

/// The control socket when none is given: `$STRATA_CONTROL_SOCKET`, else the one beside
/// [`default_socket_path`].
pub fn default_control_socket_path() -> PathBuf {
    match std::env::var_os("STRATA_CONTROL_SOCKET").filter(|p| !p.is_empty()) {
        Some(p) => PathBuf::from(p),
        None => control_socket_for(&default_socket_path()),
    }
}

/// The socket path when none is given: `$STRATA_SOCKET`, else `$XDG_RUNTIME_DIR/strata.sock`,
/// else `/tmp/strata-$UID.sock`.
pub fn default_socket_path() -> PathBuf {
    if let Some(p) = std::env::var_os("STRATA_SOCKET").filter(|p| !p.is_empty()) {
        return PathBuf::from(p);
    }
    if let Some(dir) = std::env::var_os("XDG_RUNTIME_DIR").filter(|p| !p.is_empty()) {
        return PathBuf::from(dir).join("strata.sock");
    }
    // SAFETY: getuid cannot fail.
    let uid = unsafe { libc::getuid() };
    PathBuf::from(format!("/tmp/strata-{uid}.sock"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_mismatch_names_both_versions() {
        let e = check_preamble(preamble(PROTOCOL_VERSION + 41)).expect_err("mismatch");
        let msg = e.to_string();
        assert!(msg.contains(&format!("version {}", PROTOCOL_VERSION + 41)), "{msg}");
        assert!(msg.contains(&format!("version {PROTOCOL_VERSION}")), "{msg}");
        assert!(matches!(check_preamble(*b"GET / HT"), Err(HandshakeError::NotStrata(_))));
        check_preamble(preamble(PROTOCOL_VERSION)).expect("same version");
    }

    #[test]
    fn a_control_reply_of_many_small_items_is_read_whole() {
        use crate::control::{DeviceStats, DeviceThread};
        // Many empty strings and short lists: a few bytes each on the wire, many more decoded.
        let thread = DeviceThread { tid: 1, name: String::new(), nice: 0 };
        let device = DeviceStats { threads: vec![thread; 400], ..Default::default() };
        let reply = ControlReply::Error(String::new());
        let stats = crate::control::DaemonStats {
            rss_bytes: 0,
            peak_rss_bytes: 0,
            rss_anon_bytes: 0,
            sessions: 0,
            clients: Vec::new(),
            gpu_bytes: 0,
            gpu_bytes_limit: 0,
            reserve_bytes: 0,
            daemon_bytes: 0,
            daemon_bytes_limit: 0,
            refused: Default::default(),
            objects: Default::default(),
            device_objects: Default::default(),
            compositor_device: Some(device),
            input_dropped: 0,
            pick_reads: [0; 2],
        };
        for msg in [reply, ControlReply::Stats(stats)] {
            let framed = frame(&msg).expect("encode");
            assert!(framed.len() < 4 << 10, "a small message: {} bytes", framed.len());
            let got: ControlReply =
                read_message_limited(&mut &framed[..], "control reply", MAX_CONTROL_REPLY).expect("decode");
            assert_eq!(got, msg);
        }
    }

    #[test]
    fn welcome_carries_the_vertex_wire() {
        for wire in VertexWire::ALL {
            let sent = ServerMessage::Welcome {
                client_id: 7,
                cmd_capacity: 1 << 20,
                reply_capacity: 1 << 16,
                vertex_wire: wire,
            };
            let framed = frame(&sent).expect("frame");
            let got: ServerMessage = read_message(&mut &framed[..], "welcome").expect("decode");
            assert_eq!(got, sent);
            assert_eq!(wire.name().parse::<VertexWire>().expect("parse"), wire);
        }
        // The GL enumerants are the spec's (GLES 2.0 §2.8 table 2.4, OES_vertex_half_float).
        assert_eq!(VertexWire::Half.gl_type(), 0x8D61);
        assert_eq!(VertexWire::Fixed.gl_type(), 0x140C);
        assert!("double".parse::<VertexWire>().is_err());
    }

    #[test]
    fn the_control_socket_sits_beside_the_client_socket() {
        let at = |p: &str| control_socket_for(std::path::Path::new(p));
        assert_eq!(at("/run/user/1000/strata.sock"), PathBuf::from("/run/user/1000/strata-control.sock"));
        assert_eq!(at("/tmp/strata-0.sock"), PathBuf::from("/tmp/strata-0-control.sock"));
        assert_eq!(at("/tmp/s"), PathBuf::from("/tmp/s-control"));
    }

    #[test]
    fn oversized_frame_is_refused() {
        assert!(matches!(frame_len(u32::MAX.to_le_bytes()), Err(HandshakeError::TooLarge(_))));
    }
}
