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
//! Work is rarely spread evenly over a draw's primitives (a few triangles may cover most of
//! the target), so when a pass is cut as it was last time, each piece that took longer than a
//! slice is cut again, into bands, by how much longer it took.

use std::ops::Range;
use std::time::Duration;

use super::passes::{Pass, Recorded};
use super::Renderer;

/// The most pieces one pass is cut into.
const MAX_PIECES: usize = 512;
/// Pieces of a pass whose cost is not known yet.
const FIRST_PIECES: usize = 16;
/// Fewest primitives in one range of a draw cut by primitives.
const MIN_PRIMITIVES: u32 = 16;
/// Most bands one long piece is cut into again.
const MAX_REFINE: u32 = 32;
/// Targets whose costs are remembered per client.
const REMEMBERED: usize = 256;

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

/// How a pass is cut: the pieces before refinement (`base`), the pieces submitted, and for
/// each of these the base piece it belongs to.
pub(super) struct Plan {
    k: usize,
    base: Vec<Piece>,
    pub(super) pieces: Vec<Piece>,
    owner: Vec<usize>,
}

impl Plan {
    /// The whole pass in one piece.
    pub(super) fn whole(pass: &Pass) -> Plan {
        Plan { k: 1, base: vec![Piece::whole(pass)], pieces: vec![Piece::whole(pass)], owner: vec![0] }
    }

    fn unrefined(k: usize, base: Vec<Piece>) -> Plan {
        Plan { k, owner: (0..base.len()).collect(), pieces: base.clone(), base }
    }
}

/// What a target's pass took last time: the pieces it was cut into before refinement (about
/// `k` of them) and the time of each.
pub(super) struct Costs {
    k: usize,
    base: Vec<Piece>,
    times: Vec<Duration>,
}

/// `piece` cut into `n` bands of its own band, or of the target's `height` rows.
fn rebanded(piece: &Piece, n: u32, height: u32) -> Vec<Piece> {
    let [top, bottom] = piece.band.unwrap_or([0, height.max(1)]);
    bands(bottom - top, n)
        .into_iter()
        .map(|[a, b]| Piece { draws: piece.draws.clone(), part: piece.part, band: Some([top + a, top + b]) })
        .collect()
}

/// What identifies "the same pass" across frames: its target and the shape of its draws (a
/// frame may draw into one target more than once, differently).
pub(super) fn shape(pass: &Pass) -> ((u64, u64), u64) {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for r in &pass.draws {
        (r.count, r.first, r.instances, r.index.is_some()).hash(&mut h);
    }
    (pass.target.key, h.finish())
}

impl Renderer {
    /// How to cut `pass`, judging by what the same target's pass took last time.
    pub(super) fn plan_for(&self, pass: &Pass) -> Plan {
        if let Some(n) = self.lane.forced_pieces() {
            // A test of the image: cut by primitives wherever a draw has enough of them, so
            // both kinds of cut are exercised.
            return Plan::unrefined(n, plan(pass, n.min(MAX_PIECES), 1));
        }
        let slice = self.lane.slice_target().max(Duration::from_micros(100));
        let Some(costs) = self.pass_costs.get(&shape(pass)) else {
            return Plan::unrefined(FIRST_PIECES, plan(pass, FIRST_PIECES, MIN_PRIMITIVES));
        };
        // The same pass as last time (the same draws, cut the same way): refine its pieces.
        // Otherwise cut it anew by what it took in all.
        let base = plan(pass, costs.k, MIN_PRIMITIVES);
        if base != costs.base {
            let total: Duration = costs.times.iter().sum();
            let k = (total.as_secs_f64() / slice.as_secs_f64()).ceil().clamp(1.0, MAX_PIECES as f64) as usize;
            return Plan::unrefined(k, plan(pass, k, MIN_PRIMITIVES));
        }
        let mut refined = Plan { k: costs.k, base: base.clone(), pieces: Vec::new(), owner: Vec::new() };
        for (i, (piece, t)) in base.iter().zip(&costs.times).enumerate() {
            let n = (t.as_secs_f64() / slice.as_secs_f64()).ceil().clamp(1.0, f64::from(MAX_REFINE)) as u32;
            let cut = if n > 1 { rebanded(piece, n, pass.target.height) } else { vec![piece.clone()] };
            refined.owner.extend(std::iter::repeat_n(i, cut.len()));
            refined.pieces.extend(cut);
        }
        refined
    }

    /// Remembers what each base piece of `plan` took (`None`: untimed, nothing is kept).
    pub(super) fn remember(&mut self, pass: &Pass, plan: Plan, times: &[Option<Duration>]) {
        let mut per_base = vec![Duration::ZERO; plan.base.len()];
        for (owner, t) in plan.owner.iter().zip(times) {
            let (Some(slot), Some(t)) = (per_base.get_mut(*owner), t) else { return };
            *slot += *t;
        }
        tracing::debug!(
            key = ?pass.target.key,
            draws = pass.draws.len(),
            base = plan.base.len(),
            pieces = plan.pieces.len(),
            took_ms = per_base.iter().sum::<Duration>().as_secs_f64() * 1e3,
            longest_ms = times.iter().flatten().max().map(|t| t.as_secs_f64() * 1e3),
            "sliced pass"
        );
        if self.pass_costs.len() >= REMEMBERED {
            self.pass_costs.clear();
        }
        self.pass_costs.insert(shape(pass), Costs { k: plan.k, base: plan.base, times: per_base });
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
