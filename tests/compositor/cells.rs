//! The compositor's cells (the region cut by coverage) against the f64 reference: surfaces
//! straddling each other's edges, 1-pixel surfaces, surfaces larger than the output, bad input
//! (surfaces covering nothing, off the output, regions without area, a 16384² output), the
//! 2D baseline, and an RGBA16F intermediate.

use super::*;
use strata_compositor::{Intermediate, Mode};
use strata_protocol::projection::Projection;

/// Lighting off, on (per-surface normals) and on (normals from depth).
fn lightings() -> [(&'static str, Lighting); 3] {
    [
        ("unlit", Lighting { enabled: false, ..Lighting::default() }),
        ("lit", Lighting::default()),
        ("lit from depth", Lighting { normals: NormalSource::FromDepth, ..Lighting::default() }),
    ]
}

/// Edges one pixel apart, 1×1 surfaces (at a corner of the output, where three surfaces meet,
/// touching a corner from outside), a surface without depth crossing others, two z-groups;
/// with `big`, a surface larger than the output behind everything.
fn boundary_scene(alpha: u8, big: bool) -> Vec<RefLayer> {
    let (w, h) = (OUT_W as i32, OUT_H as i32);
    let mut v = vec![
        surface(1, [10, 10, 30, 20], 0.5, alpha, true),
        surface(2, [39, 10, 30, 20], 0.5, alpha, true),
        surface(3, [10, 29, 59, 1], 0.5, alpha, true),
        surface(4, [40, 30, 1, 1], 0.5, alpha, true),
        surface(5, [39, 29, 1, 1], 0.5, alpha, true),
        surface(6, [0, 0, 1, 1], 0.5, alpha, false),
        surface(7, [w - 1, h - 1, 1, 1], 0.2, alpha, true),
        surface(8, [20, 15, 40, 30], 0.2, alpha, true),
        surface(9, [25, 5, 10, 50], 0.5, alpha, false),
        surface(10, [68, 0, 1, h], 0.2, alpha, true),
    ];
    if big {
        v.insert(0, surface(0, [-20, -10, w + 40, h + 30], 0.8, 200, true));
    }
    v
}

#[test]
fn cell_boundaries_match_the_reference_and_chain_and_redraw_exactly() {
    let Some(gpu) = gpu() else { return };
    let mut device = Compositor::new(gpu.clone(), None).expect("compositor");
    let mut four = Compositor::new(gpu.clone(), Some(4)).expect("compositor");
    for (alpha, big) in [(255, false), (255, true), (120, false)] {
        let layers = boundary_scene(alpha, big);
        for (name, light) in lightings() {
            let what = format!("{name}, alpha {alpha}, big {big}");
            let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
            let tol = if alpha == 255 && !big && !light.enabled { 0 } else { 1 };
            let out = output(&gpu);
            let got = run_into(&gpu, &mut device, &layers, &light, &out, None);
            check(&what, &got, &want, tol);
            let chained = run(&gpu, &mut four, &layers, &light);
            assert!(four.last_stats.chained > 0, "{what}: the scene must chain at --max-textures 4");
            assert!(chained == got, "{what}: --max-textures 4 differs from the device limit");
            // A region through the middle of the straddles, redrawn over a stale image.
            let stale = boundary_scene(alpha.wrapping_add(77), !big);
            run_into(&gpu, &mut device, &stale, &light, &out, None);
            let partial = run_into(&gpu, &mut device, &layers, &light, &out, Some([37, 8, 5, 30]));
            let stale_img = run(&gpu, &mut device, &stale, &light);
            for y in 0..OUT_H {
                for x in 0..OUT_W {
                    let at = ((y * OUT_W + x) * 4) as usize;
                    let inside = (37..42).contains(&x) && (8..38).contains(&y);
                    let expect = if inside { &got[at..at + 4] } else { &stale_img[at..at + 4] };
                    assert_eq!(&partial[at..at + 4], expect, "{what}: pixel {x},{y} after a partial composite");
                }
            }
        }
    }
}

#[test]
fn only_overlaps_run_the_select_and_only_deep_overlaps_chain() {
    let Some(gpu) = gpu() else { return };
    let off = Lighting { enabled: false, ..Lighting::default() };
    let mut comp = Compositor::new(gpu.clone(), Some(4)).expect("compositor");
    let disjoint = vec![
        surface(0, [0, 0, 20, 20], 0.5, 255, true),
        surface(1, [20, 0, 20, 20], 0.5, 255, true),
        surface(2, [0, 20, 40, 20], 0.5, 255, true),
    ];
    let img = run(&gpu, &mut comp, &disjoint, &off);
    check("disjoint", &img, &reference::composite(&disjoint, OUT_W, OUT_H, BACKGROUND, &off), 0);
    assert_eq!((comp.last_stats.selects, comp.last_stats.chained), (0, 0), "one surface per cell: no select");
    let mut two = disjoint.clone();
    two.push(surface(3, [10, 10, 20, 5], 0.5, 255, true));
    let img = run(&gpu, &mut comp, &two, &off);
    check("two overlap", &img, &reference::composite(&two, OUT_W, OUT_H, BACKGROUND, &off), 0);
    assert!(comp.last_stats.selects > 0 && comp.last_stats.chained == 0, "{:?}", comp.last_stats);
    let mut three = two.clone();
    three.push(surface(4, [12, 12, 4, 4], 0.5, 255, true));
    let img = run(&gpu, &mut comp, &three, &off);
    check("three overlap", &img, &reference::composite(&three, OUT_W, OUT_H, BACKGROUND, &off), 0);
    assert!(comp.last_stats.chained > 0, "three overlapping with 2 per pass must chain: {:?}", comp.last_stats);
    assert_eq!(comp.last_passes, 1 + (5 - 2usize).div_ceil(1), "the thesis' count for the group of 5");
}

/// The GPU layers of `layers`, uploaded as `up`.
fn layers_of<'a>(layers: &[RefLayer], up: &'a [Uploaded]) -> Vec<Layer<'a>> {
    layers.iter().zip(up).map(|(l, u)| u.layer(l)).collect()
}

/// A 1×1 colour image for layers whose rectangle has no area.
fn tiny(gpu: &Gpu) -> wgpu::TextureView {
    upload(gpu, &surface(0, [0, 0, 1, 1], 0.5, 255, false)).color
}

#[test]
fn surfaces_covering_nothing_and_regions_without_area_are_harmless() {
    let Some(gpu) = gpu() else { return };
    let off = Lighting { enabled: false, ..Lighting::default() };
    let (w, h) = (OUT_W as i32, OUT_H as i32);
    let layers = vec![
        surface(0, [30, 20, 20, 20], 0.5, 255, true),
        surface(1, [-1000, 5, 20, 20], 0.5, 255, true),
        surface(2, [w, 0, 10, 10], 0.5, 255, true),
        surface(3, [0, h, 10, 10], 0.5, 255, true),
        surface(4, [-10, -10, 10, 10], 0.5, 255, true),
        surface(5, [i32::MAX - 4, i32::MAX - 4, 8, 8], 0.5, 255, true),
        surface(6, [i32::MIN, i32::MIN, 8, 8], 0.5, 255, true),
        surface(7, [35, 25, 8, 8], f32::NAN, 255, true),
        surface(8, [35, 25, 8, 8], f32::INFINITY, 255, true),
    ];
    let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &off);
    let mut comp = Compositor::new(gpu.clone(), Some(4)).expect("compositor");
    let out = output(&gpu);
    let up: Vec<Uploaded> = layers.iter().map(|l| upload(&gpu, l)).collect();
    let t = tiny(&gpu);
    let mut gl = layers_of(&layers, &up);
    // Rectangles without area, over the visible surface.
    for rect in [[32, 22, 0, 5], [32, 22, 5, 0], [32, 22, -5, 5], [32, 22, i32::MIN, i32::MIN]] {
        gl.push(Layer {
            rect,
            z: 0.1,
            color: &t,
            depth: None,
            normal: [0.0, 0.0, 1.0],
            projection: Projection::RAW,
            opaque: false,
            props: Default::default(),
        });
    }
    comp.composite(&gl, &off, &out, BACKGROUND, None).expect("composite");
    let img = gpu.read_rgba8(&out, [0, 0, OUT_W, OUT_H]).expect("readback");
    check("surfaces covering nothing", &img, &want, 0);
    assert_eq!(comp.last_stats.selects, 0, "only surface 0 covers any pixel");
    // Regions without area, or off the output, change nothing and draw nothing.
    let other = vec![Layer {
        rect: [0, 0, w, h],
        z: 0.5,
        color: &up[0].color,
        depth: None,
        normal: [0.0; 3],
        projection: Projection::RAW,
        opaque: false,
        props: Default::default(),
    }];
    for region in [[10, 10, 0, 20], [10, 10, 20, 0], [OUT_W, 0, 5, 5], [0, OUT_H, 5, 5], [u32::MAX; 4]] {
        comp.composite(&other, &off, &out, BACKGROUND, Some(region)).expect("composite");
        assert_eq!((comp.last_passes, comp.last_stats.draws), (0, 0), "region {region:?} drew");
        let again = gpu.read_rgba8(&out, [0, 0, OUT_W, OUT_H]).expect("readback");
        assert!(again == img, "region {region:?} changed the output");
    }
    // A region clipped by the output's edge redraws only its part inside.
    comp.composite(&gl, &off, &out, BACKGROUND, Some([OUT_W - 3, OUT_H - 2, u32::MAX, u32::MAX])).expect("composite");
    assert!(comp.last_stats.draws > 0);
    check("edge region", &gpu.read_rgba8(&out, [0, 0, OUT_W, OUT_H]).expect("readback"), &want, 0);
}

/// `layers` moved by (−x, −y): what a window of the output at (x, y) shows, unlit.
fn shifted(layers: &[RefLayer], x: i32, y: i32) -> Vec<RefLayer> {
    layers
        .iter()
        .cloned()
        .map(|mut l| {
            l.rect[0] -= x;
            l.rect[1] -= y;
            l
        })
        .collect()
}

#[test]
fn a_16384_square_output_composites_in_bounded_tiles() {
    let Some(gpu) = gpu() else { return };
    let side = gpu.limits.max_texture_dimension_2d.min(16384);
    eprintln!("output {side}x{side}");
    let s = side as i32;
    let off = Lighting { enabled: false, ..Lighting::default() };
    // Three surfaces at one z overlapping across the chain's tile corner at (2048, 2048), so
    // the chain (2 per pass) is split between four tiles; one at the far corner; one
    // half-transparent at a nearer z over the origin.
    let mut layers = vec![
        surface(0, [2040, 2040, 16, 16], 0.5, 255, true),
        surface(1, [2044, 2036, 16, 16], 0.5, 255, true),
        surface(2, [2036, 2044, 16, 16], 0.5, 255, true),
        surface(3, [s - 40, s - 30, 40, 30], 0.5, 255, true),
        surface(4, [-5, -5, 20, 20], 0.3, 150, true),
    ];
    let out = output_of(&gpu, side, side);
    let mut comp = Compositor::new(gpu.clone(), Some(4)).expect("compositor");
    let windows = [[0, 0, 32, 32], [2028, 2028, 40, 40], [s - 48, s - 40, 48, 40], [8000, 8000, 8, 8]];
    let compare = |layers: &[RefLayer], what: &str| {
        for win in windows {
            let got = gpu.read_rgba8(&out, win.map(|v| v as u32)).expect("readback");
            let want =
                reference::composite(&shifted(layers, win[0], win[1]), win[2] as u32, win[3] as u32, BACKGROUND, &off);
            let bad = got.iter().zip(&want).filter(|(a, b)| a.abs_diff(**b) > 1).count();
            assert_eq!(bad, 0, "{what}: window {win:?} differs from the reference");
        }
    };
    let mut up: Vec<Uploaded> = layers.iter().map(|l| upload(&gpu, l)).collect();
    comp.composite(&layers_of(&layers, &up), &off, &out, BACKGROUND, None).expect("composite");
    // One chained cell, cut into four tiles: each takes an intermediate pass and a final one.
    let st = comp.last_stats;
    assert!(st.chained == 1 && st.render_passes > 4 * 2, "the chained cell spans four tiles: {st:?}");
    compare(&layers, "whole");
    // New content in the far corner, redrawn alone.
    layers[3] = surface(30, [s - 40, s - 30, 40, 30], 0.5, 255, true);
    up[3] = upload(&gpu, &layers[3]);
    comp.composite(&layers_of(&layers, &up), &off, &out, BACKGROUND, Some([side - 40, side - 30, 40, 30]))
        .expect("composite");
    compare(&layers, "partial");
    // Lit (lit in the shader: the output is too large for light maps): no panic, and the
    // background stays the background.
    comp.composite(&layers_of(&layers, &up), &Lighting::default(), &out, BACKGROUND, None).expect("composite");
    let bg = gpu.read_rgba8(&out, [8000, 8000, 8, 8]).expect("readback");
    assert!(bg.chunks(4).all(|p| p == [51, 102, 153, 255]), "background");
}

#[test]
fn the_2d_baseline_is_painters_order_of_opaque_copies() {
    let Some(gpu) = gpu() else { return };
    let mut layers = scene(9, false, 255);
    layers.extend(boundary_scene(255, false));
    layers.push(surface(20, [50, 30, 30, 20], f32::NAN, 255, true));
    // Painter's order: far (larger z) first, equal z in stacking order; all opaque, so the
    // reference with every surface at its own z, lighting off, is what a 2D compositor shows.
    let mut order: Vec<usize> = (0..layers.len()).filter(|&i| layers[i].z.is_finite()).collect();
    order.sort_by(|&a, &b| layers[b].z.total_cmp(&layers[a].z).then(a.cmp(&b)));
    let mut ranked = layers.clone();
    for (pos, &i) in order.iter().enumerate() {
        ranked[i].z = (order.len() - pos) as f32;
    }
    let off = Lighting { enabled: false, ..Lighting::default() };
    let want = reference::composite(&ranked, OUT_W, OUT_H, BACKGROUND, &off);
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor").with_mode(Mode::TwoD);
    let out = output(&gpu);
    // Lighting is not the 2D compositor's business.
    let whole = run_into(&gpu, &mut comp, &layers, &Lighting::default(), &out, None);
    check("2D", &whole, &want, 0);
    assert_eq!(comp.last_stats.selects, 0, "2D never selects by depth");
    run_into(&gpu, &mut comp, &scene(4, true, 255), &off, &out, None);
    let partial = run_into(&gpu, &mut comp, &layers, &off, &out, Some([20, 10, 30, 25]));
    let whole_stale = run(&gpu, &mut comp, &scene(4, true, 255), &off);
    for y in 0..OUT_H {
        for x in 0..OUT_W {
            let at = ((y * OUT_W + x) * 4) as usize;
            let inside = (20..50).contains(&x) && (10..35).contains(&y);
            let expect = if inside { &whole[at..at + 4] } else { &whole_stale[at..at + 4] };
            assert_eq!(&partial[at..at + 4], expect, "2D partial: pixel {x},{y}");
        }
    }
}

#[test]
fn an_rgba16f_intermediate_chains_to_within_one_level_of_one_pass() {
    let Some(gpu) = gpu() else { return };
    let mut single = Compositor::new(gpu.clone(), None).expect("device limit");
    let mut half = Compositor::new(gpu.clone(), Some(4)).expect("limit").with_intermediate(Intermediate::Rgba16f);
    assert_eq!(half.intermediate(), Intermediate::Rgba16f);
    let mut chained = 0;
    for (name, light) in lightings() {
        for k in [4, 9] {
            let layers = scene(k, true, 200);
            let want = run(&gpu, &mut single, &layers, &light);
            let got = run(&gpu, &mut half, &layers, &light);
            chained += half.last_stats.chained;
            check(&format!("{k} surfaces, {name}, RGBA16F intermediate"), &got, &want, 1);
        }
    }
    assert!(chained > 0, "the scenes chain at --max-textures 4");
}
