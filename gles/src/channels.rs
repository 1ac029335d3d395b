//! The channels of each colour format: the bits of each (as Strata keeps the format), the
//! channels an attachment lacks (which draws never write), and the border colour a texture of
//! the format shows.

use crate::enums::*;
use crate::formats::Storage;

/// Red, green, blue and alpha bits of a colour texture's or renderbuffer's format `f`: colour
/// is stored as 8 bits per channel whatever the format, and a channel the format lacks has
/// none (RGB and luminance have no alpha bits; `GL_EXT_texture_rg`'s RED and RG no blue).
pub fn color_bits(f: u32) -> [i32; 4] {
    match f {
        RGBA16F_EXT => [16; 4],
        RGB16F_EXT => [16, 16, 16, 0],
        RG16F_EXT => [16, 16, 0, 0],
        R16F_EXT => [16, 0, 0, 0],
        // ES 3.0's (GL_EXT_color_buffer_float's) renderbuffer formats.
        RGBA32F => [32; 4],
        RG32F => [32, 32, 0, 0],
        R32F => [32, 0, 0, 0],
        crate::packed_float::R11F_G11F_B10F => [11, 11, 10, 0],
        RGB10_A2_EXT => [10, 10, 10, 2],
        RGB | LUMINANCE | RGB565 | RGB8_OES => [8, 8, 8, 0],
        RED_EXT | R8_EXT => [8, 0, 0, 0],
        RG_EXT | RG8_EXT => [8, 8, 0, 0],
        _ => crate::integer::IntFormat::from_gl(f).map_or([8; 4], |i| i.color_bits()),
    }
}

/// The bits of a colour texture of format `f` stored as `storage`: half-float images hold 16
/// per channel their format has, float ones 32, the packed formats their own.
pub fn texture_color_bits(f: u32, storage: Option<Storage>) -> [i32; 4] {
    let bits = color_bits(f);
    match storage {
        Some(Storage::Half) => bits.map(|b| if b == 0 { 0 } else { 16 }),
        Some(Storage::Float) => bits.map(|b| if b == 0 { 0 } else { 32 }),
        Some(Storage::Rgb10a2) => [10, 10, 10, 2],
        Some(Storage::Rg11b10) => [11, 11, 10, 0],
        Some(Storage::Int { bits: 10, .. }) => [10, 10, 10, 2],
        Some(Storage::Int { bits: n, .. }) => bits.map(|b| if b == 0 { 0 } else { i32::from(n) }),
        _ => bits,
    }
}

/// Whether `f` is one of ES 3.0's float renderbuffer formats of `GL_EXT_color_buffer_float`
/// beyond the half-float ones: 32-bit float red, red-green and RGBA, and packed
/// `R11F_G11F_B10F`.
pub fn is_float_renderbuffer(f: u32) -> bool {
    matches!(f, R32F | RG32F | RGBA32F | crate::packed_float::R11F_G11F_B10F)
}

/// Whether `f` is a half-float renderbuffer format (`GL_EXT_color_buffer_half_float`).
pub fn is_half_renderbuffer(f: u32) -> bool {
    matches!(f, RGBA16F_EXT | RGB16F_EXT | RG16F_EXT | R16F_EXT)
}

/// The channels a colour attachment of format `f` lacks (see [`color_bits`]); luminance is
/// never attached, so only its alpha counts.
pub fn absent_channels(f: u32) -> wgpu::ColorWrites {
    let bits = color_bits(f);
    let mut absent = wgpu::ColorWrites::empty();
    for (b, ch) in bits.iter().zip([
        wgpu::ColorWrites::RED,
        wgpu::ColorWrites::GREEN,
        wgpu::ColorWrites::BLUE,
        wgpu::ColorWrites::ALPHA,
    ]) {
        if *b == 0 {
            absent |= ch;
        }
    }
    absent
}

/// The border colour (`GL_EXT_texture_border_clamp`) a texture of internal format `f` shows:
/// `c` as a texel of that format (a colour channel it lacks 0, a lacking alpha 1, luminance
/// and depth from red, an alpha image black), clamped to [0, 1] unless the image is `float`.
pub fn border_color(f: u32, float: bool, c: [f32; 4]) -> [f32; 4] {
    let [r, g, b, a] = if float { c } else { c.map(|v| v.clamp(0.0, 1.0)) };
    match f {
        LUMINANCE | LUMINANCE8_OES | DEPTH_COMPONENT | DEPTH_STENCIL_OES => [r, r, r, 1.0],
        LUMINANCE_ALPHA | LUMINANCE8_ALPHA8_OES | LUMINANCE4_ALPHA4_OES => [r, r, r, a],
        ALPHA | ALPHA8_OES => [0.0, 0.0, 0.0, a],
        // ETC1 and the opaque DXT1 formats have no alpha.
        0x8D64 | 0x83F0 | 0x8C4C => [r, g, b, 1.0],
        _ => {
            let bits = color_bits(f);
            let keep = |i: usize, v: f32, absent: f32| if bits[i] == 0 { absent } else { v };
            [keep(0, r, 0.0), keep(1, g, 0.0), keep(2, b, 0.0), keep(3, a, 1.0)]
        }
    }
}
