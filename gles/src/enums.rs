//! The GL ES 2.0 and EGL 1.4 enumerants the executor interprets (values from Khronos' headers).
#![allow(missing_docs)]

pub use crate::enums_es3::*;

// Errors.
pub const NO_ERROR: u32 = 0;
pub const INVALID_ENUM: u32 = 0x0500;
pub const INVALID_VALUE: u32 = 0x0501;
pub const INVALID_OPERATION: u32 = 0x0502;
pub const OUT_OF_MEMORY: u32 = 0x0505;
pub const INVALID_FRAMEBUFFER_OPERATION: u32 = 0x0506;

// Primitives.
pub const POINTS: u32 = 0x0000;
pub const LINES: u32 = 0x0001;
pub const LINE_LOOP: u32 = 0x0002;
pub const LINE_STRIP: u32 = 0x0003;
pub const TRIANGLES: u32 = 0x0004;
pub const TRIANGLE_STRIP: u32 = 0x0005;
pub const TRIANGLE_FAN: u32 = 0x0006;

// Types.
pub const BYTE: u32 = 0x1400;
pub const UNSIGNED_BYTE: u32 = 0x1401;
pub const SHORT: u32 = 0x1402;
pub const UNSIGNED_SHORT: u32 = 0x1403;
pub const INT: u32 = 0x1404;
pub const UNSIGNED_INT: u32 = 0x1405;
pub const FLOAT: u32 = 0x1406;
pub const FIXED: u32 = 0x140C;
pub const HALF_FLOAT_OES: u32 = 0x8D61;
/// `GL_CONTEXT_ROBUST_ACCESS_EXT` (`EXT_robustness`).
pub const CONTEXT_ROBUST_ACCESS_EXT: u32 = 0x90F3;
/// `GL_RESET_NOTIFICATION_STRATEGY_EXT`.
pub const RESET_NOTIFICATION_STRATEGY_EXT: u32 = 0x8256;
/// `GL_LOSE_CONTEXT_ON_RESET_EXT`.
pub const LOSE_CONTEXT_ON_RESET_EXT: u32 = 0x8252;
/// `GL_NO_RESET_NOTIFICATION_EXT`.
pub const NO_RESET_NOTIFICATION_EXT: u32 = 0x8261;
/// `GL_FRAMEBUFFER_UNDEFINED_OES` (`OES_surfaceless_context`): framebuffer 0 with no surface.
pub const FRAMEBUFFER_UNDEFINED_OES: u32 = 0x8219;
/// `GL_DEPTH_CLAMP_EXT` (`EXT_depth_clamp`).
pub const DEPTH_CLAMP_EXT: u32 = 0x864F;
/// `GL_UNSIGNED_INT_2_10_10_10_REV_EXT` (`EXT_texture_type_2_10_10_10_REV`).
pub const UNSIGNED_INT_2_10_10_10_REV_EXT: u32 = 0x8368;
/// `GL_RGB10_A2_EXT`, the sized format of RGBA 2_10_10_10_REV data.
pub const RGB10_A2_EXT: u32 = 0x8059;
/// `GL_RGB10_EXT`, the sized format of RGB 2_10_10_10_REV data.
pub const RGB10_EXT: u32 = 0x8052;
pub const UNSIGNED_SHORT_4_4_4_4: u32 = 0x8033;
pub const UNSIGNED_SHORT_5_5_5_1: u32 = 0x8034;
pub const UNSIGNED_SHORT_5_6_5: u32 = 0x8363;

// Buffers.
pub const ARRAY_BUFFER: u32 = 0x8892;
pub const ELEMENT_ARRAY_BUFFER: u32 = 0x8893;
pub const ARRAY_BUFFER_BINDING: u32 = 0x8894;
pub const ELEMENT_ARRAY_BUFFER_BINDING: u32 = 0x8895;
/// `GL_NV_pixel_buffer_object`'s targets and bindings.
pub const PIXEL_PACK_BUFFER_NV: u32 = 0x88EB;
pub const PIXEL_UNPACK_BUFFER_NV: u32 = 0x88EC;
pub const PIXEL_PACK_BUFFER_BINDING_NV: u32 = 0x88ED;
pub const PIXEL_UNPACK_BUFFER_BINDING_NV: u32 = 0x88EF;
pub const STREAM_DRAW: u32 = 0x88E0;
pub const STATIC_DRAW: u32 = 0x88E4;
pub const DYNAMIC_DRAW: u32 = 0x88E8;
pub const BUFFER_SIZE: u32 = 0x8764;
pub const BUFFER_USAGE: u32 = 0x8765;

// Capabilities.
pub const CULL_FACE: u32 = 0x0B44;
pub const BLEND: u32 = 0x0BE2;
pub const DITHER: u32 = 0x0BD0;
pub const STENCIL_TEST: u32 = 0x0B90;
pub const DEPTH_TEST: u32 = 0x0B71;
pub const SCISSOR_TEST: u32 = 0x0C11;
pub const POLYGON_OFFSET_FILL: u32 = 0x8037;
pub const SAMPLE_ALPHA_TO_COVERAGE: u32 = 0x809E;
pub const SAMPLE_COVERAGE: u32 = 0x80A0;

// Faces and winding.
pub const FRONT: u32 = 0x0404;
pub const BACK: u32 = 0x0405;
pub const FRONT_AND_BACK: u32 = 0x0408;
pub const CW: u32 = 0x0900;
pub const CCW: u32 = 0x0901;

// Comparison.
pub const NEVER: u32 = 0x0200;
pub const LESS: u32 = 0x0201;
pub const EQUAL: u32 = 0x0202;
pub const LEQUAL: u32 = 0x0203;
pub const GREATER: u32 = 0x0204;
pub const NOTEQUAL: u32 = 0x0205;
pub const GEQUAL: u32 = 0x0206;
pub const ALWAYS: u32 = 0x0207;

// Blending.
pub const ZERO: u32 = 0;
pub const ONE: u32 = 1;
pub const SRC_COLOR: u32 = 0x0300;
pub const ONE_MINUS_SRC_COLOR: u32 = 0x0301;
pub const SRC_ALPHA: u32 = 0x0302;
pub const ONE_MINUS_SRC_ALPHA: u32 = 0x0303;
pub const DST_ALPHA: u32 = 0x0304;
pub const ONE_MINUS_DST_ALPHA: u32 = 0x0305;
pub const DST_COLOR: u32 = 0x0306;
pub const ONE_MINUS_DST_COLOR: u32 = 0x0307;
pub const SRC_ALPHA_SATURATE: u32 = 0x0308;
pub const SRC1_ALPHA_EXT: u32 = 0x8589;
pub const SRC1_COLOR_EXT: u32 = 0x88F9;
pub const ONE_MINUS_SRC1_COLOR_EXT: u32 = 0x88FA;
pub const ONE_MINUS_SRC1_ALPHA_EXT: u32 = 0x88FB;
pub const MAX_DUAL_SOURCE_DRAW_BUFFERS_EXT: u32 = 0x88FC;
pub const CONSTANT_COLOR: u32 = 0x8001;
pub const ONE_MINUS_CONSTANT_COLOR: u32 = 0x8002;
pub const CONSTANT_ALPHA: u32 = 0x8003;
pub const ONE_MINUS_CONSTANT_ALPHA: u32 = 0x8004;
pub const FUNC_ADD: u32 = 0x8006;
pub const FUNC_SUBTRACT: u32 = 0x800A;
pub const FUNC_REVERSE_SUBTRACT: u32 = 0x800B;
pub const MIN_EXT: u32 = 0x8007;
pub const MAX_EXT: u32 = 0x8008;

// Stencil ops.
pub const KEEP: u32 = 0x1E00;
pub const REPLACE: u32 = 0x1E01;
pub const INCR: u32 = 0x1E02;
pub const DECR: u32 = 0x1E03;
pub const INVERT: u32 = 0x150A;
pub const INCR_WRAP: u32 = 0x8507;
pub const DECR_WRAP: u32 = 0x8508;

// Clear bits.
pub const DEPTH_BUFFER_BIT: u32 = 0x0100;
pub const STENCIL_BUFFER_BIT: u32 = 0x0400;
pub const COLOR_BUFFER_BIT: u32 = 0x4000;

// Pixel formats.
pub const DEPTH_COMPONENT: u32 = 0x1902;
pub const ALPHA: u32 = 0x1906;
pub const RGB: u32 = 0x1907;
pub const RGBA: u32 = 0x1908;
pub const LUMINANCE: u32 = 0x1909;
pub const LUMINANCE_ALPHA: u32 = 0x190A;
pub const UNPACK_ALIGNMENT: u32 = 0x0CF5;
pub const UNPACK_ROW_LENGTH: u32 = 0x0CF2;
pub const UNPACK_SKIP_ROWS: u32 = 0x0CF3;
pub const UNPACK_SKIP_PIXELS: u32 = 0x0CF4;
/// `GL_PACK_ROW_LENGTH_NV` (`NV_pack_subimage`).
pub const PACK_ROW_LENGTH: u32 = 0x0D02;
/// `GL_PACK_SKIP_ROWS_NV`.
pub const PACK_SKIP_ROWS: u32 = 0x0D03;
/// `GL_PACK_SKIP_PIXELS_NV`.
pub const PACK_SKIP_PIXELS: u32 = 0x0D04;
/// `GL_PACK_REVERSE_ROW_ORDER_ANGLE` (`ANGLE_pack_reverse_row_order`).
pub const PACK_REVERSE_ROW_ORDER_ANGLE: u32 = 0x93A4;
pub const BGRA_EXT: u32 = 0x80E1;
/// `GL_BGR_EXT` (`MESA_bgra`).
pub const BGR_EXT: u32 = 0x80E0;
pub const BUFFER_OBJECT_EXT: u32 = 0x9151;
pub const SHADER_OBJECT_EXT: u32 = 0x8B48;
pub const PROGRAM_OBJECT_EXT: u32 = 0x8B40;
pub const VERTEX_ARRAY_OBJECT_EXT: u32 = 0x9154;
pub const QUERY_OBJECT_EXT: u32 = 0x9153;
pub const PROGRAM_PIPELINE_OBJECT_EXT: u32 = 0x8A4F;
pub const RED_EXT: u32 = 0x1903;
pub const RG_EXT: u32 = 0x8227;
pub const R8_EXT: u32 = 0x8229;
pub const RG8_EXT: u32 = 0x822B;
/// `GL_EXT_read_format_bgra`'s reversed 16-bit packings.
pub const UNSIGNED_SHORT_4_4_4_4_REV_EXT: u32 = 0x8365;
pub const UNSIGNED_SHORT_1_5_5_5_REV_EXT: u32 = 0x8366;
pub const DEPTH_STENCIL_OES: u32 = 0x84F9;
pub const UNSIGNED_INT_24_8_OES: u32 = 0x84FA;
pub const COMPRESSED_RGB_S3TC_DXT1_EXT: u32 = 0x83F0;
pub const COMPRESSED_RGBA_S3TC_DXT1_EXT: u32 = 0x83F1;
pub const COMPRESSED_RGBA_S3TC_DXT3_EXT: u32 = 0x83F2;
pub const COMPRESSED_RGBA_S3TC_DXT5_EXT: u32 = 0x83F3;
/// `GL_EXT_texture_compression_s3tc_srgb`'s formats.
pub const COMPRESSED_SRGB_S3TC_DXT1_EXT: u32 = 0x8C4C;
pub const COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT: u32 = 0x8C4D;
pub const COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT: u32 = 0x8C4E;
pub const COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT: u32 = 0x8C4F;
pub const ETC1_RGB8_OES: u32 = 0x8D64;
pub const PACK_ALIGNMENT: u32 = 0x0D05;

// Textures.
pub const TEXTURE: u32 = 0x1702;
pub const TEXTURE_2D: u32 = 0x0DE1;
pub const TEXTURE_CUBE_MAP: u32 = 0x8513;
pub const TEXTURE_CUBE_MAP_POSITIVE_X: u32 = 0x8515;
pub const TEXTURE_MAG_FILTER: u32 = 0x2800;
pub const TEXTURE_MIN_FILTER: u32 = 0x2801;
pub const TEXTURE_WRAP_S: u32 = 0x2802;
pub const TEXTURE_WRAP_T: u32 = 0x2803;
/// `GL_OES_texture_3D`: the target, its binding, its size limit, the r wrap, the sampler
/// type and the attached slice.
pub const TEXTURE_3D_OES: u32 = 0x806F;
pub const TEXTURE_BINDING_3D_OES: u32 = 0x806A;
pub const MAX_3D_TEXTURE_SIZE_OES: u32 = 0x8073;
pub const TEXTURE_WRAP_R_OES: u32 = 0x8072;
pub const SAMPLER_3D_OES: u32 = 0x8B5F;
pub const FRAMEBUFFER_ATTACHMENT_TEXTURE_3D_ZOFFSET_OES: u32 = 0x8CD4;
pub const NEAREST: u32 = 0x2600;
pub const LINEAR: u32 = 0x2601;
pub const NEAREST_MIPMAP_NEAREST: u32 = 0x2700;
pub const LINEAR_MIPMAP_NEAREST: u32 = 0x2701;
pub const NEAREST_MIPMAP_LINEAR: u32 = 0x2702;
pub const LINEAR_MIPMAP_LINEAR: u32 = 0x2703;
pub const REPEAT: u32 = 0x2901;
pub const CLAMP_TO_EDGE: u32 = 0x812F;
pub const MIRRORED_REPEAT: u32 = 0x8370;
/// `GL_MIRROR_CLAMP_TO_EDGE_EXT` (`GL_EXT_texture_mirror_clamp_to_edge`).
pub const MIRROR_CLAMP_TO_EDGE_EXT: u32 = 0x8743;
/// `GL_CLAMP_TO_BORDER_EXT` (`GL_EXT_texture_border_clamp`, `GL_OES_texture_border_clamp`).
pub const CLAMP_TO_BORDER_EXT: u32 = 0x812D;
/// `GL_RGBA16F_EXT` (`GL_EXT_color_buffer_half_float` renderbuffers).
pub const RGBA16F_EXT: u32 = 0x881A;
/// `GL_RGB16F_EXT`.
pub const RGB16F_EXT: u32 = 0x881B;
/// `GL_RG16F_EXT`.
pub const RG16F_EXT: u32 = 0x822F;
/// `GL_R16F_EXT`.
pub const R16F_EXT: u32 = 0x822D;
/// `GL_TEXTURE_BORDER_COLOR_EXT`.
pub const TEXTURE_BORDER_COLOR_EXT: u32 = 0x1004;
pub const TEXTURE0: u32 = 0x84C0;

// Shaders and programs.
pub const FRAGMENT_SHADER: u32 = 0x8B30;
pub const VERTEX_SHADER: u32 = 0x8B31;
pub const SHADER_TYPE: u32 = 0x8B4F;
pub const DELETE_STATUS: u32 = 0x8B80;
pub const COMPILE_STATUS: u32 = 0x8B81;
pub const LINK_STATUS: u32 = 0x8B82;
/// `GL_EXT_clip_control`'s enumerants.
pub const LOWER_LEFT_EXT: u32 = 0x8CA1;
pub const UPPER_LEFT_EXT: u32 = 0x8CA2;
pub const CLIP_ORIGIN_EXT: u32 = 0x935C;
pub const CLIP_DEPTH_MODE_EXT: u32 = 0x935D;
pub const NEGATIVE_ONE_TO_ONE_EXT: u32 = 0x935E;
pub const ZERO_TO_ONE_EXT: u32 = 0x935F;
/// `GL_PROGRAM_BINARY_LENGTH_OES`.
pub const PROGRAM_BINARY_LENGTH_OES: u32 = 0x8741;
/// `GL_NUM_PROGRAM_BINARY_FORMATS_OES`.
pub const NUM_PROGRAM_BINARY_FORMATS_OES: u32 = 0x87FE;
/// `GL_PROGRAM_BINARY_FORMATS_OES`.
pub const PROGRAM_BINARY_FORMATS_OES: u32 = 0x87FF;
pub const VALIDATE_STATUS: u32 = 0x8B83;
/// `GL_PROGRAM_SEPARABLE_EXT` (`GL_EXT_separate_shader_objects`).
pub const PROGRAM_SEPARABLE_EXT: u32 = 0x8258;
pub const INFO_LOG_LENGTH: u32 = 0x8B84;
pub const ATTACHED_SHADERS: u32 = 0x8B85;
pub const ACTIVE_UNIFORMS: u32 = 0x8B86;
pub const ACTIVE_UNIFORM_MAX_LENGTH: u32 = 0x8B87;
pub const SHADER_SOURCE_LENGTH: u32 = 0x8B88;
pub const ACTIVE_ATTRIBUTES: u32 = 0x8B89;
pub const ACTIVE_ATTRIBUTE_MAX_LENGTH: u32 = 0x8B8A;
pub const CURRENT_PROGRAM: u32 = 0x8B8D;
pub const LOW_FLOAT: u32 = 0x8DF0;
pub const HIGH_INT: u32 = 0x8DF5;

// Uniform types.
pub const FLOAT_VEC2: u32 = 0x8B50;
pub const FLOAT_VEC3: u32 = 0x8B51;
pub const FLOAT_VEC4: u32 = 0x8B52;
pub const INT_VEC2: u32 = 0x8B53;
pub const INT_VEC3: u32 = 0x8B54;
pub const INT_VEC4: u32 = 0x8B55;
pub const BOOL: u32 = 0x8B56;
pub const BOOL_VEC2: u32 = 0x8B57;
pub const BOOL_VEC3: u32 = 0x8B58;
pub const BOOL_VEC4: u32 = 0x8B59;
pub const FLOAT_MAT2: u32 = 0x8B5A;
pub const FLOAT_MAT3: u32 = 0x8B5B;
pub const FLOAT_MAT4: u32 = 0x8B5C;
pub const SAMPLER_2D: u32 = 0x8B5E;
pub const SAMPLER_CUBE: u32 = 0x8B60;

// Vertex attribute queries.
pub const VERTEX_ATTRIB_ARRAY_ENABLED: u32 = 0x8622;
pub const VERTEX_ATTRIB_ARRAY_SIZE: u32 = 0x8623;
pub const VERTEX_ATTRIB_ARRAY_STRIDE: u32 = 0x8624;
pub const VERTEX_ATTRIB_ARRAY_TYPE: u32 = 0x8625;
pub const CURRENT_VERTEX_ATTRIB: u32 = 0x8626;
pub const VERTEX_ATTRIB_ARRAY_NORMALIZED: u32 = 0x886A;
pub const VERTEX_ATTRIB_ARRAY_POINTER: u32 = 0x8645;
pub const VERTEX_ATTRIB_ARRAY_BUFFER_BINDING: u32 = 0x889F;

// Framebuffers.
pub const FRAMEBUFFER: u32 = 0x8D40;
pub const RENDERBUFFER: u32 = 0x8D41;
pub const RGBA4: u32 = 0x8056;
pub const RGB5_A1: u32 = 0x8057;
pub const RGB565: u32 = 0x8D62;
pub const DEPTH_COMPONENT16: u32 = 0x81A5;
pub const STENCIL_INDEX8: u32 = 0x8D48;
pub const DEPTH24_STENCIL8_OES: u32 = 0x88F0;
pub const DEPTH_COMPONENT24_OES: u32 = 0x81A6;
pub const RGBA8_OES: u32 = 0x8058;
pub const RGB8_OES: u32 = 0x8051;
/// `GL_OES_required_internalformat`'s sized luminance and alpha formats.
pub const ALPHA8_OES: u32 = 0x803C;
pub const LUMINANCE8_OES: u32 = 0x8040;
pub const LUMINANCE4_ALPHA4_OES: u32 = 0x8043;
pub const LUMINANCE8_ALPHA8_OES: u32 = 0x8045;
/// A sized format of an extension Strata does not offer, which Mesa knows.
pub const DEPTH_COMPONENT32_OES: u32 = 0x81A7;
pub const COLOR_ATTACHMENT0: u32 = 0x8CE0;
pub const READ_FRAMEBUFFER: u32 = 0x8CA8;
pub const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
pub const MAX_COLOR_ATTACHMENTS: u32 = 0x8CDF;
pub const MAX_DRAW_BUFFERS: u32 = 0x8824;
pub const DRAW_BUFFER0: u32 = 0x8825;
pub const DRAW_BUFFER7: u32 = 0x882C;
pub const DEPTH_ATTACHMENT: u32 = 0x8D00;
pub const STENCIL_ATTACHMENT: u32 = 0x8D20;
/// `GL_DEPTH_STENCIL_ATTACHMENT` (ES 3.0): the depth and the stencil attachments at once.
pub const DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;
pub const FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;
pub const FRAMEBUFFER_INCOMPLETE_ATTACHMENT: u32 = 0x8CD6;
pub const FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: u32 = 0x8CD7;
pub const FRAMEBUFFER_INCOMPLETE_DIMENSIONS: u32 = 0x8CD9;
pub const FRAMEBUFFER_UNSUPPORTED: u32 = 0x8CDD;
pub const FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE: u32 = 0x8CD0;
pub const FRAMEBUFFER_ATTACHMENT_OBJECT_NAME: u32 = 0x8CD1;
pub const FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL: u32 = 0x8CD2;
pub const FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE: u32 = 0x8CD3;
pub const RENDERBUFFER_WIDTH: u32 = 0x8D42;
pub const RENDERBUFFER_HEIGHT: u32 = 0x8D43;
pub const RENDERBUFFER_INTERNAL_FORMAT: u32 = 0x8D44;
/// `GL_RENDERBUFFER_RED_SIZE`; green, blue, alpha, depth and stencil follow it.
pub const RENDERBUFFER_RED_SIZE: u32 = 0x8D50;
pub const RENDERBUFFER_STENCIL_SIZE: u32 = 0x8D55;
pub const NONE: u32 = 0;

// Strings and limits.
pub const VENDOR: u32 = 0x1F00;
pub const RENDERER: u32 = 0x1F01;
pub const VERSION: u32 = 0x1F02;
pub const EXTENSIONS: u32 = 0x1F03;
pub const SHADING_LANGUAGE_VERSION: u32 = 0x8B8C;
pub const MAX_TEXTURE_SIZE: u32 = 0x0D33;
pub const MAX_VIEWPORT_DIMS: u32 = 0x0D3A;
pub const VIEWPORT: u32 = 0x0BA2;
pub const SCISSOR_BOX: u32 = 0x0C10;
pub const COLOR_CLEAR_VALUE: u32 = 0x0C22;
pub const DEPTH_CLEAR_VALUE: u32 = 0x0B73;
pub const DEPTH_RANGE: u32 = 0x0B70;
pub const DEPTH_FUNC: u32 = 0x0B74;
pub const DEPTH_WRITEMASK: u32 = 0x0B72;
pub const COLOR_WRITEMASK: u32 = 0x0C23;
pub const BLEND_COLOR: u32 = 0x8005;
pub const MAX_VERTEX_ATTRIBS: u32 = 0x8869;
pub const MAX_VERTEX_UNIFORM_VECTORS: u32 = 0x8DFB;
pub const MAX_VARYING_VECTORS: u32 = 0x8DFC;
pub const MAX_COMBINED_TEXTURE_IMAGE_UNITS: u32 = 0x8B4D;
pub const MAX_VERTEX_TEXTURE_IMAGE_UNITS: u32 = 0x8B4C;
pub const MAX_TEXTURE_IMAGE_UNITS: u32 = 0x8872;
pub const MAX_FRAGMENT_UNIFORM_VECTORS: u32 = 0x8DFD;
pub const MAX_CUBE_MAP_TEXTURE_SIZE: u32 = 0x851C;
pub const MAX_RENDERBUFFER_SIZE: u32 = 0x84E8;
pub const ALIASED_POINT_SIZE_RANGE: u32 = 0x846D;
pub const ALIASED_LINE_WIDTH_RANGE: u32 = 0x846E;
pub const RED_BITS: u32 = 0x0D52;
pub const GREEN_BITS: u32 = 0x0D53;
pub const BLUE_BITS: u32 = 0x0D54;
pub const ALPHA_BITS: u32 = 0x0D55;
pub const DEPTH_BITS: u32 = 0x0D56;
pub const STENCIL_BITS: u32 = 0x0D57;
pub const SUBPIXEL_BITS: u32 = 0x0D50;
pub const IMPLEMENTATION_COLOR_READ_TYPE: u32 = 0x8B9A;
pub const IMPLEMENTATION_COLOR_READ_FORMAT: u32 = 0x8B9B;
pub const NUM_COMPRESSED_TEXTURE_FORMATS: u32 = 0x86A2;
pub const COMPRESSED_TEXTURE_FORMATS: u32 = 0x86A3;
pub const NUM_SHADER_BINARY_FORMATS: u32 = 0x8DF9;
pub const SHADER_COMPILER: u32 = 0x8DFA;
pub const FRAMEBUFFER_BINDING: u32 = 0x8CA6;
pub const RENDERBUFFER_BINDING: u32 = 0x8CA7;
pub const TEXTURE_BINDING_2D: u32 = 0x8069;
pub const TEXTURE_BINDING_CUBE_MAP: u32 = 0x8514;
/// `GL_TEXTURE_BINDING_EXTERNAL_OES` (`GL_OES_EGL_image_external`).
pub const TEXTURE_BINDING_EXTERNAL_OES: u32 = 0x8D67;
pub const ACTIVE_TEXTURE: u32 = 0x84E0;
pub const CULL_FACE_MODE: u32 = 0x0B45;
pub const FRONT_FACE: u32 = 0x0B46;
pub const LINE_WIDTH: u32 = 0x0B21;
pub const GENERATE_MIPMAP_HINT: u32 = 0x8192;
/// `GL_FRAGMENT_SHADER_DERIVATIVE_HINT_OES` (OES_standard_derivatives).
pub const FRAGMENT_SHADER_DERIVATIVE_HINT_OES: u32 = 0x8B8B;
pub const DONT_CARE: u32 = 0x1100;
pub const FASTEST: u32 = 0x1101;
pub const NICEST: u32 = 0x1102;

// GL_OES_vertex_array_object.
pub const VERTEX_ARRAY_BINDING_OES: u32 = 0x85B5;

// GL_KHR_debug.
pub const STACK_OVERFLOW: u32 = 0x0503;
pub const STACK_UNDERFLOW: u32 = 0x0504;
pub const DEBUG_OUTPUT: u32 = 0x92E0;
pub const DEBUG_OUTPUT_SYNCHRONOUS: u32 = 0x8242;
pub const MAX_DEBUG_MESSAGE_LENGTH: u32 = 0x9143;
pub const MAX_DEBUG_LOGGED_MESSAGES: u32 = 0x9144;
pub const DEBUG_LOGGED_MESSAGES: u32 = 0x9145;
pub const DEBUG_NEXT_LOGGED_MESSAGE_LENGTH: u32 = 0x8243;
pub const MAX_DEBUG_GROUP_STACK_DEPTH: u32 = 0x826C;
pub const DEBUG_GROUP_STACK_DEPTH: u32 = 0x826D;
pub const MAX_LABEL_LENGTH: u32 = 0x82E8;
pub const DEBUG_SOURCE_API: u32 = 0x8246;
pub const DEBUG_SOURCE_WINDOW_SYSTEM: u32 = 0x8247;
pub const DEBUG_SOURCE_SHADER_COMPILER: u32 = 0x8248;
pub const DEBUG_SOURCE_THIRD_PARTY: u32 = 0x8249;
pub const DEBUG_SOURCE_APPLICATION: u32 = 0x824A;
pub const DEBUG_SOURCE_OTHER: u32 = 0x824B;
pub const DEBUG_TYPE_ERROR: u32 = 0x824C;
pub const DEBUG_TYPE_DEPRECATED_BEHAVIOR: u32 = 0x824D;
pub const DEBUG_TYPE_UNDEFINED_BEHAVIOR: u32 = 0x824E;
pub const DEBUG_TYPE_PORTABILITY: u32 = 0x824F;
pub const DEBUG_TYPE_PERFORMANCE: u32 = 0x8250;
pub const DEBUG_TYPE_OTHER: u32 = 0x8251;
pub const DEBUG_TYPE_MARKER: u32 = 0x8268;
pub const DEBUG_TYPE_PUSH_GROUP: u32 = 0x8269;
pub const DEBUG_TYPE_POP_GROUP: u32 = 0x826A;
pub const DEBUG_SEVERITY_HIGH: u32 = 0x9146;
pub const DEBUG_SEVERITY_MEDIUM: u32 = 0x9147;
pub const DEBUG_SEVERITY_LOW: u32 = 0x9148;
pub const DEBUG_SEVERITY_NOTIFICATION: u32 = 0x826B;
pub const BUFFER_KHR: u32 = 0x82E0;
pub const SHADER_KHR: u32 = 0x82E1;
pub const PROGRAM_KHR: u32 = 0x82E2;
pub const VERTEX_ARRAY_KHR: u32 = 0x8074;
pub const QUERY_KHR: u32 = 0x82E3;
pub const PROGRAM_PIPELINE_KHR: u32 = 0x82E4;
pub const SAMPLER_KHR: u32 = 0x82E6;
// State queries (ES 2.0 state tables 6.5, 6.6, 6.9, 6.10, 6.17).
pub const BLEND_EQUATION_RGB: u32 = 0x8009;
pub const BLEND_EQUATION_ALPHA: u32 = 0x883D;
pub const BLEND_DST_RGB: u32 = 0x80C8;
pub const BLEND_SRC_RGB: u32 = 0x80C9;
pub const BLEND_DST_ALPHA: u32 = 0x80CA;
pub const BLEND_SRC_ALPHA: u32 = 0x80CB;
pub const STENCIL_CLEAR_VALUE: u32 = 0x0B91;
pub const STENCIL_FUNC: u32 = 0x0B92;
pub const STENCIL_VALUE_MASK: u32 = 0x0B93;
pub const STENCIL_FAIL: u32 = 0x0B94;
pub const STENCIL_PASS_DEPTH_FAIL: u32 = 0x0B95;
pub const STENCIL_PASS_DEPTH_PASS: u32 = 0x0B96;
pub const STENCIL_REF: u32 = 0x0B97;
pub const STENCIL_WRITEMASK: u32 = 0x0B98;
pub const STENCIL_BACK_FUNC: u32 = 0x8800;
pub const STENCIL_BACK_FAIL: u32 = 0x8801;
pub const STENCIL_BACK_PASS_DEPTH_FAIL: u32 = 0x8802;
pub const STENCIL_BACK_PASS_DEPTH_PASS: u32 = 0x8803;
pub const STENCIL_BACK_REF: u32 = 0x8CA3;
pub const STENCIL_BACK_VALUE_MASK: u32 = 0x8CA4;
pub const STENCIL_BACK_WRITEMASK: u32 = 0x8CA5;
pub const POLYGON_OFFSET_UNITS: u32 = 0x2A00;
pub const POLYGON_OFFSET_FACTOR: u32 = 0x8038;
pub const POLYGON_OFFSET_CLAMP_EXT: u32 = 0x8E1B;
pub const MAX_SHADER_COMPILER_THREADS_KHR: u32 = 0x91B0;
pub const CONTEXT_RELEASE_BEHAVIOR_KHR: u32 = 0x82FB;
pub const READ_BUFFER_NV: u32 = 0x0C02;
pub const TEXTURE_MAX_ANISOTROPY_EXT: u32 = 0x84FE;
/// `GL_TEXTURE_MAX_LEVEL_APPLE` (`APPLE_texture_max_level`).
pub const TEXTURE_MAX_LEVEL_APPLE: u32 = 0x813D;
pub const MAX_TEXTURE_MAX_ANISOTROPY_EXT: u32 = 0x84FF;
pub const CONTEXT_RELEASE_BEHAVIOR_FLUSH_KHR: u32 = 0x82FC;
pub const COMPLETION_STATUS_KHR: u32 = 0x91B1;
pub const SAMPLE_BUFFERS: u32 = 0x80A8;
pub const SAMPLES: u32 = 0x80A9;
pub const SAMPLE_COVERAGE_VALUE: u32 = 0x80AA;
pub const SAMPLE_COVERAGE_INVERT: u32 = 0x80AB;
pub const SHADER_BINARY_FORMATS: u32 = 0x8DF8;
/// `GL_MAX_CLIP_PLANES` (desktop GL and ES 1.x; see `queries`).
pub const MAX_CLIP_PLANES: u32 = 0x0D32;

// EXT_discard_framebuffer.
pub const COLOR_EXT: u32 = 0x1800;
pub const DEPTH_EXT: u32 = 0x1801;
pub const STENCIL_EXT: u32 = 0x1802;

// EGL.
pub const EGL_SUCCESS: i32 = 0x3000;
pub const EGL_NOT_INITIALIZED: i32 = 0x3001;
pub const EGL_BAD_ALLOC: i32 = 0x3003;
pub const EGL_BAD_ATTRIBUTE: i32 = 0x3004;
pub const EGL_BAD_CONFIG: i32 = 0x3005;
pub const EGL_BAD_CONTEXT: i32 = 0x3006;
pub const EGL_BAD_DISPLAY: i32 = 0x3008;
pub const EGL_BAD_MATCH: i32 = 0x3009;
pub const EGL_BAD_NATIVE_WINDOW: i32 = 0x300B;
pub const EGL_BAD_PARAMETER: i32 = 0x300C;
pub const EGL_BAD_SURFACE: i32 = 0x300D;
pub const EGL_BUFFER_SIZE: i32 = 0x3020;
pub const EGL_ALPHA_SIZE: i32 = 0x3021;
pub const EGL_BLUE_SIZE: i32 = 0x3022;
pub const EGL_GREEN_SIZE: i32 = 0x3023;
pub const EGL_RED_SIZE: i32 = 0x3024;
pub const EGL_DEPTH_SIZE: i32 = 0x3025;
pub const EGL_STENCIL_SIZE: i32 = 0x3026;
pub const EGL_CONFIG_CAVEAT: i32 = 0x3027;
pub const EGL_CONFIG_ID: i32 = 0x3028;
pub const EGL_LEVEL: i32 = 0x3029;
pub const EGL_MAX_PBUFFER_HEIGHT: i32 = 0x302A;
pub const EGL_MAX_PBUFFER_PIXELS: i32 = 0x302B;
pub const EGL_MAX_PBUFFER_WIDTH: i32 = 0x302C;
pub const EGL_NATIVE_RENDERABLE: i32 = 0x302D;
pub const EGL_NATIVE_VISUAL_ID: i32 = 0x302E;
pub const EGL_NATIVE_VISUAL_TYPE: i32 = 0x302F;
pub const EGL_SAMPLES: i32 = 0x3031;
pub const EGL_SAMPLE_BUFFERS: i32 = 0x3032;
pub const EGL_SURFACE_TYPE: i32 = 0x3033;
pub const EGL_TRANSPARENT_TYPE: i32 = 0x3034;
pub const EGL_TRANSPARENT_BLUE_VALUE: i32 = 0x3035;
pub const EGL_TRANSPARENT_GREEN_VALUE: i32 = 0x3036;
pub const EGL_TRANSPARENT_RED_VALUE: i32 = 0x3037;
pub const EGL_NONE: i32 = 0x3038;
pub const EGL_TRUE: i32 = 1;
pub const EGL_BIND_TO_TEXTURE_RGB: i32 = 0x3039;
pub const EGL_BIND_TO_TEXTURE_RGBA: i32 = 0x303A;
pub const EGL_MIN_SWAP_INTERVAL: i32 = 0x303B;
pub const EGL_MAX_SWAP_INTERVAL: i32 = 0x303C;
pub const EGL_LUMINANCE_SIZE: i32 = 0x303D;
pub const EGL_ALPHA_MASK_SIZE: i32 = 0x303E;
pub const EGL_COLOR_BUFFER_TYPE: i32 = 0x303F;
pub const EGL_RENDERABLE_TYPE: i32 = 0x3040;
pub const EGL_CONFORMANT: i32 = 0x3042;
pub const EGL_RGB_BUFFER: i32 = 0x308E;
pub const EGL_HEIGHT: i32 = 0x3056;
pub const EGL_WIDTH: i32 = 0x3057;
pub const EGL_PBUFFER_BIT: i32 = 0x0001;
pub const EGL_WINDOW_BIT: i32 = 0x0004;
pub const EGL_OPENGL_ES2_BIT: i32 = 0x0004;
pub const EGL_DONT_CARE: i32 = -1;
/// `EGL_KHR_gl_colorspace`: the surface attribute and its two values.
pub const EGL_GL_COLORSPACE_KHR: i32 = 0x309D;
/// sRGB-encoded colour.
pub const EGL_GL_COLORSPACE_SRGB_KHR: i32 = 0x3089;
/// Linear colour (the default).
pub const EGL_GL_COLORSPACE_LINEAR_KHR: i32 = 0x308A;
/// `EGL_EXT_pixel_format_float`: the attribute and its two values.
pub const EGL_COLOR_COMPONENT_TYPE_EXT: i32 = 0x3339;
/// Fixed-point (normalised) colour components.
pub const EGL_COLOR_COMPONENT_TYPE_FIXED_EXT: i32 = 0x333A;
/// Floating-point colour components.
pub const EGL_COLOR_COMPONENT_TYPE_FLOAT_EXT: i32 = 0x333B;
pub const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;
/// `EGL_KHR_create_context`: the minor version, the flags and their bits, the profile (desktop
/// OpenGL's) and the reset notification strategy.
pub const EGL_CONTEXT_MINOR_VERSION_KHR: i32 = 0x30FB;
/// The context's flags.
pub const EGL_CONTEXT_FLAGS_KHR: i32 = 0x30FC;
/// A debug context.
pub const EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR: i32 = 0x1;
/// Forward-compatible (desktop OpenGL only).
pub const EGL_CONTEXT_OPENGL_FORWARD_COMPATIBLE_BIT_KHR: i32 = 0x2;
/// Robust buffer access.
pub const EGL_CONTEXT_OPENGL_ROBUST_ACCESS_BIT_KHR: i32 = 0x4;
/// The profile (desktop OpenGL only).
pub const EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR: i32 = 0x30FD;
/// The reset notification strategy, and its two values.
pub const EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_KHR: i32 = 0x31BD;
/// No reset notification.
pub const EGL_NO_RESET_NOTIFICATION_KHR: i32 = 0x31BE;
/// The context is lost on a reset.
pub const EGL_LOSE_CONTEXT_ON_RESET_KHR: i32 = 0x31BF;
/// `EGL_IMG_context_priority`: the attribute and its three levels.
pub const EGL_CONTEXT_PRIORITY_LEVEL_IMG: i32 = 0x3100;
/// High priority.
pub const EGL_CONTEXT_PRIORITY_HIGH_IMG: i32 = 0x3101;
/// Medium priority (the default).
pub const EGL_CONTEXT_PRIORITY_MEDIUM_IMG: i32 = 0x3102;
/// Low priority.
pub const EGL_CONTEXT_PRIORITY_LOW_IMG: i32 = 0x3103;
pub const EGL_RENDER_BUFFER: i32 = 0x3086;
pub const EGL_BACK_BUFFER: i32 = 0x3084;
pub const EGL_SWAP_BEHAVIOR: i32 = 0x3093;
/// `EGL_BUFFER_AGE_EXT` (`EGL_EXT_buffer_age`).
pub const EGL_BUFFER_AGE_EXT: i32 = 0x313D;
pub const EGL_BUFFER_DESTROYED: i32 = 0x3095;

// Query and texture targets of extensions.
/// `GL_TIME_ELAPSED_EXT`.
pub const TIME_ELAPSED: u32 = 0x88BF;
/// `GL_TIMESTAMP_EXT`.
pub const TIMESTAMP: u32 = 0x8E28;
/// `GL_QUERY_COUNTER_BITS_EXT`.
pub const QUERY_COUNTER_BITS: u32 = 0x8864;
/// `GL_GPU_DISJOINT_EXT`.
pub const GPU_DISJOINT: u32 = 0x8FBB;
/// `GL_TEXTURE_EXTERNAL_OES`.
pub const TEXTURE_EXTERNAL_OES: u32 = 0x8D65;
