//! `GL_OES_texture_3D` (with `GL_KHR_texture_compression_astc_sliced_3d`): a 4×4×4 image
//! sampled across its slices by a coordinate whose r runs with s and t, nearest and linear,
//! under every r wrap (and the border, where offered); mipmaps generated and minified
//! through; a box updated in part; luminance and half-float images; projective, biased,
//! parameter and vertex-stage lookups; a slice rendered into, read back and copied into; ASTC
//! slices; and the queries and errors, marked as colours.

use super::draw_buffers::compiles;
use super::multi_draw::mark_all;
use super::textures::float_data;
use super::*;

const TEXTURE_3D: u32 = 0x806F;
const TEXTURE_BINDING_3D: u32 = 0x806A;
const MAX_3D_TEXTURE_SIZE: u32 = 0x8073;
const TEXTURE_WRAP_R: u32 = 0x8072;
const ZOFFSET: u32 = 0x8CD4;
const CUBE_MAP_FACE: u32 = 0x8CD3;
const REPEAT: i32 = 0x2901;
const MIRRORED_REPEAT: i32 = 0x8370;
const CLAMP_TO_BORDER: i32 = 0x812D;
const BORDER_COLOR: u32 = 0x1004;
const LINEAR_MIPMAP_LINEAR: i32 = 0x2703;
const HALF_FLOAT_OES: u32 = 0x8D61;
const ASTC_4X4: u32 = 0x93B0;
const ETC1: u32 = 0x8D64;
const DEPTH_COMPONENT: u32 = 0x1902;
const FRAGMENT_SHADER: u32 = 0x8B30;
const VERTEX_SHADER: u32 = 0x8B31;

/// Texel (x, y, z) of the 4×4×4 image.
fn texel(x: usize, y: usize, z: usize) -> [u8; 4] {
    [(x * 60 + 10) as u8, (y * 60 + 10) as u8, (z * 60 + 10) as u8, (255 - (x + y + z) * 20) as u8]
}

/// The 4×4×4 image's bytes, slice by slice.
fn volume() -> Vec<u8> {
    (0..64).flat_map(|i| texel(i % 4, i / 4 % 4, i / 16)).collect()
}

/// Samples the bound 3D texture at (t, r) where r runs with s and t.
const FS_3D: &str = "#extension GL_OES_texture_3D : enable
    precision highp float; uniform lowp sampler3D s; varying vec2 t;
    void main() { gl_FragColor = texture3D(s, vec3(t, t.y * 0.8 + t.x * 0.2)); }";
/// Projective and biased lookups, by a `precision` statement for the sampler.
const FS_PROJ: &str = "#extension GL_OES_texture_3D : require
    precision highp float; precision mediump sampler3D; uniform sampler3D s; varying vec2 t;
    void main() { vec3 c = vec3(t, 1.0 - t.x);
                  gl_FragColor = t.x > t.y + 0.1 ? texture3DProj(s, vec4(c * 2.0, 2.0)) : texture3D(s, c, 0.5); }";
/// A lookup through a function's sampler parameter, of an element of a sampler array.
const FS_PARAM: &str = "#extension GL_OES_texture_3D : enable
    precision highp float; uniform highp sampler3D s[2]; varying vec2 t;
    vec4 look(lowp sampler3D x, vec3 c) { return texture3D(x, c); }
    void main() { gl_FragColor = look(s[1], vec3(t.yx, t.x)); }";
/// A vertex-stage lookup at each corner, interpolated.
const VS_LOOKUP: &str = "#extension GL_OES_texture_3D : enable
    attribute vec4 pos; attribute vec2 uv; uniform lowp sampler3D s; varying vec4 c;
    void main() { c = texture3DLod(s, vec3(uv, 0.6), 0.0) + texture3DProjLod(s, vec4(uv, 0.3, 1.0), 0.0) * 0.5;
                  gl_Position = pos; }";
const FS_VARYING: &str = "precision mediump float; varying vec4 c; void main() { gl_FragColor = c; }";
/// One slice (`SLICE` replaced by its r) of the bound texture.
const FS_SLICE: &str = "#extension GL_OES_texture_3D : enable
    precision highp float; uniform lowp sampler3D s; varying vec2 t;
    void main() { gl_FragColor = texture3D(s, vec3(t, SLICE)); }";

/// A new 3D texture on unit 0 with the given filters.
fn new_volume(gl: Gl<'_>, n: &mut Names, min: i32, mag: i32) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glActiveTexture(TEXTURE0)?;
    gl.glBindTexture(TEXTURE_3D, t)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_MIN_FILTER, min)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_MAG_FILTER, mag)?;
    Ok(t)
}

/// Sets the bound 3D texture's wraps.
fn wrap(gl: Gl<'_>, s: i32, t: i32, r: i32) -> R {
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_WRAP_S, s)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_WRAP_T, t)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_WRAP_R, r)
}

/// Draws the bound texture into the 10×10 square of cell `c` (six across), coordinates from
/// -0.75 to 1.75.
fn cell(gl: Gl<'_>, n: &mut Names, c: i32) -> R {
    gl.glViewport(c % 6 * 10, c / 6 * 10, 10, 10)?;
    textured_quad(gl, n, -0.75, 1.75)
}

/// Sampling: every filter and r wrap, mipmaps, a box updated, other formats and lookups.
fn texture_3d_sampling(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_3D, &["pos", "uv"])?;
    let border = gl.glGetString(0x1F03)?.unwrap_or_default().contains("GL_OES_texture_border_clamp");
    let tex = new_volume(gl, n, NEAREST, NEAREST)?;
    gl.glPixelStorei(UNPACK_ALIGNMENT, 1)?;
    gl.glTexImage3DOES(TEXTURE_3D, 0, RGBA, 4, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&volume())))?;
    let mut c = 0;
    for filter in [NEAREST, LINEAR] {
        gl.glTexParameteri(TEXTURE_3D, TEXTURE_MIN_FILTER, filter)?;
        gl.glTexParameteri(TEXTURE_3D, TEXTURE_MAG_FILTER, filter)?;
        for (s, t, r) in [
            (CLAMP_TO_EDGE, CLAMP_TO_EDGE, REPEAT),
            (REPEAT, CLAMP_TO_EDGE, CLAMP_TO_EDGE),
            (CLAMP_TO_EDGE, REPEAT, MIRRORED_REPEAT),
        ] {
            wrap(gl, s, t, r)?;
            cell(gl, n, c)?;
            c += 1;
        }
        if border {
            // The border on r alone, then on every axis.
            gl.glTexParameterfv(TEXTURE_3D, BORDER_COLOR, Slice::new(&[0.9, 0.2, 0.5, 0.7]))?;
            wrap(gl, CLAMP_TO_EDGE, CLAMP_TO_EDGE, CLAMP_TO_BORDER)?;
            cell(gl, n, c)?;
            wrap(gl, CLAMP_TO_BORDER, CLAMP_TO_BORDER, CLAMP_TO_BORDER)?;
            cell(gl, n, c + 1)?;
        }
        c += 2;
    }
    // Mipmaps, minified through: 4×4 pixels for 4×4×4 texels over 2.5 repeats.
    wrap(gl, REPEAT, REPEAT, REPEAT)?;
    gl.glGenerateMipmap(TEXTURE_3D)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_MIN_FILTER, LINEAR_MIPMAP_LINEAR)?;
    gl.glViewport(c % 6 * 10, c / 6 * 10, 4, 4)?;
    textured_quad(gl, n, -0.75, 1.75)?;
    gl.glViewport(c % 6 * 10 + 4, c / 6 * 10, 2, 2)?;
    textured_quad(gl, n, -0.75, 1.75)?;
    c += 1;
    // A 2×3×2 box of level 0 updated, drawn nearest.
    let boxed: Vec<u8> = (0..12).flat_map(|i| [250, (i * 20) as u8, 40, 255]).collect();
    gl.glTexSubImage3DOES(TEXTURE_3D, 0, 1, 0, 2, 2, 3, 2, RGBA, UNSIGNED_BYTE, Blob::borrowed(&boxed))?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_MAG_FILTER, NEAREST)?;
    cell(gl, n, c)?;
    c += 1;
    // Luminance-alpha bytes, and RGB half floats of 3×5×2 (not a power of two), linear.
    new_volume(gl, n, LINEAR, LINEAR)?;
    let la: Vec<u8> = (0..64).flat_map(|i| [(i * 4) as u8, (255 - i * 3) as u8]).collect();
    gl.glTexImage3DOES(
        TEXTURE_3D,
        0,
        LUMINANCE_ALPHA,
        4,
        4,
        4,
        0,
        LUMINANCE_ALPHA,
        UNSIGNED_BYTE,
        Some(Blob::borrowed(&la)),
    )?;
    cell(gl, n, c)?;
    new_volume(gl, n, LINEAR, LINEAR)?;
    let v: Vec<f32> = (0..90).map(|i| (i % 11) as f32 * 0.1).collect();
    let half = float_data(&v, HALF_FLOAT_OES);
    gl.glTexImage3DOES(TEXTURE_3D, 0, RGB, 3, 5, 2, 0, RGB, HALF_FLOAT_OES, Some(Blob::borrowed(&half)))?;
    cell(gl, n, c + 1)?;
    c += 2;
    // The other lookups, of the first texture (mipmapped, linear).
    gl.glBindTexture(TEXTURE_3D, tex)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_MIN_FILTER, LINEAR_MIPMAP_LINEAR)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_MAG_FILTER, LINEAR)?;
    for (vs, fs) in [(VS_TEX, FS_PROJ), (VS_TEX, FS_PARAM), (VS_LOOKUP, FS_VARYING)] {
        let p = program(gl, n, vs, fs, &["pos", "uv"])?;
        if fs == FS_PARAM {
            // Both elements on unit 0.
            let loc = gl.glGetUniformLocation(p, Text::borrowed("s[1]"))?;
            gl.glUniform1i(loc, 0)?;
        }
        cell(gl, n, c)?;
        c += 1;
    }
    Ok(())
}

/// Rendering into slices: cleared and drawn, read back, then sampled; a copy from the window
/// into a slice; ASTC slices; and the queries and errors.
fn texture_3d_targets(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    // An 8×8×4 image; slice 2 becomes a framebuffer's colour.
    let tex = new_volume(gl, n, NEAREST, NEAREST)?;
    let data: Vec<u8> = (0..256).flat_map(|i| texel(i % 8 / 2, i / 8 % 8 / 2, i / 64)).collect();
    gl.glTexImage3DOES(TEXTURE_3D, 0, RGBA, 8, 8, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&data)))?;
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture3DOES(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_3D, tex, 0, 2)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    marks.push(gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, ZOFFSET)? as u32);
    marks.push(gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, CUBE_MAP_FACE)? as u32);
    gl.glViewport(0, 0, 8, 8)?;
    gl.glClearColor(0.2, 0.9, 0.4, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    vertex_quad(gl, n, [-0.5, -1.0, 1.0, 0.5], |x, y| [x, y, 0.0, 0.5 + x * 0.5, 0.3, 0.5 - y * 0.5, 1.0])?;
    let px = gl.glReadPixels(1, 1, 6, 1, RGBA, UNSIGNED_BYTE)?.0;
    marks.extend(px.chunks_exact(4).map(|p| u32::from(p[0]) | u32::from(p[2]) << 8));
    // A slice past the level's is incomplete; so is a depth attachment of a colour image.
    gl.glFramebufferTexture3DOES(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_3D, tex, 0, 4)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glFramebufferTexture3DOES(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_3D, tex, 0, 3)?;
    gl.glFramebufferTexture3DOES(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_3D, tex, 0, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    // Slices 1 (untouched) and 2 (drawn), then a copy of the window's corner into slice 3.
    gl.glViewport(0, 0, W, H)?;
    gl.glClearColor(0.1, 0.3, 0.7, 0.6)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    for (slice, x) in [("0.375", 0), ("0.625", 16)] {
        program(gl, n, VS_TEX, &FS_SLICE.replace("SLICE", slice), &["pos", "uv"])?;
        gl.glViewport(x, 0, 16, 16)?;
        textured_quad(gl, n, 0.0, 1.0)?;
    }
    gl.glCopyTexSubImage3DOES(TEXTURE_3D, 0, 2, 1, 3, 14, 2, 5, 6)?;
    marks.push(gl.glGetError()?);
    program(gl, n, VS_TEX, &FS_SLICE.replace("SLICE", "0.875"), &["pos", "uv"])?;
    gl.glViewport(32, 0, 16, 16)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    // ASTC: two 20×13 slices, the second the first's blocks reversed.
    if let Some(blocks) = astc_blocks() {
        new_volume(gl, n, NEAREST, NEAREST)?;
        let mut both = blocks.clone();
        both.extend(blocks.chunks_exact(16).rev().flatten());
        gl.glCompressedTexImage3DOES(TEXTURE_3D, 0, ASTC_4X4, 20, 13, 2, 0, Blob::borrowed(&both))?;
        marks.push(gl.glGetError()?);
        for (slice, y) in [("0.25", 16), ("0.75", 29)] {
            program(gl, n, VS_TEX, &FS_SLICE.replace("SLICE", slice), &["pos", "uv"])?;
            gl.glViewport(48, y, 16, 13)?;
            textured_quad(gl, n, 0.0, 1.0)?;
        }
        // A block of slice 1 replaced by slice 0's first.
        gl.glCompressedTexSubImage3DOES(TEXTURE_3D, 0, 4, 4, 1, 4, 4, 1, ASTC_4X4, Blob::borrowed(&blocks[..16]))?;
        marks.push(gl.glGetError()?);
        textured_quad(gl, n, 0.0, 1.0)?;
        // Errors: a size the blocks do not fill, and ETC1, which has no 3D images.
        gl.glCompressedTexImage3DOES(TEXTURE_3D, 0, ASTC_4X4, 20, 13, 2, 0, Blob::borrowed(&blocks))?;
        marks.push(gl.glGetError()?);
        gl.glCompressedTexImage3DOES(TEXTURE_3D, 0, ETC1, 4, 4, 1, 0, Blob::borrowed(&[0; 8]))?;
        marks.push(gl.glGetError()?);
        // A box too large for any data (its size overflows what a length can hold).
        let huge = i32::MAX;
        gl.glCompressedTexSubImage3DOES(
            TEXTURE_3D,
            0,
            0,
            0,
            0,
            huge,
            huge,
            huge,
            ASTC_4X4,
            Blob::borrowed(&blocks[..16]),
        )?;
        marks.push(gl.glGetError()?);
        gl.glCompressedTexImage3DOES(TEXTURE_2D, 0, ASTC_4X4, 4, 4, 1, 0, Blob::borrowed(&blocks[..16]))?;
        marks.push(gl.glGetError()?);
    }
    marks.extend(queries_and_errors(gl, n, tex)?);
    mark_all(gl, &marks)
}

/// piglit's 20×13 ASTC 4×4 image (its waffle's fourth level), if piglit is installed.
fn astc_blocks() -> Option<Vec<u8>> {
    let dir = "/usr/lib/x86_64-linux-gnu/piglit/tests/spec/khr_texture_compression_astc/compressed/2D/ldrl";
    let Ok(file) = std::fs::read(format!("{dir}/waffles-4x4.ktx")) else {
        assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "piglit's ASTC images are missing");
        eprintln!("SKIPPED: piglit's ASTC images are not installed (tools/install-deps installs piglit)");
        return None;
    };
    // KTX 1: the key-value bytes, then each level as a size and its data (4-byte aligned).
    let word = |i: usize| u32::from_le_bytes(file[12 + 4 * i..16 + 4 * i].try_into().unwrap_or_default()) as usize;
    let mut at = 64 + word(12);
    for level in 0..4 {
        let size = u32::from_le_bytes(file.get(at..at + 4)?.try_into().ok()?) as usize;
        if level == 3 {
            return file.get(at + 4..at + 4 + size).map(<[u8]>::to_vec);
        }
        at += 4 + size.div_ceil(4) * 4;
    }
    None
}

/// The state queries, and each call's error where it should fail, as marks.
fn queries_and_errors(gl: Gl<'_>, n: &mut Names, tex: u32) -> Result<Vec<u32>, ClientError> {
    let mut m = Vec::new();
    m.push(gl.glGetIntegerv(MAX_3D_TEXTURE_SIZE)?.first().copied().unwrap_or(-1) as u32);
    m.push((gl.glGetIntegerv(TEXTURE_BINDING_3D)?.first().copied().unwrap_or(-1) as u32).wrapping_sub(tex));
    m.push(gl.glGetTexParameteriv(TEXTURE_3D, TEXTURE_WRAP_R)?.first().copied().unwrap_or(-1) as u32);
    gl.glBindTexture(TEXTURE_3D, tex)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_WRAP_R, MIRRORED_REPEAT)?;
    m.push(gl.glGetTexParameteriv(TEXTURE_3D, TEXTURE_WRAP_R)?.first().copied().unwrap_or(-1) as u32);
    // Every texture has an r wrap.
    let flat = n.next();
    gl.glBindTexture(TEXTURE_2D, flat)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_R, CLAMP_TO_EDGE)?;
    m.push(gl.glGetError()?);
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_WRAP_R, NEAREST)?;
    m.push(gl.glGetError()?);
    let px = [7u8; 64];
    let some = || Some(Blob::borrowed(&px));
    let errors: [(&str, [i32; 5], u32, u32); 6] = [
        ("2D target", [0, 2, 2, 2, 0], TEXTURE_2D, RGBA),
        ("border", [0, 2, 2, 2, 1], TEXTURE_3D, RGBA),
        ("negative depth", [0, 2, 2, -1, 0], TEXTURE_3D, RGBA),
        ("too deep", [0, 2, 2, 4096, 0], TEXTURE_3D, RGBA),
        ("level 12", [12, 1, 1, 1, 0], TEXTURE_3D, RGBA),
        ("depth format", [0, 2, 2, 2, 0], TEXTURE_3D, DEPTH_COMPONENT),
    ];
    for (_, [level, w, h, d, border], target, format) in errors {
        let ty = if format == DEPTH_COMPONENT { UNSIGNED_INT } else { UNSIGNED_BYTE };
        gl.glTexImage3DOES(target, level, format, w, h, d, border, format, ty, if d > 100 { None } else { some() })?;
        m.push(gl.glGetError()?);
    }
    // Sub-images: a box past the slices, another format, an undefined level.
    gl.glTexSubImage3DOES(TEXTURE_3D, 0, 0, 0, 3, 2, 2, 2, RGBA, UNSIGNED_BYTE, Blob::borrowed(&px))?;
    m.push(gl.glGetError()?);
    gl.glTexSubImage3DOES(TEXTURE_3D, 0, 0, 0, 0, 1, 1, 1, RGB, UNSIGNED_BYTE, Blob::borrowed(&px))?;
    m.push(gl.glGetError()?);
    gl.glTexSubImage3DOES(TEXTURE_3D, 2, 0, 0, 0, 1, 1, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&px))?;
    m.push(gl.glGetError()?);
    gl.glCopyTexSubImage3DOES(TEXTURE_3D, 0, 0, 0, 4, 0, 0, 2, 2)?;
    m.push(gl.glGetError()?);
    gl.glCopyTexSubImage3DOES(TEXTURE_2D, 0, 0, 0, 0, 0, 0, 2, 2)?;
    m.push(gl.glGetError()?);
    // Attachments: a 2D target for a 3D texture, a 3D target for a 2D one, a 3D texture through
    // glFramebufferTexture2D, slices and levels out of range.
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 2, 2, 0, RGBA, UNSIGNED_BYTE, some())?;
    for (textarget, t, level, z) in [
        (TEXTURE_2D, tex, 0, 0),
        (TEXTURE_3D, flat, 0, 0),
        (TEXTURE_3D, tex, 0, -1),
        (TEXTURE_3D, tex, 0, 2048),
        (TEXTURE_3D, tex, 12, 0),
    ] {
        gl.glFramebufferTexture3DOES(FRAMEBUFFER, COLOR_ATTACHMENT0, textarget, t, level, z)?;
        m.push(gl.glGetError()?);
    }
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    m.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    // Shaders: 3D lookups need the directive; sampler3D has no default precision; no
    // explicit-level lookups in fragment shaders.
    for (ty, source) in [
        (FRAGMENT_SHADER, "precision mediump float; uniform lowp sampler3D s; void main() { gl_FragColor = texture3D(s, vec3(0.5)); }"),
        (FRAGMENT_SHADER, "#extension GL_OES_texture_3D : enable\nprecision mediump float; uniform sampler3D s; void main() { gl_FragColor = texture3D(s, vec3(0.5)); }"),
        (FRAGMENT_SHADER, "#extension GL_OES_texture_3D : enable\nprecision mediump float; uniform lowp sampler3D s; void main() { gl_FragColor = texture3DLod(s, vec3(0.5), 1.0); }"),
        (FRAGMENT_SHADER, "#extension GL_OES_texture_3D : disable\nprecision mediump float; uniform lowp sampler3D s; void main() { gl_FragColor = texture3D(s, vec3(0.5)); }"),
        (FRAGMENT_SHADER, "#ifndef GL_OES_texture_3D\n#error no\n#endif\nprecision mediump float; void main() { gl_FragColor = vec4(GL_OES_texture_3D); }"),
        (VERTEX_SHADER, "uniform sampler3D s; void main() { gl_Position = vec4(0.0); }"),
        (VERTEX_SHADER, "precision lowp sampler3D; uniform sampler3D s; void main() { gl_Position = vec4(0.0); }"),
        (VERTEX_SHADER, "#extension GL_OES_texture_3D : enable\nprecision lowp sampler3D; uniform sampler3D s; void main() { gl_Position = vec4(0.0); }"),
    ] {
        m.push(compiles(gl, n, ty, source)?);
    }
    Ok(m)
}

/// Every program of this file, with its tolerance: linear filtering across slices and the
/// generated mipmaps round differently by a step or two.
pub fn all() -> Vec<Case> {
    let tol = Tol { max_diff: 2, min_fraction: 0.999 };
    vec![
        Case { name: "texture_3d_sampling", run: texture_3d_sampling, tol, expects_error: false },
        Case { name: "texture_3d_targets", run: texture_3d_targets, tol, expects_error: false },
    ]
}
