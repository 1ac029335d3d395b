//! Daemon-owned EGL surfaces: their colour and depth/stencil images, the front buffer of a
//! window surface, the swap that shows a frame, and resizing a window surface in place.

use std::collections::HashMap;

use strata_protocol::projection::Projection;
use strata_protocol::wire::EglHandle;
use strata_protocol::EglResult;

use crate::egl_config::Config;
use crate::enums::*;
use crate::limits::MAX_TEXTURE;
use strata_scene::transfer::{self, CopyPath, Transfer};
use strata_scene::{Acquired, Producer, Swapped, Views};

use crate::render::Target;

use crate::formats::COLOR_FORMAT;
use crate::objects::surface::surface_bytes;
use crate::objects::surface::Surface;
use crate::objects::window::{Buffer, Window};
use crate::GlesExecutor;

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
            depth_image: depth_tex.clone().map(|t| (t, 0, 0)),
            width: w,
            height: h,
            absent,
            samples: 1,
        };
        self.r.clear(
            &target,
            Some((target.stored([0.0; 4]), wgpu::ColorWrites::ALL, None)),
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
