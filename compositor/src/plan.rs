//! The compositor's plan, made on the CPU before anything is drawn: the redrawn region is cut
//! into rectangles ("cells") by coverage, so that every pixel of a cell is covered by exactly
//! the same surfaces. Each cell then costs only what its coverage needs: nothing covers it (a
//! background fill), one surface per z-group (one fetch), or several at one z (the depth
//! select, over those surfaces only, chained only where more than a pass can sample overlap).
//!
//! Because the work for a pixel depends only on the set of surfaces covering it, a partial
//! composite does, pixel for pixel, what a whole one does.

use std::collections::{BTreeMap, HashMap};

/// A rectangle `[x0, y0, x1, y1]` (ends exclusive) in output pixels.
pub type Rect = [i32; 4];

/// A rectangle of the region in which every pixel is covered by the same surfaces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Cell {
    /// Where, in output pixels.
    pub rect: Rect,
    /// The covering surfaces (indices into the layer list, in stacking order); empty for
    /// background.
    pub members: Vec<u32>,
}

/// `r` (x, y, width, height; any values) clipped to `region`, or `None` if nothing is left.
/// Computed in 64 bits, so rectangles near the ends of the `i32` range cannot overflow.
pub fn clip(r: [i32; 4], region: Rect) -> Option<Rect> {
    let (w, h) = (i64::from(r[2]), i64::from(r[3]));
    if w <= 0 || h <= 0 {
        return None;
    }
    let x0 = i64::from(r[0]).max(i64::from(region[0]));
    let y0 = i64::from(r[1]).max(i64::from(region[1]));
    let x1 = (i64::from(r[0]) + w).min(i64::from(region[2]));
    let y1 = (i64::from(r[1]) + h).min(i64::from(region[3]));
    // Inside the region, so every coordinate fits in an i32 again.
    (x0 < x1 && y0 < y1).then_some([x0 as i32, y0 as i32, x1 as i32, y1 as i32])
}

/// Cuts `region` into cells by coverage: `rects[i]` is surface `i` clipped to the region
/// (`None`: it covers nothing). The cells partition the region exactly; neighbours with the
/// same coverage are merged, first along rows, then down columns of equal extent.
pub fn cells(rects: &[Option<Rect>], region: Rect) -> Vec<Cell> {
    if region[0] >= region[2] || region[1] >= region[3] {
        return Vec::new();
    }
    let mut xs = vec![region[0], region[2]];
    let mut ys = vec![region[1], region[3]];
    for r in rects.iter().flatten() {
        xs.extend([r[0], r[2]]);
        ys.extend([r[1], r[3]]);
    }
    xs.sort_unstable();
    xs.dedup();
    ys.sort_unstable();
    ys.dedup();
    let column = |x: i32| xs.partition_point(|&v| v < x);
    let spans: Vec<Option<(usize, usize)>> = rects.iter().map(|r| r.map(|r| (column(r[0]), column(r[2])))).collect();
    let mut coverage: Vec<Vec<u32>> = vec![Vec::new(); xs.len() - 1];
    let mut out: Vec<Cell> = Vec::new();
    // Cells ending at the current band's top, by extent and coverage, for merging downwards.
    let mut open: HashMap<(i32, i32, Vec<u32>), usize> = HashMap::new();
    for band in ys.windows(2) {
        let (y0, y1) = (band[0], band[1]);
        coverage.iter_mut().for_each(Vec::clear);
        for (i, (r, span)) in rects.iter().zip(&spans).enumerate() {
            if let (Some(r), Some((a, b))) = (r, span) {
                if r[1] <= y0 && y1 <= r[3] {
                    for c in &mut coverage[*a..*b] {
                        c.push(i as u32);
                    }
                }
            }
        }
        let mut next = HashMap::with_capacity(open.len());
        let mut j = 0;
        while j < coverage.len() {
            let mut e = j + 1;
            while e < coverage.len() && coverage[e] == coverage[j] {
                e += 1;
            }
            let key = (xs[j], xs[e], coverage[j].clone());
            let at = match open.remove(&key) {
                Some(at) => {
                    out[at].rect[3] = y1;
                    at
                }
                None => {
                    out.push(Cell { rect: [xs[j], y0, xs[e], y1], members: key.2.clone() });
                    out.len() - 1
                }
            };
            next.insert(key, at);
            j = e;
        }
        open = next;
    }
    out
}

/// What one z-group draws into the output, and the cells it must chain.
#[derive(Debug, Default, PartialEq)]
pub struct GroupPlan {
    /// By (covering members in stacking order, `base`): the cells. `base` is set where this
    /// group is the farthest one at those pixels, so it lies directly on the background.
    pub draws: BTreeMap<(Vec<u32>, bool), Vec<Rect>>,
}

/// The 3D plan: background cells, then every z-group far to near.
#[derive(Debug, Default, PartialEq)]
pub struct Plan {
    /// Cells no surface covers.
    pub fill: Vec<Rect>,
    /// The z-groups, far (larger z) to near.
    pub groups: Vec<GroupPlan>,
    /// Surfaces left out of cells (counted once per cell) because a nearer group of opaque
    /// surfaces covers the cell.
    pub culled: usize,
}

/// Distinct finite z values, far (larger) to near.
pub fn depth_layers(zs: impl Iterator<Item = f32>) -> Vec<f32> {
    let mut v: Vec<f32> = zs.filter(|z| z.is_finite()).collect();
    v.sort_by(|a, b| b.total_cmp(a));
    v.dedup();
    v
}

/// The 3D plan for surfaces at depths `z` (stacking order) covering `cells`. With `opaque`
/// (culling on; `opaque[i]`: surface `i`'s colour has alpha 1 everywhere), a cell drops every
/// group farther than the nearest group whose members there are all opaque: that group covers
/// every pixel of the cell with alpha 1, so nothing beneath it can show, and it is laid on the
/// background instead. Which surface each remaining group selects at a pixel does not change.
pub fn plan_3d(cells: &[Cell], z: &[f32], opaque: Option<&[bool]>) -> Plan {
    let layers = depth_layers(z.iter().copied());
    let mut plan = Plan { groups: layers.iter().map(|_| GroupPlan::default()).collect(), ..Plan::default() };
    for cell in cells {
        let present: Vec<(usize, Vec<u32>)> = layers
            .iter()
            .enumerate()
            .filter_map(|(g, &lz)| {
                let members: Vec<u32> = cell.members.iter().copied().filter(|&m| z[m as usize] == lz).collect();
                (!members.is_empty()).then_some((g, members))
            })
            .collect();
        if present.is_empty() {
            plan.fill.push(cell.rect);
            continue;
        }
        let start = opaque
            .and_then(|o| present.iter().rposition(|(_, m)| m.iter().all(|&i| o.get(i as usize) == Some(&true))))
            .unwrap_or(0);
        plan.culled += present[..start].iter().map(|(_, m)| m.len()).sum::<usize>();
        for (at, (g, members)) in present.into_iter().enumerate().skip(start) {
            plan.groups[g].draws.entry((members, at == start)).or_default().push(cell.rect);
        }
    }
    plan
}

/// The 2D plan: background cells, and per surface the cells where it is on top (nearest z;
/// on equal z the later in stacking order), in stacking order.
pub fn plan_2d(cells: &[Cell], z: &[f32]) -> (Vec<Rect>, BTreeMap<u32, Vec<Rect>>) {
    let mut fill = Vec::new();
    let mut copies: BTreeMap<u32, Vec<Rect>> = BTreeMap::new();
    for cell in cells {
        let top = cell.members.iter().copied().filter(|&m| z[m as usize].is_finite()).reduce(|best, m| {
            if z[m as usize] <= z[best as usize] {
                m
            } else {
                best
            }
        });
        match top {
            Some(t) => copies.entry(t).or_default().push(cell.rect),
            None => fill.push(cell.rect),
        }
    }
    (fill, copies)
}

/// How a group of `k` surfaces splits into passes of at most `p` surfaces: the first takes
/// `p`, every further one the previous pass's result and `p − 1` new surfaces.
pub fn chunks(k: usize, p: usize) -> Vec<std::ops::Range<usize>> {
    let first = 0..k.min(p);
    let mut out = vec![first];
    let mut at = k.min(p);
    while at < k {
        let take = (k - at).min(p.saturating_sub(1).max(1));
        out.push(at..at + take);
        at += take;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The coverage of pixel (x, y) counted directly from the rectangles.
    fn covering(rects: &[Option<Rect>], x: i32, y: i32) -> Vec<u32> {
        (0..rects.len() as u32)
            .filter(|&i| rects[i as usize].is_some_and(|r| r[0] <= x && x < r[2] && r[1] <= y && y < r[3]))
            .collect()
    }

    fn check_partition(rects: &[Option<Rect>], region: Rect) -> usize {
        let cs = cells(rects, region);
        let (w, h) = ((region[2] - region[0]) as usize, (region[3] - region[1]) as usize);
        let mut seen = vec![0u8; w * h];
        for c in &cs {
            assert!(c.rect[0] < c.rect[2] && c.rect[1] < c.rect[3], "empty cell {c:?}");
            for y in c.rect[1]..c.rect[3] {
                for x in c.rect[0]..c.rect[2] {
                    seen[(y - region[1]) as usize * w + (x - region[0]) as usize] += 1;
                    assert_eq!(covering(rects, x, y), c.members, "pixel {x},{y} of {c:?}");
                }
            }
        }
        assert!(seen.iter().all(|&n| n == 1), "cells must cover the region exactly once");
        cs.len()
    }

    #[test]
    fn cells_partition_the_region_by_coverage() {
        let region = [0, 0, 40, 30];
        let raw = [[5, 5, 10, 10], [10, 8, 20, 5], [-5, -5, 100, 3], [39, 29, 1, 1], [0, 0, 40, 30], [12, 0, 0, 9]];
        let rects: Vec<Option<Rect>> = raw.iter().map(|&r| clip(r, region)).collect();
        check_partition(&rects, region);
        // Seeded pseudo-random scenes.
        let mut s = 12345u64;
        let mut next = |m: i32| {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((s >> 33) % m as u64) as i32
        };
        for _ in 0..50 {
            let region = [next(10), next(10), 30 + next(20), 25 + next(20)];
            let rects: Vec<Option<Rect>> =
                (0..next(9)).map(|_| clip([next(60) - 10, next(60) - 10, next(30), next(30)], region)).collect();
            check_partition(&rects, region);
        }
    }

    #[test]
    fn identical_rectangles_are_one_cell_and_merging_is_maximal_for_a_window() {
        let region = [0, 0, 100, 50];
        let r = clip([10, 10, 30, 20], region);
        assert_eq!(check_partition(&[r, r, r], region), 5, "above, left, the window, right, below");
        assert_eq!(check_partition(&[], region), 1);
    }

    #[test]
    fn clipping_is_overflow_free() {
        let region = [0, 0, 16384, 16384];
        assert_eq!(clip([i32::MAX, i32::MAX, i32::MAX, i32::MAX], region), None);
        assert_eq!(clip([i32::MIN, i32::MIN, i32::MAX, i32::MAX], region), None);
        assert_eq!(clip([-10, -10, i32::MAX, 20], region), Some([0, 0, 16384, 10]));
        assert_eq!(clip([5, 5, 0, 7], region), None);
        assert_eq!(clip([5, 5, -3, 7], region), None);
    }

    #[test]
    fn chunks_follow_the_pass_formula() {
        for p in 2..6 {
            for k in 1..30 {
                let c = chunks(k, p);
                let want = if k <= p { 1 } else { 1 + (k - p).div_ceil(p - 1) };
                assert_eq!(c.len(), want, "k={k} p={p}");
                assert_eq!(c.iter().map(|r| r.len()).sum::<usize>(), k);
            }
        }
    }

    #[test]
    fn base_is_the_farthest_group_at_each_cell() {
        let region = [0, 0, 10, 10];
        let rects = [clip([0, 0, 6, 10], region), clip([4, 0, 6, 10], region)];
        let cs = cells(&rects, region);
        let plan = plan_3d(&cs, &[0.5, 0.2], None);
        assert!(plan.fill.is_empty());
        // Group 0 (z 0.5, far): surface 0 everywhere it is, always on the background.
        assert_eq!(plan.groups[0].draws.keys().collect::<Vec<_>>(), [&(vec![0], true)]);
        // Group 1 (z 0.2): on the background at x 6..10, over group 0 at x 4..6.
        assert_eq!(plan.groups[1].draws[&(vec![1], false)], vec![[4, 0, 6, 10]]);
        assert_eq!(plan.groups[1].draws[&(vec![1], true)], vec![[6, 0, 10, 10]]);
        let (fill, copies) = plan_2d(&cs, &[0.5, 0.2]);
        assert!(fill.is_empty());
        assert_eq!(copies[&0], vec![[0, 0, 4, 10]]);
        assert_eq!(copies[&1], vec![[4, 0, 6, 10], [6, 0, 10, 10]]);
    }

    #[test]
    fn an_opaque_nearer_group_culls_what_lies_beneath() {
        // Surface 0 (z 0.9) fills the region; 1 and 2 (z 0.5) lie side by side over its left
        // half; 3 (z 0.1) covers x 2..6. Cells by x: [0,2) {0,1}, [2,4) {0,1,3}, [4,5) {0,2,3},
        // [5,6) {0,3}, [6,10) {0}.
        let region = [0, 0, 10, 4];
        let raw = [[0, 0, 10, 4], [0, 0, 4, 4], [4, 0, 1, 4], [2, 0, 4, 4]];
        let rects: Vec<Option<Rect>> = raw.iter().map(|&r| clip(r, region)).collect();
        let cs = cells(&rects, region);
        let z = [0.9, 0.5, 0.5, 0.1];
        let draws = |p: &Plan, g: usize| -> Vec<(Vec<u32>, bool, Vec<Rect>)> {
            p.groups[g].draws.iter().map(|((m, b), r)| (m.clone(), *b, r.clone())).collect()
        };
        // Culling off, or nothing opaque: every group is drawn wherever it is.
        let off = plan_3d(&cs, &z, None);
        assert_eq!(plan_3d(&cs, &z, Some(&[false; 4])), off);
        assert_eq!(off.culled, 0);
        let every = vec![[0, 0, 2, 4], [2, 0, 4, 4], [4, 0, 5, 4], [5, 0, 6, 4], [6, 0, 10, 4]];
        assert_eq!(draws(&off, 0), vec![(vec![0], true, every)]);
        // Surface 1 opaque, 2 not: group z 0.5 is all opaque only where 1 alone covers, so
        // surface 0 is dropped at x 0..4 (two cells) and stays under surface 2.
        let on = plan_3d(&cs, &z, Some(&[false, true, false, false]));
        assert_eq!(on.culled, 2);
        assert_eq!(draws(&on, 0), vec![(vec![0], true, vec![[4, 0, 5, 4], [5, 0, 6, 4], [6, 0, 10, 4]])]);
        assert_eq!(
            draws(&on, 1),
            vec![(vec![1], true, vec![[0, 0, 2, 4], [2, 0, 4, 4]]), (vec![2], false, vec![[4, 0, 5, 4]])]
        );
        // Nearer groups are untouched.
        assert_eq!(on.groups[2], off.groups[2]);
        // Surface 3 opaque: at x 2..6 only it is drawn, on the background; the farther ones
        // are dropped there (0 and 1 at x 2..4, 0 and 2 at 4..5, 0 at 5..6).
        let near = plan_3d(&cs, &z, Some(&[false, false, false, true]));
        assert_eq!(near.culled, 5);
        assert_eq!(draws(&near, 2), vec![(vec![3], true, vec![[2, 0, 4, 4], [4, 0, 5, 4], [5, 0, 6, 4]])]);
        assert_eq!(draws(&near, 1), vec![(vec![1], false, vec![[0, 0, 2, 4]])]);
        // A group of which one member is transparent culls nothing: where 1 and 2 would
        // overlap, the select may show either.
        let rects2 = [clip([0, 0, 10, 4], region), clip([0, 0, 6, 4], region), clip([3, 0, 6, 4], region)];
        let cs2 = cells(&rects2, region);
        let mixed = plan_3d(&cs2, &[0.9, 0.5, 0.5], Some(&[false, true, false]));
        assert_eq!(mixed.culled, 1, "only the cell x 0..3, where surface 1 alone covers");
        assert!(mixed.groups[0].draws.values().flatten().all(|r| r[0] >= 3));
        assert!(plan_3d(&cs, &z, Some(&[true; 4])).fill.is_empty());
    }
}
