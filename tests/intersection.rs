//! Two real client processes render tilted geometry at the same z over overlapping
//! rectangles (`stratad demo`). Pixel probes, placed from the two depth planes, confirm that
//! each side of the intersection shows the client whose geometry is nearer there.

mod support;

use strata_server::demo::{HU_PLANE, HU_RECT, IC_PLANE, IC_RECT};

/// Clip-space x, y of output pixel (px, py) within `rect`, if inside.
fn local(rect: [i32; 4], px: u32, py: u32) -> Option<(f32, f32)> {
    let x = (px as f32 + 0.5 - rect[0] as f32) / rect[2] as f32 * 2.0 - 1.0;
    let y = 1.0 - (py as f32 + 0.5 - rect[1] as f32) / rect[3] as f32 * 2.0;
    ((-1.0..1.0).contains(&x) && (-1.0..1.0).contains(&y)).then_some((x, y))
}

#[test]
fn two_clients_intersect_per_fragment() {
    let dir = support::TempDir::new("intersection");
    let png = dir.0.join("demo.png");
    let out = std::process::Command::new(support::stratad())
        .args(["demo", "--frames", "3", "--out"])
        .arg(&png)
        .output()
        .expect("demo");
    assert!(
        out.status.success(),
        "demo failed: {}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(&png).expect("png").to_rgba8();
    let (mut ic_wins, mut hu_wins) = (0, 0);
    for py in (0..img.height()).step_by(9) {
        for px in (0..img.width()).step_by(9) {
            let (Some((ix, iy)), Some((hx, hy))) = (local(IC_RECT, px, py), local(HU_RECT, px, py)) else { continue };
            // Only where both have geometry for certain: inside the dial's face and the map block.
            if ix * ix + iy * iy > 0.8 * 0.8 || hx.abs() > 0.9 || hy.abs() > 0.9 {
                continue;
            }
            let zi = IC_PLANE[0] * ix + IC_PLANE[1] * iy + IC_PLANE[2];
            let zh = HU_PLANE[0] * hx + HU_PLANE[1] * hy + HU_PLANE[2];
            if (zi - zh).abs() < 0.08 {
                continue; // too close to the intersection line to call
            }
            // The needle sweeps over the dial; skip the region it may cover.
            let p = img.get_pixel(px, py).0;
            let (r, b) = (i32::from(p[0]), i32::from(p[2]));
            let orange = r > b + 20;
            let blue = b > r + 20;
            if zi < zh {
                assert!(
                    orange || (p[1] < 60 && r > 100),
                    "({px}, {py}): the dial is nearer (z {zi:.2} < {zh:.2}) but the pixel is {p:?}"
                );
                ic_wins += 1;
            } else {
                assert!(blue, "({px}, {py}): the map is nearer (z {zh:.2} < {zi:.2}) but the pixel is {p:?}");
                hu_wins += 1;
            }
        }
    }
    assert!(ic_wins >= 20 && hu_wins >= 20, "too few probes on each side: dial {ic_wins}, map {hu_wins}");
}
