//! The clients `strata-bench soak` starts and kills: each runs one behaviour until it is
//! killed or, for the behaviours that end by themselves, until it is done.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{bail, Result};
use strata_client::setup::{egl_context, Current, SurfaceKind};
use strata_client::workload::Workload;
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::{Blob, Slice};

const GL_TEXTURE_2D: u32 = 0x0DE1;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_OUT_OF_MEMORY: u32 = 0x0505;

/// What a soak client does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Behaviour {
    /// Streams an endless seeded mix of GLES commands (killed mid-command).
    Commands,
    /// Uploads 2048² RGBA8 textures, 16 MiB each, one after another (killed mid-upload).
    Upload,
    /// Swaps a window surface unthrottled (killed mid-swap).
    Swap,
    /// Swaps a window surface paced at the refresh rate, so it is mostly blocked in the swap
    /// (killed while blocked).
    Paced,
    /// Shows one frame, then never swaps again (killed while stalled).
    Stall,
    /// Draws a few frames, then disconnects cleanly.
    Clean,
    /// Allocates textures until its quota refuses one, then leaves.
    Quota,
}

impl Behaviour {
    /// Every behaviour, in the order the soak cycles through them.
    pub const ALL: [Behaviour; 7] = [
        Behaviour::Commands,
        Behaviour::Upload,
        Behaviour::Swap,
        Behaviour::Paced,
        Behaviour::Stall,
        Behaviour::Clean,
        Behaviour::Quota,
    ];

    /// Whether the client ends by itself (the others are killed with SIGKILL).
    pub fn ends_itself(self) -> bool {
        matches!(self, Behaviour::Clean | Behaviour::Quota)
    }
}

/// The `soak-client` arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Socket of the daemon.
    #[arg(long)]
    pub socket: PathBuf,
    /// What to do.
    #[arg(long, value_enum)]
    pub behaviour: Behaviour,
    /// Seed of the command mix and placement.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// Runs one soak client.
pub fn run(args: &Args) -> Result<()> {
    let opts = ConnectOptions {
        socket: args.socket.clone(),
        name: format!("soak-{:?}", args.behaviour).to_lowercase(),
        role: "hu".into(),
        ..ConnectOptions::default()
    };
    let mut gl = Connection::connect(&opts)?;
    // Beside the bystander, never over it: x from 128 on.
    let x = 128 + (args.seed % 4) as i32 * 32;
    let window = SurfaceKind::Window { rect: [x, 0, 96, 96], z: 0.5 };
    match args.behaviour {
        Behaviour::Commands => {
            egl_context(&mut gl, 0, 0, window)?;
            let mut load = Workload::new(args.seed, 64 << 10);
            loop {
                gl.send(&load.next_command())?;
            }
        }
        Behaviour::Upload => {
            egl_context(&mut gl, 0, 0, SurfaceKind::Pbuffer { width: 16, height: 16 })?;
            let texels = vec![0x5a; 2048 * 2048 * 4];
            gl.glBindTexture(GL_TEXTURE_2D, 1)?;
            loop {
                let data = Some(Blob::borrowed(&texels));
                gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, 2048, 2048, 0, GL_RGBA, GL_UNSIGNED_BYTE, data)?;
            }
        }
        Behaviour::Swap | Behaviour::Paced => {
            let cur = egl_context(&mut gl, 24, 0, window)?;
            let interval = i32::from(args.behaviour == Behaviour::Paced);
            let _ = gl.eglSwapInterval(cur.display, interval)?;
            for f in 0u32.. {
                frame(&mut gl, cur, f)?;
            }
            Ok(())
        }
        Behaviour::Stall => {
            let cur = egl_context(&mut gl, 24, 0, window)?;
            frame(&mut gl, cur, 0)?;
            gl.glFinish()?;
            loop {
                std::thread::sleep(Duration::from_secs(1));
            }
        }
        Behaviour::Clean => {
            let cur = egl_context(&mut gl, 24, 0, window)?;
            for f in 0..5 {
                frame(&mut gl, cur, f)?;
            }
            let _ = gl.eglTerminate(cur.display)?;
            Ok(())
        }
        Behaviour::Quota => {
            egl_context(&mut gl, 0, 0, SurfaceKind::Pbuffer { width: 16, height: 16 })?;
            let start = Instant::now();
            for name in 1.. {
                gl.glBindTexture(GL_TEXTURE_2D, name)?;
                gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, 1024, 1024, 0, GL_RGBA, GL_UNSIGNED_BYTE, None)?;
                if gl.glGetError()? == GL_OUT_OF_MEMORY {
                    // Refused, and still working: the rest of the stream is served.
                    gl.glDeleteTextures(Slice::new(&[1]))?;
                    gl.glFinish()?;
                    return Ok(());
                }
                if start.elapsed() > Duration::from_secs(60) {
                    break;
                }
            }
            bail!("no quota refused a texture in 60 s")
        }
    }
}

fn frame(gl: &mut Connection, cur: Current, f: u32) -> Result<()> {
    let c = (f % 50) as f32 / 50.0;
    gl.glClearColor(c, 0.3, 1.0 - c, 1.0)?;
    gl.glClear(GL_COLOR_BUFFER_BIT)?;
    gl.eglSwapBuffers(cur.display, cur.surface)?.map_err(|e| anyhow::anyhow!("eglSwapBuffers: EGL error {e:#x}"))?;
    Ok(())
}
