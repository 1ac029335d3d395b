//! One GL context's state, grouped the way GL groups it: named objects, bindings, vertex
//! arrays, rasterisation, depth and stencil, blending and colour output, pixel store.

use std::collections::{HashMap, HashSet};

use crate::egl_config::Config;
use crate::enums::*;
use crate::error::{ErrorFlag, GlError};
use crate::limits::{MAX_ATTRIBS, MAX_UNITS};
use crate::names::Names;
use crate::objects::buffer::Buffer;
use crate::objects::debug::DebugState;
use crate::objects::framebuffer::{Framebuffer, Renderbuffer};
use crate::objects::program::Program;
use crate::objects::program::ShaderObj;
use crate::objects::texture::Texture;
use crate::objects::vertex_array::Attrib;
use crate::objects::vertex_array::VertexArray;
use crate::typed::ClipControl;
use crate::typed::{BufferTarget, Capability, TextureTarget};

/// The context's name tables.
#[derive(Default)]
pub struct Objects {
    /// Buffer objects.
    pub buffers: Names<Buffer>,
    /// Texture objects.
    pub textures: Names<Texture>,
    /// Renderbuffer objects.
    pub renderbuffers: Names<Renderbuffer>,
    /// Framebuffer objects.
    pub framebuffers: Names<Framebuffer>,
    /// Shader objects (one namespace with programs).
    pub shaders: HashMap<u32, ShaderObj>,
    /// Program objects.
    pub programs: HashMap<u32, Program>,
    /// Vertex array objects other than the bound one, whose state is in `Context::attribs`.
    pub vertex_arrays: Names<VertexArray>,
    /// Program pipeline objects (`GL_EXT_separate_shader_objects`).
    pub pipelines: Names<crate::objects::pipeline::Pipeline>,
    /// Sampler objects (ES 3.0), shared as textures are.
    pub samplers: Names<crate::objects::sampler::Sampler>,
    /// `GL_KHR_debug` object labels by (namespace, name).
    pub labels: HashMap<(u32, u32), Vec<u8>>,
    /// Texture 0 of each target (by [`TextureTarget::slot`]): the context's default textures,
    /// which take images and parameters as any texture does, and are never shared.
    pub default_textures: [Texture; 5],
}

impl Objects {
    /// The texture `name` bound to `target` is: for 0, the context's default texture of
    /// `target`.
    pub fn texture_mut(&mut self, target: TextureTarget, name: u32) -> Option<&mut Texture> {
        if name != 0 {
            return self.textures.get_mut(&name);
        }
        let t = &mut self.default_textures[target.slot()];
        t.target = target.as_gl();
        Some(t)
    }

    /// [`Self::texture_mut`], to read: a default texture never used has target 0.
    pub fn texture(&self, target: TextureTarget, name: u32) -> Option<&Texture> {
        if name == 0 {
            Some(&self.default_textures[target.slot()])
        } else {
            self.textures.get(&name)
        }
    }

    /// Takes the tables a share group shares (buffers, textures, renderbuffers, framebuffers,
    /// as ES 2.0 and Mesa share them, shaders and programs) from `from`, whose tables are left
    /// as this one's were: a group's tables are kept by one of its contexts at a time (see
    /// `GlesExecutor::hold_shared`). Vertex arrays and program pipelines stay each context's.
    pub fn take_shared(&mut self, from: &mut Objects) {
        std::mem::swap(&mut self.buffers, &mut from.buffers);
        std::mem::swap(&mut self.textures, &mut from.textures);
        std::mem::swap(&mut self.samplers, &mut from.samplers);
        std::mem::swap(&mut self.renderbuffers, &mut from.renderbuffers);
        std::mem::swap(&mut self.framebuffers, &mut from.framebuffers);
        std::mem::swap(&mut self.shaders, &mut from.shaders);
        std::mem::swap(&mut self.programs, &mut from.programs);
    }

    /// The error for `name` where a shader or program of the other kind was expected: the
    /// wrong kind is `GL_INVALID_OPERATION`, no object at all `GL_INVALID_VALUE`.
    pub fn shader_or_program_error(&self, name: u32) -> GlError {
        if self.shaders.contains_key(&name) || self.programs.contains_key(&name) {
            GlError::InvalidOperation
        } else {
            GlError::InvalidValue
        }
    }
}

/// What is bound where.
#[derive(Default)]
pub struct Bindings {
    /// `GL_ARRAY_BUFFER_BINDING`.
    pub array_buffer: u32,
    /// `GL_ELEMENT_ARRAY_BUFFER_BINDING`.
    pub element_buffer: u32,
    /// `GL_PIXEL_PACK_BUFFER_BINDING_NV` (`GL_NV_pixel_buffer_object`).
    pub pixel_pack: u32,
    /// `GL_PIXEL_UNPACK_BUFFER_BINDING_NV`.
    pub pixel_unpack: u32,
    /// `GL_ACTIVE_TEXTURE` − `GL_TEXTURE0`.
    pub active_unit: usize,
    /// Per texture unit: the 2D, the cube map, the external (`GL_OES_EGL_image_external`),
    /// the 3D (`GL_OES_texture_3D`) and the 2D array (ES 3.0) texture.
    pub units: [[u32; 5]; MAX_UNITS],
    /// Per texture unit: the sampler object bound (ES 3.0's `glBindSampler`), 0 for none.
    pub samplers: [u32; MAX_UNITS],
    /// `GL_CURRENT_PROGRAM`.
    pub program: u32,
    /// `GL_PROGRAM_PIPELINE_BINDING_EXT`: the pipeline that draws while no program is in use.
    pub pipeline: u32,
    /// `GL_FRAMEBUFFER_BINDING`: the framebuffer draws and clears address.
    pub framebuffer: u32,
    /// The framebuffer reads and copies address. `glBindFramebuffer(GL_FRAMEBUFFER)` binds both;
    /// Mesa's ES 2.0 also takes `GL_DRAW_FRAMEBUFFER` and `GL_READ_FRAMEBUFFER` there, which
    /// bind one each.
    pub read_framebuffer: u32,
    /// `GL_RENDERBUFFER_BINDING`.
    pub renderbuffer: u32,
    /// `GL_VERTEX_ARRAY_BINDING_OES`.
    pub vertex_array: u32,
    /// `GL_UNIFORM_BUFFER_BINDING` (ES 3.0): the generic uniform buffer binding.
    pub uniform_buffer: u32,
    /// `GL_COPY_READ_BUFFER_BINDING` and `GL_COPY_WRITE_BUFFER_BINDING` (ES 3.0).
    pub copy_buffers: [u32; 2],
    /// `GL_TRANSFORM_FEEDBACK_BUFFER_BINDING` (ES 3.0): the generic binding.
    pub xfb_buffer: u32,
    /// The indexed uniform buffer bindings uniform blocks read (`glBindBufferBase`/`Range`).
    pub uniform_buffers: [RangeBinding; crate::glsl::blocks::MAX_COMBINED_UNIFORM_BLOCKS],
}

pub use crate::objects::buffer::RangeBinding;

impl Bindings {
    /// The buffer bound to `target`.
    pub fn buffer(&self, target: BufferTarget) -> u32 {
        match target {
            BufferTarget::Array => self.array_buffer,
            BufferTarget::ElementArray => self.element_buffer,
            BufferTarget::PixelPack => self.pixel_pack,
            BufferTarget::PixelUnpack => self.pixel_unpack,
            BufferTarget::Uniform => self.uniform_buffer,
            BufferTarget::CopyRead => self.copy_buffers[0],
            BufferTarget::CopyWrite => self.copy_buffers[1],
            BufferTarget::TransformFeedback => self.xfb_buffer,
        }
    }

    /// The texture bound to `target` of the active unit.
    pub fn texture(&self, target: TextureTarget) -> u32 {
        self.units[self.active_unit][target.slot()]
    }
}

/// Rasterisation: viewport, scissor, culling, polygon offset, lines, multisample coverage.
pub struct Raster {
    /// `GL_VIEWPORT`.
    pub viewport: [i32; 4],
    /// `GL_SCISSOR_BOX`.
    pub scissor: [i32; 4],
    /// `GL_SCISSOR_TEST`.
    pub scissor_test: bool,
    /// `GL_CULL_FACE`.
    pub cull: bool,
    /// `GL_CULL_FACE_MODE`.
    pub cull_face: u32,
    /// `GL_FRONT_FACE`.
    pub front_face: u32,
    /// `GL_POLYGON_OFFSET_FILL`.
    pub polygon_offset_fill: bool,
    /// `GL_DEPTH_CLAMP_EXT`.
    pub depth_clamp: bool,
    /// `GL_RASTERIZER_DISCARD` (ES 3.0): draws rasterize nothing, and clears do nothing.
    pub discard: bool,
    /// `GL_PRIMITIVE_RESTART_FIXED_INDEX` (ES 3.0): an index of the type's largest value
    /// ends a primitive and starts the next.
    pub primitive_restart: bool,
    /// `GL_CLIP_ORIGIN_EXT` and `GL_CLIP_DEPTH_MODE_EXT` (`GL_EXT_clip_control`).
    pub clip: ClipControl,
    /// `GL_POLYGON_OFFSET_FACTOR`, `_UNITS` and `_CLAMP_EXT`.
    pub polygon_offset: [f32; 3],
    /// `GL_LINE_WIDTH`.
    pub line_width: f32,
    /// `GL_SAMPLE_COVERAGE`.
    pub sample_coverage: bool,
    /// `GL_SAMPLE_ALPHA_TO_COVERAGE`.
    pub alpha_to_coverage: bool,
    /// `GL_SAMPLE_COVERAGE_VALUE` and `GL_SAMPLE_COVERAGE_INVERT` (multisample targets'
    /// draws mask their samples with them; see `draw_state::raster_state`).
    pub coverage: (f32, bool),
}

impl Default for Raster {
    fn default() -> Self {
        Raster {
            viewport: [0; 4],
            scissor: [0; 4],
            scissor_test: false,
            cull: false,
            cull_face: BACK,
            front_face: CCW,
            polygon_offset_fill: false,
            depth_clamp: false,
            primitive_restart: false,
            discard: false,
            clip: ClipControl::default(),
            polygon_offset: [0.0; 3],
            line_width: 1.0,
            sample_coverage: false,
            alpha_to_coverage: false,
            coverage: (1.0, false),
        }
    }
}

/// One face's stencil state.
#[derive(Clone, Copy)]
pub struct StencilFace {
    /// Comparison function.
    pub func: u32,
    /// Reference value.
    pub reference: i32,
    /// Comparison mask.
    pub mask: u32,
    /// Write mask.
    pub write: u32,
    /// Operation when the stencil test fails.
    pub fail: u32,
    /// Operation when the depth test fails.
    pub zfail: u32,
    /// Operation when both pass.
    pub zpass: u32,
}

impl Default for StencilFace {
    fn default() -> Self {
        StencilFace {
            func: ALWAYS,
            // "All ones" of the 8-bit stencil buffers every config and renderbuffer has,
            // which is also what Mesa reports.
            reference: 0,
            mask: 0xFF,
            write: 0xFF,
            fail: KEEP,
            zfail: KEEP,
            zpass: KEEP,
        }
    }
}

/// Depth and stencil testing, and their clear values.
pub struct DepthStencil {
    /// `GL_DEPTH_TEST`.
    pub depth_test: bool,
    /// `GL_DEPTH_FUNC`.
    pub depth_func: u32,
    /// `GL_DEPTH_WRITEMASK`.
    pub depth_mask: bool,
    /// `GL_DEPTH_RANGE`, clamped to [0, 1].
    pub depth_range: [f32; 2],
    /// `GL_DEPTH_CLEAR_VALUE`.
    pub clear_depth: f32,
    /// `GL_STENCIL_TEST`.
    pub stencil_test: bool,
    /// Front and back stencil state.
    pub stencil: [StencilFace; 2],
    /// `GL_STENCIL_CLEAR_VALUE`.
    pub clear_stencil: i32,
}

impl Default for DepthStencil {
    fn default() -> Self {
        DepthStencil {
            depth_test: false,
            depth_func: LESS,
            depth_mask: true,
            depth_range: [0.0, 1.0],
            clear_depth: 1.0,
            stencil_test: false,
            stencil: [StencilFace::default(); 2],
            clear_stencil: 0,
        }
    }
}

/// Blending and the rest of colour output: write mask, clear colour, dithering.
pub struct Blend {
    /// `GL_BLEND`.
    pub enabled: bool,
    /// Source and destination factors: RGB source, RGB destination, alpha source, alpha destination.
    pub func: [u32; 4],
    /// RGB and alpha equations.
    pub eq: [u32; 2],
    /// `GL_BLEND_COLOR`.
    pub color: [f32; 4],
    /// `GL_COLOR_WRITEMASK`.
    pub color_mask: [bool; 4],
    /// `GL_COLOR_CLEAR_VALUE`.
    pub clear_color: [f32; 4],
    /// `GL_DITHER`.
    pub dither: bool,
}

impl Default for Blend {
    fn default() -> Self {
        Blend {
            enabled: false,
            func: [ONE, ZERO, ONE, ZERO],
            eq: [FUNC_ADD, FUNC_ADD],
            color: [0.0; 4],
            color_mask: [true; 4],
            clear_color: [0.0; 4],
            dither: true,
        }
    }
}

/// `glPixelStorei` state.
pub struct PixelStore {
    /// `GL_UNPACK_ALIGNMENT`.
    pub unpack_alignment: i32,
    /// `GL_PACK_ALIGNMENT`.
    pub pack_alignment: i32,
    /// `GL_UNPACK_ROW_LENGTH_EXT` (`EXT_unpack_subimage`; 0: the image's width).
    pub unpack_row_length: i32,
    /// `GL_UNPACK_SKIP_ROWS_EXT`.
    pub unpack_skip_rows: i32,
    /// `GL_UNPACK_SKIP_PIXELS_EXT`.
    pub unpack_skip_pixels: i32,
    /// `GL_PACK_ROW_LENGTH_NV`, `GL_PACK_SKIP_ROWS_NV` and `GL_PACK_SKIP_PIXELS_NV`
    /// (`NV_pack_subimage`): where `glReadPixels` puts its rows in the application's memory,
    /// which the drop-in library applies.
    pub pack_rows: [i32; 3],
    /// `GL_PACK_REVERSE_ROW_ORDER_ANGLE`, kept as the byte Mesa keeps (nonzero: the top row
    /// first).
    pub pack_reverse: u8,
    /// ES 3.0's `GL_UNPACK_IMAGE_HEIGHT` and `GL_UNPACK_SKIP_IMAGES`: kept and answered; the
    /// client library gathers a 3D upload's slices by them, so that they arrive as slices
    /// without them.
    pub unpack_images: [i32; 2],
}

impl Default for PixelStore {
    fn default() -> Self {
        PixelStore {
            unpack_alignment: 4,
            pack_alignment: 4,
            unpack_row_length: 0,
            unpack_skip_rows: 0,
            unpack_skip_pixels: 0,
            pack_rows: [0; 3],
            pack_reverse: 0,
            unpack_images: [0; 2],
        }
    }
}

/// One GL context's state.
pub struct Context {
    /// The EGL config of the surface it was last made current with (the one it was created
    /// with before that, or the first for `EGL_KHR_no_config_context`): what framebuffer 0's
    /// bits answer, as on Mesa.
    pub config: Config,
    /// The pending GL error.
    pub error: ErrorFlag,
    /// Whether it has been current with a surface (the first such `eglMakeCurrent` sizes
    /// viewport and scissor, as on Mesa).
    pub made_current: bool,
    /// Current with no surface (`EGL_KHR_surfaceless_context`): framebuffer 0 is
    /// `GL_FRAMEBUFFER_UNDEFINED_OES`.
    pub surfaceless: bool,
    /// Name tables.
    pub objects: Objects,
    /// Query objects (`GL_EXT_occlusion_query_boolean`; a context's own, never shared).
    pub queries: crate::names::Names<crate::objects::query::Query>,
    /// The `GL_TIME_ELAPSED_EXT` query active, if any (`GL_EXT_disjoint_timer_query`).
    pub active_timer: Option<u32>,
    /// The occlusion query active, if any.
    pub active_query: Option<crate::objects::query::Active>,
    /// While a conditional render is active (`GL_NV_conditional_render`): whether its query
    /// passed a sample, so that draws and clears are done.
    pub conditional: Option<bool>,
    /// The share group: the handle of the group's first context (`eglCreateContext`'s
    /// `share_context`).
    pub group: u32,
    /// The programs the group's other contexts use (their current program and their
    /// pipelines'), which a deletion here leaves pending: as of this context's taking the
    /// group's tables, since no other context runs while it is current.
    pub others_use: HashSet<u32>,
    /// Bindings.
    pub bindings: Bindings,
    /// Generic vertex attributes.
    pub attribs: Vec<Attrib>,
    /// Rasterisation state.
    pub raster: Raster,
    /// Depth and stencil state.
    pub depth_stencil: DepthStencil,
    /// Blending and colour output.
    pub blend: Blend,
    /// Pixel store.
    pub pixel_store: PixelStore,
    /// `GL_GENERATE_MIPMAP_HINT`.
    pub mipmap_hint: u32,
    /// `GL_MAX_SHADER_COMPILER_THREADS_KHR` (`GL_KHR_parallel_shader_compile`).
    pub compiler_threads: u32,
    /// Debug output (`GL_KHR_debug`).
    pub debug: DebugState,
    /// The GL call being executed, which debug messages about its errors name.
    pub call: &'static str,
    /// `GL_FRAGMENT_SHADER_DERIVATIVE_HINT_OES`.
    pub derivative_hint: u32,
    /// Created with `EGL_CONTEXT_OPENGL_NO_ERROR_KHR` (`GL_KHR_no_error`): calls are still
    /// validated, and one in error still does nothing, but only `GL_OUT_OF_MEMORY` is reported.
    pub no_error: bool,
    /// Created with `EGL_CONTEXT_RELEASE_BEHAVIOR_NONE_KHR` (`GL_KHR_context_flush_control`).
    pub release_none: bool,
    /// Created with `EGL_LOSE_CONTEXT_ON_RESET_KHR`: `GL_RESET_NOTIFICATION_STRATEGY_EXT`.
    pub lose_on_reset: bool,
    /// Created with robust buffer access (`EGL_EXT_create_context_robustness`,
    /// `GL_KHR_robust_buffer_access_behavior`): draws that read past their arrays or index
    /// data draw, reading zeros, instead of failing with `GL_INVALID_OPERATION`.
    pub robust: bool,
    /// Reads from the default framebuffer select no colour buffer (`GL_NV_read_buffer`).
    pub read_none: bool,
    /// Draws to the default framebuffer write no colour buffer (`glDrawBuffersEXT(GL_NONE)`).
    pub draw_none: bool,
    /// Transform feedback (ES 3.0).
    pub xfb: crate::objects::xfb::XfbState,
    /// The OpenGL ES major version it was created for: 2, or 3 where the daemon offers ES 3.0.
    pub major: u8,
}

impl Context {
    /// A new context's default state.
    pub fn new(config: Config) -> Self {
        Context {
            config,
            error: ErrorFlag::default(),
            made_current: false,
            surfaceless: false,
            objects: Objects::default(),
            queries: Default::default(),
            active_query: None,
            active_timer: None,
            conditional: None,
            group: 0,
            others_use: HashSet::new(),
            bindings: Bindings::default(),
            attribs: vec![Attrib::default(); MAX_ATTRIBS],
            raster: Raster::default(),
            depth_stencil: DepthStencil::default(),
            blend: Blend::default(),
            pixel_store: PixelStore::default(),
            mipmap_hint: DONT_CARE,
            compiler_threads: u32::MAX,
            debug: DebugState::default(),
            call: "",
            derivative_hint: DONT_CARE,
            no_error: false,
            release_none: false,
            lose_on_reset: false,
            robust: false,
            read_none: false,
            draw_none: false,
            xfb: Default::default(),
            major: 2,
        }
    }

    /// Whether it is an OpenGL ES 3.0 context (ES 3.0's entry points, enums and language).
    pub fn es3(&self) -> bool {
        self.major >= 3
    }

    /// Records `e` (the first error wins until `glGetError`), and generates its debug message.
    pub fn record(&mut self, e: GlError) {
        if self.no_error && e != GlError::OutOfMemory {
            return;
        }
        self.error.record(e);
        self.debug.error(self.call, e);
    }

    /// Whether capability `cap` is enabled.
    pub fn enabled(&self, cap: Capability) -> bool {
        match cap {
            Capability::CullFace => self.raster.cull,
            Capability::Blend => self.blend.enabled,
            Capability::DepthTest => self.depth_stencil.depth_test,
            Capability::ScissorTest => self.raster.scissor_test,
            Capability::StencilTest => self.depth_stencil.stencil_test,
            Capability::PolygonOffsetFill => self.raster.polygon_offset_fill,
            Capability::DepthClamp => self.raster.depth_clamp,
            Capability::PrimitiveRestartFixedIndex => self.raster.primitive_restart,
            Capability::RasterizerDiscard => self.raster.discard,
            Capability::Dither => self.blend.dither,
            Capability::SampleCoverage => self.raster.sample_coverage,
            Capability::SampleAlphaToCoverage => self.raster.alpha_to_coverage,
            Capability::DebugOutput => self.debug.output,
            Capability::DebugOutputSynchronous => self.debug.synchronous,
        }
    }

    /// The flag of capability `cap`, for `glEnable`/`glDisable`.
    pub fn enabled_mut(&mut self, cap: Capability) -> &mut bool {
        match cap {
            Capability::CullFace => &mut self.raster.cull,
            Capability::Blend => &mut self.blend.enabled,
            Capability::DepthTest => &mut self.depth_stencil.depth_test,
            Capability::ScissorTest => &mut self.raster.scissor_test,
            Capability::StencilTest => &mut self.depth_stencil.stencil_test,
            Capability::PolygonOffsetFill => &mut self.raster.polygon_offset_fill,
            Capability::DepthClamp => &mut self.raster.depth_clamp,
            Capability::PrimitiveRestartFixedIndex => &mut self.raster.primitive_restart,
            Capability::RasterizerDiscard => &mut self.raster.discard,
            Capability::Dither => &mut self.blend.dither,
            Capability::SampleCoverage => &mut self.raster.sample_coverage,
            Capability::SampleAlphaToCoverage => &mut self.raster.alpha_to_coverage,
            Capability::DebugOutput => &mut self.debug.output,
            Capability::DebugOutputSynchronous => &mut self.debug.synchronous,
        }
    }
}
