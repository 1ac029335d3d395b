//! `strata-bench`: throughput benchmarks for Strata. Every figure is reported beside a baseline
//! measured in the same run, because shared machines are noisy.

mod transport;

use anyhow::Result;
use clap::{Parser, Subcommand};

/// Strata benchmarks.
#[derive(Parser)]
#[command(name = "strata-bench", version)]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Command-stream transport: small commands/s and bulk GB/s through a separate daemon
    /// process, against memcpy measured in the same run.
    Transport(transport::Args),
    /// Runs the daemon half of a benchmark (started by the benchmark itself).
    #[command(hide = true)]
    Daemon {
        /// Socket to serve on.
        #[arg(long)]
        socket: std::path::PathBuf,
    },
}

fn main() -> Result<()> {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "warn".into());
    tracing_subscriber::fmt().with_env_filter(filter).with_writer(std::io::stderr).init();
    match Cli::parse().command {
        Cmd::Transport(args) => transport::run(&args),
        Cmd::Daemon { socket } => transport::daemon(socket),
    }
}
