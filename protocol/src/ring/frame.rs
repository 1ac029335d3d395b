//! One frame as the reading end finds it: its header read once and checked against the
//! published head and the data area's end.

use super::*;

/// Consumed bytes after which the reader hands space back to the writer even mid-batch, so
/// that a writer returning to the ring's start early (see [`super::writer::HOT_WINDOW`]) finds it free.
pub(super) const RELEASE_EVERY: u32 = 256 << 10;

/// A frame as [`next_frame`] found it, every field checked against the ring and the head.
pub(super) struct Frame {
    /// Its offset in the data area.
    pub off: usize,
    /// Its payload's length (0 for a wrap).
    pub len: usize,
    /// Its kind.
    pub kind: u32,
    /// Bytes it occupies, or for a wrap, bytes skipped to the ring's start.
    pub size: usize,
}

/// Reads and checks the frame at `tail`, of the bytes up to `head`: each header word read
/// once, every length checked against what was published and the data area's end.
pub(super) fn next_frame(ring: &RingRegion, tail: u32, head: u32) -> Result<Frame, RingError> {
    let cap = ring.capacity;
    let ahead = head.wrapping_sub(tail);
    if ahead > cap {
        return Err(RingError::BadHead { ahead, capacity: cap });
    }
    let available = ahead as usize;
    if available < FRAME_HEADER {
        return Err(RingError::Truncated { needed: FRAME_HEADER, available });
    }
    let off = ring.offset(tail);
    // Frames keep the tail aligned; only a tail planted before the reader began is not.
    if !off.is_multiple_of(8) {
        return Err(RingError::MisalignedTail(tail));
    }
    let (len, kind) = ring.read_header(off);
    if kind == KIND_WRAP {
        let skip = cap as usize - off;
        if skip > available {
            return Err(RingError::Truncated { needed: skip, available });
        }
        return Ok(Frame { off, len: 0, kind, size: skip });
    }
    let limit = cap as usize - off - FRAME_HEADER;
    if len as usize > limit {
        return Err(RingError::BadLength { len, limit });
    }
    let size = frame_size(len as usize);
    if size > available {
        return Err(RingError::Truncated { needed: size, available });
    }
    Ok(Frame { off, len: len as usize, kind, size })
}
