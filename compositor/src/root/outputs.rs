//! The compositor's outputs: how one is named and sized (`--output`), and what each keeps
//! between composites (its image, its window, its counts and timings).

use std::str::FromStr;
use std::time::Duration;

use strata_device::Gpu;

/// Default output: the width and height of a typical automotive centre display.
pub const DEFAULT_OUTPUT: (u32, u32) = (1920, 720);

/// Where an output's image goes besides the daemon's memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// Off-screen only (screenshots).
    Headless,
    /// Also shown in a desktop window; failing to open one is an error.
    Window,
    /// A window when a display exists and one opens, else headless.
    Auto,
}

/// One output: a name and the rectangle of the global output space it shows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputSpec {
    /// Name used by `stratad ctl screenshot`.
    pub name: String,
    /// Headless, window, or whichever the environment allows.
    pub kind: OutputKind,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Left edge in the output space.
    pub x: i32,
    /// Top edge in the output space.
    pub y: i32,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            name: "main".into(),
            kind: OutputKind::Auto,
            width: DEFAULT_OUTPUT.0,
            height: DEFAULT_OUTPUT.1,
            x: 0,
            y: 0,
        }
    }
}

/// An output specification that does not parse.
#[derive(Debug, thiserror::Error)]
#[error("output {0:?} is not [window:|headless:]NAME=WxH[+X+Y] with sizes 1..=8192 (e.g. main=1920x720+0+0)")]
pub struct BadOutputSpec(String);

impl FromStr for OutputSpec {
    type Err = BadOutputSpec;

    /// Parses `[window:|headless:]NAME=WxH[+X+Y]` (or `WxH`, named `main`); headless unless
    /// `window:` is given.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || BadOutputSpec(s.to_string());
        let (kind, rest) = if let Some(r) = s.strip_prefix("window:") {
            (OutputKind::Window, r)
        } else {
            (OutputKind::Headless, s.strip_prefix("headless:").unwrap_or(s))
        };
        let (name, geom) = match rest.split_once('=') {
            Some((n, g)) if !n.is_empty() => (n.to_string(), g),
            Some(_) => return Err(bad()),
            None => ("main".to_string(), rest),
        };
        let mut parts = geom.split('+');
        let size = parts.next().ok_or_else(bad)?;
        let (w, h) = size.split_once('x').ok_or_else(bad)?;
        let width: u32 = w.parse().map_err(|_| bad())?;
        let height: u32 = h.parse().map_err(|_| bad())?;
        let x: i32 = parts.next().map(str::parse).transpose().map_err(|_| bad())?.unwrap_or(0);
        let y: i32 = parts.next().map(str::parse).transpose().map_err(|_| bad())?.unwrap_or(0);
        if parts.next().is_some() || !(1..=8192).contains(&width) || !(1..=8192).contains(&height) {
            return Err(bad());
        }
        Ok(OutputSpec { name, kind, width, height, x, y })
    }
}

pub(crate) struct Output {
    pub(crate) spec: OutputSpec,
    pub(crate) texture: wgpu::Texture,
    pub(crate) window: Option<crate::window::WindowOutput>,
    pub(crate) composites: u64,
    /// Of those, the ones drawn band by band.
    pub(crate) banded: u64,
    pub(crate) passes: u64,
    /// The part the last composite redrew (output pixels).
    pub(crate) region: [i32; 4],
    /// Whether the last composite reached the window (if any).
    pub(crate) presented: bool,
    /// The composites' own device time so far.
    pub(crate) device: Duration,
    /// Time they waited on the queue.
    pub(crate) queue: Duration,
    /// Time spent planning, encoding and submitting them.
    pub(crate) encode: Duration,
    /// Where banded composites are drawn before they are copied in (made when first needed).
    pub(crate) staging: Option<wgpu::Texture>,
}

impl Output {
    /// The output's staging image, made on first use.
    pub(crate) fn staging(&mut self, gpu: &Gpu) -> &wgpu::Texture {
        let (w, h) = (self.spec.width, self.spec.height);
        self.staging.get_or_insert_with(|| output_texture(gpu, "output staging", w, h))
    }
}

/// An output-sized image the compositor draws into and copies from and to.
pub(crate) fn output_texture(gpu: &Gpu, label: &str, width: u32, height: u32) -> wgpu::Texture {
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST
        | wgpu::TextureUsages::TEXTURE_BINDING;
    gpu.texture_2d(label, wgpu::TextureFormat::Rgba8Unorm, (width, height), usage)
}
