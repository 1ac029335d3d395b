//! 2D array textures: layers specified whole (`glTexImage3D`) and in part
//! (`glTexSubImage3D`), immutable (`glTexStorage3D`) with levels, mipmaps generated per layer,
//! sampled through `sampler2DArray` (`texture` with the layer rounded and clamped, `textureLod`,
//! `texelFetch`, `textureSize`), a layer rendered to (`glFramebufferTextureLayer`) and copied
//! into (`glCopyTexSubImage3D`); the queries and the errors, as colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const TEXTURE_BINDING_2D_ARRAY: u32 = 0x8C1D;
const MAX_ARRAY_TEXTURE_LAYERS: u32 = 0x88FF;
const RGBA8: u32 = 0x8058;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform highp sampler2DArray s;
    uniform int mode; uniform vec3 coord; uniform float lod;
    out vec4 o;
    void main() {
        if (mode == 0) o = texture(s, coord);
        else if (mode == 1) o = textureLod(s, coord, lod);
        else if (mode == 2) o = texelFetch(s, ivec3(coord), int(lod));
        else o = vec4(vec3(textureSize(s, int(lod))) / 16.0, 1.0);
    }";

/// The uniforms' locations: mode, coord, lod.
struct Cells([i32; 3]);

impl Cells {
    /// Draws cell `k` (8 across, 8×8 pixels each, from the bottom left) reading in `mode` at
    /// `coord` (s, t, layer) and level `lod`.
    fn draw(&self, gl: Gl<'_>, n: &mut Names, k: usize, mode: i32, coord: [f32; 3], lod: f32) -> R {
        let [m, c, l] = self.0;
        gl.glUniform1i(m, mode)?;
        gl.glUniform3f(c, coord[0], coord[1], coord[2])?;
        gl.glUniform1f(l, lod)?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    }
}

/// `layers` layers of `size`×`size` texels, layer `z`'s texel (x, y) a colour of all three.
fn layered(size: usize, layers: usize) -> Vec<u8> {
    let mut v = Vec::new();
    for z in 0..layers {
        for y in 0..size {
            for x in 0..size {
                v.extend([(60 * z + 20) as u8, (40 * x + 30) as u8, (40 * y + 30) as u8, 255]);
            }
        }
    }
    v
}

/// A new 2D array texture bound on unit 0, filtered nearest (mipmapped where `mipmaps`).
fn new_array(gl: Gl<'_>, n: &mut Names, mipmaps: bool) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D_ARRAY, t)?;
    gl.glTexParameteri(TEXTURE_2D_ARRAY, TEXTURE_MIN_FILTER, if mipmaps { NEAREST_MIPMAP_NEAREST } else { NEAREST })?;
    gl.glTexParameteri(TEXTURE_2D_ARRAY, TEXTURE_MAG_FILTER, NEAREST)?;
    Ok(t)
}

/// The array program.
pub fn texture_arrays(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let loc = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let cells = Cells([loc(gl, "mode")?, loc(gl, "coord")?, loc(gl, "lod")?]);
    let mut marks = Vec::new();
    marks.push(gl.glGetActiveUniform(p, 0)?.map_or(0, |u| u.ty));
    gl.glActiveTexture(TEXTURE0)?;

    // Three 4×4 layers given whole, a rectangle of layer 1 replaced; each layer sampled, the
    // layer coordinate rounded and clamped.
    let a = new_array(gl, n, false)?;
    marks.push(u32::from(gl.glGetIntegerv(TEXTURE_BINDING_2D_ARRAY)?.first().is_some_and(|v| *v != 0)));
    let data = layered(4, 3);
    gl.glTexImage3DOES(TEXTURE_2D_ARRAY, 0, RGBA, 4, 4, 3, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&data)))?;
    let patch = [250u8, 250, 0, 255].repeat(4);
    gl.glTexSubImage3DOES(TEXTURE_2D_ARRAY, 0, 2, 2, 1, 2, 2, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&patch))?;
    for (k, layer) in [0.6, 1.0, 2.0, 1.7, 5.0, -1.0].iter().enumerate() {
        cells.draw(gl, n, k, 0, [0.1, 0.1, *layer], 0.0)?;
    }
    cells.draw(gl, n, 6, 0, [0.9, 0.9, 1.0], 0.0)?;
    cells.draw(gl, n, 7, 2, [3.0, 1.0, 2.0], 0.0)?;
    cells.draw(gl, n, 8, 3, [0.0, 0.0, 0.0], 0.0)?;
    cells.draw(gl, n, 9, 2, [1.0, 2.0, 0.0], 0.0)?;

    // A layer rendered to, then the window's pixels copied into another.
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTextureLayer(FRAMEBUFFER, COLOR_ATTACHMENT0, a, 0, 2)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glViewport(0, 0, 4, 4)?;
    gl.glClearColor(0.2, 0.4, 0.8, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    cells.draw(gl, n, 10, 0, [0.5, 0.5, 2.0], 0.0)?;
    // Window pixels (0..4, 0..4) are cell 0's: layer 1's first texel (layer 0.6 rounded).
    gl.glCopyTexSubImage3DOES(TEXTURE_2D_ARRAY, 0, 0, 0, 1, 0, 0, 2, 2)?;
    cells.draw(gl, n, 11, 0, [0.1, 0.1, 1.0], 0.0)?;

    // Mipmaps generated for each of two layers of a checker.
    new_array(gl, n, true)?;
    let mut checker = Vec::new();
    for z in 0..2u8 {
        for i in 0..16 {
            checker.extend(if (i % 4 + i / 4) % 2 == 0 { [0, 0, 0, 255] } else { [200, 100 * z, 50, 255] });
        }
    }
    gl.glTexImage3DOES(TEXTURE_2D_ARRAY, 0, RGBA, 4, 4, 2, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&checker)))?;
    gl.glGenerateMipmap(TEXTURE_2D_ARRAY)?;
    cells.draw(gl, n, 12, 1, [0.5, 0.5, 0.0], 2.0)?;
    cells.draw(gl, n, 13, 1, [0.5, 0.5, 1.0], 2.0)?;

    // Immutable storage of two levels of three layers, each level and layer written.
    new_array(gl, n, true)?;
    gl.glTexStorage3D(TEXTURE_2D_ARRAY, 2, RGBA8, 8, 8, 3)?;
    for level in 0..2 {
        let size = 8 >> level;
        for z in 0..3 {
            let c = [(80 * level + 40) as u8, (70 * z + 20) as u8, 160, 255].repeat((size * size) as usize);
            gl.glTexSubImage3DOES(
                TEXTURE_2D_ARRAY,
                level,
                0,
                0,
                z,
                size,
                size,
                1,
                RGBA,
                UNSIGNED_BYTE,
                Blob::borrowed(&c),
            )?;
        }
    }
    for (k, (layer, lod)) in [(0.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 3.0)].iter().enumerate() {
        cells.draw(gl, n, 14 + k, 1, [0.5, 0.5, *layer], *lod)?;
    }
    cells.draw(gl, n, 18, 3, [0.0, 0.0, 0.0], 1.0)?;

    // More layers than texels across: the chain counts the width and height only, so two
    // levels make it complete.
    new_array(gl, n, true)?;
    for (level, size) in [(0, 2), (1, 1)] {
        let c = [30, 60 + 100 * level as u8, 200, 255].repeat(size * size * 8);
        let s = size as i32;
        gl.glTexImage3DOES(TEXTURE_2D_ARRAY, level, RGBA, s, s, 8, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&c)))?;
    }
    cells.draw(gl, n, 19, 1, [0.5, 0.5, 7.0], 1.0)?;

    // The queries and errors.
    marks.push(u32::from(gl.glGetIntegerv(MAX_ARRAY_TEXTURE_LAYERS)?.first().is_some_and(|v| *v >= 256)));
    // ES 3.0's other limits, each at least its minimum (table 6.31 and after): uniform
    // components, varying, output and input components, the element counts, texel offsets.
    let at_least = [(0x8B4A, 1024), (0x8B49, 896), (0x8B4B, 60), (0x9122, 64), (0x9125, 60), (0x80E8, 1), (0x80E9, 1)];
    for (pname, min) in at_least {
        marks.push(u32::from(gl.glGetIntegerv(pname)?.first().is_some_and(|v| *v >= min)));
    }
    marks.push(u32::from(gl.glGetIntegerv(0x8904)?.first().is_some_and(|v| *v <= -8)));
    marks.push(u32::from(gl.glGetIntegerv(0x8905)?.first().is_some_and(|v| *v >= 7)));
    marks.push(gl.glGetError()?);
    let flat = n.next();
    gl.glBindTexture(TEXTURE_2D, flat)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 1, 1, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glBindTexture(TEXTURE_2D_ARRAY, a)?;
    let calls: [&dyn Fn(Gl<'_>) -> R; 8] = [
        &|gl| gl.glTexImage3DOES(TEXTURE_2D_ARRAY, 0, RGBA, 4, 4, 100_000, 0, RGBA, UNSIGNED_BYTE, None),
        &|gl| {
            gl.glTexSubImage3DOES(TEXTURE_2D_ARRAY, 0, 0, 0, 2, 1, 1, 2, RGBA, UNSIGNED_BYTE, Blob::borrowed(&[0; 8]))
        },
        &|gl| gl.glTexImage2D(TEXTURE_2D_ARRAY, 0, RGBA as i32, 1, 1, 0, RGBA, UNSIGNED_BYTE, None),
        &|gl| gl.glFramebufferTextureLayer(FRAMEBUFFER, COLOR_ATTACHMENT0, flat, 0, 0),
        &|gl| gl.glFramebufferTextureLayer(FRAMEBUFFER, COLOR_ATTACHMENT0, a, 0, -1),
        &|gl| gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, a, 0),
        &|gl| gl.glBindTexture(TEXTURE_2D_ARRAY, flat),
        &|gl| gl.glTexStorage3D(TEXTURE_2D_ARRAY, 4, RGBA8, 4, 4, 16),
    ];
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    for call in calls {
        call(gl)?;
        marks.push(gl.glGetError()?);
    }
    // Framebuffer 0 takes no layer.
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glFramebufferTextureLayer(FRAMEBUFFER, COLOR_ATTACHMENT0, a, 0, 0)?;
    marks.push(gl.glGetError()?);
    // The 3D unpack state: set, answered, a negative value refused; back to 0.
    for (pname, v) in [(0x806E, 4), (0x806D, 2), (0x806E, -1)] {
        gl.glPixelStorei(pname, v)?;
        marks.push(gl.glGetError()?);
        marks.push(gl.glGetIntegerv(pname)?.first().copied().unwrap_or(-1) as u32);
    }
    gl.glPixelStorei(0x806E, 0)?;
    gl.glPixelStorei(0x806D, 0)?;
    mark_all(gl, &marks)
}
