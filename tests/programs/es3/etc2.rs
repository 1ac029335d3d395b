//! ES 3.0's ten ETC2 and EAC formats: 8×8 images of pseudo-random blocks (every mode of ETC2
//! occurs among them) drawn texel for texel, signed EAC mapped into [0, 1]; an image of each
//! kind made by `glTexStorage2D` and written a block at a time, a level of a mip chain, a
//! filtered EAC image, a layer of a compressed 2D array; the errors (misaligned and foreign
//! sub-images, wrong sizes, 3D images, uncompressed data), and the formats listed, as marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const NUM_COMPRESSED_TEXTURE_FORMATS: u32 = 0x86A2;
const COMPRESSED_TEXTURE_FORMATS: u32 = 0x86A3;
const TEXTURE_3D: u32 = 0x806F;

/// `GL_COMPRESSED_R11_EAC` … `GL_COMPRESSED_SRGB8_ALPHA8_ETC2_EAC`, with their bytes per block
/// and whether their values are signed.
const FORMATS: [(u32, usize, bool); 10] = [
    (0x9270, 8, false),
    (0x9271, 8, true),
    (0x9272, 16, false),
    (0x9273, 16, true),
    (0x9274, 8, false),
    (0x9275, 8, false),
    (0x9276, 8, false),
    (0x9277, 8, false),
    (0x9278, 16, false),
    (0x9279, 16, false),
];

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform highp sampler2D s; uniform highp sampler2DArray a;
    uniform vec4 area; uniform float lod, layer, scale; uniform int array;
    out vec4 o;
    void main() {
        vec2 uv = (gl_FragCoord.xy - area.xy) / area.zw;
        vec4 c = array == 1 ? texture(a, vec3(uv, layer)) : textureLod(s, uv, lod);
        o = scale == 1.0 ? c : c * scale + (1.0 - scale);
    }";

/// `n` bytes from a linear congruential sequence seeded by `seed`.
fn blocks(seed: u32, n: usize) -> Vec<u8> {
    let mut x = seed.wrapping_mul(2_654_435_761).wrapping_add(12345);
    (0..n)
        .map(|_| {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
            (x >> 16) as u8
        })
        .collect()
}

/// The uniforms' locations: area, lod, layer, scale, array.
struct Draw([i32; 5]);

impl Draw {
    /// Draws the bound texture (or 2D array, at `layer`) over `w`×`h` pixels at (`x`, `y`),
    /// reading level `lod`; signed values are mapped into [0, 1].
    #[allow(clippy::too_many_arguments)]
    fn at(&self, gl: Gl<'_>, n: &mut Names, [x, y, w, h]: [i32; 4], lod: f32, layer: Option<f32>, signed: bool) -> R {
        let [area, l, lay, scale, array] = self.0;
        gl.glUniform4f(area, x as f32, y as f32, w as f32, h as f32)?;
        gl.glUniform1f(l, lod)?;
        gl.glUniform1f(lay, layer.unwrap_or(0.0))?;
        gl.glUniform1f(scale, if signed { 0.5 } else { 1.0 })?;
        gl.glUniform1i(array, i32::from(layer.is_some()))?;
        gl.glViewport(x, y, w, h)?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)
    }
}

/// A new texture bound to `target` on unit 0 (2D) or 1 (arrays), filtered by `filter`.
fn new_texture(gl: Gl<'_>, n: &mut Names, target: u32, filter: i32) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glActiveTexture(if target == TEXTURE_2D { TEXTURE0 } else { TEXTURE0 + 1 })?;
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(target, t)?;
    gl.glTexParameteri(target, TEXTURE_MIN_FILTER, filter)?;
    gl.glTexParameteri(target, TEXTURE_MAG_FILTER, if filter == LINEAR { LINEAR } else { NEAREST })?;
    Ok(t)
}

/// The ETC2 and EAC program.
pub fn etc2(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let mut locs = [0; 5];
    for (l, name) in locs.iter_mut().zip(["area", "lod", "layer", "scale", "array"]) {
        *l = gl.glGetUniformLocation(p, Text::borrowed(name))?;
    }
    let draw = Draw(locs);
    let array_unit = gl.glGetUniformLocation(p, Text::borrowed("a"))?;
    gl.glUniform1i(array_unit, 1)?;
    let mut marks = Vec::new();

    // Every format whole, texel for texel: 8 across the bottom two rows of 8×8 tiles.
    for (i, &(format, bytes, signed)) in FORMATS.iter().enumerate() {
        new_texture(gl, n, TEXTURE_2D, NEAREST)?;
        let data = blocks(i as u32, 4 * bytes);
        gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 8, 8, 0, Blob::borrowed(&data))?;
        marks.push(gl.glGetError()?);
        let (x, y) = (i as i32 % 8 * 8, i as i32 / 8 * 8);
        draw.at(gl, n, [x, y, 8, 8], 0.0, None, signed)?;
    }

    // Immutable storage written a block at a time, for an EAC and a colour format.
    for (k, &(format, bytes, signed)) in [FORMATS[3], FORMATS[8]].iter().enumerate() {
        new_texture(gl, n, TEXTURE_2D, NEAREST)?;
        gl.glTexStorage2D(TEXTURE_2D, 1, format, 8, 8)?;
        for (b, (x, y)) in [(0, 0), (4, 0), (0, 4), (4, 4)].into_iter().enumerate() {
            let data = blocks(20 + b as u32, bytes);
            gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, x, y, 4, 4, format, Blob::borrowed(&data))?;
        }
        marks.push(gl.glGetError()?);
        draw.at(gl, n, [16 + 8 * k as i32, 8, 8, 8], 0.0, None, signed)?;
    }

    // A mip chain of 8×8, 4×4 and 2×2 (one block each below the first), level 1 drawn; a
    // 12×8 image not a whole number of blocks wide at its last level.
    let (format, bytes, _) = FORMATS[4];
    new_texture(gl, n, TEXTURE_2D, NEAREST_MIPMAP_NEAREST)?;
    for (level, size) in [8usize, 4, 2, 1].into_iter().enumerate() {
        let data = blocks(30 + level as u32, size.div_ceil(4) * size.div_ceil(4) * bytes);
        gl.glCompressedTexImage2D(
            TEXTURE_2D,
            level as i32,
            format,
            size as i32,
            size as i32,
            0,
            Blob::borrowed(&data),
        )?;
    }
    marks.push(gl.glGetError()?);
    draw.at(gl, n, [32, 8, 8, 8], 1.0, None, false)?;
    draw.at(gl, n, [40, 8, 8, 8], 2.0, None, false)?;

    // EAC and ETC2 filtered: an 8×8 image over 16×16 pixels.
    for (k, &(format, bytes, signed)) in [FORMATS[2], FORMATS[9]].iter().enumerate() {
        new_texture(gl, n, TEXTURE_2D, LINEAR)?;
        let data = blocks(40 + k as u32, 4 * bytes);
        gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 8, 8, 0, Blob::borrowed(&data))?;
        draw.at(gl, n, [16 * k as i32, 16, 16, 16], 0.0, None, signed)?;
    }

    // A compressed 2D array of three 4×4 layers, and a layer replaced in part.
    let (format, bytes, _) = FORMATS[6];
    new_texture(gl, n, TEXTURE_2D_ARRAY, NEAREST)?;
    let data = blocks(50, 3 * bytes);
    gl.glCompressedTexImage3DOES(TEXTURE_2D_ARRAY, 0, format, 4, 4, 3, 0, Blob::borrowed(&data))?;
    marks.push(gl.glGetError()?);
    draw.at(gl, n, [32, 16, 8, 8], 0.0, Some(1.0), false)?;
    let data = blocks(51, bytes);
    gl.glCompressedTexSubImage3DOES(TEXTURE_2D_ARRAY, 0, 0, 0, 2, 4, 4, 1, format, Blob::borrowed(&data))?;
    marks.push(gl.glGetError()?);
    draw.at(gl, n, [40, 16, 8, 8], 0.0, Some(2.0), false)?;
    draw.at(gl, n, [48, 16, 8, 8], 0.0, Some(0.0), false)?;

    // The errors, on a fresh 8×8 RGB8_ETC2 image.
    let (format, bytes, _) = FORMATS[4];
    new_texture(gl, n, TEXTURE_2D, NEAREST)?;
    let data = blocks(60, 4 * bytes);
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 8, 8, 0, Blob::borrowed(&data[..3 * bytes]))?;
    marks.push(gl.glGetError()?);
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 8, 8, 0, Blob::borrowed(&data))?;
    let one = &data[..bytes];
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 2, 0, 4, 4, format, Blob::borrowed(one))?;
    marks.push(gl.glGetError()?);
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, FORMATS[0].0, Blob::borrowed(one))?;
    marks.push(gl.glGetError()?);
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&[1, 2, 3, 4]))?;
    marks.push(gl.glGetError()?);
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 8, 8, 1, Blob::borrowed(&data))?;
    marks.push(gl.glGetError()?);
    let t3 = n.next();
    gl.glGenTextures(Slice::new(&[t3]))?;
    gl.glBindTexture(TEXTURE_3D, t3)?;
    gl.glCompressedTexImage3DOES(TEXTURE_3D, 0, format, 4, 4, 1, 0, Blob::borrowed(one))?;
    marks.push(gl.glGetError()?);
    gl.glTexStorage3D(TEXTURE_3D, 1, format, 4, 4, 1)?;
    marks.push(gl.glGetError()?);
    gl.glTexImage2D(TEXTURE_2D, 0, format as i32, 4, 4, 0, RGB, UNSIGNED_BYTE, None)?;
    marks.push(gl.glGetError()?);

    // Every ETC2 and EAC format is listed.
    let listed = gl.glGetIntegerv(COMPRESSED_TEXTURE_FORMATS)?;
    marks.push(FORMATS.iter().filter(|f| listed.contains(&(f.0 as i32))).count() as u32);
    let count = gl.glGetIntegerv(NUM_COMPRESSED_TEXTURE_FORMATS)?.first().copied().unwrap_or(0);
    marks.push(u32::from(count as usize == listed.len()));
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)
}
