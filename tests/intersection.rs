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

/// Runs `stratad demo` with `args`, writing `png`, and returns the image.
fn demo(png: &std::path::Path, args: &[&str]) -> image::RgbaImage {
    let out = std::process::Command::new(support::stratad())
        .arg("demo")
        .args(args)
        .arg("--out")
        .arg(png)
        .output()
        .expect("demo");
    assert!(
        out.status.success(),
        "demo failed: {}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    image::open(png).expect("png").to_rgba8()
}

#[test]
fn two_clients_intersect_per_fragment() {
    let dir = support::TempDir::new("intersection");
    let img = demo(&dir.0.join("demo.png"), &["--frames", "3"]);
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

/// Runs `stratad demo --scene planes` with `projections` and returns, per row of the planes'
/// rectangle, the column where the blue plane takes over.
fn plane_line(dir: &support::TempDir, projections: &str) -> Vec<Option<u32>> {
    let png = dir.0.join(format!("planes-{projections}.png"));
    let img = demo(&png, &["--scene", "planes", "--frames", "2", "--projections", projections]);
    strata_server::demo::planes::line_columns(img.as_raw(), img.width())
}

#[test]
fn declared_projections_put_the_intersection_where_the_f64_geometry_does() {
    use strata_server::demo::planes;
    let dir = support::TempDir::new("projections");
    let want = planes::expected_column();
    // The f64 geometry: the planes meet at NDC x = 1/4.1, between columns 248 and 249.
    assert_eq!(want, 249, "line at NDC x {}", planes::line_x());
    // Two client processes, each declaring its own near/far: the line lies within a pixel of
    // the f64 line on every row.
    let declared = plane_line(&dir, "declared");
    for (row, c) in declared.iter().enumerate() {
        let c = c.unwrap_or_else(|| panic!("row {row}: no red-to-blue transition"));
        assert!(c.abs_diff(want) <= 1, "row {row}: the line is at column {c}, the f64 line at {want}");
    }
    // Undeclared, depth is compared raw and the line is misplaced: measure by how much.
    let raw = plane_line(&dir, "raw");
    let found: Vec<u32> = raw.into_iter().flatten().collect();
    assert!(!found.is_empty(), "compared raw, no row shows the planes meeting");
    let off = found.iter().map(|&c| f64::from(c.abs_diff(want))).sum::<f64>() / found.len() as f64;
    eprintln!("compared raw, the line is misplaced by {off:.1} pixels on average ({} rows)", found.len());
    // The raw-depth line, from the same f64 geometry: where the two window depths are equal.
    let (mut lo, mut hi) = (-1.0f64, planes::line_x());
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if planes::A.depth(mid) < planes::B.depth(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let raw_col = ((lo + 1.0) / 2.0 * f64::from(planes::RECT[2]) - 0.5).ceil();
    let raw_mean = found.iter().map(|&c| f64::from(c)).sum::<f64>() / found.len() as f64;
    assert!((raw_mean - raw_col).abs() <= 1.0, "compared raw, the line is at column {raw_mean}, expected {raw_col}");
    assert!(off > 100.0, "compared raw, the line should be far off: {off} pixels");
}
