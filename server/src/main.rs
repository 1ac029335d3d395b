//! `stratad`: the Strata daemon and its companion commands.

use std::path::PathBuf;
use std::process::Stdio;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use strata_client::workload::Workload;
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::handshake::default_socket_path;
use strata_server::{serve, ExecutorKind, ServeOptions};
use tracing::info;

/// Strata: a consolidated 3D compositing window manager daemon.
#[derive(Parser)]
#[command(name = "stratad", version)]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Serve clients on a Unix socket until SIGINT or SIGTERM.
    Serve {
        /// Socket path [default: $XDG_RUNTIME_DIR/strata.sock, else /tmp/strata-$UID.sock].
        #[arg(long, env = "STRATA_SOCKET")]
        socket: Option<PathBuf>,
        /// Command ring bytes per client (power of two).
        #[arg(long, default_value_t = 8 << 20)]
        cmd_ring: u32,
        /// Reply ring bytes per client (power of two).
        #[arg(long, default_value_t = 1 << 20)]
        reply_ring: u32,
        /// What executes client commands.
        #[arg(long, value_enum, default_value_t = ExecutorKind::Gles)]
        executor: ExecutorKind,
    },
    /// Sample client: stream a seeded mix of GLES commands and have the daemon verify them.
    Client {
        /// Socket path [default: as for serve].
        #[arg(long, env = "STRATA_SOCKET")]
        socket: Option<PathBuf>,
        /// Client name.
        #[arg(long, default_value = "sample")]
        name: String,
        /// Client role (e.g. ic, hu).
        #[arg(long, default_value = "app")]
        role: String,
        /// Commands to stream.
        #[arg(long, default_value_t = 100_000)]
        commands: u64,
        /// Ask the daemon to verify count and CRC-32 after every this many commands (0: only at the end).
        #[arg(long, default_value_t = 0)]
        verify_every: u64,
        /// Largest bulk upload in the mix, bytes.
        #[arg(long, default_value_t = 4096)]
        max_upload: usize,
        /// Seed of the command mix.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// Start a daemon and two sample clients (IC and HU) that stream and verify, then stop.
    Demo {
        /// Commands each client streams.
        #[arg(long, default_value_t = 1_000_000)]
        commands: u64,
    },
}

fn init_logging() {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "info".into());
    use std::io::IsTerminal;
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_ansi(std::io::stderr().is_terminal())
        .with_writer(std::io::stderr)
        .init();
}

fn main() -> Result<()> {
    init_logging();
    match Cli::parse().command {
        Cmd::Serve { socket, cmd_ring, reply_ring, executor } => {
            let opts =
                ServeOptions { socket: socket.unwrap_or_else(default_socket_path), cmd_ring, reply_ring, executor };
            run_daemon(opts)
        }
        Cmd::Client { socket, name, role, commands, verify_every, max_upload, seed } => {
            let opts = ConnectOptions {
                socket: socket.unwrap_or_else(default_socket_path),
                name,
                role,
                tally: true,
                ..ConnectOptions::default()
            };
            sample_client(&opts, commands, verify_every, max_upload, seed)
        }
        Cmd::Demo { commands } => demo(commands),
    }
}

fn run_daemon(opts: ServeOptions) -> Result<()> {
    let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build()?;
    rt.block_on(async {
        let shutdown = async {
            use tokio::signal::unix::{signal, SignalKind};
            match (signal(SignalKind::interrupt()), signal(SignalKind::terminate())) {
                (Ok(mut int), Ok(mut term)) => {
                    tokio::select! {
                        _ = int.recv() => info!("SIGINT received"),
                        _ = term.recv() => info!("SIGTERM received"),
                    }
                }
                _ => std::future::pending::<()>().await,
            }
        };
        serve(opts, shutdown).await
    })?;
    Ok(())
}

fn sample_client(opts: &ConnectOptions, commands: u64, verify_every: u64, max_upload: usize, seed: u64) -> Result<()> {
    let mut conn = Connection::connect(opts).with_context(|| format!("connecting to {}", opts.socket.display()))?;
    let mut load = Workload::new(seed, max_upload);
    let start = Instant::now();
    let mut verifies = 0u64;
    for i in 1..=commands {
        conn.send(&load.next_command())?;
        if verify_every > 0 && i % verify_every == 0 {
            check(conn.verify()?, &opts.name)?;
            verifies += 1;
        }
    }
    let tally = conn.verify()?;
    check(tally, &opts.name)?;
    let secs = start.elapsed().as_secs_f64();
    println!(
        "{} ({}): {} commands verified by stratad (crc32 {:08x}, {} checks), {:.2} M commands/s",
        opts.name,
        opts.role,
        commands,
        tally.crc32,
        verifies + 1,
        commands as f64 / secs / 1e6
    );
    Ok(())
}

fn check(t: strata_protocol::StreamTally, name: &str) -> Result<()> {
    if !t.matches {
        bail!(
            "{name}: stratad saw {} commands with crc32 {:08x}, which differs from what was sent",
            t.commands,
            t.crc32
        );
    }
    Ok(())
}

fn demo(commands: u64) -> Result<()> {
    let dir = std::env::temp_dir().join(format!("strata-demo-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let socket = dir.join("strata.sock");
    let exe = std::env::current_exe()?;
    let mut daemon = std::process::Command::new(&exe)
        .args(["serve", "--socket"])
        .arg(&socket)
        .spawn()
        .context("starting the daemon")?;
    let deadline = Instant::now() + std::time::Duration::from_secs(10);
    while std::os::unix::net::UnixStream::connect(&socket).is_err() {
        if Instant::now() > deadline {
            let _ = daemon.kill();
            bail!("daemon did not start listening on {}", socket.display());
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let clients: Vec<_> = [("instrument-cluster", "ic", 1), ("head-unit", "hu", 2)]
        .into_iter()
        .map(|(name, role, seed)| {
            std::process::Command::new(&exe)
                .args(["client", "--name", name, "--role", role, "--seed", &seed.to_string()])
                .args(["--commands", &commands.to_string(), "--verify-every", "100000", "--socket"])
                .arg(&socket)
                .stdout(Stdio::inherit())
                .spawn()
                .with_context(|| format!("starting the {role} client"))
        })
        .collect::<Result<_>>()?;
    let mut ok = true;
    for mut c in clients {
        ok &= c.wait()?.success();
    }
    // SAFETY: plain kill(2) on our own child.
    unsafe { libc::kill(daemon.id() as i32, libc::SIGTERM) };
    ok &= daemon.wait()?.success();
    let _ = std::fs::remove_dir_all(&dir);
    if !ok {
        bail!("demo failed");
    }
    println!("demo: both clients' streams arrived complete and in order");
    Ok(())
}
