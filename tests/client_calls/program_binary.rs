//! `GL_OES_get_program_binary` through the C entry points: where the library writes the
//! length (0 before most errors, nothing for a bad name or a negative size), the bytes it
//! writes and leaves alone, a NULL length pointer, loads from NULL, and a loaded copy drawing.

use super::*;

const PROGRAM_BINARY_LENGTH: u32 = 0x8741;
const PROGRAM_BINARY_FORMATS: u32 = 0x87FF;
const LINK_STATUS: u32 = 0x8B82;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;

const VS: &str = "attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }";
const FS: &str = "precision mediump float; void main() { gl_FragColor = vec4(1.0, 0.5, 0.25, 1.0); }";

/// Bytes past the binary, which the library must leave alone.
const SENTINEL: u8 = 0xA5;

impl Run {
    /// Calls `glGetProgramBinaryOES` with room for `size` bytes (and `room` really there);
    /// logs the length written (a positive one as whether it is `room`), whether the format
    /// is the one offered, and the error.
    fn get_binary(&mut self, what: &str, program: u32, size: i32, room: usize, offered: u32) -> Vec<u8> {
        let mut buf = vec![SENTINEL; room + 8];
        let (mut len, mut format) = (-5i32, 7u32);
        // SAFETY: a context is current; `buf` holds `room` bytes and more.
        unsafe { (self.gl.get_program_binary)(program, size, &mut len, &mut format, buf.as_mut_ptr().cast()) };
        let kept = buf.iter().skip(len.max(0) as usize).all(|&b| b == SENTINEL);
        let written = buf.iter().take(len.max(0) as usize).any(|&b| b != SENTINEL);
        let format = if format == 7 { "untouched".to_string() } else { format!("offered {}", format == offered) };
        let length = if len > 0 { format!("the binary's {}", len as usize == room) } else { len.to_string() };
        self.note(&format!("{what}: length {length}, format {format}, written {written}, rest untouched {kept}"));
        buf.truncate(len.max(0) as usize);
        buf
    }

    /// Calls `glProgramBinaryOES`; logs the error and the link status.
    fn load_binary(&mut self, what: &str, program: u32, format: u32, binary: Option<&[u8]>, length: i32) {
        let p = binary.map_or(std::ptr::null(), |b| b.as_ptr().cast());
        // SAFETY: a context is current; `binary` holds `length` bytes, or is NULL.
        unsafe { (self.gl.program_binary)(program, format, p, length) };
        let mut status = -1;
        // SAFETY: as above.
        unsafe { (self.gl.get_programiv)(program, LINK_STATUS, &mut status) };
        self.note(&format!("{what}: link status {status}"));
    }
}

/// The program-binary sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    let p = r.program(VS, FS);
    // SAFETY: GL calls on the current context; every out-pointer has room.
    unsafe {
        let mut formats = [-1i32; 4];
        (gl.get_integerv)(PROGRAM_BINARY_FORMATS, formats.as_mut_ptr());
        let offered = formats[0] as u32;
        let mut len = -1;
        (gl.get_programiv)(p, PROGRAM_BINARY_LENGTH, &mut len);
        r.note(&format!("length above 16: {}", len > 16));
        let room = len.max(0) as usize;
        r.get_binary("one byte short", p, len - 1, room, offered);
        r.get_binary("negative size", p, -1, room, offered);
        r.get_binary("no such program", 0xBAD, len, room, offered);
        let unlinked = (gl.create_program)();
        r.get_binary("unlinked", unlinked, len, room, offered);
        let binary = r.get_binary("exact size", p, len, room, offered);
        r.log.push(format!("as long as said: {}", binary.len() as i32 == len));
        r.get_binary("larger buffer", p, len + 8, room, offered);
        let mut buf = vec![SENTINEL; room];
        let mut format = 0u32;
        (gl.get_program_binary)(p, len, std::ptr::null_mut(), &mut format, buf.as_mut_ptr().cast());
        r.note(&format!("no length pointer: the same bytes {}", buf == binary));

        let q = (gl.create_program)();
        r.load_binary("NULL, length 0", q, offered, None, 0);
        r.load_binary("NULL, length -1", q, offered, None, -1);
        r.load_binary("half of it", q, offered, Some(&binary), len / 2);
        r.load_binary("all of it", q, offered, Some(&binary), len);
        (gl.use_program)(q);
        (gl.viewport)(0, 0, 4, 4);
        (gl.clear_color)(0.0, 0.0, 0.0, 0.0);
        (gl.clear)(0x4000);
        let quad: [f32; 12] = [-1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0, -1.0, 1.0, 1.0, -1.0, 1.0];
        (gl.bind_buffer)(ARRAY, 0);
        (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 0, quad.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(0);
        (gl.draw_arrays)(0x0004, 0, 6);
        let mut px = [0u8; 4];
        (gl.read_pixels)(1, 1, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        r.note(&format!("the copy draws {px:?}"));
    }
}
