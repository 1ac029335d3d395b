//! `GL_EXT_draw_instanced`: `glDrawArraysInstancedEXT` and `glDrawElementsInstancedEXT` draw
//! one shape several times, each instance placed and coloured by its `gl_InstanceIDEXT`, from
//! arrays, an element buffer and client indices, as triangles and as points; and the errors
//! the calls give, drawn as colours.

use super::multi_draw::mark_error;
use super::*;

/// Moves each instance right by 0.45, and up by `lift` plus `shift` per instance; colours it
/// by its number.
const VS_INSTANCED: &str = "#extension GL_EXT_draw_instanced : enable
attribute vec4 pos;
attribute vec4 col;
uniform float lift;
uniform float shift;
varying vec4 v;
void main() {
    float i = float(gl_InstanceIDEXT);
    v = vec4(col.rg, i / 4.0, 1.0);
    gl_Position = pos + vec4(i * 0.45, lift + i * shift, 0.0, 0.0);
    gl_PointSize = 3.0 + i;
}";

/// The instanced program over a small quad at the lower left (four strip vertices).
fn instanced_quad(gl: Gl<'_>, n: &mut Names) -> Result<u32, ClientError> {
    let p = program(gl, n, VS_INSTANCED, FS_VARY, &["pos", "col"])?;
    let v: Vec<f32> = [(-0.95, -0.95), (-0.65, -0.95), (-0.95, -0.7), (-0.65, -0.7)]
        .iter()
        .flat_map(|&(x, y)| [x, y, 0.0, (x + 1.0) * 3.0, (y + 1.0) * 3.0, 0.0, 1.0])
        .collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    Ok(p)
}

/// Sets the program's `lift` and `shift` uniforms.
fn place(gl: Gl<'_>, program: u32, lift: f32, shift: f32) -> R {
    let lift_at = gl.glGetUniformLocation(program, Text::borrowed("lift"))?;
    gl.glUniform1f(lift_at, lift)?;
    let shift_at = gl.glGetUniformLocation(program, Text::borrowed("shift"))?;
    gl.glUniform1f(shift_at, shift)
}

/// Four instances from the arrays, three from the element buffer (and a zero-instance draw
/// over them that draws nothing), two from client indices, three of points; a row each.
fn draw_instanced(gl: Gl<'_>, n: &mut Names) -> R {
    let p = instanced_quad(gl, n)?;
    place(gl, p, 0.0, 0.0)?;
    gl.glDrawArraysInstancedEXT(TRIANGLE_STRIP, 0, 4, 4)?;
    let indices: Vec<u8> = [0u16, 1, 2, 1, 3, 2].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &indices)?;
    place(gl, p, 0.45, 0.02)?;
    gl.glDrawElementsInstancedEXT(TRIANGLES, 6, UNSIGNED_SHORT, 0, 3)?;
    place(gl, p, 0.45, -0.1)?;
    gl.glDrawElementsInstancedEXT(TRIANGLES, 6, UNSIGNED_SHORT, 0, 0)?;
    gl.glBindBuffer(ELEMENT_ARRAY_BUFFER, 0)?;
    place(gl, p, 0.9, 0.1)?;
    let bytes: Vec<u8> = vec![0, 1, 2, 1, 3, 2];
    gl.strataDrawElementsInstancedData(TRIANGLES, 6, UNSIGNED_BYTE, Blob::borrowed(&bytes), 2)?;
    place(gl, p, 1.4, 0.05)?;
    gl.glDrawArraysInstancedEXT(POINTS, 0, 4, 3)
}

/// The calls' errors: negative counts and instance counts, a bad mode, bad index types (FLOAT,
/// INT), an instance count of zero (none).
fn draw_instanced_errors(gl: Gl<'_>, n: &mut Names) -> R {
    instanced_quad(gl, n)?;
    let indices: Vec<u8> = [0u16, 1, 2].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &indices)?;
    let mut i = 0;
    let mut check = |gl: Gl<'_>| -> R {
        let e = gl.glGetError()?;
        mark_error(gl, i, e)?;
        i += 1;
        Ok(())
    };
    for (mode, first, count, instances) in [
        (TRIANGLES, 0, 3, -1),
        (TRIANGLES, 0, -1, 2),
        (TRIANGLES, -1, 3, 2),
        (0x20, 0, 3, 2),
        (0x20, 0, 3, -1),
        (TRIANGLES, 0, 3, 0),
    ] {
        gl.glDrawArraysInstancedEXT(mode, first, count, instances)?;
        check(gl)?;
        if first == 0 {
            gl.glDrawElementsInstancedEXT(mode, count, UNSIGNED_SHORT, 0, instances)?;
            check(gl)?;
        }
    }
    for ty in [FLOAT, 0x1404] {
        gl.glDrawElementsInstancedEXT(TRIANGLES, 3, ty, 0, -1)?;
        check(gl)?;
        gl.glDrawElementsInstancedEXT(TRIANGLES, 3, ty, 0, 2)?;
        check(gl)?;
    }
    Ok(())
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![
        Case { name: "draw_instanced", run: draw_instanced, tol: DEFAULT, expects_error: false },
        Case { name: "draw_instanced_errors", run: draw_instanced_errors, tol: DEFAULT, expects_error: false },
    ]
}
