//! `stratad ctl`: the operator's commands against a running daemon, and how their answers
//! are printed (part of the `stratad` binary).

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Subcommand;
use strata_client::ControlConnection;
use strata_protocol::control::LightChange;
use strata_protocol::handshake::{ControlReply, ControlRequest};

use crate::{save_png, Normals};

#[derive(Subcommand)]
pub enum CtlCmd {
    /// List every output and window surface.
    List,
    /// Save an output's current image as a PNG (`screenshot OUTPUT FILE.png`), or one window
    /// surface's newest complete frame (`screenshot --surface ID FILE.png`).
    Screenshot {
        /// Output name (as `list` shows it), then the PNG; only the PNG with `--surface`.
        #[arg(num_args = 1..=2, required = true, value_names = ["OUTPUT", "FILE.png"])]
        targets: Vec<String>,
        /// A window surface's ID (as `list` shows it) instead of an output.
        #[arg(long)]
        surface: Option<u64>,
    },
    /// Move a window surface in the output space.
    Move {
        /// Surface id (as `list` shows it).
        surface: u64,
        /// New left edge.
        #[arg(allow_negative_numbers = true)]
        x: i32,
        /// New top edge.
        #[arg(allow_negative_numbers = true)]
        y: i32,
        /// New depth layer (larger is farther).
        #[arg(allow_negative_numbers = true)]
        z: f32,
    },
    /// Set a window surface's normal for per-surface lighting.
    Normal {
        /// Surface id (as `list` shows it).
        surface: u64,
        /// The normal X,Y,Z (x right, y up, z towards the viewer).
        #[arg(value_parser = vec3, allow_hyphen_values = true)]
        normal: [f32; 3],
    },
    /// The daemon's memory, every client's GPU memory and objects against its quota, and the
    /// objects alive on the device.
    Stats,
    /// Show or change the uniform lighting.
    Light {
        #[command(subcommand)]
        what: LightCmd,
    },
    /// Destroy a client's GPU device, as a fault or a driver reset would lose it (only on a
    /// daemon started with `--allow-fault-injection`; for tests).
    #[command(hide = true)]
    LoseDevice {
        /// Client number (as `stats` shows it).
        client: u64,
    },
}

#[derive(Subcommand)]
pub enum LightCmd {
    /// Turn lighting on.
    On,
    /// Turn lighting off.
    Off,
    /// Show the lighting in force.
    Show,
    /// Change lighting parameters.
    Set {
        /// Light position X,Y,Z (output space: x, y in [-1, 1], y up, the output at z = 0).
        #[arg(long, value_parser = vec3, allow_hyphen_values = true)]
        position: Option<[f32; 3]>,
        /// Viewer position X,Y,Z.
        #[arg(long, value_parser = vec3, allow_hyphen_values = true)]
        view: Option<[f32; 3]>,
        /// Light colour R,G,B in [0, 1].
        #[arg(long, value_parser = vec3)]
        color: Option<[f32; 3]>,
        /// Ambient factor in [0, 1].
        #[arg(long)]
        ambient: Option<f32>,
        /// Specular exponent.
        #[arg(long)]
        shininess: Option<f32>,
        /// Where normals come from.
        #[arg(long, value_enum)]
        normals: Option<Normals>,
    },
}

pub fn vec3(s: &str) -> Result<[f32; 3], String> {
    let v: Vec<f32> =
        s.split(',').map(|p| p.trim().parse::<f32>().map_err(|e| format!("{p:?}: {e}"))).collect::<Result<_, _>>()?;
    <[f32; 3]>::try_from(v).map_err(|_| format!("{s:?} is not three comma-separated numbers"))
}

pub fn run(socket: &std::path::Path, json: bool, what: CtlCmd) -> Result<()> {
    let mut c = ControlConnection::connect(socket).with_context(|| format!("connecting to {}", socket.display()))?;
    let request = match &what {
        CtlCmd::List => ControlRequest::List,
        CtlCmd::Stats => ControlRequest::Stats,
        CtlCmd::LoseDevice { client } => ControlRequest::LoseDevice { client: *client },
        CtlCmd::Screenshot { targets, surface } => match (surface, targets.as_slice()) {
            (Some(surface), [_file]) => ControlRequest::SurfaceScreenshot { surface: *surface },
            (None, [output, _file]) => ControlRequest::Screenshot { output: output.clone() },
            (Some(_), _) => bail!("screenshot --surface ID takes one file: screenshot --surface ID FILE.png"),
            (None, _) => bail!("screenshot takes an output and a file: screenshot OUTPUT FILE.png"),
        },
        CtlCmd::Move { surface, x, y, z } => ControlRequest::Move { surface: *surface, x: *x, y: *y, z: *z },
        CtlCmd::Normal { surface, normal } => ControlRequest::Normal { surface: *surface, normal: *normal },
        CtlCmd::Light { what } => ControlRequest::Light(match what {
            LightCmd::On => LightChange { enabled: Some(true), ..Default::default() },
            LightCmd::Off => LightChange { enabled: Some(false), ..Default::default() },
            LightCmd::Show => LightChange::default(),
            LightCmd::Set { position, view, color, ambient, shininess, normals } => LightChange {
                enabled: None,
                ambient: *ambient,
                shininess: *shininess,
                position: *position,
                view: *view,
                color: *color,
                normals: normals.map(Into::into),
            },
        }),
    };
    match (c.request(&request)?, what) {
        (ControlReply::Error(e), _) => bail!("{e}"),
        (ControlReply::List { outputs, surfaces }, _) => {
            if json {
                println!("{}", serde_json::json!({"outputs": outputs, "surfaces": surfaces}));
                return Ok(());
            }
            println!(
                "{:<16} {:<9} {:>6} {:>6} {:>6} {:>6} {:>10} {:>6} {:>6} {:>9} {:>8} {:>9}  last redrawn",
                "output",
                "kind",
                "x",
                "y",
                "w",
                "h",
                "composites",
                "banded",
                "passes",
                "device ms",
                "queue ms",
                "encode ms"
            );
            for o in outputs {
                let r = o.region;
                let each = |us: u64| us as f64 / 1000.0 / o.composites.max(1) as f64;
                let (ms, queue, encode) = (each(o.composite_us), each(o.queue_us), each(o.encode_us));
                println!(
                    "{:<16} {:<9} {:>6} {:>6} {:>6} {:>6} {:>10} {:>6} {:>6} {ms:>9.2} {queue:>8.2} {encode:>9.2}  {}x{}+{}+{}",
                    o.name,
                    o.kind,
                    o.rect[0],
                    o.rect[1],
                    o.rect[2],
                    o.rect[3],
                    o.composites,
                    o.banded,
                    o.passes,
                    r[2],
                    r[3],
                    r[0],
                    r[1]
                );
            }
            println!();
            println!(
                "{:>4} {:<20} {:>6} {:>6} {:>6} {:>6} {:>8} {:>8} {:>8} {:>8} {:>12} {:>8} {:>8} {:>16}  projection",
                "id",
                "client",
                "x",
                "y",
                "w",
                "h",
                "z",
                "frames",
                "shown",
                "interval",
                "stream bytes",
                "priority",
                "missed",
                "shown in (p99)"
            );
            for r in surfaces {
                println!(
                    "{:>4} {:<20} {:>6} {:>6} {:>6} {:>6} {:>8.3} {:>8} {:>8} {:>8} {:>12} {:>8} {:>8} {:>16}  {}",
                    r.id,
                    format!("{} ({})", r.client, r.client_id),
                    r.rect[0],
                    r.rect[1],
                    r.rect[2],
                    r.rect[3],
                    r.z,
                    r.frames,
                    r.shown,
                    r.interval,
                    r.stream_bytes,
                    r.priority.name(),
                    if r.deadline { r.deadline_misses.to_string() } else { "-".into() },
                    format!("{:.1} ms", r.shown_latency_us[1] as f64 / 1000.0),
                    r.projection.map_or_else(|| "-".to_string(), |p| p.to_string())
                );
            }
            Ok(())
        }
        (ControlReply::Image { width, height, rgba }, CtlCmd::Screenshot { targets, .. }) => {
            let file = PathBuf::from(targets.last().map_or("", String::as_str));
            save_png(&file, width, height, rgba.0)?;
            if json {
                println!("{}", serde_json::json!({"file": file, "width": width, "height": height}));
            } else {
                println!("wrote {} ({width}x{height})", file.display());
            }
            Ok(())
        }
        (ControlReply::Stats(s), _) => {
            if json {
                println!("{}", serde_json::json!(s));
                return Ok(());
            }
            print_stats(&s);
            Ok(())
        }
        (ControlReply::Moved(r), _) => {
            if json {
                println!("{}", serde_json::json!(r));
            } else {
                println!("surface {} now at x {} y {} z {}, normal {:?}", r.id, r.rect[0], r.rect[1], r.z, r.normal);
            }
            Ok(())
        }
        (ControlReply::Light(l), _) => {
            if json {
                println!("{}", serde_json::json!(l));
            } else {
                println!(
                    "lighting {}: ambient {} shininess {} position {:?} view {:?} color {:?} normals {:?}",
                    if l.enabled { "on" } else { "off" },
                    l.ambient,
                    l.shininess,
                    l.position,
                    l.view,
                    l.color,
                    l.normals
                );
            }
            Ok(())
        }
        (other, _) => bail!("unexpected reply {other:?}"),
    }
}

fn mib(bytes: u64) -> String {
    format!("{:.1} MiB", bytes as f64 / (1 << 20) as f64)
}

/// One device as `ctl stats` prints it: busy time, its driver threads' nice values, the global
/// priority granted, whether it is the client's own and whether it was lost.
fn device_line(d: &strata_protocol::control::DeviceStats) -> String {
    let mut nice: Vec<i32> = d.threads.iter().map(|t| t.nice).collect();
    nice.sort_unstable();
    nice.dedup();
    format!(
        "busy {:.1} ms, {} threads at nice {:?}, global priority {}{}{}",
        d.busy_us as f64 / 1000.0,
        d.threads.len(),
        nice,
        d.global_priority.as_deref().unwrap_or("not offered"),
        if d.own { "" } else { ", shared" },
        if d.lost { ", LOST" } else { "" }
    )
}

fn print_stats(s: &strata_protocol::control::DaemonStats) {
    println!("daemon: rss {} (peak {}), {} sessions started", mib(s.rss_bytes), mib(s.peak_rss_bytes), s.sessions);
    println!("gpu memory: {} of {} for all clients", mib(s.gpu_bytes), mib(s.gpu_bytes_limit));
    let kinds: Vec<&String> = s.objects.keys().collect();
    print!(
        "{:>4} {:<20} {:>8} {:>8} {:>12} {:>12} {:>8}",
        "id", "client", "priority", "missed", "gpu memory", "limit", "refused"
    );
    for k in &kinds {
        print!(" {:>13}", k);
    }
    println!();
    for c in &s.clients {
        print!(
            "{:>4} {:<20} {:>8} {:>8} {:>12} {:>12} {:>8}",
            c.id,
            c.name,
            c.priority.name(),
            c.deadline_misses,
            mib(c.gpu_bytes),
            mib(c.gpu_bytes_limit),
            c.refusals
        );
        for k in &kinds {
            print!(" {:>13}", c.objects.get(*k).copied().unwrap_or(0));
        }
        println!();
    }
    print!(
        "{:>4} {:<20} {:>8} {:>8} {:>12} {:>12} {:>8}",
        "",
        "total",
        "",
        "",
        mib(s.gpu_bytes),
        mib(s.gpu_bytes_limit),
        ""
    );
    for k in &kinds {
        print!(" {:>13}", s.objects[*k]);
    }
    println!();
    println!("where frames waited (ms): swap, device; each device: busy ms, threads at nice, global priority");
    for c in &s.clients {
        let w = &c.waits;
        let ms = |us: u64| us as f64 / 1000.0;
        print!("{:>4} {:<20} {:>10.1} {:>10.1}", c.id, c.name, ms(w.swap_us), ms(w.gpu_us));
        match &c.device {
            Some(d) => println!("  {}", device_line(d)),
            None => println!(),
        }
    }
    if let Some(d) = &s.compositor_device {
        println!("{:>4} {:<20} {:>10} {:>10}  {}", "", "(compositor)", "", "", device_line(d));
    }
    if !s.device_objects.is_empty() {
        let live: Vec<String> = s.device_objects.iter().map(|(k, v)| format!("{k} {v}")).collect();
        println!("device objects: {}", live.join(", "));
    }
}
