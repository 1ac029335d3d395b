//! The hand-written entry points: everything that marshals pointers or keeps client state
//! (arrays and strings in and out, client-side vertex and index arrays, buffer shadows,
//! client-allocated object names).

use std::ffi::{c_void, CStr};

use strata_protocol::{Blob, Calls, Slice, Text};

use super::draws::{self, draw_elements};
use super::pixel_buffer::{self, PIXEL_PACK_BUFFER_NV, PIXEL_UNPACK_BUFFER_NV};
use super::pixels::{read_pixels, tex_image_bytes};
use super::{
    bytes, c_name, intern, put, send_client_arrays, sized_bytes, uses_client_arrays, values, with_gl, write_out, Call,
    ShowArg,
};
use crate::gl_state::ClientArray;
use crate::state::{self, process};
use crate::surface::follow_current_window;
use crate::types::*;

crate::entry::entry_points! {
    /// The shim's own error first (including `GL_CONTEXT_LOST`), then the daemon's.
    fn glGetError() -> GLenum {
        let Some(cur) = state::current() else { return GL_NO_ERROR };
        let pending = || process().contexts.get_mut(&cur.context).map_or(GL_NO_ERROR, |c| c.gl.take_error());
        let (e, live) = (pending(), process().live_context(cur.context).is_some());
        if e != GL_NO_ERROR || !live {
            return e;
        }
        // A loss this call runs into is reported by this call.
        match with_gl("glGetError", GL_NO_ERROR, |gl| gl.conn.glGetError()) {
            GL_NO_ERROR => pending(),
            e => e,
        }
    }

    /// Forwarded after following the draw surface's window, which applications resize
    /// before they set a viewport for the new size.
    fn glViewport(x: GLint, y: GLint, width: GLsizei, height: GLsizei) {
        if state::current().is_some() {
            follow_current_window(&mut process());
        }
        with_gl("glViewport", (), |gl| gl.conn.glViewport(x, y, width, height))
    }

    /// Strings live for the rest of the process; `GL_EXTENSIONS` adds the shim's own.
    fn glGetString(name: GLenum) -> *const GLubyte {
        with_gl("glGetString", std::ptr::null(), |gl| {
            Ok(match gl.conn.glGetString(name)? {
                Some(s) => intern(s),
                None => std::ptr::null(),
            })
        })
    }

    /// ES 3.0: one extension by index; as long-lived as `glGetString`'s strings.
    fn glGetStringi(name: GLenum, index: GLuint) -> *const GLubyte {
        with_gl("glGetStringi", std::ptr::null(), |gl| {
            Ok(match gl.conn.glGetStringi(name, index)? {
                Some(s) => intern(s),
                None => std::ptr::null(),
            })
        })
    }

    /// Booleans as `GLboolean`s.
    fn glGetBooleanv(pname: GLenum, params: *mut GLboolean) {
        with_gl(Call { name: "glGetBooleanv", args: &|| pname.show() }, (), |gl| {
            let v: Vec<GLboolean> = gl.conn.glGetBooleanv(pname)?.into_iter().map(GLboolean::from).collect();
            // SAFETY: the caller's array has room for what the query returns.
            unsafe { write_out(params, &v) };
            Ok(())
        })
    }

    /// One value, the mapping's included (the daemon keeps it).
    fn glGetBufferParameteriv(target: GLenum, pname: GLenum, params: *mut GLint) {
        with_gl("glGetBufferParameteriv", (), |gl| {
            let v = gl.conn.glGetBufferParameteriv(target, pname)?;
            // SAFETY: `params` points at one GLint.
            unsafe { put(params, v) };
            Ok(())
        })
    }

    /// The application's pointer for client-side arrays, the offset for buffer-backed ones.
    fn glGetVertexAttribPointerv(index: GLuint, pname: GLenum, pointer: *mut *mut c_void) {
        with_gl("glGetVertexAttribPointerv", (), |gl| {
            let v = gl.conn.glGetVertexAttribPointerv(index, pname)?;
            // SAFETY: `pointer` points at one pointer.
            unsafe { put(pointer, v as usize as *mut c_void) };
            Ok(())
        })
    }

    /// Range and precision of a shader number format.
    fn glGetShaderPrecisionFormat(shadertype: GLenum, precisiontype: GLenum, range: *mut GLint, precision: *mut GLint) {
        with_gl("glGetShaderPrecisionFormat", (), |gl| {
            let (r, p) = gl.conn.glGetShaderPrecisionFormat(shadertype, precisiontype)?;
            // SAFETY: `range` has room for two GLints, `precision` for one.
            unsafe {
                write_out(range, &r);
                put(precision, p);
            }
            Ok(())
        })
    }

    /// At most `max_count` shader names.
    fn glGetAttachedShaders(program: GLuint, max_count: GLsizei, count: *mut GLsizei, shaders: *mut GLuint) {
        with_gl("glGetAttachedShaders", (), |gl| {
            if max_count < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            let v = gl.conn.glGetAttachedShaders(program)?;
            let n = v.len().min(max_count as usize);
            // SAFETY: `shaders` has room for `max_count` names.
            unsafe {
                write_out(shaders, &v[..n]);
                put(count, n as GLsizei);
            }
            Ok(())
        })
    }

    /// Location of a named attribute.
    fn glGetAttribLocation(program: GLuint, name: *const GLchar) -> GLint {
        with_gl("glGetAttribLocation", -1, |gl| {
            // SAFETY: `name` is NUL-terminated.
            match unsafe { c_name(name) } {
                Some(n) => gl.conn.glGetAttribLocation(program, Text::borrowed(n)),
                None => Ok(-1),
            }
        })
    }

    /// Location of a named uniform.
    fn glGetUniformLocation(program: GLuint, name: *const GLchar) -> GLint {
        with_gl("glGetUniformLocation", -1, |gl| {
            // SAFETY: `name` is NUL-terminated.
            match unsafe { c_name(name) } {
                Some(n) => gl.conn.glGetUniformLocation(program, Text::borrowed(n)),
                None => Ok(-1),
            }
        })
    }

    /// Binds an attribute name to a location.
    fn glBindAttribLocation(program: GLuint, index: GLuint, name: *const GLchar) {
        with_gl("glBindAttribLocation", (), |gl| {
            // SAFETY: `name` is NUL-terminated.
            match unsafe { c_name(name) } {
                Some(n) => gl.conn.glBindAttribLocation(program, index, Text::borrowed(n)),
                None => {
                    gl.st.err(GL_INVALID_VALUE);
                    Ok(())
                }
            }
        })
    }

    /// Joins the application's strings into one source.
    fn glShaderSource(shader: GLuint, count: GLsizei, string: *const *const GLchar, length: *const GLint) {
        with_gl("glShaderSource", (), |gl| {
            if count < 0 || (count > 0 && string.is_null()) {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            let mut source = Vec::new();
            for i in 0..count as usize {
                // SAFETY: `string` has `count` entries, and `length` (if non-null) too.
                let (s, len) = unsafe { (*string.add(i), if length.is_null() { -1 } else { *length.add(i) }) };
                if s.is_null() {
                    continue;
                }
                if len < 0 {
                    // SAFETY: without a length the string is NUL-terminated.
                    source.extend_from_slice(unsafe { CStr::from_ptr(s) }.to_bytes());
                } else {
                    // SAFETY: with a length the string has that many bytes.
                    source.extend_from_slice(unsafe { bytes(s.cast(), len as usize) });
                }
            }
            let source = String::from_utf8_lossy(&source);
            gl.conn.glShaderSource(shader, Text::borrowed(&source))
        })
    }

    /// Not supported by the daemon (no binary formats); sent so that it reports the error.
    fn glShaderBinary(n: GLsizei, shaders: *const GLuint, binaryformat: GLenum, binary: *const c_void, length: GLsizei) {
        with_gl("glShaderBinary", (), |gl| {
            if n < 0 || length < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: `shaders` has `n` names and `binary` `length` bytes.
            let (s, b) = unsafe { (values(shaders, i64::from(n)), bytes(binary, length as usize)) };
            gl.conn.glShaderBinary(Slice::new(s), binaryformat, Blob::borrowed(b))
        })
    }

    /// A shader name allocated here (0 for an invalid type).
    fn glCreateShader(shader_type: GLenum) -> GLuint {
        with_gl("glCreateShader", 0, |gl| {
            if !matches!(shader_type, 0x8B30 | 0x8B31) {
                gl.st.err(GL_INVALID_ENUM);
                return Ok(0);
            }
            let name = gl.names(1)[0];
            gl.conn.glCreateShader(shader_type, name)?;
            Ok(name)
        })
    }

    /// A program name allocated here.
    fn glCreateProgram() -> GLuint {
        with_gl("glCreateProgram", 0, |gl| {
            let name = gl.names(1)[0];
            gl.conn.glCreateProgram(name)?;
            Ok(name)
        })
    }

    /// Buffer names allocated here.
    fn glGenBuffers(n: GLsizei, buffers: *mut GLuint) {
        with_gl("glGenBuffers", (), |gl| {
            if n < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            if buffers.is_null() {
                return Ok(());
            }
            let new = gl.names(n as usize);
            // SAFETY: the application's array has room for `n` names.
            unsafe { write_out(buffers, &new) };
            gl.conn.glGenBuffers(Slice::new(&new))
        })
    }

    /// Forgets the buffers' shadows and bindings too.
    fn glDeleteBuffers(n: GLsizei, buffers: *const GLuint) {
        with_gl("glDeleteBuffers", (), |gl| {
            if n < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: the application passes `n` names.
            let v = unsafe { values(buffers, i64::from(n)) };
            for &b in v.iter().filter(|&&b| b != 0) {
                gl.shadows.remove(&b);
                gl.maps.remove(&b);
                if gl.st.array_buffer == b {
                    gl.st.array_buffer = 0;
                }
                if gl.st.element_buffer == b {
                    gl.st.element_buffer = 0;
                }
                if gl.st.pack_buffer == b {
                    gl.st.pack_buffer = 0;
                }
                if gl.st.unpack_buffer == b {
                    gl.st.unpack_buffer = 0;
                }
                if gl.st.uniform_buffer == b {
                    gl.st.uniform_buffer = 0;
                }
                for c in gl.st.copy_buffers.iter_mut().filter(|c| **c == b) {
                    *c = 0;
                }
                if gl.st.xfb_buffer == b {
                    gl.st.xfb_buffer = 0;
                }
            }
            gl.conn.glDeleteBuffers(Slice::new(v))
        })
    }

    /// Tracks the array and element bindings (client arrays and index ranges need them), and
    /// the pixel pack and unpack bindings (`GL_NV_pixel_buffer_object`).
    fn glBindBuffer(target: GLenum, buffer: GLuint) {
        with_gl("glBindBuffer", (), |gl| {
            match target {
                GL_ARRAY_BUFFER => gl.st.array_buffer = buffer,
                GL_ELEMENT_ARRAY_BUFFER => gl.st.element_buffer = buffer,
                PIXEL_PACK_BUFFER_NV => gl.st.pack_buffer = buffer,
                PIXEL_UNPACK_BUFFER_NV => gl.st.unpack_buffer = buffer,
                GL_UNIFORM_BUFFER => gl.st.uniform_buffer = buffer,
                GL_COPY_READ_BUFFER => gl.st.copy_buffers[0] = buffer,
                GL_COPY_WRITE_BUFFER => gl.st.copy_buffers[1] = buffer,
                GL_TRANSFORM_FEEDBACK_BUFFER => gl.st.xfb_buffer = buffer,
                _ => {}
            }
            gl.conn.glBindBuffer(target, buffer)
        })
    }

    /// Copies `size` bytes (or allocates), keeping a shadow of the contents.
    fn glBufferData(target: GLenum, size: GLsizeiptr, data: *const c_void, usage: GLenum) {
        with_gl("glBufferData", (), |gl| {
            // SAFETY: a non-null `data` holds `size` bytes.
            let Some(d) = (unsafe { sized_bytes(gl.st, data, size) }) else { return Ok(()) };
            if let Some(b) = gl.st.bound(target).filter(|&b| b != 0) {
                // New contents end a mapping.
                gl.maps.remove(&b);
                let shadow = if data.is_null() { vec![0; size as usize] } else { d.to_vec() };
                gl.shadows.insert(b, shadow);
            }
            let blob = (!data.is_null()).then(|| Blob::borrowed(d));
            gl.conn.glBufferData(target, size as i64, blob, usage)
        })
    }

    /// Copies `size` bytes at `offset`, updating the shadow.
    fn glBufferSubData(target: GLenum, offset: GLintptr, size: GLsizeiptr, data: *const c_void) {
        with_gl("glBufferSubData", (), |gl| {
            if size < 0 || offset < 0 || (size > 0 && data.is_null()) {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: `data` holds `size` bytes.
            let d = unsafe { bytes(data, size as usize) };
            if let Some(shadow) = gl.st.bound(target).and_then(|b| gl.shadows.get_mut(&b)) {
                if let Some(dst) = shadow.get_mut(offset as usize..offset as usize + d.len()) {
                    dst.copy_from_slice(d);
                }
            }
            gl.conn.glBufferSubData(target, offset as i64, Blob::borrowed(d))
        })
    }

    /// Tracks enabled arrays (client arrays are sent at draw time).
    fn glEnableVertexAttribArray(index: GLuint) {
        with_gl("glEnableVertexAttribArray", (), |gl| {
            if let Some(a) = gl.st.attribs.get_mut(index as usize) {
                a.enabled = true;
            }
            gl.conn.glEnableVertexAttribArray(index)
        })
    }

    /// Tracks enabled arrays.
    fn glDisableVertexAttribArray(index: GLuint) {
        with_gl("glDisableVertexAttribArray", (), |gl| {
            if let Some(a) = gl.st.attribs.get_mut(index as usize) {
                a.enabled = false;
            }
            gl.conn.glDisableVertexAttribArray(index)
        })
    }

    /// With no array buffer bound, `pointer` is a client-side array, copied at draw time.
    fn glVertexAttribPointer(
        index: GLuint,
        size: GLint,
        ty: GLenum,
        normalized: GLboolean,
        stride: GLsizei,
        pointer: *const c_void,
    ) {
        with_gl("glVertexAttribPointer", (), |gl| {
            let client = (gl.st.array_buffer == 0 && !pointer.is_null())
                .then_some(ClientArray { ptr: pointer as usize, size, ty, stride });
            // Only the default vertex array can hold a client array: the daemon refuses one
            // in another, and the state stays as it was.
            let refused = client.is_some() && gl.st.vertex_array != 0;
            if let Some(a) = gl.st.attribs.get_mut(index as usize).filter(|_| !refused) {
                a.client = client;
            }
            gl.conn.glVertexAttribPointer(index, size, ty, normalized != 0, stride, pointer as usize as u64)
        })
    }

    /// Sends the client arrays the draw reads, then the draw.
    fn glDrawArrays(mode: GLenum, first: GLint, count: GLsizei) {
        with_gl("glDrawArrays", (), |gl| {
            if first >= 0 && count > 0 && uses_client_arrays(gl.st) {
                send_client_arrays(gl, first as u64 + count as u64, 1)?;
            }
            gl.conn.glDrawArrays(mode, first, count)
        })
    }

    /// Indices from the bound element buffer, or a client-side index array sent along.
    fn glDrawElements(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void) {
        with_gl("glDrawElements", (), |gl| draw_elements(gl, mode, count, ty, indices, draws::Extra::None))
    }

    /// Tracks the unpack state (upload sizes depend on it).
    fn glPixelStorei(pname: GLenum, param: GLint) {
        with_gl("glPixelStorei", (), |gl| {
            if pname == GL_UNPACK_ALIGNMENT && matches!(param, 1 | 2 | 4 | 8) {
                gl.st.unpack_alignment = param as usize;
            }
            // UNPACK_ROW_LENGTH_EXT, UNPACK_SKIP_ROWS_EXT, UNPACK_SKIP_PIXELS_EXT.
            if let (Some(i @ 0..=2), Ok(v)) = (pname.checked_sub(0x0CF2), usize::try_from(param)) {
                gl.st.unpack_rows[i as usize] = v;
            }
            // UNPACK_SKIP_IMAGES, UNPACK_IMAGE_HEIGHT (negative values are refused).
            if let (Some(i @ 0..=1), Ok(v)) = (pname.checked_sub(0x806D), usize::try_from(param)) {
                gl.st.unpack_images[1 - i as usize] = v;
            }
            // PACK_ALIGNMENT; NV_pack_subimage's PACK_ROW_LENGTH_NV, PACK_SKIP_ROWS_NV,
            // PACK_SKIP_PIXELS_NV; ANGLE_pack_reverse_row_order's byte.
            let pack = &mut gl.st.pack;
            match (pname, usize::try_from(param)) {
                (GL_PACK_ALIGNMENT, Ok(a @ (1 | 2 | 4 | 8))) => pack.alignment = a,
                (0x0D02..=0x0D04, Ok(v)) => pack.rows[(pname - 0x0D02) as usize] = v,
                (0x93A4, _) => pack.reverse = param as u8 != 0,
                _ => {}
            }
            gl.conn.glPixelStorei(pname, param)
        })
    }

    /// Copies the pixels an upload of this size, format and alignment reads.
    fn glTexImage2D(
        target: GLenum,
        level: GLint,
        internalformat: GLint,
        width: GLsizei,
        height: GLsizei,
        border: GLint,
        format: GLenum,
        ty: GLenum,
        pixels: *const c_void,
    ) {
        with_gl("glTexImage2D", (), |gl| {
            if let Some(from) = pixel_buffer::unpack_pixels(gl, pixels, [width, height], format, ty) {
                let Some(d) = from else { return Ok(()) };
                let data = Some(Blob::borrowed(&d));
                return gl.conn.glTexImage2D(target, level, internalformat, width, height, border, format, ty, data);
            }
            let data = tex_image_bytes(gl.st, width, height, format, ty, pixels).map(Blob::borrowed);
            gl.conn.glTexImage2D(target, level, internalformat, width, height, border, format, ty, data)
        })
    }

    /// Copies the pixels a sub-image upload reads.
    fn glTexSubImage2D(
        target: GLenum,
        level: GLint,
        xoffset: GLint,
        yoffset: GLint,
        width: GLsizei,
        height: GLsizei,
        format: GLenum,
        ty: GLenum,
        pixels: *const c_void,
    ) {
        with_gl("glTexSubImage2D", (), |gl| {
            if let Some(from) = pixel_buffer::unpack_pixels(gl, pixels, [width, height], format, ty) {
                let Some(d) = from else { return Ok(()) };
                let data = Blob::borrowed(&d);
                return gl.conn.glTexSubImage2D(target, level, xoffset, yoffset, width, height, format, ty, data);
            }
            let data = tex_image_bytes(gl.st, width, height, format, ty, pixels).unwrap_or(&[]);
            gl.conn.glTexSubImage2D(target, level, xoffset, yoffset, width, height, format, ty, Blob::borrowed(data))
        })
    }

    /// Copies `image_size` bytes.
    fn glCompressedTexImage2D(
        target: GLenum,
        level: GLint,
        internalformat: GLenum,
        width: GLsizei,
        height: GLsizei,
        border: GLint,
        image_size: GLsizei,
        data: *const c_void,
    ) {
        with_gl("glCompressedTexImage2D", (), |gl| {
            if let Some(from) = pixel_buffer::unpack(gl, data, image_size.max(0) as usize, 1) {
                let Some(d) = from else { return Ok(()) };
                let d = Blob::borrowed(&d);
                return gl.conn.glCompressedTexImage2D(target, level, internalformat, width, height, border, d);
            }
            if data.is_null() && image_size > 0 {
                // An image of undefined contents: as many zeros, so that the daemon checks the
                // size the application gave.
                let zeros = vec![0; image_size as usize];
                let d = Blob::borrowed(&zeros);
                return gl.conn.glCompressedTexImage2D(target, level, internalformat, width, height, border, d);
            }
            // SAFETY: `data` holds `image_size` bytes.
            let Some(d) = (unsafe { sized_bytes(gl.st, data, image_size as isize) }) else { return Ok(()) };
            gl.conn.glCompressedTexImage2D(target, level, internalformat, width, height, border, Blob::borrowed(d))
        })
    }

    /// Copies `image_size` bytes.
    fn glCompressedTexSubImage2D(
        target: GLenum,
        level: GLint,
        xoffset: GLint,
        yoffset: GLint,
        width: GLsizei,
        height: GLsizei,
        format: GLenum,
        image_size: GLsizei,
        data: *const c_void,
    ) {
        with_gl("glCompressedTexSubImage2D", (), |gl| {
            if let Some(from) = pixel_buffer::unpack(gl, data, image_size.max(0) as usize, 1) {
                let Some(d) = from else { return Ok(()) };
                let d = Blob::borrowed(&d);
                return gl.conn.glCompressedTexSubImage2D(target, level, xoffset, yoffset, width, height, format, d);
            }
            // SAFETY: `data` holds `image_size` bytes.
            let Some(d) = (unsafe { sized_bytes(gl.st, data, image_size as isize) }) else { return Ok(()) };
            gl.conn.glCompressedTexSubImage2D(
                target,
                level,
                xoffset,
                yoffset,
                width,
                height,
                format,
                Blob::borrowed(d),
            )
        })
    }

    /// One value, or four for `GL_TEXTURE_BORDER_COLOR_EXT`.
    fn glTexParameterfv(target: GLenum, pname: GLenum, params: *const GLfloat) {
        with_gl("glTexParameterfv", (), |gl| {
            // SAFETY: `params` holds as many values as `pname` takes.
            let v = unsafe { values(params, tex_parameter_count(pname)) };
            gl.conn.glTexParameterfv(target, pname, Slice::new(v))
        })
    }

    /// One value, or four for `GL_TEXTURE_BORDER_COLOR_EXT`.
    fn glTexParameteriv(target: GLenum, pname: GLenum, params: *const GLint) {
        with_gl("glTexParameteriv", (), |gl| {
            // SAFETY: `params` holds as many values as `pname` takes.
            let v = unsafe { values(params, tex_parameter_count(pname)) };
            gl.conn.glTexParameteriv(target, pname, Slice::new(v))
        })
    }

    /// One value, or four for `GL_TEXTURE_BORDER_COLOR_EXT`.
    fn glSamplerParameterfv(sampler: GLuint, pname: GLenum, params: *const GLfloat) {
        with_gl("glSamplerParameterfv", (), |gl| {
            // SAFETY: `params` holds as many values as `pname` takes.
            let v = unsafe { values(params, tex_parameter_count(pname)) };
            gl.conn.glSamplerParameterfv(sampler, pname, Slice::new(v))
        })
    }

    /// One value, or four for `GL_TEXTURE_BORDER_COLOR_EXT`.
    fn glSamplerParameteriv(sampler: GLuint, pname: GLenum, params: *const GLint) {
        with_gl("glSamplerParameteriv", (), |gl| {
            // SAFETY: `params` holds as many values as `pname` takes.
            let v = unsafe { values(params, tex_parameter_count(pname)) };
            gl.conn.glSamplerParameteriv(sampler, pname, Slice::new(v))
        })
    }

    /// Writes the rows the daemon returns, already laid out with `GL_PACK_ALIGNMENT`.
    fn glReadPixels(
        x: GLint,
        y: GLint,
        width: GLsizei,
        height: GLsizei,
        format: GLenum,
        ty: GLenum,
        pixels: *mut c_void,
    ) {
        with_gl("glReadPixels", (), |gl| {
            if pixel_buffer::pack(gl, [x, y, width, height], format, ty, pixels)? {
                return Ok(());
            }
            // SAFETY: `pixels` has room for the rectangle as the pack state lays it out.
            unsafe { read_pixels(gl, [x, y, width, height], format, ty, pixels, None) }
        })
    }
}

/// How many values `glTexParameter{f,i}v` and `glSamplerParameter{f,i}v` read for `pname`.
fn tex_parameter_count(pname: GLenum) -> i64 {
    if pname == 0x1004 {
        4 // GL_TEXTURE_BORDER_COLOR_EXT
    } else {
        1
    }
}
