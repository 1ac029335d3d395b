//! Immutable texture storage (`glTexStorage2D`, `glTexStorage3D`): 2D, cube and 3D textures
//! of fewer levels than a full chain, complete with a mipmap filter and clamped to their last
//! level; each level written by sub-images; normalized, half-float (from float and half-float
//! data), float, red-green, luminance-alpha and depth formats; a level rendered to through a
//! framebuffer and generated mipmaps; the immutable-format and level queries; and the errors
//! (respecification, levels, formats, sizes, targets, data the format does not take), as
//! colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const TEXTURE_3D: u32 = 0x806F;
const TEXTURE_MAX_LEVEL: u32 = 0x813D;
const TEXTURE_IMMUTABLE_FORMAT: u32 = 0x912F;
const TEXTURE_IMMUTABLE_LEVELS: u32 = 0x82DF;
const RGBA8: u32 = 0x8058;
const RG8: u32 = 0x822B;
const RG: u32 = 0x8227;
const RED: u32 = 0x1903;
const RGBA16F: u32 = 0x881A;
const R32F: u32 = 0x822E;
const LUMINANCE8_ALPHA8: u32 = 0x8045;
const DEPTH_COMPONENT: u32 = 0x1902;
const HALF_FLOAT: u32 = 0x140B;
const UNSIGNED_SHORT_4_4_4_4: u32 = 0x8033;
const ETC1_RGB8: u32 = 0x8D64;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform sampler2D s2; uniform samplerCube sc; uniform highp sampler3D s3;
    uniform int mode; uniform vec3 coord; uniform float lod; uniform float scale;
    out vec4 o;
    void main() {
        vec4 c;
        if (mode == 0 || mode == 3) c = textureLod(s2, coord.xy, lod);
        else if (mode == 1) c = texture(sc, coord);
        else c = textureLod(s3, coord, lod);
        o = mode == 3 ? vec4(c.r, 0.0, 0.0, 1.0) : c * scale;
    }";

/// The uniforms' locations, in the order mode, coord, lod, scale.
struct Sampling([i32; 4]);

impl Sampling {
    /// Draws cell `k` (8 across, 8×8 pixels each, from the bottom left) sampling in `mode` at
    /// `coord` and level of detail `lod`, scaled by `scale`.
    fn cell(&self, gl: Gl<'_>, n: &mut Names, k: usize, mode: i32, coord: [f32; 3], [lod, scale]: [f32; 2]) -> R {
        let [m, c, l, s] = self.0;
        gl.glUniform1i(m, mode)?;
        gl.glUniform3f(c, coord[0], coord[1], coord[2])?;
        gl.glUniform1f(l, lod)?;
        gl.glUniform1f(s, scale)?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    }
}

/// A new texture bound to `target` on the active unit, filtered nearest (mipmapped where
/// `mipmaps`).
fn new_texture(gl: Gl<'_>, n: &mut Names, target: u32, mipmaps: bool) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(target, t)?;
    gl.glTexParameteri(target, TEXTURE_MIN_FILTER, if mipmaps { NEAREST_MIPMAP_NEAREST } else { NEAREST })?;
    gl.glTexParameteri(target, TEXTURE_MAG_FILTER, NEAREST)?;
    Ok(t)
}

/// `count` texels of `rgba`.
fn solid(rgba: [u8; 4], count: usize) -> Vec<u8> {
    rgba.repeat(count)
}

/// Writes level `level` (`size`×`size`) of the bound 2D image as one colour.
fn fill_level(gl: Gl<'_>, target: u32, level: i32, size: i32, rgba: [u8; 4]) -> R {
    let data = solid(rgba, (size * size) as usize);
    gl.glTexSubImage2D(target, level, 0, 0, size, size, RGBA, UNSIGNED_BYTE, Blob::borrowed(&data))
}

/// The storage program.
pub fn tex_storage(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let loc = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let sampling = Sampling([loc(gl, "mode")?, loc(gl, "coord")?, loc(gl, "lod")?, loc(gl, "scale")?]);
    for (k, name) in ["s2", "sc", "s3"].iter().enumerate() {
        let l = loc(gl, name)?;
        gl.glUniform1i(l, k as i32)?;
    }
    let mut marks = Vec::new();
    // Texture 0 answers with the initial state.
    gl.glBindTexture(TEXTURE_2D, 0)?;
    for pname in [TEXTURE_IMMUTABLE_LEVELS, TEXTURE_MIN_FILTER] {
        marks.push(gl.glGetTexParameteriv(TEXTURE_2D, pname)?.first().copied().unwrap_or(-1) as u32);
    }

    // A 2D texture of three levels of a chain of four: complete with a mipmap filter, and
    // level-of-detail 3 reads the last, level 2.
    gl.glActiveTexture(TEXTURE0)?;
    new_texture(gl, n, TEXTURE_2D, true)?;
    gl.glTexStorage2D(TEXTURE_2D, 3, RGBA8, 8, 8)?;
    let colours = [[200, 40, 40, 255], [40, 200, 40, 255], [40, 40, 200, 255]];
    for (level, c) in colours.iter().enumerate() {
        fill_level(gl, TEXTURE_2D, level as i32, 8 >> level, *c)?;
    }
    for lod in 0..4 {
        sampling.cell(gl, n, lod, 0, [0.5, 0.5, 0.0], [lod as f32, 1.0])?;
    }
    for pname in [TEXTURE_IMMUTABLE_FORMAT, TEXTURE_IMMUTABLE_LEVELS] {
        marks.push(gl.glGetTexParameteriv(TEXTURE_2D, pname)?.first().copied().unwrap_or(-1) as u32);
    }
    // The errors on it: storage again, respecification by each call, a level beyond its
    // three, data the format does not take, and the query as a parameter to set.
    gl.glTexStorage2D(TEXTURE_2D, 1, RGBA8, 8, 8)?;
    marks.push(gl.glGetError()?);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, None)?;
    marks.push(gl.glGetError()?);
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA, 0, 0, 8, 8, 0)?;
    marks.push(gl.glGetError()?);
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, ETC1_RGB8, 4, 4, 0, Blob::borrowed(&[0; 8]))?;
    marks.push(gl.glGetError()?);
    gl.glTexSubImage2D(TEXTURE_2D, 3, 0, 0, 1, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&[0; 4]))?;
    marks.push(gl.glGetError()?);
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGBA, UNSIGNED_SHORT_4_4_4_4, Blob::borrowed(&[0; 2]))?;
    marks.push(gl.glGetError()?);
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_IMMUTABLE_FORMAT, 0)?;
    marks.push(gl.glGetError()?);

    // A mutable texture answers the queries with 0.
    let mutable = new_texture(gl, n, TEXTURE_2D, false)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 2, 2, 0, RGBA, UNSIGNED_BYTE, None)?;
    for pname in [TEXTURE_IMMUTABLE_FORMAT, TEXTURE_IMMUTABLE_LEVELS] {
        marks.push(gl.glGetTexParameteriv(TEXTURE_2D, pname)?.first().copied().unwrap_or(-1) as u32);
    }

    // The errors of the call itself, on the mutable texture (which none of them changes).
    let storage_errors: [(u32, i32, u32, i32, i32); 7] = [
        (TEXTURE_2D, 0, RGBA8, 4, 4),       // no levels
        (TEXTURE_2D, 1, RGBA8, 0, 4),       // no width
        (TEXTURE_2D, 4, RGBA8, 4, 4),       // more levels than the chain
        (TEXTURE_2D, 1, RGBA, 4, 4),        // unsized
        (TEXTURE_3D, 1, RGBA8, 4, 4),       // a 3D target for the 2D call
        (TEXTURE_2D, 1, RGBA8, 100_000, 1), // too wide
        (TEXTURE_CUBE_MAP, 1, RGBA8, 4, 2), // (a cube's target, but the cube is unbound: texture 0)
    ];
    for (target, levels, format, w, h) in storage_errors {
        gl.glTexStorage2D(target, levels, format, w, h)?;
        marks.push(gl.glGetError()?);
    }
    gl.glBindTexture(TEXTURE_2D, 0)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, RGBA8, 4, 4)?;
    marks.push(gl.glGetError()?);
    gl.glDeleteTextures(Slice::new(&[mutable]))?;

    // A cube map of one level, a face a colour, and a non-square one refused.
    gl.glActiveTexture(TEXTURE0 + 1)?;
    new_texture(gl, n, TEXTURE_CUBE_MAP, false)?;
    gl.glTexStorage2D(TEXTURE_CUBE_MAP, 1, RGBA8, 4, 4)?;
    let dirs =
        [[1.0, 0.1, 0.2], [-1.0, 0.1, 0.2], [0.1, 1.0, 0.2], [0.1, -1.0, 0.2], [0.1, 0.2, 1.0], [0.1, 0.2, -1.0]];
    for (face, dir) in dirs.iter().enumerate() {
        let c = [40 * face as u8 + 30, 250 - 40 * face as u8, 128, 255];
        fill_level(gl, TEXTURE_CUBE_MAP_POSITIVE_X + face as u32, 0, 4, c)?;
        sampling.cell(gl, n, 8 + face, 1, *dir, [0.0, 1.0])?;
    }
    let square = n.next();
    gl.glBindTexture(TEXTURE_CUBE_MAP, square)?;
    gl.glTexStorage2D(TEXTURE_CUBE_MAP, 1, RGBA8, 4, 2)?;
    marks.push(gl.glGetError()?);

    // A 3D texture of two levels of four slices, a slice a colour; and depth refused for it.
    gl.glActiveTexture(TEXTURE0 + 2)?;
    new_texture(gl, n, TEXTURE_3D, true)?;
    gl.glTexStorage3D(TEXTURE_3D, 2, RGBA8, 4, 4, 4)?;
    for z in 0..4u8 {
        let slice = solid([60 * z + 10, 90, 250 - 60 * z, 255], 16);
        gl.glTexSubImage3DOES(TEXTURE_3D, 0, 0, 0, z as i32, 4, 4, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&slice))?;
        sampling.cell(gl, n, 16 + z as usize, 2, [0.5, 0.5, (f32::from(z) + 0.5) / 4.0], [0.0, 1.0])?;
    }
    let last = solid([70, 140, 210, 255], 8);
    gl.glTexSubImage3DOES(TEXTURE_3D, 1, 0, 0, 0, 2, 2, 2, RGBA, UNSIGNED_BYTE, Blob::borrowed(&last))?;
    sampling.cell(gl, n, 20, 2, [0.5, 0.5, 0.5], [1.0, 1.0])?;
    let volume = n.next();
    gl.glBindTexture(TEXTURE_3D, volume)?;
    gl.glTexStorage3D(TEXTURE_3D, 1, DEPTH_COMPONENT16, 4, 4, 4)?;
    marks.push(gl.glGetError()?);
    gl.glTexStorage3D(TEXTURE_3D, 4, RGBA8, 4, 4, 4)?;
    marks.push(gl.glGetError()?);

    // Half-float from float and half-float data, float, red-green and luminance-alpha images.
    gl.glActiveTexture(TEXTURE0)?;
    new_texture(gl, n, TEXTURE_2D, false)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, RGBA16F, 2, 1)?;
    let floats = f32s(&[2.0, 0.5, 0.25, 4.0]);
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGBA, FLOAT, Blob::borrowed(&floats))?;
    let halves: Vec<u8> =
        [1.0f32, 3.0, 0.5, 2.0].iter().flat_map(|v| half::f16::from_f32(*v).to_bits().to_ne_bytes()).collect();
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 0, 1, 1, RGBA, HALF_FLOAT, Blob::borrowed(&halves))?;
    sampling.cell(gl, n, 24, 0, [0.25, 0.5, 0.0], [0.0, 0.25])?;
    sampling.cell(gl, n, 25, 0, [0.75, 0.5, 0.0], [0.0, 0.25])?;
    new_texture(gl, n, TEXTURE_2D, false)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, R32F, 1, 1)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RED, FLOAT, Blob::borrowed(&f32s(&[0.75])))?;
    sampling.cell(gl, n, 26, 0, [0.5, 0.5, 0.0], [0.0, 1.0])?;
    new_texture(gl, n, TEXTURE_2D, false)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, RG8, 1, 1)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RG, UNSIGNED_BYTE, Blob::borrowed(&[30, 220]))?;
    sampling.cell(gl, n, 27, 0, [0.5, 0.5, 0.0], [0.0, 1.0])?;
    new_texture(gl, n, TEXTURE_2D, false)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, LUMINANCE8_ALPHA8, 1, 1)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, LUMINANCE_ALPHA, UNSIGNED_BYTE, Blob::borrowed(&[200, 100]))?;
    sampling.cell(gl, n, 28, 0, [0.5, 0.5, 0.0], [0.0, 1.0])?;
    // Float data into a normalized image is refused.
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, LUMINANCE_ALPHA, FLOAT, Blob::borrowed(&f32s(&[0.5, 0.5])))?;
    marks.push(gl.glGetError()?);

    // A depth image, written as unsigned shorts and read as its red channel.
    new_texture(gl, n, TEXTURE_2D, false)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, DEPTH_COMPONENT16, 2, 2)?;
    let depths: Vec<u8> = [0x2000u16, 0x8000, 0xC000, 0xFFFF].iter().flat_map(|d| d.to_ne_bytes()).collect();
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 2, 2, DEPTH_COMPONENT, UNSIGNED_SHORT, Blob::borrowed(&depths))?;
    for (k, (x, y)) in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)].iter().enumerate() {
        sampling.cell(gl, n, 29 + k, 3, [*x, *y, 0.0], [0.0, 1.0])?;
    }

    // A level of an immutable texture rendered to, and mipmaps generated in one.
    let target = new_texture(gl, n, TEXTURE_2D, true)?;
    gl.glTexStorage2D(TEXTURE_2D, 2, RGBA8, 8, 8)?;
    fill_level(gl, TEXTURE_2D, 0, 8, [255, 255, 255, 255])?;
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, target, 1)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glViewport(0, 0, 4, 4)?;
    gl.glClearColor(0.2, 0.4, 0.6, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    sampling.cell(gl, n, 33, 0, [0.5, 0.5, 0.0], [1.0, 1.0])?;
    new_texture(gl, n, TEXTURE_2D, true)?;
    gl.glTexStorage2D(TEXTURE_2D, 3, RGBA8, 4, 4)?;
    let checker: Vec<u8> =
        (0..16).flat_map(|i| if (i % 4 + i / 4) % 2 == 0 { [0, 0, 0, 255] } else { [200, 100, 50, 255] }).collect();
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, RGBA, UNSIGNED_BYTE, Blob::borrowed(&checker))?;
    gl.glGenerateMipmap(TEXTURE_2D)?;
    sampling.cell(gl, n, 34, 0, [0.5, 0.5, 0.0], [2.0, 1.0])?;
    // The last level caps what TEXTURE_MAX_LEVEL asks beyond it.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, 7)?;
    sampling.cell(gl, n, 35, 0, [0.5, 0.5, 0.0], [5.0, 1.0])?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}
