//! Declared projections: within a z-group the compositor compares eye-space depth, each
//! surface's window depth linearised by its own projection (raw depth when it declares none; a
//! surface without a depth image at its far plane). Surfaces show planes tilted in their own
//! eye spaces under different projections, arranged so that raw and eye-space comparison pick
//! different surfaces on a known part of the overlap; the GPU compositor must match the f64
//! reference there, and chained passes must stay bit-identical to one pass.

use super::*;
use strata_protocol::projection::{Projection, ProjectionKind};

/// Relative eye-depth gap below which f32 (the shader) and f64 (the reference) may choose
/// differently.
const REL: f64 = 1e-4;

fn persp(near: f32, far: f32, reversed: bool) -> Option<Projection> {
    Some(Projection { kind: ProjectionKind::Perspective, near, far, reversed })
}

fn ortho(near: f32, far: f32) -> Option<Projection> {
    Some(Projection { kind: ProjectionKind::Orthographic, near, far, reversed: false })
}

/// The window depth of eye distance `z` under `p` (GL's projection and depth range, flipped
/// when reversed); undeclared, `z` is the raw depth itself.
fn window_depth(p: Option<&Projection>, z: f64) -> f32 {
    let Some(p) = p else { return z as f32 };
    let (n, f) = (f64::from(p.near), f64::from(p.far));
    let d = match p.kind {
        ProjectionKind::Orthographic => (z - n) / (f - n),
        ProjectionKind::Perspective if f.is_infinite() => 1.0 - n / z,
        ProjectionKind::Perspective => f * (z - n) / (z * (f - n)),
    };
    (if p.reversed { 1.0 - d } else { d }) as f32
}

/// Eye distance at fraction `t` across a plane that is `z0` away at one edge and `z1` at the
/// other: 1/z is affine across the screen, as a plane's is under perspective.
fn across(t: f64, z0: f64, z1: f64) -> f64 {
    1.0 / ((1.0 - t) / z0 + t / z1)
}

/// Surface `i` at `rect` (z-group 0.5) with `proj`, showing a plane of its own eye space that is
/// `z0` away at its left edge and `z1` at its right, leaning by `lean` (1/z, bottom to top);
/// without `z0` it has no depth image.
fn plane(i: usize, rect: [i32; 4], proj: Option<Projection>, z: Option<(f64, f64)>, lean: f64) -> RefLayer {
    let (w, h) = (rect[2], rect[3]);
    let depth = z.map(|(z0, z1)| {
        let mut d = Vec::with_capacity((w * h) as usize);
        // Rows bottom first, as GL stores them.
        for y in 0..h {
            for x in 0..w {
                let (t, u) = ((f64::from(x) + 0.5) / f64::from(w), (f64::from(y) + 0.5) / f64::from(h));
                let inv = 1.0 / across(t, z0, z1) + lean * (u - 0.5);
                d.push(window_depth(proj.as_ref(), 1.0 / inv));
            }
        }
        d
    });
    RefLayer { depth, projection: proj, ..surface(i, rect, 0.5, 255, false) }
}

/// The depth by which `l` competes at its pixel (sx, sy) (sy from the bottom): eye depth, or
/// raw window depth with `eye` false (as if no surface declared a projection).
fn compared(l: &RefLayer, sx: i32, sy: i32, eye: bool) -> f64 {
    let p = l.projection.filter(|_| eye);
    match &l.depth {
        Some(d) => {
            let d = f64::from(d[(sy * l.rect[2] + sx) as usize]);
            p.map_or(d, |p| p.eye_depth(d))
        }
        None => p.map_or(1.0, |p| f64::from(p.far)),
    }
}

/// Per output pixel (top row first) of a one-group scene: the surface that wins (nearest, the
/// later on a tie) and whether another comes within `REL` of it.
fn winners(layers: &[RefLayer], eye: bool) -> Vec<Option<(usize, bool)>> {
    let mut out = Vec::with_capacity((OUT_W * OUT_H) as usize);
    for py in 0..OUT_H as i32 {
        for px in 0..OUT_W as i32 {
            let mut cands = Vec::new();
            for (i, l) in layers.iter().enumerate() {
                let (lx, ly) = (px - l.rect[0], py - l.rect[1]);
                if lx >= 0 && ly >= 0 && lx < l.rect[2] && ly < l.rect[3] {
                    cands.push((i, compared(l, lx, l.rect[3] - 1 - ly, eye)));
                }
            }
            let best = cands.iter().fold(None::<(usize, f64)>, |b, &(i, d)| match b {
                Some((_, bd)) if d > bd => b,
                _ => Some((i, d)),
            });
            out.push(best.map(|(w, d)| {
                let close = cands.iter().any(|&(i, e)| i != w && (e - d).abs() <= REL * d.abs().max(e.abs()));
                (w, close)
            }));
        }
    }
    out
}

/// `img` with the pixels where `skip` holds blanked.
fn blank(img: &[u8], skip: &[bool]) -> Vec<u8> {
    img.chunks(4).zip(skip).flat_map(|(p, &s)| if s { [0; 4] } else { [p[0], p[1], p[2], p[3]] }).collect()
}

/// Pixels (top row first) where two images differ.
fn differs(a: &[u8], b: &[u8]) -> Vec<bool> {
    a.chunks(4).zip(b.chunks(4)).map(|(p, q)| p != q).collect()
}

/// `layers` with every projection dropped: what comparing raw depth would show.
fn raw(layers: &[RefLayer]) -> Vec<RefLayer> {
    layers.iter().cloned().map(|l| RefLayer { projection: None, ..l }).collect()
}

/// Two surfaces at one z, IC-like A at [8, 8, 64, 40] (a plane 2 → 40 away, left to right) and
/// HU-like B at [24, 16, 64, 40] (16 → 4), under the given projections; they overlap in
/// columns 24..72 and rows 16..48, and A is the nearer in eye space on 31 of those 48 columns.
fn pair(a: Option<Projection>, b: Option<Projection>) -> Vec<RefLayer> {
    vec![plane(1, [8, 8, 64, 40], a, Some((2.0, 40.0)), 0.0), plane(2, [24, 16, 64, 40], b, Some((16.0, 4.0)), 0.0)]
}

#[test]
fn declared_projections_compare_eye_depth_on_the_gpu_as_in_the_reference() {
    let off = Lighting { enabled: false, ..Lighting::default() };
    // (A, B, overlap columns where raw and eye-space comparison pick different surfaces):
    // perspective 0.1/100 against 1/10000 (finite, then reversed with far at infinity), where
    // raw depth puts B in front everywhere; orthographic 0/50 against perspective 1/10000,
    // where raw depth puts A in front everywhere.
    let cases = [
        ("IC 0.1/100 vs HU 1/10000", persp(0.1, 100.0, false), persp(1.0, 10000.0, false), 31),
        ("IC 0.1/100 vs HU reversed 1/inf", persp(0.1, 100.0, false), persp(1.0, f32::INFINITY, true), 31),
        ("orthographic 0/50 vs HU 1/10000", ortho(0.0, 50.0), persp(1.0, 10000.0, false), 48 - 31),
    ];
    let mut scenes = Vec::new();
    for (name, a, b, columns) in cases {
        let layers = pair(a, b);
        // The planes cross in eye space: A is nearer on 31 of the 48 overlapping columns.
        let eye = winners(&layers, true);
        let a_near = (24..72).filter(|&x| eye[(20 * OUT_W + x) as usize] == Some((0, false))).count();
        assert_eq!(a_near, 31, "{name}: the scene's planes");
        assert!(eye.iter().flatten().all(|&(_, close)| !close), "{name}: a pixel too close to call");
        // Raw and eye-space comparison pick different surfaces on a known part of the overlap,
        // and the reference follows the projections exactly there.
        let by_raw = winners(&layers, false);
        let flips: Vec<bool> = eye.iter().zip(&by_raw).map(|(e, r)| e.map(|e| e.0) != r.map(|r| r.0)).collect();
        let n = flips.iter().filter(|&&f| f).count();
        assert_eq!(n, columns * 32, "{name}: pixels where raw and eye-space depth disagree");
        let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &off);
        let want_raw = reference::composite(&raw(&layers), OUT_W, OUT_H, BACKGROUND, &off);
        assert!(differs(&want, &want_raw) == flips, "{name}: the reference ignores a projection");
        scenes.push((name, layers, want));
    }
    // A surface without a depth image lies at its far plane: C (perspective 0.5/6, no depth)
    // over A and B is in front where both are farther than 6, behind where either is nearer.
    let mut layers = pair(persp(0.1, 100.0, false), persp(1.0, 10000.0, false));
    layers.push(plane(3, [40, 4, 24, 56], persp(0.5, 6.0, false), None, 0.0));
    let eye = winners(&layers, true);
    assert!(eye.iter().flatten().all(|&(_, close)| !close), "far plane: a pixel too close to call");
    let c_wins = eye.iter().filter(|w| w.is_some_and(|w| w.0 == 2)).count();
    assert!(c_wins > 24 * 10 && c_wins < 24 * 46, "C must win in part of its rectangle: {c_wins}");
    let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &off);
    scenes.push(("a surface without depth at its far plane", layers, want));

    let Some(gpu) = gpu() else { return };
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    for (name, layers, want) in &scenes {
        check(name, &run(&gpu, &mut comp, layers, &off), want, 0);
        let lit = Lighting { normals: NormalSource::FromDepth, ..Lighting::default() };
        let want = reference::composite(layers, OUT_W, OUT_H, BACKGROUND, &lit);
        check(&format!("{name}, lit from depth"), &run(&gpu, &mut comp, layers, &lit), &want, 1);
    }
}

/// Seven surfaces of one group, each under its own projection (perspective finite, reversed,
/// reversed with far at infinity, orthographic, undeclared, and one without depth), overlapping
/// in the middle of the output.
fn seven() -> Vec<RefLayer> {
    vec![
        plane(0, [4, 4, 60, 44], persp(0.1, 100.0, false), Some((3.0, 30.0)), 0.02),
        plane(1, [30, 10, 60, 48], persp(1.0, 10000.0, false), Some((25.0, 4.0)), -0.01),
        plane(2, [16, 2, 56, 40], persp(0.5, f32::INFINITY, true), Some((8.0, 12.0)), 0.03),
        plane(3, [20, 20, 70, 40], ortho(0.0, 50.0), Some((40.0, 5.0)), 0.0),
        plane(4, [36, 6, 30, 50], persp(0.5, 9.0, false), None, 0.0),
        plane(5, [44, 24, 16, 12], None, Some((0.3, 0.9)), 0.1),
        plane(6, [10, 14, 80, 30], persp(1.0, 1000.0, true), Some((6.0, 20.0)), -0.02),
    ]
}

#[test]
fn chained_passes_with_declared_projections_match_one_pass_and_the_reference() {
    let layers = seven();
    let eye = winners(&layers, true);
    let by_raw = winners(&layers, false);
    let flips = eye.iter().zip(&by_raw).filter(|(e, r)| e.map(|e| e.0) != r.map(|r| r.0)).count();
    assert!(flips > 300, "raw and eye-space comparison must differ widely: {flips} pixels");
    let close: Vec<bool> = eye.iter().map(|w| w.is_some_and(|w| w.1)).collect();
    let n_close = close.iter().filter(|&&c| c).count();
    assert!(n_close * 100 < close.len(), "{n_close} pixels too close to call");
    for w in 0..layers.len() {
        assert!(eye.iter().any(|e| e.is_some_and(|e| e.0 == w)), "surface {w} must win somewhere");
    }

    let Some(gpu) = gpu() else { return };
    let mut single = Compositor::new(gpu.clone(), None).expect("device limit");
    let off = Lighting { enabled: false, ..Lighting::default() };
    let lit = Lighting { normals: NormalSource::FromDepth, ..Lighting::default() };
    for (name, light, tol) in [("unlit", off, 0), ("lit from depth", lit, 1)] {
        let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
        let one = run(&gpu, &mut single, &layers, &light);
        check(name, &blank(&one, &close), &blank(&want, &close), tol);
        for m in [4u32, 6] {
            let mut c = Compositor::new(gpu.clone(), Some(m)).expect("limit");
            let got = run(&gpu, &mut c, &layers, &light);
            assert!(c.last_stats.chained > 0, "{name}: --max-textures {m} must chain");
            assert!(got == one, "{name}: --max-textures {m} differs from one pass");
        }
    }
}
