//! A daemon-owned EGL surface: its render target (a window surface's back buffer), its
//! buffers, its config, its declared projection, and how its depth is stored.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};

use strata_protocol::projection::{Projection, ProjectionKind};

use crate::egl_config::Config;
use crate::objects::window::Window;
use crate::render::Target;

/// The depth image format of surfaces whose config has depth (`stratad serve --depth-format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum DepthFormat {
    /// The config's `EGL_DEPTH_SIZE` decides: 16 → Depth16Unorm, 24 → Depth24Plus (with
    /// stencil Depth24PlusStencil8), 32 → Depth32Float.
    #[default]
    Config,
    /// Depth16Unorm (a config with stencil keeps Depth24PlusStencil8).
    #[value(name = "16unorm")]
    Unorm16,
    /// Depth24Plus: at least 24 bits, the backend's choice of unorm or float.
    #[value(name = "24plus")]
    Plus24,
    /// Depth32Float (with stencil Depth32FloatStencil8 where the device has it).
    #[value(name = "32float")]
    Float32,
}

/// How this daemon stores surfaces' depth: the format, and whether a surface that declares a
/// forward perspective projection gets reversed depth (`stratad serve --reversed-z`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DepthOptions {
    /// The depth image format.
    pub format: DepthFormat,
    /// Store a declared forward perspective projection's depth reversed.
    pub reversed_z: bool,
}

/// Whether the "stencil keeps its format" line was logged (once per daemon).
pub(crate) static STENCIL_FALLBACK_LOGGED: AtomicBool = AtomicBool::new(false);

impl DepthOptions {
    /// The depth image format of a surface of `config` on a device with `features`, or `None`
    /// when the config has neither depth nor stencil.
    pub fn format(self, config: Config, features: wgpu::Features) -> Option<wgpu::TextureFormat> {
        use wgpu::TextureFormat as F;
        let (depth, stencil) = (config.depth, config.stencil);
        if depth == 0 && stencil == 0 {
            return None;
        }
        let by_config = match (depth, stencil) {
            (16, 0) => F::Depth16Unorm,
            (32, 0) => F::Depth32Float,
            (_, 0) => F::Depth24Plus,
            _ => F::Depth24PlusStencil8,
        };
        if depth == 0 {
            return Some(by_config);
        }
        Some(match (self.format, stencil > 0) {
            (DepthFormat::Config, _) => by_config,
            (DepthFormat::Unorm16, false) => F::Depth16Unorm,
            (DepthFormat::Plus24, false) => F::Depth24Plus,
            (DepthFormat::Float32, false) => F::Depth32Float,
            (DepthFormat::Plus24, true) => F::Depth24PlusStencil8,
            (DepthFormat::Float32, true) if features.contains(wgpu::Features::DEPTH32FLOAT_STENCIL8) => {
                F::Depth32FloatStencil8
            }
            (DepthFormat::Unorm16 | DepthFormat::Float32, true) => {
                if !STENCIL_FALLBACK_LOGGED.swap(true, Ordering::Relaxed) {
                    tracing::info!(
                        requested = ?self.format,
                        "--depth-format cannot apply to configs with stencil (no such depth-stencil format on this \
                         device): they keep Depth24PlusStencil8"
                    );
                }
                by_config
            }
        })
    }

    /// The reversed-Z constants for a surface with `projection` in effect: the declared near
    /// and far when the option is on and the projection is a forward perspective one.
    pub fn reversed(self, projection: Option<&Projection>) -> Option<ReversedZ> {
        let p = projection?;
        (self.reversed_z && p.kind == ProjectionKind::Perspective && !p.reversed)
            .then_some(ReversedZ { near: p.near, far: p.far })
    }
}

/// A surface whose framebuffer 0 stores reversed depth: the near and far planes of its
/// declared perspective projection (far may be infinite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReversedZ {
    /// Distance to the near plane.
    pub near: f32,
    /// Distance to the far plane.
    pub far: f32,
}

impl ReversedZ {
    /// The projection the compositor is given: the declared one, reversed as stored.
    pub fn stored(self, declared: Projection) -> Projection {
        Projection { reversed: true, ..declared }
    }
}

/// A daemon-owned EGL surface: its colour and optional depth/stencil images.
pub struct Surface {
    /// The render target framebuffer 0 resolves to (the back buffer of a window surface).
    pub target: Target,
    /// A window surface's buffers, of which `target` is the back one (`None`: a pbuffer).
    pub(crate) frames: Option<Window>,
    /// The config it was made with.
    pub config: Config,
    /// Window surface (composited) rather than pbuffer.
    pub window: bool,
    /// The projection in effect for its depth (`EGL_STRATA_surface_projection`; the daemon's
    /// layout's for a window surface when it gives one), as `eglQuerySurface` reports it.
    pub projection: Option<Projection>,
    /// Reversed-Z constants when its framebuffer 0 stores reversed depth.
    pub reversed: Option<ReversedZ>,
    /// Stages of reversed-Z draws (the vertex stage with the reversed-Z epilogue, and a
    /// fragment stage reading `gl_FragCoord` as GL's depth), by program id and points variant.
    pub(crate) reversed_stages: HashMap<(u64, bool, bool), crate::objects::program::Stages>,
    /// A pbuffer's memory, held against the client's quota (a window's buffers hold theirs).
    pub(crate) _reserved: Option<strata_device::account::Reservation>,
    /// A window surface's ID in the scene (`ctl`'s, and `EGL_SURFACE_ID_STRATA`'s answer).
    pub scene_id: Option<u64>,
    /// `EGL_GL_COLORSPACE_SRGB_KHR` (`EGL_KHR_gl_colorspace`): draws store sRGB-encoded colour.
    pub srgb: bool,
}

/// Bytes of the images of one `w`×`h` buffer with depth/stencil `format`: colour and
/// depth/stencil.
pub fn surface_bytes(format: Option<wgpu::TextureFormat>, w: u32, h: u32) -> u64 {
    use wgpu::TextureFormat as F;
    let depth = match format {
        None => 0,
        Some(F::Depth16Unorm) => 2,
        Some(F::Depth32FloatStencil8) => 8,
        Some(_) => 4,
    };
    u64::from(w) * u64::from(h) * (4 + depth)
}

#[cfg(test)]
mod tests {
    use strata_protocol::projection::{Projection, ProjectionKind};

    use super::*;

    fn config(depth: i32, stencil: i32) -> Config {
        Config { id: 0, rgba: [8; 4], depth, stencil }
    }

    #[test]
    fn depth_format_overrides_configs_with_depth() {
        use wgpu::TextureFormat as F;
        let none = wgpu::Features::empty();
        let with = wgpu::Features::DEPTH32FLOAT_STENCIL8;
        let opts = |format| DepthOptions { format, reversed_z: false };
        let by_config = opts(DepthFormat::Config);
        assert_eq!(by_config.format(config(16, 0), none), Some(F::Depth16Unorm));
        assert_eq!(by_config.format(config(24, 0), none), Some(F::Depth24Plus));
        assert_eq!(by_config.format(config(24, 8), none), Some(F::Depth24PlusStencil8));
        assert_eq!(by_config.format(config(32, 0), none), Some(F::Depth32Float));
        assert_eq!(by_config.format(config(0, 0), none), None);
        assert_eq!(opts(DepthFormat::Unorm16).format(config(32, 0), none), Some(F::Depth16Unorm));
        assert_eq!(opts(DepthFormat::Plus24).format(config(16, 0), none), Some(F::Depth24Plus));
        assert_eq!(opts(DepthFormat::Float32).format(config(16, 0), none), Some(F::Depth32Float));
        // A stencil aspect is kept.
        assert_eq!(opts(DepthFormat::Float32).format(config(24, 8), with), Some(F::Depth32FloatStencil8));
        assert_eq!(opts(DepthFormat::Float32).format(config(24, 8), none), Some(F::Depth24PlusStencil8));
        assert_eq!(opts(DepthFormat::Unorm16).format(config(24, 8), with), Some(F::Depth24PlusStencil8));
        // Quota bytes follow the format: 4 colour + 2, 4 or 8 depth bytes per pixel.
        assert_eq!(surface_bytes(Some(F::Depth16Unorm), 10, 10), 600);
        assert_eq!(surface_bytes(Some(F::Depth32Float), 10, 10), 800);
        assert_eq!(surface_bytes(Some(F::Depth32FloatStencil8), 10, 10), 1200);
        assert_eq!(surface_bytes(None, 10, 10), 400);
    }

    #[test]
    fn only_forward_perspective_declarations_are_reversed() {
        let on = DepthOptions { format: DepthFormat::Config, reversed_z: true };
        let p = |kind, reversed| Projection { kind, near: 0.5, far: 20.0, reversed };
        let persp = p(ProjectionKind::Perspective, false);
        assert_eq!(on.reversed(Some(&persp)), Some(ReversedZ { near: 0.5, far: 20.0 }));
        assert_eq!(on.reversed(Some(&p(ProjectionKind::Perspective, true))), None);
        assert_eq!(on.reversed(Some(&p(ProjectionKind::Orthographic, false))), None);
        assert_eq!(on.reversed(None), None);
        assert_eq!(DepthOptions::default().reversed(Some(&persp)), None);
        assert!(ReversedZ { near: 0.5, far: 20.0 }.stored(persp).reversed);
    }
}
