//! Small GLES 2.0 programs, each exercising part of the executor, written once against `Calls`
//! and run by `gles_oracle.rs` through both Strata and Mesa.
#![allow(dead_code)]

use strata_client::{Calls, ClientError};
use strata_protocol::{Blob, Slice, Text};

/// Framebuffer width.
pub const W: i32 = 64;
/// Framebuffer height.
pub const H: i32 = 64;

/// A backend-neutral GL.
pub type Gl<'a> = &'a mut dyn Calls<Error = ClientError>;
type R = Result<(), ClientError>;

/// Per-case tolerance and why it is what it is.
#[derive(Clone, Copy)]
pub struct Tol {
    /// Largest per-channel difference that counts as equal.
    pub max_diff: u8,
    /// Fraction of pixels that must be equal.
    pub min_fraction: f64,
}

/// The default: ≤ 1/255 per channel on ≥ 99.9 % of pixels (rounding of the last bit).
pub const DEFAULT: Tol = Tol { max_diff: 1, min_fraction: 0.999 };

/// One program of the suite.
pub struct Case {
    /// Name (also the failure image prefix).
    pub name: &'static str,
    /// The program.
    pub run: fn(Gl<'_>, &mut Names) -> R,
    /// Its tolerance.
    pub tol: Tol,
    /// Whether it deliberately leaves a GL error behind.
    pub expects_error: bool,
}

/// Client-side name allocation, as an application's shim does it.
#[derive(Default)]
pub struct Names(u32);

impl Names {
    /// An allocator whose names start above `base`.
    pub fn starting_at(base: u32) -> Names {
        Names(base)
    }

    /// A fresh object name.
    pub fn next(&mut self) -> u32 {
        self.0 += 1;
        self.0 + 100
    }
}

// GL enums used below.
pub const POINTS: u32 = 0x0000;
pub const TRIANGLES: u32 = 0x0004;
pub const TRIANGLE_STRIP: u32 = 0x0005;
pub const TRIANGLE_FAN: u32 = 0x0006;
pub const LINES: u32 = 0x0001;
pub const LINE_LOOP: u32 = 0x0002;
pub const LINE_STRIP: u32 = 0x0003;
pub const FLOAT: u32 = 0x1406;
pub const BYTE: u32 = 0x1400;
pub const UNSIGNED_BYTE: u32 = 0x1401;
pub const SHORT: u32 = 0x1402;
pub const UNSIGNED_SHORT: u32 = 0x1403;
pub const UNSIGNED_INT: u32 = 0x1405;
pub const FIXED: u32 = 0x140C;
pub const HALF_FLOAT_OES: u32 = 0x8D61;
pub const ARRAY_BUFFER: u32 = 0x8892;
pub const ELEMENT_ARRAY_BUFFER: u32 = 0x8893;
pub const STATIC_DRAW: u32 = 0x88E4;
pub const COLOR_BUFFER_BIT: u32 = 0x4000;
pub const DEPTH_BUFFER_BIT: u32 = 0x0100;
pub const STENCIL_BUFFER_BIT: u32 = 0x0400;
pub const DEPTH_TEST: u32 = 0x0B71;
pub const CULL_FACE: u32 = 0x0B44;
pub const BLEND: u32 = 0x0BE2;
pub const SCISSOR_TEST: u32 = 0x0C11;
pub const STENCIL_TEST: u32 = 0x0B90;
pub const POLYGON_OFFSET_FILL: u32 = 0x8037;
pub const TEXTURE_2D: u32 = 0x0DE1;
pub const TEXTURE_CUBE_MAP: u32 = 0x8513;
pub const TEXTURE_CUBE_MAP_POSITIVE_X: u32 = 0x8515;
pub const TEXTURE0: u32 = 0x84C0;
pub const RGBA: u32 = 0x1908;
pub const RGB: u32 = 0x1907;
pub const ALPHA: u32 = 0x1906;
pub const LUMINANCE: u32 = 0x1909;
pub const LUMINANCE_ALPHA: u32 = 0x190A;
pub const NEAREST: i32 = 0x2600;
pub const LINEAR: i32 = 0x2601;
pub const LINEAR_MIPMAP_LINEAR: i32 = 0x2703;
pub const NEAREST_MIPMAP_NEAREST: i32 = 0x2700;
pub const TEXTURE_MAG_FILTER: u32 = 0x2800;
pub const TEXTURE_MIN_FILTER: u32 = 0x2801;
pub const TEXTURE_WRAP_S: u32 = 0x2802;
pub const TEXTURE_WRAP_T: u32 = 0x2803;
pub const REPEAT: i32 = 0x2901;
pub const CLAMP_TO_EDGE: i32 = 0x812F;
pub const MIRRORED_REPEAT: i32 = 0x8370;
pub const FRAMEBUFFER: u32 = 0x8D40;
pub const RENDERBUFFER: u32 = 0x8D41;
pub const COLOR_ATTACHMENT0: u32 = 0x8CE0;
pub const DEPTH_ATTACHMENT: u32 = 0x8D00;
pub const DEPTH_COMPONENT16: u32 = 0x81A5;
pub const UNPACK_ALIGNMENT: u32 = 0x0CF5;

/// Compiles and links `vs` + `fs` with `attribs` bound to locations 0, 1, …, and uses it.
pub fn program(gl: Gl<'_>, names: &mut Names, vs: &str, fs: &str, attribs: &[&str]) -> Result<u32, ClientError> {
    let ids = (names.next(), names.next(), names.next());
    strata_client::setup::link_program(gl, ids, vs, fs, attribs)
}

/// A buffer holding `data`, left bound to `target`.
pub fn buffer(gl: Gl<'_>, names: &mut Names, target: u32, data: &[u8]) -> Result<u32, ClientError> {
    let b = names.next();
    gl.glGenBuffers(Slice::new(&[b]))?;
    gl.glBindBuffer(target, b)?;
    gl.glBufferData(target, data.len() as i64, Some(Blob::borrowed(data)), STATIC_DRAW)?;
    Ok(b)
}

/// Floats as bytes.
pub fn f32s(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_ne_bytes()).collect()
}

/// Binds attribute `index` to the bound array buffer with `size` floats per vertex.
pub fn attrib(gl: Gl<'_>, index: u32, size: i32, ty: u32, normalized: bool, stride: i32, offset: u64) -> R {
    gl.glVertexAttribPointer(index, size, ty, normalized, stride, offset)?;
    gl.glEnableVertexAttribArray(index)
}

/// An axis-aligned quad as two triangles at depth `z`, in clip space.
pub fn quad(x0: f32, y0: f32, x1: f32, y1: f32, z: f32) -> Vec<f32> {
    vec![x0, y0, z, x1, y0, z, x1, y1, z, x0, y0, z, x1, y1, z, x0, y1, z]
}

/// Draws `verts` (xyz triples) with the bound program, attribute 0 = position.
pub fn draw_positions(gl: Gl<'_>, names: &mut Names, verts: &[f32], mode: u32) -> R {
    buffer(gl, names, ARRAY_BUFFER, &f32s(verts))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    gl.glDrawArrays(mode, 0, (verts.len() / 3) as i32)
}

/// Sets the `color` uniform of program `p`.
pub fn color(gl: Gl<'_>, p: u32, c: [f32; 4]) -> R {
    let loc = gl.glGetUniformLocation(p, Text::borrowed("color"))?;
    gl.glUniform4f(loc, c[0], c[1], c[2], c[3])
}

/// A 2D texture from RGBA8 pixels, bound to unit 0, with the given filters and wraps.
#[allow(clippy::too_many_arguments)]
pub fn texture(
    gl: Gl<'_>,
    names: &mut Names,
    w: i32,
    h: i32,
    format: u32,
    ty: u32,
    px: &[u8],
    filter: i32,
    wrap: i32,
) -> Result<u32, ClientError> {
    let t = names.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glActiveTexture(TEXTURE0)?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexImage2D(TEXTURE_2D, 0, format as i32, w, h, 0, format, ty, Some(Blob::borrowed(px)))?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, filter)?;
    gl.glTexParameteri(
        TEXTURE_2D,
        TEXTURE_MAG_FILTER,
        if filter == LINEAR || filter == LINEAR_MIPMAP_LINEAR { LINEAR } else { NEAREST },
    )?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_S, wrap)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_T, wrap)?;
    Ok(t)
}

/// A deterministic test pattern of `w`×`h` RGBA8 pixels.
pub fn pattern(w: i32, h: i32) -> Vec<u8> {
    let mut v = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            v.extend_from_slice(&[
                (x * 255 / (w - 1).max(1)) as u8,
                (y * 255 / (h - 1).max(1)) as u8,
                ((x ^ y) * 37 % 256) as u8,
                255,
            ]);
        }
    }
    v
}

pub const VS_POS: &str = "attribute vec4 pos; void main() { gl_Position = pos; }";
pub const FS_COLOR: &str = "precision mediump float; uniform vec4 color; void main() { gl_FragColor = color; }";
pub const VS_COLOR: &str =
    "attribute vec4 pos; attribute vec4 col; varying vec4 v; void main() { v = col; gl_Position = pos; }";
pub const FS_VARY: &str = "precision mediump float; varying vec4 v; void main() { gl_FragColor = v; }";
pub const VS_TEX: &str =
    "attribute vec4 pos; attribute vec2 uv; varying vec2 t; void main() { t = uv; gl_Position = pos; }";
pub const FS_TEX: &str =
    "precision mediump float; uniform sampler2D s; varying vec2 t; void main() { gl_FragColor = texture2D(s, t); }";

/// Draws the quad from corner (`x0`, `y0`) to (`x1`, `y1`) in clip space as two triangles, each
/// vertex's position (xyz) and colour (rgba) given by `vertex(x, y)`, with the bound program's
/// attribute 0 the position and 1 the colour.
pub fn vertex_quad(gl: Gl<'_>, n: &mut Names, [x0, y0, x1, y1]: [f32; 4], vertex: impl Fn(f32, f32) -> [f32; 7]) -> R {
    let v: Vec<f32> =
        [(x0, y0), (x1, y0), (x1, y1), (x0, y0), (x1, y1), (x0, y1)].iter().flat_map(|&(x, y)| vertex(x, y)).collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)
}

/// Shows a sampled depth: d in red, fract(16·d) in green, to make depth errors visible.
pub const FS_DEPTH: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    void main() { float d = texture2D(s, t).r; gl_FragColor = vec4(d, fract(d * 16.0), 0.0, 1.0); }";

/// A `size`×`size` `DEPTH_COMPONENT` texture bound as the depth of a new framebuffer object,
/// which is bound with the viewport on it and the depth test on; the texture.
pub fn depth_texture_target(gl: Gl<'_>, n: &mut Names, size: i32) -> Result<u32, ClientError> {
    let (fb, tex) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, 0x1902, size, size, 0, 0x1902, UNSIGNED_INT, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_2D, tex, 0)?;
    if gl.glCheckFramebufferStatus(FRAMEBUFFER)? != 0x8CD5 {
        return Err(ClientError::Unsupported("depth-only framebuffer incomplete".into()));
    }
    gl.glViewport(0, 0, size, size)?;
    gl.glEnable(DEPTH_TEST)?;
    Ok(tex)
}

/// Back to the window (depth test off, full viewport), showing depth texture `tex` with
/// [`FS_DEPTH`] over it.
pub fn show_depth_texture(gl: Gl<'_>, n: &mut Names, tex: u32) -> R {
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glDisable(DEPTH_TEST)?;
    gl.glViewport(0, 0, W, H)?;
    program(gl, n, VS_TEX, FS_DEPTH, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    textured_quad(gl, n, 0.0, 1.0)
}

/// A full-screen quad with texture coordinates `uv0..uv1` drawn with the bound texture program.
pub fn textured_quad(gl: Gl<'_>, names: &mut Names, uv0: f32, uv1: f32) -> R {
    let v = [
        -1.0, -1.0, uv0, uv0, 1.0, -1.0, uv1, uv0, 1.0, 1.0, uv1, uv1, -1.0, -1.0, uv0, uv0, 1.0, 1.0, uv1, uv1, -1.0,
        1.0, uv0, uv1,
    ];
    buffer(gl, names, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
    attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)
}

mod anisotropic;
mod astc;
mod base_vertex;
mod blend_extended;
mod border_clamp;
mod cases;
mod clip_control;
mod compressed;
mod debug_label;
mod depth_clamp;
mod depth_cube;
mod derivatives;
mod draw_buffers;
pub mod es3;
mod filter_choice;
mod frag_depth;
mod framebuffer_ext;
mod half_float_color;
pub mod harness;
mod instanced;
mod max_level;
mod mesa_bgra;
mod multi_draw;
mod objects;
mod occlusion;
mod offset_clamp;
mod parallel_compile;
mod points;
mod program_binary;
mod read_buffer;
mod read_depth;
mod render_mipmap;
mod s3tc_srgb;
mod samplers;
mod struct_uniforms;
mod texture_3d;
mod texture_rg;
mod textures;
mod type_2_10_10_10;

/// Every program, with its tolerance.
pub fn all() -> Vec<Case> {
    let mut all = cases::all();
    all.extend(objects::all());
    all.extend(textures::all());
    all.extend(compressed::all());
    all.extend(points::all());
    all.extend(framebuffer_ext::all());
    all.extend(frag_depth::all());
    all.extend(offset_clamp::all());
    all.extend(parallel_compile::all());
    all.extend(base_vertex::all());
    all.extend(multi_draw::all());
    all.extend(instanced::all());
    all.extend(texture_rg::all());
    all.extend(texture_3d::all());
    all.extend(debug_label::all());
    all.extend(read_buffer::all());
    all.extend(render_mipmap::all());
    all.extend(anisotropic::all());
    all.extend(filter_choice::all());
    all.extend(derivatives::all());
    all.extend(samplers::all());
    all.extend(type_2_10_10_10::all());
    all.extend(depth_clamp::all());
    all.extend(draw_buffers::all());
    all.extend(blend_extended::all());
    all.extend(max_level::all());
    all.extend(half_float_color::all());
    all.extend(border_clamp::all());
    all.extend(mesa_bgra::all());
    all.extend(occlusion::all());
    all.extend(program_binary::all());
    all.extend(clip_control::all());
    all.extend(s3tc_srgb::all());
    all.extend(astc::all());
    all.extend(read_depth::all());
    all.extend(depth_cube::all());
    all.extend(struct_uniforms::all());
    all
}
