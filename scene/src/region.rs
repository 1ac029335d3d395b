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

/// The output region a frame changed, from the damage its client stated
/// (`EGL_KHR_swap_buffers_with_damage`): `damage` rectangles in the image's GL coordinates
/// (x, y from the bottom, width, height) of an image of size `image`, whose `source` part (x,
/// y from the top; all of it for `None`) shows scaled into output rectangle `rect`. Mapped
/// outwards to whole pixels, one pixel wider on each side where the image is scaled (its
/// filtering reaches the neighbours), within `rect`.
pub fn damage_in_output(rect: [i32; 4], image: [i32; 2], source: Option<[i32; 4]>, damage: &[[i32; 4]]) -> Region {
    let src = source.unwrap_or([0, 0, image[0], image[1]]);
    if src[2] <= 0 || src[3] <= 0 || rect[2] <= 0 || rect[3] <= 0 {
        return Region::None;
    }
    let scaled = (src[2], src[3]) != (rect[2], rect[3]);
    let margin = i64::from(scaled);
    let mut out = Region::None;
    for d in damage {
        // To the image's top-origin coordinates, then within the part shown.
        let top = [d[0], image[1].saturating_sub(d[1].saturating_add(d[3])), d[2], d[3]];
        let Some(part) = intersect(top, src) else { continue };
        let map = |v: i32, from: i32, len: i32, to: i32, out_len: i32, ceil: bool| -> i64 {
            let num = i64::from(v - from) * i64::from(out_len);
            let den = i64::from(len);
            i64::from(to) + if ceil { (num + den - 1).div_euclid(den) } else { num.div_euclid(den) }
        };
        let x0 = map(part[0], src[0], src[2], rect[0], rect[2], false) - margin;
        let x1 = map(part[0] + part[2], src[0], src[2], rect[0], rect[2], true) + margin;
        let y0 = map(part[1], src[1], src[3], rect[1], rect[3], false) - margin;
        let y1 = map(part[1] + part[3], src[1], src[3], rect[1], rect[3], true) + margin;
        let r = [x0 as i32, y0 as i32, (x1 - x0) as i32, (y1 - y0) as i32];
        if let Some(r) = intersect(r, rect) {
            out = out.with(r);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stated_damage_maps_into_the_output() {
        // Unscaled at (100, 50): a 10×10 square at the image's bottom left is at its top left
        // in the output's top-origin space, 90 rows down a 100-row image.
        let r = damage_in_output([100, 50, 200, 100], [200, 100], None, &[[0, 0, 10, 10]]);
        assert_eq!(r, Region::Rect([100, 140, 10, 10]));
        // Two rectangles: their bounding box.
        let r = damage_in_output([0, 0, 200, 100], [200, 100], None, &[[0, 0, 10, 10], [50, 90, 10, 10]]);
        assert_eq!(r, Region::Rect([0, 0, 60, 100]));
        // Scaled by two, with a pixel of margin each side.
        let r = damage_in_output([0, 0, 400, 200], [200, 100], None, &[[10, 10, 10, 10]]);
        assert_eq!(r, Region::Rect([19, 159, 22, 22]));
        // A source part: damage outside it changes nothing; inside, it maps from its corner.
        let src = Some([50, 0, 100, 100]);
        assert_eq!(damage_in_output([0, 0, 100, 100], [200, 100], src, &[[0, 0, 10, 10]]), Region::None);
        assert_eq!(
            damage_in_output([0, 0, 100, 100], [200, 100], src, &[[60, 0, 10, 10]]),
            Region::Rect([10, 90, 10, 10])
        );
        // Damage past the image is clipped to the surface's rectangle.
        assert_eq!(
            damage_in_output([5, 5, 20, 20], [20, 20], None, &[[-10, -10, 100, 100]]),
            Region::Rect([5, 5, 20, 20])
        );
        assert_eq!(damage_in_output([5, 5, 20, 20], [20, 20], None, &[]), Region::None);
    }
}
