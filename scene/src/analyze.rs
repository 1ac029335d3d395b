//! `stratad ctl analyze SURFACE`: why a surface does not show. Every reason that holds is
//! given: no frame yet, its own or a layer's visibility off, opacity 0, no area, off every
//! output, or covered wherever it lies on an output by opaque surfaces of nearer groups.

use strata_protocol::events::{Analysis, Reason};
use strata_protocol::properties::Rect;

use crate::region::intersect;
use crate::state::{Scene, SceneSurface};

/// `a` less `b`: up to four rectangles.
fn subtract(a: Rect, b: Rect) -> Vec<Rect> {
    let (a, b) = (a.map(i64::from), b.map(i64::from));
    let (ax1, ay1, bx1, by1) = (a[0] + a[2], a[1] + a[3], b[0] + b[2], b[1] + b[3]);
    if b[0] >= ax1 || bx1 <= a[0] || b[1] >= ay1 || by1 <= a[1] {
        return vec![a.map(|v| v as i32)];
    }
    let mut out = Vec::new();
    let mut push = |x0: i64, y0: i64, x1: i64, y1: i64| {
        if x1 > x0 && y1 > y0 {
            // Within `a`, so each fits in an i32.
            out.push([x0 as i32, y0 as i32, (x1 - x0) as i32, (y1 - y0) as i32]);
        }
    };
    let (iy0, iy1) = (a[1].max(b[1]), ay1.min(by1));
    push(a[0], a[1], ax1, iy0);
    push(a[0], iy1, ax1, ay1);
    push(a[0], iy0, b[0].max(a[0]), iy1);
    push(bx1.min(ax1), iy0, ax1, iy1);
    out
}

impl Scene {
    /// Why surface `id` does not show on outputs `outputs` (rectangles in the output space), or
    /// that it does; `None` if there is no such surface.
    pub fn analyze(&self, id: u64, outputs: &[Rect]) -> Option<Analysis> {
        let g = self.lock()?;
        let s = g.surfaces.values().find(|s| s.id == id)?;
        let mut reasons = Vec::new();
        if s.color.is_none() {
            reasons.push(Reason::NoFrame);
        }
        if !s.props.visible {
            reasons.push(Reason::Hidden);
        }
        for (name, l) in &g.layers {
            if !l.visible && l.surfaces.contains(&id) {
                reasons.push(Reason::LayerHidden { layer: name.clone() });
            }
        }
        let (_, opacity) = s.shown_in(&g.layers);
        if opacity <= 0.0 {
            reasons.push(Reason::Transparent);
        }
        let empty = s.rect[2] <= 0 || s.rect[3] <= 0 || s.source_region().is_none();
        if empty {
            reasons.push(Reason::ZeroSize);
        }
        let on: Vec<Rect> =
            if empty { Vec::new() } else { outputs.iter().filter_map(|o| intersect(s.rect, *o)).collect() };
        if !empty && on.is_empty() {
            reasons.push(Reason::OffOutputs);
        }
        if reasons.is_empty() {
            // What is left of it on the outputs after every opaque surface of a nearer group.
            let mut nearer: Vec<&SceneSurface> = g
                .surfaces
                .values()
                .filter(|o| {
                    let (visible, opacity) = o.shown_in(&g.layers);
                    o.z < s.z
                        && visible
                        && opacity >= 1.0
                        && o.opaque
                        && o.color.is_some()
                        && o.source_region().is_some()
                })
                .collect();
            nearer.sort_by(|a, b| a.z.total_cmp(&b.z).then(b.order.cmp(&a.order)));
            let mut left = on;
            let mut by = Vec::new();
            for o in nearer {
                if left.iter().any(|r| intersect(*r, o.rect).is_some()) {
                    by.push(o.id);
                    left = left.into_iter().flat_map(|r| subtract(r, o.rect)).collect();
                }
            }
            if left.is_empty() {
                reasons.push(Reason::Covered { by });
            }
        }
        Some(Analysis { surface: id, visible: reasons.is_empty(), reasons })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pixels of `rects` (which must not overlap), counted.
    fn area(rects: &[Rect]) -> i64 {
        rects.iter().map(|r| i64::from(r[2]) * i64::from(r[3])).sum()
    }

    #[test]
    fn subtraction_leaves_exactly_the_pixels_outside() {
        let a = [0, 0, 10, 8];
        for b in [[2, 2, 3, 3], [-5, -5, 8, 8], [0, 0, 10, 8], [9, 7, 5, 5], [20, 20, 1, 1], [3, -2, 2, 20]] {
            let left = subtract(a, b);
            for x in -1..11 {
                for y in -1..9 {
                    let inside = |r: &Rect| r[0] <= x && x < r[0] + r[2] && r[1] <= y && y < r[1] + r[3];
                    let n = left.iter().filter(|r| inside(r)).count();
                    assert_eq!(n, usize::from(inside(&a) && !inside(&b)), "{b:?} at {x},{y}");
                }
            }
            assert!(area(&left) <= area(&[a]));
        }
        assert_eq!(intersect(a, [5, 5, 10, 10]), Some([5, 5, 5, 3]));
        assert_eq!(intersect(a, [10, 0, 1, 1]), None);
    }
}
