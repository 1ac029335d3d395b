//! The transport benchmark: a client process streams to a daemon process (this binary,
//! re-executed, running the real `strata_server::serve`).

use std::path::PathBuf;
use std::process::{Child, Command as Proc};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::codec;
use strata_protocol::ring::{BULK_PIECE, HOT_WINDOW};
use strata_protocol::wire::Blob;
use strata_protocol::Command;

/// Options of `strata-bench transport`.
#[derive(clap::Args)]
pub struct Args {
    /// Print one JSON object as the last line.
    #[arg(long)]
    json: bool,
    /// Small commands to stream.
    #[arg(long, default_value_t = 10_000_000)]
    small: u64,
    /// 1 MiB payloads to stream.
    #[arg(long, default_value_t = 4096)]
    bulk: u64,
}

/// Runs the daemon half with `opts` until killed, with `outputs` (none: the daemon's default
/// output).
pub fn daemon(mut opts: strata_server::ServeOptions, outputs: Vec<strata_compositor::root::OutputSpec>) -> Result<()> {
    let rt = tokio::runtime::Builder::new_current_thread().enable_all().build()?;
    if !outputs.is_empty() {
        opts.outputs = outputs;
    }
    rt.block_on(strata_server::serve(opts, std::future::pending()))?;
    Ok(())
}

/// A benchmark daemon process and its client socket; killed on drop, its sockets removed.
pub struct DaemonProc(Child, pub PathBuf);

impl Drop for DaemonProc {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
        let _ = std::fs::remove_file(&self.1);
        let _ = std::fs::remove_file(strata_protocol::handshake::control_socket_for(&self.1));
    }
}

/// Starts this binary's daemon half with `executor` and waits until it listens.
pub fn start_daemon(executor: strata_server::ExecutorKind) -> Result<DaemonProc> {
    start_daemon_with(executor, &[], None)
}

/// Like `start_daemon`, with extra daemon arguments (e.g. `--output`) and its stderr written to
/// `log` (inherited when `None`).
pub fn start_daemon_with(
    executor: strata_server::ExecutorKind,
    extra: &[String],
    log: Option<&std::path::Path>,
) -> Result<DaemonProc> {
    // One socket per daemon: a benchmark may run several side by side.
    static STARTED: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let k = STARTED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let socket = std::env::temp_dir().join(format!("strata-bench-{}-{k}.sock", std::process::id()));
    let kind = match executor {
        strata_server::ExecutorKind::Gles => "gles",
        strata_server::ExecutorKind::Drain => "drain",
    };
    let mut cmd = Proc::new(std::env::current_exe()?);
    cmd.args(["daemon", "--executor", kind, "--socket"]).arg(&socket).args(extra);
    if let Some(log) = log {
        cmd.stderr(std::fs::File::create(log).with_context(|| format!("creating {}", log.display()))?);
    }
    let mut child = cmd.spawn().context("starting the benchmark daemon")?;
    let deadline = Instant::now() + Duration::from_secs(20);
    while std::os::unix::net::UnixStream::connect(&socket).is_err() {
        if Instant::now() > deadline || child.try_wait()?.is_some() {
            let _ = child.kill();
            let _ = child.wait();
            let why = log.and_then(|l| std::fs::read_to_string(l).ok()).unwrap_or_default();
            bail!("benchmark daemon did not start listening on {}\n{why}", socket.display());
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    Ok(DaemonProc(child, socket))
}

/// A progress bar on stderr.
pub fn bar(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} {per_sec} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    pb
}

/// The small-command mix: real GLES state calls, each at most 32 bytes encoded.
fn small_command(i: u64) -> Command<'static> {
    let f = (i % 977) as f32 * 0.001;
    match i % 6 {
        0 => Command::Uniform4f { location: (i % 16) as i32, x: f, y: 1.0 - f, z: 0.5, w: 1.0 },
        1 => Command::DrawArrays { mode: 4, first: 0, count: (i % 3000) as i32 + 3 },
        2 => Command::BindBuffer { target: 0x8892, buffer: (i % 64) as u32 },
        3 => Command::Enable { cap: 0x0B71 },
        4 => Command::Viewport { x: 0, y: 0, width: 1920, height: 720 },
        _ => Command::VertexAttribPointer {
            index: (i % 8) as u32,
            size: 3,
            attrib_type: 0x1406,
            normalized: false,
            stride: 24,
            offset: 12,
        },
    }
}

/// memcpy bandwidth over the same payload size and count, single thread.
pub fn memcpy_gbps(payload: usize, count: u64, pb: &ProgressBar) -> f64 {
    let src: Vec<u8> = (0..payload).map(|i| i as u8).collect();
    let mut dst = vec![0u8; payload];
    let start = Instant::now();
    for i in 0..count {
        dst.copy_from_slice(std::hint::black_box(&src));
        std::hint::black_box(&mut dst);
        if i % 64 == 0 {
            pb.set_position(i);
        }
    }
    let secs = start.elapsed().as_secs_f64();
    pb.finish();
    (payload as u64 * count) as f64 / secs / 1e9
}

/// The machine's floor for what bulk transport does: one thread copies `count` payloads of
/// `payload` bytes, in [`BULK_PIECE`] pieces, into a buffer of twice [`HOT_WINDOW`] that a
/// thread on the other core copies out of as each piece is published (spinning, no framing,
/// no checks, no processes): each byte crosses between the cores' caches once, as in the
/// ring. Returns GB/s.
pub fn cross_core_gbps(payload: usize, count: u64, pb: &ProgressBar) -> f64 {
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A byte buffer two threads write and read in disjoint parts, ordered by `head`/`tail`.
    struct Shared(std::cell::UnsafeCell<Vec<u8>>);
    // SAFETY: the writer only writes bytes the reader has released (`tail`), the reader only
    // reads bytes the writer has published (`head`), so no byte is accessed by both at once.
    unsafe impl Sync for Shared {}
    #[repr(align(64))]
    struct Line(AtomicUsize);

    let cap = 2 * HOT_WINDOW;
    let ring = Shared(std::cell::UnsafeCell::new(vec![0u8; cap]));
    let (head, tail) = (Line(AtomicUsize::new(0)), Line(AtomicUsize::new(0)));
    // Borrowed whole, so that the threads share `Shared` (which is `Sync`), not its cell.
    let ring = &ring;
    let src: Vec<u8> = (0..payload).map(|i| (i * 7) as u8).collect();
    let total = payload as u64 * count;
    let start = Instant::now();
    std::thread::scope(|s| {
        s.spawn(|| {
            let mut dst = vec![0u8; payload];
            let mut t = 0usize;
            for _ in 0..count {
                let mut got = 0;
                while got < payload {
                    let h = loop {
                        let h = head.0.load(Ordering::Acquire);
                        if h != t {
                            break h;
                        }
                        std::hint::spin_loop();
                    };
                    let n = (h - t).min(payload - got).min(cap - t % cap);
                    // SAFETY: `t..t + n` (mod cap) was published by the writer and is not
                    // rewritten until `tail` passes it.
                    unsafe {
                        let base = (*ring.0.get()).as_ptr();
                        std::ptr::copy_nonoverlapping(base.add(t % cap), dst.as_mut_ptr().add(got), n);
                    }
                    got += n;
                    t += n;
                    tail.0.store(t, Ordering::Release);
                }
                std::hint::black_box(&mut dst);
            }
        });
        let mut h = 0usize;
        for i in 0..count {
            let mut done = 0;
            while done < payload {
                let n = BULK_PIECE.min(payload - done).min(cap - h % cap);
                while h + n - tail.0.load(Ordering::Acquire) > cap {
                    std::hint::spin_loop();
                }
                // SAFETY: `h..h + n` (mod cap) was released by the reader.
                unsafe {
                    let base = (*ring.0.get()).as_mut_ptr();
                    std::ptr::copy_nonoverlapping(src.as_ptr().add(done), base.add(h % cap), n);
                }
                done += n;
                h += n;
                head.0.store(h, Ordering::Release);
            }
            if i % 64 == 0 {
                pb.set_position(i);
            }
        }
    });
    let secs = start.elapsed().as_secs_f64();
    pb.finish();
    total as f64 / secs / 1e9
}

/// Runs the benchmark and prints its report.
pub fn run(args: &Args) -> Result<()> {
    for i in 0..6 {
        let n = codec::encoded_len(&small_command(i))?;
        if n > 32 {
            bail!("small command {i} encodes to {n} bytes, more than 32");
        }
    }
    let daemon = start_daemon(strata_server::ExecutorKind::Drain)?;
    let opts = ConnectOptions { socket: daemon.1.clone(), name: "bench".into(), ..ConnectOptions::default() };
    let mut conn = Connection::connect(&opts).context("connecting to the benchmark daemon")?;

    // Warm up both ends.
    for i in 0..100_000 {
        conn.send(&small_command(i))?;
    }
    conn.strataPing(0)?;

    let pb = bar(args.small, "small cmds");
    let start = Instant::now();
    for i in 0..args.small {
        conn.send(&small_command(i))?;
        if i % 65536 == 0 {
            pb.set_position(i);
        }
    }
    conn.strataPing(1)?;
    let small_secs = start.elapsed().as_secs_f64();
    pb.finish();
    let small_cmds_per_s = args.small as f64 / small_secs;

    const MIB: usize = 1 << 20;
    let payload: Vec<u8> = (0..MIB).map(|i| (i * 7) as u8).collect();
    let pb = bar(args.bulk, "1 MiB bulk");
    let start = Instant::now();
    for i in 0..args.bulk {
        conn.glBufferSubData(0x8892, 0, Blob::borrowed(&payload))?;
        if i % 64 == 0 {
            pb.set_position(i);
        }
    }
    conn.strataPing(2)?;
    let bulk_secs = start.elapsed().as_secs_f64();
    pb.finish();
    let bulk_gb_per_s = (MIB as u64 * args.bulk) as f64 / bulk_secs / 1e9;
    drop(conn);
    drop(daemon);

    let memcpy_gb_per_s = memcpy_gbps(MIB, args.bulk, &bar(args.bulk, "memcpy"));
    let bulk_vs_memcpy = bulk_gb_per_s / memcpy_gb_per_s;
    let cross_gb_per_s = cross_core_gbps(MIB, args.bulk, &bar(args.bulk, "cross-core"));
    let bulk_vs_cross = bulk_gb_per_s / cross_gb_per_s;

    println!("transport: client and daemon in separate processes, one shared-memory ring");
    println!(
        "  small commands (<= 32 B):  {:>8.2} M commands/s  ({} in {:.3} s)",
        small_cmds_per_s / 1e6,
        args.small,
        small_secs
    );
    println!("  bulk 1 MiB payloads:        {:>8.2} GB/s        ({} in {:.3} s)", bulk_gb_per_s, args.bulk, bulk_secs);
    println!("  memcpy 1 MiB, same run:     {:>8.2} GB/s", memcpy_gb_per_s);
    println!("  bulk / memcpy:              {:>8.3}", bulk_vs_memcpy);
    println!("  cross-core copy, same run:  {:>8.2} GB/s  (two threads, 64 KiB pieces, no framing)", cross_gb_per_s);
    println!("  bulk / cross-core copy:     {:>8.3}", bulk_vs_cross);
    if args.json {
        let report = serde_json::json!({
            "small_cmds_per_s": small_cmds_per_s,
            "bulk_gb_per_s": bulk_gb_per_s,
            "memcpy_gb_per_s": memcpy_gb_per_s,
            "bulk_vs_memcpy": bulk_vs_memcpy,
            "cross_core_gb_per_s": cross_gb_per_s,
            "bulk_vs_cross_core": bulk_vs_cross,
            "small_commands": args.small,
            "bulk_payloads": args.bulk,
            "payload_bytes": MIB,
        });
        println!("{report}");
    }
    Ok(())
}
