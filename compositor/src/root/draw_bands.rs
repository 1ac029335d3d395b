//! Drawing a composite band by band over several refreshes: the next band within the time
//! left before the refresh, and the finished image copied to the outputs.

use std::time::Instant;

use strata_scene::Region;

use super::bands::{overlaps, KeptLayer, BAND_SLACK};
use super::state::{Inner, Root, BACKGROUND};
use crate::Layer;

impl Root {
    /// Draws bands of the composite in progress: until `deadline` (at least one band), or
    /// with none to its end, which copies it in.
    pub(super) fn run_bands(&self, inner: &mut Inner, deadline: Option<Instant>) {
        let mut ran = false;
        loop {
            let Inner { compositor, outputs, bands, cost, .. } = &mut *inner;
            let Some(b) = bands.as_mut() else { return };
            let Some(job) = b.jobs.iter_mut().find(|j| !j.finished()) else {
                self.finish_bands(inner);
                return;
            };
            let band = job.next_band(cost.rows(job.region[2], self.bands.target));
            let pixels = u64::from(band[2]) * u64::from(band[3]);
            if let (true, Some(d)) = (ran, deadline) {
                // With room to spare: a band that runs late delays the next refresh.
                if Instant::now() + cost.predict(pixels).unwrap_or_default().mul_f64(BAND_SLACK) > d {
                    return;
                }
            }
            let Some(out) = outputs.get_mut(job.output) else {
                job.rows_done = job.region[3];
                continue;
            };
            let started = Instant::now();
            let layers: Vec<Layer<'_>> = job.layers.iter().map(KeptLayer::layer).collect();
            if let Err(e) = compositor.composite(&layers, &b.light, out.staging(&self.gpu), BACKGROUND, Some(band)) {
                // The band keeps what the staging image held.
                tracing::error!(output = %out.spec.name, "{e}");
            }
            let passes = compositor.last_passes as u64;
            job.rows_done += band[3];
            let output = job.output;
            let (device, waited) = self.wait_composite(inner);
            inner.cost.record(pixels, started.elapsed());
            if let Some(out) = inner.outputs.get_mut(output) {
                out.passes = passes;
                out.device += device;
                out.queue += waited - device;
                out.encode += started.elapsed().saturating_sub(waited);
            }
            ran = true;
        }
    }

    /// The last band is drawn: copies each region in, then lets the frames it read go. Where
    /// a high-priority surface has come to overlap a region meanwhile, that region is
    /// composited again instead, since the copy would cover what was drawn of it since.
    fn finish_bands(&self, inner: &mut Inner) {
        let Some(b) = inner.bands.take() else { return };
        let high = self.scene.high_rects();
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        let mut copied = Vec::new();
        for job in &b.jobs {
            let Some(out) = inner.outputs.get_mut(job.output) else { continue };
            let (ox, oy) = (out.spec.x, out.spec.y);
            let [x, y, w, h] = job.region;
            let global = [i64::from(ox) + i64::from(x), i64::from(oy) + i64::from(y), i64::from(w), i64::from(h)];
            if high.iter().any(|r| overlaps(r.map(i64::from), global)) {
                self.scene.redraw(Region::Rect(global));
                continue;
            }
            let origin = wgpu::Origin3d { x, y, z: 0 };
            let at = |texture| wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin,
                aspect: wgpu::TextureAspect::All,
            };
            let staging = out.staging(&self.gpu).clone();
            encoder.copy_texture_to_texture(
                at(&staging),
                at(&out.texture),
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
            copied.push((job.output, job.region));
        }
        inner.compositor.last_submission = Some(self.gpu.submit(&self.gpu.lane, vec![encoder.finish()]));
        for &(i, r) in &copied {
            if let Some(out) = inner.outputs.get_mut(i) {
                out.composites += 1;
                out.banded += 1;
                out.region = r.map(|v| v as i32);
                if let Some(w) = &mut out.window {
                    w.present(&self.gpu, &out.texture);
                }
            }
        }
        self.wait_composite(inner);
        self.scene.release(b.shown);
        inner.composited = Some(b.seen);
    }
}
