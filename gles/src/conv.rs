//! Every mapping from GL state to wgpu state, with the conventions that tie the two together
//! written down once (the GL enums parsed at the boundary into typed values are in `typed`):
//!
//! - **Clip z.** GL clips z to [-w, w], wgpu to [0, w]: every vertex shader's generated `main`
//!   maps z to (z + w) / 2 (`glsl/link.rs`).
//! - **Y flip and winding.** The same `main` negates y, so memory row 0 is GL's bottom row.
//!   Mirroring the image reverses the winding, so GL's front face is the opposite one in wgpu
//!   ([`front_face`]).
//! - **Window coordinates.** Because of the flip, viewport and scissor rectangles are used as
//!   GL gives them, bottom-left origin included ([`viewport`], [`clip_rect`]).
//! - **Depth range.** `glDepthRangef` becomes the viewport's depth range ([`viewport`]).
//! - **Reversed Z.** Framebuffer 0 of a surface with a declared forward perspective
//!   projection under `stratad serve --reversed-z` stores 1 − GL's depth: its vertex stages
//!   compute clip z as `n·(f − w)/(f − n)` (`glsl/link.rs`), and the depth state is mirrored
//!   ([`Mirror`]): compare functions swap less and greater, a clear value c becomes 1 − c, the
//!   depth range [a, b] becomes [1 − b, 1 − a], polygon offset is negated.
//! - **Texture origin.** GL's first uploaded row is the bottom row (t = 0), which is memory
//!   row 0: uploads, render-to-texture and `glReadPixels` need no flips.

use crate::enums::*;
use crate::limits::MAX_TEXTURE;
use crate::objects::texture::SamplerState;
use crate::render::Target;

/// Whether `f` is one of the eight comparison functions.
pub fn valid_func(f: u32) -> bool {
    (NEVER..=ALWAYS).contains(&f)
}

/// The wgpu comparison for a (validated) GL comparison function.
pub fn compare(f: u32) -> wgpu::CompareFunction {
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

/// The depth state of a reversed-Z framebuffer: GL's depth d is stored as 1 − d, so every
/// depth comparison, value and offset the application gives is mirrored.
pub struct Mirror;

impl Mirror {
    /// The compare function that orders 1 − d as `f` orders d.
    pub fn compare(f: wgpu::CompareFunction) -> wgpu::CompareFunction {
        use wgpu::CompareFunction as C;
        match f {
            C::Less => C::Greater,
            C::LessEqual => C::GreaterEqual,
            C::Greater => C::Less,
            C::GreaterEqual => C::LessEqual,
            other => other,
        }
    }

    /// The stored value of depth `d` (a clear value).
    pub fn depth(d: f32) -> f32 {
        1.0 - d
    }

    /// The depth range `[a, b]` as stored: `[1 − b, 1 − a]`.
    pub fn range([a, b]: [f32; 2]) -> [f32; 2] {
        [1.0 - b, 1.0 - a]
    }

    /// Polygon offset (factor bits, units, clamp bits) as stored: all three negated (a
    /// clamp bounds the offset's size on the side the offset moves to).
    pub fn bias((factor, units, clamp): (u32, i32, u32)) -> (u32, i32, u32) {
        ((-f32::from_bits(factor)).to_bits(), units.saturating_neg(), (-f32::from_bits(clamp)).to_bits())
    }
}

/// Whether `op` is a stencil operation.
pub fn valid_stencil_op(op: u32) -> bool {
    matches!(op, ZERO | KEEP | REPLACE | INCR | DECR | INVERT | INCR_WRAP | DECR_WRAP)
}

/// The wgpu stencil operation for a (validated) GL one.
pub fn stencil_op(op: u32) -> wgpu::StencilOperation {
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

/// The wgpu blend factor for a GL one, `None` if `f` is not a blend factor.
pub fn blend_factor(f: u32) -> Option<wgpu::BlendFactor> {
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
        // GL_EXT_blend_func_extended: the fragment's second colour.
        SRC1_COLOR_EXT => B::Src1,
        ONE_MINUS_SRC1_COLOR_EXT => B::OneMinusSrc1,
        SRC1_ALPHA_EXT => B::Src1Alpha,
        ONE_MINUS_SRC1_ALPHA_EXT => B::OneMinusSrc1Alpha,
        _ => return None,
    })
}

/// Whether `f` reads the second colour (`GL_EXT_blend_func_extended`).
pub fn reads_src1(f: u32) -> bool {
    matches!(f, SRC1_COLOR_EXT | ONE_MINUS_SRC1_COLOR_EXT | SRC1_ALPHA_EXT | ONE_MINUS_SRC1_ALPHA_EXT)
}

/// The wgpu blend operation for a GL blend equation (`EXT_blend_minmax` included), `None`
/// if `e` is not one.
pub fn blend_op(e: u32) -> Option<wgpu::BlendOperation> {
    Some(match e {
        FUNC_ADD => wgpu::BlendOperation::Add,
        FUNC_SUBTRACT => wgpu::BlendOperation::Subtract,
        FUNC_REVERSE_SUBTRACT => wgpu::BlendOperation::ReverseSubtract,
        MIN_EXT => wgpu::BlendOperation::Min,
        MAX_EXT => wgpu::BlendOperation::Max,
        _ => return None,
    })
}

/// One blend component: GL's `MIN`/`MAX` ignore the factors, and wgpu requires them to be
/// `One` for those operations. Without a second colour (`dual` false: the program writes
/// none, which GL leaves undefined and wgpu refuses to blend with) the second colour's factors
/// read it as 0.
pub fn blend_component(src: u32, dst: u32, eq: u32, dual: bool) -> wgpu::BlendComponent {
    let operation = blend_op(eq).unwrap_or(wgpu::BlendOperation::Add);
    if matches!(operation, wgpu::BlendOperation::Min | wgpu::BlendOperation::Max) {
        return wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation,
        };
    }
    let f = |x| match (blend_factor(x).unwrap_or(wgpu::BlendFactor::One), dual) {
        (wgpu::BlendFactor::Src1 | wgpu::BlendFactor::Src1Alpha, false) => wgpu::BlendFactor::Zero,
        (wgpu::BlendFactor::OneMinusSrc1 | wgpu::BlendFactor::OneMinusSrc1Alpha, false) => wgpu::BlendFactor::One,
        (b, _) => b,
    };
    wgpu::BlendComponent { src_factor: f(src), dst_factor: f(dst), operation }
}

/// wgpu's front face for GL's: the y flip mirrors the image, so the winding reverses.
pub fn front_face(gl_front_ccw: bool) -> wgpu::FrontFace {
    if gl_front_ccw {
        wgpu::FrontFace::Cw
    } else {
        wgpu::FrontFace::Ccw
    }
}

/// The colour write mask of `glColorMask`'s four flags.
pub fn color_writes(mask: [bool; 4]) -> wgpu::ColorWrites {
    let mut writes = wgpu::ColorWrites::empty();
    for (bit, on) in
        [wgpu::ColorWrites::RED, wgpu::ColorWrites::GREEN, wgpu::ColorWrites::BLUE, wgpu::ColorWrites::ALPHA]
            .into_iter()
            .zip(mask)
    {
        if on {
            writes |= bit;
        }
    }
    writes
}

/// A GL window rectangle (x, y, w, h, bottom-left origin) clipped to the target, as wgpu's
/// scissor wants it; the y flip makes GL's window y the target's row.
pub fn clip_rect(r: [i32; 4], t: &Target) -> [u32; 4] {
    let x0 = r[0].clamp(0, t.width as i32);
    let y0 = r[1].clamp(0, t.height as i32);
    let x1 = (r[0].saturating_add(r[2])).clamp(0, t.width as i32);
    let y1 = (r[1].saturating_add(r[3])).clamp(0, t.height as i32);
    [x0 as u32, y0 as u32, (x1 - x0).max(0) as u32, (y1 - y0).max(0) as u32]
}

/// wgpu's viewport (x, y, w, h, min depth, max depth) for GL's viewport and depth range, or
/// `None` if it is empty. It may extend past the target: wgpu, like Vulkan, accepts viewports
/// within twice the largest dimension, and clips. Beyond that it is moved inside that range,
/// where it still covers no pixel of any target.
pub fn viewport(vp: [i32; 4], depth_range: [f32; 2]) -> Option<[f32; 6]> {
    let [vx, vy, vw, vh] = vp;
    if vw <= 0 || vh <= 0 {
        return None;
    }
    let bound = 2 * i64::from(MAX_TEXTURE);
    let place = |v: i32, size: i32| i64::from(v).clamp(-bound, bound - 1 - i64::from(size)) as f32;
    Some([
        place(vx, vw),
        place(vy, vh),
        vw as f32,
        vh as f32,
        depth_range[0].min(depth_range[1]),
        depth_range[0].max(depth_range[1]),
    ])
}

/// Bytes per component of a vertex attribute type, `None` if `ty` is not one.
pub fn type_size(ty: u32) -> Option<usize> {
    Some(match ty {
        BYTE | UNSIGNED_BYTE => 1,
        SHORT | UNSIGNED_SHORT | HALF_FLOAT_OES => 2,
        FLOAT | FIXED => 4,
        _ => return None,
    })
}

/// The wgpu format that reads GL attribute data as-is, if there is one.
pub fn native_format(ty: u32, size: i32, normalized: bool) -> Option<wgpu::VertexFormat> {
    use wgpu::VertexFormat as F;
    Some(match (ty, size, normalized) {
        (FLOAT, 1, _) => F::Float32,
        (FLOAT, 2, _) => F::Float32x2,
        (FLOAT, 3, _) => F::Float32x3,
        (FLOAT, 4, _) => F::Float32x4,
        (HALF_FLOAT_OES | HALF_FLOAT, 2, _) => F::Float16x2,
        (HALF_FLOAT_OES | HALF_FLOAT, 4, _) => F::Float16x4,
        (UNSIGNED_BYTE, 4, true) => F::Unorm8x4,
        (BYTE, 4, true) => F::Snorm8x4,
        (UNSIGNED_SHORT, 2, true) => F::Unorm16x2,
        (UNSIGNED_SHORT, 4, true) => F::Unorm16x4,
        (SHORT, 2, true) => F::Snorm16x2,
        (SHORT, 4, true) => F::Snorm16x4,
        _ => return None,
    })
}

/// `GL_INT_2_10_10_10_REV` (ES 3.0): four signed components packed in 32 bits.
pub const INT_2_10_10_10_REV: u32 = 0x8D9F;

/// Whether `ty` may type a float attribute's array: ES 2.0's types and `GL_HALF_FLOAT` (Mesa
/// takes ES 3.0's value for the OES one in ES 2.0 contexts too), and in an ES 3.0 context
/// (`es3`) its 32-bit integers and the two packed types.
pub fn attrib_type(ty: u32, es3: bool) -> bool {
    type_size(ty).is_some()
        || ty == HALF_FLOAT
        || (es3 && matches!(ty, INT | UNSIGNED_INT | INT_2_10_10_10_REV | UNSIGNED_INT_2_10_10_10_REV_EXT))
}

/// Whether `ty` packs a whole element into 32 bits (size 4 only).
pub fn packed(ty: u32) -> bool {
    matches!(ty, INT_2_10_10_10_REV | UNSIGNED_INT_2_10_10_10_REV_EXT)
}

/// Bytes of one element of `size` components of `ty`.
pub fn element_size(ty: u32, size: i32) -> usize {
    match ty {
        _ if packed(ty) => 4,
        INT | UNSIGNED_INT => 4 * size as usize,
        HALF_FLOAT => 2 * size as usize,
        _ => type_size(ty).unwrap_or(4) * size as usize,
    }
}

/// A signed integer of `bits` bits as GL converts it to float (ES 3.0 §2.1.6.1): as it is, or
/// normalized to [-1, 1] by `max(c / (2^(bits-1) - 1), -1)`, as the device's snorm formats do.
fn signed(v: i64, bits: u32, normalized: bool) -> f32 {
    if normalized {
        (v as f64 / ((1i64 << (bits - 1)) - 1) as f64).max(-1.0) as f32
    } else {
        v as f32
    }
}

/// An unsigned integer of `bits` bits as GL converts it to float: as it is, or `c / (2^bits - 1)`.
fn unsigned(v: u64, bits: u32, normalized: bool) -> f32 {
    if normalized {
        (v as f64 / ((1u64 << bits) - 1) as f64) as f32
    } else {
        v as f32
    }
}

/// Reads one attribute component as GL converts it to float (ES 3.0 §2.9, table 2.2).
pub fn component(bytes: &[u8], ty: u32, normalized: bool) -> f32 {
    let word = || [bytes[0], bytes[1], bytes[2], bytes[3]];
    match ty {
        FLOAT => f32::from_ne_bytes(word()),
        FIXED => i32::from_ne_bytes(word()) as f32 / 65536.0,
        HALF_FLOAT_OES | HALF_FLOAT => half::f16::from_bits(u16::from_ne_bytes([bytes[0], bytes[1]])).to_f32(),
        UNSIGNED_BYTE => unsigned(u64::from(bytes[0]), 8, normalized),
        BYTE => signed(i64::from(bytes[0] as i8), 8, normalized),
        UNSIGNED_SHORT => unsigned(u64::from(u16::from_ne_bytes([bytes[0], bytes[1]])), 16, normalized),
        INT => signed(i64::from(i32::from_ne_bytes(word())), 32, normalized),
        UNSIGNED_INT => unsigned(u64::from(u32::from_ne_bytes(word())), 32, normalized),
        _ => signed(i64::from(i16::from_ne_bytes([bytes[0], bytes[1]])), 16, normalized),
    }
}

/// Appends one element of `size` components of `ty` at the start of `bytes` as floats.
pub fn element(bytes: &[u8], ty: u32, size: i32, normalized: bool, out: &mut Vec<u8>) {
    if packed(ty) {
        // x in bits 0-9, y 10-19, z 20-29, w 30-31.
        let v = u32::from_ne_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
        for (shift, bits) in [(0, 10), (10, 10), (20, 10), (30, 2)] {
            let raw = (v >> shift) & ((1 << bits) - 1);
            let f = if ty == INT_2_10_10_10_REV {
                // Sign-extended from `bits` bits.
                let s = (i64::from(raw) << (64 - bits)) >> (64 - bits);
                signed(s, bits, normalized)
            } else {
                unsigned(u64::from(raw), bits, normalized)
            };
            out.extend_from_slice(&f.to_ne_bytes());
        }
        return;
    }
    let ts = element_size(ty, 1);
    for c in 0..size as usize {
        out.extend_from_slice(&component(&bytes[c * ts..c * ts + ts], ty, normalized).to_ne_bytes());
    }
}

/// The float vertex format with `n` components (converted attributes).
pub fn float_format(n: i32) -> wgpu::VertexFormat {
    match n {
        1 => wgpu::VertexFormat::Float32,
        2 => wgpu::VertexFormat::Float32x2,
        3 => wgpu::VertexFormat::Float32x3,
        _ => wgpu::VertexFormat::Float32x4,
    }
}

/// The wgpu sampler for a texture's GL sampling state; `white`: the border sampler of
/// `GL_CLAMP_TO_BORDER_EXT`, whose border is opaque white where the other's is transparent
/// black (`glsl::link::lookup_helpers` weighs the application's border colour by their
/// difference).
pub fn sampler_descriptor(s: SamplerState, white: bool) -> wgpu::SamplerDescriptor<'static> {
    let filter = |f: u32| {
        if matches!(f, LINEAR | LINEAR_MIPMAP_NEAREST | LINEAR_MIPMAP_LINEAR) {
            wgpu::FilterMode::Linear
        } else {
            wgpu::FilterMode::Nearest
        }
    };
    let wrap = |w: u32| match w {
        // GL_EXT_texture_mirror_clamp_to_edge: the shader takes the coordinate's magnitude.
        CLAMP_TO_EDGE | MIRROR_CLAMP_TO_EDGE_EXT => wgpu::AddressMode::ClampToEdge,
        CLAMP_TO_BORDER_EXT => wgpu::AddressMode::ClampToBorder,
        MIRRORED_REPEAT => wgpu::AddressMode::MirrorRepeat,
        _ => wgpu::AddressMode::Repeat,
    };
    let mip = if matches!(s.min, NEAREST_MIPMAP_LINEAR | LINEAR_MIPMAP_LINEAR) {
        wgpu::MipmapFilterMode::Linear
    } else {
        wgpu::MipmapFilterMode::Nearest
    };
    let all_linear = s.mag == LINEAR && s.min == LINEAR_MIPMAP_LINEAR;
    // Levels of detail count from the base level (the view's first); levels past
    // TEXTURE_MAX_LEVEL are never sampled; GL_TEXTURE_MIN_LOD and _MAX_LOD clamp within that
    // (a negative least level is the base level's).
    // A device chooses between the magnification and minification filters by the clamped
    // level of detail: a most of 0 would always magnify. Where one level is read (no mipmap
    // filter, or a nearest one over one level) the most is a quarter, which still rounds to
    // the first level.
    let lod_max = if s.uses_mipmaps() {
        let levels = s.max_level.saturating_sub(s.base_level) as f32;
        let one: f32 = if mip == wgpu::MipmapFilterMode::Nearest { 0.25 } else { 0.0 };
        levels.min(f32::from_bits(s.max_lod)).clamp(0.0, 32.0).max(one.min(f32::from_bits(s.max_lod).max(0.0)))
    } else {
        0.25f32.min(f32::from_bits(s.max_lod).max(0.0))
    };
    let least = f32::from_bits(s.min_lod);
    let lod_min = if least.is_nan() { 0.0 } else { least.clamp(0.0, lod_max) };
    wgpu::SamplerDescriptor {
        label: None,
        address_mode_u: wrap(s.wrap_s),
        address_mode_v: wrap(s.wrap_t),
        address_mode_w: wrap(s.wrap_r),
        mag_filter: filter(s.mag),
        min_filter: filter(s.min),
        mipmap_filter: mip,
        lod_min_clamp: lod_min,
        lod_max_clamp: lod_max,
        compare: None,
        // wgpu filters anisotropically only with every filter linear: GL's anisotropy with
        // another filter is left out.
        anisotropy_clamp: if all_linear { f32::from_bits(s.anisotropy).round().clamp(1.0, 16.0) as u16 } else { 1 },
        border_color: s.clamps_to_border(true).then_some(if white {
            wgpu::SamplerBorderColor::OpaqueWhite
        } else {
            wgpu::SamplerBorderColor::TransparentBlack
        }),
    }
}
