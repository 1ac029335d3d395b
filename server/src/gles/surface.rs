//! Daemon-owned EGL surfaces: their colour and depth/stencil images, the front buffer of a
//! window surface, the swap that shows a frame, and resizing a window surface in place.

use strata_protocol::wire::EglHandle;
use strata_protocol::EglResult;

use super::context::MAX_TEXTURE;
use super::egl::Config;
use super::enums::*;
use super::render::{Target, COLOR_FORMAT};
use super::GlesExecutor;

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
    pub projection: Option<strata_protocol::projection::Projection>,
    /// The images' memory, held against the client's quota.
    _reserved: crate::quota::Reservation,
}

/// Bytes of the images of a `w`×`h` surface of `config`: colour and depth/stencil, twice for a
/// window surface's front buffer.
fn surface_bytes(config: Config, w: u32, h: u32, window: bool) -> u64 {
    let depth = match (config.depth, config.stencil) {
        (0, 0) => 0,
        (16, 0) => 2,
        _ => 4,
    };
    u64::from(w) * u64::from(h) * (4 + depth) * if window { 2 } else { 1 }
}

impl GlesExecutor {
    /// One colour (+ depth) render target of a surface, cleared to transparent black as Mesa's
    /// are, with a depth-only view for sampling.
    fn make_target(&mut self, config: Config, w: u32, h: u32) -> (Target, Option<wgpu::TextureView>) {
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
        let depth = (config.depth > 0 || config.stencil > 0).then(|| {
            let format = match (config.depth, config.stencil) {
                (16, 0) => wgpu::TextureFormat::Depth16Unorm,
                (_, 0) => wgpu::TextureFormat::Depth24Plus,
                _ => wgpu::TextureFormat::Depth24PlusStencil8,
            };
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
        let target =
            Target { key: (uid, 0), color: Some((color, color_view)), depth, width: w, height: h, opaque: false };
        self.r.clear(
            &target,
            Some(([0.0; 4], wgpu::ColorWrites::ALL)),
            target.depth.as_ref().map(|_| (1.0, true)),
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
        projection: Option<strata_protocol::projection::Projection>,
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
        let reserved = self.account.reserve(surface_bytes(config, w, h, window)).map_err(exceeded)?;
        let (target, depth_sample) = self.make_target(config, w, h);
        // Window surfaces are double-buffered: a front buffer holds the last completed frame.
        let front = window.then(|| self.make_target(config, w, h));
        let id = self.next_handle;
        self.next_handle += 1;
        self.surfaces
            .insert(id, Surface { target, depth_sample, front, config, window, projection, _reserved: reserved });
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
            scene.0.present(scene.1, surface, view.clone(), front_depth.clone());
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
        let config = s.config;
        // The new images are reserved before the old ones are given back, which they are once
        // replaced.
        let reserved = self.account.reserve(surface_bytes(config, w, h, true)).map_err(|_| EGL_BAD_ALLOC)?;
        // Work recorded for the old images goes first.
        self.flush();
        let (target, depth_sample) = self.make_target(config, w, h);
        let front = self.make_target(config, w, h);
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
