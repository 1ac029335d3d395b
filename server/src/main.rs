//! `stratad`: the Strata daemon and its companion commands.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use strata_client::workload::Workload;
use strata_client::{Calls, ConnectOptions, Connection};
use strata_compositor::root::OutputSpec;
use strata_compositor::{Intermediate, Lighting, Mode};
use strata_gles::{DepthFormat, DepthOptions, TransferMode};
use strata_protocol::handshake::VertexWire;
use strata_protocol::handshake::{control_socket_for, default_control_socket_path, default_socket_path};
use strata_server::layout::{Config, LayoutEntry};
use strata_server::{serve, DeviceMode, ExecutorKind, ServeOptions};
use tracing::info;

use args::{Normals, Projections, Scene, Switch};

mod args;
mod ctl;
mod demo_run;
mod launch;
mod png;
#[cfg(test)]
mod readme_commands;

/// Strata: a consolidated 3D compositing window manager daemon.
#[derive(Parser)]
#[command(name = "stratad", version)]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

// Parsed once at start: the size of the `serve` variant's options costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Subcommand)]
enum Cmd {
    /// Serve clients on a Unix socket until SIGINT or SIGTERM.
    Serve {
        /// The client socket, where render clients connect [default: $XDG_RUNTIME_DIR/strata.sock,
        /// else /tmp/strata-$UID.sock].
        #[arg(long, env = "STRATA_SOCKET")]
        socket: Option<PathBuf>,
        /// The control socket, where `stratad ctl` and controllers connect [default: beside the
        /// client socket, NAME-control.sock].
        #[arg(long, env = "STRATA_CONTROL_SOCKET")]
        control_socket: Option<PathBuf>,
        /// Open the client socket to this group (name or number; mode 0660), so that clients
        /// running as other users can connect [default: the daemon's user only, 0600].
        #[arg(long)]
        client_group: Option<String>,
        /// Open the control socket to this group (name or number; mode 0660) [default: the
        /// daemon's user only, 0600].
        #[arg(long)]
        control_group: Option<String>,
        /// Command ring bytes per client (power of two).
        #[arg(long, default_value_t = 8 << 20)]
        cmd_ring: u32,
        /// Reply ring bytes per client (power of two).
        #[arg(long, default_value_t = 1 << 20)]
        reply_ring: u32,
        /// What executes client commands.
        #[arg(long, value_enum, default_value_t = ExecutorKind::Gles)]
        executor: ExecutorKind,
        /// Sampled textures per compositor pass (at least 4; default: the device's limit).
        #[arg(long)]
        max_textures: Option<u32>,
        /// The compositor: 3d (per-fragment depth within z-groups, lit) or 2d (the baseline:
        /// painter's order by z, every surface an opaque copy, no depth, no lighting).
        #[arg(long, value_enum, default_value_t = Mode::ThreeD)]
        compositor: Mode,
        /// The colour format of chained compositor passes' intermediates.
        #[arg(long, value_enum, default_value_t = Intermediate::Rgba8)]
        intermediate: Intermediate,
        /// The depth image format of surfaces whose config has depth: config (the config's
        /// EGL_DEPTH_SIZE decides), or one format for all (configs with stencil keep a stencil
        /// aspect: 32float only where the device has Depth32FloatStencil8).
        #[arg(long, value_enum, default_value_t = DepthFormat::Config)]
        depth_format: DepthFormat,
        /// Store the depth of surfaces that declare a forward perspective projection reversed
        /// (1 at the near plane), transparently to the application: with 32float, far more
        /// precise.
        #[arg(long)]
        reversed_z: bool,
        /// How render clients send GL_FLOAT client-side vertex arrays: float (as given), half
        /// (IEEE binary16) or fixed (16.16); buffer objects and other types go as given.
        #[arg(long, default_value_t = VertexWire::Float)]
        vertex_wire: VertexWire,
        /// Leave out of the composite what an opaque nearer z-group covers (the image is the
        /// same; off only to measure what culling saves).
        #[arg(long, value_enum, default_value_t = Switch::On)]
        cull: Switch,
        /// Uniform Phong lighting of the composited output.
        #[arg(long, value_enum, default_value_t = Switch::On)]
        lighting: Switch,
        /// Where lighting takes normals from.
        #[arg(long, value_enum, default_value_t = Normals::PerSurface)]
        normals: Normals,
        /// An output: [window:|headless:]NAME=WxH[+X+Y], the part of the output space it shows
        /// (repeatable; headless unless `window:`) [default: main=1920x720, in a window when
        /// $DISPLAY is set, else headless].
        #[arg(long = "output")]
        outputs: Vec<OutputSpec>,
        /// Most composites per second (the refresh rate paced swaps follow).
        #[arg(long, default_value_t = 60.0)]
        refresh_hz: f64,
        /// Frames a window surface may have swapped but not yet shown before eglSwapBuffers blocks.
        #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=16))]
        frames_in_flight: u32,
        /// Configuration file (TOML): `[[layout]]` entries with client, x, y, z, and optionally
        /// width and height, placing a client's windows by its name, and `priority` (high,
        /// normal, low) and `deadline` (true: count its missed frames); `[[quota]]` entries.
        #[arg(long)]
        config: Option<PathBuf>,
        /// A layout entry: CLIENT=X,Y,Z[,WxH] (repeatable; before the config file's entries).
        #[arg(long = "layout")]
        layouts: Vec<LayoutEntry>,
        /// Each client's limits (a `[[quota]]` entry of the config file overrides them for a
        /// client by name), and the total.
        #[command(flatten)]
        quota: strata_server::quota::QuotaArgs,
        /// The class of clients the configuration does not name.
        #[command(flatten)]
        schedule: strata_server::schedule::ScheduleArgs,
        /// Caps on sessions, devices and handshakes, and the reserves of the reserved class.
        #[command(flatten)]
        caps: strata_server::caps::CapArgs,
        /// Real input devices (libinput), off by default.
        #[command(flatten)]
        input: strata_server::input::libinput::InputArgs,
        /// Which device each client renders on: per-client (a device and instance of its
        /// own, at its class's priority; frames reach the compositor's device through shared
        /// memory) or shared (the compositor's, one queue for all).
        #[arg(long, value_enum, default_value_t = DeviceMode::PerClient)]
        devices: DeviceMode,
        /// How window surfaces' frames reach the compositor's device: auto (the same memory,
        /// exported and imported, where the driver can share it; else copied) or copy (always
        /// copied through host memory).
        #[arg(long, value_enum, default_value_t = TransferMode::Auto)]
        frame_transfer: TransferMode,
        /// Give OpenGL ES 3.0 contexts to clients that ask for version 3 (else
        /// `EGL_BAD_MATCH`, and they fall back to 2.0). ES 3.0 is being built: what is there
        /// and what is not is in docs/gles3.md.
        #[arg(long)]
        es3: bool,
        /// With `--es3`, give OpenGL ES 3.0 contexts to clients that ask for 2.0 too, as Mesa
        /// answers such a request with the highest version it has (piglit's GLSL ES 3.00
        /// compiler tests run in contexts asked for as 2.0). Off by default: until ES 3.0 is
        /// whole, a request for 2.0 gets 2.0.
        #[arg(long, requires = "es3")]
        es3_for_es2: bool,
        /// Do not ask for a queue global priority by class (VK_KHR/EXT_global_priority).
        #[arg(long)]
        no_global_priority: bool,
        /// Rasterizer threads of each client's device on a CPU rasterizer (lavapipe): one
        /// keeps clients from contending for cores inside each other's draws; 0: the driver's
        /// default (one per core). The compositor's device keeps the default.
        #[arg(long, default_value_t = 1)]
        client_rasterizer_threads: u32,
        /// Most clients' devices open at once (0: as many as the driver opens); clients beyond
        /// it, and any whose device the driver refuses, share the compositor's device.
        #[arg(long, default_value_t = 0)]
        max_client_devices: usize,
        /// A change of lower-priority surfaces that the compositor predicts will take longer
        /// than this (milliseconds) is drawn band by band between refreshes, so that it never
        /// holds up a high-priority surface's next composite (0: every such change; a very
        /// large value: none).
        #[arg(long, default_value_t = 4.0)]
        band_above_ms: f64,
        /// What each band is sized to take, in milliseconds (0: the smallest bands, 8 rows).
        #[arg(long, default_value_t = 2.0)]
        band_ms: f64,
        /// Let `ctl` destroy a client's device, as a fault would (for tests).
        #[arg(long, hide = true)]
        allow_fault_injection: bool,
    },
    /// Run an unmodified GLES 2.0 application on the drop-in libraries:
    /// `stratad run [--window X,Y,Z[,WxH]] [--name NAME] [--priority CLASS] -- APP ARGS...`
    Run(launch::RunArgs),
    /// Administer a running daemon.
    Ctl {
        /// The daemon's client socket, beside which its control socket is found [default: as
        /// for serve]; before or after the command.
        #[arg(long, env = "STRATA_SOCKET", global = true)]
        socket: Option<PathBuf>,
        /// The daemon's control socket [default: beside --socket, NAME-control.sock].
        #[arg(long, env = "STRATA_CONTROL_SOCKET", global = true)]
        control_socket: Option<PathBuf>,
        /// Answer in JSON; before or after the command.
        #[arg(long, global = true)]
        json: bool,
        #[command(subcommand)]
        what: ctl::CtlCmd,
    },
    /// Run a built-in demo client (started by `stratad demo`).
    #[command(hide = true)]
    DemoClient {
        /// Socket path.
        #[arg(long)]
        socket: PathBuf,
        /// `ic` or `hu` (the dial scene), `plane-a` or `plane-b` (the planes scene).
        #[arg(long)]
        role: String,
        /// Frames to render before reporting ready.
        #[arg(long, default_value_t = 30)]
        frames: u32,
        /// Declare the plane's projection through EGL_STRATA_surface_projection.
        #[arg(long)]
        declare: bool,
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
    /// Start a daemon with two built-in client processes, an instrument cluster and a head
    /// unit whose 3D geometry intersects, and write the composited, lit output as a PNG.
    Demo {
        /// Frames each client renders before the screenshot.
        #[arg(long, default_value_t = 30)]
        frames: u32,
        /// Where to write the PNG.
        #[arg(long, default_value = "strata-demo.png")]
        out: PathBuf,
        /// What the clients draw.
        #[arg(long, value_enum, default_value_t = Scene::Dial)]
        scene: Scene,
        /// The planes scene: whether the clients declare their projections (the compositor
        /// then compares eye-space depth) or not (raw depth).
        #[arg(long, value_enum, default_value_t = Projections::Declared)]
        projections: Projections,
        /// One more option for the demo's daemon (repeatable), e.g.
        /// `--daemon-arg=--frame-transfer=copy`.
        #[arg(long = "daemon-arg", allow_hyphen_values = true)]
        daemon_args: Vec<String>,
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
    // Before any thread starts (see `settle_environment`).
    strata_device::settle_environment();
    init_logging();
    match Cli::parse().command {
        Cmd::Serve {
            socket,
            control_socket,
            client_group,
            control_group,
            cmd_ring,
            reply_ring,
            executor,
            max_textures,
            compositor,
            intermediate,
            vertex_wire,
            depth_format,
            reversed_z,
            cull,
            lighting,
            normals,
            outputs,
            refresh_hz,
            frames_in_flight,
            config,
            mut layouts,
            quota,
            schedule,
            caps,
            input,
            devices,
            frame_transfer,
            es3,
            es3_for_es2,
            no_global_priority,
            allow_fault_injection,
            client_rasterizer_threads,
            max_client_devices,
            band_above_ms,
            band_ms,
        } => {
            let mut c = Config::default();
            if let Some(path) = config {
                c = Config::load(&path)?;
                layouts = strata_server::layout::merge(layouts, c.layout)?;
            }
            let quotas = c.quota;
            let mut outputs = outputs;
            if outputs.is_empty() {
                // Checked when the configuration was read.
                outputs = c.output.iter().filter_map(|o| o.parse().ok()).collect();
            }
            let lighting = c.lighting.unwrap_or(Lighting {
                enabled: matches!(lighting, Switch::On),
                normals: normals.into(),
                ..Lighting::default()
            });
            if !(refresh_hz.is_finite() && (1.0..=1000.0).contains(&refresh_hz)) {
                bail!("--refresh-hz {refresh_hz} must lie in 1..=1000");
            }
            let ms = |name: &str, v: f64| -> Result<std::time::Duration> {
                std::time::Duration::try_from_secs_f64(v / 1000.0)
                    .map_err(|_| anyhow::anyhow!("--{name} {v} must be a number of milliseconds, 0 or more"))
            };
            let bands = strata_compositor::root::BandOptions {
                above: ms("band-above-ms", band_above_ms)?,
                target: ms("band-ms", band_ms)?,
            };
            if let Some(m) = max_textures {
                if m < 4 {
                    bail!("{}", strata_compositor::CompositorError::TooFewTextures(m));
                }
            }
            let group = |g: Option<String>, what: &str| -> Result<Option<u32>> {
                g.map(|g| g.parse().or_else(|_| strata_server::credentials::group_id(&g)))
                    .transpose()
                    .with_context(|| format!("--{what}"))
            };
            let opts = ServeOptions {
                socket: socket.unwrap_or_else(default_socket_path),
                control_socket,
                client_group: group(client_group, "client-group")?,
                control_group: group(control_group, "control-group")?,
                cmd_ring,
                reply_ring,
                executor,
                max_textures,
                compositor,
                intermediate,
                vertex_wire,
                depth: DepthOptions { format: depth_format, reversed_z },
                cull: matches!(cull, Switch::On),
                lighting,
                outputs: if outputs.is_empty() { vec![OutputSpec::default()] } else { outputs },
                refresh_hz,
                frames_in_flight,
                layout: layouts,
                surfaces: c.surface,
                layers: c.layer,
                limits: quota.limits(),
                quotas,
                total_gpu_bytes: quota.total(),
                total_daemon_bytes: quota.total_daemon(),
                command_time: quota.command_time().map_err(anyhow::Error::msg)?,
                default_class: schedule.default_priority,
                devices,
                frame_transfer,
                es3: match (es3, es3_for_es2) {
                    (true, true) => strata_gles::Es3Contexts::ForEs2,
                    (true, false) => strata_gles::Es3Contexts::Asked,
                    _ => strata_gles::Es3Contexts::Off,
                },
                global_priority: !no_global_priority,
                fault_injection: allow_fault_injection,
                client_rasterizer_threads: (client_rasterizer_threads > 0).then_some(client_rasterizer_threads),
                max_client_devices: (max_client_devices > 0).then_some(max_client_devices),
                caps,
                bands,
                input,
            };
            run_daemon(opts)
        }
        Cmd::Run(args) => launch::run(args),
        Cmd::Ctl { socket, control_socket, json, what } => {
            let control = control_socket.unwrap_or_else(|| match socket {
                Some(s) => control_socket_for(&s),
                None => default_control_socket_path(),
            });
            ctl::run(&control, json, what)
        }
        Cmd::DemoClient { socket, role, frames, declare } => {
            if role.starts_with("plane-") {
                strata_server::demo::planes::run_client(&socket, &role, frames, declare)?;
            } else {
                strata_server::demo::run_client(&socket, &role, frames)?;
            }
            Ok(())
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
        Cmd::Demo { frames, out, scene, projections, daemon_args } => {
            demo_run::demo(frames, &out, scene, projections, &daemon_args)
        }
    }
}

/// Makes the daemon give memory back when clients leave: allocations of 1 MiB and more (ring
/// messages being assembled, uploads, the driver's images) are mapped on their own and unmapped
/// when freed. By default glibc raises this threshold after the first large free, after which
/// such blocks are carved from its heaps, which a departed client's frees leave fragmented and
/// resident; and it keeps one heap per thread that ever allocated, up to 8 per core.
fn return_memory_when_clients_leave() {
    // SAFETY: mallopt only changes allocator parameters; it is called before other threads start.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 20);
        libc::mallopt(libc::M_ARENA_MAX, 4);
    }
}

fn run_daemon(opts: ServeOptions) -> Result<()> {
    return_memory_when_clients_leave();
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
    drop(rt);
    // Every session, device and output is closed by now. Leave without running the C
    // libraries' exit handlers: the Vulkan loader may already have unloaded a driver that
    // registered one (lavapipe's), and calling into it crashed one stop in ten.
    use std::io::Write;
    let _ = std::io::stdout().flush();
    let _ = std::io::stderr().flush();
    // SAFETY: _exit ends the process at once; nothing after it runs.
    unsafe { libc::_exit(0) }
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
