//! Vertex arrays: each attribute's pointer, enable and current value, and a vertex array
//! object's attributes and element buffer.

use crate::enums::*;
use crate::limits::MAX_ATTRIBS;

/// One generic vertex attribute: its array and its current value.
#[derive(Clone)]
pub struct Attrib {
    /// `VERTEX_ATTRIB_ARRAY_ENABLED`.
    pub enabled: bool,
    /// Components per vertex (1–4).
    pub size: i32,
    /// Component type.
    pub ty: u32,
    /// Whether integers are normalised.
    pub normalized: bool,
    /// Byte stride (0: tightly packed).
    pub stride: i32,
    /// Byte offset into the buffer (the pointer).
    pub offset: u64,
    /// The array buffer bound when the pointer was set; 0 for a client-side array.
    pub buffer: u32,
    /// The current value, used while the array is disabled.
    pub current: [f32; 4],
    /// A client-side array's bytes for the next draw (`buffer` is 0).
    pub client: Option<Vec<u8>>,
    /// The type and stride the application set, while `client` holds an array the client
    /// converted for the wire (`ty` and `stride` then describe those bytes, tightly packed).
    pub declared: Option<(u32, i32)>,
    /// `GL_VERTEX_ATTRIB_ARRAY_DIVISOR` (ES 3.0): 0 reads per vertex, d per d instances.
    pub divisor: u32,
    /// `GL_VERTEX_ATTRIB_ARRAY_INTEGER` (ES 3.0): set by `glVertexAttribIPointer`.
    pub integer: bool,
    /// The current value as integers, where `glVertexAttribI4i`/`ui` set it last (what an
    /// integer input reads while the array is disabled).
    pub current_int: Option<[u32; 4]>,
}

impl Default for Attrib {
    fn default() -> Self {
        Attrib {
            enabled: false,
            size: 4,
            ty: FLOAT,
            normalized: false,
            stride: 0,
            offset: 0,
            buffer: 0,
            current: [0.0, 0.0, 0.0, 1.0],
            client: None,
            declared: None,
            divisor: 0,
            integer: false,
            current_int: None,
        }
    }
}

impl Attrib {
    /// Puts back the type and stride the application set, if a wire array stood in for them.
    pub(crate) fn restore_declared(&mut self) {
        if let Some((ty, stride)) = self.declared.take() {
            self.ty = ty;
            self.stride = stride;
        }
    }
}

/// A vertex array object that is not bound.
pub struct VertexArray {
    /// Its attribute arrays (their `current` fields mean nothing here).
    pub(crate) attribs: Vec<Attrib>,
    /// `GL_ELEMENT_ARRAY_BUFFER_BINDING`.
    pub(crate) element_buffer: u32,
    /// Whether it has been bound: a generated name becomes a vertex array object only then
    /// (`glIsVertexArrayOES` is false before).
    pub(crate) ever_bound: bool,
}

impl Default for VertexArray {
    /// A generated name's initial state.
    fn default() -> Self {
        VertexArray { attribs: vec![Attrib::default(); MAX_ATTRIBS], element_buffer: 0, ever_bound: false }
    }
}
