//! The precision extremes of `docs/precision.md` ("Extremes"), one test each: near/far ratios
//! up to 1e9, coplanar surfaces, NaN and infinity in depth images, zero normals, lighting at
//! the ends of its ranges, 1×1 and maximum-size surfaces, 64 surfaces in one group, and a
//! depth-only phantom surface. The GPU compositor against the f64 reference throughout.

use super::*;
use strata_protocol::projection::{Projection, ProjectionKind};

const RED: [u8; 4] = [255, 0, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];

fn persp(near: f32, far: f32, reversed: bool) -> Option<Projection> {
    Some(Projection { kind: ProjectionKind::Perspective, near, far, reversed })
}

fn ortho(near: f32, far: f32) -> Option<Projection> {
    Some(Projection { kind: ProjectionKind::Orthographic, near, far, reversed: false })
}

/// A surface of one colour (straight alpha) at `rect` and `z`, with `depth` (rows bottom first)
/// or none, and `projection`.
fn solid(rect: [i32; 4], z: f32, rgba: [u8; 4], depth: Option<Vec<f32>>, projection: Option<Projection>) -> RefLayer {
    let n = (rect[2] * rect[3]) as usize;
    RefLayer { rect, z, color: rgba.repeat(n), depth, normal: [0.0, 0.0, 1.0], projection, props: Default::default() }
}

/// A `w`×`h` depth image (rows bottom first) whose texel at (x, y) is `f(x, y)`.
fn depth_map(w: i32, h: i32, f: impl Fn(i32, i32) -> f32) -> Vec<f32> {
    (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).map(|(x, y)| f(x, y)).collect()
}

/// The output pixel at (x, y) (from the top).
fn px(img: &[u8], x: i32, y: i32) -> [u8; 4] {
    let at = ((y * OUT_W as i32 + x) * 4) as usize;
    [img[at], img[at + 1], img[at + 2], img[at + 3]]
}

fn unlit() -> Lighting {
    Lighting { enabled: false, ..Lighting::default() }
}

/// A uniform number in [0, 1) from `seed` (splitmix64).
fn unit(seed: u64) -> f64 {
    let mut x = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((x ^ (x >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// Window depth of eye distance `e` under `p`, rounded to f32 as a depth image holds it.
fn window(p: &Projection, e: f64) -> f32 {
    let (n, f) = (f64::from(p.near), f64::from(p.far));
    let d = match p.kind {
        ProjectionKind::Orthographic => (e - n) / (f - n),
        ProjectionKind::Perspective => f * (e - n) / (e * (f - n)),
    };
    (if p.reversed { 1.0 - d } else { d }) as f32
}

/// One ulp of 1.0 in f32.
const ULP: f64 = 1.0 / 16_777_216.0;

/// The f32 select's error bound (docs/precision.md): the shader's eye depth of texel `d` lies
/// within the f64 eye depths of `d ± 4 ULP`, widened by 4 ULP relative.
fn eye_bounds(p: &Projection, d: f32) -> (f64, f64) {
    let d = f64::from(d);
    let (a, b) = (p.eye_depth(d - 4.0 * ULP), p.eye_depth(d + 4.0 * ULP));
    let (lo, hi) = (a.min(b), a.max(b));
    (lo - lo.abs() * 4.0 * ULP, hi + hi.abs() * 4.0 * ULP)
}

/// Near == far (ratio 1) is refused, for either kind: `EGL_BAD_ATTRIBUTE`, or a start-up error
/// from the layout.
#[test]
fn a_near_far_ratio_of_one_is_refused() {
    for kind in [ProjectionKind::Perspective, ProjectionKind::Orthographic] {
        let p = Projection { kind, near: 1.0, far: 1.0, reversed: false };
        assert!(p.validate().is_err(), "{kind:?} near == far must be refused");
        let mut attribs = p.to_egl_attribs().to_vec();
        attribs.push(0x3038);
        assert!(Projection::from_egl_attribs(&attribs).is_err(), "{kind:?} attributes");
    }
}

/// Near/far ratios 10 … 1e9: two full-output surfaces of one group whose eye depths are spread
/// log-uniformly over [near, far] (half the pixels independent, half within a relative gap of
/// 1e-9 … 1e-1 of each other). Wherever their eye-depth bounds (`eye_bounds`) are disjoint the
/// GPU picks what the reference picks; the rest is counted.
#[test]
fn near_far_ratios_up_to_1e9_select_as_the_reference_beyond_the_f32_bound() {
    let Some(gpu) = gpu() else { return };
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    let (w, h) = (OUT_W as i32, OUT_H as i32);
    let mut report = Vec::new();
    for r in [10.0f32, 1e3, 1e6, 1e9] {
        let pairs = [
            ("perspective", persp(1.0, r, false), persp(1.0, r, false)),
            ("perspective vs reversed", persp(1.0, r, false), persp(1.0, r, true)),
            ("perspective vs orthographic", persp(1.0, r, false), ortho(1.0, r)),
            ("orthographic", ortho(1.0, r), ortho(1.0, r)),
        ];
        for (name, pa, pb) in pairs {
            let (pa, pb) = (pa.expect("declared"), pb.expect("declared"));
            let (n, f) = (1.0f64, f64::from(r));
            let (mut da, mut db) = (Vec::new(), Vec::new());
            for i in 0..(w * h) as u64 {
                let ea = n * (f / n).powf(unit(3 * i));
                let eb = if i % 2 == 0 {
                    n * (f / n).powf(unit(3 * i + 1))
                } else {
                    let gap = 10f64.powf(-9.0 + 8.0 * unit(3 * i + 1));
                    let sign = if unit(3 * i + 2) < 0.5 { -1.0 } else { 1.0 };
                    (ea * (1.0 + sign * gap)).clamp(n, f)
                };
                da.push(window(&pa, ea));
                db.push(window(&pb, eb));
            }
            let layers = vec![
                solid([0, 0, w, h], 0.5, RED, Some(da.clone()), Some(pa)),
                solid([0, 0, w, h], 0.5, BLUE, Some(db.clone()), Some(pb)),
            ];
            let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &unlit());
            let got = run(&gpu, &mut comp, &layers, &unlit());
            let (mut close, mut differ, mut differ_far) = (0, 0, 0);
            for i in 0..(w * h) as usize {
                let (sx, sy) = (i as i32 % w, i as i32 / w);
                let (a, b) = (eye_bounds(&pa, da[i]), eye_bounds(&pb, db[i]));
                let overlap = a.0 <= b.1 && b.0 <= a.1;
                let (g, e) = (px(&got, sx, h - 1 - sy), px(&want, sx, h - 1 - sy));
                assert!(e == RED || e == BLUE, "{name} 1:{r}: the reference shows neither surface");
                close += usize::from(overlap);
                if g != e {
                    differ += 1;
                    differ_far += usize::from(pa.eye_depth(f64::from(da[i])) > 1e3);
                    assert!(
                        overlap,
                        "{name} 1:{r}: pixel {sx},{sy}: GPU and reference differ though the eye depths \
                         {a:?} and {b:?} are further apart than the f32 bound"
                    );
                }
            }
            report
                .push(format!("1:{r:e} {name}: {close} too close to call, {differ} differ ({differ_far} beyond 1e3)"));
        }
    }
    eprintln!("{}", report.join("\n"));
}

/// A surface's depth everywhere (`None`: no depth image) and projection.
type Spec = (Option<f32>, Option<Projection>);

/// Coplanar surfaces of different clients (one z, equal depth): the later surface in stacking
/// order wins, on the GPU as in the reference, in one pass and chained, with raw depth, with
/// one declared projection, and at the far plane of a surface without a depth image.
#[test]
fn coplanar_surfaces_go_to_the_later_one_in_stacking_order() {
    let rects = [[10, 10, 50, 40], [30, 20, 50, 40], [20, 5, 40, 30]];
    let colors = [RED, GREEN, BLUE];
    let flat = |r: [i32; 4], v: f32| depth_map(r[2], r[3], move |_, _| v);
    let p = persp(0.1, 100.0, false);
    let q = persp(1.0, 100.0, false);
    let cases: [(&str, [Spec; 3]); 3] = [
        ("raw depth 0.4", [(Some(0.4), None), (Some(0.4), None), (Some(0.4), None)]),
        ("declared 0.1/100 at 0.4", [(Some(0.4), p), (Some(0.4), p), (Some(0.4), p)]),
        // Eye depth 100 = 1·100 / (100 − 99), exactly, and the far plane of a surface without
        // depth.
        ("declared 1/100 at the far plane", [(Some(1.0), q), (None, q), (Some(1.0), q)]),
    ];
    let mut scenes = Vec::new();
    for (name, spec) in cases {
        let layers: Vec<RefLayer> =
            (0..3).map(|i| solid(rects[i], 0.5, colors[i], spec[i].0.map(|v| flat(rects[i], v)), spec[i].1)).collect();
        // What the rule says: the last covering surface, else the background.
        let mut expect = Vec::new();
        for y in 0..OUT_H as i32 {
            for x in 0..OUT_W as i32 {
                let top = (0..3).rev().find(|&i| {
                    let r = rects[i];
                    x >= r[0] && y >= r[1] && x < r[0] + r[2] && y < r[1] + r[3]
                });
                expect.extend_from_slice(&top.map_or([51, 102, 153, 255], |i| colors[i]));
            }
        }
        let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &unlit());
        check(&format!("{name}: the reference"), &want, &expect, 0);
        scenes.push((name, layers, expect));
    }
    let Some(gpu) = gpu() else { return };
    for m in [None, Some(4)] {
        let mut comp = Compositor::new(gpu.clone(), m).expect("compositor");
        for (name, layers, expect) in &scenes {
            check(&format!("{name}, limit {m:?}"), &run(&gpu, &mut comp, layers, &unlit()), expect, 0);
        }
    }
}

/// Reads a Depth32Float image back.
fn read_depth(gpu: &Gpu, tex: &wgpu::Texture) -> Vec<f32> {
    let (w, h) = (tex.width(), tex.height());
    let row = (w * 4).div_ceil(256) * 256;
    let buf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(row * h),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    enc.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: tex,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::DepthOnly,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buf,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    gpu.submit(&gpu.lane, vec![enc.finish()]);
    let slice = buf.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    let _ = gpu.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: None });
    rx.recv().expect("mapped").expect("map");
    let data = slice.get_mapped_range().expect("range");
    let mut out = Vec::with_capacity((w * h) as usize);
    for r in 0..h as usize {
        let start = r * row as usize;
        let bytes = &data[start..start + (w * 4) as usize];
        out.extend(bytes.chunks_exact(4).map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]])));
    }
    out
}

/// Texels of the non-finite test, by column (mod 10): quiet NaN, negative NaN, signalling
/// NaN, +inf, −inf, 2, −1, 0.25, 0.75, 1.
fn special(x: i32) -> f32 {
    let v = [
        f32::NAN,
        f32::from_bits(0xffc0_0000),
        f32::from_bits(0x7f80_0001),
        f32::INFINITY,
        f32::NEG_INFINITY,
        2.0,
        -1.0,
        0.25,
        0.75,
        1.0,
    ];
    v[x.rem_euclid(10) as usize]
}

/// NaN, ±inf and out-of-range texels: NaN lies at the surface's far plane, everything is
/// clamped to [0, 1]; the reference says so (whatever the stacking order), and the GPU, given
/// what the device stores for such texels, shows what the reference shows for them.
#[test]
fn nan_and_infinite_depth_texels_read_as_the_far_plane_and_clamped() {
    let (w, h) = (OUT_W as i32, OUT_H as i32);
    let odd = depth_map(w, h, |x, _| special(x));
    // B: depth 0.5 everywhere. Which surface each column's texel puts in front, per projection.
    let raw_wins_a = [false, false, false, false, true, false, true, true, false, false];
    let rev_wins_a = [false, false, false, true, false, true, false, false, true, true];
    let projections = [("raw", None, raw_wins_a), ("reversed 1/100", persp(1.0, 100.0, true), rev_wins_a)];
    let scene = |depth: &[f32], p: Option<Projection>, a_first: bool| {
        let a = solid([0, 0, w, h], 0.5, RED, Some(depth.to_vec()), p);
        let b = solid([0, 0, w, h], 0.5, BLUE, Some(vec![0.5; (w * h) as usize]), p);
        if a_first {
            vec![a, b]
        } else {
            vec![b, a]
        }
    };
    for (name, p, wins) in projections {
        for a_first in [true, false] {
            let img = reference::composite(&scene(&odd, p, a_first), OUT_W, OUT_H, BACKGROUND, &unlit());
            for x in 0..10 {
                let want = if wins[x as usize] { RED } else { BLUE };
                assert_eq!(px(&img, x, 5), want, "{name}, A first {a_first}: the reference at texel {}", special(x));
            }
        }
    }
    // Surfaces at +inf eye depth (far at infinity, at d = 1 or without depth): a tie, so the
    // later one wins.
    let inf = persp(1.0, f32::INFINITY, false);
    let at_inf = vec![
        solid([0, 0, 40, 40], 0.5, RED, Some(vec![1.0; 1600]), inf),
        solid([20, 0, 40, 40], 0.5, GREEN, None, inf),
        solid([40, 0, 40, 40], 0.5, BLUE, Some(vec![1.0; 1600]), inf),
    ];
    let img = reference::composite(&at_inf, OUT_W, OUT_H, BACKGROUND, &unlit());
    assert_eq!([px(&img, 30, 5), px(&img, 50, 5), px(&img, 70, 5)], [GREEN, BLUE, BLUE], "ties at +inf");

    let Some(gpu) = gpu() else { return };
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    check("+inf eye depths", &run(&gpu, &mut comp, &at_inf, &unlit()), &img, 0);
    // The device's depth image for those texels (wgpu writes depth through a fragment's depth).
    let usage =
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let tex = texture(&gpu, w as u32, h as u32, wgpu::TextureFormat::Depth32Float, usage);
    strata_scene::depth::Depth::of(&gpu).write(&tex, w as u32, h as u32, &odd);
    let stored = read_depth(&gpu, &tex);
    let shown: Vec<String> = stored[..10].iter().map(|v| format!("{v:?}")).collect();
    eprintln!("Depth32Float holds, for {:?}: [{}]", (0..10).map(special).collect::<Vec<_>>(), shown.join(", "));
    let view = tex.create_view(&Default::default());
    let lit = Lighting { normals: NormalSource::FromDepth, ..Lighting::default() };
    for (name, p, _) in projections {
        for a_first in [true, false] {
            let layers = scene(&stored, p, a_first);
            let up: Vec<Uploaded> = layers.iter().map(|l| upload(&gpu, l)).collect();
            for (light, tol) in [(unlit(), 0), (lit, 1)] {
                let mut gl: Vec<Layer<'_>> = layers.iter().zip(&up).map(|(l, u)| u.layer(l)).collect();
                // A's depth: the image as the device wrote it.
                gl[usize::from(!a_first)].depth = Some(&view);
                let out = output(&gpu);
                comp.composite(&gl, &light, &out, BACKGROUND, None).expect("composite");
                let got = gpu.read_rgba8(&out, [0, 0, OUT_W, OUT_H]).expect("readback");
                let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
                check(&format!("{name}, A first {a_first}, lit {}", light.enabled), &got, &want, tol);
            }
        }
    }
}

/// A zero normal (also a NaN or infinite one) has no direction: ambient only, whatever the
/// light, view or shininess; a tiny finite one is a direction like any other.
#[test]
fn zero_normals_are_lit_by_ambient_only() {
    let c = [200, 100, 50, 255];
    let mut layers = vec![
        solid([4, 4, 20, 20], 0.5, c, None, None),
        solid([30, 4, 20, 20], 0.5, c, None, None),
        solid([56, 4, 20, 20], 0.5, c, None, None),
        solid([4, 34, 20, 20], 0.5, c, None, None),
        solid([30, 34, 20, 20], 0.5, c, None, None),
        // Over the first: the select runs where they overlap.
        solid([14, 14, 20, 20], 0.5, c, None, None),
        solid([60, 30, 30, 30], 0.3, [90, 180, 240, 255], None, None),
    ];
    let normals = [[0.0; 3], [f32::NAN, 0.0, 1.0], [f32::INFINITY, 1.0, 0.0], [1e-30, 0.0, 0.0], [0.0, 0.0, 1.0]];
    for (l, n) in layers.iter_mut().zip(normals) {
        l.normal = n;
    }
    layers[5].normal = [0.0; 3];
    layers[6].normal = [0.3, -0.2, 1.0];
    let Some(gpu) = gpu() else { return };
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    let lightings = [
        ("default", Lighting::default()),
        ("light behind the output", Lighting { position: [0.0, 0.0, -2.0], ..Lighting::default() }),
        ("shininess 0", Lighting { shininess: 0.0, ..Lighting::default() }),
    ];
    for (name, light) in lightings {
        let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
        let got = run(&gpu, &mut comp, &layers, &light);
        check(name, &got, &want, 1);
        let amb = c.map(|v| (f32::from(v) * light.ambient).round() as u8);
        for (x, y, what) in [(8, 8, "zero"), (34, 8, "NaN"), (60, 8, "infinite"), (20, 20, "zero, selected")] {
            let p = px(&got, x, y);
            let near = p.iter().zip(&amb).take(3).all(|(a, b)| a.abs_diff(*b) <= 1);
            assert!(near, "{name}: a {what} normal must be lit by ambient only: {p:?}, not {amb:?}");
        }
        assert_ne!(px(&got, 8, 38)[..3], amb[..3], "{name}: a tiny normal is a direction");
    }
}

/// Shininess 0 and 128, ambient 0 and 1, with normals facing away from the light (where the
/// specular base is 0, so shininess 0 meets pow(0, 0)): the GPU as the reference.
#[test]
fn lighting_at_its_extremes_matches_the_reference() {
    let mut layers = scene(8, true, 255);
    layers[1].normal = [1.0, 0.0, 0.0];
    layers[2].normal = [0.0, 0.0, -1.0];
    layers[3].normal = [0.0, -1.0, 0.05];
    let Some(gpu) = gpu() else { return };
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    for normals in [NormalSource::PerSurface, NormalSource::FromDepth] {
        for (shininess, ambient) in [(0.0, 0.1), (128.0, 0.1), (32.0, 0.0), (32.0, 1.0), (0.0, 1.0), (128.0, 0.0)] {
            let light = Lighting { shininess, ambient, normals, ..Lighting::default() };
            let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
            let name = format!("{normals:?}, shininess {shininess}, ambient {ambient}");
            check(&name, &run(&gpu, &mut comp, &layers, &light), &want, 1);
        }
    }
}

/// 1×1 surfaces and surfaces of the device's largest texture side (max × 3 and 3 × max; a
/// max × max surface would take 2 GiB of colour and depth at 16384), partly off the output.
#[test]
fn one_pixel_and_maximum_size_surfaces_match_the_reference() {
    let Some(gpu) = gpu() else { return };
    let max = gpu.limits.max_texture_dimension_2d as i32;
    eprintln!("largest texture side {max}");
    let layers = vec![
        surface(0, [60 - max, 10, max, 3], 0.5, 255, true),
        surface(1, [40, 50 - max, 3, max], 0.5, 255, true),
        surface(2, [50, 30, max, 3], 0.5, 200, true),
        surface(3, [70, 20, 3, max], 0.5, 255, false),
        surface(4, [41, 11, 1, 1], 0.5, 255, true),
        surface(5, [0, 0, 1, 1], 0.5, 255, true),
        surface(6, [OUT_W as i32 - 1, OUT_H as i32 - 1, 1, 1], 0.3, 255, true),
        surface(7, [-1, -1, 1, 1], 0.5, 255, true),
        surface(8, [OUT_W as i32, 5, 1, 1], 0.5, 255, true),
        surface(9, [71, 31, 1, 1], 0.2, 150, true),
    ];
    let lightings = [
        ("unlit", unlit(), 0),
        ("lit", Lighting::default(), 1),
        ("lit from depth", Lighting { normals: NormalSource::FromDepth, ..Lighting::default() }, 1),
    ];
    for m in [None, Some(4)] {
        let mut comp = Compositor::new(gpu.clone(), m).expect("compositor");
        for (name, light, tol) in &lightings {
            let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, light);
            check(&format!("{name}, limit {m:?}"), &run(&gpu, &mut comp, &layers, light), &want, *tol);
        }
        assert!(comp.last_stats.selects > 0, "the 1×1 surface over both strips selects");
    }
}

/// 64 surfaces of one group overlapping in the middle of the output: chained passes
/// bit-identical to one pass, both as the reference.
#[test]
fn sixty_four_surfaces_in_one_group_chain_exactly() {
    let layers: Vec<RefLayer> = (0..64)
        .map(|i| surface(i, [20 + (i % 8) as i32 * 3, 12 + (i / 8) as i32 * 3, 40, 30], 0.5, 200, i % 7 != 6))
        .collect();
    let Some(gpu) = gpu() else { return };
    let mut single = Compositor::new(gpu.clone(), None).expect("device limit");
    let lit = Lighting { normals: NormalSource::FromDepth, ..Lighting::default() };
    // One lighting (the costliest: normals from depth); each lighting compiles its own
    // 32-surface shader, which on lavapipe takes most of this test's time.
    let (name, light) = ("lit from depth", lit);
    let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
    let one = run(&gpu, &mut single, &layers, &light);
    check(name, &one, &want, 1);
    eprintln!("{name}: the device limit takes {} passes", single.last_passes);
    let m = 4u32;
    let mut c = Compositor::new(gpu.clone(), Some(m)).expect("limit");
    let got = run(&gpu, &mut c, &layers, &light);
    let p = (m / 2) as usize;
    assert_eq!(c.last_passes, 1 + (64 - p).div_ceil(p - 1), "{name} m={m}: passes");
    assert!(got == one, "{name}: --max-textures {m} differs from the device limit");
}

/// A depth-only phantom (alpha 0, depth written) at the same z as an opaque surface hides it
/// where it is nearer and shows what lies beneath there (a farther group): AR occlusion.
#[test]
fn a_depth_only_phantom_occludes_and_shows_what_lies_beneath() {
    let (w, h) = (80, 48);
    let a = solid([8, 8, w, h], 0.5, RED, Some(vec![0.5; (w * h) as usize]), None);
    let phantom_depth = depth_map(w, h, |x, _| if x < w / 2 { 0.3 } else { 1.0 });
    let p = solid([8, 8, w, h], 0.5, [0, 255, 0, 0], Some(phantom_depth), None);
    let back = solid([0, 0, OUT_W as i32, OUT_H as i32], 0.9, BLUE, None, None);
    // Behind A, in the phantom's left half: hidden by the phantom too.
    let q = solid([20, 20, 10, 10], 0.5, GREEN, Some(vec![0.8; 100]), None);
    let scenes = [
        ("phantom later", vec![back.clone(), a.clone(), p.clone()]),
        ("phantom earlier", vec![back.clone(), p.clone(), a.clone()]),
        ("phantom earlier, three in the group", vec![back.clone(), p.clone(), q.clone(), a.clone()]),
    ];
    for (name, layers) in &scenes {
        let img = reference::composite(layers, OUT_W, OUT_H, BACKGROUND, &unlit());
        for (x, y, want) in [(10, 10, BLUE), (25, 25, BLUE), (47, 30, BLUE), (48, 30, RED), (86, 54, RED), (2, 2, BLUE)]
        {
            assert_eq!(px(&img, x, y), want, "{name}: the reference at {x},{y}");
        }
    }
    let Some(gpu) = gpu() else { return };
    for m in [None, Some(4)] {
        let mut comp = Compositor::new(gpu.clone(), m).expect("compositor");
        for (name, layers) in &scenes {
            for (light, tol) in [(unlit(), 0), (Lighting::default(), 1)] {
                let want = reference::composite(layers, OUT_W, OUT_H, BACKGROUND, &light);
                let what = format!("{name}, limit {m:?}, lit {}", light.enabled);
                check(&what, &run(&gpu, &mut comp, layers, &light), &want, tol);
            }
        }
    }
}
