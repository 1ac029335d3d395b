//! Daemon-owned EGL surfaces: their colour and depth/stencil images, the front buffer of a
//! window surface, the swap that shows a frame, and resizing a window surface in place.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};

use strata_protocol::projection::{Projection, ProjectionKind};
use strata_protocol::wire::EglHandle;
use strata_protocol::EglResult;

use super::context::MAX_TEXTURE;
use super::egl::Config;
use super::enums::*;
use super::render::{Target, COLOR_FORMAT};
use super::GlesExecutor;

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
static STENCIL_FALLBACK_LOGGED: AtomicBool = AtomicBool::new(false);

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
    /// A depth-only view of the target's depth, for the compositor.
    depth_sample: Option<wgpu::TextureView>,
    /// A window surface's front buffer: the last completed frame.
    front: Option<(Target, Option<wgpu::TextureView>)>,
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
    pub(super) reversed_stages: HashMap<(u64, bool), (wgpu::ShaderModule, Option<wgpu::ShaderModule>)>,
    /// The images' memory, held against the client's quota.
    _reserved: crate::quota::Reservation,
}

/// Bytes of the images of a `w`×`h` surface with depth/stencil `format`: colour and
/// depth/stencil, twice for a window surface's front buffer.
fn surface_bytes(format: Option<wgpu::TextureFormat>, w: u32, h: u32, window: bool) -> u64 {
    use wgpu::TextureFormat as F;
    let depth = match format {
        None => 0,
        Some(F::Depth16Unorm) => 2,
        Some(F::Depth32FloatStencil8) => 8,
        Some(_) => 4,
    };
    u64::from(w) * u64::from(h) * (4 + depth) * if window { 2 } else { 1 }
}

impl GlesExecutor {
    /// The depth/stencil format of a surface of `config` under this daemon's depth options.
    fn depth_format(&self, config: Config) -> Option<wgpu::TextureFormat> {
        self.depth.format(config, self.gpu.features)
    }

    /// One colour (+ depth) render target of a surface, cleared to transparent black as Mesa's
    /// are (opaque black without alpha, which then stays 1; depth to the far plane: 0 when
    /// `reversed`), with a depth-only view for sampling.
    fn make_target(&mut self, config: Config, w: u32, h: u32, reversed: bool) -> (Target, Option<wgpu::TextureView>) {
        let depth_format = self.depth_format(config);
        let d = &self.gpu.device;
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST;
        let size = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };
        let color = d.create_texture(&wgpu::TextureDescriptor {
            label: Some("surface colour"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: COLOR_FORMAT,
            usage,
            view_formats: &[],
        });
        let color_view = color.create_view(&Default::default());
        let mut sample = None;
        let depth = depth_format.map(|format| {
            let t = d.create_texture(&wgpu::TextureDescriptor {
                label: Some("surface depth"),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            });
            sample = Some(t.create_view(&wgpu::TextureViewDescriptor {
                aspect: wgpu::TextureAspect::DepthOnly,
                ..Default::default()
            }));
            (t.create_view(&Default::default()), format)
        });
        let uid = self.next_uid();
        let opaque = config.rgba[3] == 0;
        let target = Target { key: (uid, 0), color: Some((color, color_view)), depth, width: w, height: h, opaque };
        self.r.clear(
            &target,
            Some(([0.0, 0.0, 0.0, if target.opaque { 1.0 } else { 0.0 }], wgpu::ColorWrites::ALL)),
            target.depth.as_ref().map(|_| (if reversed { 0.0 } else { 1.0 }, true)),
            target.has_stencil().then_some((0, 0xff)),
            None,
        );
        (target, sample)
    }

    /// A new pbuffer or window surface of `width`×`height` with `projection` in effect; its
    /// handle, or the EGL error.
    pub(super) fn make_surface(
        &mut self,
        config: Config,
        width: i32,
        height: i32,
        window: bool,
        projection: Option<Projection>,
    ) -> Result<u32, i32> {
        if width < 0 || height < 0 {
            return Err(EGL_BAD_PARAMETER);
        }
        if width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
            return Err(if window { EGL_BAD_NATIVE_WINDOW } else { EGL_BAD_PARAMETER });
        }
        let (w, h) = ((width as u32).max(1), (height as u32).max(1));
        let exceeded = |_| EGL_BAD_ALLOC;
        self.account.admit(crate::quota::Kind::Surface, self.surfaces.len() as u64, 1).map_err(exceeded)?;
        let reserved =
            self.account.reserve(surface_bytes(self.depth_format(config), w, h, window)).map_err(exceeded)?;
        let reversed = if config.depth > 0 { self.depth.reversed(projection.as_ref()) } else { None };
        let (target, depth_sample) = self.make_target(config, w, h, reversed.is_some());
        // Window surfaces are double-buffered: a front buffer holds the last completed frame.
        let front = window.then(|| self.make_target(config, w, h, reversed.is_some()));
        let id = self.next_handle;
        self.next_handle += 1;
        let reversed_stages = HashMap::new();
        let s = Surface {
            target,
            depth_sample,
            front,
            config,
            window,
            projection,
            reversed,
            reversed_stages,
            _reserved: reserved,
        };
        self.surfaces.insert(id, s);
        Ok(id)
    }

    /// `eglSwapBuffers`: the back buffer becomes the front (and is shown), the old front
    /// becomes the next back buffer.
    pub(super) fn swap(&mut self, surface: u32) -> Result<(), i32> {
        self.flush();
        let s = self.surfaces.get_mut(&surface).ok_or(EGL_BAD_SURFACE)?;
        let Some((front, front_depth)) = &mut s.front else { return Ok(()) };
        std::mem::swap(&mut s.target, front);
        std::mem::swap(&mut s.depth_sample, front_depth);
        if let (Some(scene), Some((_, view))) = (&self.scene, &front.color) {
            scene.0.present(scene.1, surface, view.clone(), front_depth.clone(), front.opaque);
            let start = std::time::Instant::now();
            scene.0.throttle(scene.1, surface);
            self.r.lane.add_swap_wait(start.elapsed());
        }
        // At most one frame of this client on the queue: whatever is submitted after it
        // never waits behind a backlog of its frames.
        self.r.lane.frame_boundary(&self.gpu);
        Ok(())
    }

    /// `strataResizeSurface`: a window surface gets new back and front images of
    /// `width`×`height` (cleared, as new surfaces are), keeping its handle, which is its scene
    /// id, placement, depth layer, normal, swap interval and pacing; the scene shows the last
    /// frame until the next swap presents one of the new size. A size the daemon's layout fixes
    /// stays as it is.
    #[allow(non_snake_case)]
    pub(super) fn strataResizeSurface(
        &mut self,
        display: EglHandle,
        surface: EglHandle,
        width: i32,
        height: i32,
    ) -> EglResult<()> {
        self.check_display(display)?;
        let s = self.surfaces.get(&surface).ok_or(EGL_BAD_SURFACE)?;
        if !s.window {
            return Err(EGL_BAD_SURFACE);
        }
        if width <= 0 || height <= 0 || width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
            return Err(EGL_BAD_NATIVE_WINDOW);
        }
        let fixed = self.layout.as_ref().is_some_and(|l| l.width.is_some() && l.height.is_some());
        let (w, h) = (width as u32, height as u32);
        if fixed || (s.target.width, s.target.height) == (w, h) {
            return Ok(());
        }
        let (config, reversed) = (s.config, s.reversed.is_some());
        // The new images are reserved before the old ones are given back, which they are once
        // replaced.
        let bytes = surface_bytes(self.depth_format(config), w, h, true);
        let reserved = self.account.reserve(bytes).map_err(|_| EGL_BAD_ALLOC)?;
        // Work recorded for the old images goes first.
        self.flush();
        let (target, depth_sample) = self.make_target(config, w, h, reversed);
        let front = self.make_target(config, w, h, reversed);
        let s = self.surfaces.get_mut(&surface).ok_or(EGL_BAD_SURFACE)?;
        s.target = target;
        s.depth_sample = depth_sample;
        s.front = Some(front);
        s._reserved = reserved;
        if let Some((scene, client, _)) = &self.scene {
            scene.resize(*client, surface, width, height);
        }
        Ok(())
    }
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
        assert_eq!(surface_bytes(Some(F::Depth16Unorm), 10, 10, false), 600);
        assert_eq!(surface_bytes(Some(F::Depth32Float), 10, 10, true), 1600);
        assert_eq!(surface_bytes(Some(F::Depth32FloatStencil8), 10, 10, false), 1200);
        assert_eq!(surface_bytes(None, 10, 10, false), 400);
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
