//! `GL_KHR_parallel_shader_compile`: the thread-count hint and its query, and every shader and
//! program reporting its compile or link complete.

use super::*;

/// `GL_MAX_SHADER_COMPILER_THREADS_KHR` and `GL_COMPLETION_STATUS_KHR`.
const MAX_THREADS: u32 = 0x91B0;
const COMPLETION: u32 = 0x91B1;

/// Sets the hint, compiles and links, and draws what the queries answer: each shader's and the
/// program's completion in red, green and blue, the hint (before and after) in alpha.
fn parallel_shader_compile(gl: Gl<'_>, n: &mut Names) -> R {
    let initial = gl.glGetIntegerv(MAX_THREADS)?.first().copied().unwrap_or(0);
    gl.glMaxShaderCompilerThreadsKHR(2)?;
    let set = gl.glGetIntegerv(MAX_THREADS)?.first().copied().unwrap_or(0);
    // `program` names the program, then its vertex and fragment shaders.
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    let done =
        [gl.glGetShaderiv(p + 1, COMPLETION)?, gl.glGetShaderiv(p + 2, COMPLETION)?, gl.glGetProgramiv(p, COMPLETION)?];
    let alpha = (initial as f32 + 1.0) * 0.5 + set as f32 * 0.2;
    color(gl, p, [done[0] as f32, done[1] as f32, done[2] as f32, alpha])?;
    draw_positions(gl, n, &quad(-0.5, -0.5, 0.5, 0.5, 0.0), TRIANGLES)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "parallel_shader_compile", run: parallel_shader_compile, tol: DEFAULT, expects_error: false }]
}
