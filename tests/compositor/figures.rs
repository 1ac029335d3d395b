//! The thesis' figures 5.6 and 5.7: two intersecting triangles lit by a far and by a near light,
//! checked against the f64 reference.

use super::*;
use strata_compositor::figures::{far_light, near_light, two_triangles};

/// The RGBA of pixel (x, y), top row first.
fn at(img: &[u8], x: u32, y: u32) -> [u8; 4] {
    let p = ((y * OUT_W + x) * 4) as usize;
    [img[p], img[p + 1], img[p + 2], img[p + 3]]
}

#[test]
fn two_triangles_lit_far_and_near_match_the_reference() {
    let Some(gpu) = gpu() else { return };
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    let layers = two_triangles(OUT_W, OUT_H);
    let mut images = Vec::new();
    for (name, light) in [("figure 5.6, far light", far_light()), ("figure 5.7, near light", near_light())] {
        let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
        let got = run(&gpu, &mut comp, &layers, &light);
        check(name, &got, &want, 1);
        // The triangles cross: orange in front on the left, blue on the right, both lit.
        let (left, right) = (at(&got, OUT_W / 4, OUT_H / 2), at(&got, OUT_W * 3 / 4, OUT_H / 2));
        assert!(left[0] > left[2] && right[2] > right[0], "{name}: orange left, blue right: {left:?} {right:?}");
        images.push(got);
    }
    // A near light shades each triangle unevenly; a far one almost evenly.
    let spread = |img: &[u8]| {
        let row = OUT_H / 2;
        let shades: Vec<u8> = (OUT_W / 8..OUT_W / 3).map(|x| at(img, x, row)[0]).collect();
        shades.iter().max().copied().unwrap_or(0) - shades.iter().min().copied().unwrap_or(0)
    };
    assert!(spread(&images[1]) > spread(&images[0]) + 8, "the near light must shade the triangle unevenly");
}
