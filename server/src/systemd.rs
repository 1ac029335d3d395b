//! systemd integration through `sd-notify`: the listening sockets handed over by socket
//! activation (`LISTEN_FDS`, `LISTEN_FDNAMES`), readiness (`READY=1` once clients can connect and the compositor
//! runs; a `Type=notify` unit waits for it), `STOPPING=1` on the way out, and the watchdog:
//! with `WatchdogSec=` set, the compositor thread sends `WATCHDOG=1` at half the interval, so
//! that a wedged compositor stops the pings and systemd restarts the daemon. Without systemd
//! (no `NOTIFY_SOCKET`, no `LISTEN_PID` naming this process) every call does nothing.

use std::os::fd::FromRawFd;
use std::time::Duration;

use sd_notify::NotifyState;
use tracing::{debug, warn};

/// A socket handed over by the service manager that the daemon cannot serve on.
#[derive(Debug, thiserror::Error)]
pub enum ActivationError {
    /// `LISTEN_FDS` is malformed.
    #[error("LISTEN_FDS: {0}")]
    Environment(std::io::Error),
    /// More sockets were passed than the daemon serves.
    #[error(
        "socket activation passed {0}; stratad serves one client socket and one control socket \
         (FileDescriptorName=control)"
    )]
    Count(String),
    /// The descriptor is not a listening Unix stream socket.
    #[error("socket activation passed descriptor {fd}, which is not a listening Unix stream socket ({why})")]
    NotUnixStream {
        /// The descriptor.
        fd: i32,
        /// What it is instead.
        why: String,
    },
}

/// The sockets socket activation passed: the client socket, and the control socket (the one
/// named `control` by `FileDescriptorName=`).
#[derive(Debug, Default)]
pub struct Activated {
    /// The client socket.
    pub client: Option<std::os::unix::net::UnixListener>,
    /// The control socket.
    pub control: Option<std::os::unix::net::UnixListener>,
}

/// The listening sockets socket activation passed, if the service manager started the daemon
/// that way.
pub fn activated_sockets() -> Result<Activated, ActivationError> {
    let fds: Vec<(i32, String)> = sd_notify::listen_fds_with_names().map_err(ActivationError::Environment)?.collect();
    let mut got = Activated::default();
    for (fd, name) in &fds {
        // SAFETY: the service manager hands this descriptor to the process, which owns it from
        // here on; nothing else in the daemon uses it.
        let listener = unsafe { std::os::unix::net::UnixListener::from_raw_fd(*fd) };
        let bad = |why: String| ActivationError::NotUnixStream { fd: *fd, why };
        check_listening_unix_stream(&listener).map_err(bad)?;
        listener.set_nonblocking(true).map_err(|e| bad(e.to_string()))?;
        let slot = if name == "control" { &mut got.control } else { &mut got.client };
        if slot.replace(listener).is_some() {
            let names: Vec<&str> = fds.iter().map(|(_, n)| n.as_str()).collect();
            return Err(ActivationError::Count(format!("{} sockets named {names:?}", fds.len())));
        }
    }
    if got.control.is_some() && got.client.is_none() {
        return Err(ActivationError::Count("only the control socket".into()));
    }
    Ok(got)
}

/// Whether `listener` is a listening Unix stream socket.
fn check_listening_unix_stream(listener: &std::os::unix::net::UnixListener) -> Result<(), String> {
    use std::os::fd::AsRawFd;
    let fd = listener.as_raw_fd();
    let get = |option| {
        let mut v: libc::c_int = 0;
        let mut len = std::mem::size_of::<libc::c_int>() as libc::socklen_t;
        // SAFETY: getsockopt writes at most `len` bytes into `v`.
        let r =
            unsafe { libc::getsockopt(fd, libc::SOL_SOCKET, option, (&mut v as *mut libc::c_int).cast(), &mut len) };
        if r == 0 {
            Ok(v)
        } else {
            Err(std::io::Error::last_os_error().to_string())
        }
    };
    let (domain, ty, listening) = (get(libc::SO_DOMAIN)?, get(libc::SO_TYPE)?, get(libc::SO_ACCEPTCONN)?);
    if domain != libc::AF_UNIX || ty != libc::SOCK_STREAM || listening == 0 {
        return Err(format!("domain {domain}, type {ty}, listening {listening}"));
    }
    Ok(())
}

/// Sends `states` to the service manager, if there is one; a failure is logged.
fn notify(states: &[NotifyState<'_>]) {
    if std::env::var_os("NOTIFY_SOCKET").is_none() {
        return;
    }
    if let Err(e) = sd_notify::notify(states) {
        warn!("telling the service manager {states:?} failed: {e}");
    }
}

/// `READY=1`: clients can connect and the compositor runs.
pub fn ready(status: &str) {
    debug!("ready: {status}");
    notify(&[NotifyState::Ready, NotifyState::Status(status)]);
}

/// `STOPPING=1`: the daemon is shutting down.
pub fn stopping() {
    notify(&[NotifyState::Stopping, NotifyState::Status("stopping")]);
}

/// How often the compositor thread pings the watchdog: half the unit's `WatchdogSec=`, if set
/// for this process.
pub fn watchdog_period() -> Option<Duration> {
    sd_notify::watchdog_enabled().map(|d| d / 2)
}

/// `WATCHDOG=1`: the compositor thread is alive.
pub fn watchdog_ping() {
    notify(&[NotifyState::Watchdog]);
}
