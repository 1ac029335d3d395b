//! `GL_OES_get_program_binary`: a program's binary read back and loaded into other programs,
//! which then draw as the original does, with their uniforms at their initial values and the
//! attribute bindings of the link; the query and load errors; damaged binaries, which fail
//! the load without an error; a failed load into the program in use. All as colours.

use super::multi_draw::mark_all;
use super::*;
use strata_protocol::Bytes;

const PROGRAM_BINARY_LENGTH: u32 = 0x8741;
const NUM_PROGRAM_BINARY_FORMATS: u32 = 0x87FE;
const PROGRAM_BINARY_FORMATS: u32 = 0x87FF;
const LINK_STATUS: u32 = 0x8B82;
const ATTACHED_SHADERS: u32 = 0x8B85;
const VERTEX_SHADER: u32 = 0x8B31;

/// Attributes declared colour first, so that only the bindings put the position at 0. The
/// shaders end and begin with long comments, so that a byte flipped a third or two thirds
/// into a binary that holds the sources changes only a comment: only a checksum finds it.
fn vs() -> String {
    format!("attribute vec4 col; attribute vec4 pos; varying vec4 v;\n void main() {{ v = col; gl_Position = pos; }}\n// {}\n", "x".repeat(500))
}

/// The varying plus a uniform offset.
fn fs() -> String {
    format!(
        "// {}\nprecision mediump float; varying vec4 v; uniform vec4 k;\n void main() {{ gl_FragColor = v + k; }}\n",
        "x".repeat(500)
    )
}

/// What `glGetProgramBinaryOES` answered, as a number: 0 nothing written, 1 an empty
/// length, 2 a binary; the error beside it.
fn query(gl: Gl<'_>, marks: &mut Vec<u32>, program: u32, size: i32) -> Result<Option<(u32, Bytes)>, ClientError> {
    let answer = gl.glGetProgramBinaryOES(program, size)?;
    marks.push(match &answer {
        None => 0,
        Some(None) => 1,
        Some(Some(_)) => 2,
    });
    marks.push(gl.glGetError()?);
    Ok(answer.flatten())
}

/// Loads `bytes` into `program`, marking the error and the link status.
fn load(gl: Gl<'_>, marks: &mut Vec<u32>, program: u32, format: u32, length: i32, bytes: &[u8]) -> R {
    gl.glProgramBinaryOES(program, format, length, Blob::borrowed(bytes))?;
    marks.push(gl.glGetError()?);
    marks.push(gl.glGetProgramiv(program, LINK_STATUS)? as u32);
    Ok(())
}

/// Draws a quad over `rect` with the program in use, colour `col`.
fn quad(gl: Gl<'_>, n: &mut Names, rect: [f32; 4], col: [f32; 4]) -> R {
    vertex_quad(gl, n, rect, |x, y| [x, y, 0.0, col[0], col[1] * (y + 1.0) / 2.0, col[2] * (x + 1.0) / 2.0, col[3]])
}

fn program_binary(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = vec![gl.glGetIntegerv(NUM_PROGRAM_BINARY_FORMATS)?.first().copied().unwrap_or(-1) as u32];
    let formats = gl.glGetIntegerv(PROGRAM_BINARY_FORMATS)?;
    marks.push(formats.len() as u32);
    marks.push(gl.glGetError()?);
    let format = formats.first().copied().unwrap_or(0) as u32;

    // An unlinked program has no binary.
    let unlinked = n.next();
    gl.glCreateProgram(unlinked)?;
    marks.push(gl.glGetProgramiv(unlinked, PROGRAM_BINARY_LENGTH)? as u32);
    query(gl, &mut marks, unlinked, 100_000)?;

    let a = program(gl, n, &vs(), &fs(), &["pos", "col"])?;
    let k = gl.glGetUniformLocation(a, Text::borrowed("k"))?;
    gl.glUniform4f(k, 0.25, 0.0, 0.0, 0.0)?;
    let len = gl.glGetProgramiv(a, PROGRAM_BINARY_LENGTH)?;
    marks.push(u32::from(len > 16));
    // Too small a buffer, a negative size, a name that is no program, a shader.
    query(gl, &mut marks, a, len - 1)?;
    query(gl, &mut marks, a, -1)?;
    query(gl, &mut marks, 0xBAD, len)?;
    let shader = n.next();
    gl.glCreateShader(VERTEX_SHADER, shader)?;
    query(gl, &mut marks, shader, len)?;
    let Some((got, binary)) = query(gl, &mut marks, a, len + 10)? else { return mark_all(gl, &marks) };
    marks.push(u32::from(got == format));
    marks.push(u32::from(binary.0.len() as i32 == len));
    let bin = binary.0;

    // A copy: linked, no shaders attached, the link's bindings, uniforms at zero.
    let b = n.next();
    gl.glCreateProgram(b)?;
    load(gl, &mut marks, b, format, len, &bin)?;
    marks.push(gl.glGetProgramiv(b, ATTACHED_SHADERS)? as u32);
    marks.push(gl.glGetAttribLocation(b, Text::borrowed("pos"))? as u32);
    let kb = gl.glGetUniformLocation(b, Text::borrowed("k"))?;
    marks.extend(gl.glGetUniformfv(b, kb)?.iter().map(|v| (v * 100.0) as u32));
    // The copy's own binary loads too.
    let len_b = gl.glGetProgramiv(b, PROGRAM_BINARY_LENGTH)?;
    marks.push(u32::from(len_b > 16));

    // The original and the copy draw side by side, each with its own uniform.
    gl.glUseProgram(a)?;
    quad(gl, n, [-1.0, -1.0, 0.0, 0.0], [0.5, 0.75, 0.5, 1.0])?;
    gl.glUseProgram(b)?;
    quad(gl, n, [0.0, -1.0, 1.0, 0.0], [0.5, 0.75, 0.5, 1.0])?;
    gl.glUniform4f(kb, 0.0, 0.0, 0.5, 0.0)?;
    quad(gl, n, [0.0, -0.5, 1.0, 0.0], [0.25, 0.5, 0.5, 1.0])?;

    // Damaged binaries fail the load without an error: a byte flipped at the start, a third
    // and two thirds in, and at the end, a truncated one, an empty one. A bad format and a negative
    // length are errors, and unlink the program as well.
    let c = n.next();
    gl.glCreateProgram(c)?;
    for at in [0, bin.len() / 3, bin.len() * 2 / 3, bin.len() - 1] {
        let mut flipped = bin.clone();
        flipped[at] ^= 0x01;
        load(gl, &mut marks, c, format, len, &flipped)?;
    }
    load(gl, &mut marks, c, format, len - 7, &bin)?;
    load(gl, &mut marks, c, format, 0, &[])?;
    load(gl, &mut marks, c, format, len, &bin)?;
    load(gl, &mut marks, c, format ^ 0x1, len, &bin)?;
    load(gl, &mut marks, c, format, len, &bin)?;
    load(gl, &mut marks, c, format, -1, &bin)?;
    marks.push(gl.glGetProgramiv(c, PROGRAM_BINARY_LENGTH)? as u32);
    // Loads into names that are no programs.
    gl.glProgramBinaryOES(0xBAD, format, len, Blob::borrowed(&bin))?;
    marks.push(gl.glGetError()?);
    gl.glProgramBinaryOES(shader, format, len, Blob::borrowed(&bin))?;
    marks.push(gl.glGetError()?);

    // A good load into c, used; then a failed load into c while in use: c's executable stays
    // in use. (The upper rows of the picture hold the marks, so these quads stay below them.)
    load(gl, &mut marks, c, format, len, &bin)?;
    gl.glUseProgram(c)?;
    let kc = gl.glGetUniformLocation(c, Text::borrowed("k"))?;
    gl.glUniform4f(kc, 0.0, 0.5, 0.0, 0.0)?;
    quad(gl, n, [-1.0, 0.0, 0.0, 0.375], [0.5, 0.25, 0.75, 1.0])?;
    let mut flipped = bin.clone();
    flipped[bin.len() * 2 / 3] ^= 0x01;
    load(gl, &mut marks, c, format, len, &flipped)?;
    quad(gl, n, [-0.5, 0.0, 0.0, 0.375], [0.75, 0.5, 0.25, 1.0])?;
    marks.push(gl.glGetError()?);
    gl.glUseProgram(b)?;
    quad(gl, n, [0.0, 0.0, 1.0, 0.375], [1.0, 0.5, 1.0, 0.5])?;
    mark_all(gl, &marks)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "program_binary", run: program_binary, tol: DEFAULT, expects_error: false }]
}
