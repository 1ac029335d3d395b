//! The client-side GL state the C ABI needs: per context, the vertex attributes and their
//! client-side arrays, the vertex array objects, the pack and unpack state, buffer shadows and
//! the `GL_KHR_debug` callback; per process, the memory of mapped buffers.

use std::collections::HashMap;
use std::ffi::c_void;

use crate::types::*;

/// Vertex attribute slots the shim tracks (the daemon's `GL_MAX_VERTEX_ATTRIBS`).
pub(crate) const MAX_ATTRIBS: usize = 16;

/// A client-side vertex array: where the application's bytes are and how to walk them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ClientArray {
    /// The application's pointer.
    pub ptr: usize,
    /// Components per vertex.
    pub size: i32,
    /// Component type.
    pub ty: GLenum,
    /// Byte stride (0 = tightly packed).
    pub stride: i32,
}

/// What the shim remembers about one vertex attribute.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Attrib {
    /// `glEnableVertexAttribArray`.
    pub enabled: bool,
    /// Set when the last `glVertexAttribPointer` had no array buffer bound.
    pub client: Option<ClientArray>,
    /// `GL_VERTEX_ATTRIB_ARRAY_DIVISOR` (ES 3.0).
    pub divisor: u32,
}

/// The pack state `glReadPixels` lays its rows out by in the application's memory.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pack {
    /// `GL_PACK_ALIGNMENT`.
    pub alignment: usize,
    /// `GL_PACK_ROW_LENGTH_NV`, `GL_PACK_SKIP_ROWS_NV`, `GL_PACK_SKIP_PIXELS_NV`
    /// (`NV_pack_subimage`).
    pub rows: [usize; 3],
    /// `GL_PACK_REVERSE_ROW_ORDER_ANGLE`: the top row first.
    pub reverse: bool,
}

/// The client-side part of one GL context.
#[derive(Debug)]
pub(crate) struct GlState {
    /// An error the shim raised itself; `glGetError` reports it before the daemon's.
    pub error: GLenum,
    /// `GL_ARRAY_BUFFER` binding.
    pub array_buffer: u32,
    /// `GL_ELEMENT_ARRAY_BUFFER` binding (of the bound vertex array object).
    pub element_buffer: u32,
    /// Vertex attributes (of the bound vertex array object).
    pub attribs: [Attrib; MAX_ATTRIBS],
    /// `GL_VERTEX_ARRAY_BINDING_OES`.
    pub vertex_array: u32,
    /// The vertex array objects not bound, with their state (see `gl::vao`).
    pub vertex_arrays: HashMap<u32, VertexArray>,
    /// `GL_KHR_debug` state the library keeps: the callback and the two enables.
    pub debug: DebugClient,
    /// `GL_UNPACK_ALIGNMENT`.
    pub unpack_alignment: usize,
    /// `GL_UNPACK_ROW_LENGTH_EXT`, `GL_UNPACK_SKIP_ROWS_EXT`, `GL_UNPACK_SKIP_PIXELS_EXT`
    /// (`EXT_unpack_subimage`): where an upload's rows lie in the application's memory.
    pub unpack_rows: [usize; 3],
    /// `GL_UNPACK_IMAGE_HEIGHT` and `GL_UNPACK_SKIP_IMAGES` (ES 3.0): where a 3D upload's
    /// images lie in the application's memory.
    pub unpack_images: [usize; 2],
    /// Where `glReadPixels` puts its rows: see [`Pack`].
    pub pack: Pack,
    /// `GL_PIXEL_PACK_BUFFER_BINDING_NV` (`GL_NV_pixel_buffer_object`).
    pub pack_buffer: u32,
    /// `GL_PIXEL_UNPACK_BUFFER_BINDING_NV`.
    pub unpack_buffer: u32,
    /// `GL_UNIFORM_BUFFER_BINDING` (ES 3.0).
    pub uniform_buffer: u32,
    /// `GL_COPY_READ_BUFFER_BINDING` and `GL_COPY_WRITE_BUFFER_BINDING` (ES 3.0).
    pub copy_buffers: [u32; 2],
    /// `GL_TRANSFORM_FEEDBACK_BUFFER_BINDING` (ES 3.0): the generic binding.
    pub xfb_buffer: u32,
    /// An ES 3.0 context: the ES 3.0 entry points the library implements with other commands
    /// work (in an ES 2.0 context they record `GL_INVALID_OPERATION`, as the daemon does for
    /// its own).
    pub es3: bool,
    /// `GL_PRIMITIVE_RESTART_FIXED_INDEX` (ES 3.0): the all-ones index restarts and reads no
    /// vertex, so it does not count for the client arrays sent with a draw.
    pub restart: bool,
}

impl Default for GlState {
    fn default() -> Self {
        GlState {
            error: GL_NO_ERROR,
            array_buffer: 0,
            element_buffer: 0,
            attribs: [Attrib::default(); MAX_ATTRIBS],
            vertex_array: 0,
            vertex_arrays: HashMap::new(),
            debug: DebugClient::default(),
            unpack_alignment: 4,
            unpack_rows: [0; 3],
            unpack_images: [0; 2],
            pack: Pack { alignment: 4, rows: [0; 3], reverse: false },
            pack_buffer: 0,
            unpack_buffer: 0,
            uniform_buffer: 0,
            copy_buffers: [0; 2],
            xfb_buffer: 0,
            es3: false,
            restart: false,
        }
    }
}

impl GlState {
    /// Records an error unless one is already pending (the first error wins).
    pub fn err(&mut self, e: GLenum) {
        if self.error == GL_NO_ERROR {
            self.error = e;
        }
    }

    /// Returns and clears the pending error.
    pub fn take_error(&mut self) -> GLenum {
        std::mem::replace(&mut self.error, GL_NO_ERROR)
    }

    /// The buffer bound to `target`, if `target` is a buffer target.
    pub fn bound(&self, target: GLenum) -> Option<u32> {
        match target {
            GL_ARRAY_BUFFER => Some(self.array_buffer),
            GL_ELEMENT_ARRAY_BUFFER => Some(self.element_buffer),
            0x88EB => Some(self.pack_buffer),
            0x88EC => Some(self.unpack_buffer),
            GL_UNIFORM_BUFFER => Some(self.uniform_buffer),
            GL_COPY_READ_BUFFER => Some(self.copy_buffers[0]),
            GL_COPY_WRITE_BUFFER => Some(self.copy_buffers[1]),
            GL_TRANSFORM_FEEDBACK_BUFFER => Some(self.xfb_buffer),
            _ => None,
        }
    }
}

/// A vertex array object that is not bound: its client-side state (see `gl::vao`).
#[derive(Debug, Clone, Default)]
pub(crate) struct VertexArray {
    /// Enables and client arrays.
    pub attribs: [Attrib; MAX_ATTRIBS],
    /// `GL_ELEMENT_ARRAY_BUFFER` binding.
    pub element_buffer: u32,
}

/// `GLDEBUGPROCKHR`.
pub type DebugProc =
    Option<unsafe extern "C" fn(GLenum, GLenum, GLuint, GLenum, GLsizei, *const GLchar, *const c_void)>;

/// What the library keeps of a context's debug state (see `gl::debug_callback`).
#[derive(Debug, Default)]
pub(crate) struct DebugClient {
    /// The application's callback.
    pub callback: DebugProc,
    /// Its user parameter (an address, kept as an integer so the state can cross threads).
    pub user: usize,
    /// `GL_DEBUG_OUTPUT_KHR`, as the application set it.
    pub output: bool,
    /// `GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR`, as the application set it.
    pub synchronous: bool,
}

/// `GL_MAP_WRITE_BIT_EXT`.
pub(crate) const MAP_WRITE: u32 = 0x2;
/// `GL_MAP_FLUSH_EXPLICIT_BIT_EXT`.
pub(crate) const MAP_FLUSH_EXPLICIT: u32 = 0x10;
/// The alignment of a mapping's pointer less its offset, as on Mesa (`GL_MIN_MAP_BUFFER_ALIGNMENT`).
const ALIGN: usize = 64;

/// A mapped buffer as the library holds it.
pub(crate) struct Mapping {
    /// The memory handed out is `mem[start..start + length]`.
    mem: Vec<u8>,
    /// Where the handed-out memory starts in `mem`: its address less the mapped offset is a
    /// multiple of [`ALIGN`].
    start: usize,
    /// The mapped bytes.
    length: usize,
    /// The mapped range's first byte in the buffer.
    pub offset: usize,
    /// The bytes as the daemon answered them; `None` where the map invalidated them.
    before: Option<Vec<u8>>,
    /// The map's `GL_MAP_*_BIT_EXT` flags.
    pub access: u32,
}

impl Mapping {
    /// Memory for `length` bytes at `offset` holding `answered` (empty: invalidated).
    pub fn new(offset: usize, length: usize, access: u32, answered: Vec<u8>) -> Mapping {
        let mut mem = vec![0u8; length + ALIGN];
        let base = mem.as_ptr() as usize % ALIGN;
        let start = (offset % ALIGN + ALIGN - base) % ALIGN;
        let before = (answered.len() == length).then(|| {
            mem[start..start + length].copy_from_slice(&answered);
            answered
        });
        Mapping { mem, start, length, offset, before, access }
    }

    /// The pointer handed to the application.
    pub fn ptr(&mut self) -> *mut c_void {
        self.mem[self.start..].as_mut_ptr().cast()
    }

    /// The mapped bytes as the application left them.
    pub fn bytes(&self) -> &[u8] {
        &self.mem[self.start..self.start + self.length]
    }

    /// What `glUnmapBufferOES` writes back: the buffer offset and the bytes changed (none for a
    /// map that only reads, or whose writes were flushed explicitly).
    pub fn written(&self) -> (usize, &[u8]) {
        if self.access & MAP_WRITE == 0 || self.access & MAP_FLUSH_EXPLICIT != 0 {
            return (0, &[]);
        }
        let now = self.bytes();
        let Some(before) = &self.before else { return (self.offset, now) };
        let differs = |(a, b): (&u8, &u8)| a != b;
        match (now.iter().zip(before).position(differs), now.iter().zip(before).rposition(differs)) {
            (Some(first), Some(last)) => (self.offset + first, &now[first..=last]),
            _ => (0, &[]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The handed-out pointer less the offset is aligned, and only the bytes that changed go
    /// back: none for an unchanged or read-only map, all for an invalidated one.
    #[test]
    fn mappings_align_and_send_back_what_changed() {
        for offset in [0, 1, 63, 64, 100] {
            let mut m = Mapping::new(offset, 8, MAP_WRITE, vec![7; 8]);
            assert_eq!((m.ptr() as usize).wrapping_sub(offset) % ALIGN, 0, "offset {offset}");
            assert_eq!(m.written(), (0, &[][..]));
            m.mem[m.start + 2] = 1;
            m.mem[m.start + 5] = 2;
            assert_eq!(m.written(), (offset + 2, &[1, 7, 7, 2][..]));
        }
        let mut read = Mapping::new(0, 4, 0x1, vec![1; 4]);
        read.mem[read.start] = 9;
        assert_eq!(read.written(), (0, &[][..]));
        let invalidated = Mapping::new(4, 3, MAP_WRITE | 0x4, Vec::new());
        assert_eq!(invalidated.written(), (4, &[0, 0, 0][..]));
        let explicit = Mapping::new(0, 2, MAP_WRITE | MAP_FLUSH_EXPLICIT, vec![0; 2]);
        assert_eq!(explicit.written(), (0, &[][..]));
    }
}
