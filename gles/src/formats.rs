//! Texture formats: which GL format/type pairs an upload accepts, the storage each is kept in
//! on the GPU, and the compressed formats offered (S3TC, ETC1 and ASTC LDR, sampled natively
//! where the device has the block format, else decoded on upload).

use crate::compressed::{astc, astc::Astc, etc1, etc2::Etc2, s3tc::S3tc};
use crate::enums::*;
use crate::error::{GlError, GlResult};

/// Colour format of every colour target and texture.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Format of half-float colour buffers (`GL_EXT_color_buffer_half_float`), whatever channels
/// their GL format has.
pub const HALF_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// How a texture's texels are kept on the GPU.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Storage {
    /// RGBA8: every 8-bit and packed 16-bit colour upload, BGRA, and compressed images that
    /// are decoded on upload.
    Rgba8,
    /// RGBA8 holding sRGB-encoded colour (ES 3.0's `SRGB8_ALPHA8` and `SRGB8`): sampled as
    /// linear, written (and blended) in linear and encoded.
    Srgb8,
    /// RGBA16F: `HALF_FLOAT_OES` uploads (`OES_texture_half_float`).
    Half,
    /// RGBA32F: `FLOAT` uploads (`OES_texture_float`), and ES 3.0's 32-bit float formats.
    Float,
    /// 10-bit RGB and 2-bit alpha, normalized: ES 3.0's `RGB10_A2`, kept in its own precision
    /// so that draws into it round as GL's 10- and 2-bit channels do.
    Rgb10a2,
    /// Unsigned 11-, 11- and 10-bit floats: ES 3.0's `R11F_G11F_B10F` on a device that renders
    /// to that format (elsewhere it is kept as [`Storage::Half`]).
    Rg11b10,
    /// Depth32Float: `DEPTH_COMPONENT` (`OES_depth_texture`).
    Depth,
    /// Depth24PlusStencil8: `DEPTH_STENCIL_OES` (`OES_packed_depth_stencil`).
    DepthStencil,
    /// The compressed blocks as they were uploaded, in the device's matching block format.
    Native(Compressed),
    /// Integers (ES 3.0's `*I` and `*UI` formats): RGBA of `bits`-bit components, signed or
    /// unsigned; `bits` 10 is `RGB10_A2UI`'s packed layout ([`crate::integer`]).
    Int {
        /// Whether the components are signed.
        signed: bool,
        /// Bits per component (10: 10/10/10/2).
        bits: u8,
    },
}

impl Storage {
    /// The wgpu format of the image.
    pub fn wgpu(self) -> wgpu::TextureFormat {
        match self {
            Storage::Rgba8 => COLOR_FORMAT,
            Storage::Srgb8 => wgpu::TextureFormat::Rgba8UnormSrgb,
            Storage::Half => wgpu::TextureFormat::Rgba16Float,
            Storage::Float => wgpu::TextureFormat::Rgba32Float,
            Storage::Rgb10a2 => wgpu::TextureFormat::Rgb10a2Unorm,
            Storage::Rg11b10 => wgpu::TextureFormat::Rg11b10Ufloat,
            Storage::Depth => wgpu::TextureFormat::Depth32Float,
            Storage::DepthStencil => wgpu::TextureFormat::Depth24PlusStencil8,
            Storage::Native(c) => c.native_format().unwrap_or(COLOR_FORMAT),
            Storage::Int { signed, bits } => crate::integer::int_wgpu(signed, bits),
        }
    }

    /// Bytes per texel of the data an upload writes (RGBA of the storage's component type).
    pub fn texel_bytes(self) -> u32 {
        match self {
            Storage::Half => 8,
            Storage::Float => 16,
            Storage::Int { bits, .. } => crate::integer::texel_bytes(bits),
            _ => 4,
        }
    }

    /// An integer image.
    pub fn is_int(self) -> bool {
        matches!(self, Storage::Int { .. })
    }

    /// A depth or depth-stencil image.
    pub fn is_depth(self) -> bool {
        matches!(self, Storage::Depth | Storage::DepthStencil)
    }

    /// Whether a framebuffer can render into it as its colour attachment, when its format is
    /// `f` and its data came as `GL_HALF_FLOAT_OES` (`half`): 8-bit images, and half-float
    /// RGBA, RGB, RG and RED ones (`GL_EXT_color_buffer_half_float`; not luminance or alpha,
    /// nor 2_10_10_10 images, as on Mesa); in ES 3.0 (`es3`) also `RGB10_A2` and
    /// `R11F_G11F_B10F` images (`GL_EXT_color_buffer_float`; 32-bit float images are judged
    /// by [`float_attachment`]); compressed images never.
    pub fn color_renderable(self, f: u32, half: bool, es3: bool) -> bool {
        self == Storage::Rgba8
            || (self.is_int() && f != RGB)
            || (self == Storage::Srgb8 && f == RGBA)
            || (self == Storage::Half && half && matches!(f, RGBA | RGB | RG_EXT | RED_EXT))
            || (es3 && matches!(self, Storage::Rgb10a2 | Storage::Rg11b10))
    }

    /// This storage as a device with `features` keeps it: `R11F_G11F_B10F` images as half
    /// floats where the device cannot render to its packed format.
    pub fn on(self, features: wgpu::Features) -> Storage {
        match self {
            Storage::Rg11b10 if !features.contains(wgpu::Features::RG11B10UFLOAT_RENDERABLE) => Storage::Half,
            s => s,
        }
    }

    /// Whether the image can be a render attachment in wgpu at all.
    pub fn attachable(self) -> bool {
        !matches!(self, Storage::Native(_))
    }
}

/// Whether an ES 3.0 context's framebuffer renders into a 32-bit float image of unsized format
/// `base` made in sized format `sized` (0 for an unsized image), or the status that says why
/// not, as Mesa answers (`GL_EXT_color_buffer_float`): `R32F`, `RG32F` and `RGBA32F`, and the
/// unsized RED and RG float images, which Mesa makes those; RGB and RGBA ones unsized, and
/// `RGB32F`, unsupported; luminance and alpha ones incomplete.
pub fn float_attachment(base: u32, sized: u32) -> Result<(), u32> {
    match (sized, base) {
        (R32F | RG32F | RGBA32F, _) | (0, RED_EXT | RG_EXT) => Ok(()),
        (RGB32F, _) | (0, RGB | RGBA) => Err(FRAMEBUFFER_UNSUPPORTED),
        _ => Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT),
    }
}

/// Whether a colour buffer of `format` holds floats that are not clamped to [0, 1]: half and
/// 32-bit floats, and the packed 11- and 10-bit ones.
pub fn is_float_color(format: wgpu::TextureFormat) -> bool {
    use wgpu::TextureFormat as F;
    matches!(format, F::Rgba16Float | F::Rgba32Float | F::Rg11b10Ufloat)
}

/// A compressed internal format offered by `glCompressedTexImage2D`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Compressed {
    /// One of `EXT_texture_compression_s3tc`'s four formats.
    S3tc(S3tc),
    /// Its sRGB form (`EXT_texture_compression_s3tc_srgb`): the colour channels are sRGB
    /// encoded, and read as linear.
    S3tcSrgb(S3tc),
    /// `ETC1_RGB8_OES` (`OES_compressed_ETC1_RGB8_texture`).
    Etc1,
    /// An ASTC LDR format of one footprint (`KHR_texture_compression_astc_ldr`).
    Astc(Astc),
    /// Its sRGB form: the colour channels are sRGB encoded, and read as linear.
    AstcSrgb(Astc),
    /// An ETC2 or EAC format (ES 3.0 contexts only).
    Etc2(Etc2),
    /// Its sRGB form: the colour channels are sRGB encoded, and read as linear.
    Etc2Srgb(Etc2),
}

/// The S3TC and ETC1 formats, in the order `GL_COMPRESSED_TEXTURE_FORMATS` lists the offered
/// ones; the ASTC formats follow them ([`Astc::all_gl`]).
const COMPRESSED_FORMATS: [u32; 5] = [
    COMPRESSED_RGB_S3TC_DXT1_EXT,
    COMPRESSED_RGBA_S3TC_DXT1_EXT,
    COMPRESSED_RGBA_S3TC_DXT3_EXT,
    COMPRESSED_RGBA_S3TC_DXT5_EXT,
    ETC1_RGB8_OES,
];

impl Compressed {
    /// The compressed format `f` names, if it is one offered.
    pub fn from_gl(f: u32) -> Option<Self> {
        Some(match f {
            COMPRESSED_RGB_S3TC_DXT1_EXT => Compressed::S3tc(S3tc::Dxt1Rgb),
            COMPRESSED_RGBA_S3TC_DXT1_EXT => Compressed::S3tc(S3tc::Dxt1Rgba),
            COMPRESSED_RGBA_S3TC_DXT3_EXT => Compressed::S3tc(S3tc::Dxt3),
            COMPRESSED_RGBA_S3TC_DXT5_EXT => Compressed::S3tc(S3tc::Dxt5),
            COMPRESSED_SRGB_S3TC_DXT1_EXT => Compressed::S3tcSrgb(S3tc::Dxt1Rgb),
            COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT => Compressed::S3tcSrgb(S3tc::Dxt1Rgba),
            COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT => Compressed::S3tcSrgb(S3tc::Dxt3),
            COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT => Compressed::S3tcSrgb(S3tc::Dxt5),
            ETC1_RGB8_OES => Compressed::Etc1,
            _ if Etc2::from_gl(f).is_some() => match Etc2::from_gl(f)? {
                (e, false) => Compressed::Etc2(e),
                (e, true) => Compressed::Etc2Srgb(e),
            },
            _ => match Astc::from_gl(f)? {
                (a, false) => Compressed::Astc(a),
                (a, true) => Compressed::AstcSrgb(a),
            },
        })
    }

    /// Bytes per block.
    pub fn block_bytes(self) -> usize {
        match self {
            Compressed::S3tc(d) | Compressed::S3tcSrgb(d) => d.block_bytes(),
            Compressed::Etc1 => 8,
            Compressed::Etc2(e) | Compressed::Etc2Srgb(e) => e.block_bytes(),
            Compressed::Astc(_) | Compressed::AstcSrgb(_) => astc::BLOCK_BYTES,
        }
    }

    /// Width and height of a block in texels: 4×4 but for ASTC's footprints.
    pub fn block_size(self) -> (u32, u32) {
        match self {
            Compressed::Astc(a) | Compressed::AstcSrgb(a) => (u32::from(a.width), u32::from(a.height)),
            _ => (4, 4),
        }
    }

    /// Whether the colour channels are sRGB encoded.
    pub fn is_srgb(self) -> bool {
        matches!(self, Compressed::S3tcSrgb(_) | Compressed::AstcSrgb(_) | Compressed::Etc2Srgb(_))
    }

    /// Blocks across and down a `width`×`height` image: one per started block.
    pub fn blocks(self, width: u32, height: u32) -> (u32, u32) {
        let (bw, bh) = self.block_size();
        (width.div_ceil(bw), height.div_ceil(bh))
    }

    /// Bytes of a `width`×`height` image.
    pub fn image_size(self, width: u32, height: u32) -> usize {
        let (across, down) = self.blocks(width, height);
        across as usize * down as usize * self.block_bytes()
    }

    /// The wgpu block format that samples exactly as GL defines this format. DXT1's RGB
    /// variant has none: its "transparent" code is opaque black, wgpu's BC1 gives alpha 0.
    pub fn native_format(self) -> Option<wgpu::TextureFormat> {
        use wgpu::TextureFormat as F;
        match self {
            Compressed::S3tc(S3tc::Dxt1Rgb) => None,
            Compressed::S3tc(S3tc::Dxt1Rgba) => Some(F::Bc1RgbaUnorm),
            Compressed::S3tc(S3tc::Dxt3) => Some(F::Bc2RgbaUnorm),
            Compressed::S3tc(S3tc::Dxt5) => Some(F::Bc3RgbaUnorm),
            Compressed::S3tcSrgb(S3tc::Dxt1Rgb) => None,
            Compressed::S3tcSrgb(S3tc::Dxt1Rgba) => Some(F::Bc1RgbaUnormSrgb),
            Compressed::S3tcSrgb(S3tc::Dxt3) => Some(F::Bc2RgbaUnormSrgb),
            Compressed::S3tcSrgb(S3tc::Dxt5) => Some(F::Bc3RgbaUnormSrgb),
            // ETC1 is the subset of ETC2 RGB8 without ETC2's extra modes.
            Compressed::Etc1 => Some(F::Etc2Rgb8Unorm),
            Compressed::Astc(a) => Some(a.native(false)),
            Compressed::AstcSrgb(a) => Some(a.native(true)),
            Compressed::Etc2(e) => Some(e.native(false)),
            Compressed::Etc2Srgb(e) => Some(e.native(true)),
        }
    }

    /// Whether a device with `features` offers this format to a context of ES 3.0 (`es3`) or
    /// 2.0: ETC1 and ASTC everywhere (decoded where the device lacks them), S3TC where the
    /// device has BC formats, ETC2 and EAC in ES 3.0 (decoded likewise).
    pub fn offered(self, features: wgpu::Features, es3: bool) -> bool {
        match self {
            Compressed::S3tc(_) | Compressed::S3tcSrgb(_) => features.contains(wgpu::Features::TEXTURE_COMPRESSION_BC),
            Compressed::Etc1 | Compressed::Astc(_) | Compressed::AstcSrgb(_) => true,
            Compressed::Etc2(_) | Compressed::Etc2Srgb(_) => es3,
        }
    }

    /// The compressed format `f` names, if a device with `features` offers it to a context of
    /// ES 3.0 (`es3`) or 2.0.
    pub fn offered_gl(f: u32, features: wgpu::Features, es3: bool) -> Option<Self> {
        Self::from_gl(f).filter(|c| c.offered(features, es3))
    }

    /// The EAC format this is, if it is one: decoded to float.
    fn eac(self) -> Option<Etc2> {
        match self {
            Compressed::Etc2(e) if e.is_eac() => Some(e),
            _ => None,
        }
    }

    /// The native format if `features` make it available.
    pub fn native_on(self, features: wgpu::Features) -> Option<wgpu::TextureFormat> {
        self.native_format().filter(|f| features.contains(f.required_features()))
    }

    /// The storage of an image of this format that is decoded on upload: RGBA8, or for the
    /// sRGB formats RGBA16F holding the linear values ([`Self::decode_for`]), which filter as
    /// GL filters an sRGB image, after the conversion.
    pub fn decoded_storage(self) -> Storage {
        if self.is_srgb() || self.eac().is_some() {
            Storage::Half
        } else {
            Storage::Rgba8
        }
    }

    /// Decodes a `width`×`height` image to texels of [`Self::decoded_storage`].
    pub fn decode_for(self, data: &[u8], width: u32, height: u32) -> Vec<u8> {
        if let Some(e) = self.eac() {
            let texels = self.place(data, width, height, |b| e.decode_eac_block(b).to_vec());
            return texels.iter().flatten().flat_map(|&v| half::f16::from_f32(v).to_bits().to_ne_bytes()).collect();
        }
        let rgba = self.decode(data, width, height);
        match self.is_srgb() {
            true => rgba
                .chunks_exact(4)
                .flat_map(|px| {
                    let linear =
                        [srgb_to_linear(px[0]), srgb_to_linear(px[1]), srgb_to_linear(px[2]), f32::from(px[3]) / 255.0];
                    linear.map(|v| half::f16::from_f32(v).to_bits().to_ne_bytes())
                })
                .flatten()
                .collect(),
            false => rgba,
        }
    }

    /// Decodes a `width`×`height` image (blocks in row order) to tightly packed RGBA8 rows.
    /// `data` must hold [`Self::image_size`] bytes.
    pub fn decode(self, data: &[u8], width: u32, height: u32) -> Vec<u8> {
        let texels = self.place(data, width, height, |block| match self {
            Compressed::S3tc(d) | Compressed::S3tcSrgb(d) => crate::compressed::s3tc::decode_block(d, block).to_vec(),
            Compressed::Etc1 => etc1::decode_block(block).to_vec(),
            Compressed::Etc2(e) | Compressed::Etc2Srgb(e) => e.decode_block(block).to_vec(),
            Compressed::Astc(a) | Compressed::AstcSrgb(a) => a.decode_block(block),
        });
        texels.into_iter().flatten().collect()
    }

    /// The texels of a `width`×`height` image (blocks in row order), row by row, each block
    /// decoded by `decode` to its texels row by row; texels of blocks past the image's edge are
    /// dropped.
    fn place<T: Copy + Default>(
        self,
        data: &[u8],
        width: u32,
        height: u32,
        decode: impl Fn(&[u8]) -> Vec<T>,
    ) -> Vec<T> {
        let (w, h) = (width as usize, height as usize);
        let mut out = vec![T::default(); w * h];
        let (across, down) = self.blocks(width, height);
        let (bw, bh) = self.block_size();
        let (across, bw, bh) = (across as usize, bw as usize, bh as usize);
        for (i, block) in data.chunks_exact(self.block_bytes()).take(across * down as usize).enumerate() {
            let (x0, y0) = ((i % across) * bw, (i / across) * bh);
            for (t, px) in decode(block).into_iter().enumerate() {
                let (x, y) = (x0 + t % bw, y0 + t / bw);
                if x < w && y < h {
                    out[y * w + x] = px;
                }
            }
        }
        out
    }
}

/// An sRGB-encoded 8-bit value as linear (the sRGB transfer function).
fn srgb_to_linear(v: u8) -> f32 {
    let c = f32::from(v) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The compressed formats a device with `features` offers (`GL_COMPRESSED_TEXTURE_FORMATS`).
pub fn offered_compressed(features: wgpu::Features, es3: bool) -> Vec<u32> {
    COMPRESSED_FORMATS
        .into_iter()
        .chain(Etc2::all_gl())
        .chain(Astc::all_gl())
        .filter(|&f| Compressed::offered_gl(f, features, es3).is_some())
        .collect()
}

/// Whether `f` is a colour format of uploads (`BGRA_EXT`, and `GL_EXT_texture_rg`'s
/// `RED_EXT` and `RG_EXT`, included).
pub fn is_color_format(f: u32) -> bool {
    matches!(f, RGBA | RGB | LUMINANCE | ALPHA | LUMINANCE_ALPHA | BGRA_EXT | RED_EXT | RG_EXT)
}

/// Whether `f` is a format enum uploads know at all (`MESA_bgra`'s `BGR_EXT` included, which
/// no type uploads on an ES 2.0 context, as on Mesa).
fn known_format(f: u32) -> bool {
    is_color_format(f)
        || crate::integer::is_integer_format(f)
        || matches!(f, DEPTH_COMPONENT | DEPTH_STENCIL_OES | BGR_EXT)
}

/// Whether data in `format` fits an image of internal format `internal` without compression:
/// the same format, or RGBA and BGRA for each other (`MESA_bgra`).
pub fn same_layout(internal: u32, format: u32) -> bool {
    internal == format || matches!((internal, format), (RGBA, BGRA_EXT) | (BGRA_EXT, RGBA))
}

/// Whether `ty` is a type enum uploads know at all.
fn known_type(ty: u32) -> bool {
    matches!(
        ty,
        UNSIGNED_BYTE
            | UNSIGNED_SHORT_5_6_5
            | UNSIGNED_SHORT_4_4_4_4
            | UNSIGNED_SHORT_5_5_5_1
            | UNSIGNED_SHORT
            | UNSIGNED_INT
            | FLOAT
            | HALF_FLOAT_OES
            | UNSIGNED_INT_24_8_OES
            | UNSIGNED_INT_2_10_10_10_REV_EXT
            // Reversed packings Mesa knows, which no upload takes on an ES 2.0 context.
            | 0x8365
            | 0x8366
            | 0x8367
    )
}

/// Whether `internal` names an internal format `glTexImage2D` knows at all: Mesa answers
/// `GL_INVALID_VALUE` for one that does not (`MESA_bgra`'s `BGR_EXT` among them, and the ETC1
/// and ASTC formats, which only compressed uploads name), before it pairs format and type.
pub fn known_internal(internal: u32) -> bool {
    (is_color_format(internal) || matches!(internal, DEPTH_COMPONENT | DEPTH_STENCIL_OES | DEPTH_COMPONENT32_OES))
        || sized_fits(internal, 0, 0).is_some()
        || matches!(Compressed::from_gl(internal), Some(Compressed::S3tc(_) | Compressed::S3tcSrgb(_)))
}

/// The storage an upload of `format`/`ty` data is kept in: `GL_INVALID_ENUM` for an unknown
/// format or type, `GL_INVALID_OPERATION` for a pair ES 2.0 and its extensions do not list,
/// except that a depth format with another type is `GL_INVALID_ENUM` (as Mesa and ANGLE
/// answer, and as Strata always has).
pub fn upload_storage(format: u32, ty: u32) -> GlResult<Storage> {
    let plain = matches!(format, RGBA | RGB | LUMINANCE | ALPHA | LUMINANCE_ALPHA | RED_EXT | RG_EXT);
    Ok(match (format, ty) {
        (_, UNSIGNED_BYTE) if plain || format == BGRA_EXT => Storage::Rgba8,
        (RGB, UNSIGNED_SHORT_5_6_5) | (RGBA, UNSIGNED_SHORT_4_4_4_4 | UNSIGNED_SHORT_5_5_5_1) => Storage::Rgba8,
        (_, FLOAT) if plain => Storage::Float,
        (_, HALF_FLOAT_OES) if plain => Storage::Half,
        // EXT_texture_type_2_10_10_10_REV: 10 bits a channel need more than RGBA8 keeps; as
        // on Mesa, such an image cannot be rendered to.
        (RGBA | RGB, UNSIGNED_INT_2_10_10_10_REV_EXT) => Storage::Half,
        (DEPTH_COMPONENT, UNSIGNED_SHORT | UNSIGNED_INT) => Storage::Depth,
        (DEPTH_STENCIL_OES, UNSIGNED_INT_24_8_OES) => Storage::DepthStencil,
        // As Mesa answers on an ES 2.0 context: DEPTH_STENCIL_OES with a basic type is an
        // unknown combination, any other known type a mismatch.
        (DEPTH_STENCIL_OES, UNSIGNED_BYTE | UNSIGNED_SHORT | UNSIGNED_INT | FLOAT) => return Err(GlError::InvalidEnum),
        _ if known_format(format) && known_type(ty) => return Err(GlError::InvalidOperation),
        _ => return Err(GlError::InvalidEnum),
    })
}

/// `GL_OES_required_internalformat`: whether an upload in `format` and `ty` may fill sized
/// internal format `internal`, which then stores as that unsized format would (Mesa's table on
/// an ES 2.0 context: each sized format takes its own format with unsigned bytes, and the packed
/// or wider type its bits name); `None` where `internal` is no sized format.
pub fn sized_fits(internal: u32, format: u32, ty: u32) -> Option<bool> {
    Some(match internal {
        ALPHA8_OES => format == ALPHA && ty == UNSIGNED_BYTE,
        LUMINANCE8_OES => format == LUMINANCE && ty == UNSIGNED_BYTE,
        LUMINANCE4_ALPHA4_OES | LUMINANCE8_ALPHA8_OES => format == LUMINANCE_ALPHA && ty == UNSIGNED_BYTE,
        RGB8_OES => format == RGB && ty == UNSIGNED_BYTE,
        RGB565 => format == RGB && matches!(ty, UNSIGNED_BYTE | UNSIGNED_SHORT_5_6_5),
        // GL_EXT_texture_format_BGRA8888's uploads fit RGBA8 too.
        RGBA8_OES => matches!(format, RGBA | BGRA_EXT) && ty == UNSIGNED_BYTE,
        RGB5_A1 => format == RGBA && matches!(ty, UNSIGNED_BYTE | UNSIGNED_SHORT_5_5_5_1),
        RGBA4 => format == RGBA && matches!(ty, UNSIGNED_BYTE | UNSIGNED_SHORT_4_4_4_4),
        R8_EXT => format == RED_EXT && ty == UNSIGNED_BYTE,
        RG8_EXT => format == RG_EXT && ty == UNSIGNED_BYTE,
        RGB10_A2_EXT => format == RGBA && ty == UNSIGNED_INT_2_10_10_10_REV_EXT,
        RGB10_EXT => format == RGB && ty == UNSIGNED_INT_2_10_10_10_REV_EXT,
        DEPTH_COMPONENT16 => format == DEPTH_COMPONENT && matches!(ty, UNSIGNED_SHORT | UNSIGNED_INT),
        DEPTH_COMPONENT24_OES => format == DEPTH_COMPONENT && ty == UNSIGNED_INT,
        DEPTH24_STENCIL8_OES => format == DEPTH_STENCIL_OES && ty == UNSIGNED_INT_24_8_OES,
        _ => return None,
    })
}

/// How a texture that `glTexStorage*` makes in sized internal format `internal` is kept: the
/// unsized format whose image it behaves as (as `GL_OES_required_internalformat`'s images do),
/// its storage, and whether its data counts as half-float (renderable, as
/// `GL_EXT_color_buffer_half_float` has it). `None` for a format that is not sized, and for
/// the sized formats Strata cannot keep yet (the packed 10-bit and shared-exponent formats,
/// compressed formats).
pub fn immutable_storage(internal: u32, features: wgpu::Features) -> Option<(u32, Storage, bool)> {
    Some(match internal {
        // ES 3.0's renderable 10-bit format, kept at its precision.
        RGB10_A2_EXT => (RGBA, Storage::Rgb10a2, false),
        // Packed floats: the device's format where it renders to it, else half floats, which
        // hold every value of it (`packed_float`).
        crate::packed_float::R11F_G11F_B10F => (RGB, Storage::Rg11b10.on(features), false),
        RGBA8_OES | RGBA4 | RGB5_A1 => (RGBA, Storage::Rgba8, false),
        SRGB8_ALPHA8 => (RGBA, Storage::Srgb8, false),
        // Signed normalized: half floats hold every value of 8 signed bits within their
        // precision; none is renderable.
        R8_SNORM => (RED_EXT, Storage::Half, false),
        RG8_SNORM => (RG_EXT, Storage::Half, false),
        RGB8_SNORM => (RGB, Storage::Half, false),
        RGBA8_SNORM => (RGBA, Storage::Half, false),
        SRGB8 => (RGB, Storage::Srgb8, false),
        RGB8_OES | RGB565 => (RGB, Storage::Rgba8, false),
        BGRA8_EXT => (BGRA_EXT, Storage::Rgba8, false),
        R8_EXT => (RED_EXT, Storage::Rgba8, false),
        RG8_EXT => (RG_EXT, Storage::Rgba8, false),
        ALPHA8_OES => (ALPHA, Storage::Rgba8, false),
        LUMINANCE8_OES => (LUMINANCE, Storage::Rgba8, false),
        LUMINANCE8_ALPHA8_OES => (LUMINANCE_ALPHA, Storage::Rgba8, false),
        RGBA16F_EXT => (RGBA, Storage::Half, true),
        RGB16F_EXT => (RGB, Storage::Half, true),
        RG16F_EXT => (RG_EXT, Storage::Half, true),
        R16F_EXT => (RED_EXT, Storage::Half, true),
        ALPHA16F_EXT => (ALPHA, Storage::Half, true),
        LUMINANCE16F_EXT => (LUMINANCE, Storage::Half, true),
        LUMINANCE_ALPHA16F_EXT => (LUMINANCE_ALPHA, Storage::Half, true),
        RGBA32F => (RGBA, Storage::Float, false),
        RGB32F => (RGB, Storage::Float, false),
        RG32F => (RG_EXT, Storage::Float, false),
        R32F => (RED_EXT, Storage::Float, false),
        ALPHA32F_EXT => (ALPHA, Storage::Float, false),
        LUMINANCE32F_EXT => (LUMINANCE, Storage::Float, false),
        LUMINANCE_ALPHA32F_EXT => (LUMINANCE_ALPHA, Storage::Float, false),
        DEPTH_COMPONENT16 | DEPTH_COMPONENT24_OES | DEPTH_COMPONENT32F => (DEPTH_COMPONENT, Storage::Depth, false),
        DEPTH24_STENCIL8_OES | DEPTH32F_STENCIL8 => (DEPTH_STENCIL_OES, Storage::DepthStencil, false),
        // Every value of the shared-exponent format is a half float (`packed_float`).
        crate::packed_float::RGB9_E5 => (RGB, Storage::Half, false),
        _ => {
            let f = crate::integer::IntFormat::from_gl(internal)?;
            (f.base, Storage::Int { signed: f.signed, bits: f.bits }, false)
        }
    })
}

/// Whether `internal` is an unsized format, which `glTexStorage*` refuses: the base colour
/// formats, depth and depth-stencil.
pub fn is_unsized(internal: u32) -> bool {
    is_color_format(internal) || matches!(internal, DEPTH_COMPONENT | DEPTH_STENCIL_OES)
}

/// The unsized colour format a sized colour internal format stores as
/// (`GL_OES_required_internalformat`), for `glCopyTexImage2D`; `None` for any other format.
pub fn sized_color_base(internal: u32) -> Option<u32> {
    Some(match internal {
        ALPHA8_OES => ALPHA,
        LUMINANCE8_OES => LUMINANCE,
        LUMINANCE4_ALPHA4_OES | LUMINANCE8_ALPHA8_OES => LUMINANCE_ALPHA,
        RGB8_OES | RGB565 => RGB,
        RGBA8_OES | RGB5_A1 | RGBA4 => RGBA,
        _ => return None,
    })
}

/// Whether `internal` may hold an upload in `format`: ES 2.0 wants them equal; an offered
/// S3TC internal format takes RGB or RGBA data, which is kept uncompressed (as RGBA8).
pub fn internal_accepts(internal: u32, format: u32, features: wgpu::Features) -> bool {
    match Compressed::from_gl(internal) {
        Some(c @ Compressed::S3tc(_)) => c.offered(features, false) && matches!(format, RGB | RGBA),
        // As on Mesa: the sRGB forms, ETC and ASTC take compressed data only.
        Some(_) => false,
        None => same_layout(internal, format),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_type_pairs() {
        assert_eq!(upload_storage(RGBA, UNSIGNED_BYTE), Ok(Storage::Rgba8));
        assert_eq!(upload_storage(BGRA_EXT, UNSIGNED_BYTE), Ok(Storage::Rgba8));
        assert_eq!(upload_storage(LUMINANCE_ALPHA, FLOAT), Ok(Storage::Float));
        assert_eq!(upload_storage(ALPHA, HALF_FLOAT_OES), Ok(Storage::Half));
        assert_eq!(upload_storage(DEPTH_STENCIL_OES, UNSIGNED_INT_24_8_OES), Ok(Storage::DepthStencil));
        assert_eq!(upload_storage(BGRA_EXT, FLOAT), Err(GlError::InvalidOperation));
        assert_eq!(upload_storage(RGB, UNSIGNED_SHORT_4_4_4_4), Err(GlError::InvalidOperation));
        assert_eq!(upload_storage(DEPTH_STENCIL_OES, UNSIGNED_INT), Err(GlError::InvalidEnum));
        assert_eq!(upload_storage(DEPTH_COMPONENT, FLOAT), Err(GlError::InvalidOperation));
        assert_eq!(upload_storage(DEPTH_STENCIL_OES, UNSIGNED_SHORT_5_6_5), Err(GlError::InvalidOperation));
        assert_eq!(upload_storage(RGBA, UNSIGNED_INT_24_8_OES), Err(GlError::InvalidOperation));
        assert_eq!(upload_storage(RGBA, 0x1234), Err(GlError::InvalidEnum));
        assert_eq!(upload_storage(0x1234, UNSIGNED_BYTE), Err(GlError::InvalidEnum));
    }

    #[test]
    fn compressed_sizes_round_up_to_blocks() {
        let dxt1 = Compressed::from_gl(COMPRESSED_RGB_S3TC_DXT1_EXT).expect("dxt1");
        let dxt5 = Compressed::from_gl(COMPRESSED_RGBA_S3TC_DXT5_EXT).expect("dxt5");
        assert_eq!(dxt1.image_size(1, 1), 8);
        assert_eq!(dxt1.image_size(5, 4), 16);
        assert_eq!(dxt5.image_size(127, 63), 32 * 16 * 16);
        assert_eq!(dxt5.image_size(0, 0), 0);
    }
}
