//! ES 3.0's integer vertex attributes: signed shorts and unsigned bytes through
//! `glVertexAttribIPointer` (one value per quad, so that no flat varying depends on which
//! vertex provokes it), unsigned ints per instance, a current value from `glVertexAttribI4i`,
//! read by `ivec`/`uvec` inputs; and what the queries answer, and the errors, as colours.

use super::super::multi_draw::mark_all;
use super::super::*;

const INT: u32 = 0x1404;
const CURRENT_VERTEX_ATTRIB: u32 = 0x8626;
const VERTEX_ATTRIB_ARRAY_INTEGER: u32 = 0x88FD;

const VS: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    layout(location = 1) in ivec2 shorts;
    layout(location = 2) in uvec2 bytes;
    layout(location = 3) in uint instance_data;
    layout(location = 4) in ivec4 constant;
    flat out ivec4 k;
    flat out uvec3 u;
    void main() {
        k = ivec4(shorts, constant.xy);
        u = uvec3(bytes, instance_data);
        gl_Position = vec4(pos.x * 0.2 - 0.7 + float(gl_InstanceID) * 0.5, pos.y, 0.0, 1.0);
    }";
const FS: &str = "#version 300 es
    precision highp float;
    precision highp int;
    flat in ivec4 k;
    flat in uvec3 u;
    out vec4 o;
    void main() {
        o = vec4(float(k.x + 300) / 600.0, float(u.x * 2u + u.y) / 255.0, float(u.z >> 24) / 255.0,
                 float(k.y * 64 + k.z - k.w) / 255.0);
    }";

/// Three instances of a strip of three quads, each quad its own integers.
pub fn int_attributes(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS, FS, &[])?;
    // Three quads stacked up the screen, as one strip with degenerate joins: each quad's four
    // vertices carry the same integers.
    let mut pos = Vec::new();
    let (mut shorts, mut bytes) = (Vec::new(), Vec::new());
    for q in 0..3i16 {
        let (y0, y1) = (-0.9 + f32::from(q) * 0.6, -0.5 + f32::from(q) * 0.6);
        for (x, y) in [(-1.0, y0), (-1.0, y0), (1.0, y0), (-1.0, y1), (1.0, y1), (1.0, y1)] {
            pos.extend([x, y]);
            shorts.extend([-250 + q * 200, q + 1].iter().flat_map(|v| v.to_ne_bytes()));
            bytes.extend([40 * q as u8 + 10, 7 * q as u8]);
        }
    }
    buffer(gl, n, ARRAY_BUFFER, &f32s(&pos))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    buffer(gl, n, ARRAY_BUFFER, &shorts)?;
    gl.glVertexAttribIPointer(1, 2, SHORT, 0, 0)?;
    gl.glEnableVertexAttribArray(1)?;
    buffer(gl, n, ARRAY_BUFFER, &bytes)?;
    gl.glVertexAttribIPointer(2, 2, UNSIGNED_BYTE, 2, 0)?;
    gl.glEnableVertexAttribArray(2)?;
    let per_instance: Vec<u8> =
        [0x1000_0000u32, 0x8000_0000, 0xFF00_0000].iter().flat_map(|v| v.to_ne_bytes()).collect();
    buffer(gl, n, ARRAY_BUFFER, &per_instance)?;
    gl.glVertexAttribIPointer(3, 1, UNSIGNED_INT, 0, 0)?;
    gl.glEnableVertexAttribArray(3)?;
    gl.glVertexAttribDivisor(3, 1)?;
    gl.glVertexAttribI4i(4, 3, 17, 0, 0)?;
    gl.glDrawArraysInstancedEXT(TRIANGLE_STRIP, 0, 18, 3)?;
    let mut marks = Vec::new();
    marks.extend(gl.glGetVertexAttribIiv(4, CURRENT_VERTEX_ATTRIB)?.iter().map(|&v| v as u32));
    gl.glVertexAttribI4ui(5, 0xFFFF_FFFF, 2, 3, 4)?;
    marks.extend(gl.glGetVertexAttribIuiv(5, CURRENT_VERTEX_ATTRIB)?.iter().map(|v| v >> 16));
    for i in [0, 1, 3] {
        marks.extend(gl.glGetVertexAttribiv(i, VERTEX_ATTRIB_ARRAY_INTEGER)?.iter().map(|&v| v as u32));
    }
    gl.glVertexAttribIPointer(1, 2, FLOAT, 0, 0)?;
    marks.push(gl.glGetError()?);
    gl.glVertexAttribIPointer(1, 5, INT, 0, 0)?;
    marks.push(gl.glGetError()?);
    gl.glVertexAttribIPointer(1, 2, INT, -4, 0)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}
