//! Matrix vertex inputs (GLSL ES 3.00's `in mat2`, `mat3x2`, `mat4`, and ES 1.00's
//! `attribute mat3` in an ES 3.0 context): each column a location of its own, fed by arrays
//! per column and by constant values, at locations the shader gives and the linker chooses;
//! their locations as marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const VS: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    layout(location = 2) in mat2 turn;
    in mat3x2 shear;
    in mat4 tint;
    out vec4 c;
    void main() {
        vec2 p = turn * pos + shear * vec3(pos, 1.0) * 0.1;
        gl_Position = vec4(p * 0.9, 0.0, 1.0);
        c = tint * vec4(0.5, 0.25, 0.75, 1.0);
    }";
const FS: &str = "#version 300 es
    precision highp float;
    in vec4 c;
    out vec4 o;
    void main() { o = c; }";
const VS_100: &str = "attribute vec2 pos; attribute mat3 m; varying vec4 c;
    void main() { gl_Position = vec4((m * vec3(pos, 1.0)).xy, 0.0, 1.0); c = vec4(m[2], 1.0); }";
const FS_100: &str = "precision mediump float; varying vec4 c; void main() { gl_FragColor = c; }";

/// The matrix input program.
pub fn matrix_inputs(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let mut marks = Vec::new();
    for name in ["pos", "turn", "shear", "tint"] {
        marks.push(gl.glGetAttribLocation(p, Text::borrowed(name))? as u32);
    }
    let (turn, shear, tint) = (marks[1], marks[2], marks[3]);
    // A triangle fan of 4 vertices, each with its own rotation columns.
    let pos = [-0.5f32, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&pos))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    let cols: Vec<f32> = (0..4)
        .flat_map(|i| {
            let a = 0.3 * i as f32;
            [a.cos(), a.sin(), -a.sin(), a.cos()]
        })
        .collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&cols))?;
    attrib(gl, turn, 2, FLOAT, false, 16, 0)?;
    attrib(gl, turn + 1, 2, FLOAT, false, 16, 8)?;
    // The shear's columns constant; the tint's first two columns arrays, the others constant.
    gl.glVertexAttrib2f(shear, 1.0, 0.5)?;
    gl.glVertexAttrib2f(shear + 1, -0.5, 1.0)?;
    gl.glVertexAttrib2f(shear + 2, 0.2, -0.3)?;
    let tint_cols: Vec<f32> =
        (0..4).flat_map(|i| [0.2 * i as f32, 0.5, 0.1, 0.0, 0.3, 0.1 * i as f32, 0.2, 0.0]).collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&tint_cols))?;
    attrib(gl, tint, 4, FLOAT, false, 32, 0)?;
    attrib(gl, tint + 1, 4, FLOAT, false, 32, 16)?;
    gl.glVertexAttrib4f(tint + 2, 0.1, 0.2, 0.6, 0.0)?;
    gl.glVertexAttrib4f(tint + 3, 0.0, 0.0, 0.0, 1.0)?;
    gl.glDrawArrays(TRIANGLE_FAN, 0, 4)?;
    for l in 0..8 {
        gl.glDisableVertexAttribArray(l)?;
    }

    // GLSL ES 1.00's matrix attribute, bound by the application.
    let q = program(gl, n, VS_100, FS_100, &["pos", "m"])?;
    marks.push(gl.glGetAttribLocation(q, Text::borrowed("m"))? as u32);
    let tri = [0.6f32, 0.6, 0.9, 0.6, 0.9, 0.9];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&tri))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    gl.glVertexAttrib3f(1, 1.0, 0.0, 0.0)?;
    gl.glVertexAttrib3f(2, 0.0, 1.0, 0.0)?;
    gl.glVertexAttrib3f(3, 0.05, -0.1, 0.5)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)?;
    gl.glDisableVertexAttribArray(0)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}
