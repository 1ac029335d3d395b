//! GL and EGL state of one client, and the dispatch of every command onto it.

use std::collections::HashMap;
use std::sync::Arc;

use strata_protocol::{ActiveVariable, Bytes, Command, Reply};
use tracing::warn;

use super::egl::{self, Config};
use super::enums::*;
use super::glsl::{self, Scalar, Stage, Ty};
use super::objects::*;
use super::render::{DrawSpec, RasterState, Renderer, Source, Target, VertexInput, COLOR_FORMAT};
use crate::executor::{ExecError, Executor};
use crate::gpu::Gpu;

const MAX_ATTRIBS: usize = 16;
const MAX_UNITS: usize = 16;
const MAX_TEXTURE: u32 = 8192;

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
}

#[derive(Clone)]
struct Attrib {
    enabled: bool,
    size: i32,
    ty: u32,
    normalized: bool,
    stride: i32,
    offset: u64,
    buffer: u32,
    current: [f32; 4],
    /// A client-side array's bytes for the next draw (`buffer` is 0).
    client: Option<Vec<u8>>,
}

/// Where a draw's indices come from.
enum Indices {
    /// The bound element array buffer, at a byte offset.
    Buffer(u32, u64),
    /// A client-side index array sent with the draw.
    Client(u32, Vec<u8>),
}

impl Default for Attrib {
    fn default() -> Self {
        Attrib {
            enabled: false,
            size: 4,
            ty: FLOAT,
            normalized: false,
            stride: 0,
            offset: 0,
            buffer: 0,
            current: [0.0, 0.0, 0.0, 1.0],
            client: None,
        }
    }
}

#[derive(Clone, Copy)]
struct StencilFace {
    func: u32,
    reference: i32,
    mask: u32,
    write: u32,
    fail: u32,
    zfail: u32,
    zpass: u32,
}

impl Default for StencilFace {
    fn default() -> Self {
        StencilFace {
            func: ALWAYS,
            reference: 0,
            mask: u32::MAX,
            write: u32::MAX,
            fail: KEEP,
            zfail: KEEP,
            zpass: KEEP,
        }
    }
}

/// One GL context's state.
struct Context {
    config: Config,
    error: u32,
    buffers: HashMap<u32, Buffer>,
    textures: HashMap<u32, Texture>,
    renderbuffers: HashMap<u32, Renderbuffer>,
    framebuffers: HashMap<u32, Framebuffer>,
    shaders: HashMap<u32, ShaderObj>,
    programs: HashMap<u32, Program>,
    array_buffer: u32,
    element_buffer: u32,
    active_unit: usize,
    units: [[u32; 2]; MAX_UNITS],
    program: u32,
    framebuffer: u32,
    renderbuffer: u32,
    attribs: Vec<Attrib>,
    viewport: [i32; 4],
    scissor: [i32; 4],
    made_current: bool,
    cull: bool,
    blend: bool,
    depth_test: bool,
    scissor_test: bool,
    stencil_test: bool,
    polygon_offset_fill: bool,
    dither: bool,
    sample_coverage: bool,
    alpha_to_coverage: bool,
    depth_func: u32,
    depth_mask: bool,
    depth_range: [f32; 2],
    cull_face: u32,
    front_face: u32,
    blend_func: [u32; 4],
    blend_eq: [u32; 2],
    blend_color: [f32; 4],
    color_mask: [bool; 4],
    clear_color: [f32; 4],
    clear_depth: f32,
    clear_stencil: i32,
    stencil: [StencilFace; 2],
    polygon_offset: [f32; 2],
    line_width: f32,
    unpack_alignment: i32,
    pack_alignment: i32,
    mipmap_hint: u32,
}

impl Context {
    fn new(config: Config) -> Self {
        Context {
            config,
            error: NO_ERROR,
            buffers: HashMap::new(),
            textures: HashMap::new(),
            renderbuffers: HashMap::new(),
            framebuffers: HashMap::new(),
            shaders: HashMap::new(),
            programs: HashMap::new(),
            array_buffer: 0,
            element_buffer: 0,
            active_unit: 0,
            units: [[0; 2]; MAX_UNITS],
            program: 0,
            framebuffer: 0,
            renderbuffer: 0,
            attribs: vec![Attrib::default(); MAX_ATTRIBS],
            viewport: [0; 4],
            scissor: [0; 4],
            made_current: false,
            cull: false,
            blend: false,
            depth_test: false,
            scissor_test: false,
            stencil_test: false,
            polygon_offset_fill: false,
            dither: true,
            sample_coverage: false,
            alpha_to_coverage: false,
            depth_func: LESS,
            depth_mask: true,
            depth_range: [0.0, 1.0],
            cull_face: BACK,
            front_face: CCW,
            blend_func: [ONE, ZERO, ONE, ZERO],
            blend_eq: [FUNC_ADD, FUNC_ADD],
            blend_color: [0.0; 4],
            color_mask: [true; 4],
            clear_color: [0.0; 4],
            clear_depth: 1.0,
            clear_stencil: 0,
            stencil: [StencilFace::default(); 2],
            polygon_offset: [0.0; 2],
            line_width: 1.0,
            unpack_alignment: 4,
            pack_alignment: 4,
            mipmap_hint: DONT_CARE,
        }
    }

    fn err(&mut self, e: u32) {
        if self.error == NO_ERROR {
            self.error = e;
        }
    }

    fn cap(&mut self, cap: u32) -> Option<&mut bool> {
        Some(match cap {
            CULL_FACE => &mut self.cull,
            BLEND => &mut self.blend,
            DEPTH_TEST => &mut self.depth_test,
            SCISSOR_TEST => &mut self.scissor_test,
            STENCIL_TEST => &mut self.stencil_test,
            POLYGON_OFFSET_FILL => &mut self.polygon_offset_fill,
            DITHER => &mut self.dither,
            SAMPLE_COVERAGE => &mut self.sample_coverage,
            SAMPLE_ALPHA_TO_COVERAGE => &mut self.alpha_to_coverage,
            _ => return None,
        })
    }

    fn texture_slot(target: u32) -> Option<usize> {
        match target {
            TEXTURE_2D => Some(0),
            TEXTURE_CUBE_MAP => Some(1),
            _ => None,
        }
    }

    fn bound_texture(&self, target: u32) -> Option<u32> {
        Self::texture_slot(target).map(|s| self.units[self.active_unit][s])
    }

    fn buffer_binding(&self, target: u32) -> Option<u32> {
        match target {
            ARRAY_BUFFER => Some(self.array_buffer),
            ELEMENT_ARRAY_BUFFER => Some(self.element_buffer),
            _ => None,
        }
    }
}

/// Runs one client's commands on the shared GPU.
pub struct GlesExecutor {
    gpu: Arc<Gpu>,
    r: Renderer,
    initialized: bool,
    surfaces: HashMap<u32, Surface>,
    contexts: HashMap<u32, Context>,
    next_handle: u32,
    current: Option<(u32, u32)>,
    uid: u64,
    /// Where window surfaces are shown: the scene, this client's id and name.
    scene: Option<(Arc<crate::scene::Scene>, u64, String)>,
    /// The daemon's layout entry for this client: overrides where its windows go.
    layout: Option<crate::layout::LayoutEntry>,
}

impl Drop for GlesExecutor {
    fn drop(&mut self) {
        // A client that leaves, even mid-frame, disappears from the next composite.
        if let Some((scene, client, _)) = &self.scene {
            scene.remove(*client, None);
        }
    }
}

fn valid_func(f: u32) -> bool {
    (NEVER..=ALWAYS).contains(&f)
}

fn compare(f: u32) -> wgpu::CompareFunction {
    match f {
        NEVER => wgpu::CompareFunction::Never,
        LESS => wgpu::CompareFunction::Less,
        EQUAL => wgpu::CompareFunction::Equal,
        LEQUAL => wgpu::CompareFunction::LessEqual,
        GREATER => wgpu::CompareFunction::Greater,
        NOTEQUAL => wgpu::CompareFunction::NotEqual,
        GEQUAL => wgpu::CompareFunction::GreaterEqual,
        _ => wgpu::CompareFunction::Always,
    }
}

fn valid_stencil_op(op: u32) -> bool {
    matches!(op, ZERO | KEEP | REPLACE | INCR | DECR | INVERT | INCR_WRAP | DECR_WRAP)
}

fn stencil_op(op: u32) -> wgpu::StencilOperation {
    match op {
        ZERO => wgpu::StencilOperation::Zero,
        REPLACE => wgpu::StencilOperation::Replace,
        INCR => wgpu::StencilOperation::IncrementClamp,
        DECR => wgpu::StencilOperation::DecrementClamp,
        INVERT => wgpu::StencilOperation::Invert,
        INCR_WRAP => wgpu::StencilOperation::IncrementWrap,
        DECR_WRAP => wgpu::StencilOperation::DecrementWrap,
        _ => wgpu::StencilOperation::Keep,
    }
}

fn blend_factor(f: u32) -> Option<wgpu::BlendFactor> {
    use wgpu::BlendFactor as B;
    Some(match f {
        ZERO => B::Zero,
        ONE => B::One,
        SRC_COLOR => B::Src,
        ONE_MINUS_SRC_COLOR => B::OneMinusSrc,
        SRC_ALPHA => B::SrcAlpha,
        ONE_MINUS_SRC_ALPHA => B::OneMinusSrcAlpha,
        DST_ALPHA => B::DstAlpha,
        ONE_MINUS_DST_ALPHA => B::OneMinusDstAlpha,
        DST_COLOR => B::Dst,
        ONE_MINUS_DST_COLOR => B::OneMinusDst,
        SRC_ALPHA_SATURATE => B::SrcAlphaSaturated,
        CONSTANT_COLOR => B::Constant,
        ONE_MINUS_CONSTANT_COLOR => B::OneMinusConstant,
        // wgpu has one blend constant; its alpha is what CONSTANT_ALPHA reads.
        CONSTANT_ALPHA => B::Constant,
        ONE_MINUS_CONSTANT_ALPHA => B::OneMinusConstant,
        _ => return None,
    })
}

fn blend_op(e: u32) -> Option<wgpu::BlendOperation> {
    Some(match e {
        FUNC_ADD => wgpu::BlendOperation::Add,
        FUNC_SUBTRACT => wgpu::BlendOperation::Subtract,
        FUNC_REVERSE_SUBTRACT => wgpu::BlendOperation::ReverseSubtract,
        _ => return None,
    })
}

fn type_size(ty: u32) -> Option<usize> {
    Some(match ty {
        BYTE | UNSIGNED_BYTE => 1,
        SHORT | UNSIGNED_SHORT | HALF_FLOAT_OES => 2,
        FLOAT | FIXED => 4,
        _ => return None,
    })
}

/// The wgpu format that reads GL attribute data as-is, if there is one.
fn native_format(ty: u32, size: i32, normalized: bool) -> Option<wgpu::VertexFormat> {
    use wgpu::VertexFormat as F;
    Some(match (ty, size, normalized) {
        (FLOAT, 1, _) => F::Float32,
        (FLOAT, 2, _) => F::Float32x2,
        (FLOAT, 3, _) => F::Float32x3,
        (FLOAT, 4, _) => F::Float32x4,
        (HALF_FLOAT_OES, 2, _) => F::Float16x2,
        (HALF_FLOAT_OES, 4, _) => F::Float16x4,
        (UNSIGNED_BYTE, 4, true) => F::Unorm8x4,
        (BYTE, 4, true) => F::Snorm8x4,
        (UNSIGNED_SHORT, 2, true) => F::Unorm16x2,
        (UNSIGNED_SHORT, 4, true) => F::Unorm16x4,
        (SHORT, 2, true) => F::Snorm16x2,
        (SHORT, 4, true) => F::Snorm16x4,
        _ => return None,
    })
}

/// Reads one attribute component as GL converts it to float (ES 2.0 §2.1.2, table 2.7).
fn component(bytes: &[u8], ty: u32, normalized: bool) -> f32 {
    match ty {
        FLOAT => f32::from_ne_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]),
        FIXED => i32::from_ne_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]) as f32 / 65536.0,
        HALF_FLOAT_OES => half::f16::from_bits(u16::from_ne_bytes([bytes[0], bytes[1]])).to_f32(),
        UNSIGNED_BYTE => {
            let v = f32::from(bytes[0]);
            if normalized {
                v / 255.0
            } else {
                v
            }
        }
        BYTE => {
            let v = f32::from(bytes[0] as i8);
            if normalized {
                (2.0 * v + 1.0) / 255.0
            } else {
                v
            }
        }
        UNSIGNED_SHORT => {
            let v = f32::from(u16::from_ne_bytes([bytes[0], bytes[1]]));
            if normalized {
                v / 65535.0
            } else {
                v
            }
        }
        _ => {
            let v = f32::from(i16::from_ne_bytes([bytes[0], bytes[1]]));
            if normalized {
                (2.0 * v + 1.0) / 65535.0
            } else {
                v
            }
        }
    }
}

fn float_format(n: i32) -> wgpu::VertexFormat {
    match n {
        1 => wgpu::VertexFormat::Float32,
        2 => wgpu::VertexFormat::Float32x2,
        3 => wgpu::VertexFormat::Float32x3,
        _ => wgpu::VertexFormat::Float32x4,
    }
}

enum Value {
    Ints(Vec<i32>),
    Floats(Vec<f32>),
    Bools(Vec<bool>),
}

impl GlesExecutor {
    /// An executor drawing on `gpu`; it logs within its session's span.
    pub fn new(gpu: Arc<Gpu>) -> Self {
        GlesExecutor {
            r: Renderer::new(gpu.clone()),
            gpu,
            initialized: false,
            surfaces: HashMap::new(),
            contexts: HashMap::new(),
            next_handle: 1,
            current: None,
            uid: 1,
            scene: None,
            layout: None,
        }
    }

    /// Places this client's window surfaces by `layout` instead of where it asks.
    pub fn with_layout(mut self, layout: Option<crate::layout::LayoutEntry>) -> Self {
        self.layout = layout;
        self
    }

    /// Shows this client's window surfaces in `scene` as client `id` named `name`.
    pub fn with_scene(mut self, scene: Arc<crate::scene::Scene>, id: u64, name: &str) -> Self {
        self.scene = Some((scene, id, name.to_string()));
        self
    }

    /// Pipelines created because none in the cache matched.
    pub fn pipeline_cache_misses(&self) -> u64 {
        self.r.pipeline_misses
    }

    /// The surface with handle `id`, for the compositor and tests.
    pub fn surface(&self, id: u32) -> Option<&Surface> {
        self.surfaces.get(&id)
    }

    fn next_uid(&mut self) -> u64 {
        self.uid += 1;
        self.uid
    }

    fn flush(&mut self) {
        self.r.flush();
    }

    /// Logs every GPU error caught since the last command against this client and records
    /// `GL_OUT_OF_MEMORY` (after which GL leaves the state undefined, as a lost GPU would).
    fn charge(&mut self, extra: Option<wgpu::Error>) {
        let mut errors = std::mem::take(&mut self.r.errors);
        errors.extend(extra.map(|e| super::render::error_chain(&e)));
        for e in errors {
            warn!("GPU validation error charged to this client: {e}");
            if let Some(ctx) = self.current.and_then(|(c, _)| self.contexts.get_mut(&c)) {
                ctx.err(OUT_OF_MEMORY);
            }
        }
    }

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
        let target = Target { key: (uid, 0), color: Some((color, color_view)), depth, width: w, height: h };
        self.r.clear(
            &target,
            Some(([0.0; 4], wgpu::ColorWrites::ALL)),
            target.depth.as_ref().map(|_| (1.0, true)),
            target.has_stencil().then_some((0, 0xff)),
            None,
        );
        (target, sample)
    }

    fn make_surface(&mut self, config: Config, width: i32, height: i32, window: bool) -> Result<u32, i32> {
        if width < 0 || height < 0 {
            return Err(EGL_BAD_PARAMETER);
        }
        if width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
            return Err(if window { EGL_BAD_NATIVE_WINDOW } else { EGL_BAD_PARAMETER });
        }
        let (w, h) = ((width as u32).max(1), (height as u32).max(1));
        let (target, depth_sample) = self.make_target(config, w, h);
        // Window surfaces are double-buffered: a front buffer holds the last completed frame.
        let front = window.then(|| self.make_target(config, w, h));
        let id = self.next_handle;
        self.next_handle += 1;
        self.surfaces.insert(id, Surface { target, depth_sample, front, config, window });
        Ok(id)
    }

    /// `eglSwapBuffers`: the back buffer becomes the front (and is shown), the old front
    /// becomes the next back buffer.
    fn swap(&mut self, surface: u32) -> Result<(), i32> {
        self.flush();
        let s = self.surfaces.get_mut(&surface).ok_or(EGL_BAD_SURFACE)?;
        let Some((front, front_depth)) = &mut s.front else { return Ok(()) };
        std::mem::swap(&mut s.target, front);
        std::mem::swap(&mut s.depth_sample, front_depth);
        if let (Some(scene), Some((_, view))) = (&self.scene, &front.color) {
            scene.0.present(scene.1, surface, view.clone(), front_depth.clone());
            scene.0.throttle(scene.1, surface);
        }
        Ok(())
    }

    fn egl(&mut self, cmd: Command<'_>) -> Option<Reply> {
        Some(match cmd {
            Command::GetDisplay { .. } | Command::GetPlatformDisplay { .. } => Reply::GetDisplay(1),
            Command::Initialize { display } => {
                if display != 1 {
                    return Some(Reply::Initialize(Err(EGL_BAD_DISPLAY)));
                }
                self.initialized = true;
                Reply::Initialize(Ok((1, 4)))
            }
            Command::Terminate { display } => Reply::Terminate(if display == 1 {
                self.initialized = false;
                Ok(())
            } else {
                Err(EGL_BAD_DISPLAY)
            }),
            Command::ChooseConfig { display, attribs, config_size } => {
                Reply::ChooseConfig(self.check_display(display).and_then(|()| {
                    let mut ids = egl::choose(&attribs.to_vec())?;
                    if config_size >= 0 {
                        ids.truncate(config_size as usize);
                    }
                    Ok(ids)
                }))
            }
            Command::GetConfigAttrib { display, config, attribute } => {
                Reply::GetConfigAttrib(self.check_display(display).and_then(|()| {
                    Config::get(config).ok_or(EGL_BAD_CONFIG)?.attrib(attribute).ok_or(EGL_BAD_ATTRIBUTE)
                }))
            }
            Command::CreatePbufferSurface { display, config, attribs } => {
                Reply::CreatePbufferSurface(self.check_display(display).and_then(|()| {
                    let c = Config::get(config).ok_or(EGL_BAD_CONFIG)?;
                    let (w, h) = egl::pbuffer_size(&attribs.to_vec())?;
                    self.make_surface(c, w, h, false)
                }))
            }
            Command::CreateWindowSurface { display, config, mut x, mut y, mut z, mut width, mut height, .. } => {
                if let Some(l) = &self.layout {
                    (x, y, z) = (l.x, l.y, l.z);
                    if let (Some(w), Some(h)) = (l.width, l.height) {
                        (width, height) = (w as i32, h as i32);
                    }
                }
                Reply::CreateWindowSurface(self.check_display(display).and_then(|()| {
                    let c = Config::get(config).ok_or(EGL_BAD_CONFIG)?;
                    if !z.is_finite() || width <= 0 || height <= 0 {
                        return Err(EGL_BAD_NATIVE_WINDOW);
                    }
                    let id = self.make_surface(c, width, height, true)?;
                    if let Some((scene, client, name)) = &self.scene {
                        scene.add(*client, id, name, [x, y, width, height], z);
                    }
                    Ok(id)
                }))
            }
            Command::CreateContext { display, config, attribs, .. } => {
                Reply::CreateContext(self.check_display(display).and_then(|()| {
                    let c = Config::get(config).ok_or(EGL_BAD_CONFIG)?;
                    let mut version = 1;
                    for pair in attribs.to_vec().chunks(2) {
                        match *pair {
                            [EGL_NONE, ..] => break,
                            [EGL_CONTEXT_CLIENT_VERSION, v] => version = v,
                            [_, _] => return Err(EGL_BAD_ATTRIBUTE),
                            _ => return Err(EGL_BAD_ATTRIBUTE),
                        }
                    }
                    if version != 2 {
                        return Err(EGL_BAD_CONFIG);
                    }
                    let id = self.next_handle;
                    self.next_handle += 1;
                    self.contexts.insert(id, Context::new(c));
                    Ok(id)
                }))
            }
            Command::MakeCurrent { display, draw, read, context } => {
                Reply::MakeCurrent(self.check_display(display).and_then(|()| {
                    if context == 0 {
                        if draw != 0 || read != 0 {
                            return Err(EGL_BAD_MATCH);
                        }
                        self.flush();
                        self.current = None;
                        return Ok(());
                    }
                    if draw != read {
                        return Err(EGL_BAD_MATCH);
                    }
                    let surface = self.surfaces.get(&draw).ok_or(EGL_BAD_SURFACE)?;
                    let (w, h) = (surface.target.width as i32, surface.target.height as i32);
                    let ctx = self.contexts.get_mut(&context).ok_or(EGL_BAD_CONTEXT)?;
                    if !ctx.made_current {
                        ctx.made_current = true;
                        ctx.viewport = [0, 0, w, h];
                        ctx.scissor = [0, 0, w, h];
                    }
                    self.flush();
                    self.current = Some((context, draw));
                    Ok(())
                }))
            }
            Command::SwapInterval { display, interval } => {
                Reply::SwapInterval(self.check_display(display).and_then(|()| {
                    // EGL: the interval applies to the window surface bound to the current context.
                    let (_, surface) = self.current.ok_or(EGL_BAD_CONTEXT)?;
                    if let Some((scene, client, _)) = &self.scene {
                        scene.set_interval(*client, surface, interval);
                    }
                    Ok(())
                }))
            }
            Command::QuerySurface { display, surface, attribute } => {
                Reply::QuerySurface(self.check_display(display).and_then(|()| {
                    let s = self.surfaces.get(&surface).ok_or(EGL_BAD_SURFACE)?;
                    match attribute {
                        EGL_WIDTH => Ok(s.target.width as i32),
                        EGL_HEIGHT => Ok(s.target.height as i32),
                        EGL_CONFIG_ID => Ok(s.config.id as i32),
                        EGL_RENDER_BUFFER => Ok(EGL_BACK_BUFFER),
                        EGL_SWAP_BEHAVIOR => Ok(EGL_BUFFER_DESTROYED),
                        _ => Err(EGL_BAD_ATTRIBUTE),
                    }
                }))
            }
            Command::DestroySurface { display, surface } => {
                Reply::DestroySurface(self.check_display(display).and_then(|()| {
                    self.surfaces.remove(&surface).ok_or(EGL_BAD_SURFACE)?;
                    if let Some((scene, client, _)) = &self.scene {
                        scene.remove(*client, Some(surface));
                    }
                    Ok(())
                }))
            }
            Command::DestroyContext { display, context } => {
                Reply::DestroyContext(self.check_display(display).and_then(|()| {
                    if self.current.is_some_and(|(c, _)| c == context) {
                        self.flush();
                        self.current = None;
                    }
                    self.contexts.remove(&context).map(|_| ()).ok_or(EGL_BAD_CONTEXT)
                }))
            }
            Command::SwapBuffers { display, surface } => {
                Reply::SwapBuffers(self.check_display(display).and_then(|()| self.swap(surface)))
            }
            _ => return None,
        })
    }

    fn check_display(&self, display: u32) -> Result<(), i32> {
        if display != 1 {
            Err(EGL_BAD_DISPLAY)
        } else if !self.initialized {
            Err(EGL_NOT_INITIALIZED)
        } else {
            Ok(())
        }
    }

    fn resolve_target(&mut self) -> Result<Target, u32> {
        let (cid, sid) = self.current.ok_or(FRAMEBUFFER_UNSUPPORTED)?;
        let ctx = self.contexts.get(&cid).ok_or(FRAMEBUFFER_UNSUPPORTED)?;
        if ctx.framebuffer == 0 {
            return self.surfaces.get(&sid).map(|s| s.target.clone()).ok_or(FRAMEBUFFER_UNSUPPORTED);
        }
        let fb = ctx.framebuffers.get(&ctx.framebuffer).cloned().unwrap_or_default();
        let mut size: Option<(u32, u32)> = None;
        let mut same = |w: u32, h: u32| -> Result<(), u32> {
            match size {
                Some(s) if s != (w, h) => Err(FRAMEBUFFER_INCOMPLETE_DIMENSIONS),
                _ => {
                    size = Some((w, h));
                    Ok(())
                }
            }
        };
        let mut key = (ctx.framebuffer as u64) << 32;
        let color = match fb.color {
            Attachment::None => None,
            Attachment::Texture { name, level, face } => {
                let t = ctx.textures.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                let img = t.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                if t.depth {
                    return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                }
                if t.defined[face as usize] & (1 << level) == 0 {
                    return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                }
                same((img.width >> level).max(1), (img.height >> level).max(1))?;
                key ^= t.uid.wrapping_mul(31).wrapping_add(u64::from(level) * 7 + u64::from(face));
                let view = img.texture.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_mip_level: level,
                    mip_level_count: Some(1),
                    base_array_layer: face,
                    array_layer_count: Some(1),
                    ..Default::default()
                });
                Some((img.texture.clone(), view))
            }
            Attachment::Renderbuffer(name) => {
                let rb = ctx.renderbuffers.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                let (tex, view) = rb.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                if !matches!(rb.format, RGBA4 | RGB5_A1 | RGB565 | RGBA8_OES | RGB8_OES) {
                    return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                }
                same(rb.width, rb.height)?;
                key ^= rb.uid.wrapping_mul(31);
                Some((tex.clone(), view.clone()))
            }
        };
        let ds = |a: Attachment, ok: &[u32]| -> Result<Option<DepthAttachment>, u32> {
            match a {
                Attachment::None => Ok(None),
                Attachment::Texture { name, .. } => {
                    let t = ctx.textures.get(&name).filter(|t| t.depth).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                    if !ok.contains(&DEPTH_COMPONENT16) {
                        return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                    }
                    let img = t.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                    Ok(Some((img.view.clone(), wgpu::TextureFormat::Depth32Float, t.uid, img.width, img.height)))
                }
                Attachment::Renderbuffer(name) => {
                    let rb = ctx.renderbuffers.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                    let (tex, view) = rb.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                    if !ok.contains(&rb.format) {
                        return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                    }
                    Ok(Some((view.clone(), tex.format(), rb.uid, rb.width, rb.height)))
                }
            }
        };
        let depth = ds(fb.depth, &[DEPTH_COMPONENT16, DEPTH_COMPONENT24_OES, DEPTH24_STENCIL8_OES])?;
        let stencil = ds(fb.stencil, &[STENCIL_INDEX8, DEPTH24_STENCIL8_OES])?;
        let depth = match (depth, stencil) {
            (Some(d), Some(s)) if d.2 != s.2 => return Err(FRAMEBUFFER_UNSUPPORTED),
            (Some(d), _) | (None, Some(d)) => Some(d),
            (None, None) => None,
        };
        if let Some(d) = &depth {
            same(d.3, d.4)?;
            key ^= d.2.wrapping_mul(131);
        }
        let (width, height) = size.ok_or(FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT)?;
        Ok(Target { key: (key, 1), color, depth: depth.map(|d| (d.0, d.1)), width, height })
    }

    fn ensure_image(gpu: &Gpu, t: &mut Texture, uid: u64, width: u32, height: u32) {
        let layers = if t.target == TEXTURE_CUBE_MAP { 6 } else { 1 };
        if t.gpu.as_ref().is_some_and(|i| i.width == width && i.height == height) {
            return;
        }
        let mips = 32 - width.max(height).max(1).leading_zeros();
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("gl texture"),
            size: wgpu::Extent3d { width: width.max(1), height: height.max(1), depth_or_array_layers: layers },
            mip_level_count: mips,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: COLOR_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let dim = if layers == 6 { wgpu::TextureViewDimension::Cube } else { wgpu::TextureViewDimension::D2 };
        let view = texture.create_view(&wgpu::TextureViewDescriptor { dimension: Some(dim), ..Default::default() });
        t.gpu = Some(TextureImage { texture, view, width, height, mips, levels: mips });
        t.defined = [0; 6];
        t.uid = uid;
        t.depth = false;
    }

    fn gl(&mut self, cmd: Command<'_>) -> Option<Reply> {
        let Some((cid, _)) = self.current else {
            // No current context: GL calls have no effect. Queries still get an answer.
            return cmd
                .opcode()
                .is_sync()
                .then(|| Reply::Unsupported(format!("{}: no current context", cmd.opcode().name())));
        };
        let uid = self.next_uid();
        // Split borrows: the context, the renderer and the GPU are used together below.
        let pending = self.r.pending();
        let needs_flush = matches!(
            cmd,
            Command::BufferData { .. }
                | Command::BufferSubData { .. }
                | Command::TexImage2D { .. }
                | Command::TexSubImage2D { .. }
                | Command::CopyTexImage2D { .. }
                | Command::CopyTexSubImage2D { .. }
                | Command::GenerateMipmap { .. }
        );
        if pending && needs_flush {
            self.flush();
        }
        match cmd {
            Command::Clear { mask } => {
                self.clear(mask);
                return None;
            }
            Command::DrawArrays { mode, first, count } => {
                if first < 0 || count < 0 {
                    self.ctx(cid).err(INVALID_VALUE);
                } else {
                    self.draw(mode, count as u32, None, first as u32);
                }
                return None;
            }
            Command::DrawElements { mode, count, index_type, offset } => {
                if count < 0 {
                    self.ctx(cid).err(INVALID_VALUE);
                } else {
                    self.draw(mode, count as u32, Some(Indices::Buffer(index_type, offset)), 0);
                }
                return None;
            }
            Command::DrawElementsData { mode, count, index_type, indices } => {
                if count < 0 {
                    self.ctx(cid).err(INVALID_VALUE);
                } else {
                    self.draw(mode, count as u32, Some(Indices::Client(index_type, indices.as_bytes().to_vec())), 0);
                }
                return None;
            }
            Command::ReadPixels { x, y, width, height, format, pixel_type } => {
                return Some(Reply::ReadPixels(Bytes(self.read_pixels(x, y, width, height, format, pixel_type))));
            }
            Command::Finish {} => {
                self.r.finish();
                return Some(Reply::Finish(()));
            }
            Command::Flush {} => {
                self.flush();
                return None;
            }
            Command::CheckFramebufferStatus { target } => {
                if target != FRAMEBUFFER {
                    self.ctx(cid).err(INVALID_ENUM);
                    return Some(Reply::CheckFramebufferStatus(0));
                }
                let s = match self.resolve_target() {
                    Ok(_) => FRAMEBUFFER_COMPLETE,
                    Err(e) => e,
                };
                return Some(Reply::CheckFramebufferStatus(s));
            }
            Command::GenerateMipmap { target } => {
                let gpu = self.gpu.clone();
                let ctx = self.ctx(cid);
                let Some(name) = ctx.bound_texture(target) else {
                    ctx.err(INVALID_ENUM);
                    return None;
                };
                let Some(t) = ctx.textures.get_mut(&name) else {
                    ctx.err(INVALID_OPERATION);
                    return None;
                };
                let layers = if t.target == TEXTURE_CUBE_MAP { 6 } else { 1 };
                if t.depth {
                    ctx.err(INVALID_OPERATION);
                    return None;
                }
                let Some(img) = &t.gpu else {
                    ctx.err(INVALID_OPERATION);
                    return None;
                };
                if t.defined[..layers].iter().any(|d| d & 1 == 0) {
                    ctx.err(INVALID_OPERATION);
                    return None;
                }
                let (tex, mips) = (img.texture.clone(), img.mips);
                for d in &mut t.defined[..layers] {
                    *d = (1 << mips) - 1;
                }
                let _ = gpu;
                self.r.generate_mipmaps(&tex, mips, layers as u32);
                return None;
            }
            Command::CopyTexImage2D { target, level, internalformat, x, y, width, height, border } => {
                self.copy_tex(target, level, Some(internalformat), 0, 0, x, y, width, height, border);
                return None;
            }
            Command::CopyTexSubImage2D { target, level, xoffset, yoffset, x, y, width, height } => {
                self.copy_tex(target, level, None, xoffset, yoffset, x, y, width, height, 0);
                return None;
            }
            Command::LinkProgram { program } => {
                self.link(program);
                return None;
            }
            Command::TexImage2D {
                target,
                level,
                internalformat,
                width,
                height,
                border,
                format: DEPTH_COMPONENT,
                pixel_type,
                pixels,
            } => {
                self.depth_tex_image(
                    target,
                    level,
                    internalformat,
                    width,
                    height,
                    border,
                    pixel_type,
                    pixels.as_ref().map(|p| p.as_bytes()),
                );
                return None;
            }
            _ => {}
        }
        let gpu = self.gpu.clone();
        let ctx = self.ctx(cid);
        ctx_command(ctx, &gpu, uid, cmd)
    }

    fn ctx(&mut self, cid: u32) -> &mut Context {
        self.contexts.get_mut(&cid).expect("current context exists")
    }

    fn link(&mut self, program: u32) {
        let Some((cid, _)) = self.current else { return };
        let gpu = self.gpu.clone();
        let id = self.next_uid();
        let ctx = self.ctx(cid);
        let Some(p) = ctx.programs.get(&program) else {
            ctx.err(if ctx.shaders.contains_key(&program) { INVALID_OPERATION } else { INVALID_VALUE });
            return;
        };
        let find = |stage: Stage| p.attached.iter().filter_map(|s| ctx.shaders.get(s)).find(|s| s.stage == stage);
        let result = match (find(Stage::Vertex), find(Stage::Fragment)) {
            (Some(vs), Some(fs)) => match (&vs.compiled, &fs.compiled) {
                (Some(v), Some(f)) if vs.compiled_ok && fs.compiled_ok => {
                    glsl::link(v, f, &p.bindings, MAX_ATTRIBS as u32)
                }
                _ => Err("error: an attached shader did not compile".to_string()),
            },
            _ => Err("error: a program needs one vertex and one fragment shader".to_string()),
        };
        let p = ctx.programs.get_mut(&program).expect("checked above");
        match result {
            Ok(info) => {
                let d = &gpu.device;
                let guard = d.push_error_scope(wgpu::ErrorFilter::Validation);
                let vs = d.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("vs"),
                    source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(info.vertex.clone())),
                });
                let fs = d.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("fs"),
                    source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(info.fragment.clone())),
                });
                let entries = super::render::layout_entries(&info, 0);
                let bgl =
                    d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: None, entries: &entries });
                let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: None,
                    bind_group_layouts: &[Some(&bgl)],
                    immediate_size: 0,
                });
                if let Some(e) = pollster::block_on(guard.pop()) {
                    p.link_ok = false;
                    p.log = format!("error: the GPU rejected the program: {}", super::render::error_chain(&e));
                    return;
                }
                let mut locations = Vec::new();
                for (i, u) in info.uniforms.iter().enumerate() {
                    for e in 0..u.len {
                        locations.push((i, e));
                    }
                }
                p.data = vec![0; info.block_size as usize];
                p.units = vec![0; info.samplers.len()];
                p.linked = Some(Arc::new(LinkedProgram { info, vs, fs, bgl, layout, locations, id }));
                p.link_ok = true;
                p.log.clear();
            }
            Err(log) => {
                p.link_ok = false;
                p.log = log;
            }
        }
    }

    /// `glTexImage2D` of a `DEPTH_COMPONENT` texture (OES_depth_texture): 2D and level 0 only,
    /// 16- or 32-bit unsigned data, stored as Depth32Float.
    #[allow(clippy::too_many_arguments)]
    fn depth_tex_image(
        &mut self,
        target: u32,
        level: i32,
        internal: i32,
        width: i32,
        height: i32,
        border: i32,
        ty: u32,
        pixels: Option<&[u8]>,
    ) {
        let Some((cid, _)) = self.current else { return };
        let gpu = self.gpu.clone();
        let uid = self.next_uid();
        let ctx = self.ctx(cid);
        let Some((_, cube)) = face_of(target) else { return ctx.err(INVALID_ENUM) };
        if !matches!(ty, UNSIGNED_SHORT | UNSIGNED_INT) {
            return ctx.err(INVALID_ENUM);
        }
        if internal as u32 != DEPTH_COMPONENT || cube || level != 0 {
            return ctx.err(INVALID_OPERATION);
        }
        if width < 0 || height < 0 || border != 0 || width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
            return ctx.err(INVALID_VALUE);
        }
        let (w, h) = (width as u32, height as u32);
        let values: Option<Vec<f32>> = match pixels {
            Some(b) => {
                let align = ctx.unpack_alignment as usize;
                let bpp = if ty == UNSIGNED_SHORT { 2 } else { 4 };
                if b.len() < upload_size(w as usize, h as usize, bpp, align) {
                    return ctx.err(INVALID_OPERATION);
                }
                let row = (w as usize * bpp).div_ceil(align) * align;
                let mut v = Vec::with_capacity((w * h) as usize);
                for y in 0..h as usize {
                    for x in 0..w as usize {
                        let at = y * row + x * bpp;
                        v.push(if bpp == 2 {
                            f32::from(u16::from_ne_bytes([b[at], b[at + 1]])) / 65535.0
                        } else {
                            (f64::from(u32::from_ne_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]))
                                / f64::from(u32::MAX)) as f32
                        });
                    }
                }
                Some(v)
            }
            None => None,
        };
        let Some(name) = ctx.bound_texture(TEXTURE_2D) else { return };
        let Some(t) = ctx.textures.get_mut(&name).filter(|_| name != 0) else { return ctx.err(INVALID_OPERATION) };
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("gl depth texture"),
            size: wgpu::Extent3d { width: w.max(1), height: h.max(1), depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Depth32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let levels = 32 - w.max(h).max(1).leading_zeros();
        t.gpu = Some(TextureImage { texture: texture.clone(), view, width: w, height: h, mips: 1, levels });
        t.defined = [1, 0, 0, 0, 0, 0];
        t.format = DEPTH_COMPONENT;
        t.depth = true;
        t.uid = uid;
        if let Some(v) = values.filter(|_| w > 0 && h > 0) {
            self.r.upload_depth(&texture, w, h, &v);
        }
    }

    fn clear(&mut self, mask: u32) {
        let Some((cid, _)) = self.current else { return };
        let ctx = self.ctx(cid);
        if mask & !(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT) != 0 {
            ctx.err(INVALID_VALUE);
            return;
        }
        let target = match self.resolve_target() {
            Ok(t) => t,
            Err(_) => {
                self.ctx(cid).err(INVALID_FRAMEBUFFER_OPERATION);
                return;
            }
        };
        let ctx = self.ctx(cid);
        let m = ctx.color_mask;
        let mut writes = wgpu::ColorWrites::empty();
        for (bit, on) in
            [wgpu::ColorWrites::RED, wgpu::ColorWrites::GREEN, wgpu::ColorWrites::BLUE, wgpu::ColorWrites::ALPHA]
                .into_iter()
                .zip(m)
        {
            if on {
                writes |= bit;
            }
        }
        let color = (mask & COLOR_BUFFER_BIT != 0 && target.color.is_some() && !writes.is_empty())
            .then(|| (ctx.clear_color.map(|c| c.clamp(0.0, 1.0)), writes));
        let depth = (mask & DEPTH_BUFFER_BIT != 0 && target.depth.is_some() && ctx.depth_mask)
            .then_some((ctx.clear_depth, true));
        let stencil = (mask & STENCIL_BUFFER_BIT != 0 && target.has_stencil() && ctx.stencil[0].write & 0xff != 0)
            .then_some((ctx.clear_stencil as u32 & 0xff, ctx.stencil[0].write & 0xff));
        let scissor = ctx.scissor_test.then(|| clip_rect(ctx.scissor, &target));
        if color.is_none() && depth.is_none() && stencil.is_none() {
            return;
        }
        self.r.clear(&target, color, depth, stencil, scissor);
    }

    fn read_pixels(&mut self, x: i32, y: i32, width: i32, height: i32, format: u32, ty: u32) -> Vec<u8> {
        let Some((cid, _)) = self.current else { return Vec::new() };
        if width < 0 || height < 0 {
            self.ctx(cid).err(INVALID_VALUE);
            return Vec::new();
        }
        if !(format == RGBA && ty == UNSIGNED_BYTE) {
            let e = if matches!(format, RGBA | RGB | ALPHA | LUMINANCE | LUMINANCE_ALPHA) && type_size(ty).is_some() {
                INVALID_OPERATION
            } else {
                INVALID_ENUM
            };
            self.ctx(cid).err(e);
            return Vec::new();
        }
        let target = match self.resolve_target() {
            Ok(t) => t,
            Err(_) => {
                self.ctx(cid).err(INVALID_FRAMEBUFFER_OPERATION);
                return Vec::new();
            }
        };
        let align = self.ctx(cid).pack_alignment.max(1) as usize;
        let (w, h) = (width as usize, height as usize);
        let row = (w * 4).div_ceil(align) * align;
        let mut out = vec![0u8; upload_size(w, h, 4, align)];
        // Only the part inside the framebuffer is defined; the rest stays zero.
        let x0 = x.clamp(0, target.width as i32);
        let y0 = y.clamp(0, target.height as i32);
        let x1 = (x + width).clamp(0, target.width as i32);
        let y1 = (y + height).clamp(0, target.height as i32);
        if x1 > x0 && y1 > y0 {
            let rect = [x0 as u32, y0 as u32, (x1 - x0) as u32, (y1 - y0) as u32];
            if let Some(px) = self.r.read_rgba(&target, rect) {
                let cw = rect[2] as usize * 4;
                for r in 0..rect[3] as usize {
                    let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * 4;
                    out[dst..dst + cw].copy_from_slice(&px[r * cw..(r + 1) * cw]);
                }
            }
        }
        out
    }

    #[allow(clippy::too_many_arguments)]
    fn copy_tex(
        &mut self,
        target: u32,
        level: i32,
        internal: Option<u32>,
        xo: i32,
        yo: i32,
        x: i32,
        y: i32,
        w: i32,
        h: i32,
        border: i32,
    ) {
        let Some((cid, _)) = self.current else { return };
        let src = match self.resolve_target() {
            Ok(t) => t,
            Err(_) => {
                self.ctx(cid).err(INVALID_FRAMEBUFFER_OPERATION);
                return;
            }
        };
        let gpu = self.gpu.clone();
        let uid = self.next_uid();
        let ctx = self.ctx(cid);
        let face = match face_of(target) {
            Some(f) => f,
            None => return ctx.err(INVALID_ENUM),
        };
        if level < 0 || w < 0 || h < 0 || border != 0 || level > 13 {
            return ctx.err(INVALID_VALUE);
        }
        if let Some(f) = internal {
            if !matches!(f, RGBA | RGB | LUMINANCE | LUMINANCE_ALPHA | ALPHA) {
                return ctx.err(INVALID_ENUM);
            }
        }
        let Some(name) = ctx.bound_texture(if face.1 { TEXTURE_CUBE_MAP } else { TEXTURE_2D }) else { return };
        let Some(t) = ctx.textures.get_mut(&name) else { return ctx.err(INVALID_OPERATION) };
        let level = level as u32;
        if let Some(f) = internal {
            if level == 0 {
                Self::ensure_image(&gpu, t, uid, w as u32, h as u32);
                t.format = f;
            }
        }
        let Some(img) = &t.gpu else { return ctx.err(INVALID_OPERATION) };
        let (lw, lh) = ((img.width >> level).max(1), (img.height >> level).max(1));
        if internal.is_some() && (lw, lh) != (w as u32, h as u32) {
            return ctx.err(INVALID_VALUE);
        }
        if xo < 0 || yo < 0 || xo + w > lw as i32 || yo + h > lh as i32 {
            return ctx.err(INVALID_VALUE);
        }
        t.defined[face.0 as usize] |= 1 << level;
        let Some((src_tex, _)) = &src.color else { return };
        // Clip the source rectangle to the framebuffer.
        let (sx0, sy0) = (x.max(0), y.max(0));
        let (sx1, sy1) = ((x + w).min(src.width as i32), (y + h).min(src.height as i32));
        if sx1 <= sx0 || sy1 <= sy0 {
            return;
        }
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_texture(
            wgpu::TexelCopyTextureInfo {
                texture: src_tex,
                mip_level: 0,
                origin: wgpu::Origin3d { x: sx0 as u32, y: sy0 as u32, z: 0 },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyTextureInfo {
                texture: &img.texture,
                mip_level: level,
                origin: wgpu::Origin3d { x: (xo + sx0 - x) as u32, y: (yo + sy0 - y) as u32, z: face.0 },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::Extent3d { width: (sx1 - sx0) as u32, height: (sy1 - sy0) as u32, depth_or_array_layers: 1 },
        );
        self.flush();
        gpu.queue.submit([enc.finish()]);
    }

    fn draw(&mut self, mode: u32, count: u32, indices: Option<Indices>, first: u32) {
        let Some((cid, _)) = self.current else { return };
        let topology = match mode {
            POINTS => wgpu::PrimitiveTopology::PointList,
            LINES => wgpu::PrimitiveTopology::LineList,
            LINE_STRIP | LINE_LOOP => wgpu::PrimitiveTopology::LineStrip,
            TRIANGLES | TRIANGLE_FAN => wgpu::PrimitiveTopology::TriangleList,
            TRIANGLE_STRIP => wgpu::PrimitiveTopology::TriangleStrip,
            _ => return self.ctx(cid).err(INVALID_ENUM),
        };
        if let Some(Indices::Buffer(ty, _) | Indices::Client(ty, _)) = &indices {
            if !matches!(*ty, UNSIGNED_BYTE | UNSIGNED_SHORT | UNSIGNED_INT) {
                return self.ctx(cid).err(INVALID_ENUM);
            }
        }
        let target = match self.resolve_target() {
            Ok(t) => t,
            Err(_) => return self.ctx(cid).err(INVALID_FRAMEBUFFER_OPERATION),
        };
        let ctx = self.contexts.get_mut(&cid).expect("current");
        let Some(program) = ctx.programs.get(&ctx.program).and_then(|p| p.linked.clone()) else { return };
        if count == 0 {
            return;
        }
        // Indices: validated against the element buffer's shadow before anything reaches the GPU.
        let mut index: Option<(Source, wgpu::IndexFormat)> = None;
        let mut list: Option<Vec<u32>> = None;
        let vertex_count: u64;
        if let Some(indices) = &indices {
            let (ty, offset, gpu, data): (u32, u64, Option<&wgpu::Buffer>, &[u8]) = match indices {
                Indices::Buffer(ty, offset) => {
                    let Some(buf) = ctx.buffers.get(&ctx.element_buffer) else { return ctx.err(INVALID_OPERATION) };
                    (*ty, *offset, buf.gpu.as_ref(), &buf.data)
                }
                // Client indices are always rewritten into the per-pass ring below.
                Indices::Client(ty, bytes) => (*ty, 0, None, bytes),
            };
            let size = if ty == UNSIGNED_BYTE {
                1
            } else if ty == UNSIGNED_SHORT {
                2
            } else {
                4
            };
            let end = offset.checked_add(u64::from(count) * size);
            let Some(bytes) = end.and_then(|e| data.get(offset as usize..e as usize)) else {
                return ctx.err(INVALID_OPERATION);
            };
            let values: Vec<u32> = match size {
                1 => bytes.iter().map(|&b| u32::from(b)).collect(),
                2 => bytes.chunks_exact(2).map(|c| u32::from(u16::from_ne_bytes([c[0], c[1]]))).collect(),
                _ => bytes.chunks_exact(4).map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]])).collect(),
            };
            vertex_count = u64::from(values.iter().copied().max().unwrap_or(0)) + 1;
            // A u16 strip containing 0xFFFF would restart under wgpu; widen it to u32, whose
            // restart value no validated index can reach.
            let strip = matches!(mode, LINE_STRIP | TRIANGLE_STRIP);
            let restart_hazard = strip && size == 2 && values.contains(&0xFFFF);
            let direct = size != 1
                && offset.is_multiple_of(size)
                && !matches!(mode, LINE_LOOP | TRIANGLE_FAN)
                && !restart_hazard
                && gpu.is_some();
            if direct {
                let fmt = if size == 2 { wgpu::IndexFormat::Uint16 } else { wgpu::IndexFormat::Uint32 };
                index = gpu.cloned().map(|g| (Source::Buffer(g, offset), fmt));
            } else {
                list = Some(values);
            }
        } else {
            vertex_count = u64::from(first) + u64::from(count);
            if matches!(mode, LINE_LOOP | TRIANGLE_FAN) {
                list = Some((first..first + count).collect());
            }
        }
        let mut draw_count = count;
        if let Some(v) = list {
            let out: Vec<u32> = match mode {
                LINE_LOOP => v.iter().copied().chain(v.first().copied()).collect(),
                TRIANGLE_FAN => (1..v.len().saturating_sub(1)).flat_map(|i| [v[0], v[i], v[i + 1]]).collect(),
                _ => v,
            };
            draw_count = out.len() as u32;
            index = Some((Source::Bytes(bytemuck::cast_slice(&out).to_vec()), wgpu::IndexFormat::Uint32));
        }
        if draw_count == 0 {
            return;
        }
        // Vertex inputs, each checked against its buffer.
        let mut inputs = Vec::with_capacity(program.info.attributes.len());
        for (var, loc) in &program.info.attributes {
            let a = &ctx.attribs[*loc as usize];
            if !a.enabled {
                inputs.push(VertexInput {
                    location: *loc,
                    format: wgpu::VertexFormat::Float32x4,
                    stride: 0,
                    source: Source::Bytes(bytemuck::cast_slice(&a.current).to_vec()),
                });
                continue;
            }
            let _ = var;
            // A buffer object's shadow, or the client array sent for this draw (offset 0).
            let (data, gpu, offset): (&[u8], Option<&wgpu::Buffer>, u64) = if a.buffer == 0 {
                match &a.client {
                    Some(bytes) => (bytes, None, 0),
                    None => return ctx.err(INVALID_OPERATION),
                }
            } else {
                match ctx.buffers.get(&a.buffer) {
                    Some(buf) => (&buf.data, buf.gpu.as_ref(), a.offset),
                    None => return ctx.err(INVALID_OPERATION),
                }
            };
            let elem = type_size(a.ty).unwrap_or(4) * a.size as usize;
            let stride = if a.stride == 0 { elem } else { a.stride as usize };
            let need = offset as usize + (vertex_count as usize - 1) * stride + elem;
            if need > data.len() {
                return ctx.err(INVALID_OPERATION);
            }
            match native_format(a.ty, a.size, a.normalized) {
                Some(fmt) if offset.is_multiple_of(4) && stride.is_multiple_of(4) => {
                    let source = match gpu {
                        Some(g) => Source::Buffer(g.clone(), offset),
                        None => Source::Bytes(data[..need].to_vec()),
                    };
                    inputs.push(VertexInput { location: *loc, format: fmt, stride: stride as u64, source });
                }
                _ => {
                    let ts = type_size(a.ty).unwrap_or(4);
                    let mut out = Vec::with_capacity(vertex_count as usize * a.size as usize * 4);
                    for v in 0..vertex_count as usize {
                        let base = offset as usize + v * stride;
                        for c in 0..a.size as usize {
                            let at = base + c * ts;
                            out.extend_from_slice(&component(&data[at..at + ts], a.ty, a.normalized).to_ne_bytes());
                        }
                    }
                    inputs.push(VertexInput {
                        location: *loc,
                        format: float_format(a.size),
                        stride: a.size as u64 * 4,
                        source: Source::Bytes(out),
                    });
                }
            }
        }
        let p = ctx.programs.get(&ctx.program).expect("current program");
        let textures = program
            .info
            .samplers
            .iter()
            .zip(&p.units)
            .map(|((ty, _), unit)| {
                let slot = if *ty == Ty::SamplerCube { 1 } else { 0 };
                let name = ctx.units.get(*unit as usize)?[slot];
                let t = ctx.textures.get(&name)?;
                let want = if *ty == Ty::SamplerCube { TEXTURE_CUBE_MAP } else { TEXTURE_2D };
                if t.target != want || !t.complete() {
                    return None;
                }
                t.gpu.as_ref().map(|img| (img.view.clone(), t.uid, t.sampler, t.depth))
            })
            .collect();
        let mut raster = raster_state(ctx, topology, &target);
        if matches!(topology, wgpu::PrimitiveTopology::LineStrip | wgpu::PrimitiveTopology::TriangleStrip) {
            raster.strip_index = index.as_ref().map(|i| i.1);
        }
        let [vx, vy, vw, vh] = ctx.viewport;
        let (tw, th) = (target.width as f32, target.height as f32);
        let x0 = (vx as f32).clamp(0.0, tw);
        let y0 = (vy as f32).clamp(0.0, th);
        let viewport = [
            x0,
            y0,
            ((vx + vw) as f32).clamp(0.0, tw) - x0,
            ((vy + vh) as f32).clamp(0.0, th) - y0,
            ctx.depth_range[0].min(ctx.depth_range[1]),
            ctx.depth_range[0].max(ctx.depth_range[1]),
        ];
        if viewport[2] <= 0.0 || viewport[3] <= 0.0 {
            return;
        }
        let scissor =
            if ctx.scissor_test { clip_rect(ctx.scissor, &target) } else { [0, 0, target.width, target.height] };
        let stencil_ref = ctx.stencil[0].reference.clamp(0, 255) as u32;
        let blend_color = ctx.blend_color.map(|c| f64::from(c.clamp(0.0, 1.0)));
        let spec = DrawSpec {
            program,
            uniforms: &p.data,
            textures,
            inputs,
            index,
            count: draw_count,
            first,
            raster,
            viewport,
            scissor,
            stencil_ref,
            blend_color,
        };
        self.r.draw(&target, spec);
    }
}

/// A resolved depth/stencil attachment: view, format, renderbuffer uid, width, height.
type DepthAttachment = (wgpu::TextureView, wgpu::TextureFormat, u64, u32, u32);

fn face_of(target: u32) -> Option<(u32, bool)> {
    match target {
        TEXTURE_2D => Some((0, false)),
        t if (TEXTURE_CUBE_MAP_POSITIVE_X..TEXTURE_CUBE_MAP_POSITIVE_X + 6).contains(&t) => {
            Some((t - TEXTURE_CUBE_MAP_POSITIVE_X, true))
        }
        _ => None,
    }
}

fn clip_rect(r: [i32; 4], t: &Target) -> [u32; 4] {
    let x0 = r[0].clamp(0, t.width as i32);
    let y0 = r[1].clamp(0, t.height as i32);
    let x1 = (r[0].saturating_add(r[2])).clamp(0, t.width as i32);
    let y1 = (r[1].saturating_add(r[3])).clamp(0, t.height as i32);
    [x0 as u32, y0 as u32, (x1 - x0).max(0) as u32, (y1 - y0).max(0) as u32]
}

fn raster_state(ctx: &Context, topology: wgpu::PrimitiveTopology, target: &Target) -> RasterState {
    let triangles = matches!(topology, wgpu::PrimitiveTopology::TriangleList | wgpu::PrimitiveTopology::TriangleStrip);
    let cull = (ctx.cull && triangles).then_some(match ctx.cull_face {
        FRONT => Some(wgpu::Face::Front),
        BACK => Some(wgpu::Face::Back),
        _ => None,
    });
    // Culling both faces draws nothing; emulate with a never-passing depth test.
    let cull_all = cull == Some(None);
    let depth = if target.depth.is_some() && (ctx.depth_test || cull_all) {
        let func = if cull_all { NEVER } else { ctx.depth_func };
        Some((compare(func), ctx.depth_mask && !cull_all))
    } else {
        None
    };
    let stencil = (ctx.stencil_test && target.has_stencil()).then(|| {
        let face = |f: &StencilFace| wgpu::StencilFaceState {
            compare: compare(f.func),
            fail_op: stencil_op(f.fail),
            depth_fail_op: stencil_op(f.zfail),
            pass_op: stencil_op(f.zpass),
        };
        wgpu::StencilState {
            front: face(&ctx.stencil[0]),
            back: face(&ctx.stencil[1]),
            read_mask: ctx.stencil[0].mask & 0xff,
            write_mask: ctx.stencil[0].write & 0xff,
        }
    });
    let blend = ctx.blend.then(|| {
        let f = |x| blend_factor(x).unwrap_or(wgpu::BlendFactor::One);
        let op = |x| blend_op(x).unwrap_or(wgpu::BlendOperation::Add);
        wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: f(ctx.blend_func[0]),
                dst_factor: f(ctx.blend_func[1]),
                operation: op(ctx.blend_eq[0]),
            },
            alpha: wgpu::BlendComponent {
                src_factor: f(ctx.blend_func[2]),
                dst_factor: f(ctx.blend_func[3]),
                operation: op(ctx.blend_eq[1]),
            },
        }
    });
    let mut write_mask = wgpu::ColorWrites::empty();
    for (bit, on) in
        [wgpu::ColorWrites::RED, wgpu::ColorWrites::GREEN, wgpu::ColorWrites::BLUE, wgpu::ColorWrites::ALPHA]
            .into_iter()
            .zip(ctx.color_mask)
    {
        if on {
            write_mask |= bit;
        }
    }
    let bias = (ctx.polygon_offset_fill && triangles && target.depth.is_some()).then(|| {
        // GL's units are in minimum resolvable depth steps, as Vulkan's constant factor is.
        (ctx.polygon_offset[0].to_bits(), ctx.polygon_offset[1] as i32)
    });
    RasterState {
        topology,
        strip_index: None,
        front_ccw: ctx.front_face == CCW,
        cull: cull.flatten(),
        depth,
        stencil,
        bias,
        blend,
        write_mask,
    }
}

/// Commands that only touch one context's state.
fn ctx_command(ctx: &mut Context, gpu: &Gpu, uid: u64, cmd: Command<'_>) -> Option<Reply> {
    use Command as C;
    let op = cmd.opcode();
    match cmd {
        C::GetError {} => {
            let e = ctx.error;
            ctx.error = NO_ERROR;
            return Some(Reply::GetError(e));
        }
        C::Enable { cap } | C::Disable { cap } => {
            let on = matches!(cmd, C::Enable { .. });
            match ctx.cap(cap) {
                Some(flag) => *flag = on,
                None => ctx.err(INVALID_ENUM),
            }
        }
        C::IsEnabled { cap } => {
            return Some(Reply::IsEnabled(match ctx.cap(cap) {
                Some(f) => *f,
                None => {
                    ctx.err(INVALID_ENUM);
                    false
                }
            }));
        }
        C::Viewport { x, y, width, height } => {
            if width < 0 || height < 0 {
                ctx.err(INVALID_VALUE);
            } else {
                ctx.viewport = [x, y, width.min(MAX_TEXTURE as i32), height.min(MAX_TEXTURE as i32)];
            }
        }
        C::Scissor { x, y, width, height } => {
            if width < 0 || height < 0 {
                ctx.err(INVALID_VALUE);
            } else {
                ctx.scissor = [x, y, width, height];
            }
        }
        C::ClearColor { red, green, blue, alpha } => ctx.clear_color = [red, green, blue, alpha],
        C::ClearDepthf { depth } => ctx.clear_depth = depth.clamp(0.0, 1.0),
        C::ClearStencil { s } => ctx.clear_stencil = s,
        C::ColorMask { red, green, blue, alpha } => ctx.color_mask = [red, green, blue, alpha],
        C::DepthMask { flag } => ctx.depth_mask = flag,
        C::DepthFunc { func } => {
            if valid_func(func) {
                ctx.depth_func = func;
            } else {
                ctx.err(INVALID_ENUM);
            }
        }
        C::DepthRangef { near, far } => ctx.depth_range = [near.clamp(0.0, 1.0), far.clamp(0.0, 1.0)],
        C::CullFace { mode } => {
            if matches!(mode, FRONT | BACK | FRONT_AND_BACK) {
                ctx.cull_face = mode;
            } else {
                ctx.err(INVALID_ENUM);
            }
        }
        C::FrontFace { mode } => {
            if matches!(mode, CW | CCW) {
                ctx.front_face = mode;
            } else {
                ctx.err(INVALID_ENUM);
            }
        }
        C::BlendFunc { sfactor, dfactor } => set_blend(ctx, [sfactor, dfactor, sfactor, dfactor]),
        C::BlendFuncSeparate { src_rgb, dst_rgb, src_alpha, dst_alpha } => {
            set_blend(ctx, [src_rgb, dst_rgb, src_alpha, dst_alpha])
        }
        C::BlendEquation { mode } => {
            if blend_op(mode).is_some() {
                ctx.blend_eq = [mode, mode];
            } else {
                ctx.err(INVALID_ENUM);
            }
        }
        C::BlendEquationSeparate { mode_rgb, mode_alpha } => {
            if blend_op(mode_rgb).is_some() && blend_op(mode_alpha).is_some() {
                ctx.blend_eq = [mode_rgb, mode_alpha];
            } else {
                ctx.err(INVALID_ENUM);
            }
        }
        C::BlendColor { red, green, blue, alpha } => ctx.blend_color = [red, green, blue, alpha],
        C::StencilFunc { func, reference, mask } => set_stencil(
            ctx,
            FRONT_AND_BACK,
            |f| {
                f.func = func;
                f.reference = reference;
                f.mask = mask;
            },
            valid_func(func),
        ),
        C::StencilFuncSeparate { face, func, reference, mask } => set_stencil(
            ctx,
            face,
            |f| {
                f.func = func;
                f.reference = reference;
                f.mask = mask;
            },
            valid_func(func),
        ),
        C::StencilMask { mask } => set_stencil(ctx, FRONT_AND_BACK, |f| f.write = mask, true),
        C::StencilMaskSeparate { face, mask } => set_stencil(ctx, face, |f| f.write = mask, true),
        C::StencilOp { fail, zfail, zpass } => set_stencil(
            ctx,
            FRONT_AND_BACK,
            |f| {
                f.fail = fail;
                f.zfail = zfail;
                f.zpass = zpass;
            },
            [fail, zfail, zpass].iter().all(|&o| valid_stencil_op(o)),
        ),
        C::StencilOpSeparate { face, fail, zfail, zpass } => set_stencil(
            ctx,
            face,
            |f| {
                f.fail = fail;
                f.zfail = zfail;
                f.zpass = zpass;
            },
            [fail, zfail, zpass].iter().all(|&o| valid_stencil_op(o)),
        ),
        C::PolygonOffset { factor, units } => ctx.polygon_offset = [factor, units],
        C::LineWidth { width } => {
            if width <= 0.0 || width.is_nan() {
                ctx.err(INVALID_VALUE);
            } else {
                ctx.line_width = width;
            }
        }
        C::Hint { target, mode } => {
            if target != GENERATE_MIPMAP_HINT || !matches!(mode, FASTEST | NICEST | DONT_CARE) {
                ctx.err(INVALID_ENUM);
            } else {
                ctx.mipmap_hint = mode;
            }
        }
        C::SampleCoverage { .. } | C::ReleaseShaderCompiler {} => {}
        C::PixelStorei { pname, param } => match pname {
            UNPACK_ALIGNMENT | PACK_ALIGNMENT if matches!(param, 1 | 2 | 4 | 8) => {
                if pname == UNPACK_ALIGNMENT {
                    ctx.unpack_alignment = param;
                } else {
                    ctx.pack_alignment = param;
                }
            }
            UNPACK_ALIGNMENT | PACK_ALIGNMENT => ctx.err(INVALID_VALUE),
            _ => ctx.err(INVALID_ENUM),
        },
        // Buffers.
        C::GenBuffers { names } => {
            for n in names.iter().filter(|&n| n != 0) {
                ctx.buffers.entry(n).or_default();
            }
        }
        C::DeleteBuffers { names } => {
            for n in names.iter() {
                if ctx.buffers.remove(&n).is_some() {
                    if ctx.array_buffer == n {
                        ctx.array_buffer = 0;
                    }
                    if ctx.element_buffer == n {
                        ctx.element_buffer = 0;
                    }
                    for a in &mut ctx.attribs {
                        if a.buffer == n {
                            a.buffer = 0;
                        }
                    }
                }
            }
        }
        C::BindBuffer { target, buffer } => {
            match target {
                ARRAY_BUFFER => ctx.array_buffer = buffer,
                ELEMENT_ARRAY_BUFFER => ctx.element_buffer = buffer,
                _ => return err(ctx, INVALID_ENUM),
            }
            if buffer != 0 {
                ctx.buffers.entry(buffer).or_default();
            }
        }
        C::IsBuffer { name } => return Some(Reply::IsBuffer(name != 0 && ctx.buffers.contains_key(&name))),
        C::BufferData { target, size, data, usage } => {
            let Some(name) = ctx.buffer_binding(target) else { return err(ctx, INVALID_ENUM) };
            if !matches!(usage, STREAM_DRAW | STATIC_DRAW | DYNAMIC_DRAW) {
                return err(ctx, INVALID_ENUM);
            }
            if size < 0 || data.as_ref().is_some_and(|d| d.len() as i64 != size) {
                return err(ctx, INVALID_VALUE);
            }
            if name == 0 {
                return err(ctx, INVALID_OPERATION);
            }
            if size > (1 << 30) {
                return err(ctx, OUT_OF_MEMORY);
            }
            let b = ctx.buffers.entry(name).or_default();
            b.data = data.map(|d| d.as_bytes().to_vec()).unwrap_or_else(|| vec![0; size as usize]);
            b.usage = usage;
            b.generation += 1;
            let padded = (b.data.len() as u64).div_ceil(4).max(1) * 4;
            let gbuf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gl buffer"),
                size: padded,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let mut padded_data = b.data.clone();
            padded_data.resize(padded as usize, 0);
            gpu.queue.write_buffer(&gbuf, 0, &padded_data);
            b.gpu = Some(gbuf);
        }
        C::BufferSubData { target, offset, data } => {
            let Some(name) = ctx.buffer_binding(target) else { return err(ctx, INVALID_ENUM) };
            let Some(b) = ctx.buffers.get_mut(&name).filter(|_| name != 0) else { return err(ctx, INVALID_OPERATION) };
            let end = offset.checked_add(data.len() as i64);
            if offset < 0 || end.is_none_or(|e| e as usize > b.data.len()) {
                return err(ctx, INVALID_VALUE);
            }
            let off = offset as usize;
            b.data[off..off + data.len()].copy_from_slice(data.as_bytes());
            b.generation += 1;
            if let Some(g) = &b.gpu {
                // wgpu writes whole 4-byte words; widen the range using the shadow.
                let start = off / 4 * 4;
                let stop = ((off + data.len()).div_ceil(4) * 4).min(g.size() as usize);
                let mut words = b.data[start..stop.min(b.data.len())].to_vec();
                words.resize(stop - start, 0);
                if !words.is_empty() {
                    gpu.queue.write_buffer(g, start as u64, &words);
                }
            }
        }
        C::GetBufferParameteriv { target, pname } => {
            let Some(name) = ctx.buffer_binding(target) else {
                ctx.err(INVALID_ENUM);
                return Some(Reply::GetBufferParameteriv(0));
            };
            let Some(b) = ctx.buffers.get(&name).filter(|_| name != 0) else {
                ctx.err(INVALID_OPERATION);
                return Some(Reply::GetBufferParameteriv(0));
            };
            let v = match pname {
                BUFFER_SIZE => b.data.len() as i32,
                BUFFER_USAGE => {
                    if b.usage == 0 {
                        STATIC_DRAW as i32
                    } else {
                        b.usage as i32
                    }
                }
                _ => {
                    ctx.err(INVALID_ENUM);
                    0
                }
            };
            return Some(Reply::GetBufferParameteriv(v));
        }
        // Vertex attributes.
        C::VertexAttribPointer { index, size, attrib_type, normalized, stride, offset } => {
            if index as usize >= MAX_ATTRIBS || !(1..=4).contains(&size) || stride < 0 {
                return err(ctx, INVALID_VALUE);
            }
            if type_size(attrib_type).is_none() {
                return err(ctx, INVALID_ENUM);
            }
            // With no array buffer bound the pointer names a client-side array, whose bytes
            // arrive with `strataVertexAttribData` before each draw.
            let buffer = ctx.array_buffer;
            let a = &mut ctx.attribs[index as usize];
            a.size = size;
            a.ty = attrib_type;
            a.normalized = normalized;
            a.stride = stride;
            a.offset = offset;
            a.buffer = buffer;
        }
        C::VertexAttribData { index, data } => match ctx.attribs.get_mut(index as usize) {
            Some(a) if a.buffer == 0 => a.client = Some(data.as_bytes().to_vec()),
            Some(_) => ctx.err(INVALID_OPERATION),
            None => ctx.err(INVALID_VALUE),
        },
        C::EnableVertexAttribArray { index } | C::DisableVertexAttribArray { index } => {
            let on = matches!(cmd, C::EnableVertexAttribArray { .. });
            match ctx.attribs.get_mut(index as usize) {
                Some(a) => a.enabled = on,
                None => ctx.err(INVALID_VALUE),
            }
        }
        C::VertexAttrib1f { index, x } => set_attrib(ctx, index, &[x, 0.0, 0.0, 1.0]),
        C::VertexAttrib2f { index, x, y } => set_attrib(ctx, index, &[x, y, 0.0, 1.0]),
        C::VertexAttrib3f { index, x, y, z } => set_attrib(ctx, index, &[x, y, z, 1.0]),
        C::VertexAttrib4f { index, x, y, z, w } => set_attrib(ctx, index, &[x, y, z, w]),
        C::VertexAttrib1fv { index, values }
        | C::VertexAttrib2fv { index, values }
        | C::VertexAttrib3fv { index, values }
        | C::VertexAttrib4fv { index, values } => {
            let n = match op {
                strata_protocol::Opcode::VertexAttrib1fv => 1,
                strata_protocol::Opcode::VertexAttrib2fv => 2,
                strata_protocol::Opcode::VertexAttrib3fv => 3,
                _ => 4,
            };
            if values.len() < n {
                return err(ctx, INVALID_VALUE);
            }
            let mut v = [0.0, 0.0, 0.0, 1.0];
            for (i, x) in values.iter().take(n).enumerate() {
                v[i] = x;
            }
            set_attrib(ctx, index, &v);
        }
        C::GetVertexAttribfv { index, pname } => {
            let Some(a) = ctx.attribs.get(index as usize).cloned() else {
                ctx.err(INVALID_VALUE);
                return Some(Reply::GetVertexAttribfv(vec![]));
            };
            let v = match pname {
                CURRENT_VERTEX_ATTRIB => a.current.to_vec(),
                _ => match attrib_param(&a, pname) {
                    Some(i) => vec![i as f32],
                    None => {
                        ctx.err(INVALID_ENUM);
                        vec![]
                    }
                },
            };
            return Some(Reply::GetVertexAttribfv(v));
        }
        C::GetVertexAttribiv { index, pname } => {
            let Some(a) = ctx.attribs.get(index as usize).cloned() else {
                ctx.err(INVALID_VALUE);
                return Some(Reply::GetVertexAttribiv(vec![]));
            };
            let v = match pname {
                CURRENT_VERTEX_ATTRIB => a.current.iter().map(|f| *f as i32).collect(),
                _ => match attrib_param(&a, pname) {
                    Some(i) => vec![i],
                    None => {
                        ctx.err(INVALID_ENUM);
                        vec![]
                    }
                },
            };
            return Some(Reply::GetVertexAttribiv(v));
        }
        C::GetVertexAttribPointerv { index, pname } => {
            if pname != VERTEX_ATTRIB_ARRAY_POINTER {
                ctx.err(INVALID_ENUM);
                return Some(Reply::GetVertexAttribPointerv(0));
            }
            let v = ctx.attribs.get(index as usize).map(|a| a.offset).unwrap_or_else(|| {
                ctx.err(INVALID_VALUE);
                0
            });
            return Some(Reply::GetVertexAttribPointerv(v));
        }
        // Textures.
        C::GenTextures { names } => {
            for n in names.iter().filter(|&n| n != 0) {
                ctx.textures.entry(n).or_default();
            }
        }
        C::DeleteTextures { names } => {
            for n in names.iter().filter(|&n| n != 0) {
                if ctx.textures.remove(&n).is_some() {
                    for u in &mut ctx.units {
                        for s in u.iter_mut() {
                            if *s == n {
                                *s = 0;
                            }
                        }
                    }
                }
            }
        }
        C::ActiveTexture { texture } => {
            let unit = texture.wrapping_sub(TEXTURE0) as usize;
            if unit < MAX_UNITS {
                ctx.active_unit = unit;
            } else {
                ctx.err(INVALID_ENUM);
            }
        }
        C::BindTexture { target, texture } => {
            let Some(slot) = Context::texture_slot(target) else { return err(ctx, INVALID_ENUM) };
            if texture != 0 {
                let t = ctx.textures.entry(texture).or_default();
                if t.target == 0 {
                    t.target = target;
                } else if t.target != target {
                    return err(ctx, INVALID_OPERATION);
                }
            }
            ctx.units[ctx.active_unit][slot] = texture;
        }
        C::IsTexture { name } => return Some(Reply::IsTexture(ctx.textures.get(&name).is_some_and(|t| t.target != 0))),
        C::TexParameteri { target, pname, param } => tex_param(ctx, target, pname, param as f32),
        C::TexParameterf { target, pname, param } => tex_param(ctx, target, pname, param),
        C::TexParameteriv { target, pname, params } => match params.get(0) {
            Some(v) => tex_param(ctx, target, pname, v as f32),
            None => ctx.err(INVALID_VALUE),
        },
        C::TexParameterfv { target, pname, params } => match params.get(0) {
            Some(v) => tex_param(ctx, target, pname, v),
            None => ctx.err(INVALID_VALUE),
        },
        C::GetTexParameteriv { target, pname } | C::GetTexParameterfv { target, pname } => {
            let v =
                ctx.bound_texture(target).and_then(|n| ctx.textures.get(&n)).map(|t| t.sampler).and_then(
                    |s| match pname {
                        TEXTURE_MIN_FILTER => Some(s.min),
                        TEXTURE_MAG_FILTER => Some(s.mag),
                        TEXTURE_WRAP_S => Some(s.wrap_s),
                        TEXTURE_WRAP_T => Some(s.wrap_t),
                        _ => None,
                    },
                );
            let v = match v {
                Some(v) => vec![v as i32],
                None => {
                    ctx.err(INVALID_ENUM);
                    vec![]
                }
            };
            return Some(if matches!(cmd, C::GetTexParameteriv { .. }) {
                Reply::GetTexParameteriv(v)
            } else {
                Reply::GetTexParameterfv(v.into_iter().map(|x| x as f32).collect())
            });
        }
        C::TexImage2D { target, level, internalformat, width, height, border, format, pixel_type, pixels } => {
            let Some((face, cube)) = face_of(target) else { return err(ctx, INVALID_ENUM) };
            if bytes_per_pixel(format, pixel_type).is_none() {
                let known = matches!(format, RGBA | RGB | LUMINANCE | ALPHA | LUMINANCE_ALPHA)
                    && matches!(
                        pixel_type,
                        UNSIGNED_BYTE | UNSIGNED_SHORT_5_6_5 | UNSIGNED_SHORT_4_4_4_4 | UNSIGNED_SHORT_5_5_5_1
                    );
                return err(ctx, if known { INVALID_OPERATION } else { INVALID_ENUM });
            }
            if internalformat as u32 != format {
                return err(ctx, INVALID_OPERATION);
            }
            if !(0..=13).contains(&level)
                || width < 0
                || height < 0
                || border != 0
                || width as u32 > MAX_TEXTURE
                || height as u32 > MAX_TEXTURE
                || (cube && width != height)
            {
                return err(ctx, INVALID_VALUE);
            }
            let name = ctx.bound_texture(if cube { TEXTURE_CUBE_MAP } else { TEXTURE_2D })?;
            let align = ctx.unpack_alignment as usize;
            let Some(t) = ctx.textures.get_mut(&name).filter(|_| name != 0) else { return err(ctx, INVALID_OPERATION) };
            let (w, h, level) = (width as u32, height as u32, level as u32);
            let rgba = match &pixels {
                Some(p) => match to_rgba8(p.as_bytes(), w as usize, h as usize, format, pixel_type, align) {
                    Some(v) => Some(v),
                    None => return err(ctx, INVALID_OPERATION),
                },
                None => None,
            };
            if level == 0 {
                GlesExecutor::ensure_image(gpu, t, uid, w, h);
                t.format = format;
            }
            let Some(img) = &t.gpu else { return None };
            if (img.width >> level).max(1) != w.max(1) || (img.height >> level).max(1) != h.max(1) || level >= img.mips
            {
                // A level inconsistent with level 0 leaves the texture incomplete.
                t.defined[face as usize] &= !(1 << level);
                return None;
            }
            t.defined[face as usize] |= 1 << level;
            if w > 0 && h > 0 {
                let data = rgba.unwrap_or_else(|| vec![0; (w * h * 4) as usize]);
                gpu.queue.write_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: &img.texture,
                        mip_level: level,
                        origin: wgpu::Origin3d { x: 0, y: 0, z: face },
                        aspect: wgpu::TextureAspect::All,
                    },
                    &data,
                    wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * 4), rows_per_image: None },
                    wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
                );
            }
        }
        C::TexSubImage2D { target, level, xoffset, yoffset, width, height, format, pixel_type, pixels } => {
            let Some((face, cube)) = face_of(target) else { return err(ctx, INVALID_ENUM) };
            if bytes_per_pixel(format, pixel_type).is_none() {
                return err(ctx, INVALID_ENUM);
            }
            let align = ctx.unpack_alignment as usize;
            let name = ctx.bound_texture(if cube { TEXTURE_CUBE_MAP } else { TEXTURE_2D })?;
            let Some(t) = ctx.textures.get_mut(&name).filter(|_| name != 0) else { return err(ctx, INVALID_OPERATION) };
            let Some(img) = &t.gpu else { return err(ctx, INVALID_OPERATION) };
            if level < 0 || t.defined[face as usize] & (1 << level) == 0 {
                return err(ctx, INVALID_OPERATION);
            }
            if t.format != format {
                return err(ctx, INVALID_OPERATION);
            }
            let (lw, lh) = ((img.width >> level).max(1) as i32, (img.height >> level).max(1) as i32);
            if xoffset < 0 || yoffset < 0 || width < 0 || height < 0 || xoffset + width > lw || yoffset + height > lh {
                return err(ctx, INVALID_VALUE);
            }
            let Some(data) = to_rgba8(pixels.as_bytes(), width as usize, height as usize, format, pixel_type, align)
            else {
                return err(ctx, INVALID_OPERATION);
            };
            if width > 0 && height > 0 {
                gpu.queue.write_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: &img.texture,
                        mip_level: level as u32,
                        origin: wgpu::Origin3d { x: xoffset as u32, y: yoffset as u32, z: face },
                        aspect: wgpu::TextureAspect::All,
                    },
                    &data,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(width as u32 * 4),
                        rows_per_image: None,
                    },
                    wgpu::Extent3d { width: width as u32, height: height as u32, depth_or_array_layers: 1 },
                );
            }
        }
        C::CompressedTexImage2D { .. } | C::CompressedTexSubImage2D { .. } => ctx.err(INVALID_ENUM),
        // Renderbuffers and framebuffers.
        C::GenRenderbuffers { names } => {
            for n in names.iter().filter(|&n| n != 0) {
                ctx.renderbuffers.entry(n).or_default();
            }
        }
        C::DeleteRenderbuffers { names } => {
            for n in names.iter().filter(|&n| n != 0) {
                ctx.renderbuffers.remove(&n);
                if ctx.renderbuffer == n {
                    ctx.renderbuffer = 0;
                }
            }
        }
        C::BindRenderbuffer { target, renderbuffer } => {
            if target != RENDERBUFFER {
                return err(ctx, INVALID_ENUM);
            }
            if renderbuffer != 0 {
                ctx.renderbuffers.entry(renderbuffer).or_default();
            }
            ctx.renderbuffer = renderbuffer;
        }
        C::IsRenderbuffer { name } => {
            return Some(Reply::IsRenderbuffer(name != 0 && ctx.renderbuffers.contains_key(&name)))
        }
        C::RenderbufferStorage { target, internalformat, width, height } => {
            if target != RENDERBUFFER {
                return err(ctx, INVALID_ENUM);
            }
            let format = match internalformat {
                RGBA4 | RGB5_A1 | RGB565 | RGBA8_OES | RGB8_OES => COLOR_FORMAT,
                DEPTH_COMPONENT16 => wgpu::TextureFormat::Depth16Unorm,
                DEPTH_COMPONENT24_OES => wgpu::TextureFormat::Depth24Plus,
                DEPTH24_STENCIL8_OES => wgpu::TextureFormat::Depth24PlusStencil8,
                STENCIL_INDEX8 => wgpu::TextureFormat::Stencil8,
                _ => return err(ctx, INVALID_ENUM),
            };
            if width < 0 || height < 0 || width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
                return err(ctx, INVALID_VALUE);
            }
            let name = ctx.renderbuffer;
            let Some(rb) = ctx.renderbuffers.get_mut(&name).filter(|_| name != 0) else {
                return err(ctx, INVALID_OPERATION);
            };
            let tex = gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("renderbuffer"),
                size: wgpu::Extent3d {
                    width: (width as u32).max(1),
                    height: (height as u32).max(1),
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            });
            let view = tex.create_view(&Default::default());
            *rb = Renderbuffer {
                format: internalformat,
                width: width as u32,
                height: height as u32,
                gpu: Some((tex, view)),
                uid,
            };
        }
        C::GetRenderbufferParameteriv { target, pname } => {
            let rb = ctx.renderbuffers.get(&ctx.renderbuffer);
            let v = match (target, pname, rb) {
                (RENDERBUFFER, RENDERBUFFER_WIDTH, Some(rb)) => rb.width as i32,
                (RENDERBUFFER, RENDERBUFFER_HEIGHT, Some(rb)) => rb.height as i32,
                (RENDERBUFFER, RENDERBUFFER_INTERNAL_FORMAT, Some(rb)) => {
                    if rb.format == 0 {
                        RGBA4 as i32
                    } else {
                        rb.format as i32
                    }
                }
                (RENDERBUFFER, _, None) => {
                    ctx.err(INVALID_OPERATION);
                    0
                }
                _ => {
                    ctx.err(INVALID_ENUM);
                    0
                }
            };
            return Some(Reply::GetRenderbufferParameteriv(v));
        }
        C::GenFramebuffers { names } => {
            for n in names.iter().filter(|&n| n != 0) {
                ctx.framebuffers.entry(n).or_default();
            }
        }
        C::DeleteFramebuffers { names } => {
            for n in names.iter().filter(|&n| n != 0) {
                ctx.framebuffers.remove(&n);
                if ctx.framebuffer == n {
                    ctx.framebuffer = 0;
                }
            }
        }
        C::BindFramebuffer { target, framebuffer } => {
            if target != FRAMEBUFFER {
                return err(ctx, INVALID_ENUM);
            }
            if framebuffer != 0 {
                ctx.framebuffers.entry(framebuffer).or_default();
            }
            ctx.framebuffer = framebuffer;
        }
        C::IsFramebuffer { name } => {
            return Some(Reply::IsFramebuffer(name != 0 && ctx.framebuffers.contains_key(&name)))
        }
        C::FramebufferTexture2D { target, attachment, textarget, texture, level } => {
            if target != FRAMEBUFFER {
                return err(ctx, INVALID_ENUM);
            }
            let Some((face, _)) = face_of(textarget) else { return err(ctx, INVALID_ENUM) };
            if level != 0 && texture != 0 {
                return err(ctx, INVALID_VALUE);
            }
            if texture != 0 && !ctx.textures.contains_key(&texture) {
                return err(ctx, INVALID_OPERATION);
            }
            let a = if texture == 0 { Attachment::None } else { Attachment::Texture { name: texture, level: 0, face } };
            set_attachment(ctx, attachment, a);
        }
        C::FramebufferRenderbuffer { target, attachment, renderbuffertarget, renderbuffer } => {
            if target != FRAMEBUFFER || renderbuffertarget != RENDERBUFFER {
                return err(ctx, INVALID_ENUM);
            }
            if renderbuffer != 0 && !ctx.renderbuffers.contains_key(&renderbuffer) {
                return err(ctx, INVALID_OPERATION);
            }
            let a = if renderbuffer == 0 { Attachment::None } else { Attachment::Renderbuffer(renderbuffer) };
            set_attachment(ctx, attachment, a);
        }
        C::GetFramebufferAttachmentParameteriv { target, attachment, pname } => {
            let fb = ctx.framebuffers.get(&ctx.framebuffer).cloned();
            let a = match (target, fb, attachment) {
                (FRAMEBUFFER, Some(fb), COLOR_ATTACHMENT0) => fb.color,
                (FRAMEBUFFER, Some(fb), DEPTH_ATTACHMENT) => fb.depth,
                (FRAMEBUFFER, Some(fb), STENCIL_ATTACHMENT) => fb.stencil,
                (FRAMEBUFFER, None, _) => {
                    ctx.err(INVALID_OPERATION);
                    return Some(Reply::GetFramebufferAttachmentParameteriv(0));
                }
                _ => {
                    ctx.err(INVALID_ENUM);
                    return Some(Reply::GetFramebufferAttachmentParameteriv(0));
                }
            };
            let v = match (pname, a) {
                (FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, Attachment::None) => NONE as i32,
                (FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, Attachment::Texture { .. }) => TEXTURE as i32,
                (FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, Attachment::Renderbuffer(_)) => RENDERBUFFER as i32,
                (FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, Attachment::Texture { name, .. }) => name as i32,
                (FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, Attachment::Renderbuffer(n)) => n as i32,
                (FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, Attachment::Texture { level, .. }) => level as i32,
                (FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE, Attachment::Texture { face, .. }) => {
                    if face == 0 {
                        0
                    } else {
                        (TEXTURE_CUBE_MAP_POSITIVE_X + face) as i32
                    }
                }
                _ => {
                    ctx.err(INVALID_ENUM);
                    0
                }
            };
            return Some(Reply::GetFramebufferAttachmentParameteriv(v));
        }
        // Shaders and programs.
        C::CreateShader { shader_type, name } => {
            let stage = match shader_type {
                VERTEX_SHADER => Stage::Vertex,
                FRAGMENT_SHADER => Stage::Fragment,
                _ => return err(ctx, INVALID_ENUM),
            };
            if name == 0 || ctx.shaders.contains_key(&name) || ctx.programs.contains_key(&name) {
                return err(ctx, INVALID_VALUE);
            }
            ctx.shaders.insert(
                name,
                ShaderObj {
                    stage,
                    source: String::new(),
                    compiled: None,
                    compiled_ok: false,
                    log: String::new(),
                    delete_pending: false,
                },
            );
        }
        C::CreateProgram { name } => {
            if name == 0 || ctx.shaders.contains_key(&name) || ctx.programs.contains_key(&name) {
                return err(ctx, INVALID_VALUE);
            }
            ctx.programs.insert(name, Program::default());
        }
        C::ShaderSource { shader, source } => match ctx.shaders.get_mut(&shader) {
            Some(s) => s.source = source.as_str().to_string(),
            None => return err(ctx, shader_or_program_error(ctx, shader)),
        },
        C::CompileShader { shader } => match ctx.shaders.get_mut(&shader) {
            Some(s) => match glsl::compile(s.stage, &s.source) {
                Ok(c) => {
                    s.compiled = Some(c);
                    s.compiled_ok = true;
                    s.log.clear();
                }
                Err(log) => {
                    s.compiled_ok = false;
                    s.log = log;
                }
            },
            None => return err(ctx, shader_or_program_error(ctx, shader)),
        },
        C::ShaderBinary { .. } => ctx.err(INVALID_ENUM),
        C::DeleteShader { shader } => {
            if shader == 0 {
                return None;
            }
            if !ctx.shaders.contains_key(&shader) {
                return err(ctx, shader_or_program_error(ctx, shader));
            }
            if ctx.programs.values().any(|p| p.attached.contains(&shader)) {
                if let Some(s) = ctx.shaders.get_mut(&shader) {
                    s.delete_pending = true;
                }
            } else {
                ctx.shaders.remove(&shader);
            }
        }
        C::DeleteProgram { program } => {
            if program == 0 {
                return None;
            }
            if !ctx.programs.contains_key(&program) {
                return err(ctx, shader_or_program_error(ctx, program));
            }
            if ctx.program == program {
                if let Some(p) = ctx.programs.get_mut(&program) {
                    p.delete_pending = true;
                }
            } else if let Some(p) = ctx.programs.remove(&program) {
                release_shaders(ctx, &p.attached);
            }
        }
        C::AttachShader { program, shader } | C::DetachShader { program, shader } => {
            let attach = matches!(cmd, C::AttachShader { .. });
            if !ctx.programs.contains_key(&program) {
                return err(ctx, shader_or_program_error(ctx, program));
            }
            let Some(stage) = ctx.shaders.get(&shader).map(|s| s.stage) else {
                return err(ctx, shader_or_program_error(ctx, shader));
            };
            let same_stage =
                ctx.programs[&program].attached.iter().any(|s| ctx.shaders.get(s).is_some_and(|x| x.stage == stage));
            let p = ctx.programs.get_mut(&program).expect("checked");
            if attach {
                if p.attached.contains(&shader) || same_stage {
                    return err(ctx, INVALID_OPERATION);
                }
                p.attached.push(shader);
            } else {
                let Some(i) = p.attached.iter().position(|&s| s == shader) else { return err(ctx, INVALID_OPERATION) };
                p.attached.remove(i);
                release_shaders(ctx, &[shader]);
            }
        }
        C::BindAttribLocation { program, index, name } => {
            if index as usize >= MAX_ATTRIBS {
                return err(ctx, INVALID_VALUE);
            }
            if name.as_str().starts_with("gl_") {
                return err(ctx, INVALID_OPERATION);
            }
            match ctx.programs.get_mut(&program) {
                Some(p) => {
                    p.bindings.insert(name.as_str().to_string(), index);
                }
                None => return err(ctx, shader_or_program_error(ctx, program)),
            }
        }
        C::UseProgram { program } => {
            if program != 0 && !ctx.programs.get(&program).is_some_and(|p| p.link_ok) {
                return err(
                    ctx,
                    if ctx.programs.contains_key(&program) || ctx.shaders.contains_key(&program) {
                        INVALID_OPERATION
                    } else {
                        INVALID_VALUE
                    },
                );
            }
            let old = ctx.program;
            ctx.program = program;
            if old != program && ctx.programs.get(&old).is_some_and(|p| p.delete_pending) {
                if let Some(p) = ctx.programs.remove(&old) {
                    release_shaders(ctx, &p.attached);
                }
            }
        }
        C::ValidateProgram { program } => match ctx.programs.get_mut(&program) {
            Some(p) => p.validated = p.link_ok,
            None => return err(ctx, shader_or_program_error(ctx, program)),
        },
        C::IsShader { name } => return Some(Reply::IsShader(ctx.shaders.contains_key(&name))),
        C::IsProgram { name } => return Some(Reply::IsProgram(ctx.programs.contains_key(&name))),
        C::GetShaderiv { shader, pname } => {
            let v = match ctx.shaders.get(&shader) {
                Some(s) => match pname {
                    SHADER_TYPE => {
                        Some(if s.stage == Stage::Vertex { VERTEX_SHADER as i32 } else { FRAGMENT_SHADER as i32 })
                    }
                    COMPILE_STATUS => Some(i32::from(s.compiled_ok)),
                    DELETE_STATUS => Some(i32::from(s.delete_pending)),
                    INFO_LOG_LENGTH => Some(if s.log.is_empty() { 0 } else { s.log.len() as i32 + 1 }),
                    SHADER_SOURCE_LENGTH => Some(if s.source.is_empty() { 0 } else { s.source.len() as i32 + 1 }),
                    _ => {
                        ctx.err(INVALID_ENUM);
                        None
                    }
                },
                None => {
                    let e = shader_or_program_error(ctx, shader);
                    ctx.err(e);
                    None
                }
            };
            return Some(Reply::GetShaderiv(v.unwrap_or(0)));
        }
        C::GetShaderInfoLog { shader } => {
            return Some(Reply::GetShaderInfoLog(with_shader(ctx, shader, String::new(), |s| s.log.clone())));
        }
        C::GetShaderSource { shader } => {
            return Some(Reply::GetShaderSource(with_shader(ctx, shader, String::new(), |s| s.source.clone())));
        }
        C::GetShaderPrecisionFormat { shader_type, precision_type } => {
            if !matches!(shader_type, VERTEX_SHADER | FRAGMENT_SHADER)
                || !(LOW_FLOAT..=HIGH_INT).contains(&precision_type)
            {
                ctx.err(INVALID_ENUM);
                return Some(Reply::GetShaderPrecisionFormat(([0, 0], 0)));
            }
            let v = if precision_type <= LOW_FLOAT + 2 { ([127, 127], 23) } else { ([31, 30], 0) };
            return Some(Reply::GetShaderPrecisionFormat(v));
        }
        C::GetProgramiv { program, pname } => {
            let v = match ctx.programs.get(&program) {
                Some(p) => {
                    let linked = p.linked.as_ref();
                    match pname {
                        LINK_STATUS => Some(i32::from(p.link_ok)),
                        DELETE_STATUS => Some(i32::from(p.delete_pending)),
                        VALIDATE_STATUS => Some(i32::from(p.validated)),
                        INFO_LOG_LENGTH => Some(if p.log.is_empty() { 0 } else { p.log.len() as i32 + 1 }),
                        ATTACHED_SHADERS => Some(p.attached.len() as i32),
                        ACTIVE_ATTRIBUTES => Some(linked.map_or(0, |l| l.info.attributes.len() as i32)),
                        ACTIVE_UNIFORMS => Some(linked.map_or(0, |l| l.info.uniforms.len() as i32)),
                        ACTIVE_ATTRIBUTE_MAX_LENGTH => Some(linked.map_or(0, |l| {
                            l.info.attributes.iter().map(|a| a.0.name.len() as i32 + 1).max().unwrap_or(0)
                        })),
                        ACTIVE_UNIFORM_MAX_LENGTH => Some(linked.map_or(0, |l| {
                            l.info
                                .uniforms
                                .iter()
                                .map(|u| u.name.len() as i32 + if u.is_array { 4 } else { 1 })
                                .max()
                                .unwrap_or(0)
                        })),
                        _ => {
                            ctx.err(INVALID_ENUM);
                            None
                        }
                    }
                }
                None => {
                    let e = shader_or_program_error(ctx, program);
                    ctx.err(e);
                    None
                }
            };
            return Some(Reply::GetProgramiv(v.unwrap_or(0)));
        }
        C::GetProgramInfoLog { program } => {
            return Some(Reply::GetProgramInfoLog(with_program(ctx, program, String::new(), |p| p.log.clone())));
        }
        C::GetAttachedShaders { program } => {
            return Some(Reply::GetAttachedShaders(with_program(ctx, program, vec![], |p| p.attached.clone())));
        }
        C::GetAttribLocation { program, name } => {
            let v = match ctx.programs.get(&program) {
                Some(p) => match &p.linked {
                    Some(l) => l.info.attributes.iter().find(|a| a.0.name == name.as_str()).map_or(-1, |a| a.1 as i32),
                    None => {
                        ctx.err(INVALID_OPERATION);
                        -1
                    }
                },
                None => {
                    let e = shader_or_program_error(ctx, program);
                    ctx.err(e);
                    -1
                }
            };
            return Some(Reply::GetAttribLocation(v));
        }
        C::GetUniformLocation { program, name } => {
            let v = match ctx.programs.get(&program) {
                Some(p) => match &p.linked {
                    Some(l) => uniform_location(l, name.as_str()),
                    None => {
                        ctx.err(INVALID_OPERATION);
                        -1
                    }
                },
                None => {
                    let e = shader_or_program_error(ctx, program);
                    ctx.err(e);
                    -1
                }
            };
            return Some(Reply::GetUniformLocation(v));
        }
        C::GetActiveAttrib { program, index } | C::GetActiveUniform { program, index } => {
            let uniform = matches!(cmd, C::GetActiveUniform { .. });
            let v = match ctx.programs.get(&program).and_then(|p| p.linked.clone()) {
                Some(l) => {
                    let v = if uniform {
                        l.info.uniforms.get(index as usize).map(|u| ActiveVariable {
                            size: u.len as i32,
                            ty: u.ty.gl_enum(),
                            name: if u.is_array { format!("{}[0]", u.name) } else { u.name.clone() },
                        })
                    } else {
                        l.info.attributes.get(index as usize).map(|(a, _)| ActiveVariable {
                            size: 1,
                            ty: a.ty.gl_enum(),
                            name: a.name.clone(),
                        })
                    };
                    if v.is_none() {
                        ctx.err(INVALID_VALUE);
                    }
                    v
                }
                None => {
                    let e = if ctx.programs.contains_key(&program) {
                        INVALID_VALUE
                    } else {
                        shader_or_program_error(ctx, program)
                    };
                    ctx.err(e);
                    None
                }
            };
            return Some(if uniform { Reply::GetActiveUniform(v) } else { Reply::GetActiveAttrib(v) });
        }
        C::Uniform1f { location, x } => set_uniform(ctx, location, 1, 0, Vals::F(&[x])),
        C::Uniform2f { location, x, y } => set_uniform(ctx, location, 2, 0, Vals::F(&[x, y])),
        C::Uniform3f { location, x, y, z } => set_uniform(ctx, location, 3, 0, Vals::F(&[x, y, z])),
        C::Uniform4f { location, x, y, z, w } => set_uniform(ctx, location, 4, 0, Vals::F(&[x, y, z, w])),
        C::Uniform1i { location, x } => set_uniform(ctx, location, 1, 0, Vals::I(&[x])),
        C::Uniform2i { location, x, y } => set_uniform(ctx, location, 2, 0, Vals::I(&[x, y])),
        C::Uniform3i { location, x, y, z } => set_uniform(ctx, location, 3, 0, Vals::I(&[x, y, z])),
        C::Uniform4i { location, x, y, z, w } => set_uniform(ctx, location, 4, 0, Vals::I(&[x, y, z, w])),
        C::Uniform1fv { location, values } => set_uniform(ctx, location, 1, 0, Vals::F(&values.to_vec())),
        C::Uniform2fv { location, values } => set_uniform(ctx, location, 2, 0, Vals::F(&values.to_vec())),
        C::Uniform3fv { location, values } => set_uniform(ctx, location, 3, 0, Vals::F(&values.to_vec())),
        C::Uniform4fv { location, values } => set_uniform(ctx, location, 4, 0, Vals::F(&values.to_vec())),
        C::Uniform1iv { location, values } => set_uniform(ctx, location, 1, 0, Vals::I(&values.to_vec())),
        C::Uniform2iv { location, values } => set_uniform(ctx, location, 2, 0, Vals::I(&values.to_vec())),
        C::Uniform3iv { location, values } => set_uniform(ctx, location, 3, 0, Vals::I(&values.to_vec())),
        C::Uniform4iv { location, values } => set_uniform(ctx, location, 4, 0, Vals::I(&values.to_vec())),
        C::UniformMatrix2fv { location, transpose, values } => matrix(ctx, location, transpose, 2, &values.to_vec()),
        C::UniformMatrix3fv { location, transpose, values } => matrix(ctx, location, transpose, 3, &values.to_vec()),
        C::UniformMatrix4fv { location, transpose, values } => matrix(ctx, location, transpose, 4, &values.to_vec()),
        C::GetUniformfv { program, location } | C::GetUniformiv { program, location } => {
            let ints = matches!(cmd, C::GetUniformiv { .. });
            let vals = get_uniform(ctx, program, location);
            return Some(if ints {
                Reply::GetUniformiv(vals.iter().map(|v| *v as i32).collect())
            } else {
                Reply::GetUniformfv(vals)
            });
        }
        // Queries.
        C::GetString { name } => {
            let s = match name {
                VENDOR => Some("Strata".to_string()),
                RENDERER => Some(format!("Strata on {}", gpu.info.name)),
                VERSION => Some(format!("OpenGL ES 2.0 Strata {}", env!("CARGO_PKG_VERSION"))),
                SHADING_LANGUAGE_VERSION => Some("OpenGL ES GLSL ES 1.00".to_string()),
                EXTENSIONS => Some(EXTENSIONS_STRING.to_string()),
                _ => {
                    ctx.err(INVALID_ENUM);
                    None
                }
            };
            return Some(Reply::GetString(s));
        }
        C::GetIntegerv { pname } | C::GetFloatv { pname } | C::GetBooleanv { pname } => {
            let v = get_state(ctx, gpu, pname);
            if v.is_none() {
                ctx.err(INVALID_ENUM);
            }
            let v = v.unwrap_or(Value::Ints(vec![]));
            return Some(match cmd {
                C::GetIntegerv { .. } => Reply::GetIntegerv(match v {
                    Value::Ints(v) => v,
                    Value::Floats(f)
                        if matches!(pname, COLOR_CLEAR_VALUE | BLEND_COLOR | DEPTH_RANGE | DEPTH_CLEAR_VALUE) =>
                    {
                        f.iter().map(|x| (f64::from(x.clamp(-1.0, 1.0)) * f64::from(i32::MAX)).round() as i32).collect()
                    }
                    Value::Floats(f) => f.iter().map(|x| x.round() as i32).collect(),
                    Value::Bools(b) => b.iter().map(|&x| i32::from(x)).collect(),
                }),
                C::GetFloatv { .. } => Reply::GetFloatv(match v {
                    Value::Ints(v) => v.iter().map(|&x| x as f32).collect(),
                    Value::Floats(f) => f,
                    Value::Bools(b) => b.iter().map(|&x| f32::from(u8::from(x))).collect(),
                }),
                _ => Reply::GetBooleanv(match v {
                    Value::Ints(v) => v.iter().map(|&x| x != 0).collect(),
                    Value::Floats(f) => f.iter().map(|&x| x != 0.0).collect(),
                    Value::Bools(b) => b,
                }),
            });
        }
        other if other.opcode().is_sync() => {
            return Some(Reply::Unsupported(format!("{} is not implemented", other.opcode().name())));
        }
        _ => {}
    }
    None
}

/// Extensions advertised in `GL_EXTENSIONS`: only what the executor implements.
const EXTENSIONS_STRING: &str = "GL_OES_element_index_uint GL_OES_vertex_half_float GL_OES_texture_npot \
GL_OES_rgb8_rgba8 GL_OES_depth24 GL_OES_packed_depth_stencil GL_OES_depth_texture";

fn err(ctx: &mut Context, e: u32) -> Option<Reply> {
    ctx.err(e);
    None
}

fn shader_or_program_error(ctx: &Context, name: u32) -> u32 {
    if ctx.shaders.contains_key(&name) || ctx.programs.contains_key(&name) {
        INVALID_OPERATION
    } else {
        INVALID_VALUE
    }
}

/// `f` of shader `name`, or `default` after recording the error GL gives for a bad name.
fn with_shader<T>(ctx: &mut Context, name: u32, default: T, f: impl FnOnce(&ShaderObj) -> T) -> T {
    match ctx.shaders.get(&name) {
        Some(s) => f(s),
        None => {
            let e = shader_or_program_error(ctx, name);
            ctx.err(e);
            default
        }
    }
}

/// `f` of program `name`, or `default` after recording the error GL gives for a bad name.
fn with_program<T>(ctx: &mut Context, name: u32, default: T, f: impl FnOnce(&Program) -> T) -> T {
    match ctx.programs.get(&name) {
        Some(p) => f(p),
        None => {
            let e = shader_or_program_error(ctx, name);
            ctx.err(e);
            default
        }
    }
}

fn release_shaders(ctx: &mut Context, shaders: &[u32]) {
    for s in shaders {
        let still = ctx.programs.values().any(|p| p.attached.contains(s));
        if !still && ctx.shaders.get(s).is_some_and(|x| x.delete_pending) {
            ctx.shaders.remove(s);
        }
    }
}

fn set_blend(ctx: &mut Context, f: [u32; 4]) {
    if f.iter().all(|&x| blend_factor(x).is_some()) && f[1] != SRC_ALPHA_SATURATE && f[3] != SRC_ALPHA_SATURATE {
        ctx.blend_func = f;
    } else {
        ctx.err(INVALID_ENUM);
    }
}

fn set_stencil(ctx: &mut Context, face: u32, f: impl Fn(&mut StencilFace), valid: bool) {
    if !valid {
        return ctx.err(INVALID_ENUM);
    }
    match face {
        FRONT => f(&mut ctx.stencil[0]),
        BACK => f(&mut ctx.stencil[1]),
        FRONT_AND_BACK => {
            f(&mut ctx.stencil[0]);
            f(&mut ctx.stencil[1]);
        }
        _ => ctx.err(INVALID_ENUM),
    }
}

fn set_attrib(ctx: &mut Context, index: u32, v: &[f32; 4]) {
    match ctx.attribs.get_mut(index as usize) {
        Some(a) => a.current = *v,
        None => ctx.err(INVALID_VALUE),
    }
}

fn attrib_param(a: &Attrib, pname: u32) -> Option<i32> {
    Some(match pname {
        VERTEX_ATTRIB_ARRAY_ENABLED => i32::from(a.enabled),
        VERTEX_ATTRIB_ARRAY_SIZE => a.size,
        VERTEX_ATTRIB_ARRAY_STRIDE => a.stride,
        VERTEX_ATTRIB_ARRAY_TYPE => a.ty as i32,
        VERTEX_ATTRIB_ARRAY_NORMALIZED => i32::from(a.normalized),
        VERTEX_ATTRIB_ARRAY_BUFFER_BINDING => a.buffer as i32,
        _ => return None,
    })
}

fn tex_param(ctx: &mut Context, target: u32, pname: u32, v: f32) {
    let Some(name) = ctx.bound_texture(target) else { return ctx.err(INVALID_ENUM) };
    let v = v as u32;
    let ok = match pname {
        TEXTURE_MIN_FILTER => matches!(
            v,
            NEAREST
                | LINEAR
                | NEAREST_MIPMAP_NEAREST
                | LINEAR_MIPMAP_NEAREST
                | NEAREST_MIPMAP_LINEAR
                | LINEAR_MIPMAP_LINEAR
        ),
        TEXTURE_MAG_FILTER => matches!(v, NEAREST | LINEAR),
        TEXTURE_WRAP_S | TEXTURE_WRAP_T => matches!(v, REPEAT | CLAMP_TO_EDGE | MIRRORED_REPEAT),
        _ => false,
    };
    if !ok {
        return ctx.err(INVALID_ENUM);
    }
    let Some(t) = ctx.textures.get_mut(&name).filter(|_| name != 0) else { return ctx.err(INVALID_OPERATION) };
    match pname {
        TEXTURE_MIN_FILTER => t.sampler.min = v,
        TEXTURE_MAG_FILTER => t.sampler.mag = v,
        TEXTURE_WRAP_S => t.sampler.wrap_s = v,
        _ => t.sampler.wrap_t = v,
    }
}

fn set_attachment(ctx: &mut Context, attachment: u32, a: Attachment) {
    let Some(fb) = ctx.framebuffers.get_mut(&ctx.framebuffer).filter(|_| ctx.framebuffer != 0) else {
        return ctx.err(INVALID_OPERATION);
    };
    match attachment {
        COLOR_ATTACHMENT0 => fb.color = a,
        DEPTH_ATTACHMENT => fb.depth = a,
        STENCIL_ATTACHMENT => fb.stencil = a,
        _ => ctx.err(INVALID_ENUM),
    }
}

fn uniform_location(l: &LinkedProgram, name: &str) -> i32 {
    let (base, index) = match name.strip_suffix(']').and_then(|n| n.rsplit_once('[')) {
        Some((b, i)) => match i.parse::<u32>() {
            Ok(i) => (b, i),
            Err(_) => return -1,
        },
        None => (name, 0),
    };
    let Some(u) = l.info.uniforms.iter().position(|u| u.name == base) else { return -1 };
    if index >= l.info.uniforms[u].len || (index > 0 && !l.info.uniforms[u].is_array) {
        return -1;
    }
    l.locations.iter().position(|&(i, e)| i == u && e == index).map_or(-1, |p| p as i32)
}

enum Vals<'a> {
    F(&'a [f32]),
    I(&'a [i32]),
}

fn set_uniform(ctx: &mut Context, location: i32, n: usize, columns: usize, vals: Vals<'_>) {
    if location == -1 {
        return;
    }
    let program = ctx.program;
    let Some(p) = ctx.programs.get_mut(&program) else { return ctx.err(INVALID_OPERATION) };
    let Some(l) = p.linked.clone() else { return ctx.err(INVALID_OPERATION) };
    let Some(&(ui, element)) = usize::try_from(location).ok().and_then(|i| l.locations.get(i)) else {
        return ctx.err(INVALID_OPERATION);
    };
    let u = &l.info.uniforms[ui];
    let len = match &vals {
        Vals::F(v) => v.len(),
        Vals::I(v) => v.len(),
    };
    let per = if columns > 0 { columns * columns } else { n };
    let expect_cols = u.ty.columns();
    if (columns > 0) != (expect_cols > 0)
        || (columns > 0 && columns != expect_cols)
        || (columns == 0 && u.ty.components() != n)
    {
        return ctx.err(INVALID_OPERATION);
    }
    let ok_kind =
        matches!((&vals, u.ty.scalar()), (_, Scalar::Bool) | (Vals::F(_), Scalar::Float) | (Vals::I(_), Scalar::Int));
    if !ok_kind || len % per != 0 || len == 0 {
        return ctx.err(if len == 0 { INVALID_VALUE } else { INVALID_OPERATION });
    }
    let count = len / per;
    if count > 1 && !u.is_array {
        return ctx.err(INVALID_OPERATION);
    }
    if let Some(si) = u.sampler {
        let Vals::I(v) = vals else { return ctx.err(INVALID_OPERATION) };
        if v[0] < 0 || v[0] as usize >= MAX_UNITS {
            return ctx.err(INVALID_VALUE);
        }
        p.units[si] = v[0] as u32;
        return;
    }
    let count = count.min((u.len - element) as usize);
    for e in 0..count {
        let base = (u.offset + (element + e as u32) * u.stride) as usize;
        for c in 0..per {
            // Matrix columns are 16 bytes apart in std140; vectors are packed.
            let at = scalar_offset(base, c, columns);
            let bytes = match (&vals, u.ty.scalar()) {
                (Vals::F(v), Scalar::Bool) => i32::from(v[e * per + c] != 0.0).to_ne_bytes(),
                (Vals::I(v), Scalar::Bool) => i32::from(v[e * per + c] != 0).to_ne_bytes(),
                (Vals::F(v), _) => v[e * per + c].to_ne_bytes(),
                (Vals::I(v), _) => v[e * per + c].to_ne_bytes(),
            };
            if let Some(dst) = p.data.get_mut(at..at + 4) {
                dst.copy_from_slice(&bytes);
            }
        }
    }
}

/// Byte offset of scalar `c` of a uniform element at `base`; matrix columns are 16 bytes apart
/// in std140, vectors are packed.
fn scalar_offset(base: usize, c: usize, columns: usize) -> usize {
    match c.checked_div(columns) {
        Some(col) => base + col * 16 + (c % columns) * 4,
        None => base + c * 4,
    }
}

fn matrix(ctx: &mut Context, location: i32, transpose: bool, n: usize, v: &[f32]) {
    if transpose {
        return ctx.err(INVALID_VALUE);
    }
    set_uniform(ctx, location, n, n, Vals::F(v));
}

fn get_uniform(ctx: &mut Context, program: u32, location: i32) -> Vec<f32> {
    let Some(p) = ctx.programs.get(&program) else {
        let e = shader_or_program_error(ctx, program);
        ctx.err(e);
        return vec![];
    };
    let Some(l) = &p.linked else {
        ctx.err(INVALID_OPERATION);
        return vec![];
    };
    let Some(&(ui, element)) = usize::try_from(location).ok().and_then(|i| l.locations.get(i)) else {
        ctx.err(INVALID_OPERATION);
        return vec![];
    };
    let u = &l.info.uniforms[ui];
    if let Some(si) = u.sampler {
        return vec![p.units[si] as f32];
    }
    let cols = u.ty.columns();
    let per = if cols > 0 { cols * cols } else { u.ty.components() };
    let base = (u.offset + element * u.stride) as usize;
    (0..per)
        .map(|c| {
            let at = scalar_offset(base, c, cols);
            let b = [p.data[at], p.data[at + 1], p.data[at + 2], p.data[at + 3]];
            match u.ty.scalar() {
                Scalar::Float => f32::from_ne_bytes(b),
                _ => i32::from_ne_bytes(b) as f32,
            }
        })
        .collect()
}

fn get_state(ctx: &Context, gpu: &Gpu, pname: u32) -> Option<Value> {
    use Value::*;
    let b = |x: bool| Bools(vec![x]);
    let i = |x: i32| Ints(vec![x]);
    Some(match pname {
        VIEWPORT => Ints(ctx.viewport.to_vec()),
        SCISSOR_BOX => Ints(ctx.scissor.to_vec()),
        COLOR_CLEAR_VALUE => Floats(ctx.clear_color.to_vec()),
        BLEND_COLOR => Floats(ctx.blend_color.to_vec()),
        DEPTH_CLEAR_VALUE => Floats(vec![ctx.clear_depth]),
        DEPTH_RANGE => Floats(ctx.depth_range.to_vec()),
        LINE_WIDTH => Floats(vec![ctx.line_width]),
        ALIASED_LINE_WIDTH_RANGE | ALIASED_POINT_SIZE_RANGE => Floats(vec![1.0, 1.0]),
        COLOR_WRITEMASK => Bools(ctx.color_mask.to_vec()),
        DEPTH_WRITEMASK => b(ctx.depth_mask),
        DEPTH_FUNC => i(ctx.depth_func as i32),
        CULL_FACE_MODE => i(ctx.cull_face as i32),
        FRONT_FACE => i(ctx.front_face as i32),
        CULL_FACE
        | BLEND
        | DEPTH_TEST
        | SCISSOR_TEST
        | STENCIL_TEST
        | POLYGON_OFFSET_FILL
        | DITHER
        | SAMPLE_COVERAGE
        | SAMPLE_ALPHA_TO_COVERAGE => {
            let mut c = Context::new(ctx.config);
            c.cull = ctx.cull;
            let v = match pname {
                CULL_FACE => ctx.cull,
                BLEND => ctx.blend,
                DEPTH_TEST => ctx.depth_test,
                SCISSOR_TEST => ctx.scissor_test,
                STENCIL_TEST => ctx.stencil_test,
                POLYGON_OFFSET_FILL => ctx.polygon_offset_fill,
                DITHER => ctx.dither,
                SAMPLE_COVERAGE => ctx.sample_coverage,
                _ => ctx.alpha_to_coverage,
            };
            b(v)
        }
        ARRAY_BUFFER_BINDING => i(ctx.array_buffer as i32),
        ELEMENT_ARRAY_BUFFER_BINDING => i(ctx.element_buffer as i32),
        CURRENT_PROGRAM => i(ctx.program as i32),
        FRAMEBUFFER_BINDING => i(ctx.framebuffer as i32),
        RENDERBUFFER_BINDING => i(ctx.renderbuffer as i32),
        TEXTURE_BINDING_2D => i(ctx.units[ctx.active_unit][0] as i32),
        TEXTURE_BINDING_CUBE_MAP => i(ctx.units[ctx.active_unit][1] as i32),
        ACTIVE_TEXTURE => i((TEXTURE0 + ctx.active_unit as u32) as i32),
        UNPACK_ALIGNMENT => i(ctx.unpack_alignment),
        PACK_ALIGNMENT => i(ctx.pack_alignment),
        GENERATE_MIPMAP_HINT => i(ctx.mipmap_hint as i32),
        MAX_TEXTURE_SIZE | MAX_CUBE_MAP_TEXTURE_SIZE | MAX_RENDERBUFFER_SIZE => {
            i(MAX_TEXTURE.min(gpu.limits.max_texture_dimension_2d) as i32)
        }
        MAX_VIEWPORT_DIMS => Ints(vec![MAX_TEXTURE as i32; 2]),
        MAX_VERTEX_ATTRIBS => i(MAX_ATTRIBS as i32),
        MAX_VERTEX_UNIFORM_VECTORS | MAX_FRAGMENT_UNIFORM_VECTORS => i(256),
        MAX_VARYING_VECTORS => i(15),
        MAX_COMBINED_TEXTURE_IMAGE_UNITS | MAX_TEXTURE_IMAGE_UNITS | MAX_VERTEX_TEXTURE_IMAGE_UNITS => {
            i(MAX_UNITS as i32)
        }
        RED_BITS | GREEN_BITS | BLUE_BITS => i(8),
        ALPHA_BITS => i(ctx.config.rgba[3]),
        DEPTH_BITS => i(ctx.config.depth),
        STENCIL_BITS => i(ctx.config.stencil),
        SUBPIXEL_BITS => i(8),
        IMPLEMENTATION_COLOR_READ_FORMAT => i(RGBA as i32),
        IMPLEMENTATION_COLOR_READ_TYPE => i(UNSIGNED_BYTE as i32),
        NUM_COMPRESSED_TEXTURE_FORMATS | NUM_SHADER_BINARY_FORMATS => i(0),
        SHADER_COMPILER => b(true),
        _ => return None,
    })
}

impl Executor for GlesExecutor {
    fn execute(&mut self, cmd: Command<'_>) -> Result<Option<Reply>, ExecError> {
        use strata_protocol::Opcode as O;
        let op = cmd.opcode();
        // Everything a command does on the device is charged to this client.
        let scope = self.gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let reply = match op {
            O::Ping => match cmd {
                Command::Ping { token } => Some(Reply::Ping(token)),
                _ => None,
            },
            O::Stats => Some(Reply::Stats(strata_protocol::ExecStats {
                pipeline_cache_misses: self.r.pipeline_misses,
                render_passes: self.r.passes,
                draws: self.r.draws,
            })),
            O::GetDisplay
            | O::GetPlatformDisplay
            | O::Initialize
            | O::Terminate
            | O::ChooseConfig
            | O::GetConfigAttrib
            | O::CreatePbufferSurface
            | O::CreateWindowSurface
            | O::CreateContext
            | O::MakeCurrent
            | O::SwapInterval
            | O::QuerySurface
            | O::DestroySurface
            | O::DestroyContext
            | O::SwapBuffers => self.egl(cmd),
            _ => self.gl(cmd),
        };
        let caught = pollster::block_on(scope.pop());
        if caught.is_some() || !self.r.errors.is_empty() {
            self.charge(caught);
        }
        Ok(reply)
    }
}
