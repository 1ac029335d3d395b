//! Shared helpers for multi-process tests: a real `stratad` in its own process, sample-client
//! processes, and raw clients that speak the protocol by hand.
#![allow(dead_code)]

pub mod egl;
pub mod gl;
pub mod scene;
pub mod users;
pub mod windows;

use std::io::Write;
use std::os::unix::net::UnixStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use strata_protocol::handshake::{self, ClientMessage, Hello, Purpose, ServerMessage, PROTOCOL_VERSION};
use strata_protocol::ring::Writer;
use strata_protocol::segment::Segment;

/// Makes `fds` descriptors 3, 4, … of the process `cmd` starts, open across its exec (as a
/// service manager passes sockets, or a parent its connection). Each is first copied above
/// that range, so that none is overwritten before it is moved.
pub fn pass_fds(cmd: &mut Command, fds: Vec<i32>) {
    use std::os::unix::process::CommandExt;
    // SAFETY: only async-signal-safe calls (fcntl, dup2) between fork and exec, on
    // descriptors the caller keeps open until the process has started.
    unsafe {
        cmd.pre_exec(move || {
            let mut high = Vec::with_capacity(fds.len());
            for &fd in &fds {
                let h = libc::fcntl(fd, libc::F_DUPFD, 100);
                if h < 0 {
                    return Err(std::io::Error::last_os_error());
                }
                high.push(h);
            }
            for (i, h) in high.into_iter().enumerate() {
                if libc::dup2(h, 3 + i as i32) < 0 {
                    return Err(std::io::Error::last_os_error());
                }
            }
            Ok(())
        });
    }
}

/// The daemon binary under test.
pub fn stratad() -> &'static str {
    env!("CARGO_BIN_EXE_stratad")
}

/// A private temporary directory, removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> TempDir {
        let p = std::env::temp_dir().join(format!("strata-test-{tag}-{}-{:08x}", std::process::id(), rand_u32()));
        std::fs::create_dir_all(&p).expect("temp dir");
        TempDir(p)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn rand_u32() -> u32 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.subsec_nanos()).unwrap_or(0)
}

/// A `stratad serve` process with its log captured to a file.
pub struct Daemon {
    pub child: Child,
    pub socket: PathBuf,
    pub log: PathBuf,
    pub dir: TempDir,
}

impl Daemon {
    pub fn start(tag: &str, extra: &[&str]) -> Daemon {
        Daemon::start_with_env(tag, extra, &[])
    }

    /// Like `start`, with extra environment variables for the daemon.
    pub fn start_with_env(tag: &str, extra: &[&str], env: &[(&str, &str)]) -> Daemon {
        let dir = TempDir::new(tag);
        let socket = dir.0.join("strata.sock");
        let log = dir.0.join("stratad.log");
        let child = Command::new(stratad())
            .arg("serve")
            .arg("--socket")
            .arg(&socket)
            .args(extra)
            .env("RUST_LOG", "info")
            .envs(env.iter().copied())
            .stderr(std::fs::File::create(&log).expect("log file"))
            .spawn()
            .expect("spawn stratad");
        let d = Daemon { child, socket, log, dir };
        d.wait_listening();
        d
    }

    /// Like `start`, listening on `socket`, a path the caller owns: it outlives this daemon, so
    /// that a later daemon can take it over.
    pub fn start_at(tag: &str, socket: &Path, extra: &[&str]) -> Daemon {
        let dir = TempDir::new(tag);
        let log = dir.0.join("stratad.log");
        let child = Command::new(stratad())
            .arg("serve")
            .arg("--socket")
            .arg(socket)
            .args(extra)
            .env("RUST_LOG", "info")
            .stderr(std::fs::File::create(&log).expect("log file"))
            .spawn()
            .expect("spawn stratad");
        let d = Daemon { child, socket: socket.to_path_buf(), log, dir };
        d.wait_listening();
        d
    }

    /// Sends SIGKILL (no clean-up at all) and waits for the process to end.
    pub fn kill(mut self) -> std::process::ExitStatus {
        let _ = self.child.kill();
        self.child.wait().expect("wait stratad")
    }

    fn wait_listening(&self) {
        let deadline = Instant::now() + Duration::from_secs(20);
        while UnixStream::connect(&self.socket).is_err() {
            assert!(Instant::now() < deadline, "stratad did not listen; log:\n{}", self.log_text());
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    pub fn log_text(&self) -> String {
        std::fs::read_to_string(&self.log).unwrap_or_default()
    }

    /// Waits until the log contains `needle`.
    pub fn wait_log(&self, needle: &str) {
        let deadline = Instant::now() + Duration::from_secs(10);
        while !self.log_text().contains(needle) {
            assert!(Instant::now() < deadline, "log never said {needle:?}; log:\n{}", self.log_text());
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    pub fn assert_running(&mut self) {
        assert!(self.child.try_wait().expect("try_wait").is_none(), "stratad exited; log:\n{}", self.log_text());
    }

    /// Sends SIGTERM and waits for a clean exit.
    pub fn stop(mut self) -> std::process::ExitStatus {
        // SAFETY: kill(2) on our own child.
        unsafe { libc::kill(self.child.id() as i32, libc::SIGTERM) };
        let status = self.child.wait().expect("wait stratad");
        if !status.success() {
            // What a failing test shows of why.
            let log = self.log_text();
            let tail: Vec<&str> = log.lines().rev().take(30).collect();
            eprintln!("stratad exited with {status}; its log's last lines, newest first:\n{}", tail.join("\n"));
        }
        status
    }
}

impl Drop for Daemon {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `stratad client` streaming `commands` verified commands.
pub fn sample_client(socket: &Path, name: &str, commands: u64, verify_every: u64, seed: u64) -> Child {
    Command::new(stratad())
        .args(["client", "--name", name, "--role", "test"])
        .args(["--commands", &commands.to_string(), "--verify-every", &verify_every.to_string()])
        .args(["--seed", &seed.to_string(), "--socket"])
        .arg(socket)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn sample client")
}

/// Waits for a sample client and checks that the daemon verified its whole stream.
pub fn expect_verified(child: Child, commands: u64) {
    let out = child.wait_with_output().expect("wait client");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && stdout.contains(&format!("{commands} commands verified by stratad")),
        "client failed: {}\nstdout: {stdout}\nstderr: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A client that performs the handshake by hand and then writes raw bytes into its ring.
pub struct RawClient {
    pub stream: UnixStream,
    pub writer: Writer,
    pub segment: Segment,
}

impl RawClient {
    pub fn connect(socket: &Path, name: &str) -> RawClient {
        let mut stream = UnixStream::connect(socket).expect("connect");
        stream.set_read_timeout(Some(Duration::from_secs(10))).expect("timeout");
        stream.write_all(&handshake::preamble(PROTOCOL_VERSION)).expect("preamble");
        let hello =
            Hello { name: name.into(), role: "raw".into(), placement: None, tally: false, purpose: Purpose::Render };
        handshake::write_message(&mut stream, &hello).expect("hello");
        let (ServerMessage::Welcome { cmd_capacity, reply_capacity, .. }, fds) =
            handshake::read_message_with_fds(&stream, "welcome").expect("welcome")
        else {
            panic!("refused");
        };
        let fd = fds.into_iter().next().expect("the welcome carries the segment");
        let segment = Segment::open(fd, cmd_capacity, reply_capacity).expect("open segment");
        handshake::write_message(&mut stream, &ClientMessage::Mapped).expect("mapped");
        let writer = Writer::new(segment.command_ring().expect("ring"), 1 << 16);
        RawClient { stream, writer, segment }
    }

    /// True once the daemon has closed our control socket.
    pub fn wait_disconnected(&mut self) -> bool {
        use std::io::Read;
        let mut b = [0u8; 16];
        loop {
            match self.stream.read(&mut b) {
                Ok(0) => return true,
                Ok(_) => continue,
                // Unread bytes on a closed Unix socket surface as a reset, not EOF.
                Err(e) => return e.kind() == std::io::ErrorKind::ConnectionReset,
            }
        }
    }
}
pub mod mesa;

/// A running daemon's `stratad ctl stats`.
pub fn stats(socket: &Path) -> strata_protocol::control::DaemonStats {
    let mut c = strata_client::ControlConnection::connect_beside(socket).expect("control");
    match c.request(&handshake::ControlRequest::Stats).expect("stats") {
        handshake::ControlReply::Stats(s) => s,
        other => panic!("stats: {other:?}"),
    }
}

/// Whether a missing oracle (Mesa, Xvfb, glmark2) must fail the test instead of skipping it.
pub fn oracles_required() -> bool {
    std::env::var_os("STRATA_REQUIRE_ORACLES").is_some()
}

/// The items of a suite that `STRATA_ONLY` (comma-separated parts of names) selects, all of
/// them when it is unset: for re-running a few programs or sequences of a long suite by hand.
/// A selection is announced, and `STRATA_REQUIRE_ORACLES` (CI) refuses one.
#[allow(dead_code)]
pub fn only<T>(items: Vec<T>, name: impl Fn(&T) -> &str) -> Vec<T> {
    let Some(only) = std::env::var("STRATA_ONLY").ok().filter(|s| !s.is_empty()) else { return items };
    assert!(!oracles_required(), "STRATA_ONLY={only} selects part of a suite, and STRATA_REQUIRE_ORACLES asks for all");
    let total = items.len();
    let kept: Vec<T> =
        items.into_iter().filter(|i| only.split(',').any(|part| name(i).contains(part.trim()))).collect();
    eprintln!("STRATA_ONLY={only}: {} of {total}", kept.len());
    kept
}

/// The path of `program` on `PATH`, if installed.
pub fn which(program: &str) -> Option<PathBuf> {
    std::env::var_os("PATH")?.to_str()?.split(':').map(|d| Path::new(d).join(program)).find(|p| p.is_file())
}

/// Whether nothing a test needs is `missing`; otherwise the test skips, or fails when
/// `STRATA_REQUIRE_ORACLES` is set.
pub fn nothing_missing(missing: &[&str]) -> bool {
    if missing.is_empty() {
        return true;
    }
    let why = format!("{} not installed (tools/install-deps installs them)", missing.join(", "));
    assert!(!oracles_required(), "STRATA_REQUIRE_ORACLES is set: {why}");
    eprintln!("skipping: {why}");
    false
}

/// Waits for `child` (spawned with piped stdout and stderr) up to `deadline`, killing it then;
/// returns its output and whether it was killed.
pub fn wait_with_deadline(mut child: Child, deadline: Duration) -> (std::process::Output, bool) {
    use std::io::Read;
    let (mut out, mut err) = (child.stdout.take().expect("stdout"), child.stderr.take().expect("stderr"));
    let t_out = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = out.read_to_end(&mut s);
        s
    });
    let t_err = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = err.read_to_end(&mut s);
        s
    });
    let start = Instant::now();
    let mut killed = false;
    let status = loop {
        if let Some(s) = child.try_wait().expect("try_wait") {
            break s;
        }
        if start.elapsed() > deadline {
            killed = true;
            let _ = child.kill();
            break child.wait().expect("wait");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let stdout = t_out.join().unwrap_or_default();
    let stderr = t_err.join().unwrap_or_default();
    (std::process::Output { status, stdout, stderr }, killed)
}

/// A private X server (Xvfb) on a display it picks itself, killed on drop.
pub struct Xvfb {
    pub child: Child,
    /// The `DISPLAY` value, e.g. `:123`.
    pub display: String,
}

impl Xvfb {
    /// Starts Xvfb with one `width`x`height` 24-bit screen, or returns why it cannot.
    pub fn start(width: u32, height: u32) -> Result<Xvfb, String> {
        use std::io::BufRead;
        let mut child = Command::new("Xvfb")
            // -noreset: by default the server resets when its last client leaves, and a client
            // connecting during the reset fails (XOpenDisplay), which short-lived programs
            // started back to back, such as piglit's tests, run into.
            .args(["-displayfd", "1", "-screen", "0", &format!("{width}x{height}x24"), "-nolisten", "tcp", "-noreset"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| format!("Xvfb could not start ({e}); install the xvfb package"))?;
        // Xvfb writes the display number it chose once it accepts connections.
        let mut line = String::new();
        let read = child.stdout.take().map(|o| std::io::BufReader::new(o).read_line(&mut line));
        match (read, line.trim().parse::<u32>()) {
            (Some(Ok(_)), Ok(n)) => Ok(Xvfb { child, display: format!(":{n}") }),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                Err(format!("Xvfb printed {line:?}, not a display number"))
            }
        }
    }
}

impl Xvfb {
    /// Starts Xvfb as [`Xvfb::start`] does; where it cannot, `None` after saying why (the test
    /// skips), or a panic when `STRATA_REQUIRE_ORACLES` is set.
    pub fn start_or_skip(width: u32, height: u32) -> Option<Xvfb> {
        match Xvfb::start(width, height) {
            Ok(x) => Some(x),
            Err(e) => {
                assert!(!oracles_required(), "STRATA_REQUIRE_ORACLES is set: {e}");
                eprintln!("skipping: {e}");
                None
            }
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A directory holding the shim under the names applications load: libEGL.so.1,
/// libGLESv2.so.2 and the unversioned names (what `tools/build-shim` installs).
pub fn shim_dir(tmp: &TempDir) -> PathBuf {
    // Cargo builds the cdylib (a dev-dependency) next to the test's dependencies.
    let exe = PathBuf::from(stratad());
    let lib = exe.parent().expect("target dir").join("deps").join("libstrata_egl.so");
    assert!(lib.is_file(), "{} not built", lib.display());
    let dir = tmp.0.join("strata-gl");
    std::fs::create_dir_all(&dir).expect("shim dir");
    for name in ["libEGL.so.1", "libGLESv2.so.2", "libEGL.so", "libGLESv2.so"] {
        std::os::unix::fs::symlink(&lib, dir.join(name)).expect("symlink shim");
    }
    dir
}
