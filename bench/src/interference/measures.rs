//! The interference benchmark's arguments, its loads, and what it measures and reports.

use std::path::PathBuf;

use clap::ValueEnum;
use serde::Serialize;
use serde_json::Value;

use crate::interference_client::FrameStats;

/// The IC's frame deadline: 1.5 refresh periods at the daemon's default 60 Hz.
pub(crate) const DEADLINE_MS: f64 = 1.5 * 1000.0 / 60.0;
/// The daemon's output (one, headless).
pub(crate) const OUTPUT: &str = "main=1920x720";

/// A head-unit load.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Load {
    /// glmark2-es2 `--benchmark terrain` through the drop-in libraries.
    Terrain,
    /// glmark2-es2 `--benchmark refract` through the drop-in libraries.
    Refract,
    /// One fullscreen quad per frame with a very long fragment loop (`interference-client`).
    HugeDraw,
    /// 64 MiB of texture uploads per frame (`interference-client`).
    Upload,
    /// No client at all: one busy thread per core outside the daemon, the CPU contention no
    /// scheduling in the daemon can remove (on lavapipe the "GPU" is the same CPU).
    CpuHog,
    /// A head unit that opens sessions until the daemon refuses one (its `[[quota]]` entry
    /// allows 8), each drawing the huge draw (`interference-client`).
    SessionFlood,
}

impl Load {
    pub(crate) fn name(self) -> String {
        self.to_possible_value().map_or_else(|| format!("{self:?}"), |v| v.get_name().to_string())
    }

    pub(crate) fn is_glmark2(self) -> bool {
        matches!(self, Load::Terrain | Load::Refract)
    }
}

/// `strata-bench interference` arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Seconds the IC is measured in each phase.
    #[arg(long, default_value_t = 20.0)]
    pub seconds: f64,
    /// Where the configuration, JSON, plot and logs go.
    #[arg(long, default_value = "target/strata-bench/interference")]
    pub out: PathBuf,
    /// The daemon binary [default: `stratad` beside this program].
    #[arg(long)]
    pub stratad: Option<PathBuf>,
    /// HU loads, in order (comma-separated).
    #[arg(long, value_enum, value_delimiter = ',', default_value = "terrain,refract,huge-draw,upload,cpu-hog")]
    pub loads: Vec<Load>,
    /// Leave `priority` and `deadline` out of the daemon's layout.
    #[arg(long)]
    pub no_priorities: bool,
    /// The HU's window size, WxH (glmark2's `-s` too).
    #[arg(long, default_value = "1280x720")]
    pub hu_size: String,
    /// Fragment-loop iterations of the huge draw.
    #[arg(long, default_value_t = 50)]
    pub iterations: u32,
    /// Directory holding libEGL.so.1 and libGLESv2.so.2 [default: libstrata_egl.so beside
    /// this binary].
    #[arg(long)]
    pub shim: Option<PathBuf>,
    /// Print only the JSON (no progress bar, no table).
    #[arg(long)]
    pub json: bool,
    /// One more option for the daemon (repeatable), e.g. `--daemon-arg=--devices=shared`.
    #[arg(long = "daemon-arg", allow_hyphen_values = true)]
    pub daemon_args: Vec<String>,
    /// Start the IC's and the HU's processes at this benchmark's own nice value, instead of at
    /// the nice value the daemon gives their classes' device threads (IC high: −5, HU low: 19),
    /// as a deployment's service units would (systemd's `Nice=`).
    #[arg(long)]
    pub same_process_nice: bool,
}

/// One phase: the IC alone or beside one load.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Phase {
    pub(crate) phase: String,
    #[serde(flatten)]
    pub(crate) ic: FrameStats,
    /// The daemon's `deadline_misses` for the IC over the phase (null where it has none).
    pub(crate) daemon_deadline_misses: Option<u64>,
    pub(crate) p50_ratio: Option<f64>,
    pub(crate) p99_ratio: Option<f64>,
    pub(crate) max_ratio: Option<f64>,
    /// The HU's frames per second over the phase, from the daemon's frame counter.
    pub(crate) hu_fps: Option<f64>,
    /// The HU's own frame rate (the client's result, or glmark2's last FPS line).
    pub(crate) hu_reported_fps: Option<f64>,
    /// The HU's frames per second with no IC connected, measured just before (from the
    /// daemon's frame counter, over as many seconds).
    pub(crate) hu_alone_fps: Option<f64>,
    /// `hu_fps` over `hu_alone_fps`: what the IC costs the HU.
    pub(crate) hu_vs_alone: Option<f64>,
    /// The HU surface's swap interval as the daemon lists it.
    pub(crate) hu_interval: Option<i64>,
    pub(crate) hu_error: Option<String>,
    pub(crate) load_average_1m: Option<f64>,
    /// The IC's surface as `ctl list` showed it at the end of the phase.
    pub(crate) ic_surface: Option<Value>,
    /// The IC's and the HU's `ctl stats` rows at the end of the phase: class, and where their
    /// frames waited (swap, device), and their devices (busy time, threads, global priority).
    pub(crate) clients: Vec<Value>,
    pub(crate) frame_times_ms: Vec<f64>,
}

/// The target for one load: p99 within 1.25× alone, no more client-side misses, and the HU
/// keeps at least 0.7 of the frame rate it has with no IC.
#[derive(Debug, Serialize)]
pub(crate) struct Verdict {
    pub(crate) load: String,
    pub(crate) p99_ratio: f64,
    pub(crate) p99_ok: bool,
    pub(crate) client_misses: u64,
    pub(crate) alone_client_misses: u64,
    pub(crate) misses_ok: bool,
    pub(crate) hu_vs_alone: Option<f64>,
    pub(crate) hu_ok: bool,
    pub(crate) pass: bool,
}

#[derive(Debug, Serialize)]
pub(crate) struct Report {
    pub(crate) benchmark: &'static str,
    pub(crate) seconds: f64,
    pub(crate) priorities: bool,
    pub(crate) config: String,
    pub(crate) output: &'static str,
    pub(crate) deadline_ms: f64,
    pub(crate) phases: Vec<Phase>,
    pub(crate) skipped: Vec<String>,
    pub(crate) failures: Vec<String>,
    pub(crate) verdicts: Vec<Verdict>,
    pub(crate) plot: String,
    pub(crate) daemon_log: String,
}
