//! ES 3.0's uniforms: unsigned scalars and vectors (`glUniform*ui[v]`), the six non-square
//! matrix shapes (`glUniformMatrix{2x3,3x2,2x4,4x2,3x4,4x3}fv`, the `matCx2` ones through the
//! block's column wrappers), an array of them, transposed uploads (which ES 2.0 refuses), and
//! the values read back (`glGetUniformuiv`, `glGetUniformfv`), each as a colour.

use super::super::multi_draw::mark_all;
use super::super::*;

/// Each matrix and unsigned value lights one band of the screen.
const FS: &str = "#version 300 es
    precision highp float;
    precision highp int;
    uniform uint u;
    uniform uvec3 uv3;
    uniform mat2x3 m23;
    uniform mat3x2 m32;
    uniform mat2x4 m24;
    uniform mat4x2 m42;
    uniform mat3x4 m34;
    uniform mat4x3 m43[2];
    uniform mat4 t4;
    in vec2 uv;
    out vec4 frag;
    void main() {
        int band = int(uv.y * 8.0);
        vec4 c = vec4(0.0, 0.0, 0.0, 1.0);
        if (band == 0) {
            c.rgb = vec3(float(u & 255u), float(uv3.x % 256u), float(uv3.z >> 24)) / 255.0;
        } else if (band == 1) {
            c.rgb = m23 * vec2(uv.x, 1.0 - uv.x);
        } else if (band == 2) {
            c.rg = m32 * vec3(uv.x, 0.5, 0.25);
        } else if (band == 3) {
            c = m24 * vec2(uv.x, 0.5);
        } else if (band == 4) {
            c.rg = m42 * vec4(uv.x, 0.5, 0.25, 1.0);
        } else if (band == 5) {
            c = m34 * vec3(uv.x, 0.5, 0.25);
        } else if (band == 6) {
            c.rgb = m43[1] * vec4(uv.x, 0.5, 0.25, 1.0) - m43[0][3];
        } else {
            c = t4 * vec4(uv.x, 1.0 - uv.x, 0.5, 1.0);
        }
        frag = vec4(clamp(c.rgb, 0.0, 1.0), 1.0);
    }";

/// Values in [0, 1] for a matrix of `n` entries, distinct per `seed`.
fn entries(n: usize, seed: f32) -> Vec<f32> {
    (0..n).map(|k| ((k as f32 * 0.37 + seed) % 1.0) * 0.6).collect()
}

/// Sets every uniform, draws, and marks what reads back.
pub fn uniforms(gl: Gl<'_>, n: &mut Names) -> R {
    let p = super::language::screen(gl, n, super::language::VS_SCREEN, FS)?;
    let at = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let u = at(gl, "u")?;
    gl.glUniform1ui(u, 0xDEAD_BEEF)?;
    let uv3 = at(gl, "uv3")?;
    gl.glUniform3uiv(uv3, Slice::new(&[300, 7, 0xC000_0000]))?;
    let [m23, m32, m24, m42, m34, m43, t4] =
        [at(gl, "m23")?, at(gl, "m32")?, at(gl, "m24")?, at(gl, "m42")?, at(gl, "m34")?, at(gl, "m43")?, at(gl, "t4")?];
    gl.glUniformMatrix2x3fv(m23, false, Slice::new(&entries(6, 0.1)))?;
    gl.glUniformMatrix3x2fv(m32, false, Slice::new(&entries(6, 0.2)))?;
    gl.glUniformMatrix2x4fv(m24, true, Slice::new(&entries(8, 0.3)))?;
    gl.glUniformMatrix4x2fv(m42, false, Slice::new(&entries(8, 0.4)))?;
    gl.glUniformMatrix3x4fv(m34, true, Slice::new(&entries(12, 0.5)))?;
    let both: Vec<f32> = entries(12, 0.6).into_iter().chain(entries(12, 0.7)).collect();
    gl.glUniformMatrix4x3fv(m43, false, Slice::new(&both))?;
    gl.glUniformMatrix4fv(t4, true, Slice::new(&entries(16, 0.8)))?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    // What reads back: the unsigned values exactly, a transposed matrix's entries in GL's
    // column order, a uniform of the wrong kind's error.
    let mut marks = Vec::new();
    marks.extend(gl.glGetUniformuiv(p, u)?.iter().map(|v| v >> 16));
    marks.extend(gl.glGetUniformuiv(p, uv3)?);
    marks.extend(gl.glGetUniformfv(p, t4)?.iter().take(5).map(|v| (v * 1000.0) as u32));
    marks.extend(gl.glGetUniformfv(p, m42)?.iter().map(|v| (v * 1000.0) as u32));
    gl.glUniform1i(u, 3)?;
    marks.push(gl.glGetError()?);
    gl.glUniform3ui(m23, 1, 2, 3)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}
