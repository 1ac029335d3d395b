//! `GL_EXT_debug_label`: labels set and read back on every kind of object an ES 2.0 context
//! has, under the extension's type names and `GL_KHR_debug`'s, and the calls' errors (objects
//! that do not exist, unknown types, negative lengths and sizes, labels too long), drawn as
//! colours.

use super::multi_draw::mark_all;
use super::*;

const BUFFER_OBJECT_EXT: u32 = 0x9151;
const SHADER_OBJECT_EXT: u32 = 0x8B48;
const PROGRAM_OBJECT_EXT: u32 = 0x8B40;
const VERTEX_ARRAY_OBJECT_EXT: u32 = 0x9154;
const QUERY_OBJECT_EXT: u32 = 0x9153;
const PROGRAM_PIPELINE_OBJECT_EXT: u32 = 0x8A4F;
const BUFFER_KHR: u32 = 0x82E0;
const TEXTURE: u32 = 0x1702;

/// A mark for a label read back: its length, and its last byte in the high bits; or the
/// error, where the read failed.
fn label_mark(gl: Gl<'_>, ty: u32, object: u32, buf_size: i32) -> Result<u32, ClientError> {
    let label = gl.glGetObjectLabelEXT(ty, object, buf_size)?;
    let e = gl.glGetError()?;
    Ok(match label {
        Some(l) if e == 0 => l.0.len() as u32 | u32::from(l.0.last().copied().unwrap_or(0)) << 8,
        _ => e,
    })
}

fn debug_label(gl: Gl<'_>, n: &mut Names) -> R {
    let (buffer, texture, renderbuffer, framebuffer, vao) = (n.next(), n.next(), n.next(), n.next(), n.next());
    gl.glGenBuffers(Slice::new(&[buffer]))?;
    gl.glBindBuffer(ARRAY_BUFFER, buffer)?;
    gl.glGenTextures(Slice::new(&[texture]))?;
    gl.glBindTexture(TEXTURE_2D, texture)?;
    gl.glGenRenderbuffers(Slice::new(&[renderbuffer]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, renderbuffer)?;
    gl.glGenFramebuffers(Slice::new(&[framebuffer]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, framebuffer)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glGenVertexArraysOES(Slice::new(&[vao]))?;
    gl.glBindVertexArrayOES(vao)?;
    gl.glBindVertexArrayOES(0)?;
    let program = self::program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    let shader = program + 1;
    let objects = [
        (BUFFER_OBJECT_EXT, buffer, 0, "vertices"),
        (TEXTURE, texture, 4, "albedo map"),
        (RENDERBUFFER, renderbuffer, 0, "depth"),
        (FRAMEBUFFER, framebuffer, 6, "shadow pass"),
        (SHADER_OBJECT_EXT, shader, 0, "vertex stage"),
        (PROGRAM_OBJECT_EXT, program, 3, "lit"),
        (VERTEX_ARRAY_OBJECT_EXT, vao, 0, "mesh"),
        (BUFFER_KHR, buffer, 2, "relabelled"),
    ];
    let mut marks = Vec::new();
    for (ty, object, length, label) in objects {
        gl.glLabelObjectEXT(ty, object, length, Some(Blob::borrowed(label.as_bytes())))?;
        marks.push(gl.glGetError()?);
        marks.push(label_mark(gl, ty, object, 64)?);
    }
    // A label removed by an empty one, and by none.
    gl.glLabelObjectEXT(TEXTURE, texture, 0, Some(Blob::borrowed(b"")))?;
    marks.push(label_mark(gl, TEXTURE, texture, 64)?);
    gl.glLabelObjectEXT(FRAMEBUFFER, framebuffer, 0, None)?;
    marks.push(label_mark(gl, FRAMEBUFFER, framebuffer, 64)?);
    // Errors: objects that do not exist, kinds with no objects, an unknown type, a negative
    // length or size, a label of 256 bytes.
    let long = vec![b'a'; 256];
    let bad: [(u32, u32, i32, &[u8]); 7] = [
        (BUFFER_OBJECT_EXT, 999, 0, b"x"),
        (VERTEX_ARRAY_OBJECT_EXT, 0, 0, b"x"),
        (QUERY_OBJECT_EXT, 1, 0, b"x"),
        (PROGRAM_PIPELINE_OBJECT_EXT, 1, 0, b"x"),
        (0x1234, buffer, 0, b"x"),
        (BUFFER_OBJECT_EXT, buffer, -1, b"x"),
        (BUFFER_OBJECT_EXT, buffer, 0, &long),
    ];
    for (ty, object, length, label) in bad {
        gl.glLabelObjectEXT(ty, object, length, Some(Blob::borrowed(label)))?;
        marks.push(gl.glGetError()?);
        // After a refused length, Mesa's label is not what the call had left (it drops the
        // old label, or keeps part of the new one); GL says a call in error changes nothing.
        if length == 0 && label.len() < 256 {
            marks.push(label_mark(gl, ty, object, 64)?);
        }
    }
    marks.push(label_mark(gl, BUFFER_OBJECT_EXT, buffer, -1)?);
    mark_all(gl, &marks)?;
    Ok(())
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "debug_label", run: debug_label, tol: DEFAULT, expects_error: false }]
}
