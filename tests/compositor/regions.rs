//! Source and destination regions and opacity, the GPU compositor against the f64 reference:
//! crops are fetched exactly, scaled surfaces are filtered bilinearly (texel centres at
//! half-integers, as a filtering sampler takes them), and opacity multiplies the selected
//! premultiplied colour. Some pixels are also checked against values worked out by hand, so
//! that the reference's own convention is anchored.

use super::*;
use strata_compositor::{Props, Source};

/// `l` showing `region` of its image over `dest`, at `opacity`.
fn placed(mut l: RefLayer, dest: [i32; 4], region: [i32; 4], opacity: f32) -> RefLayer {
    let image = [l.rect[2], l.rect[3]];
    l.rect = dest;
    l.props = Props { source: Some(Source { image, region }), opacity };
    l
}

fn unlit() -> Lighting {
    Lighting { enabled: false, ..Lighting::default() }
}

/// A scene of every kind of region: upscaled, downscaled, cropped at scale 1, cropped and
/// scaled, translucent and transparent, over two z-groups, overlapping so that the depth
/// select runs between scaled surfaces.
fn region_scene() -> Vec<RefLayer> {
    let s = |i, w, h| surface(i, [0, 0, w, h], 0.5, 255, true);
    let mut far = surface(6, [0, 0, 30, 20], 0.8, 255, true);
    far = placed(far, [0, 0, OUT_W as i32, OUT_H as i32], [0, 0, 30, 20], 1.0);
    vec![
        far,
        placed(s(0, 20, 10), [5, 5, 50, 30], [0, 0, 20, 10], 1.0),
        placed(s(1, 40, 40), [30, 10, 17, 23], [0, 0, 40, 40], 1.0),
        placed(s(2, 30, 30), [20, 20, 12, 9], [8, 11, 12, 9], 1.0),
        placed(s(3, 30, 30), [40, 25, 45, 21], [3, 4, 15, 7], 0.6),
        placed(s(4, 16, 16), [10, 30, 16, 16], [0, 0, 16, 16], 0.0),
        surface(5, [60, 5, 25, 25], 0.5, 180, true),
    ]
}

#[test]
fn regions_and_opacity_match_the_reference() {
    let Some(gpu) = gpu() else { return };
    let layers = region_scene();
    let lit_depth = Lighting { normals: NormalSource::FromDepth, ..Lighting::default() };
    for (name, light, tol) in [("unlit", unlit(), 1), ("lit", Lighting::default(), 1), ("lit from depth", lit_depth, 1)]
    {
        let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
        for limit in [None, Some(4)] {
            let mut comp = Compositor::new(gpu.clone(), limit).expect("compositor");
            let got = run(&gpu, &mut comp, &layers, &light);
            check(&format!("regions, {name}, textures {limit:?}"), &got, &want, tol);
        }
    }
}

#[test]
fn a_crop_at_scale_one_is_exact() {
    let Some(gpu) = gpu() else { return };
    // Opaque, unlit, one z-group, no overlap: nothing rounds, so the crop must be bit-exact.
    let l = placed(surface(2, [0, 0, 30, 30], 0.5, 255, true), [7, 9, 12, 9], [8, 11, 12, 9], 1.0);
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    let got = run(&gpu, &mut comp, std::slice::from_ref(&l), &unlit());
    check("crop", &got, &reference::composite(std::slice::from_ref(&l), OUT_W, OUT_H, BACKGROUND, &unlit()), 0);
    // By hand: output (7, 9) shows the region's top-left texel, image (8, 11) from the top,
    // which is row 30 - 1 - 11 = 18 in GL order.
    let at = ((9 * OUT_W + 7) * 4) as usize;
    let src = ((18 * 30 + 8) * 4) as usize;
    assert_eq!(&got[at..at + 4], &l.color[src..src + 4], "the crop's corner");
}

#[test]
fn scaling_filters_bilinearly_as_worked_out_by_hand() {
    let Some(gpu) = gpu() else { return };
    // A 2×1 image, black then white, stretched over 4×1: pixel centres fall at source x 0.25,
    // 0.75, 1.25 and 1.75 texels, i.e. between the texel centres 0.5 and 1.5 at weights
    // 0 (clamped), 0.25, 0.75 and 1 (clamped): 0, 64, 191, 255.
    let ramp = RefLayer {
        rect: [0, 0, 2, 1],
        z: 0.5,
        color: vec![0, 0, 0, 255, 255, 255, 255, 255],
        depth: None,
        normal: [0.0, 0.0, 1.0],
        projection: None,
        props: Default::default(),
    };
    let wide = placed(ramp.clone(), [3, 2, 4, 1], [0, 0, 2, 1], 1.0);
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    let got = run(&gpu, &mut comp, std::slice::from_ref(&wide), &unlit());
    let row: Vec<u8> = (3..7).map(|x| got[((2 * OUT_W + x) * 4) as usize]).collect();
    assert_eq!(row, [0, 64, 191, 255], "bilinear ramp");
    let r = reference::composite(std::slice::from_ref(&wide), OUT_W, OUT_H, BACKGROUND, &unlit());
    let ref_row: Vec<u8> = (3..7).map(|x| r[((2 * OUT_W + x) * 4) as usize]).collect();
    assert_eq!(ref_row, [0, 64, 191, 255], "the reference's bilinear ramp");
    // Half opacity over the background (51, 102, 153): white at 0.5 gives (153, 178.5, 204).
    let half = placed(ramp, [10, 2, 2, 1], [0, 0, 2, 1], 0.5);
    let got = run(&gpu, &mut comp, std::slice::from_ref(&half), &unlit());
    let at = ((2 * OUT_W + 11) * 4) as usize;
    let p = &got[at..at + 3];
    assert!(p[0] == 153 && p[1].abs_diff(178) <= 1 && p[2] == 204, "half-opaque white over the background: {p:?}");
}
