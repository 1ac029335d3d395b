//! A `stratad serve` child process for the benchmarks that drive a real daemon: started on a
//! socket of its own, waited for until it accepts connections, and stopped (SIGTERM, then
//! SIGKILL) with its socket removed when dropped.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};

/// How long a daemon may take to accept its first connection.
const START_LIMIT: Duration = Duration::from_secs(30);

/// A running `stratad serve`; stopped on drop.
pub(crate) struct Stratad {
    child: Child,
    /// Its socket, for clients and `STRATA_SOCKET`.
    pub(crate) socket: PathBuf,
    /// Its standard error (at `RUST_LOG`, by default `warn`).
    pub(crate) log: PathBuf,
    /// Whether the log is removed with the daemon.
    remove_log: bool,
}

impl Stratad {
    /// Starts `stratad serve ARGS --socket SOCKET` with its standard error in `log` (removed on
    /// drop unless `keep_log`), and waits until it accepts connections.
    pub(crate) fn start<S: AsRef<OsStr>>(
        stratad: &Path,
        args: impl IntoIterator<Item = S>,
        socket: PathBuf,
        log: PathBuf,
        keep_log: bool,
    ) -> Result<Stratad> {
        let child = Command::new(stratad)
            .arg("serve")
            .args(args)
            .arg("--socket")
            .arg(&socket)
            .env("RUST_LOG", std::env::var("RUST_LOG").unwrap_or_else(|_| "warn".into()))
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(&log).with_context(|| format!("creating {}", log.display()))?)
            .spawn()
            .with_context(|| format!("starting {}", stratad.display()))?;
        let mut d = Stratad { child, socket, log, remove_log: !keep_log };
        let deadline = Instant::now() + START_LIMIT;
        while std::os::unix::net::UnixStream::connect(&d.socket).is_err() {
            if Instant::now() > deadline || d.child.try_wait()?.is_some() {
                bail!("stratad did not start; its log {}:\n{}", d.log.display(), tail(&d.log, 15));
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        Ok(d)
    }

    /// The daemon's process id.
    pub(crate) fn pid(&self) -> u32 {
        self.child.id()
    }

    /// An error with the end of its log if the daemon has exited.
    pub(crate) fn alive(&mut self) -> Result<()> {
        match self.child.try_wait()? {
            Some(status) => bail!("stratad exited ({status}); its log:\n{}", tail(&self.log, 15)),
            None => Ok(()),
        }
    }
}

impl Drop for Stratad {
    fn drop(&mut self) {
        stop(&mut self.child, Duration::from_secs(10));
        let _ = std::fs::remove_file(&self.socket);
        let _ = std::fs::remove_file(strata_protocol::handshake::control_socket_for(&self.socket));
        if self.remove_log {
            let _ = std::fs::remove_file(&self.log);
        }
    }
}

/// Waits up to `limit` for `child` to exit.
pub(crate) fn wait_for(child: &mut Child, limit: Duration) -> Option<std::process::ExitStatus> {
    let start = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(s)) => return Some(s),
            Ok(None) if start.elapsed() < limit => std::thread::sleep(Duration::from_millis(20)),
            _ => return None,
        }
    }
}

/// SIGTERM, then SIGKILL after `grace`.
pub(crate) fn stop(child: &mut Child, grace: Duration) {
    // SAFETY: kill(2) on our own child.
    unsafe { libc::kill(child.id() as i32, libc::SIGTERM) };
    if wait_for(child, grace).is_none() {
        let _ = child.kill();
        let _ = child.wait();
    }
}

/// The last `n` lines of a log file.
pub(crate) fn tail(path: &Path, n: usize) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}
