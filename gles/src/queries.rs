//! State queries: `glGetError`, `glGetString`, and `glGetIntegerv`/`glGetFloatv`/`glGetBooleanv`
//! over one table of state values with GL's conversions between the three types.

use crate::context::Context;

use crate::channels::{color_bits, texture_color_bits};
use crate::enums::*;
use crate::error::GlError;
use crate::formats::offered_compressed;
use crate::limits::{MAX_ATTRIBS, MAX_DRAW_BUFFERS as MAX_DRAW_BUFFERS_COUNT, MAX_POINT_SIZE, MAX_TEXTURE, MAX_UNITS};
use crate::objects::framebuffer::Attachment;
use crate::typed::Capability;
use crate::GlesExecutor;
use strata_device::Gpu;

/// Extensions advertised in `GL_EXTENSIONS`: only what the executor implements.
const EXTENSIONS_STRING: &str = "GL_OES_element_index_uint GL_OES_vertex_half_float GL_OES_texture_npot \
GL_OES_rgb8_rgba8 GL_OES_depth24 GL_OES_packed_depth_stencil GL_OES_depth_texture GL_OES_vertex_array_object \
GL_KHR_debug GL_EXT_blend_minmax GL_EXT_discard_framebuffer \
GL_OES_standard_derivatives GL_EXT_frag_depth GL_EXT_polygon_offset_clamp GL_KHR_parallel_shader_compile GL_OES_required_internalformat GL_OES_draw_elements_base_vertex GL_EXT_read_format_bgra \
GL_EXT_draw_elements_base_vertex GL_EXT_multi_draw_arrays GL_EXT_draw_instanced GL_OES_stencil8 \
GL_KHR_no_error GL_KHR_context_flush_control GL_EXT_texture_rg \
GL_EXT_debug_label GL_NV_read_buffer GL_OES_fbo_render_mipmap GL_EXT_texture_filter_anisotropic \
GL_OES_mapbuffer GL_EXT_map_buffer_range GL_NV_pack_subimage GL_ANGLE_pack_reverse_row_order \
GL_EXT_texture_type_2_10_10_10_REV GL_APPLE_texture_max_level GL_OES_surfaceless_context \
GL_MESA_bgra GL_EXT_occlusion_query_boolean GL_NV_conditional_render GL_EXT_robustness GL_KHR_robustness \
GL_OES_EGL_sync GL_OES_get_program_binary GL_EXT_clip_control GL_KHR_robust_buffer_access_behavior GL_NV_read_depth GL_NV_read_stencil GL_NV_read_depth_stencil GL_OES_depth_texture_cube_map \
GL_OES_EGL_image GL_OES_EGL_image_external GL_NV_pixel_buffer_object GL_EXT_separate_shader_objects GL_EXT_texture_mirror_clamp_to_edge GL_EXT_color_buffer_half_float GL_OES_texture_3D";

/// The texture-format extensions a device with `features` supports: float and half-float
/// textures (RGBA32F filtering only with `FLOAT32_FILTERABLE`), BGRA uploads, unpack
/// sub-rectangles, ETC1 (native or decoded, and updated in part), ASTC LDR (native or
/// decoded), and S3TC where the device has BC formats.
fn texture_extensions(features: wgpu::Features) -> String {
    let mut ext = vec!["GL_OES_texture_float", "GL_OES_texture_half_float", "GL_OES_texture_half_float_linear"];
    if features.contains(wgpu::Features::FLOAT32_FILTERABLE) {
        ext.push("GL_OES_texture_float_linear");
    }
    ext.extend(["GL_EXT_texture_format_BGRA8888", "GL_EXT_unpack_subimage", "GL_OES_compressed_ETC1_RGB8_texture"]);
    ext.extend(["GL_EXT_compressed_ETC1_RGB8_sub_texture", "GL_KHR_texture_compression_astc_ldr"]);
    // ASTC slices of 3D images (GL_OES_texture_3D), decoded on upload.
    ext.push("GL_KHR_texture_compression_astc_sliced_3d");
    if features.contains(wgpu::Features::TEXTURE_COMPRESSION_BC) {
        // The S3TC formats, and the same formats under the names of their subsets.
        ext.extend([
            "GL_EXT_texture_compression_s3tc",
            "GL_EXT_texture_compression_dxt1",
            "GL_ANGLE_texture_compression_dxt3",
            "GL_ANGLE_texture_compression_dxt5",
            "GL_EXT_texture_compression_s3tc_srgb",
        ]);
    }
    ext.join(" ")
}

/// A state value in the type GL stores it as.
enum Value {
    /// Integers (enums, names, counts).
    Ints(Vec<i32>),
    /// Floats.
    Floats(Vec<f32>),
    /// Booleans.
    Bools(Vec<bool>),
}

/// Red, green, blue, alpha, depth and stencil bits of the framebuffer draws address: the
/// surface's config for framebuffer 0, else what the object's attachments store.
fn framebuffer_bits(ctx: &Context) -> [i32; 6] {
    let bound = ctx.bindings.framebuffer;
    let Some(fb) = ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) else {
        if ctx.surfaceless {
            return [0; 6];
        }
        let c = &ctx.config;
        return [8, 8, 8, c.rgba[3], c.depth, c.stencil];
    };
    // Colour is stored as RGBA8 (or RGBA16F) whatever the format; a format without alpha
    // reads alpha 1.
    // The first colour attachment's, as Mesa answers.
    let first = fb.colors.iter().find(|a| **a != Attachment::None).copied().unwrap_or_default();
    let color = match first {
        Attachment::None => [0; 4],
        Attachment::Texture { name, .. } => ctx
            .objects
            .textures
            .get(&name)
            .map_or([0; 4], |t| texture_color_bits(t.format, t.gpu.as_ref().map(|i| i.storage))),
        Attachment::Renderbuffer(name) => match ctx.objects.renderbuffers.get(&name).map(|r| r.format) {
            Some(0) | None => [0; 4],
            Some(f) => color_bits(f),
        },
    };
    let ds_bits = |a: Attachment| -> (i32, i32) {
        match a {
            Attachment::None => (0, 0),
            // Depth textures are Depth32Float images, which hold at least 24 bits.
            Attachment::Texture { .. } => (24, 0),
            Attachment::Renderbuffer(name) => match ctx.objects.renderbuffers.get(&name).map(|r| r.format) {
                Some(DEPTH_COMPONENT16) => (16, 0),
                Some(DEPTH_COMPONENT24_OES) => (24, 0),
                Some(DEPTH24_STENCIL8_OES) => (24, 8),
                Some(STENCIL_INDEX8) => (0, 8),
                _ => (0, 0),
            },
        }
    };
    [color[0], color[1], color[2], color[3], ds_bits(fb.depth).0, ds_bits(fb.stencil).1]
}

/// The value of state `pname`, `None` if it is not one `glGet*` answers.
fn get_state(ctx: &Context, gpu: &Gpu, pname: u32) -> Option<Value> {
    use Value::*;
    let b = |x: bool| Bools(vec![x]);
    let i = |x: i32| Ints(vec![x]);
    let u = |x: u32| Ints(vec![x as i32]);
    let f = |x: f32| Floats(vec![x]);
    if let Ok(cap) = Capability::on(pname, gpu.features, ctx.es3()) {
        return Some(b(ctx.enabled(cap)));
    }
    let (raster, ds, blend, bind) = (&ctx.raster, &ctx.depth_stencil, &ctx.blend, &ctx.bindings);
    let bits = framebuffer_bits(ctx);
    let [front, back] = &ds.stencil;
    // The reference is clamped to the stencil buffer's range when queried (ES 2.0 §4.1.5).
    let stencil_ref = |r: i32| i(r.clamp(0, (1 << bits[5]) - 1));
    Some(match pname {
        VIEWPORT => Ints(raster.viewport.to_vec()),
        SCISSOR_BOX => Ints(raster.scissor.to_vec()),
        COLOR_CLEAR_VALUE => Floats(blend.clear_color.to_vec()),
        BLEND_COLOR => Floats(blend.color.to_vec()),
        DEPTH_CLEAR_VALUE => f(ds.clear_depth),
        DEPTH_RANGE => Floats(ds.depth_range.to_vec()),
        LINE_WIDTH => f(raster.line_width),
        ALIASED_LINE_WIDTH_RANGE => Floats(vec![1.0, 1.0]),
        ALIASED_POINT_SIZE_RANGE => Floats(vec![1.0, MAX_POINT_SIZE]),
        COLOR_WRITEMASK => Bools(blend.color_mask.to_vec()),
        DEPTH_WRITEMASK => b(ds.depth_mask),
        DEPTH_FUNC => u(ds.depth_func),
        CULL_FACE_MODE => u(raster.cull_face),
        FRONT_FACE => u(raster.front_face),
        POLYGON_OFFSET_FACTOR => f(raster.polygon_offset[0]),
        POLYGON_OFFSET_UNITS => f(raster.polygon_offset[1]),
        POLYGON_OFFSET_CLAMP_EXT => f(raster.polygon_offset[2]),
        SAMPLE_COVERAGE_VALUE => f(raster.coverage.0),
        SAMPLE_COVERAGE_INVERT => b(raster.coverage.1),
        BLEND_EQUATION_RGB => u(blend.eq[0]),
        BLEND_EQUATION_ALPHA => u(blend.eq[1]),
        BLEND_SRC_RGB => u(blend.func[0]),
        BLEND_DST_RGB => u(blend.func[1]),
        BLEND_SRC_ALPHA => u(blend.func[2]),
        BLEND_DST_ALPHA => u(blend.func[3]),
        STENCIL_CLEAR_VALUE => i(ds.clear_stencil),
        STENCIL_FUNC => u(front.func),
        STENCIL_VALUE_MASK => u(front.mask),
        STENCIL_REF => stencil_ref(front.reference),
        STENCIL_FAIL => u(front.fail),
        STENCIL_PASS_DEPTH_FAIL => u(front.zfail),
        STENCIL_PASS_DEPTH_PASS => u(front.zpass),
        STENCIL_WRITEMASK => u(front.write),
        STENCIL_BACK_FUNC => u(back.func),
        STENCIL_BACK_VALUE_MASK => u(back.mask),
        STENCIL_BACK_REF => stencil_ref(back.reference),
        STENCIL_BACK_FAIL => u(back.fail),
        STENCIL_BACK_PASS_DEPTH_FAIL => u(back.zfail),
        STENCIL_BACK_PASS_DEPTH_PASS => u(back.zpass),
        STENCIL_BACK_WRITEMASK => u(back.write),
        ARRAY_BUFFER_BINDING => u(bind.array_buffer),
        // GL_EXT_disjoint_timer_query: the device's clock never jumps.
        crate::enums::GPU_DISJOINT if gpu.features.contains(wgpu::Features::TIMESTAMP_QUERY) => b(false),
        ELEMENT_ARRAY_BUFFER_BINDING => u(bind.element_buffer),
        PIXEL_PACK_BUFFER_BINDING_NV => u(bind.pixel_pack),
        PIXEL_UNPACK_BUFFER_BINDING_NV => u(bind.pixel_unpack),
        CURRENT_PROGRAM => u(bind.program),
        FRAMEBUFFER_BINDING => u(bind.framebuffer),
        RENDERBUFFER_BINDING => u(bind.renderbuffer),
        TEXTURE_BINDING_2D => u(bind.units[bind.active_unit][0]),
        TEXTURE_BINDING_CUBE_MAP => u(bind.units[bind.active_unit][1]),
        TEXTURE_BINDING_EXTERNAL_OES => u(bind.units[bind.active_unit][2]),
        TEXTURE_BINDING_3D_OES => u(bind.units[bind.active_unit][3]),
        MAX_3D_TEXTURE_SIZE_OES => i(crate::limits::max_3d_size(gpu) as i32),
        ACTIVE_TEXTURE => u(TEXTURE0 + bind.active_unit as u32),
        UNPACK_ALIGNMENT => i(ctx.pixel_store.unpack_alignment),
        PACK_ALIGNMENT => i(ctx.pixel_store.pack_alignment),
        UNPACK_ROW_LENGTH => i(ctx.pixel_store.unpack_row_length),
        UNPACK_SKIP_ROWS => i(ctx.pixel_store.unpack_skip_rows),
        UNPACK_SKIP_PIXELS => i(ctx.pixel_store.unpack_skip_pixels),
        PACK_ROW_LENGTH => i(ctx.pixel_store.pack_rows[0]),
        PACK_SKIP_ROWS => i(ctx.pixel_store.pack_rows[1]),
        PACK_SKIP_PIXELS => i(ctx.pixel_store.pack_rows[2]),
        PACK_REVERSE_ROW_ORDER_ANGLE => i(i32::from(ctx.pixel_store.pack_reverse)),
        GENERATE_MIPMAP_HINT => u(ctx.mipmap_hint),
        // 0xFFFFFFFF (the implementation's choice) reads as -1, as on Mesa.
        MAX_SHADER_COMPILER_THREADS_KHR => u(ctx.compiler_threads),
        READ_BUFFER_NV => u(crate::framebuffers::read_buffer(ctx)),
        MAX_DRAW_BUFFERS | MAX_COLOR_ATTACHMENTS => u(MAX_DRAW_BUFFERS_COUNT as u32),
        MAX_DUAL_SOURCE_DRAW_BUFFERS_EXT if gpu.dual_source() => i(1),
        DRAW_BUFFER0..=DRAW_BUFFER7 => u(crate::framebuffers::draw_buffer(ctx, (pname - DRAW_BUFFER0) as usize)),
        MAX_TEXTURE_MAX_ANISOTROPY_EXT => f(crate::limits::MAX_ANISOTROPY),
        // GL_KHR_context_flush_control: GL_CONTEXT_RELEASE_BEHAVIOR_FLUSH_KHR, or none.
        CONTEXT_RELEASE_BEHAVIOR_KHR => u(if ctx.release_none { 0 } else { CONTEXT_RELEASE_BEHAVIOR_FLUSH_KHR }),
        // EXT_robustness / KHR_robustness: never a robust-access context; the strategy asked.
        CONTEXT_ROBUST_ACCESS_EXT => b(ctx.robust),
        RESET_NOTIFICATION_STRATEGY_EXT => {
            u(if ctx.lose_on_reset { LOSE_CONTEXT_ON_RESET_EXT } else { NO_RESET_NOTIFICATION_EXT })
        }
        FRAGMENT_SHADER_DERIVATIVE_HINT_OES => u(ctx.derivative_hint),
        MAX_TEXTURE_SIZE | MAX_CUBE_MAP_TEXTURE_SIZE | MAX_RENDERBUFFER_SIZE => {
            i(MAX_TEXTURE.min(gpu.limits.max_texture_dimension_2d) as i32)
        }
        MAX_VIEWPORT_DIMS => Ints(vec![MAX_TEXTURE as i32; 2]),
        MAX_VERTEX_ATTRIBS => i(MAX_ATTRIBS as i32),
        MAX_VERTEX_UNIFORM_VECTORS | MAX_FRAGMENT_UNIFORM_VECTORS => i(256),
        MAX_VARYING_VECTORS => i(crate::limits::MAX_VARYING_VECTORS as i32),
        MAX_COMBINED_TEXTURE_IMAGE_UNITS => i(MAX_UNITS as i32),
        MAX_TEXTURE_IMAGE_UNITS | MAX_VERTEX_TEXTURE_IMAGE_UNITS => i(crate::limits::MAX_STAGE_UNITS as i32),
        RED_BITS => i(bits[0]),
        GREEN_BITS => i(bits[1]),
        BLUE_BITS => i(bits[2]),
        ALPHA_BITS => i(bits[3]),
        DEPTH_BITS => i(bits[4]),
        STENCIL_BITS => i(bits[5]),
        SUBPIXEL_BITS => i(8),
        // Every surface and framebuffer object is single-sampled.
        SAMPLE_BUFFERS | SAMPLES => i(0),
        // RGBA, or for GL_EXT_texture_rg's framebuffers RED or RG, as Mesa answers; half-float
        // buffers (GL_EXT_color_buffer_half_float) read as GL_HALF_FLOAT.
        // Integer buffers read in their own format and type, as Mesa answers.
        IMPLEMENTATION_COLOR_READ_FORMAT | IMPLEMENTATION_COLOR_READ_TYPE
            if crate::pixels::read_buffer_int(ctx).is_some() =>
        {
            let (format, ty) = crate::pixels::read_buffer_int(ctx).map_or((0, 0), |f| f.upload());
            u(if pname == IMPLEMENTATION_COLOR_READ_FORMAT { format } else { ty })
        }
        IMPLEMENTATION_COLOR_READ_FORMAT => u(match framebuffer_bits(ctx) {
            [8 | 16, 0, 0, ..] => RED_EXT,
            [8 | 16, 8 | 16, 0, ..] => RG_EXT,
            _ => RGBA,
        }),
        IMPLEMENTATION_COLOR_READ_TYPE => u(if framebuffer_bits(ctx)[0] == 16 { HALF_FLOAT } else { UNSIGNED_BYTE }),
        NUM_COMPRESSED_TEXTURE_FORMATS => i(offered_compressed(gpu.features, ctx.es3()).len() as i32),
        COMPRESSED_TEXTURE_FORMATS => {
            Ints(offered_compressed(gpu.features, ctx.es3()).into_iter().map(|f| f as i32).collect())
        }
        NUM_SHADER_BINARY_FORMATS => i(0),
        SHADER_BINARY_FORMATS => Ints(vec![]),
        NUM_PROGRAM_BINARY_FORMATS_OES => i(1),
        CLIP_ORIGIN_EXT => u(if raster.clip.upper_left { UPPER_LEFT_EXT } else { LOWER_LEFT_EXT }),
        CLIP_DEPTH_MODE_EXT => u(if raster.clip.zero_to_one { ZERO_TO_ONE_EXT } else { NEGATIVE_ONE_TO_ONE_EXT }),
        PROGRAM_BINARY_FORMATS_OES => u(crate::programs::PROGRAM_BINARY_FORMAT),
        // Not ES 2.0 state (desktop GL and ES 1.x), answered anyway as Mesa does: piglit's
        // shader_runner asks for it unconditionally. No user clip planes.
        MAX_CLIP_PLANES => i(0),
        // 3D unpack state (in ES 2.0 contexts its initial value: apitrace asks for it beside
        // GL_EXT_unpack_subimage's state to size every traced texture upload).
        UNPACK_IMAGE_HEIGHT => i(ctx.pixel_store.unpack_images[0]),
        UNPACK_SKIP_IMAGES => i(ctx.pixel_store.unpack_images[1]),
        SHADER_COMPILER => b(true),
        VERTEX_ARRAY_BINDING_OES => i(bind.vertex_array as i32),
        MAX_LABEL_LENGTH => i(strata_protocol::commands::MAX_LABEL_LENGTH),
        MAX_DEBUG_MESSAGE_LENGTH => i(strata_protocol::commands::MAX_DEBUG_MESSAGE_LENGTH),
        MAX_DEBUG_LOGGED_MESSAGES => i(crate::limits::MAX_LOGGED as i32),
        MAX_DEBUG_GROUP_STACK_DEPTH => i(crate::limits::MAX_GROUP_DEPTH as i32),
        DEBUG_LOGGED_MESSAGES => i(ctx.debug.logged() as i32),
        DEBUG_NEXT_LOGGED_MESSAGE_LENGTH => i(ctx.debug.next_length() as i32),
        DEBUG_GROUP_STACK_DEPTH => i(ctx.debug.depth() as i32),
        _ => return None,
    })
}

/// The implementation read format and type of `target`'s read buffer where it is a 32-bit
/// float, packed float or 10-bit image; `None` for any other.
fn es3_read_format(target: &crate::render::Target) -> Option<(u32, u32)> {
    use wgpu::TextureFormat as F;
    Some(match target.color_format()? {
        F::Rgba32Float if target.absent.contains(wgpu::ColorWrites::GREEN) => (RED_EXT, FLOAT),
        F::Rgba32Float if target.absent.contains(wgpu::ColorWrites::BLUE) => (RG_EXT, FLOAT),
        F::Rgba32Float => (RGBA, FLOAT),
        F::Rg11b10Ufloat => (RGB, crate::packed_float::UNSIGNED_INT_10F_11F_11F_REV),
        F::Rgb10a2Unorm => (RGBA, UNSIGNED_INT_2_10_10_10_REV_EXT),
        _ => return None,
    })
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// State `pname`, recording `GL_INVALID_ENUM` (and answering nothing) if there is none.
    fn state(&mut self, ctx: &mut Context, pname: u32) -> Value {
        if let Some(v) = self.version_state(ctx, pname) {
            return Value::Ints(v);
        }
        // The read format of a framebuffer that cannot be read (framebuffer 0 with no surface):
        // an error, and 0 written, as Mesa writes it.
        let read_format = matches!(pname, IMPLEMENTATION_COLOR_READ_FORMAT | IMPLEMENTATION_COLOR_READ_TYPE);
        if read_format && ctx.bindings.read_framebuffer == 0 && ctx.surfaceless {
            ctx.record(GlError::InvalidOperation);
            return Value::Ints(vec![0]);
        }
        // The read formats of ES 3.0's float and 10-bit buffers (GL_EXT_color_buffer_float),
        // as Mesa answers them: a 32-bit float buffer's channels as floats, the packed formats'
        // own types.
        if read_format && ctx.es3() {
            if let Some((format, ty)) = self.read_target(ctx).ok().and_then(|t| es3_read_format(&t)) {
                return Value::Ints(vec![(if pname == IMPLEMENTATION_COLOR_READ_FORMAT { format } else { ty }) as i32]);
            }
        }
        let gpu = &self.gpu;
        get_state(ctx, gpu, pname).unwrap_or_else(|| {
            ctx.record(GlError::InvalidEnum);
            Value::Ints(vec![])
        })
    }

    pub(super) fn glGetError(&mut self, ctx: &mut Context) -> u32 {
        ctx.error.take()
    }

    pub(super) fn glGetString(&mut self, ctx: &mut Context, name: u32) -> Option<String> {
        Some(match name {
            VENDOR => "Strata".to_string(),
            RENDERER => format!("Strata on {}", self.gpu.info.name),
            VERSION => crate::version::version_string(ctx),
            SHADING_LANGUAGE_VERSION => crate::version::language_string(ctx).to_string(),
            EXTENSIONS => self.extensions(ctx),
            _ => {
                ctx.record(GlError::InvalidEnum);
                return None;
            }
        })
    }

    /// `GL_EXTENSIONS`: what the executor implements on this device for `ctx`'s version,
    /// separated by spaces. An ES 3.0 context adds `GL_EXT_color_buffer_float` (and
    /// `GL_EXT_float_blend` where the device blends 32-bit floats), as Mesa held to ES 3.0
    /// does; an ES 2.0 context's list is Mesa's held to ES 2.0.
    pub(super) fn extensions(&self, ctx: &Context) -> String {
        {
            let clamp = self.gpu.features.contains(wgpu::Features::DEPTH_CLIP_CONTROL);
            let depth_clamp = if clamp { " GL_EXT_depth_clamp" } else { "" };
            // Every draw buffer is a colour attachment of one pass.
            let mrt = self.gpu.limits.max_color_attachments as usize >= MAX_DRAW_BUFFERS_COUNT;
            let draw_buffers =
                if mrt { " GL_EXT_draw_buffers GL_NV_draw_buffers GL_NV_fbo_color_attachments" } else { "" };
            let dual = if self.gpu.dual_source() { " GL_EXT_blend_func_extended" } else { "" };
            let timers = if self.has_timers() { " GL_EXT_disjoint_timer_query" } else { "" };
            let border =
                if self.has_border_clamp() { " GL_EXT_texture_border_clamp GL_OES_texture_border_clamp" } else { "" };
            let float_blend = self.gpu.features.contains(wgpu::Features::FLOAT32_BLENDABLE);
            let es3 = match (ctx.es3(), float_blend) {
                (true, true) => " GL_EXT_color_buffer_float GL_EXT_float_blend",
                (true, false) => " GL_EXT_color_buffer_float",
                (false, _) => "",
            };
            format!(
                "{EXTENSIONS_STRING} {}{depth_clamp}{draw_buffers}{dual}{timers}{border}{es3}",
                texture_extensions(self.gpu.features)
            )
        }
    }

    /// Whether the device clamps to a border (`GL_EXT_texture_border_clamp` and the OES
    /// extension; the shader adds the application's colour).
    pub(super) fn has_border_clamp(&self) -> bool {
        self.gpu.features.contains(wgpu::Features::ADDRESS_MODE_CLAMP_TO_BORDER)
    }

    /// `GL_EXT_disjoint_timer_query`'s 64-bit form of `glGetIntegerv` (which, as on Mesa held
    /// to ES 2.0, does not answer `GL_TIMESTAMP_EXT`).
    pub(super) fn glGetInteger64vEXT(&mut self, ctx: &mut Context, pname: u32) -> Vec<i64> {
        self.glGetIntegerv(ctx, pname).into_iter().map(i64::from).collect()
    }

    pub(super) fn glGetIntegerv(&mut self, ctx: &mut Context, pname: u32) -> Vec<i32> {
        match self.state(ctx, pname) {
            Value::Ints(v) => v,
            // Colours and depths map [-1, 1] linearly onto the whole integer range.
            Value::Floats(f) if matches!(pname, COLOR_CLEAR_VALUE | BLEND_COLOR | DEPTH_RANGE | DEPTH_CLEAR_VALUE) => {
                f.iter().map(|x| (f64::from(x.clamp(-1.0, 1.0)) * f64::from(i32::MAX)).round() as i32).collect()
            }
            Value::Floats(f) => f.iter().map(|x| x.round() as i32).collect(),
            Value::Bools(b) => b.iter().map(|&x| i32::from(x)).collect(),
        }
    }

    pub(super) fn glGetFloatv(&mut self, ctx: &mut Context, pname: u32) -> Vec<f32> {
        match self.state(ctx, pname) {
            Value::Ints(v) => v.iter().map(|&x| x as f32).collect(),
            Value::Floats(f) => f,
            Value::Bools(b) => b.iter().map(|&x| f32::from(u8::from(x))).collect(),
        }
    }

    pub(super) fn glGetBooleanv(&mut self, ctx: &mut Context, pname: u32) -> Vec<bool> {
        match self.state(ctx, pname) {
            Value::Ints(v) => v.iter().map(|&x| x != 0).collect(),
            Value::Floats(f) => f.iter().map(|&x| x != 0.0).collect(),
            Value::Bools(b) => b,
        }
    }
}
