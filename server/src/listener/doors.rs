//! The daemon's two sockets: the client socket, where render clients connect (`--socket`,
//! 0600, or 0660 with `--client-group`), and the control socket, where `stratad ctl` and HMI
//! controllers connect (`--control-socket`, beside the client socket by default, 0600, or 0660
//! with `--control-group`). Also the reads and the write that carry descriptors: reads that
//! refuse any a client sends, and the welcome that hands a client its segment.

use std::os::fd::{AsFd, BorrowedFd};
use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::path::{Path, PathBuf};

use strata_protocol::fd_passing;
use tokio::io::{AsyncWriteExt, Interest};
use tokio::net::{UnixListener, UnixStream};
use tracing::info;

use super::options::{io_err, ServeOptions, ServerError};

/// Which socket a connection came through.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Door {
    /// The client socket: rendering only.
    Client,
    /// The control socket: control only.
    Control,
}

/// The two listening sockets and where they are.
pub(super) struct Doors {
    pub client: UnixListener,
    pub control: UnixListener,
    pub client_path: PathBuf,
    pub control_path: PathBuf,
    /// Which of them the service manager passed (and keeps for the next start).
    pub activated: (bool, bool),
}

/// Claims `path`: refuses a live socket, replaces a stale one; then makes it 0600, or 0660 to
/// `group` where one is named.
fn claim_socket(path: &Path, group: Option<u32>) -> Result<UnixListener, ServerError> {
    if let Ok(meta) = std::fs::symlink_metadata(path) {
        if !meta.file_type().is_socket() {
            return Err(ServerError::NotASocket(path.into()));
        }
        if std::os::unix::net::UnixStream::connect(path).is_ok() {
            return Err(ServerError::AlreadyServing(path.into()));
        }
        info!(socket = %path.display(), "replacing stale socket");
        std::fs::remove_file(path).map_err(io_err(format!("removing stale socket {}", path.display())))?;
    }
    let listener = bind_private(path).map_err(io_err(format!("binding {}", path.display())))?;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o600))
        .map_err(io_err(format!("restricting {}", path.display())))?;
    if let Some(gid) = group {
        std::os::unix::fs::chown(path, None, Some(gid))
            .map_err(io_err(format!("giving {} to group {gid}", path.display())))?;
        std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o660))
            .map_err(io_err(format!("opening {} to group {gid}", path.display())))?;
    }
    Ok(listener)
}

/// Binds a socket at `path` under a umask of 077, so that it is never open to anyone but the
/// daemon's user, not even between its creation and the mode `claim_socket` then gives it.
/// The umask is the process's: the daemon binds its sockets at start, before any other thread
/// of its creates files.
fn bind_private(path: &Path) -> std::io::Result<UnixListener> {
    // SAFETY: umask only swaps the process's file-creation mask; it cannot fail.
    let old = unsafe { libc::umask(0o077) };
    let bound = UnixListener::bind(path);
    // SAFETY: as above, restoring the mask found.
    unsafe { libc::umask(old) };
    bound
}

/// How long a door stops accepting after `accept` fails (out of descriptors, say): the
/// connection stays queued in the kernel, so retrying at once would only spin.
const ACCEPT_BACKOFF: std::time::Duration = std::time::Duration::from_millis(100);

/// A door's failed accepts: it pauses after each, and logs at most one line a second, with
/// the count since the last.
#[derive(Debug, Default)]
pub(super) struct Refusals {
    /// Until when the door does not accept.
    paused_until: Option<tokio::time::Instant>,
    /// Failures since the last line logged.
    unlogged: u64,
    /// Failures in all.
    pub(super) total: u64,
    /// When the last line was logged.
    logged_at: Option<tokio::time::Instant>,
}

impl Refusals {
    /// Whether the door accepts now.
    pub(super) fn open(&self) -> bool {
        self.paused_until.is_none()
    }

    /// When the door opens again (now if it is open).
    pub(super) fn reopens_at(&self) -> tokio::time::Instant {
        self.paused_until.unwrap_or_else(tokio::time::Instant::now)
    }

    /// Opens the door again.
    pub(super) fn reopen(&mut self) {
        self.paused_until = None;
    }

    /// Counts a failed accept on door `what`, pauses the door, and logs if a second has passed
    /// since the last line.
    pub(super) fn failed(&mut self, what: &str, e: &std::io::Error) {
        let now = tokio::time::Instant::now();
        self.total += 1;
        self.unlogged += 1;
        self.paused_until = Some(now + ACCEPT_BACKOFF);
        if self.logged_at.is_none_or(|t| now.duration_since(t) >= std::time::Duration::from_secs(1)) {
            tracing::warn!(
                door = what,
                failures = self.unlogged,
                total = self.total,
                "accept failed: {e}; pausing this door {} ms after each failure",
                ACCEPT_BACKOFF.as_millis()
            );
            self.unlogged = 0;
            self.logged_at = Some(now);
        }
    }
}

/// Where a listener listens (`fallback` if it has no path).
fn path_of(l: &UnixListener, fallback: &Path) -> PathBuf {
    l.local_addr().ok().and_then(|a| a.as_pathname().map(Path::to_path_buf)).unwrap_or_else(|| fallback.into())
}

/// The sockets the service manager passed, else those at `--socket` and `--control-socket`.
pub(super) fn open(opts: &ServeOptions) -> Result<Doors, ServerError> {
    let passed = crate::systemd::activated_sockets()?;
    let from_std = |l: std::os::unix::net::UnixListener| {
        UnixListener::from_std(l).map_err(io_err("serving on an activated socket"))
    };
    let activated = (passed.client.is_some(), passed.control.is_some());
    let passed_client = passed.client.map(from_std).transpose()?;
    let client_path = passed_client.as_ref().map_or_else(|| opts.socket.clone(), |l| path_of(l, &opts.socket));
    let wanted =
        opts.control_socket.clone().unwrap_or_else(|| strata_protocol::handshake::control_socket_for(&client_path));
    // The control socket is claimed first: whoever finds the client socket listening finds
    // the control socket too.
    let control = match passed.control {
        Some(l) => from_std(l)?,
        None => claim_socket(&wanted, opts.control_group)?,
    };
    let control_path = path_of(&control, &wanted);
    let client = match passed_client {
        Some(l) => l,
        None => claim_socket(&opts.socket, opts.client_group).inspect_err(|_| {
            if !activated.1 {
                let _ = std::fs::remove_file(&control_path);
            }
        })?,
    };
    Ok(Doors { client, control, client_path, control_path, activated })
}

/// Removes the sockets the daemon bound itself (the service manager's stay for the next start).
pub(super) fn close(doors: &Doors) {
    if !doors.activated.0 {
        let _ = std::fs::remove_file(&doors.client_path);
    }
    if !doors.activated.1 {
        let _ = std::fs::remove_file(&doors.control_path);
    }
}

/// What a client is told when it sends descriptors or other ancillary data.
pub(super) const ANCILLARY: &str =
    "the client sent file descriptors or other ancillary data, which stratad never accepts from a client";

/// Fills `buf` from the socket; an `InvalidData` error (saying [`ANCILLARY`]) if descriptors
/// or other ancillary data come with the bytes (the descriptors are closed at once).
pub(super) async fn read_plain(stream: &UnixStream, buf: &mut [u8]) -> std::io::Result<()> {
    let mut have = 0;
    while have < buf.len() {
        stream.readable().await?;
        let got = match stream.try_io(Interest::READABLE, || fd_passing::recv(stream.as_fd(), &mut buf[have..])) {
            Ok(got) => got,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => continue,
            Err(e) => return Err(e),
        };
        if got.has_ancillary() {
            return Err(std::io::Error::new(std::io::ErrorKind::InvalidData, ANCILLARY));
        }
        if got.bytes == 0 {
            return Err(std::io::ErrorKind::UnexpectedEof.into());
        }
        have += got.bytes;
    }
    Ok(())
}

/// Writes `bytes` with `fd` attached to the first of them.
pub(super) async fn write_with_fd(stream: &mut UnixStream, bytes: &[u8], fd: BorrowedFd<'_>) -> std::io::Result<()> {
    let sent = loop {
        stream.writable().await?;
        match stream.try_io(Interest::WRITABLE, || fd_passing::send_with_fd(stream.as_fd(), bytes, fd)) {
            Ok(n) => break n,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => continue,
            Err(e) => return Err(e),
        }
    };
    stream.write_all(&bytes[sent..]).await
}

#[cfg(test)]
mod tests {
    use std::os::unix::fs::PermissionsExt;

    /// Even under a umask of 0, a socket is created closed to group and others.
    #[tokio::test]
    async fn a_socket_is_born_private() {
        let dir = std::env::temp_dir().join(format!("strata-doors-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("s.sock");
        let _ = std::fs::remove_file(&path);
        // SAFETY: swaps the process's file-creation mask; restored below.
        let old = unsafe { libc::umask(0) };
        let bound = super::bind_private(&path);
        // SAFETY: as above.
        unsafe { libc::umask(old) };
        let _listener = bound.expect("bind");
        let mode = std::fs::metadata(&path).expect("stat").permissions().mode();
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(mode & 0o077, 0, "a fresh socket is open to others: {mode:o}");
    }
}
