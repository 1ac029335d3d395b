//! Cutting a low-priority client's pass into pieces that are submitted one at a time (see
//! `crate::schedule`), each taking about the scheduler's slice time. The image is the same
//! as the whole pass's: pieces keep GL's order, and each fragment is drawn by one piece.
//!
//! - A pass with at least as many draws as pieces is cut into runs of draws.
//! - Otherwise each draw is cut on its own: a draw with enough primitives into ranges of them
//!   (vertex or index ranges on primitive boundaries, even triangles for strips so that
//!   winding is kept; instances for points), which divides both its vertex and its fragment
//!   work; a draw with few primitives (a full-screen quad) into bands of the target's rows,
//!   scissored, which divides its fragment work.
//!
//! How many pieces: what the same target's pass took last time divided by the slice time; a
//! target not seen yet is cut into `FIRST_PIECES`, since its first pass may be the longest.

use std::ops::Range;

use super::passes::{Pass, Recorded};
use super::Renderer;

/// The most pieces one pass is cut into.
const MAX_PIECES: usize = 512;
/// Pieces of a pass whose cost is not known yet.
const FIRST_PIECES: usize = 16;
/// Fewest primitives in one range of a draw cut by primitives.
const MIN_PRIMITIVES: u32 = 16;

/// A part of one draw: a range of its vertices (or indices), or of its instances.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Part {
    /// Elements `start..start + count`, relative to the draw's first vertex (or index).
    Elements(u32, u32),
    /// Instances `start..start + count`, relative to the draw's first instance.
    Instances(u32, u32),
}

/// A piece of a pass submitted on its own: a run of its draws, or a part of one draw, drawn
/// only into a band of rows (first and last row, exclusive) of the target when given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Piece {
    pub(super) draws: Range<usize>,
    pub(super) part: Option<Part>,
    pub(super) band: Option<[u32; 2]>,
}

impl Piece {
    /// The whole pass.
    pub(super) fn whole(pass: &Pass) -> Piece {
        Piece { draws: 0..pass.draws.len(), part: None, band: None }
    }
}

/// How a draw's primitives map onto its elements: elements per primitive, elements shared
/// with the next primitive, and the alignment of a range's first primitive.
fn layout(topology: wgpu::PrimitiveTopology) -> (u32, u32, u32) {
    use wgpu::PrimitiveTopology as T;
    match topology {
        T::PointList => (1, 0, 1),
        T::LineList => (2, 0, 1),
        T::LineStrip => (1, 1, 1),
        T::TriangleList => (3, 0, 1),
        T::TriangleStrip => (1, 2, 2),
    }
}

/// Whether `r` draws instances (points as quads); indexed draws always draw one.
fn instanced(r: &Recorded) -> bool {
    r.index.is_none() && r.instances.1 > 1
}

/// The primitives (or, for points drawn as instanced quads, the instances) of `r`.
fn primitives(r: &Recorded) -> u32 {
    if instanced(r) {
        return r.instances.1;
    }
    let (per, shared, _) = layout(r.topology);
    r.count.saturating_sub(shared) / per
}

/// `r` cut into `n` parts of whole primitives (fewer if it has fewer).
fn parts(r: &Recorded, n: u32) -> Vec<Part> {
    if instanced(r) {
        let prims = r.instances.1;
        let run = prims.div_ceil(n).max(1);
        return (0..prims).step_by(run as usize).map(|a| Part::Instances(a, run.min(prims - a))).collect();
    }
    element_parts(r.topology, r.count, n)
}

/// `count` elements of `topology` cut into at most `n` ranges of whole primitives.
fn element_parts(topology: wgpu::PrimitiveTopology, count: u32, n: u32) -> Vec<Part> {
    let (per, shared, align) = layout(topology);
    let prims = count.saturating_sub(shared) / per;
    let run = prims.div_ceil(n.max(1)).div_ceil(align).max(1) * align;
    (0..prims)
        .step_by(run as usize)
        .map(|a| {
            let b = (a + run).min(prims);
            Part::Elements(a * per, (b - a) * per + shared)
        })
        .collect()
}

/// `height` rows cut into at most `n` bands.
fn bands(height: u32, n: u32) -> Vec<[u32; 2]> {
    let height = height.max(1);
    let rows = height.div_ceil(n.clamp(1, height));
    (0..height).step_by(rows as usize).map(|y| [y, (y + rows).min(height)]).collect()
}

/// `pass` cut into about `k` pieces, cutting a draw by primitives when it has at least
/// `min_primitives` per piece.
pub(super) fn plan(pass: &Pass, k: usize, min_primitives: u32) -> Vec<Piece> {
    let draws = pass.draws.len();
    if k <= 1 || draws == 0 {
        return vec![Piece::whole(pass)];
    }
    if draws >= k {
        let run = draws.div_ceil(k);
        return (0..draws)
            .step_by(run)
            .map(|a| Piece { draws: a..(a + run).min(draws), part: None, band: None })
            .collect();
    }
    let per = k.div_ceil(draws) as u32;
    let mut pieces = Vec::new();
    for (d, r) in pass.draws.iter().enumerate() {
        if primitives(r) >= per * min_primitives {
            pieces.extend(parts(r, per).into_iter().map(|p| Piece { draws: d..d + 1, part: Some(p), band: None }));
        } else {
            let height = pass.target.height;
            pieces.extend(bands(height, per).into_iter().map(|b| Piece { draws: d..d + 1, part: None, band: Some(b) }));
        }
    }
    pieces
}

impl Renderer {
    /// How to cut `pass`, judging by what the same target's pass took last time.
    pub(super) fn pieces(&self, pass: &Pass) -> Vec<Piece> {
        let k = match (self.lane.forced_pieces(), self.pass_costs.get(&pass.target.key)) {
            // Forced (a test of the image): cut by primitives wherever a draw has enough of
            // them, so both kinds of cut are exercised.
            (Some(n), _) => return plan(pass, n.min(MAX_PIECES), 1),
            (None, Some(est)) => {
                let target = self.lane.slice_target().as_secs_f64().max(1e-4);
                (est.as_secs_f64() / target).ceil().clamp(1.0, MAX_PIECES as f64) as usize
            }
            (None, None) => FIRST_PIECES,
        };
        plan(pass, k.min(MAX_PIECES), MIN_PRIMITIVES)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn covered(parts: &[Part], topology: wgpu::PrimitiveTopology, count: u32) -> Vec<u32> {
        // Every primitive's first element, as the parts draw them.
        let (per, shared, _) = layout(topology);
        let mut firsts = Vec::new();
        for p in parts {
            let Part::Elements(s, n) = *p else { panic!("elements expected") };
            assert!(s + n <= count, "{p:?} runs past {count}");
            let mut e = s;
            while e + per + shared <= s + n {
                firsts.push(e);
                e += per;
            }
        }
        firsts
    }

    #[test]
    fn parts_draw_every_primitive_once_and_keep_strip_winding() {
        use wgpu::PrimitiveTopology as T;
        for (topology, count) in
            [(T::TriangleList, 300), (T::TriangleStrip, 301), (T::LineList, 100), (T::LineStrip, 77)]
        {
            for n in [1, 2, 3, 7, 16] {
                let (per, shared, _) = layout(topology);
                let prims = (count - shared) / per;
                let p = element_parts(topology, count, n);
                assert!(p.len() as u32 <= n, "{topology:?} in {n}: {} parts", p.len());
                let firsts = covered(&p, topology, count);
                let want: Vec<u32> = (0..prims).map(|i| i * per).collect();
                assert_eq!(firsts, want, "{topology:?} in {n}");
                if topology == T::TriangleStrip {
                    assert!(p.iter().all(|p| matches!(p, Part::Elements(s, _) if s % 2 == 0)), "odd strip start");
                }
            }
        }
    }

    #[test]
    fn bands_cover_every_row_once() {
        for (h, n) in [(1, 5), (720, 16), (720, 512), (7, 3)] {
            let b = bands(h, n);
            assert!(b.len() as u32 <= n.max(1));
            assert_eq!(b.first().map(|b| b[0]), Some(0));
            assert_eq!(b.last().map(|b| b[1]), Some(h));
            assert!(b.windows(2).all(|w| w[0][1] == w[1][0]), "{b:?}");
        }
    }
}
