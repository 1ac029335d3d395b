//! A window output: an output's composited image shown in a desktop window (winit, X11).
//! The window's event loop runs on its own thread; the compositor thread presents into the
//! window's surface after each composite with a one-pass copy of the output image.

use std::sync::mpsc;
use std::sync::Arc;

use tracing::{info, warn};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::platform::x11::EventLoopBuilderExtX11;
use winit::window::{Window, WindowId};

use strata_protocol::input::InputRequest;

use strata_device::Gpu;

/// Why a window output could not be opened.
#[derive(Debug, thiserror::Error)]
pub enum WindowError {
    /// No display server answered.
    #[error("no display for a window output ({0}); use a headless output (--output NAME=WxH)")]
    NoDisplay(String),
    /// The window or its GPU surface could not be created.
    #[error("creating the output window failed: {0}")]
    Create(String),
}

/// Whether a display server is configured for this process (X11).
pub fn display_available() -> bool {
    std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty())
}

struct App {
    title: String,
    size: (u32, u32),
    tx: mpsc::Sender<Result<Arc<Window>, String>>,
    window: Option<Arc<Window>>,
    /// Where the window's pointer, touch and key events go, as actions on its output.
    input: Option<mpsc::Sender<InputRequest>>,
    pointer: crate::pointer::PointerState,
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let attrs = Window::default_attributes()
            .with_title(self.title.clone())
            .with_inner_size(winit::dpi::PhysicalSize::new(self.size.0, self.size.1))
            .with_resizable(false);
        match event_loop.create_window(attrs) {
            Ok(w) => {
                let w = Arc::new(w);
                self.window = Some(w.clone());
                let _ = self.tx.send(Ok(w));
            }
            Err(e) => {
                let _ = self.tx.send(Err(e.to_string()));
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, _: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        if let Some(tx) = &self.input {
            for action in self.pointer.actions(&event) {
                let _ = tx.send(InputRequest { output: self.title.clone(), action });
            }
        }
        if let WindowEvent::CloseRequested = event {
            // The output keeps compositing; only the daemon decides when it ends.
            info!(window = %self.title, "close requested; the output stays (stop stratad to close it)");
        }
    }
}

/// A window showing one output.
pub struct WindowOutput {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

/// The copy into the window (`shaders/blit.wgsl`).
const BLIT: &str = include_str!("../../shaders/blit.wgsl");

impl WindowOutput {
    /// Opens a `width`×`height` window titled `title` (the output's name) on the display in
    /// `$DISPLAY`; its pointer, touch and key events go to `input` as actions on that output.
    pub fn open(
        gpu: &Gpu,
        title: &str,
        width: u32,
        height: u32,
        input: Option<mpsc::Sender<InputRequest>>,
    ) -> Result<WindowOutput, WindowError> {
        if !display_available() {
            return Err(WindowError::NoDisplay("DISPLAY is not set".into()));
        }
        let (tx, rx) = mpsc::channel();
        let app_title = title.to_string();
        std::thread::Builder::new()
            .name(format!("window {title}"))
            .spawn(move || {
                let event_loop = match EventLoop::builder().with_any_thread(true).build() {
                    Ok(l) => l,
                    Err(e) => {
                        let _ = tx.send(Err(e.to_string()));
                        return;
                    }
                };
                let mut app = App {
                    title: app_title,
                    size: (width, height),
                    tx,
                    window: None,
                    input,
                    pointer: Default::default(),
                };
                if let Err(e) = event_loop.run_app(&mut app) {
                    warn!("the output window's event loop ended: {e}");
                }
            })
            .map_err(|e| WindowError::Create(e.to_string()))?;
        let window = rx
            .recv_timeout(std::time::Duration::from_secs(10))
            .map_err(|_| WindowError::NoDisplay("the window system did not answer".into()))?
            .map_err(WindowError::NoDisplay)?;
        let surface = gpu.instance.create_surface(window.clone()).map_err(|e| WindowError::Create(e.to_string()))?;
        let caps = surface.get_capabilities(&gpu.adapter);
        // A UNORM format, so the composited values reach the screen unchanged.
        let format = [wgpu::TextureFormat::Bgra8Unorm, wgpu::TextureFormat::Rgba8Unorm]
            .into_iter()
            .find(|f| caps.formats.contains(f))
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| WindowError::Create("the window's surface supports no format".into()))?;
        let present_mode = if caps.present_modes.contains(&wgpu::PresentMode::Mailbox) {
            wgpu::PresentMode::Mailbox
        } else {
            wgpu::PresentMode::Fifo
        };
        let mut config = surface
            .get_default_config(&gpu.adapter, width, height)
            .ok_or_else(|| WindowError::Create("the adapter cannot present to this window".into()))?;
        config.format = format;
        config.present_mode = present_mode;
        surface.configure(&gpu.device, &config);
        let (layout, pipeline) = gpu.pipeline(
            "window blit",
            wgpu::ShaderSource::Wgsl(BLIT.into()),
            &[strata_device::texture_entry(0, strata_device::UNFILTERED)],
            &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
            None,
            strata_device::VertexInput::None,
        );
        info!(window = title, width, height, ?format, ?present_mode, "window output open");
        Ok(WindowOutput { window, surface, config, layout, pipeline })
    }

    /// Shows `image` (the output's texture, same size) in the window.
    pub fn present(&mut self, gpu: &Gpu, image: &wgpu::Texture) {
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f) | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&gpu.device, &self.config);
                return;
            }
            _ => return,
        };
        let src = image.create_view(&Default::default());
        let bind = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("window blit"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&src) }],
        });
        let dst = frame.texture.create_view(&Default::default());
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("window blit"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &dst,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            rp.set_pipeline(&self.pipeline);
            rp.set_bind_group(0, &bind, &[]);
            rp.draw(0..3, 0..1);
        }
        gpu.submit(&gpu.lane, vec![enc.finish()]);
        self.window.pre_present_notify();
        gpu.present(frame);
    }
}
