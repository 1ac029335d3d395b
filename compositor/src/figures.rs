//! The scene of the thesis' figures 5.6 and 5.7: two triangles at one z whose depth planes
//! cross, so that each is in front on one side of the crossing, lit by a light far from the
//! output (5.6: nearly parallel rays, each triangle one shade) and near it (5.7: shading that
//! varies across each triangle, with a highlight). Both the benchmark that draws the figures and
//! the test that checks them against the f64 reference use these.

use crate::reference::RefLayer;
use crate::{Lighting, NormalSource};

/// Two triangles filling most of a `width`×`height` output: an orange one pointing right whose
/// depth grows from left to right, and a blue one pointing left whose depth shrinks; each faces
/// the side where it is nearer. Outside a triangle its image is transparent at depth 1, so the
/// other triangle or the background shows there.
pub fn two_triangles(width: u32, height: u32) -> Vec<RefLayer> {
    let (w, h) = (width as i32, height as i32);
    let triangle = |points_right: bool, color: [u8; 3], normal: [f32; 3]| {
        let mut rgba = Vec::with_capacity((w * h * 4) as usize);
        let mut depth = Vec::with_capacity((w * h) as usize);
        // Rows bottom first, as the reference and GL store them.
        for y in 0..h {
            for x in 0..w {
                let u = (x as f32 + 0.5) / w as f32;
                let v = (y as f32 + 0.5) / h as f32;
                // Distance from the base edge along x, and the half-height allowed there.
                let along = if points_right { u - 0.05 } else { 0.95 - u };
                let inside = (0.0..=0.9).contains(&along) && (v - 0.5).abs() <= 0.45 * (1.0 - along / 0.9);
                if inside {
                    rgba.extend_from_slice(&[color[0], color[1], color[2], 255]);
                    let d = if points_right { 0.25 + 0.5 * u } else { 0.75 - 0.5 * u };
                    depth.push(d);
                } else {
                    rgba.extend_from_slice(&[0, 0, 0, 0]);
                    depth.push(1.0);
                }
            }
        }
        RefLayer {
            rect: [0, 0, w, h],
            z: 0.5,
            color: rgba,
            depth: Some(depth),
            normal,
            projection: None,
            props: Default::default(),
        }
    };
    vec![triangle(true, [240, 140, 40], [-0.6, 0.0, 1.0]), triangle(false, [60, 120, 240], [0.6, 0.0, 1.0])]
}

/// Figure 5.6: a light far above the output's upper right, per-surface normals.
pub fn far_light() -> Lighting {
    Lighting { position: [40.0, 40.0, 80.0], normals: NormalSource::PerSurface, ..Lighting::default() }
}

/// Figure 5.7: a light just above the crossing, per-surface normals.
pub fn near_light() -> Lighting {
    Lighting { position: [0.1, 0.15, 0.35], normals: NormalSource::PerSurface, ..Lighting::default() }
}
