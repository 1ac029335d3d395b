//! ES 3.0's transform feedback, drawn: triangles' moved positions and colours captured
//! interleaved with the rasterizer discarding, then drawn from the buffer; instanced triangles
//! captured into two buffers while they are drawn too, then drawn from those; a paused capture
//! that draws without writing.

use strata_protocol::{Slice, Text};

use super::super::multi_draw::mark_all;
use super::super::*;

const TRANSFORM_FEEDBACK: u32 = 0x8E22;
const TF_BUFFER: u32 = 0x8C8E;
const INTERLEAVED: u32 = 0x8C8C;
const SEPARATE: u32 = 0x8C8D;
const RASTERIZER_DISCARD: u32 = 0x8C89;

/// Moves each vertex and gives it a colour, both captured; draws it where it was.
const VS_CAPTURE: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    out vec4 moved; out vec4 tint;
    void main() {
        moved = vec4(pos * 0.4 + vec2(0.3, 0.2) + vec2(float(gl_InstanceID) * -0.9, 0.0), 0.0, 1.0);
        tint = vec4(pos * 0.3 + 0.5, 0.4 + 0.3 * float(gl_InstanceID), 1.0);
        gl_Position = vec4(pos * 0.3 - 0.6, 0.0, 1.0);
    }";
const FS_CAPTURE: &str = "#version 300 es
    precision mediump float; in vec4 moved; in vec4 tint; out vec4 o; void main() { o = tint.bgra; }";
/// Draws what was captured.
const VS_REPLAY: &str = "#version 300 es
    layout(location = 0) in vec4 pos; layout(location = 1) in vec4 color; out vec4 c;
    void main() { c = color; gl_Position = pos; }";
const FS_REPLAY: &str = "#version 300 es
    precision mediump float; in vec4 c; out vec4 o; void main() { o = c; }";

/// A program capturing `moved` and `tint` in `mode`, in use.
fn capturing(gl: Gl<'_>, n: &mut Names, mode: u32) -> R {
    let (p, v, f) = (n.next(), n.next(), n.next());
    gl.glCreateProgram(p)?;
    for (name, ty, src) in [(v, 0x8B31u32, VS_CAPTURE), (f, 0x8B30, FS_CAPTURE)] {
        gl.glCreateShader(ty, name)?;
        gl.glShaderSource(name, Text::borrowed(src))?;
        gl.glCompileShader(name)?;
        gl.glAttachShader(p, name)?;
    }
    gl.glTransformFeedbackVaryings(p, 2, Text::borrowed("moved\ntint\n"), mode)?;
    gl.glLinkProgram(p)?;
    gl.glUseProgram(p)
}

/// An empty buffer of `size` bytes bound to the generic transform feedback binding.
fn xfb_buffer(gl: Gl<'_>, n: &mut Names, size: usize) -> Result<u32, strata_client::ClientError> {
    buffer(gl, n, TF_BUFFER, &vec![0u8; size])
}

/// Captured triangles drawn from their buffers.
pub fn transform_feedback(gl: Gl<'_>, n: &mut Names) -> R {
    let x = n.next();
    gl.glGenTransformFeedbacks(Slice::new(&[x]))?;
    gl.glBindTransformFeedback(TRANSFORM_FEEDBACK, x)?;
    let grid: Vec<f32> = vec![-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, 1.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&grid))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    // Interleaved, nothing rasterized.
    capturing(gl, n, INTERLEAVED)?;
    let one = xfb_buffer(gl, n, 6 * 32)?;
    gl.glBindBufferBase(TF_BUFFER, 0, one)?;
    gl.glEnable(RASTERIZER_DISCARD)?;
    gl.glBeginTransformFeedback(TRIANGLES)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)?;
    gl.glEndTransformFeedback()?;
    gl.glDisable(RASTERIZER_DISCARD)?;
    // Separate, two instances, drawn as well; a paused draw between writes nothing.
    capturing(gl, n, SEPARATE)?;
    let (moved, tint) = (xfb_buffer(gl, n, 12 * 16)?, xfb_buffer(gl, n, 12 * 16 + 64)?);
    gl.glBindBufferBase(TF_BUFFER, 0, moved)?;
    gl.glBindBufferRange(TF_BUFFER, 1, tint, 64, 12 * 16)?;
    gl.glBeginTransformFeedback(TRIANGLES)?;
    gl.glDrawArraysInstancedEXT(TRIANGLES, 0, 3, 2)?;
    gl.glPauseTransformFeedback()?;
    gl.glDrawArrays(TRIANGLES, 3, 3)?;
    gl.glResumeTransformFeedback()?;
    gl.glDrawArraysInstancedEXT(TRIANGLES, 3, 3, 2)?;
    gl.glEndTransformFeedback()?;
    let e = gl.glGetError()?;
    // What was captured, drawn.
    program(gl, n, VS_REPLAY, FS_REPLAY, &[])?;
    gl.glBindBuffer(ARRAY_BUFFER, one)?;
    attrib(gl, 0, 4, FLOAT, false, 32, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 32, 16)?;
    // The interleaved capture in the lower right quarter, apart from the separate one's.
    gl.glViewport(W / 2, 0, W / 2, H / 2)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glBindBuffer(ARRAY_BUFFER, moved)?;
    gl.glVertexAttribPointer(0, 4, FLOAT, false, 0, 0)?;
    gl.glBindBuffer(ARRAY_BUFFER, tint)?;
    gl.glVertexAttribPointer(1, 4, FLOAT, false, 0, 64)?;
    gl.glDrawArrays(TRIANGLES, 0, 12)?;
    mark_all(gl, &[e])
}
