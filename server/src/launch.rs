//! `stratad run`: starts an unmodified GLES 2.0 application on the drop-in libraries, so that
//! nobody sets `LD_LIBRARY_PATH` by hand. The libraries are found in `STRATA_GL_DIR`, else
//! next to the binary as `tools/install` lays them out (`PREFIX/lib/strata` beside
//! `PREFIX/bin/stratad`), else where `tools/build-shim` puts them in a build tree
//! (`target/strata-gl`). The placement, name, class and surface ID become the environment the
//! libraries read (`STRATA_WINDOW`, `STRATA_NAME`, `STRATA_PRIORITY`, `STRATA_SURFACE_ID`);
//! the process then becomes the application (`exec`), keeping its PID and signals.

use std::ffi::OsString;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::Args;
use strata_protocol::control::Priority;
use strata_protocol::window::WindowPlacement;

/// `stratad run`'s options.
#[derive(Args)]
pub struct RunArgs {
    /// Where its window surfaces go: X,Y,Z or X,Y,Z,WxH (top left in the output space, depth
    /// layer, size); the daemon's layout applies without it.
    #[arg(long)]
    window: Option<String>,
    /// The client name the daemon's layout and quotas match [default: the program's name].
    #[arg(long)]
    name: Option<String>,
    /// The class its contexts ask for (high, normal, low); the daemon's configuration wins.
    #[arg(long)]
    priority: Option<Priority>,
    /// Stable surface ID(s) of its window surfaces, in creation order: ID or ID,ID,…
    #[arg(long)]
    surface_id: Option<String>,
    /// Socket path [default: as for serve].
    #[arg(long, env = "STRATA_SOCKET")]
    socket: Option<PathBuf>,
    /// The application and its arguments, after `--`.
    #[arg(last = true, required = true, value_name = "APP ARGS")]
    command: Vec<OsString>,
}

/// The drop-in libraries' directory: one holding `libEGL.so.1` and `libGLESv2.so.2`.
fn library_dir() -> Result<PathBuf> {
    let has_libraries = |d: &Path| d.join("libEGL.so.1").exists() && d.join("libGLESv2.so.2").exists();
    if let Some(dir) = std::env::var_os("STRATA_GL_DIR").map(PathBuf::from) {
        if has_libraries(&dir) {
            return Ok(dir);
        }
        bail!("STRATA_GL_DIR={} holds no libEGL.so.1 and libGLESv2.so.2", dir.display());
    }
    let exe = std::env::current_exe().context("finding stratad's own path")?;
    let bin = exe.parent().context("stratad's directory")?;
    let candidates = [bin.join("../lib/strata"), bin.join("../strata-gl"), bin.join("strata-gl")];
    candidates.iter().find(|d| has_libraries(d)).map(|d| d.canonicalize().unwrap_or_else(|_| d.clone())).with_context(
        || {
            let tried: Vec<String> = candidates.iter().map(|d| d.display().to_string()).collect();
            format!(
                "the drop-in libraries are not installed: tried {}; run tools/install or tools/build-shim, or set STRATA_GL_DIR",
                tried.join(", ")
            )
        },
    )
}

/// Checks the options, sets the environment and becomes the application; returns only on
/// failure.
pub fn run(args: RunArgs) -> Result<()> {
    if let Some(w) = &args.window {
        w.parse::<WindowPlacement>()?;
    }
    if let Some(ids) = &args.surface_id {
        for id in ids.split(',') {
            strata_protocol::surface_id::parse(id).with_context(|| format!("--surface-id {ids}"))?;
        }
    }
    let dir = library_dir()?;
    let (program, rest) = args.command.split_first().context("no application given after --")?;
    let mut path = OsString::from(&dir);
    if let Some(old) = std::env::var_os("LD_LIBRARY_PATH").filter(|p| !p.is_empty()) {
        path.push(":");
        path.push(old);
    }
    let mut cmd = std::process::Command::new(program);
    cmd.args(rest).env("LD_LIBRARY_PATH", path);
    let vars = [
        (strata_protocol::window::ENV, args.window),
        ("STRATA_NAME", args.name),
        (strata_protocol::control::PRIORITY_ENV, args.priority.map(|p| p.name().to_string())),
        (strata_protocol::surface_id::ENV, args.surface_id),
    ];
    for (var, value) in vars {
        if let Some(v) = value {
            cmd.env(var, v);
        }
    }
    if let Some(s) = args.socket {
        cmd.env("STRATA_SOCKET", s);
    }
    // The drop-in library delivers input as core X11 events; Qt 5 reads only XInput 2 events
    // where the server has them, unless told to use core events.
    if std::env::var_os("QT_XCB_NO_XI2").is_none() {
        cmd.env("QT_XCB_NO_XI2", "1");
    }
    let err = cmd.exec();
    Err(err).with_context(|| format!("starting {}", Path::new(program).display()))
}
