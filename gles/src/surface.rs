//! Daemon-owned EGL surfaces: their colour and depth/stencil images, the front buffer of a
//! window surface, the swap that shows a frame, and resizing a window surface in place.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};

use strata_protocol::projection::{Projection, ProjectionKind};
use strata_protocol::wire::EglHandle;
use strata_protocol::EglResult;

use super::context::MAX_TEXTURE;
use super::egl_config::Config;
use super::enums::*;
use strata_scene::transfer::{self, CopyPath, Transfer};
use strata_scene::{Acquired, Producer, Swapped, Views};

use super::render::{Target, COLOR_FORMAT};
use super::window::{Buffer, Window};
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
    /// A window surface's buffers, of which `target` is the back one (`None`: a pbuffer).
    pub(super) frames: Option<Window>,
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
    pub(super) reversed_stages: HashMap<(u64, bool, bool), super::stages::Stages>,
    /// A pbuffer's memory, held against the client's quota (a window's buffers hold theirs).
    _reserved: Option<strata_device::account::Reservation>,
    /// A window surface's ID in the scene (`ctl`'s, and `EGL_SURFACE_ID_STRATA`'s answer).
    pub scene_id: Option<u64>,
    /// `EGL_GL_COLORSPACE_SRGB_KHR` (`EGL_KHR_gl_colorspace`): draws store sRGB-encoded colour.
    pub srgb: bool,
}

/// Bytes of the images of one `w`×`h` buffer with depth/stencil `format`: colour and
/// depth/stencil.
fn surface_bytes(format: Option<wgpu::TextureFormat>, w: u32, h: u32) -> u64 {
    use wgpu::TextureFormat as F;
    let depth = match format {
        None => 0,
        Some(F::Depth16Unorm) => 2,
        Some(F::Depth32FloatStencil8) => 8,
        Some(_) => 4,
    };
    u64::from(w) * u64::from(h) * (4 + depth)
}

/// Most buffers a window surface has: the back buffer, the newest frame, and one whose work
/// is still running (so that a swap never waits for its own frame to complete), and at swap
/// interval 0 also one a composite still reads, so that such a swap never waits for the
/// compositor.
fn most_buffers(interval: i32) -> usize {
    if interval == 0 {
        4
    } else {
        3
    }
}

impl GlesExecutor {
    /// The depth/stencil format of a surface of `config` under this daemon's depth options.
    fn depth_format(&self, config: Config) -> Option<wgpu::TextureFormat> {
        self.depth.format(config, self.gpu.features)
    }

    /// One colour (+ depth) render target of a surface, in `images` when given (else new
    /// ones), cleared to transparent black as Mesa's are (opaque black without alpha, which
    /// then stays 1; depth to the far plane: 0 when `reversed`); with its depth texture.
    /// An `srgb` surface draws through an sRGB view of its colour image, which everything else
    /// (reads, copies, the compositor) sees as the encoded bytes.
    #[allow(clippy::too_many_arguments)]
    fn make_target(
        &mut self,
        config: Config,
        w: u32,
        h: u32,
        reversed: bool,
        srgb: bool,
        images: Option<(wgpu::Texture, Option<wgpu::Texture>)>,
    ) -> (Target, Option<wgpu::Texture>) {
        let depth_format = self.depth_format(config);
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST;
        let new = |label, format, usage| {
            let views: &[wgpu::TextureFormat] = if format == COLOR_FORMAT { &strata_device::SRGB_VIEW } else { &[] };
            let desc = strata_device::descriptor_2d(label, format, (w, h), usage);
            self.gpu.device.create_texture(&wgpu::TextureDescriptor { view_formats: views, ..desc })
        };
        let (color, depth_tex) = match images {
            Some(images) => images,
            None => {
                let depth_usage = wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC;
                (new("surface colour", COLOR_FORMAT, usage), depth_format.map(|f| new("surface depth", f, depth_usage)))
            }
        };
        let color_view = color.create_view(&wgpu::TextureViewDescriptor {
            format: srgb.then(|| color.format().add_srgb_suffix()),
            ..Default::default()
        });
        let depth = depth_tex.as_ref().map(|t| (t.create_view(&Default::default()), t.format()));
        let uid = self.next_uid();
        let absent = if config.rgba[3] == 0 { wgpu::ColorWrites::ALPHA } else { wgpu::ColorWrites::empty() };
        let target = Target {
            key: (uid, 0),
            color: Some((color, color_view)),
            color_at: Default::default(),
            more: Vec::new(),
            slices: Vec::new(),
            srgb,
            depth,
            depth_image: depth_tex.clone().map(|t| (t, 0)),
            width: w,
            height: h,
            absent,
        };
        self.r.clear(
            &target,
            Some((target.stored([0.0; 4]), wgpu::ColorWrites::ALL)),
            target.depth.as_ref().map(|_| (if reversed { 0.0 } else { 1.0 }, true)),
            target.has_stencil().then_some((0, 0xff)),
            None,
        );
        (target, depth_tex)
    }

    /// How window surfaces of `config` hand their frames to the compositor.
    fn transfer_for(&self, config: Config) -> Transfer {
        let comp = self.scene.as_ref().and_then(|(scene, _, _)| scene.compositor());
        transfer::transfer(&self.gpu, comp.as_ref(), self.depth_format(config), self.frame_transfer)
    }

    /// One buffer of a `w`×`h` window surface, reserved against the quota, and the
    /// compositor's views of it.
    #[allow(clippy::too_many_arguments)]
    fn make_buffer(
        &mut self,
        config: Config,
        w: u32,
        h: u32,
        reversed: bool,
        srgb: bool,
        transfer: &mut Transfer,
    ) -> Result<(Buffer, Views), i32> {
        let depth_format = self.depth_format(config);
        let extra = if *transfer == Transfer::Copy { CopyPath::bytes((w, h), depth_format.is_some()) } else { 0 };
        let reserved = self.account.reserve(surface_bytes(depth_format, w, h) + extra).map_err(|_| EGL_BAD_ALLOC)?;
        let comp = self.scene.as_ref().and_then(|(scene, _, _)| scene.compositor());
        if let (Transfer::Export, Some(comp)) = (*transfer, &comp) {
            let pick = self.scene.as_ref().and_then(|(scene, _, _)| scene.pick_device());
            match transfer::shared_images(&self.gpu, comp, pick.as_deref(), (w, h), depth_format) {
                Ok((images, views)) => {
                    let (target, _) = self.make_target(config, w, h, reversed, srgb, Some(images));
                    return Ok((Buffer { target, copy: None, _reserved: reserved, swapped_at: None }, views));
                }
                Err(e) => {
                    tracing::warn!("sharing a window surface's images failed ({e}); its frames are copied instead");
                    *transfer = Transfer::Copy;
                    return self.make_buffer(config, w, h, reversed, srgb, transfer);
                }
            }
        }
        let (target, depth_tex) = self.make_target(config, w, h, reversed, srgb, None);
        let depth_view = depth_tex.as_ref().map(transfer::depth_view);
        match (*transfer, comp) {
            (Transfer::Copy, Some(comp)) => {
                let (path, views) = CopyPath::new(&self.gpu, &comp, (w, h), depth_view.as_ref());
                Ok((
                    Buffer { target, copy: Some(std::sync::Arc::new(path)), _reserved: reserved, swapped_at: None },
                    views,
                ))
            }
            _ => {
                // The compositor reads the stored bytes (an sRGB surface's encoded colour).
                let color =
                    target.color.as_ref().map(|(t, _)| t.create_view(&Default::default())).ok_or(EGL_BAD_ALLOC)?;
                Ok((
                    Buffer { target, copy: None, _reserved: reserved, swapped_at: None },
                    Views::shown(color, depth_view),
                ))
            }
        }
    }

    /// A window surface's first two buffers (the first is the back buffer) and their views.
    fn make_window(
        &mut self,
        config: Config,
        (w, h): (u32, u32),
        reversed: bool,
        srgb: bool,
    ) -> Result<(Window, Vec<Views>), i32> {
        let mut transfer = self.transfer_for(config);
        let mut buffers = Vec::new();
        let mut views = Vec::new();
        for _ in 0..2 {
            let (b, v) = self.make_buffer(config, w, h, reversed, srgb, &mut transfer)?;
            buffers.push(b);
            views.push(v);
        }
        Ok((Window { buffers, back: 0, transfer, swaps: 0 }, views))
    }

    /// The scene's side of window surface `id`'s frames (`None`: no compositor).
    fn producer(&self, id: u32) -> Option<Producer> {
        self.scene.as_ref().map(|(scene, client, _)| scene.producer(*client, id))
    }

    /// Shows surface `id`'s buffers to the scene (the back one as such).
    pub(super) fn register_buffers(&self, id: u32, views: Vec<Views>) {
        if let Some(producer) = self.producer(id) {
            let back = self.surfaces.get(&id).and_then(|s| s.frames.as_ref()).map_or(0, |w| w.back);
            for (i, v) in views.into_iter().enumerate() {
                producer.add_buffer(v, i == back);
            }
        }
    }

    /// A new pbuffer or window surface of `width`×`height` with `projection` in effect; its
    /// handle, or the EGL error, and for a window surface the compositor's views of its
    /// buffers (for [`GlesExecutor::register_buffers`]).
    pub(super) fn make_surface(
        &mut self,
        config: Config,
        width: i32,
        height: i32,
        window: bool,
        projection: Option<Projection>,
        srgb: bool,
    ) -> Result<(u32, Vec<Views>), i32> {
        if width < 0 || height < 0 {
            return Err(EGL_BAD_PARAMETER);
        }
        if width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
            return Err(if window { EGL_BAD_NATIVE_WINDOW } else { EGL_BAD_PARAMETER });
        }
        let (w, h) = ((width as u32).max(1), (height as u32).max(1));
        self.account
            .admit(strata_device::account::Kind::Surface, self.surfaces.len() as u64, 1)
            .map_err(|_| EGL_BAD_ALLOC)?;
        let reversed = if config.depth > 0 { self.depth.reversed(projection.as_ref()) } else { None };
        let (target, frames, views, reserved) = if window {
            let (win, views) = self.make_window(config, (w, h), reversed.is_some(), srgb)?;
            (win.buffers[0].target.clone(), Some(win), views, None)
        } else {
            let bytes = surface_bytes(self.depth_format(config), w, h);
            let reserved = self.account.reserve(bytes).map_err(|_| EGL_BAD_ALLOC)?;
            let (target, _) = self.make_target(config, w, h, reversed.is_some(), srgb, None);
            (target, None, Vec::new(), Some(reserved))
        };
        let id = self.next_handle;
        self.next_handle += 1;
        let s = Surface {
            target,
            frames,
            config,
            window,
            projection,
            reversed,
            reversed_stages: HashMap::new(),
            _reserved: reserved,
            scene_id: None,
            srgb,
        };
        self.surfaces.insert(id, s);
        Ok((id, views))
    }

    /// `eglSwapBuffers`: the back buffer's frame is published once its work completes on this
    /// client's device (the compositor then takes it), and a free buffer becomes the back one;
    /// `damage`: what changed since the previous frame (`EGL_KHR_swap_buffers_with_damage`,
    /// image GL coordinates; `None`: all of it).
    pub(super) fn swap(&mut self, surface: u32, damage: Option<Vec<[i32; 4]>>) -> Result<(), i32> {
        self.r.flush();
        if !self.surfaces.get(&surface).ok_or(EGL_BAD_SURFACE)?.window {
            return Ok(());
        }
        let Some(producer) = self.producer(surface) else {
            // No compositor: the two buffers take turns.
            let s = self.surfaces.get_mut(&surface).ok_or(EGL_BAD_SURFACE)?;
            if let Some(win) = &mut s.frames {
                win.swapped(win.back);
                win.back = (win.back + 1) % win.buffers.len();
                s.target = win.buffers[win.back].target.clone();
            }
            return Ok(());
        };
        let s = self.surfaces.get_mut(&surface).ok_or(EGL_BAD_SURFACE)?;
        let Some(win) = &mut s.frames else { return Ok(()) };
        let back = win.back;
        win.swapped(back);
        let opaque = s.target.opaque();
        let buffer = &win.buffers[back];
        let copy = buffer.copy.clone().zip(buffer.target.color.as_ref().map(|(t, _)| t));
        let frame = Swapped { buffer: back, opaque, damage, copy };
        producer.queue(&self.gpu, &self.r.lane, &mut self.waiter, frame);
        let next = self.next_back(&producer, surface)?;
        if let Some(s) = self.surfaces.get_mut(&surface) {
            if let Some(win) = &mut s.frames {
                win.back = next;
                s.target = win.buffers[next].target.clone();
            }
        }
        let start = std::time::Instant::now();
        producer.throttle();
        self.r.lane.add_swap_wait(start.elapsed());
        // At most one frame of this client in flight on its device.
        self.r.lane.frame_boundary(&self.gpu.device);
        Ok(())
    }

    /// The buffer surface `surface` draws its next frame into: a free one, a new one while
    /// the surface has fewer than its swap interval needs, else the first to become free.
    fn next_back(&mut self, producer: &Producer, surface: u32) -> Result<usize, i32> {
        let most = most_buffers(producer.interval());
        match producer.dequeue(most) {
            Acquired::Buffer(i) => Ok(i),
            Acquired::Grow => {
                let s = self.surfaces.get(&surface).ok_or(EGL_BAD_SURFACE)?;
                let (config, w, h, reversed) = (s.config, s.target.width, s.target.height, s.reversed.is_some());
                let srgb = s.srgb;
                let mut transfer = s.frames.as_ref().map_or(Transfer::Same, |f| f.transfer);
                let (buffer, views) = self.make_buffer(config, w, h, reversed, srgb, &mut transfer)?;
                let i = producer.add_buffer(views, true).ok_or(EGL_BAD_SURFACE)?;
                let win = self.surfaces.get_mut(&surface).and_then(|s| s.frames.as_mut()).ok_or(EGL_BAD_SURFACE)?;
                win.transfer = transfer;
                win.buffers.push(buffer);
                debug_assert_eq!(win.buffers.len(), i + 1);
                Ok(i)
            }
            Acquired::TimedOut => {
                tracing::warn!(
                    surface,
                    "no buffer became free in time (a wedged compositor?); drawing into the one shown"
                );
                Ok(producer.take_any().ok_or(EGL_BAD_SURFACE)?)
            }
            Acquired::Gone => Err(EGL_BAD_SURFACE),
        }
    }

    /// `strataResizeSurface`: a window surface gets new buffers of `width`×`height` (cleared,
    /// as new surfaces are), keeping its handle, which is its scene id, placement, depth layer,
    /// normal, swap interval and pacing; the scene shows the last frame until the next swap
    /// presents one of the new size. A size the daemon's layout fixes stays as it is.
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
        let fixed = self.placement.is_some_and(|p| p.size.is_some());
        let (w, h) = (width as u32, height as u32);
        if fixed || (s.target.width, s.target.height) == (w, h) {
            return Ok(());
        }
        let (config, reversed, srgb) = (s.config, s.reversed.is_some(), s.srgb);
        // Work recorded for the old images goes first. The new buffers are reserved before
        // the old ones are given back, which they are once replaced.
        self.r.flush();
        let (win, views) = self.make_window(config, (w, h), reversed, srgb)?;
        let s = self.surfaces.get_mut(&surface).ok_or(EGL_BAD_SURFACE)?;
        s.target = win.buffers[0].target.clone();
        s.frames = Some(win);
        if let Some(producer) = self.producer(surface) {
            producer.replace_buffers(width, height, views);
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
