//! `GL_OES_mapbuffer` and `GL_EXT_map_buffer_range`: maps, writes, flushes, unmaps, the
//! mapping queries, and draws from vertices written through maps.

use super::*;

const WRITE_ONLY: u32 = 0x88B9;
const MAPPED: u32 = 0x88BC;
const ACCESS: u32 = 0x88BB;
const ACCESS_FLAGS: u32 = 0x911F;
const MAP_LENGTH: u32 = 0x9120;
const MAP_OFFSET: u32 = 0x9121;
const MAP_POINTER: u32 = 0x88BD;
const READ: u32 = 0x1;
const WRITE: u32 = 0x2;
const INVALIDATE_RANGE: u32 = 0x4;
const INVALIDATE_BUFFER: u32 = 0x8;
const FLUSH_EXPLICIT: u32 = 0x10;

/// Colour from an attribute.
const VS_COLOR: &str = "attribute vec2 pos; attribute vec4 color; varying vec4 v; \
                        void main() { v = color; gl_Position = vec4(pos, 0.0, 1.0); }";
/// The interpolated colour.
const FS_COLOR: &str = "precision mediump float; varying vec4 v; void main() { gl_FragColor = v; }";

impl Run {
    /// Logs the buffer parameters of the array buffer.
    fn params(&mut self, when: &str) {
        for (name, pname) in [
            ("mapped", MAPPED),
            ("access", ACCESS),
            ("flags", ACCESS_FLAGS),
            ("length", MAP_LENGTH),
            ("offset", MAP_OFFSET),
        ] {
            let mut v = -7;
            // SAFETY: one GLint out.
            unsafe { (self.gl.get_buffer_parameteriv)(ARRAY, pname, &mut v) };
            self.log.push(format!("{when}: {name} = {v:#x}"));
        }
        self.note(&format!("{when}: parameters"));
    }

    /// Maps `len` bytes at `off` with `access` and logs the result: null or not, the pointer's
    /// alignment less the offset, whether it is the one `glGetBufferPointervOES` answers, and
    /// the bytes (for a map that reads).
    fn map_range(&mut self, off: isize, len: isize, access: u32) -> Ptr {
        // SAFETY: a context is current.
        let p = unsafe { (self.gl.map_range)(ARRAY, off, len, access) };
        self.mapped(&format!("map_range({off}, {len}, {access:#x})"), p, len, access & READ != 0);
        p
    }

    /// Logs a map's result (see [`Run::map_range`]).
    fn mapped(&mut self, what: &str, p: Ptr, len: isize, read: bool) {
        self.note(&format!("{what} null {}", p.is_null()));
        if p.is_null() {
            return;
        }
        let mut q: Ptr = std::ptr::null_mut();
        // SAFETY: one pointer out; a non-null map holds `len` bytes.
        unsafe { (self.gl.get_pointer)(ARRAY, MAP_POINTER, &mut q) };
        self.log.push(format!("  pointer: the same {}, off 64-byte alignment by {}", q == p, p as usize % 64));
        if read {
            // SAFETY: as above.
            let bytes = unsafe { std::slice::from_raw_parts(p as *const u8, len as usize) };
            self.log.push(format!("  bytes {bytes:?}"));
        }
    }

    /// Unmaps the array buffer and logs the answer.
    fn unmap(&mut self, what: &str) {
        // SAFETY: a context is current.
        let r = unsafe { (self.gl.unmap)(ARRAY) };
        self.note(&format!("unmap {what}: {r}"));
    }

    /// Reads the whole array buffer through a map that only reads.
    fn contents(&mut self, what: &str, len: isize) {
        self.log.push(format!("contents {what}:"));
        self.map_range(0, len, READ);
        self.unmap("after reading");
    }
}

/// A quad from `x0` to `x1` across the whole height, in one colour: six vertices of position
/// (2 floats) then colour (4 unsigned bytes), 12 bytes each.
fn quad(x0: f32, x1: f32, rgba: [u8; 4]) -> Vec<u8> {
    let mut v = Vec::new();
    for (x, y) in [(x0, -1.0f32), (x1, -1.0), (x1, 1.0), (x0, -1.0), (x1, 1.0), (x0, 1.0)] {
        v.extend(x.to_ne_bytes());
        v.extend(y.to_ne_bytes());
        v.extend(rgba);
    }
    v
}

/// The mapping sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    let init: Vec<u8> = (0..64).collect();
    // SAFETY: a context is current; every pointer passed holds what the call reads or writes,
    // and mapped pointers are used only within their mapped length while mapped.
    unsafe {
        let mut b = [0u32; 3];
        (gl.gen_buffers)(3, b.as_mut_ptr());
        // Nothing bound, no data store, accesses and targets that are not allowed.
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map with nothing bound", p, 0, false);
        (gl.bind_buffer)(ARRAY, b[0]);
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map of no data store", p, 0, false);
        (gl.buffer_data)(ARRAY, 64, init.as_ptr().cast(), STATIC_DRAW);
        for (what, target, access) in
            [("read only", ARRAY, 0x88B8), ("read-write", ARRAY, 0x88BA), ("bad target", 0x1234, WRITE_ONLY)]
        {
            let p = (gl.map)(target, access);
            r.mapped(&format!("map {what}"), p, 0, false);
        }
        r.params("before mapping");
        // The whole buffer, written in two places.
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map", p, 64, true);
        let again = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map again", again, 0, false);
        r.params("mapped");
        let mut q: Ptr = std::ptr::null_mut();
        (gl.get_pointer)(ARRAY, 0x1234, &mut q);
        r.note("pointer of a bad name");
        (gl.get_pointer)(0x1234, MAP_POINTER, &mut q);
        r.note("pointer of a bad target");
        (gl.buffer_sub_data)(ARRAY, 0, 4, init.as_ptr().cast());
        r.note("glBufferSubData while mapped");
        if !p.is_null() {
            *p.cast::<u8>().add(3) = 200;
            *p.cast::<u8>().add(60) = 0;
        }
        r.unmap("the map");
        r.unmap("again");
        let u = (gl.unmap)(0x1234);
        r.note(&format!("unmap of a bad target: {u}"));
        let mut q: Ptr = 1 as Ptr;
        (gl.get_pointer)(ARRAY, MAP_POINTER, &mut q);
        r.note(&format!("pointer after unmap: null {}", q.is_null()));
        r.params("unmapped");
        r.contents("after the whole-buffer map", 64);
        // Ranges in error, in Mesa's order of checks.
        for (off, len, access) in [
            (-1, 4, WRITE),
            (0, -1, WRITE),
            (0, 0, WRITE),
            (60, 8, WRITE),
            (0, 4, 0),
            (0, 4, READ | INVALIDATE_RANGE),
            (0, 4, READ | INVALIDATE_BUFFER),
            (0, 4, READ | 0x20),
            (0, 4, READ | FLUSH_EXPLICIT),
            (0, 4, WRITE | 0x40),
            (0, 4, WRITE | 0x80),
            (0, 4, WRITE | 0x100),
            (-1, 0, 0),
            (0, 0, 0x100),
            (60, 8, 0),
            (60, 8, READ | INVALIDATE_RANGE),
        ] {
            r.map_range(off, len, access);
        }
        // Explicit flushes: only the flushed bytes are written.
        let p = r.map_range(4, 8, WRITE | FLUSH_EXPLICIT);
        r.params("mapped for explicit flushes");
        for (off, len) in [(-1, 2), (0, -1), (0, 100), (6, 4), (0, 0)] {
            (gl.flush_range)(ARRAY, off, len);
            r.note(&format!("flush({off}, {len})"));
        }
        if !p.is_null() {
            *p.cast::<u8>() = 99;
            *p.cast::<u8>().add(7) = 98;
            (gl.flush_range)(ARRAY, 0, 1);
            r.note("flush(0, 1)");
            (gl.flush_range)(ARRAY, 7, 1);
            r.note("flush(7, 1)");
        }
        r.unmap("explicitly flushed");
        r.contents("after explicit flushes", 64);
        // A range that reads and writes, then one invalidated and rewritten whole (zeros too).
        let p = r.map_range(24, 8, READ | WRITE);
        r.params("mapped to read and write");
        if !p.is_null() {
            *p.cast::<u8>().add(1) = 7;
        }
        r.unmap("read and written");
        let p = r.map_range(8, 16, WRITE | INVALIDATE_RANGE);
        if !p.is_null() {
            std::ptr::write_bytes(p.cast::<u8>(), 0, 16);
            *p.cast::<u8>().add(15) = 5;
        }
        r.unmap("invalidated");
        r.map_range(0, 4, READ);
        r.params("mapped to read");
        (gl.flush_range)(ARRAY, 0, 1);
        r.note("flush of a map that reads");
        r.unmap("read only");
        r.params("after a map that reads");
        (gl.flush_range)(ARRAY, 0, 1);
        r.note("flush with nothing mapped");
        (gl.flush_range)(0x1234, 0, 1);
        r.note("flush of a bad target");
        r.contents("after the ranges", 64);
        // New contents and deletion end a mapping.
        r.map_range(0, 8, WRITE);
        (gl.buffer_data)(ARRAY, 32, std::ptr::null(), STATIC_DRAW);
        r.note("glBufferData while mapped");
        r.params("after glBufferData");
        r.map_range(0, 8, WRITE);
        (gl.delete_buffers)(1, b.as_ptr());
        r.note("glDeleteBuffers while mapped");
        (gl.bind_buffer)(ARRAY, b[1]);
        (gl.buffer_data)(ARRAY, 0, std::ptr::null(), STATIC_DRAW);
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map of an empty buffer", p, 0, false);
        r.unmap("never mapped");
        (gl.bind_buffer)(ARRAY, 0);
        let mut q: Ptr = 1 as Ptr;
        (gl.get_pointer)(ARRAY, MAP_POINTER, &mut q);
        r.note(&format!("pointer with nothing bound: untouched {}", q as usize == 1));
        r.map_range(0, 4, WRITE);
        // Vertices written through maps: the first draw keeps the vertices it was given when
        // the second draw's are written over them.
        r.program(VS_COLOR, FS_COLOR);
        (gl.viewport)(0, 0, 16, 16);
        (gl.clear_color)(0.0, 0.0, 1.0, 1.0);
        (gl.clear)(0x4000);
        (gl.bind_buffer)(ARRAY, b[2]);
        (gl.buffer_data)(ARRAY, 72, std::ptr::null(), 0x88E8);
        (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 12, std::ptr::null());
        (gl.vertex_attrib_pointer)(1, 4, 0x1401, 1, 12, 8 as *const c_void);
        (gl.enable_vertex_attrib_array)(0);
        (gl.enable_vertex_attrib_array)(1);
        for (x0, x1, rgba, access) in
            [(-1.0, 1.0, [255, 0, 0, 255], WRITE | INVALIDATE_BUFFER), (-1.0, 0.0, [0, 255, 0, 255], WRITE)]
        {
            let v = quad(x0, x1, rgba);
            let p = (gl.map_range)(ARRAY, 0, v.len() as isize, access);
            if !p.is_null() {
                std::ptr::copy_nonoverlapping(v.as_ptr(), p.cast::<u8>(), v.len());
            }
            r.unmap("vertices");
            (gl.draw_arrays)(0x0004, 0, 6);
            r.note("draw");
        }
        let mut px = [0u8; 16 * 4];
        (gl.read_pixels)(0, 8, 16, 1, 0x1908, 0x1401, px.as_mut_ptr().cast());
        r.note("read");
        r.log.push(format!("left {:?}, right {:?}", &px[..4], &px[60..]));
    }
}
