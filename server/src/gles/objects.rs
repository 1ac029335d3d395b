//! GL objects in one client's name tables: buffers, textures, renderbuffers, framebuffers,
//! shaders and programs, plus pixel-format conversion for uploads.

use std::collections::HashMap;
use std::sync::Arc;

use super::enums::*;
use super::glsl;

/// A buffer object: a CPU shadow (used to validate draws and convert formats) plus its GPU copy.
#[derive(Default)]
pub struct Buffer {
    /// The contents as the client last wrote them.
    pub data: Vec<u8>,
    /// The GPU copy (size rounded up to 4 bytes).
    pub gpu: Option<wgpu::Buffer>,
    /// `GL_BUFFER_USAGE`.
    pub usage: u32,
    /// Bumped on every write, so derived data (widened indices, converted attributes) can be cached.
    pub generation: u64,
}

/// Where one attachment of a framebuffer object comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Attachment {
    /// Nothing attached.
    #[default]
    None,
    /// A texture level (cube maps: face 0..6).
    Texture {
        /// Texture name.
        name: u32,
        /// Mip level.
        level: u32,
        /// Cube face, 0 for 2D.
        face: u32,
    },
    /// A renderbuffer.
    Renderbuffer(u32),
}

/// A framebuffer object.
#[derive(Default, Clone)]
pub struct Framebuffer {
    /// `COLOR_ATTACHMENT0`.
    pub color: Attachment,
    /// `DEPTH_ATTACHMENT`.
    pub depth: Attachment,
    /// `STENCIL_ATTACHMENT`.
    pub stencil: Attachment,
}

/// A renderbuffer.
#[derive(Default)]
pub struct Renderbuffer {
    /// Internal format enum, 0 until storage is allocated.
    pub format: u32,
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// The GPU image.
    pub gpu: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// Unique id for caches.
    pub uid: u64,
}

/// Sampling state of a texture (ES 2.0 keeps it in the texture object).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SamplerState {
    /// `TEXTURE_MIN_FILTER`.
    pub min: u32,
    /// `TEXTURE_MAG_FILTER`.
    pub mag: u32,
    /// `TEXTURE_WRAP_S`.
    pub wrap_s: u32,
    /// `TEXTURE_WRAP_T`.
    pub wrap_t: u32,
}

impl Default for SamplerState {
    fn default() -> Self {
        SamplerState { min: NEAREST_MIPMAP_LINEAR, mag: LINEAR, wrap_s: REPEAT, wrap_t: REPEAT }
    }
}

impl SamplerState {
    /// Whether the minification filter reads mipmaps.
    pub fn uses_mipmaps(&self) -> bool {
        !matches!(self.min, NEAREST | LINEAR)
    }
}

/// A texture object; every colour texture is stored as RGBA8 on the GPU.
#[derive(Default)]
pub struct Texture {
    /// `TEXTURE_2D` or `TEXTURE_CUBE_MAP` once bound, 0 before.
    pub target: u32,
    /// Sampling state.
    pub sampler: SamplerState,
    /// The GPU image, its view, base size and mip count.
    pub gpu: Option<TextureImage>,
    /// Per face: bitmask of the levels that have been specified.
    pub defined: [u32; 6],
    /// Internal format of level 0 (`RGBA`, `LUMINANCE`, …).
    pub format: u32,
    /// Unique id for caches; changes when the image is recreated.
    pub uid: u64,
    /// A `DEPTH_COMPONENT` texture (`OES_depth_texture`), stored as Depth32Float.
    pub depth: bool,
}

/// A texture's GPU image.
pub struct TextureImage {
    /// The texture.
    pub texture: wgpu::Texture,
    /// A view of all levels (and faces).
    pub view: wgpu::TextureView,
    /// Level-0 width.
    pub width: u32,
    /// Level-0 height.
    pub height: u32,
    /// Mip levels allocated.
    pub mips: u32,
    /// Levels of GL's full mip chain for this size (completeness is judged against these).
    pub levels: u32,
}

impl Texture {
    /// Whether sampling would read defined data (GL ES 2.0 §3.7.10 completeness).
    pub fn complete(&self) -> bool {
        let Some(img) = &self.gpu else { return false };
        let faces = if self.target == TEXTURE_CUBE_MAP { 6 } else { 1 };
        let need = if self.sampler.uses_mipmaps() { ((1u64 << img.levels) - 1) as u32 } else { 1 };
        self.defined[..faces].iter().all(|d| d & need == need)
    }
}

/// A shader object.
pub struct ShaderObj {
    /// Vertex or fragment.
    pub stage: glsl::Stage,
    /// The source as last set.
    pub source: String,
    /// The compiled interface, after a successful compile.
    pub compiled: Option<glsl::Shader>,
    /// Whether the last compile succeeded.
    pub compiled_ok: bool,
    /// The info log of the last compile.
    pub log: String,
    /// Deleted while attached: freed when detached.
    pub delete_pending: bool,
}

/// A linked program's GPU-side state.
pub struct LinkedProgram {
    /// Reflection from the linker.
    pub info: glsl::Linked,
    /// Vertex module.
    pub vs: wgpu::ShaderModule,
    /// Fragment module.
    pub fs: wgpu::ShaderModule,
    /// Bind group layout: uniform block, then texture/sampler pairs.
    pub bgl: wgpu::BindGroupLayout,
    /// Pipeline layout.
    pub layout: wgpu::PipelineLayout,
    /// Location → (uniform index, array element).
    pub locations: Vec<(usize, u32)>,
    /// Unique id for caches.
    pub id: u64,
}

/// A program object.
#[derive(Default)]
pub struct Program {
    /// Attached shader names.
    pub attached: Vec<u32>,
    /// `glBindAttribLocation` requests for the next link.
    pub bindings: HashMap<String, u32>,
    /// The result of the last successful link.
    pub linked: Option<Arc<LinkedProgram>>,
    /// Whether the last link succeeded.
    pub link_ok: bool,
    /// The info log.
    pub log: String,
    /// Uniform block contents (std140).
    pub data: Vec<u8>,
    /// Texture unit of each sampler uniform.
    pub units: Vec<u32>,
    /// Deleted while current: freed when no longer in use.
    pub delete_pending: bool,
    /// `glValidateProgram` result.
    pub validated: bool,
}

/// Bytes per pixel of a client upload, or `None` for an invalid format/type pair.
pub fn bytes_per_pixel(format: u32, ty: u32) -> Option<usize> {
    Some(match (format, ty) {
        (RGBA, UNSIGNED_BYTE) => 4,
        (RGB, UNSIGNED_BYTE) => 3,
        (LUMINANCE_ALPHA, UNSIGNED_BYTE) => 2,
        (LUMINANCE | ALPHA, UNSIGNED_BYTE) => 1,
        (RGB, UNSIGNED_SHORT_5_6_5) | (RGBA, UNSIGNED_SHORT_4_4_4_4) | (RGBA, UNSIGNED_SHORT_5_5_5_1) => 2,
        _ => return None,
    })
}

/// Bytes a `width`×`height` upload occupies with `alignment` row padding (the last row unpadded).
pub fn upload_size(width: usize, height: usize, bpp: usize, alignment: usize) -> usize {
    if width == 0 || height == 0 {
        return 0;
    }
    let row = (width * bpp).div_ceil(alignment) * alignment;
    row * (height - 1) + width * bpp
}

/// Converts a client upload to tightly packed RGBA8, honouring `UNPACK_ALIGNMENT`.
pub fn to_rgba8(src: &[u8], width: usize, height: usize, format: u32, ty: u32, alignment: usize) -> Option<Vec<u8>> {
    let bpp = bytes_per_pixel(format, ty)?;
    if src.len() < upload_size(width, height, bpp, alignment) {
        return None;
    }
    let row = (width * bpp).div_ceil(alignment) * alignment;
    let mut out = Vec::with_capacity(width * height * 4);
    let expand = |v: u16, bits: u32| -> u8 {
        let max = (1u32 << bits) - 1;
        ((u32::from(v) * 255 + max / 2) / max) as u8
    };
    for y in 0..height {
        let line = &src[y * row..y * row + width * bpp];
        for px in line.chunks_exact(bpp) {
            let rgba = match (format, ty) {
                (RGBA, UNSIGNED_BYTE) => [px[0], px[1], px[2], px[3]],
                (RGB, UNSIGNED_BYTE) => [px[0], px[1], px[2], 255],
                (LUMINANCE_ALPHA, UNSIGNED_BYTE) => [px[0], px[0], px[0], px[1]],
                (LUMINANCE, UNSIGNED_BYTE) => [px[0], px[0], px[0], 255],
                (ALPHA, UNSIGNED_BYTE) => [0, 0, 0, px[0]],
                (_, t) => {
                    let v = u16::from_ne_bytes([px[0], px[1]]);
                    match t {
                        UNSIGNED_SHORT_5_6_5 => [expand(v >> 11, 5), expand((v >> 5) & 63, 6), expand(v & 31, 5), 255],
                        UNSIGNED_SHORT_4_4_4_4 => {
                            [expand(v >> 12, 4), expand((v >> 8) & 15, 4), expand((v >> 4) & 15, 4), expand(v & 15, 4)]
                        }
                        _ => [expand(v >> 11, 5), expand((v >> 6) & 31, 5), expand((v >> 1) & 31, 5), expand(v & 1, 1)],
                    }
                }
            };
            out.extend_from_slice(&rgba);
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uploads_convert_to_rgba8() {
        // 3x1 RGB with alignment 4: one 9-byte row.
        let rgb = [1, 2, 3, 4, 5, 6, 7, 8, 9];
        assert_eq!(to_rgba8(&rgb, 3, 1, RGB, UNSIGNED_BYTE, 4).expect("rgb").len(), 12);
        // 1x2 LUMINANCE with alignment 4: rows are padded to 4 bytes.
        let l = [10, 0, 0, 0, 20];
        assert_eq!(
            to_rgba8(&l, 1, 2, LUMINANCE, UNSIGNED_BYTE, 4).expect("lum"),
            vec![10, 10, 10, 255, 20, 20, 20, 255]
        );
        let white565 = 0xFFFFu16.to_ne_bytes();
        assert_eq!(to_rgba8(&white565, 1, 1, RGB, UNSIGNED_SHORT_5_6_5, 1).expect("565"), vec![255; 4]);
        let red4444 = 0xF00Fu16.to_ne_bytes();
        assert_eq!(to_rgba8(&red4444, 1, 1, RGBA, UNSIGNED_SHORT_4_4_4_4, 1).expect("4444"), vec![255, 0, 0, 255]);
        assert!(to_rgba8(&rgb[..5], 3, 1, RGB, UNSIGNED_BYTE, 4).is_none(), "short data");
        assert!(bytes_per_pixel(RGBA, FLOAT).is_none());
    }
}
