//! Sampler objects and ES 3.0's level parameters: a sampler bound to a unit overriding the
//! filters, wraps and level-of-detail clamps of the texture read through it (one texture read
//! through two units with and without one in a draw), unbinding and deleting a bound sampler;
//! the texture's own `GL_TEXTURE_BASE_LEVEL`, `GL_TEXTURE_MAX_LEVEL`, `GL_TEXTURE_MIN_LOD` and
//! `GL_TEXTURE_MAX_LOD`, an immutable texture's base level clamped to its levels; the
//! parameters' queries, `GL_SAMPLER_BINDING`, `glIsSampler`; and the errors, as colours and
//! marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const TEXTURE_MAX_LEVEL: u32 = 0x813D;
const TEXTURE_BASE_LEVEL: u32 = 0x813C;
const TEXTURE_MIN_LOD: u32 = 0x813A;
const TEXTURE_MAX_LOD: u32 = 0x813B;
const TEXTURE_COMPARE_MODE: u32 = 0x884C;
const TEXTURE_COMPARE_FUNC: u32 = 0x884D;
const COMPARE_REF_TO_TEXTURE: i32 = 0x884E;
const TEXTURE_MAX_ANISOTROPY: u32 = 0x84FE;
const SAMPLER_BINDING: u32 = 0x8919;
const RGBA8: u32 = 0x8058;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform sampler2D a; uniform sampler2D b;
    uniform int which; uniform vec2 uv; uniform float lod;
    out vec4 o;
    void main() {
        if (which == 0) o = textureLod(a, uv, lod);
        else if (which == 1) o = textureLod(b, uv, lod);
        else o = 0.5 * textureLod(a, uv, lod) + 0.5 * textureLod(b, uv, lod);
    }";

/// The level colours of the 8×8 texture's chain.
const LEVELS: [[u8; 4]; 4] = [[220, 30, 30, 255], [30, 220, 30, 255], [30, 30, 220, 255], [200, 200, 40, 255]];

/// The uniforms' locations: which, uv, lod.
struct Cells([i32; 3]);

impl Cells {
    /// Draws cell `k` (8 across, 8×8 pixels each, from the bottom left) reading unit `which`
    /// (2: both, averaged) at `uv` and level of detail `lod`.
    fn draw(&self, gl: Gl<'_>, n: &mut Names, k: usize, which: i32, uv: [f32; 2], lod: f32) -> R {
        let [w, c, l] = self.0;
        gl.glUniform1i(w, which)?;
        gl.glUniform2f(c, uv[0], uv[1])?;
        gl.glUniform1f(l, lod)?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    }
}

/// The sampler program.
pub fn samplers(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let loc = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let cells = Cells([loc(gl, "which")?, loc(gl, "uv")?, loc(gl, "lod")?]);
    let (a, b) = (loc(gl, "a")?, loc(gl, "b")?);
    gl.glUniform1i(a, 0)?;
    gl.glUniform1i(b, 1)?;
    let mut marks = Vec::new();
    let centre = [0.5, 0.5];

    // An 8×8 texture with its whole chain, a level a colour, filtered without mipmaps; the
    // same texture on units 0 and 1.
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    for unit in [1, 0] {
        gl.glActiveTexture(TEXTURE0 + unit)?;
        gl.glBindTexture(TEXTURE_2D, t)?;
    }
    for (level, c) in LEVELS.iter().enumerate() {
        let size = 8 >> level;
        let data = c.repeat((size * size) as usize);
        gl.glTexImage2D(
            TEXTURE_2D,
            level as i32,
            RGBA as i32,
            size,
            size,
            0,
            RGBA,
            UNSIGNED_BYTE,
            Some(Blob::borrowed(&data)),
        )?;
    }
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    cells.draw(gl, n, 0, 0, centre, 2.0)?;

    // A sampler on unit 0 with a mipmap filter: levels by the level of detail, clamped by its
    // least and greatest levels of detail.
    let s = n.next();
    gl.glGenSamplers(Slice::new(&[s]))?;
    marks.push(u32::from(gl.glIsSampler(s)?));
    marks.push(gl.glGetSamplerParameteriv(s, TEXTURE_MIN_FILTER)?.first().copied().unwrap_or(-1) as u32);
    gl.glBindSampler(0, s)?;
    marks.push(u32::from(gl.glGetIntegerv(SAMPLER_BINDING)?.first().is_some_and(|v| *v != 0)));
    gl.glSamplerParameteri(s, TEXTURE_MIN_FILTER, NEAREST_MIPMAP_NEAREST)?;
    gl.glSamplerParameterf(s, TEXTURE_MAG_FILTER, NEAREST as f32)?;
    cells.draw(gl, n, 1, 0, centre, 2.0)?;
    cells.draw(gl, n, 2, 0, centre, 1.0)?;
    gl.glSamplerParameterf(s, TEXTURE_MIN_LOD, 2.0)?;
    cells.draw(gl, n, 3, 0, centre, 1.0)?;
    gl.glSamplerParameterfv(s, TEXTURE_MIN_LOD, Slice::new(&[-4.0]))?;
    gl.glSamplerParameteriv(s, TEXTURE_MAX_LOD, Slice::new(&[1]))?;
    cells.draw(gl, n, 4, 0, centre, 3.0)?;
    marks.push(gl.glGetSamplerParameteriv(s, TEXTURE_MAX_LOD)?.first().copied().unwrap_or(-1) as u32);
    marks.push(gl.glGetSamplerParameterfv(s, TEXTURE_MIN_LOD)?.first().map_or(0, |v| (-v) as u32));
    gl.glSamplerParameterf(s, TEXTURE_MAX_LOD, 1000.0)?;
    // Unit 1 reads the same texture by its own state; both in one draw.
    cells.draw(gl, n, 5, 1, centre, 2.0)?;
    cells.draw(gl, n, 6, 2, centre, 2.0)?;

    // Wraps: a 2×1 texture (red, green) repeating, read past its right edge through unit 1,
    // then through a sampler clamping to the edge.
    gl.glActiveTexture(TEXTURE0 + 1)?;
    let u = n.next();
    gl.glGenTextures(Slice::new(&[u]))?;
    gl.glBindTexture(TEXTURE_2D, u)?;
    let pair = [255, 0, 0, 255, 0, 255, 0, 255];
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 2, 1, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&pair)))?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    cells.draw(gl, n, 7, 1, [1.3, 0.5], 0.0)?;
    let clamp = n.next();
    gl.glGenSamplers(Slice::new(&[clamp]))?;
    gl.glSamplerParameteri(clamp, TEXTURE_WRAP_S, CLAMP_TO_EDGE)?;
    gl.glSamplerParameteri(clamp, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glSamplerParameteri(clamp, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glBindSampler(1, clamp)?;
    cells.draw(gl, n, 8, 1, [1.3, 0.5], 0.0)?;

    // Unbinding the sampler, and deleting a bound one, give unit 0 the texture's state back.
    gl.glBindSampler(0, 0)?;
    gl.glActiveTexture(TEXTURE0)?;
    marks.push(gl.glGetIntegerv(SAMPLER_BINDING)?.first().copied().unwrap_or(-1) as u32);
    cells.draw(gl, n, 9, 0, centre, 2.0)?;
    gl.glBindSampler(0, s)?;
    cells.draw(gl, n, 10, 0, centre, 2.0)?;
    gl.glDeleteSamplers(Slice::new(&[s]))?;
    marks.push(gl.glGetIntegerv(SAMPLER_BINDING)?.first().copied().unwrap_or(-1) as u32);
    marks.push(u32::from(gl.glIsSampler(s)?));
    marks.push(u32::from(gl.glIsSampler(t)?));
    cells.draw(gl, n, 11, 0, centre, 2.0)?;

    // The texture's own levels: a base level of 1, then a max level of 2, then its least and
    // greatest levels of detail.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST_MIPMAP_NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_BASE_LEVEL, 1)?;
    marks.push(gl.glGetTexParameteriv(TEXTURE_2D, TEXTURE_BASE_LEVEL)?.first().copied().unwrap_or(-1) as u32);
    cells.draw(gl, n, 12, 0, centre, 0.0)?;
    cells.draw(gl, n, 13, 0, centre, 1.0)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, 2)?;
    cells.draw(gl, n, 14, 0, centre, 3.0)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_BASE_LEVEL, 0)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, 1000)?;
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MIN_LOD, 1.0)?;
    cells.draw(gl, n, 15, 0, centre, 0.25)?;
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MIN_LOD, -1000.0)?;
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_LOD, 2.0)?;
    cells.draw(gl, n, 16, 0, centre, 3.0)?;
    marks.push(gl.glGetTexParameteriv(TEXTURE_2D, TEXTURE_MAX_LOD)?.first().copied().unwrap_or(-1) as u32);
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_LOD, 1000.0)?;
    // A base level past the last is incomplete: unit 0 reads black.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_BASE_LEVEL, 4)?;
    cells.draw(gl, n, 17, 0, centre, 0.0)?;

    // An immutable texture's base level is clamped to its levels.
    let im = n.next();
    gl.glGenTextures(Slice::new(&[im]))?;
    gl.glBindTexture(TEXTURE_2D, im)?;
    gl.glTexStorage2D(TEXTURE_2D, 3, RGBA8, 8, 8)?;
    for (level, c) in LEVELS.iter().take(3).enumerate() {
        let size = 8 >> level;
        let data = c.repeat((size * size) as usize);
        gl.glTexSubImage2D(TEXTURE_2D, level as i32, 0, 0, size, size, RGBA, UNSIGNED_BYTE, Blob::borrowed(&data))?;
    }
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST_MIPMAP_NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_BASE_LEVEL, 5)?;
    cells.draw(gl, n, 18, 0, centre, 0.0)?;

    // Comparison state, stored and read back.
    let c = n.next();
    gl.glGenSamplers(Slice::new(&[c]))?;
    marks.push(gl.glGetSamplerParameteriv(c, TEXTURE_COMPARE_FUNC)?.first().copied().unwrap_or(-1) as u32);
    gl.glSamplerParameteri(c, TEXTURE_COMPARE_MODE, COMPARE_REF_TO_TEXTURE)?;
    marks.push(gl.glGetSamplerParameteriv(c, TEXTURE_COMPARE_MODE)?.first().copied().unwrap_or(-1) as u32);

    // The errors.
    let unknown = 4321;
    let calls: [&dyn Fn(Gl<'_>) -> R; 12] = [
        &|gl| gl.glBindSampler(1000, c),
        &|gl| gl.glBindSampler(0, unknown),
        &|gl| gl.glSamplerParameteri(unknown, TEXTURE_MIN_FILTER, NEAREST),
        &|gl| gl.glSamplerParameteri(0, TEXTURE_MIN_FILTER, NEAREST),
        &|gl| gl.glSamplerParameteri(c, TEXTURE_BASE_LEVEL, 1),
        &|gl| gl.glSamplerParameteri(c, TEXTURE_MIN_FILTER, 0x1234),
        &|gl| gl.glSamplerParameterf(c, TEXTURE_MAX_ANISOTROPY, 0.5),
        &|gl| gl.glSamplerParameteri(c, TEXTURE_COMPARE_FUNC, 0x1234),
        &|gl| gl.glGetSamplerParameteriv(unknown, TEXTURE_MIN_FILTER).map(drop),
        &|gl| gl.glGetSamplerParameteriv(c, TEXTURE_MAX_LEVEL).map(drop),
        &|gl| gl.glTexParameteri(TEXTURE_2D, TEXTURE_BASE_LEVEL, -1),
        &|gl| gl.glTexParameteri(TEXTURE_2D, TEXTURE_COMPARE_MODE, 0x1234),
    ];
    for call in calls {
        call(gl)?;
        marks.push(gl.glGetError()?);
    }
    mark_all(gl, &marks)
}
