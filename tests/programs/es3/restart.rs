//! ES 3.0's index and vertex order rules: `GL_PRIMITIVE_RESTART_FIXED_INDEX` (strips, lists,
//! fans, line strips and loops and points restarted at each index type's largest value, from
//! element buffers and client indices; the same largest value drawn as a vertex with restart
//! disabled; vertex ranges unaffected) and GL's provoking vertex, the last of each primitive,
//! for `flat` varyings (float and integer) in every primitive mode, drawn from vertex ranges
//! and from indices, with and without restarts.

use strata_protocol::Blob;

use super::super::multi_draw::mark_all;
use super::super::*;

const PRIMITIVE_RESTART_FIXED_INDEX: u32 = 0x8D69;

/// Smooth colours per vertex.
const VS_SMOOTH: &str = "#version 300 es
    layout(location = 0) in vec2 pos; layout(location = 1) in vec4 color; out vec4 c;
    void main() { c = color; gl_PointSize = 4.0; gl_Position = vec4(pos, 0.0, 1.0); }";
const FS_SMOOTH: &str = "#version 300 es
    precision mediump float; in vec4 c; out vec4 o; void main() { o = c; }";
/// One colour per primitive, and the provoking vertex's number.
const VS_FLAT: &str = "#version 300 es
    layout(location = 0) in vec2 pos; layout(location = 1) in vec4 color;
    flat out vec4 c; flat out int k;
    void main() { c = color; k = gl_VertexID; gl_PointSize = 4.0; gl_Position = vec4(pos, 0.0, 1.0); }";
const FS_FLAT: &str = "#version 300 es
    precision mediump float; flat in vec4 c; flat in int k; out vec4 o;
    void main() { o = vec4(c.rg, float(k % 4) * 0.25, 1.0); }";

/// The corner of grid cell (`cx`, `cy`) of four columns and three rows, below the marks.
fn cell(cx: u32, cy: u32) -> (f32, f32) {
    (-0.95 + cx as f32 * 0.48, -0.95 + cy as f32 * 0.58)
}

/// A colour of its own for vertex `k`.
fn color(k: usize) -> [f32; 4] {
    let f = |m: f32| (k as f32 * m).fract();
    [f(0.37), f(0.61), 0.3 + 0.7 * f(0.13), 1.0]
}

/// 256 vertices (positions then colours, in two buffers at attributes 0 and 1), those `v`
/// lists first and the rest at the origin but for `last`, vertex 255.
fn vertices(gl: Gl<'_>, n: &mut Names, v: &[[f32; 2]], last: [f32; 2]) -> R {
    let mut pos: Vec<f32> = v.iter().flatten().copied().collect();
    pos.resize(255 * 2, 0.0);
    pos.extend(last);
    buffer(gl, n, ARRAY_BUFFER, &f32s(&pos))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    let colors: Vec<f32> = (0..256).flat_map(color).collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&colors))?;
    attrib(gl, 1, 4, FLOAT, false, 0, 0)
}

/// A strip's four corners of a `w`×`h` quad at (`x`, `y`).
fn quad(x: f32, y: f32, w: f32, h: f32) -> [[f32; 2]; 4] {
    [[x, y], [x + w, y], [x, y + h], [x + w, y + h]]
}

/// Index bytes of `ty` (`UNSIGNED_BYTE`, `_SHORT` or `_INT`).
fn index_bytes(ty: u32, v: &[u32]) -> Vec<u8> {
    match ty {
        UNSIGNED_BYTE => v.iter().map(|&i| i as u8).collect(),
        UNSIGNED_SHORT => v.iter().flat_map(|&i| (i as u16).to_ne_bytes()).collect(),
        _ => v.iter().flat_map(|&i| i.to_ne_bytes()).collect(),
    }
}

/// Draws `v` as `ty` indices from a fresh element buffer.
fn draw_indexed(gl: Gl<'_>, n: &mut Names, mode: u32, ty: u32, v: &[u32]) -> R {
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &index_bytes(ty, v))?;
    gl.glDrawElements(mode, v.len() as i32, ty, 0)
}

/// Restarted primitives of every mode and index type.
pub fn primitive_restart(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_SMOOTH, FS_SMOOTH, &[])?;
    let mut v: Vec<[f32; 2]> = Vec::new();
    let two_quads = |v: &mut Vec<[f32; 2]>, cx, cy| {
        let (x, y) = cell(cx, cy);
        v.extend(quad(x, y, 0.18, 0.45));
        v.extend(quad(x + 0.24, y + 0.1, 0.18, 0.35));
    };
    two_quads(&mut v, 0, 0); // 0..8
    two_quads(&mut v, 1, 0); // 8..16
    let (x, y) = cell(2, 0);
    v.extend([[x, y], [x + 0.2, y], [x, y + 0.4], [x + 0.3, y + 0.45]]); // 16..20
    v.extend([[x + 0.25, y], [x + 0.45, y], [x + 0.45, y + 0.4]]); // 20..23
    let (x, y) = cell(3, 0);
    for (dx, dy) in [(0.1f32, 0.1f32), (0.32, 0.3)] {
        let (cx, cy) = (x + dx, y + dy);
        v.extend([[cx, cy], [cx + 0.1, cy], [cx + 0.07, cy + 0.07], [cx, cy + 0.1]]);
        // 23..31
    }
    let (x, y) = cell(0, 1);
    v.extend([[x, y], [x + 0.2, y + 0.4], [x + 0.2, y]]); // 31..34
    v.extend([[x + 0.25, y], [x + 0.45, y + 0.4], [x + 0.45, y]]); // 34..37
    let (x, y) = cell(1, 1);
    v.extend([[x, y], [x + 0.2, y + 0.4], [x + 0.2, y]]); // 37..40
    v.extend([[x + 0.25, y], [x + 0.45, y + 0.4], [x + 0.45, y]]); // 40..43
    let (x, y) = cell(2, 1);
    v.extend([[x + 0.05, y + 0.1], [x + 0.2, y + 0.2], [x + 0.35, y + 0.3]]); // 43..46
    two_quads(&mut v, 3, 1); // 46..54
    two_quads(&mut v, 0, 2); // 54..62
    let (x, y) = cell(1, 2);
    v.extend(quad(x, y, 0.4, 0.4)); // 62..66
    let (lx, ly) = cell(3, 1);
    vertices(gl, n, &v, [lx + 0.45, ly + 0.5])?;
    let mut marks = vec![u32::from(gl.glIsEnabled(PRIMITIVE_RESTART_FIXED_INDEX)?)];
    gl.glEnable(PRIMITIVE_RESTART_FIXED_INDEX)?;
    marks.push(u32::from(gl.glIsEnabled(PRIMITIVE_RESTART_FIXED_INDEX)?));
    let s = 0xFFFF;
    draw_indexed(gl, n, TRIANGLE_STRIP, UNSIGNED_SHORT, &[0, 1, 2, 3, s, 4, 5, 6, 7])?;
    let client = index_bytes(UNSIGNED_BYTE, &[8, 9, 10, 11, 0xFF, 12, 13, 14, 15]);
    gl.glBindBuffer(ELEMENT_ARRAY_BUFFER, 0)?;
    gl.strataDrawElementsData(TRIANGLE_STRIP, 9, UNSIGNED_BYTE, Blob::borrowed(&client))?;
    // A list: the triangle the restart cuts short is dropped.
    draw_indexed(gl, n, TRIANGLES, UNSIGNED_INT, &[16, 17, 18, 19, u32::MAX, 20, 21, 22])?;
    draw_indexed(gl, n, TRIANGLE_FAN, UNSIGNED_SHORT, &[23, 24, 25, 26, s, 27, 28, 29, 30])?;
    // Lines in one colour each: what the restart leaves out is what is compared.
    gl.glDisableVertexAttribArray(1)?;
    gl.glVertexAttrib4f(1, 1.0, 0.8, 0.2, 1.0)?;
    draw_indexed(gl, n, LINE_STRIP, UNSIGNED_SHORT, &[31, 32, 33, s, 34, 35, 36])?;
    gl.glVertexAttrib4f(1, 0.2, 0.9, 1.0, 1.0)?;
    draw_indexed(gl, n, LINE_LOOP, UNSIGNED_INT, &[37, 38, 39, u32::MAX, 40, 41, 42])?;
    gl.glEnableVertexAttribArray(1)?;
    draw_indexed(gl, n, POINTS, UNSIGNED_SHORT, &[43, s, 44, 45, s])?;
    // Restart disabled: 255 is a vertex (the cell's top right corner).
    gl.glDisable(PRIMITIVE_RESTART_FIXED_INDEX)?;
    draw_indexed(gl, n, TRIANGLE_STRIP, UNSIGNED_BYTE, &[46, 47, 48, 49, 255, 50, 51, 52, 53])?;
    gl.glEnable(PRIMITIVE_RESTART_FIXED_INDEX)?;
    draw_indexed(gl, n, TRIANGLE_STRIP, UNSIGNED_BYTE, &[54, 55, 56, 57, 255, 58, 59, 60, 61])?;
    // A vertex range knows no restart.
    gl.glDrawArrays(TRIANGLE_STRIP, 62, 4)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

/// Flat colours from each primitive's last vertex, in every mode (lines in bands across the
/// window, triangles in cells).
pub fn provoking_vertex(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_FLAT, FS_FLAT, &[])?;
    let mut v: Vec<[f32; 2]> = Vec::new();
    let (x, y) = cell(0, 0);
    v.extend([[x, y], [x + 0.4, y], [x, y + 0.4], [x + 0.05, y + 0.45], [x + 0.45, y + 0.05], [x + 0.45, y + 0.45]]); // 0..6
    let (x, y) = cell(1, 0);
    v.extend([[x, y], [x + 0.15, y + 0.45], [x + 0.2, y], [x + 0.3, y + 0.45], [x + 0.4, y], [x + 0.45, y + 0.45]]); // 6..12
    let (x, y) = cell(2, 0);
    v.extend([[x + 0.2, y + 0.2], [x, y], [x + 0.4, y], [x + 0.45, y + 0.45], [x, y + 0.4]]); // 12..17
    let (x, y) = cell(3, 0);
    v.extend(quad(x, y, 0.2, 0.45)); // 17..21
    v.extend(quad(x + 0.25, y, 0.2, 0.45)); // 21..25
                                            // Lines with their ends off the window: GL lets the last pixel of a segment differ
                                            // (its diamond-exit rule is a "should"), and drawing a segment from its last vertex does.
    let (l, r) = (-1.5, 1.5);
    v.extend([[l, 0.22], [r, 0.3], [l, 0.34], [r, 0.26]]); // 25..29
    v.extend([[l, 0.4], [r, 0.46], [l, 0.5], [r, 0.44]]); // 29..33
    v.extend([[l, 0.56], [r, 0.6], [r, 0.68]]); // 33..36
    let (x, y) = cell(3, 1);
    v.extend(quad(x, y, 0.45, 0.45)); // 36..40
    vertices(gl, n, &v, [0.0, 0.0])?;
    gl.glDrawArrays(TRIANGLES, 0, 6)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 6, 6)?;
    gl.glDrawArrays(TRIANGLE_FAN, 12, 5)?;
    // A strip from indices with a restart in it, back faces culled: turned, each triangle
    // keeps its winding.
    gl.glEnable(PRIMITIVE_RESTART_FIXED_INDEX)?;
    gl.glEnable(CULL_FACE)?;
    draw_indexed(gl, n, TRIANGLE_STRIP, UNSIGNED_SHORT, &[17, 18, 19, 20, 0xFFFF, 21, 22, 23, 24])?;
    gl.glDisable(CULL_FACE)?;
    gl.glDisable(PRIMITIVE_RESTART_FIXED_INDEX)?;
    gl.glDrawArrays(LINES, 25, 4)?;
    draw_indexed(gl, n, LINE_STRIP, UNSIGNED_BYTE, &[29, 30, 31, 32])?;
    gl.glDrawArrays(LINE_LOOP, 33, 3)?;
    let client = index_bytes(UNSIGNED_INT, &[36, 37, 38, 38, 37, 39]);
    gl.glBindBuffer(ELEMENT_ARRAY_BUFFER, 0)?;
    gl.strataDrawElementsData(TRIANGLES, 6, UNSIGNED_INT, Blob::borrowed(&client))?;
    let e = gl.glGetError()?;
    mark_all(gl, &[e])
}
