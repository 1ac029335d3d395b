//! The enums of ES 3.0's image side and of `GL_EXT_texture_storage`: the half-float type, the
//! image unpack state, the sized float, depth and BGRA formats immutable storage takes, the 2D
//! array target, immutability, the sampler namespace and the swizzles. `enums` re-exports them.

/// `GL_TEXTURE_2D_ARRAY` (ES 3.0).
pub const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
/// `GL_RGBA32F` (ES 3.0; `GL_EXT_texture_storage`'s `GL_RGBA32F_EXT`).
pub const RGBA32F: u32 = 0x8814;
/// `GL_RGB32F`.
pub const RGB32F: u32 = 0x8815;
/// `GL_RG32F`.
pub const RG32F: u32 = 0x8230;
/// `GL_R32F`.
pub const R32F: u32 = 0x822E;
/// `GL_ALPHA32F_EXT` (`GL_EXT_texture_storage`).
pub const ALPHA32F_EXT: u32 = 0x8816;
/// `GL_LUMINANCE32F_EXT`.
pub const LUMINANCE32F_EXT: u32 = 0x8818;
/// `GL_LUMINANCE_ALPHA32F_EXT`.
pub const LUMINANCE_ALPHA32F_EXT: u32 = 0x8819;
/// `GL_ALPHA16F_EXT`.
pub const ALPHA16F_EXT: u32 = 0x881C;
/// `GL_LUMINANCE16F_EXT`.
pub const LUMINANCE16F_EXT: u32 = 0x881E;
/// `GL_LUMINANCE_ALPHA16F_EXT`.
pub const LUMINANCE_ALPHA16F_EXT: u32 = 0x881F;
/// `GL_BGRA8_EXT` (`GL_EXT_texture_format_BGRA8888` with texture storage).
pub const BGRA8_EXT: u32 = 0x93A1;
/// `GL_DEPTH_COMPONENT32F` (ES 3.0).
pub const DEPTH_COMPONENT32F: u32 = 0x8CAC;
/// `GL_DEPTH32F_STENCIL8` (ES 3.0).
pub const DEPTH32F_STENCIL8: u32 = 0x8CAD;
/// `GL_TEXTURE_IMMUTABLE_FORMAT` (ES 3.0): whether `glTexStorage*` made the texture's levels.
pub const TEXTURE_IMMUTABLE_FORMAT: u32 = 0x912F;
/// `GL_TEXTURE_IMMUTABLE_LEVELS` (ES 3.0): how many levels `glTexStorage*` made.
pub const TEXTURE_IMMUTABLE_LEVELS: u32 = 0x82DF;
/// `GL_SAMPLER` (`GL_KHR_debug`): the namespace of sampler objects' labels.
pub const SAMPLER: u32 = 0x82E6;
/// `GL_HALF_FLOAT`: the type Mesa names as the implementation read type of a half-float
/// colour buffer (the ES 3.0 enum, not `GL_HALF_FLOAT_OES`).
pub const HALF_FLOAT: u32 = 0x140B;
/// `GL_UNPACK_SKIP_IMAGES` (ES 3.0 and OES_texture_3D; see `queries`).
pub const UNPACK_SKIP_IMAGES: u32 = 0x806D;
/// `GL_UNPACK_IMAGE_HEIGHT` (ES 3.0 and OES_texture_3D; see `queries`).
pub const UNPACK_IMAGE_HEIGHT: u32 = 0x806E;
/// `GL_SRGB8_ALPHA8` (ES 3.0).
pub const SRGB8_ALPHA8: u32 = 0x8C43;
/// `GL_SRGB8` (ES 3.0).
pub const SRGB8: u32 = 0x8C41;
/// `GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING` (ES 3.0).
pub const FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING: u32 = 0x8210;
/// `GL_SRGB` (ES 3.0): an sRGB colour encoding.
pub const SRGB: u32 = 0x8C40;
/// `GL_R8_SNORM` (ES 3.0), and the other signed normalized formats after it.
pub const R8_SNORM: u32 = 0x8F94;
/// `GL_RG8_SNORM`.
pub const RG8_SNORM: u32 = 0x8F95;
/// `GL_RGB8_SNORM`.
pub const RGB8_SNORM: u32 = 0x8F96;
/// `GL_RGBA8_SNORM`.
pub const RGBA8_SNORM: u32 = 0x8F97;
/// `GL_FLOAT_32_UNSIGNED_INT_24_8_REV` (ES 3.0): a float depth, then a word whose low 8 bits
/// are the stencil.
pub const FLOAT_32_UNSIGNED_INT_24_8_REV: u32 = 0x8DAD;
/// `GL_GREEN` (ES 3.0: a swizzle source).
pub const GREEN: u32 = 0x1904;
/// `GL_BLUE` (ES 3.0: a swizzle source).
pub const BLUE: u32 = 0x1905;
/// `GL_TEXTURE_SWIZZLE_R` (ES 3.0); `_G`, `_B` and `_A` follow it.
pub const TEXTURE_SWIZZLE_R: u32 = 0x8E42;
/// `GL_RED_INTEGER` (ES 3.0): integer data of one channel.
pub const RED_INTEGER: u32 = 0x8D94;
/// `GL_RG_INTEGER` (ES 3.0).
pub const RG_INTEGER: u32 = 0x8228;
/// `GL_RGB_INTEGER` (ES 3.0).
pub const RGB_INTEGER: u32 = 0x8D98;
/// `GL_RGBA_INTEGER` (ES 3.0).
pub const RGBA_INTEGER: u32 = 0x8D99;
/// `GL_R8I` (ES 3.0); `R8UI`, `R16I`, `R16UI`, `R32I`, `R32UI` and the RG ones follow it.
pub const R8I: u32 = 0x8231;
/// `GL_RG32UI`, the last of the R and RG integer formats.
pub const RG32UI: u32 = 0x823C;
/// `GL_RGBA32UI` (ES 3.0).
pub const RGBA32UI: u32 = 0x8D70;
/// `GL_RGB32UI`.
pub const RGB32UI: u32 = 0x8D71;
/// `GL_RGBA16UI`.
pub const RGBA16UI: u32 = 0x8D76;
/// `GL_RGB16UI`.
pub const RGB16UI: u32 = 0x8D77;
/// `GL_RGBA8UI`.
pub const RGBA8UI: u32 = 0x8D7C;
/// `GL_RGB8UI`.
pub const RGB8UI: u32 = 0x8D7D;
/// `GL_RGBA32I`.
pub const RGBA32I: u32 = 0x8D82;
/// `GL_RGB32I`.
pub const RGB32I: u32 = 0x8D83;
/// `GL_RGBA16I`.
pub const RGBA16I: u32 = 0x8D88;
/// `GL_RGB16I`.
pub const RGB16I: u32 = 0x8D89;
/// `GL_RGBA8I`.
pub const RGBA8I: u32 = 0x8D8E;
/// `GL_RGB8I`.
pub const RGB8I: u32 = 0x8D8F;
/// `GL_RGB10_A2UI` (ES 3.0): unsigned integers of 10, 10, 10 and 2 bits.
pub const RGB10_A2UI: u32 = 0x906F;

/// `GL_RENDERBUFFER_SAMPLES` (ES 3.0).
pub const RENDERBUFFER_SAMPLES: u32 = 0x8CAB;
/// `GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE` (ES 3.0): attachments of different sample counts.
pub const FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: u32 = 0x8D56;
/// `GL_MAX_SAMPLES` (ES 3.0).
pub const MAX_SAMPLES: u32 = 0x8D57;
/// `GL_NUM_SAMPLE_COUNTS` (ES 3.0's `glGetInternalformativ`).
pub const NUM_SAMPLE_COUNTS: u32 = 0x9380;
