//! `strata-bench precision`'s report: its rows, their table and the error-against-speed plot.

use std::path::Path;

use anyhow::{Context, Result};
use plotters::prelude::*;

use super::BAND;

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
            "{:>2} {:<12} {:<25} {:>7.2} {:>6} {:>10.2e} {:>10.2e} {:>9} {:>9} {:>9} {:>5} {:>7.4}",
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
            r.colour_err_max,
            r.colour_err_mean
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
    println!("not measured: vertex-data formats (FIXED/HALF/FLOAT on the wire)");
}

/// Writes the error-against-speed plot: one numbered point per row.
pub(super) fn scatter(path: &Path, title: &str, rows: &[Row]) -> Result<()> {
    crate::plot::register_font()?;
    let x1 = rows.iter().map(|r| r.ms).fold(0.0, f64::max).max(1e-3) * 1.15;
    // A log axis: the errors span orders of magnitude; an error of 0 is drawn at the floor.
    const FLOOR: f64 = 1e-3;
    let y1 = rows.iter().map(|r| r.colour_err_mean).fold(FLOOR, f64::max) * 3.0;
    let root = BitMapBackend::new(path, (1100, 620)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(0.0..x1, (FLOOR..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("composite ms (median, GPU-completed)")
        .y_desc("mean |RGBA8 difference| from the f64 reference (log; 0 at 0.001)")
        .label_style(("sans-serif", 15))
        .draw()?;
    let palette = [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44), RGBColor(120, 120, 120)];
    for (i, r) in rows.iter().enumerate() {
        let color = palette[i % palette.len()];
        let at = (r.ms, r.colour_err_mean.max(FLOOR));
        chart
            .draw_series([Circle::new(at, 4, color.filled())])?
            .label(format!("{} {}: {}", i + 1, r.knob, r.setting))
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
        chart.draw_series([Text::new(format!("{}", i + 1), at, ("sans-serif", 14).into_font())])?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
    root.present().with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// `Some(x)` as a percentage, `-` for none.
fn pct(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{:.3}%", v * 100.0))
}
