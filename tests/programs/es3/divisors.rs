//! ES 3.0's instanced attributes (`glVertexAttribDivisor`): a per-instance offset read as it is
//! (divisor 1, floats), a colour every two instances (divisor 2, normalized bytes, converted),
//! a lift every three instances (divisor 3, an odd stride), in array and element draws, and the
//! divisor read back.

use super::super::multi_draw::mark_all;
use super::super::*;

const VERTEX_ATTRIB_ARRAY_DIVISOR: u32 = 0x88FE;

const VS: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    layout(location = 1) in vec2 offset;
    layout(location = 2) in vec4 color;
    layout(location = 3) in float lift;
    out vec4 c;
    void main() { c = color; gl_Position = vec4(pos * 0.12 + offset + vec2(0.0, lift), 0.0, 1.0); }";
const FS: &str = "#version 300 es
    precision mediump float; in vec4 c; out vec4 o; void main() { o = c; }";

/// Six instances of a small quad, as strips and as indexed triangles.
pub fn divisors(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS, FS, &[])?;
    buffer(gl, n, ARRAY_BUFFER, &f32s(&[-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0]))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    let offsets: Vec<f32> = (0..6).flat_map(|i| [-0.8 + i as f32 * 0.3, -0.7]).collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&offsets))?;
    attrib(gl, 1, 2, FLOAT, false, 0, 0)?;
    gl.glVertexAttribDivisor(1, 1)?;
    let colors: Vec<u8> = [[255u8, 40, 0, 255], [0, 200, 80, 255], [60, 60, 255, 255]].concat();
    buffer(gl, n, ARRAY_BUFFER, &colors)?;
    attrib(gl, 2, 4, UNSIGNED_BYTE, true, 0, 0)?;
    gl.glVertexAttribDivisor(2, 2)?;
    // Lifts at a stride of 6 bytes: two floats' room, read as halves of them.
    let mut lifts = Vec::new();
    for l in [0.0f32, 0.5] {
        lifts.extend(l.to_ne_bytes());
        lifts.extend([0u8, 0]);
    }
    buffer(gl, n, ARRAY_BUFFER, &lifts)?;
    attrib(gl, 3, 1, FLOAT, false, 6, 0)?;
    gl.glVertexAttribDivisor(3, 3)?;
    gl.glDrawArraysInstancedEXT(TRIANGLE_STRIP, 0, 4, 6)?;
    // The same from indices, higher up.
    let indices: Vec<u8> = [0u16, 1, 2, 1, 3, 2].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &indices)?;
    gl.glVertexAttribDivisor(3, 0)?;
    gl.glVertexAttrib1f(3, 1.1)?;
    gl.glDisableVertexAttribArray(3)?;
    gl.glDrawElementsInstancedEXT(TRIANGLES, 6, UNSIGNED_SHORT, 0, 5)?;
    let mut marks = Vec::new();
    for i in 0..4 {
        marks.extend(gl.glGetVertexAttribiv(i, VERTEX_ATTRIB_ARRAY_DIVISOR)?.iter().map(|&v| v as u32));
    }
    gl.glVertexAttribDivisor(99, 1)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}
