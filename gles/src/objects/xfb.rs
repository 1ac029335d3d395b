//! Transform feedback objects (ES 3.0) and a context's transform feedback state: the object
//! bound, the others by name, and while capture is active what it writes and has written.

use std::collections::HashMap;
use std::sync::Arc;

use crate::objects::buffer::RangeBinding;
use crate::objects::program::LinkedProgram;
use crate::typed::Primitive;

/// `GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS`: the indexed buffer bindings.
pub const MAX_BUFFERS: usize = 4;

/// A transform feedback object.
#[derive(Clone, Default)]
pub struct TransformFeedback {
    /// The indexed `GL_TRANSFORM_FEEDBACK_BUFFER` bindings.
    pub buffers: [RangeBinding; MAX_BUFFERS],
    /// While capture is active (between `glBeginTransformFeedback` and its end).
    pub active: Option<Capturing>,
    /// Whether it was ever bound (`glIsTransformFeedback` answers true only then).
    pub bound_once: bool,
}

/// An active capture.
#[derive(Clone)]
pub struct Capturing {
    /// The primitive mode every draw must have.
    pub mode: Primitive,
    /// Whether it is paused.
    pub paused: bool,
    /// The program it captures the varyings of.
    pub program: Arc<LinkedProgram>,
    /// Per buffer binding: the buffer, its first byte, and the bytes it may hold.
    pub targets: Vec<(u32, u64, u64)>,
    /// Per buffer binding: the bytes written so far.
    pub written: Vec<u64>,
}

/// A context's transform feedback state.
pub struct XfbState {
    /// The objects by name; 0, the default one, always there.
    pub objects: HashMap<u32, TransformFeedback>,
    /// `GL_TRANSFORM_FEEDBACK_BINDING`.
    pub bound: u32,
    /// The active `GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN` query and its count so far.
    pub query: Option<(u32, u64)>,
}

impl Default for XfbState {
    fn default() -> Self {
        XfbState { objects: HashMap::from([(0, TransformFeedback::default())]), bound: 0, query: None }
    }
}

impl XfbState {
    /// The bound object.
    pub fn current(&self) -> Option<&TransformFeedback> {
        self.objects.get(&self.bound)
    }

    /// The bound object, to change.
    pub fn current_mut(&mut self) -> Option<&mut TransformFeedback> {
        self.objects.get_mut(&self.bound)
    }

    /// The active capture, if any (paused or not).
    pub fn active(&self) -> Option<&Capturing> {
        self.current().and_then(|x| x.active.as_ref())
    }

    /// The capture draws write to now: active and not paused.
    pub fn capturing(&self) -> Option<&Capturing> {
        self.active().filter(|a| !a.paused)
    }
}
