//! `strata-bench`: throughput benchmarks for Strata. Every figure is reported beside a baseline
//! measured in the same run, because shared machines are noisy.

mod clients;
mod composite;
mod control;
mod execute;
mod execute_es3;
mod glmark2;
mod input;
mod interference;
mod interference_client;
mod mesh;
mod plot;
mod precision;
mod side;
mod soak;
mod soak_client;
mod stratad;
mod thesis;
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
    /// GLES execution: the glmark2 horse through stratad against the same drawing in plain
    /// wgpu, measured in the same run.
    Execute(execute::Args),
    /// Compositor: ms per output frame for k = 1…16 surfaces at a chaining limit and at the
    /// device's limit, against the device's copy of the same bytes, measured in the same run.
    Composite(composite::Args),
    /// Unmodified glmark2-es2 through Strata against native Mesa (same run, same Xvfb), and
    /// n = 1…10 concurrent instances at one z and area.
    Glmark2(glmark2::Args),
    /// Runs the daemon half of a benchmark (started by the benchmark itself).
    #[command(hide = true)]
    Daemon {
        /// Socket to serve on.
        #[arg(long)]
        socket: std::path::PathBuf,
        /// Executor for client sessions.
        #[arg(long, value_enum, default_value_t = strata_server::ExecutorKind::Drain)]
        executor: strata_server::ExecutorKind,
        /// An output, as for `stratad serve --output` (repeatable).
        #[arg(long = "output")]
        outputs: Vec<strata_compositor::root::OutputSpec>,
        /// The compositor, as for `stratad serve --compositor`.
        #[arg(long, value_enum, default_value_t = strata_compositor::Mode::ThreeD)]
        compositor: strata_compositor::Mode,
        /// Textures per compositor pass, as for `stratad serve --max-textures`.
        #[arg(long)]
        max_textures: Option<u32>,
        /// Which device each client renders on, as for `stratad serve --devices`.
        #[arg(long, value_enum, default_value_t = strata_server::DeviceMode::PerClient)]
        devices: strata_server::DeviceMode,
        /// How frames reach the compositor, as for `stratad serve --frame-transfer`.
        #[arg(long, value_enum, default_value_t = strata_gles::TransferMode::Auto)]
        frame_transfer: strata_gles::TransferMode,
        /// As for `stratad serve --client-rasterizer-threads`.
        #[arg(long, default_value_t = 1)]
        client_rasterizer_threads: u32,
        /// As for `stratad serve --es3`.
        #[arg(long)]
        es3: bool,
    },
    /// What an idle client costs the daemon: resident memory and threads per connected client
    /// at 10 and 64 clients, against the empty daemon.
    Clients(clients::Args),
    /// The thesis' evaluation (chapter 5) on this machine: n = 1…10 glmark2-es2 instances over
    /// one area at one z, natively, at one z each, and through the 2D baseline; JSON and a PNG
    /// per figure.
    Thesis(thesis::Args),
    /// The daemon under client churn: a bystander's every frame checked against the same
    /// frame alone while clients are started and killed at random points; RSS over time as
    /// JSON and a PNG.
    Soak(soak::Args),
    /// One client of the soak (started by `soak` itself).
    #[command(hide = true)]
    SoakClient(soak_client::Args),
    /// Freedom from interference: an instrument cluster's frame times alone and beside each
    /// head-unit load (glmark2 terrain and refract, a huge draw, 64 MiB uploads per frame).
    Interference(interference::Args),
    /// One client of the interference benchmark (started by `interference` itself).
    #[command(hide = true)]
    InterferenceClient(interference_client::Args),
    /// Precision knobs, one row per setting: composite ms beside depth, selection and colour
    /// error against the f64 reference compositor, measured in the same run.
    Precision(precision::Args),
    /// The control surface under a full scene: how many refreshes a batch takes to show, and
    /// how long `ctl list --json` takes to answer, with 64 surfaces from real clients.
    Control(control::Args),
    #[command(hide = true)]
    ControlClient(control::ClientArgs),
    /// Input routing under load: a tap's time from arrival to the client's queue with 8
    /// clients drawing (against none drawing), and the refreshes until the client's reaction
    /// shows on the output.
    Input(input::Args),
}

fn main() -> Result<()> {
    // Before any thread starts (see `settle_environment`).
    strata_device::settle_environment();
    let filter = tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "warn".into());
    tracing_subscriber::fmt().with_env_filter(filter).with_writer(std::io::stderr).init();
    match Cli::parse().command {
        Cmd::Transport(args) => transport::run(&args),
        Cmd::Execute(args) => execute::run(&args),
        Cmd::Composite(args) => composite::run(&args),
        Cmd::Glmark2(args) => glmark2::run(&args),
        Cmd::Daemon {
            socket,
            executor,
            outputs,
            compositor,
            max_textures,
            devices,
            frame_transfer,
            client_rasterizer_threads,
            es3,
        } => {
            let opts = strata_server::ServeOptions {
                socket,
                executor,
                compositor,
                max_textures,
                devices,
                frame_transfer,
                client_rasterizer_threads: (client_rasterizer_threads > 0).then_some(client_rasterizer_threads),
                es3: if es3 { strata_gles::Es3Contexts::Asked } else { strata_gles::Es3Contexts::Off },
                ..Default::default()
            };
            transport::daemon(opts, outputs)
        }
        Cmd::Thesis(args) => thesis::run(&args),
        Cmd::Clients(args) => clients::run(&args),
        Cmd::Soak(args) => soak::run(&args),
        Cmd::SoakClient(args) => soak_client::run(&args),
        Cmd::Interference(args) => interference::run(&args),
        Cmd::InterferenceClient(args) => interference_client::run(&args),
        Cmd::Precision(args) => precision::run(&args),
        Cmd::Control(args) => control::run(&args),
        Cmd::ControlClient(args) => control::client(&args),
        Cmd::Input(args) => input::run(&args),
    }
}
