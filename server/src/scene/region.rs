//! The part of the output space that changed since the last composite.

/// The part of the output space that changed since the last composite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Region {
    /// Nothing.
    None,
    /// This rectangle (x, y, width, height), the bounding box of every change; 64-bit, so
    /// that the box of rectangles anywhere in the `i32` output space cannot overflow.
    Rect([i64; 4]),
    /// Everything (the first composite, a lighting change).
    Full,
}

impl Region {
    /// This region grown to cover `r` (x, y, width, height) as well; a rectangle without area
    /// adds nothing.
    pub fn with(self, r: [i32; 4]) -> Region {
        if r[2] <= 0 || r[3] <= 0 {
            return self;
        }
        self.union(Region::Rect(r.map(i64::from)))
    }

    /// The smallest region covering both.
    pub fn union(self, other: Region) -> Region {
        match (self, other) {
            (Region::Full, _) | (_, Region::Full) => Region::Full,
            (Region::None, o) | (o, Region::None) => o,
            (Region::Rect(a), Region::Rect(r)) => {
                let (x0, y0) = (a[0].min(r[0]), a[1].min(r[1]));
                let x1 = (a[0] + a[2]).max(r[0] + r[2]);
                let y1 = (a[1] + a[3]).max(r[1] + r[3]);
                Region::Rect([x0, y0, x1 - x0, y1 - y0])
            }
        }
    }
}

/// `a ∩ b` (x, y, width, height), or `None` where they do not overlap; in 64 bits, so that
/// rectangles anywhere in the `i32` plane cannot overflow.
pub fn intersect(a: [i32; 4], b: [i32; 4]) -> Option<[i32; 4]> {
    let (a, b) = (a.map(i64::from), b.map(i64::from));
    let x0 = a[0].max(b[0]);
    let y0 = a[1].max(b[1]);
    let x1 = (a[0] + a[2]).min(b[0] + b[2]);
    let y1 = (a[1] + a[3]).min(b[1] + b[3]);
    // Within both, so each fits in an i32.
    (x1 > x0 && y1 > y0).then(|| [x0 as i32, y0 as i32, (x1 - x0) as i32, (y1 - y0) as i32])
}
