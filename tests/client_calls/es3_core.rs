//! ES 3.0's core names for what ES 2.0 extensions gave, through the C entry points in an ES 3.0
//! context: vertex array objects (and ES 3.0's refusal of client arrays in one), instanced
//! draws from client arrays and indices, mapped ranges written, flushed (whole: what an unflushed
//! part holds is undefined, and Mesa and Strata differ there) and read back, draw and
//! read buffers of a framebuffer, a 3D image (and one read by `GL_UNPACK_IMAGE_HEIGHT` and
//! `GL_UNPACK_SKIP_IMAGES`), an occlusion query, and a 64-bit state query.

use super::*;

const TRIANGLES: u32 = 0x0004;
const FLOAT: u32 = 0x1406;
const UNSIGNED_BYTE: u32 = 0x1401;
const UNSIGNED_SHORT: u32 = 0x1403;
const RGBA: u32 = 0x1908;
const MAP_READ: u32 = 0x0001;
const MAP_WRITE: u32 = 0x0002;
const MAP_FLUSH_EXPLICIT: u32 = 0x0010;
const BUFFER_MAP_POINTER: u32 = 0x88BD;
const FRAMEBUFFER: u32 = 0x8D40;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const TEXTURE_2D: u32 = 0x0DE1;
const UNPACK_IMAGE_HEIGHT: u32 = 0x806E;
const UNPACK_SKIP_IMAGES: u32 = 0x806D;
const UNPACK_SKIP_ROWS: u32 = 0x0CF3;
const TEXTURE_3D: u32 = 0x806F;
const ANY_SAMPLES_PASSED: u32 = 0x8C2F;
const QUERY_RESULT: u32 = 0x8866;
const MAJOR_VERSION: u32 = 0x821B;
const COPY_READ: u32 = 0x8F36;
const COPY_WRITE: u32 = 0x8F37;
const UNSIGNED_INT_2_10_10_10_REV: u32 = 0x8368;

/// Instances side by side, coloured by their number; vertex positions from attribute 0.
const VS_INSTANCES: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    out vec4 c;
    void main() {
        c = vec4(float(gl_InstanceID) / 3.0, 0.5, 1.0, 1.0);
        gl_Position = vec4(pos.x * 0.25 - 0.75 + float(gl_InstanceID) * 0.5, pos.y, 0.0, 1.0);
    }";
const FS_VARY: &str = "#version 300 es
    precision mediump float; in vec4 c; out vec4 o; void main() { o = c; }";
/// A colour per vertex from location 1.
const VS_COLORED: &str = "#version 300 es
    layout(location = 0) in vec2 pos; layout(location = 1) in vec4 col; out vec4 c;
    void main() { c = col; gl_Position = vec4(pos, 0.0, 1.0); }";
/// Instances placed by a per-instance attribute (location 1) rather than by their number.
const VS_PLACED: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    layout(location = 1) in vec2 offset;
    out vec4 c;
    void main() {
        c = vec4(offset.x > 0.0 ? 1.0 : 0.0, offset.x < -0.5 ? 1.0 : 0.0, 1.0, 1.0);
        gl_Position = vec4(pos * 0.25 + offset, 0.0, 1.0);
    }";
/// Two outputs: the first red, the second the vertex colour.
const FS_TWO: &str = "#version 300 es
    precision mediump float; in vec4 c;
    layout(location = 0) out vec4 a; layout(location = 1) out vec4 b;
    void main() { a = vec4(1.0, 0.0, 0.0, 1.0); b = c; }";
/// A 3D image's middle slice over the window.
const VS_UV: &str = "#version 300 es
    layout(location = 0) in vec2 pos; out vec2 uv;
    void main() { uv = pos * 0.5 + 0.5; gl_Position = vec4(pos, 0.0, 1.0); }";
const FS_3D: &str = "#version 300 es
    precision mediump float; precision lowp sampler3D; uniform sampler3D s; in vec2 uv; out vec4 o;
    void main() { o = texture(s, vec3(uv, 0.5)); }";

/// Compiles and uses a program of `vs` and `fs` (inputs at their layout locations).
fn program(r: &mut Run, vs: &str, fs: &str) {
    r.program(vs, fs);
}

/// Logs the 16×16 window's pixels at a few places.
fn pixels(r: &mut Run, what: &str) {
    let mut px = vec![0u8; 16 * 16 * 4];
    // SAFETY: a context is current; `px` holds the window's RGBA8 pixels.
    unsafe { (r.gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast()) };
    let at = |x: usize, y: usize| px[(y * 16 + x) * 4..(y * 16 + x) * 4 + 4].to_vec();
    r.note(&format!("{what}: {:?} {:?} {:?} {:?}", at(1, 8), at(5, 8), at(9, 8), at(12, 8)));
}

/// The ES 3.0 core-names sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls with a current context; every pointer holds what the call reads or
    // writes; client arrays outlive the draws that read them.
    unsafe {
        (gl.viewport)(0, 0, 16, 16);
        let mut v = -1i64;
        (gl.core_get_integer64v)(MAJOR_VERSION, &mut v);
        r.note(&format!("glGetInteger64v(GL_MAJOR_VERSION) = {v}"));

        // Vertex array objects, and ES 3.0's refusal of client arrays in one.
        let mut vao = 0;
        (gl.core_gen_vertex_arrays)(1, &mut vao);
        r.note(&format!("glIsVertexArray before binding: {}", (gl.core_is_vertex_array)(vao)));
        (gl.core_bind_vertex_array)(vao);
        r.note(&format!("glIsVertexArray bound: {}", (gl.core_is_vertex_array)(vao)));
        let tri: [f32; 6] = [-1.0, -1.0, 1.0, -1.0, 0.0, 1.0];
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, tri.as_ptr().cast());
        r.note("a client array in a vertex array object");
        let mut buf = 0;
        (gl.gen_buffers)(1, &mut buf);
        (gl.bind_buffer)(ARRAY, buf);
        (gl.buffer_data)(ARRAY, 24, tri.as_ptr().cast(), STATIC_DRAW);
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, std::ptr::null());
        (gl.enable_vertex_attrib_array)(0);
        program(r, VS_INSTANCES, FS_VARY);
        (gl.clear_color)(0.0, 0.0, 0.0, 1.0);
        (gl.clear)(0x4000);
        (gl.core_draw_arrays_instanced)(TRIANGLES, 0, 3, 4);
        pixels(r, "four instances from a buffer in a vertex array object");
        (gl.core_bind_vertex_array)(0);
        (gl.core_delete_vertex_arrays)(1, &vao);
        r.note(&format!("glIsVertexArray deleted: {}", (gl.core_is_vertex_array)(vao)));

        // Instanced draws from client arrays and client indices (vertex array 0).
        (gl.bind_buffer)(ARRAY, 0);
        let quad: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, quad.as_ptr().cast());
        // Vertex array 0's own attribute state: the object's enable went with it.
        (gl.enable_vertex_attrib_array)(0);
        (gl.clear)(0x4000);
        (gl.core_draw_arrays_instanced)(TRIANGLES, 0, 3, 2);
        pixels(r, "two instances from a client array");
        let indices: [u16; 6] = [0, 1, 2, 1, 3, 2];
        (gl.clear)(0x4000);
        (gl.core_draw_elements_instanced)(TRIANGLES, 6, UNSIGNED_SHORT, indices.as_ptr().cast(), 3);
        pixels(r, "three instances from client indices");
        (gl.clear)(0x4000);
        (gl.draw_range_elements)(TRIANGLES, 0, 3, 6, UNSIGNED_SHORT, indices.as_ptr().cast());
        pixels(r, "glDrawRangeElements from client indices");
        (gl.draw_range_elements)(TRIANGLES, 3, 0, 6, UNSIGNED_SHORT, indices.as_ptr().cast());
        r.note("glDrawRangeElements with end before start");

        // A client array with a divisor: one element per instance, which the library sends
        // as many of as the draw has instances.
        program(r, VS_PLACED, FS_VARY);
        let places: [f32; 6] = [-0.75, 0.0, -0.25, 0.0, 0.5, 0.0];
        (gl.vertex_attrib_pointer)(1, 2, FLOAT, 0, 0, places.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(1);
        (gl.core_vertex_attrib_divisor)(1, 1);
        (gl.clear)(0x4000);
        (gl.core_draw_arrays_instanced)(0x0005, 0, 4, 3);
        pixels(r, "three instances placed by a client array with divisor 1");
        (gl.core_vertex_attrib_divisor)(1, 2);
        (gl.clear)(0x4000);
        (gl.core_draw_elements_instanced)(TRIANGLES, 6, UNSIGNED_SHORT, indices.as_ptr().cast(), 4);
        pixels(r, "four indexed instances, two to each element (divisor 2)");
        (gl.core_vertex_attrib_divisor)(1, 0);
        (gl.disable_vertex_attrib_array)(1);
        program(r, VS_INSTANCES, FS_VARY);

        // A mapped range written, flushed in part, unmapped and read back.
        (gl.bind_buffer)(ARRAY, buf);
        let p = (gl.core_map_buffer_range)(ARRAY, 4, 16, MAP_WRITE | MAP_FLUSH_EXPLICIT);
        r.note(&format!("glMapBufferRange for writing: null {}", p.is_null()));
        if !p.is_null() {
            std::ptr::copy_nonoverlapping([7u8; 16].as_ptr(), p.cast::<u8>(), 16);
            let mut q: Ptr = std::ptr::null_mut();
            (gl.core_get_buffer_pointerv)(ARRAY, BUFFER_MAP_POINTER, &mut q);
            r.note(&format!("glGetBufferPointerv is the mapping: {}", q == p));
            (gl.core_flush_mapped_buffer_range)(ARRAY, 0, 16);
            r.note(&format!("glUnmapBuffer: {}", (gl.core_unmap_buffer)(ARRAY)));
        }
        let p = (gl.core_map_buffer_range)(ARRAY, 0, 24, MAP_READ);
        if !p.is_null() {
            let bytes = std::slice::from_raw_parts(p.cast::<u8>(), 24).to_vec();
            r.note(&format!("read back: {bytes:?}"));
            (gl.core_unmap_buffer)(ARRAY);
        }
        (gl.bind_buffer)(ARRAY, 0);

        // Copies between buffers: a range, then the errors; read back through a mapping.
        let mut bufs = [0u32; 2];
        (gl.gen_buffers)(2, bufs.as_mut_ptr());
        let source: Vec<u8> = (0..32).collect();
        for (k, &b) in bufs.iter().enumerate() {
            (gl.bind_buffer)(COPY_READ + k as u32, b);
            let data = if k == 0 { source.clone() } else { vec![0xEE; 32] };
            (gl.buffer_data)(COPY_READ + k as u32, 32, data.as_ptr().cast(), STATIC_DRAW);
        }
        (gl.copy_buffer_sub_data)(COPY_READ, COPY_WRITE, 4, 12, 8);
        r.note("glCopyBufferSubData of 8 bytes");
        for (read, write, size) in [(0, 40, 8), (-1, 0, 8), (30, 0, 4), (0, 0, -2)] {
            (gl.copy_buffer_sub_data)(COPY_READ, COPY_WRITE, read, write, size);
            r.note(&format!("a copy from {read} to {write} of {size}"));
        }
        (gl.bind_buffer)(COPY_WRITE, bufs[0]);
        (gl.copy_buffer_sub_data)(COPY_READ, COPY_WRITE, 0, 4, 8);
        r.note("an overlapping copy within one buffer");
        (gl.copy_buffer_sub_data)(COPY_READ, COPY_WRITE, 0, 16, 8);
        r.note("a copy within one buffer that does not overlap");
        (gl.copy_buffer_sub_data)(COPY_READ, 0x8892 + 0x10, 0, 0, 4);
        r.note("a copy to a target that is none");
        for (k, &b) in bufs.iter().enumerate() {
            (gl.bind_buffer)(COPY_WRITE, b);
            let mut size = -1i64;
            (gl.get_buffer_parameteri64v)(COPY_WRITE, 0x8764, &mut size);
            let p = (gl.core_map_buffer_range)(COPY_WRITE, 0, 32, MAP_READ);
            if !p.is_null() {
                let bytes = std::slice::from_raw_parts(p.cast::<u8>(), 32).to_vec();
                r.note(&format!("buffer {k} ({size} bytes) reads {bytes:?}"));
                (gl.core_unmap_buffer)(COPY_WRITE);
            }
        }

        // Two draw buffers of a framebuffer, each read through glReadBuffer.
        let mut tex = [0u32; 2];
        (gl.gen_textures)(2, tex.as_mut_ptr());
        let mut fb = 0;
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb);
        for (k, &t) in tex.iter().enumerate() {
            (gl.bind_texture)(TEXTURE_2D, t);
            (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 16, 16, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
            (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0 + k as u32, TEXTURE_2D, t, 0);
        }
        let both = [COLOR_ATTACHMENT0, COLOR_ATTACHMENT0 + 1];
        (gl.core_draw_buffers)(2, both.as_ptr());
        r.note("glDrawBuffers");
        program(r, VS_INSTANCES, FS_TWO);
        (gl.clear)(0x4000);
        (gl.core_draw_arrays_instanced)(TRIANGLES, 0, 4, 4);
        for k in 0..2 {
            (gl.core_read_buffer)(COLOR_ATTACHMENT0 + k);
            pixels(r, &format!("colour attachment {k}"));
        }
        (gl.core_read_buffer)(COLOR_ATTACHMENT0 + 8);
        r.note("glReadBuffer of an attachment past the limit");
        // Invalidation of a framebuffer object's attachments, and the errors.
        for (target, list) in [
            (FRAMEBUFFER, &[COLOR_ATTACHMENT0, 0x8D00, 0x821A][..]),
            (0x8CA8, &[COLOR_ATTACHMENT0 + 1][..]),
            (FRAMEBUFFER, &[0x1800][..]),
            (FRAMEBUFFER, &[COLOR_ATTACHMENT0 + 9][..]),
            (0x0DE1, &[COLOR_ATTACHMENT0][..]),
        ] {
            (gl.invalidate_framebuffer)(target, list.len() as i32, list.as_ptr());
            r.note(&format!("glInvalidateFramebuffer({target:#x}, {list:x?})"));
        }
        (gl.invalidate_sub_framebuffer)(FRAMEBUFFER, 1, [COLOR_ATTACHMENT0].as_ptr(), 0, 0, -1, 4);
        r.note("glInvalidateSubFramebuffer with a negative width");
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);
        let back = [0x1800, 0x1801, 0x1802];
        (gl.invalidate_sub_framebuffer)(FRAMEBUFFER, 3, back.as_ptr(), 0, 0, 8, 8);
        r.note("glInvalidateSubFramebuffer of the default framebuffer's buffers");
        (gl.invalidate_framebuffer)(FRAMEBUFFER, 1, [COLOR_ATTACHMENT0].as_ptr());
        r.note("glInvalidateFramebuffer of an attachment the default framebuffer has not");

        // A 3D image through the core name.
        let mut t3 = 0;
        (gl.gen_textures)(1, &mut t3);
        (gl.bind_texture)(TEXTURE_3D, t3);
        let texels: Vec<u8> = (0..2 * 2 * 3 * 4).map(|i: u32| (i * 29 + 5) as u8).collect();
        (gl.core_tex_image_3d)(TEXTURE_3D, 0, RGBA as i32, 2, 2, 3, 0, RGBA, UNSIGNED_BYTE, texels.as_ptr().cast());
        (gl.tex_parameteri)(TEXTURE_3D, 0x2801, 0x2600);
        (gl.tex_parameteri)(TEXTURE_3D, 0x2800, 0x2600);
        r.note("glTexImage3D");
        program(r, VS_UV, FS_3D);
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, quad.as_ptr().cast());
        (gl.draw_arrays)(0x0005, 0, 4);
        pixels(r, "the 3D image's middle slice");
        // Its slices laid out three rows apart after one skipped image and one skipped row.
        (gl.pixel_store_i)(UNPACK_IMAGE_HEIGHT, 3);
        (gl.pixel_store_i)(UNPACK_SKIP_IMAGES, 1);
        (gl.pixel_store_i)(UNPACK_SKIP_ROWS, 1);
        let spaced: Vec<u8> = (0..128u32).map(|i| (i * 41 + 7) as u8).collect();
        (gl.core_tex_image_3d)(TEXTURE_3D, 0, RGBA as i32, 2, 2, 3, 0, RGBA, UNSIGNED_BYTE, spaced.as_ptr().cast());
        (gl.draw_arrays)(0x0005, 0, 4);
        pixels(r, "a 3D image read by image height, skipped images and rows");
        for p in [UNPACK_IMAGE_HEIGHT, UNPACK_SKIP_IMAGES, UNPACK_SKIP_ROWS] {
            (gl.pixel_store_i)(p, 0);
        }

        // An occlusion query around a draw that passes samples.
        let mut q = 0;
        (gl.core_gen_queries)(1, &mut q);
        (gl.core_begin_query)(ANY_SAMPLES_PASSED, q);
        (gl.draw_arrays)(0x0005, 0, 4);
        (gl.core_end_query)(ANY_SAMPLES_PASSED);
        let mut result = 7;
        (gl.core_get_query_object_uiv)(q, QUERY_RESULT, &mut result);
        r.note(&format!("glGetQueryObjectuiv(GL_QUERY_RESULT) = {result}, glIsQuery {}", (gl.core_is_query)(q)));
        (gl.core_delete_queries)(1, &q);

        // A colour from a client array of a packed type: the library sends four bytes a vertex.
        program(r, VS_COLORED, FS_VARY);
        let packed: Vec<u8> = [(1023u32, 300u32, 0u32, 3u32), (0, 700, 1023, 1), (512, 512, 512, 2), (90, 0, 900, 0)]
            .iter()
            .flat_map(|&(x, y, z, w)| (x | (y << 10) | (z << 20) | (w << 30)).to_ne_bytes())
            .collect();
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, quad.as_ptr().cast());
        (gl.vertex_attrib_pointer)(1, 4, UNSIGNED_INT_2_10_10_10_REV, 1, 0, packed.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(1);
        (gl.draw_arrays)(0x0005, 0, 4);
        pixels(r, "a packed client array's colours");
        (gl.disable_vertex_attrib_array)(1);
        let _ = indices;
    }
}
