//! Line plots of benchmark curves, written as PNG next to the JSON.

use std::path::Path;

use anyhow::{Context, Result};
use plotters::prelude::*;

/// Font files tried for axis labels (Debian's fonts-dejavu-core).
const FONTS: [&str; 2] = ["/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf"];

/// Registers the sans-serif font plots label with.
pub(crate) fn register_font() -> Result<()> {
    static DONE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        FONTS.iter().find_map(|p| std::fs::read(p).ok()).is_some_and(|bytes| {
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok()
        })
    });
    ok.then_some(()).with_context(|| format!("no font for plot labels (tried {FONTS:?}; install fonts-dejavu-core)"))
}

/// One named curve.
pub struct Series {
    /// Legend label.
    pub name: String,
    /// (x, y) points in x order.
    pub points: Vec<(f64, f64)>,
    /// Dashed reference line rather than a measured curve.
    pub reference: bool,
}

/// Writes a line plot of `series` to `path` (PNG, 960×540).
pub fn line_plot(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Result<()> {
    register_font()?;
    let all = series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = all.clone().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let y1 = all.fold(0.0f64, |a, p| a.max(p.1)) * 1.1;
    let root = BitMapBackend::new(path, (960, 540)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, 0.0..y1.max(1e-9))?;
    // Whole-number x values (counts) are labelled without a fraction.
    let x_fmt = |x: &f64| if x.fract() == 0.0 { format!("{x:.0}") } else { format!("{x:.2}") };
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&x_fmt)
        .label_style(("sans-serif", 15))
        .draw()?;
    let palette = [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44), RGBColor(120, 120, 120)];
    for (i, s) in series.iter().enumerate() {
        let color = palette[i % palette.len()];
        let style = color.stroke_width(2);
        if s.reference {
            chart
                .draw_series(DashedLineSeries::new(s.points.iter().copied(), 8, 6, style))?
                .label(&s.name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
        } else {
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), style))?
                .label(&s.name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
            chart.draw_series(s.points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
    root.present().with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}
