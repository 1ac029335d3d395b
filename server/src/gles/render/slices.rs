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
//! slice is cut again, into bands, by how much longer it took, and neighbouring pieces that
//! took little are joined. Frame after frame, the cuts follow where the work is.

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
/// Most bands one long piece is cut into again at one pass.
const MAX_REFINE: u32 = 64;
/// Targets whose costs are remembered per client.
const REMEMBERED: usize = 256;

/// A part of one draw: a range of its vertices (or indices), or of its instances.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
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

/// How a pass is cut: the pieces before refinement (`base`, about `k` of them), which say
/// whether the next pass is the same one, and the pieces submitted.
pub(super) struct Plan {
    k: usize,
    base: Vec<Piece>,
    pub(super) pieces: Vec<Piece>,
}

impl Plan {
    /// The whole pass in one piece.
    pub(super) fn whole(pass: &Pass) -> Plan {
        Plan { k: 1, base: vec![Piece::whole(pass)], pieces: vec![Piece::whole(pass)] }
    }

    fn unrefined(k: usize, base: Vec<Piece>) -> Plan {
        Plan { k, pieces: base.clone(), base }
    }
}

/// What a target's pass took last time: how it was cut (its plan) and the time of each piece.
pub(super) struct Costs {
    plan: Plan,
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

/// `a` and `b` (which follows it) as one piece, if they are adjacent parts of the same work:
/// neighbouring bands of one draw (or part), or neighbouring runs of whole draws.
fn merged(a: &Piece, b: &Piece) -> Option<Piece> {
    match (a.band, b.band) {
        (Some([top, mid]), Some([mid2, bottom])) if a.draws == b.draws && a.part == b.part && mid == mid2 => {
            Some(Piece { draws: a.draws.clone(), part: a.part, band: Some([top, bottom]) })
        }
        (None, None) if a.part.is_none() && b.part.is_none() && a.draws.end == b.draws.start => {
            Some(Piece { draws: a.draws.start..b.draws.end, part: None, band: None })
        }
        _ => None,
    }
}

/// What cutting needs to know of a draw: its topology, its elements and, for points drawn as
/// instanced quads, its instances (else 1).
#[derive(Debug, Clone, Copy)]
pub(super) struct DrawSize {
    topology: wgpu::PrimitiveTopology,
    count: u32,
    instances: u32,
}

impl DrawSize {
    /// The size of recorded draw `r`.
    pub(super) fn of(r: &Recorded) -> DrawSize {
        DrawSize { topology: r.topology, count: r.count, instances: if instanced(r) { r.instances.1 } else { 1 } }
    }
}

/// `piece` cut into about `n` pieces, dividing vertex work as well as fragment work where it
/// can: a run of draws into its draws, a draw (or a part of one) with enough primitives into
/// ranges of them, and only what is left into bands of rows.
fn split(piece: &Piece, n: u32, sizes: &[DrawSize], height: u32) -> Vec<Piece> {
    let draws = piece.draws.clone();
    if piece.part.is_none() && draws.len() > 1 {
        let per = n.div_ceil(draws.len() as u32);
        return draws
            .flat_map(|d| split(&Piece { draws: d..d + 1, part: None, band: piece.band }, per, sizes, height))
            .collect();
    }
    let sub = match (sizes.get(draws.start), piece.part, piece.band) {
        (Some(z), part, None) if z.instances > 1 => {
            let (start, count) = match part {
                Some(Part::Instances(s, c)) => (s, c),
                _ => (0, z.instances),
            };
            let run = count.div_ceil(n).max(1);
            (0..count).step_by(run as usize).map(|a| Part::Instances(start + a, run.min(count - a))).collect()
        }
        (Some(z), part, None) => {
            let (start, count) = match part {
                Some(Part::Elements(s, c)) => (s, c),
                _ => (0, z.count),
            };
            let (per, shared, _) = layout(z.topology);
            if count.saturating_sub(shared) / per >= n * MIN_PRIMITIVES {
                element_parts(z.topology, count, n)
                    .into_iter()
                    .filter_map(|p| match p {
                        Part::Elements(s, c) => Some(Part::Elements(start + s, c)),
                        Part::Instances(..) => None,
                    })
                    .collect()
            } else {
                Vec::new()
            }
        }
        _ => Vec::new(),
    };
    if sub.len() > 1 {
        return sub.into_iter().map(|p| Piece { draws: draws.clone(), part: Some(p), band: None }).collect();
    }
    rebanded(piece, n, height)
}

/// The pieces of last time, each cut again by how much longer than `slice` it took (see
/// `split`), and neighbours that together took less than half a slice joined. Repeated frame
/// after frame, the cuts narrow onto where the work is, and the number of submissions stays
/// near the pass's time divided by the slice (at most `MAX_PIECES`).
fn refine(pieces: &[Piece], times: &[Duration], slice: Duration, sizes: &[DrawSize], height: u32) -> Vec<Piece> {
    let mut out: Vec<Piece> = Vec::with_capacity(pieces.len());
    // What the last piece of `out` took (a slice for one just cut, so nothing joins it).
    let mut last = slice;
    for (i, (piece, &t)) in pieces.iter().zip(times).enumerate() {
        let room = MAX_PIECES.saturating_sub(out.len() + pieces.len() - i) as u32 + 1;
        let n = (t.as_secs_f64() / slice.as_secs_f64()).ceil().clamp(1.0, f64::from(MAX_REFINE.min(room))) as u32;
        if n > 1 {
            out.extend(split(piece, n, sizes, height));
            last = slice;
            continue;
        }
        if let Some(joined) = out.last().filter(|_| last + t <= slice / 2).and_then(|prev| merged(prev, piece)) {
            if let Some(prev) = out.last_mut() {
                *prev = joined;
            }
            last += t;
            continue;
        }
        out.push(piece.clone());
        last = t;
    }
    out
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
        let base = plan(pass, costs.plan.k, MIN_PRIMITIVES);
        if base != costs.plan.base {
            let total: Duration = costs.times.iter().sum();
            let k = (total.as_secs_f64() / slice.as_secs_f64()).ceil().clamp(1.0, MAX_PIECES as f64) as usize;
            return Plan::unrefined(k, plan(pass, k, MIN_PRIMITIVES));
        }
        let sizes: Vec<DrawSize> = pass.draws.iter().map(DrawSize::of).collect();
        let pieces = refine(&costs.plan.pieces, &costs.times, slice, &sizes, pass.target.height);
        Plan { k: costs.plan.k, base, pieces }
    }

    /// Remembers what each piece of `plan` took (`None`: untimed, nothing is kept).
    pub(super) fn remember(&mut self, pass: &Pass, plan: Plan, times: &[Option<Duration>]) {
        let Some(times) = times.iter().copied().collect::<Option<Vec<Duration>>>() else { return };
        if times.len() != plan.pieces.len() {
            return;
        }
        tracing::debug!(
            key = ?pass.target.key,
            draws = pass.draws.len(),
            pieces = plan.pieces.len(),
            took_ms = times.iter().sum::<Duration>().as_secs_f64() * 1e3,
            longest_ms = times.iter().max().map(|t| t.as_secs_f64() * 1e3),
            "sliced pass"
        );
        if self.pass_costs.len() >= REMEMBERED {
            self.pass_costs.clear();
        }
        self.pass_costs.insert(shape(pass), Costs { plan, times });
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

    /// Every (draw, part, row) the pieces draw, sorted: each fragment's draws keep their
    /// order within a piece, and the pieces keep the pass's.
    fn cells(pieces: &[Piece], height: u32) -> Vec<(usize, Option<Part>, u32)> {
        let mut out = Vec::new();
        for p in pieces {
            for d in p.draws.clone() {
                let [a, b] = p.band.unwrap_or([0, height]);
                out.extend((a..b).map(|y| (d, p.part, y)));
            }
        }
        out.sort_unstable();
        out
    }

    #[test]
    fn refining_narrows_long_pieces_joins_short_ones_and_draws_everything_once() {
        let ms = Duration::from_millis;
        let height = 720;
        let draws = |r: Range<usize>| Piece { draws: r, part: None, band: None };
        let pieces = vec![draws(0..2), draws(2..4), draws(4..6), draws(6..7)];
        let times = [ms(40), Duration::from_micros(300), Duration::from_micros(400), ms(3)];
        let out = refine(&pieces, &times, ms(2), &[], height);
        assert!(cells(&out, height) == cells(&pieces, height), "{} pieces", out.len());
        // 40 ms in 2 ms slices: 20 bands; the two short runs joined; 3 ms in two bands.
        assert_eq!(out.len(), 20 + 1 + 2, "{out:?}");
        assert_eq!(out[20], draws(2..6));
        // Again, with all the time in one band of the first piece: only that band is cut.
        let mut t = vec![Duration::from_micros(100); out.len()];
        t[3] = ms(10);
        let again = refine(&out, &t, ms(2), &[], height);
        assert!(cells(&again, height) == cells(&pieces, height));
        // Bands 0–2 joined, band 3 in five, bands 4–19 joined in runs of at most half a
        // slice (ten), the runs of draws, and the last draw's two bands joined.
        assert_eq!(again.len(), 1 + 5 + 2 + 1 + 1, "{again:?}");
        let narrow = again.iter().filter(|p| p.band.is_some_and(|[a, b]| b - a < 36)).count();
        assert_eq!(narrow, 5, "{again:?}");
        // Never more than MAX_PIECES, however long.
        let huge = refine(&out, &vec![ms(1000); out.len()], ms(2), &[], height);
        assert!(huge.len() <= MAX_PIECES, "{}", huge.len());
        assert!(cells(&huge, height) == cells(&pieces, height));
    }

    #[test]
    fn long_draws_are_cut_by_primitives_before_rows() {
        use wgpu::PrimitiveTopology as T;
        let sizes = [
            DrawSize { topology: T::TriangleList, count: 3000, instances: 1 },
            DrawSize { topology: T::TriangleStrip, count: 4, instances: 1 },
            DrawSize { topology: T::TriangleStrip, count: 4, instances: 400 },
        ];
        let whole = |d: usize| Piece { draws: d..d + 1, part: None, band: None };
        // A thousand triangles in four ranges; a range of them in four again, within it.
        let four = split(&whole(0), 4, &sizes, 100);
        assert_eq!(four.len(), 4);
        assert!(four.iter().all(|p| p.band.is_none()), "{four:?}");
        let again = split(&four[1], 4, &sizes, 100);
        let elements: Vec<(u32, u32)> = again
            .iter()
            .map(|p| match p.part {
                Some(Part::Elements(s, c)) => (s, c),
                _ => (0, 0),
            })
            .collect();
        assert_eq!(elements, vec![(750, 189), (939, 189), (1128, 189), (1317, 183)]);
        // A quad has too few primitives: rows.
        let quad = split(&whole(1), 4, &sizes, 100);
        assert_eq!(quad.iter().map(|p| p.band).collect::<Vec<_>>(), [[0, 25], [25, 50], [50, 75], [75, 100]].map(Some));
        // Points drawn as instances: ranges of instances.
        let points = split(&whole(2), 4, &sizes, 100);
        assert_eq!(points[3].part, Some(Part::Instances(300, 100)));
        // A run of draws: its draws first, each cut on its own.
        let run = split(&Piece { draws: 0..2, part: None, band: None }, 8, &sizes, 100);
        assert_eq!(run.len(), 8, "{run:?}");
        assert_eq!(run.iter().filter(|p| p.draws == (0..1)).count(), 4);
    }
}
