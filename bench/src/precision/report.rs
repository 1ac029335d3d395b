//! `strata-bench precision`'s report: its rows, their table and the error-against-speed plot.

use std::path::Path;

use anyhow::{Context, Result};
use plotters::prelude::*;

use super::scene::BAND;

/// One measured row.
#[derive(serde::Serialize)]
pub(super) struct Row {
    pub(super) knob: &'static str,
    pub(super) setting: &'static str,
    pub(super) surfaces: usize,
    pub(super) depth_format: &'static str,
    pub(super) reversed: bool,
    pub(super) declared: bool,
    pub(super) lit: bool,
    pub(super) normals: &'static str,
    pub(super) max_textures: Option<u32>,
    pub(super) intermediate: &'static str,
    pub(super) passes: usize,
    pub(super) chained_cells: usize,
    pub(super) ms: f64,
    pub(super) depth_err_max: f64,
    pub(super) depth_err_p99: f64,
    pub(super) line_pixels: usize,
    pub(super) wrong_line: Option<f64>,
    pub(super) wrong_all: Option<f64>,
    pub(super) stored_wrong_line: Option<f64>,
    pub(super) colour_err_max: u8,
    pub(super) colour_err_mean: f64,
    pub(super) note: &'static str,
}

/// Prints the rows as a table, with the columns' meaning and the rows' notes.
pub(super) fn print(rows: &[Row], w: u32, h: u32, frames: u32) {
    println!(
        "precision: {w}x{h} surfaces at one z, perspective planes 20..60 away meeting along lines; {frames} composites per row"
    );
    println!(
        "{:>2} {:<12} {:<25} {:>7} {:>6} {:>10} {:>10} {:>9} {:>9} {:>9} {:>5} {:>7}",
        "#",
        "knob",
        "setting",
        "ms",
        "passes",
        "depth max",
        "depth p99",
        "fmt@ln",
        "wrong@ln",
        "wrong all",
        "c.max",
        "c.mean"
    );
    for (i, r) in rows.iter().enumerate() {
        println!(
            "{:>2} {:<12} {:<25} {:>7.2} {:>6} {:>10.2e} {:>10.2e} {:>9} {:>9} {:>9} {:>5} {:>7}",
            i + 1,
            r.knob,
            r.setting,
            r.ms,
            r.passes,
            r.depth_err_max,
            r.depth_err_p99,
            pct(r.stored_wrong_line),
            pct(r.wrong_line),
            pct(r.wrong_all),
            colour(r).map_or_else(|| "-".into(), |(max, _)| max.to_string()),
            colour(r).map_or_else(|| "-".into(), |(_, mean)| format!("{mean:.4}"))
        );
    }
    println!("depth max/p99: eye-space error of the stored depth (scene units; planes 20..60 away)");
    println!(
        "fmt@ln: pixels within {BAND} px of an intersection line that an exact (f64) select of the stored depths gets wrong"
    );
    println!("wrong@ln, wrong all: pixels the compositor shows wrongly, near a line and anywhere");
    println!("c.max/c.mean: |RGBA8 difference| from the f64 reference fed exact depths");
    for (i, r) in rows.iter().enumerate().filter(|(_, r)| !r.note.is_empty()) {
        println!("  {}: {}", i + 1, r.note);
    }
    println!(
        "vertex wire rows: ms is a client's frame time; depth max/p99 and fmt@ln are the wire-quantised vertices' (no composite)"
    );
    println!(
        "daemon depth rows: a real stratad and two clients; ms is a client's frame time; wrong@ln/all read off a screenshot"
    );
}

/// The colour error (max, mean) of a row that composited (`None` for rows measured without a
/// composite of their own: the vertex wire and daemon rows).
fn colour(r: &Row) -> Option<(u8, f64)> {
    (r.passes > 0).then_some((r.colour_err_max, r.colour_err_mean))
}

/// Wrongly selected pixels near an intersection line: the compositor's where it ran, else
/// what an exact select of the row's stored depths gets wrong.
fn wrong_near_line(r: &Row) -> Option<f64> {
    r.wrong_line.or(r.stored_wrong_line)
}

/// Writes the error-against-speed plot: one numbered point per row, in two panels (the colour
/// error of the rows that composite, and the wrongly selected pixels near the line of every
/// row that has a line), with the rows named beside them.
pub(super) fn scatter(path: &Path, title: &str, rows: &[Row]) -> Result<()> {
    crate::plot::register_font()?;
    let root = BitMapBackend::new(path, (1500, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let (charts, legend) = root.split_horizontally(1080);
    let (left, right) = charts.split_horizontally(540);
    let palette = [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44), RGBColor(120, 120, 120)];
    let colour_points: Vec<(usize, f64, f64)> =
        rows.iter().enumerate().filter_map(|(i, r)| colour(r).map(|(_, mean)| (i, r.ms, mean))).collect();
    let line_points: Vec<(usize, f64, f64)> =
        rows.iter().enumerate().filter_map(|(i, r)| wrong_near_line(r).map(|w| (i, r.ms, w * 100.0))).collect();
    for (area, points, y_desc, floor) in [
        (&left, &colour_points, "mean |RGBA8 difference| from the f64 reference (log; 0 at 0.001)", 1e-3),
        (&right, &line_points, "wrongly selected pixels near the line, % (log; 0 at 0.01)", 1e-2),
    ] {
        let x1 = points.iter().map(|p| p.1).filter(|v| v.is_finite()).fold(1e-3, f64::max) * 1.15;
        let y1 = points.iter().map(|p| p.2).fold(floor, f64::max) * 3.0;
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(0.0..x1, (floor..y1).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("ms (composite; client frame for 17+)")
            .y_desc(y_desc)
            .label_style(("sans-serif", 13))
            .draw()?;
        for &(i, ms, y) in points.iter().filter(|p| p.1.is_finite()) {
            let at = (ms, y.max(floor));
            let color = palette[i % palette.len()];
            chart.draw_series([Circle::new(at, 4, color.filled())])?;
            chart.draw_series([Text::new(format!("{}", i + 1), at, ("sans-serif", 14).into_font())])?;
        }
    }
    for (i, r) in rows.iter().enumerate() {
        let color = palette[i % palette.len()];
        let y = 30 + 22 * i as i32;
        legend.draw(&Circle::new((14, y + 7), 4, color.filled()))?;
        legend.draw(&Text::new(format!("{} {}: {}", i + 1, r.knob, r.setting), (26, y), ("sans-serif", 14)))?;
    }
    root.present().with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// `Some(x)` as a percentage, `-` for none.
fn pct(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{:.3}%", v * 100.0))
}
