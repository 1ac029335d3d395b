//! Composites drawn band by band between refreshes. On a CPU rasterizer a large change of
//! lower-priority surfaces (a head unit's full frame) can take longer than a refresh period to
//! composite, and the compositor's device runs one composite at a time: the next refresh's
//! high-priority composite would wait behind it. Such a change is therefore drawn in bands,
//! a few milliseconds each, into a staging image, and as many bands run after each refresh's
//! high-priority composite as fit before the next refresh. When the last band is done, the
//! region is copied to the output in one step, so the output never shows half of a frame.
//!
//! A screenshot finishes the bands first. Banding happens only while high-priority surfaces
//! are shown (otherwise there is nothing to protect), and only in regions none of them
//! overlaps: the high-priority composites between bands draw elsewhere on the output, and the
//! copy cannot hide them.

use std::time::Duration;

use strata_protocol::control::Lighting;

use crate::{Layer, Props};
use strata_scene::Shown;

/// When the compositor draws a change band by band (`--band-above-ms`, `--band-ms`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandOptions {
    /// A change predicted to take longer than this is banded (zero: every change that may be).
    pub above: Duration,
    /// What each band is sized to take (zero: the smallest bands).
    pub target: Duration,
}

impl Default for BandOptions {
    fn default() -> Self {
        BandOptions { above: Duration::from_millis(4), target: Duration::from_millis(2) }
    }
}
/// A band starts only if this many times its predicted time fits before the next refresh.
pub(crate) const BAND_SLACK: f64 = 1.5;
/// Fewest rows in a band.
const MIN_ROWS: u32 = 8;
/// Weight of the newest composite in the running cost per pixel.
const COST_WEIGHT: f64 = 0.3;

/// One surface of a banded composite, kept (with its views) until the last band.
pub struct KeptLayer {
    rect: [i32; 4],
    z: f32,
    color: wgpu::TextureView,
    depth: Option<wgpu::TextureView>,
    normal: [f32; 3],
    projection: [f32; 4],
    opaque: bool,
    props: Props,
}

impl KeptLayer {
    /// Keeps `l`'s views for later bands.
    pub fn keep(l: &Layer<'_>) -> KeptLayer {
        KeptLayer {
            rect: l.rect,
            z: l.z,
            color: l.color.clone(),
            depth: l.depth.cloned(),
            normal: l.normal,
            projection: l.projection,
            opaque: l.opaque,
            props: l.props,
        }
    }

    /// The layer as the compositor takes it.
    pub fn layer(&self) -> Layer<'_> {
        Layer {
            rect: self.rect,
            z: self.z,
            color: &self.color,
            depth: self.depth.as_ref(),
            normal: self.normal,
            projection: self.projection,
            opaque: self.opaque,
            props: self.props,
        }
    }
}

/// One output's banded region.
pub struct Job {
    /// The output's index.
    pub output: usize,
    /// x, y, width, height in the output's pixels.
    pub region: [u32; 4],
    /// Rows of the region drawn so far.
    pub rows_done: u32,
    /// The surfaces, in stacking order, in the output's pixels.
    pub layers: Vec<KeptLayer>,
}

impl Job {
    /// Whether every row is drawn.
    pub fn finished(&self) -> bool {
        self.rows_done >= self.region[3]
    }

    /// The next band: `rows` rows (at least `MIN_ROWS`) from where the last ended.
    pub fn next_band(&self, rows: u32) -> [u32; 4] {
        let [x, y, w, h] = self.region;
        let rows = rows.max(MIN_ROWS).min(h - self.rows_done.min(h));
        [x, y + self.rows_done, w, rows]
    }
}

/// A composite in progress over several refreshes.
pub struct Banded {
    /// Per output, its region and what is drawn of it.
    pub jobs: Vec<Job>,
    /// The lighting when it was taken.
    pub light: Lighting,
    /// The new frames it took, recorded when it completes.
    pub shown: Shown,
    /// The damage count it reflects.
    pub seen: u64,
}

/// The compositor's running cost per output pixel, from the composites it has timed.
#[derive(Default)]
pub struct Cost {
    us_per_pixel: Option<f64>,
}

impl Cost {
    /// Folds in a composite of `pixels` pixels that took `took`.
    pub fn record(&mut self, pixels: u64, took: Duration) {
        if pixels == 0 {
            return;
        }
        let now = took.as_secs_f64() * 1e6 / pixels as f64;
        self.us_per_pixel = Some(self.us_per_pixel.map_or(now, |c| c + COST_WEIGHT * (now - c)));
    }

    /// The predicted time of `pixels` pixels (none until a composite was timed).
    pub fn predict(&self, pixels: u64) -> Option<Duration> {
        self.us_per_pixel.map(|c| Duration::from_secs_f64(c * pixels as f64 / 1e6))
    }

    /// Rows of `width` pixels that take about `target`.
    pub fn rows(&self, width: u32, target: Duration) -> u32 {
        let per_row = self.us_per_pixel.unwrap_or(0.0) * f64::from(width.max(1));
        if per_row <= 0.0 {
            return u32::MAX;
        }
        (target.as_secs_f64() * 1e6 / per_row).clamp(1.0, f64::from(u32::MAX)) as u32
    }
}

/// Whether rectangles `a` and `b` (x, y, width, height) share a pixel.
pub fn overlaps(a: [i64; 4], b: [i64; 4]) -> bool {
    a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_cover_the_region_once_in_order() {
        let mut job = Job { output: 0, region: [10, 20, 100, 45], rows_done: 0, layers: Vec::new() };
        let mut rows = Vec::new();
        while !job.finished() {
            let b = job.next_band(10);
            assert_eq!((b[0], b[2]), (10, 100));
            rows.push((b[1], b[3]));
            job.rows_done += b[3];
        }
        assert_eq!(rows, [(20, 10), (30, 10), (40, 10), (50, 10), (60, 5)]);
    }

    #[test]
    fn the_cost_model_sizes_bands_to_the_target() {
        let mut c = Cost::default();
        assert_eq!(c.predict(1000), None);
        let target = Duration::from_millis(2);
        assert_eq!(c.rows(100, target), u32::MAX);
        // 1 µs a pixel: 2 ms is 2000 pixels, 20 rows of 100.
        c.record(10_000, Duration::from_millis(10));
        assert_eq!(c.rows(100, target), 20);
        assert_eq!(c.predict(5000), Some(Duration::from_millis(5)));
        // A slower composite moves the estimate part of the way.
        c.record(10_000, Duration::from_millis(20));
        assert!((c.predict(1_000_000).unwrap().as_secs_f64() - 1.3).abs() < 1e-9);
    }

    #[test]
    fn rectangles_overlap_only_when_they_share_a_pixel() {
        assert!(overlaps([0, 0, 10, 10], [9, 9, 5, 5]));
        assert!(!overlaps([0, 0, 10, 10], [10, 0, 5, 5]));
        assert!(!overlaps([0, 0, 10, 10], [0, 10, 5, 5]));
        assert!(!overlaps([0, 0, 0, 10], [0, 0, 5, 5]));
    }
}
