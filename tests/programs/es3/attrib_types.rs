//! ES 3.0's new types for float vertex attributes through `glVertexAttribPointer`: 32-bit
//! signed and unsigned integers (normalized and not), `GL_HALF_FLOAT`, and the packed
//! `GL_INT_2_10_10_10_REV` and `GL_UNSIGNED_INT_2_10_10_10_REV` (normalized and not; one
//! from a client array), each colouring a strip of its own; signed bytes at both ends of their
//! range; and the errors, as colours.

use super::super::multi_draw::mark_all;
use super::super::*;

const INT: u32 = 0x1404;
const UNSIGNED_INT: u32 = 0x1405;
const HALF_FLOAT: u32 = 0x140B;
const INT_2_10_10_10_REV: u32 = 0x8D9F;
const UNSIGNED_INT_2_10_10_10_REV: u32 = 0x8368;

const VS: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    layout(location = 1) in vec4 col;
    uniform vec2 scale_bias;
    out vec4 c;
    void main() { c = col * scale_bias.x + scale_bias.y; gl_Position = vec4(pos, 0.0, 1.0); }";
const FS: &str = "#version 300 es
    precision highp float;
    in vec4 c; out vec4 o;
    void main() { o = vec4(c.x, c.y, c.z * 0.5 + c.w * 0.5, 1.0); }";

/// `x`, `y`, `z` (10 bits each) and `w` (2 bits) packed as the `2_10_10_10_REV` types hold them.
fn pack(x: i32, y: i32, z: i32, w: i32) -> [u8; 4] {
    let v = (x as u32 & 0x3FF) | ((y as u32 & 0x3FF) << 10) | ((z as u32 & 0x3FF) << 20) | ((w as u32 & 3) << 30);
    v.to_ne_bytes()
}

/// One case: type, size, normalized, one element, scale and bias into [0, 1], from a client
/// array.
type AttribCase = (u32, i32, bool, Vec<u8>, [f32; 2], bool);

/// One strip per type; each strip's four vertices carry one element.
pub fn attrib_types(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let sb = gl.glGetUniformLocation(p, Text::borrowed("scale_bias"))?;
    let strips = 9;
    let mut pos = Vec::new();
    for k in 0..strips {
        let (x0, x1) = (-1.0 + 2.0 * k as f32 / strips as f32, -1.0 + 2.0 * (k + 1) as f32 / strips as f32);
        pos.extend([x0, -0.9, x1, -0.9, x0, 0.9, x1, 0.9]);
    }
    buffer(gl, n, ARRAY_BUFFER, &f32s(&pos))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    let words = |v: &[u32]| v.iter().flat_map(|x| x.to_ne_bytes()).collect::<Vec<u8>>();
    let halfs = |v: &[f32]| v.iter().flat_map(|x| half::f16::from_f32(*x).to_bits().to_ne_bytes()).collect::<Vec<u8>>();
    let max = i32::MAX;
    // (type, size, normalized, one element, scale and bias into [0, 1], from a client array)
    let cases: [AttribCase; 9] = [
        (INT, 4, true, words(&[(max / 2) as u32, (-max / 3) as u32, max as u32, (-max) as u32]), [0.5, 0.5], false),
        (INT, 4, false, words(&[1, 2, (-3i32) as u32, 4]), [0.125, 0.5], false),
        (UNSIGNED_INT, 4, true, words(&[u32::MAX / 4, u32::MAX / 2, u32::MAX, 0]), [1.0, 0.0], false),
        (UNSIGNED_INT, 3, false, words(&[1, 3, 5]), [0.125, 0.0], false),
        (HALF_FLOAT, 3, false, halfs(&[0.25, 0.5, 0.75]), [1.0, 0.0], false),
        (INT_2_10_10_10_REV, 4, true, pack(-300, 200, 511, -1).to_vec(), [0.5, 0.5], true),
        (UNSIGNED_INT_2_10_10_10_REV, 4, true, pack(100, 700, 1023, 2).to_vec(), [1.0, 0.0], false),
        (UNSIGNED_INT_2_10_10_10_REV, 4, false, pack(3, 5, 7, 1).to_vec(), [0.125, 0.0], false),
        (BYTE, 4, true, vec![0x80, 0x81, 0x00, 0x7F], [0.5, 0.5], false),
    ];
    for (k, (ty, size, normalized, element, [scale, bias], client)) in cases.iter().enumerate() {
        // Every vertex up to the strip's last carries the element.
        let data: Vec<u8> = element.repeat(4 * (k + 1));
        gl.glUniform2f(sb, *scale, *bias)?;
        if *client {
            gl.glBindBuffer(ARRAY_BUFFER, 0)?;
            gl.glVertexAttribPointer(1, *size, *ty, *normalized, 0, 0)?;
            gl.strataVertexAttribData(1, Blob::borrowed(&data))?;
        } else {
            buffer(gl, n, ARRAY_BUFFER, &data)?;
            attrib(gl, 1, *size, *ty, *normalized, 0, 0)?;
        }
        gl.glEnableVertexAttribArray(1)?;
        gl.glDrawArrays(TRIANGLE_STRIP, 4 * k as i32, 4)?;
    }
    // The errors: a packed type of three components, an unknown type.
    let mut marks = Vec::new();
    gl.glVertexAttribPointer(1, 3, INT_2_10_10_10_REV, true, 0, 0)?;
    marks.push(gl.glGetError()?);
    gl.glVertexAttribPointer(1, 4, 0x1234, false, 0, 0)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}
