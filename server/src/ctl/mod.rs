//! `stratad ctl`: the operator's commands against a running daemon, and how their answers
//! are printed (part of the `stratad` binary).

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Subcommand;
use strata_client::ControlConnection;
use strata_protocol::control::LightChange;
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::input::{Action, Device, InputRequest};

use strata_protocol::properties::{Batch, Change};

use crate::args::Normals;
use crate::png::save_png;

mod print;

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
    /// Set a window surface's visibility, opacity, source region (the part of its image
    /// shown) or destination region (where it shows, scaled to fit).
    Surface {
        /// Surface ID (as `list` shows it).
        surface: u64,
        #[command(subcommand)]
        what: SurfaceCmd,
    },
    /// Layers, named groups of surfaces: `layer create NAME`, `layer destroy NAME`,
    /// `layer NAME add|remove SURFACE`, `layer NAME visibility on|off`, `layer NAME opacity A`.
    Layer {
        /// The words of the command, as above.
        #[arg(num_args = 2..=3, required = true, value_names = ["NAME|create|destroy", "..."])]
        words: Vec<String>,
    },
    /// Apply a batch of changes from a JSON file (`{"changes": [...]}`, see docs/control.md) in
    /// one composite: all of it shows at once, or none of it applies.
    Apply {
        /// The batch.
        file: PathBuf,
    },
    /// Why a surface does not show: no frame yet, visibility off (its own or a layer's),
    /// opacity 0, no area, off every output, or covered by nearer opaque surfaces.
    Analyze {
        /// Surface ID (as `list` shows it).
        surface: u64,
    },
    /// Write the whole scene (outputs, layout, surfaces with their properties, layers,
    /// lighting, quotas) as JSON that `stratad serve --config FILE.json` reads back.
    Export {
        /// The file to write.
        file: PathBuf,
    },
    /// Stream events, one line each, until interrupted: clients and surfaces coming and going
    /// (with name and pid), property changes, and each surface's frame statistics once a second.
    Watch,
    /// The daemon's memory, every client's GPU memory and objects against its quota, and the
    /// objects alive on the device.
    Stats,
    /// Input on an output, delivered to the surface shown at the point (per fragment, by
    /// depth) or to the output's focused surface: `input tap X Y`, `input press|move X Y
    /// [--touch ID | --button N]`, `input release [--touch ID | --button N]`, `input key NAME`,
    /// `input text STRING`, `input focus SURFACE`.
    Input {
        /// The output (as `list` shows it; default: the first).
        #[arg(long, default_value = "")]
        output: String,
        #[command(subcommand)]
        what: InputCmd,
    },
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
    /// Stop the compositor thread as a composite that never returns would (only on a daemon
    /// started with `--allow-fault-injection`; for tests of the watchdog).
    #[command(hide = true)]
    WedgeCompositor,
}

/// `on` or `off`.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum OnOff {
    /// Shown.
    On,
    /// Hidden.
    Off,
}

#[derive(Subcommand)]
pub enum SurfaceCmd {
    /// Show or hide it (hidden, it takes no part in the depth select).
    Visibility {
        /// on or off.
        #[arg(value_enum)]
        state: OnOff,
    },
    /// Multiply its premultiplied colour by A in [0, 1].
    Opacity {
        /// The opacity.
        #[arg(allow_negative_numbers = true)]
        opacity: f32,
    },
    /// Show only part of its image: X Y (from the image's top) W H.
    SourceRegion {
        /// x, y, width, height.
        #[arg(num_args = 4, allow_negative_numbers = true, value_names = ["X", "Y", "W", "H"])]
        region: Vec<i32>,
    },
    /// Whether it accepts input (off: input passes over it to what lies behind).
    Input {
        /// on or off.
        #[arg(value_enum)]
        state: OnOff,
    },
    /// Show it at X Y in the output space, scaled to W×H.
    DestinationRegion {
        /// x, y, width, height.
        #[arg(num_args = 4, allow_negative_numbers = true, value_names = ["X", "Y", "W", "H"])]
        region: Vec<i32>,
    },
}

/// Which point `ctl input press|move|release` acts on.
#[derive(clap::Args, Clone, Copy)]
pub struct PointArgs {
    /// A touch point's ID (a touchscreen).
    #[arg(long, conflicts_with = "button")]
    touch: Option<u32>,
    /// A pointer button: 1 left (the default), 2 middle, 3 right.
    #[arg(long)]
    button: Option<u32>,
}

impl PointArgs {
    fn point(self) -> (Device, u32) {
        match (self.touch, self.button) {
            (Some(id), _) => (Device::Touch, id),
            (None, b) => (Device::Pointer, b.unwrap_or(1)),
        }
    }
}

#[derive(Subcommand)]
pub enum InputCmd {
    /// A touch down and up at X Y (output pixels from the top-left corner).
    Tap {
        /// x.
        x: f32,
        /// y.
        y: f32,
    },
    /// A button press or touch down at X Y.
    Press {
        /// x.
        x: f32,
        /// y.
        y: f32,
        #[command(flatten)]
        point: PointArgs,
    },
    /// A move of a pressed button or touch point to X Y.
    Move {
        /// x.
        #[arg(allow_negative_numbers = true)]
        x: f32,
        /// y.
        #[arg(allow_negative_numbers = true)]
        y: f32,
        #[command(flatten)]
        point: PointArgs,
    },
    /// A button release or touch up.
    Release {
        #[command(flatten)]
        point: PointArgs,
    },
    /// A key pressed and released (X keysym name: Return, BackSpace, Left, F1, a, …).
    Key {
        /// The key's name.
        name: String,
    },
    /// Text typed into the focused surface.
    Text {
        /// The text.
        text: String,
    },
    /// Give the output's keyboard focus to a surface.
    Focus {
        /// Surface ID (as `list` shows it).
        surface: u64,
    },
}

impl InputCmd {
    /// The action it asks for.
    fn action(&self) -> Action {
        match self {
            InputCmd::Tap { x, y } => Action::Tap { x: *x, y: *y },
            InputCmd::Press { x, y, point } => {
                let (device, id) = point.point();
                Action::Press { device, id, x: *x, y: *y }
            }
            InputCmd::Move { x, y, point } => {
                let (device, id) = point.point();
                Action::Move { device, id, x: *x, y: *y }
            }
            InputCmd::Release { point } => {
                let (device, id) = point.point();
                Action::Release { device, id }
            }
            InputCmd::Key { name } => Action::Key { name: name.clone() },
            InputCmd::Text { text } => Action::Text { text: text.clone() },
            InputCmd::Focus { surface } => Action::Focus { surface: *surface },
        }
    }
}

/// The change `ctl surface ID …` asks for.
fn surface_change(surface: u64, what: &SurfaceCmd) -> Result<Change> {
    let rect = |v: &[i32]| <[i32; 4]>::try_from(v).map_err(|_| anyhow::anyhow!("a region is four numbers: X Y W H"));
    Ok(match what {
        SurfaceCmd::Visibility { state } => Change::Visibility { surface, visible: matches!(state, OnOff::On) },
        SurfaceCmd::Input { state } => Change::InputAcceptance { surface, accepts: matches!(state, OnOff::On) },
        SurfaceCmd::Opacity { opacity } => Change::Opacity { surface, opacity: *opacity },
        SurfaceCmd::SourceRegion { region } => Change::SourceRegion { surface, region: rect(region)? },
        SurfaceCmd::DestinationRegion { region } => Change::DestinationRegion { surface, region: rect(region)? },
    })
}

/// The change `ctl layer …` asks for.
fn layer_change(words: &[String]) -> Result<Change> {
    let w: Vec<&str> = words.iter().map(String::as_str).collect();
    let on = |v: &str| match v {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => bail!("visibility is on or off, not {v:?}"),
    };
    let id = |v: &str| v.parse::<u64>().with_context(|| format!("surface ID {v:?}"));
    let layer = |n: &str| n.to_string();
    Ok(match w.as_slice() {
        ["create", name] => Change::LayerCreate { layer: layer(name) },
        ["destroy", name] => Change::LayerDestroy { layer: layer(name) },
        [name, "add", s] => Change::LayerAdd { layer: layer(name), surface: id(s)? },
        [name, "remove", s] => Change::LayerRemove { layer: layer(name), surface: id(s)? },
        [name, "visibility", v] => Change::LayerVisibility { layer: layer(name), visible: on(v)? },
        [name, "opacity", a] => {
            Change::LayerOpacity { layer: layer(name), opacity: a.parse().with_context(|| format!("opacity {a:?}"))? }
        }
        _ => bail!(
            "`layer {}` is not a layer command: layer create NAME, layer destroy NAME, layer NAME add|remove SURFACE, layer NAME visibility on|off, layer NAME opacity A",
            w.join(" ")
        ),
    })
}

/// Refuses, before sending, what JSON cannot carry (numbers that are not finite) with the
/// daemon's own words, and changes the daemon would refuse.
fn check(request: &ControlRequest) -> Result<()> {
    match request {
        ControlRequest::Move { z, .. } if !z.is_finite() => bail!("z {z} is not a finite number"),
        ControlRequest::Normal { normal, .. } if !normal.iter().all(|v| v.is_finite()) => {
            bail!("normal {normal:?} must be finite and not zero")
        }
        ControlRequest::Light(change) => change.validate().map_err(|e| anyhow::anyhow!("{e}")),
        ControlRequest::Input(req) => req.action.validate().map_err(|e| anyhow::anyhow!("{e}")),
        ControlRequest::Apply { changes } => {
            strata_protocol::properties::validate_batch(changes).map_err(|e| anyhow::anyhow!("{e}"))
        }
        _ => Ok(()),
    }
}

/// The batch in `file`; nothing is sent if it does not parse.
fn read_batch(file: &std::path::Path) -> Result<Vec<Change>> {
    let text = std::fs::read_to_string(file).with_context(|| format!("reading {}", file.display()))?;
    let batch: Batch = serde_json::from_str(&text).with_context(|| {
        format!("{} is not a batch of changes (see docs/control.md); nothing applied", file.display())
    })?;
    Ok(batch.changes)
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
    if let CtlCmd::Watch = what {
        return watch(c, json);
    }
    let mut changes = Vec::new();
    let request = match &what {
        CtlCmd::Analyze { surface } => ControlRequest::Analyze { surface: *surface },
        CtlCmd::Export { .. } => ControlRequest::Export,
        CtlCmd::Watch => ControlRequest::Watch,
        CtlCmd::WedgeCompositor => ControlRequest::WedgeCompositor,
        CtlCmd::List => ControlRequest::List,
        CtlCmd::Surface { surface, what } => ControlRequest::Apply { changes: vec![surface_change(*surface, what)?] },
        CtlCmd::Layer { words } => ControlRequest::Apply { changes: vec![layer_change(words)?] },
        CtlCmd::Apply { file } => {
            changes = read_batch(file)?;
            ControlRequest::Apply { changes: changes.clone() }
        }
        CtlCmd::Stats => ControlRequest::Stats,
        CtlCmd::LoseDevice { client } => ControlRequest::LoseDevice { client: *client },
        CtlCmd::Input { output, what } => {
            ControlRequest::Input(InputRequest { output: output.clone(), action: what.action() })
        }
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
    check(&request)?;
    match (c.request(&request)?, what) {
        (ControlReply::Error(e), _) => bail!("{e}"),
        (ControlReply::List { outputs, surfaces, layers, .. }, what) => {
            let applied = match what {
                CtlCmd::Surface { .. } | CtlCmd::Layer { .. } => Some(1),
                CtlCmd::Apply { .. } => Some(changes.len()),
                _ => None,
            };
            if json {
                println!("{}", serde_json::json!({"outputs": outputs, "surfaces": surfaces, "layers": layers}));
            } else if let Some(n) = applied {
                println!("applied {n} change{}", if n == 1 { "" } else { "s" });
            } else {
                print::list(&outputs, &surfaces, &layers);
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
        (ControlReply::Analysis(a), _) => {
            if json {
                println!("{}", serde_json::json!(a));
            } else if a.visible {
                println!("surface {} shows", a.surface);
            } else {
                println!("surface {} does not show:", a.surface);
                for r in &a.reasons {
                    println!("  {r}");
                }
            }
            Ok(())
        }
        (ControlReply::Scene(scene), CtlCmd::Export { file }) => {
            let text = serde_json::to_string_pretty(&scene)?;
            std::fs::write(&file, text + "\n").with_context(|| format!("writing {}", file.display()))?;
            if json {
                println!("{}", serde_json::json!({ "file": file }));
            } else {
                println!("wrote {}", file.display());
            }
            Ok(())
        }
        (ControlReply::Stats(s), _) => {
            if json {
                println!("{}", serde_json::json!(s));
                return Ok(());
            }
            print::stats(&s);
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
        (ControlReply::Input(o), _) => {
            if json {
                println!("{}", serde_json::json!(o));
            } else {
                match (o.surface, &o.dropped) {
                    (Some(s), _) => println!("to surface {s}"),
                    (None, Some(why)) => println!("dropped: {why}"),
                    (None, None) => println!("dropped"),
                }
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

/// Prints every event until the daemon closes the stream (or the process is interrupted).
fn watch(c: ControlConnection, json: bool) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    for e in c.watch()? {
        let e = e?;
        if json {
            writeln!(out, "{}", serde_json::json!(e))?;
        } else {
            writeln!(out, "{}", print::event(&e))?;
        }
        out.flush()?;
    }
    Ok(())
}
