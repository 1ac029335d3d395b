//! The composite's own device time: timestamps written at the start of its first pass and the
//! end of its last (where the device has `TIMESTAMP_QUERY`), read back once the composite has
//! completed. The rest of the time from submission to completion is time the composite waited
//! on its queue.

use std::time::Duration;

use strata_device::Gpu;

/// Timestamps around one composite.
pub struct Timing {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    /// Whether the last composite wrote timestamps that are not read yet.
    written: bool,
}

impl Timing {
    /// Timestamps on `gpu`, if it has them.
    pub fn new(gpu: &Gpu) -> Option<Timing> {
        if !gpu.features.contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let d = &gpu.device;
        let buffer = |label, usage| {
            d.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size: 16, usage, mapped_at_creation: false })
        };
        Some(Timing {
            set: d.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("composite timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: buffer("composite timestamps", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            readback: buffer("composite timestamps read", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
            written: false,
        })
    }

    /// The timestamp writes of pass `i` of `n`: the start of the first, the end of the last.
    pub fn writes(&self, i: usize, n: usize) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        let begin = (i == 0).then_some(0);
        let end = (i + 1 == n).then_some(1);
        (begin.is_some() || end.is_some()).then_some(wgpu::RenderPassTimestampWrites {
            query_set: &self.set,
            beginning_of_pass_write_index: begin,
            end_of_pass_write_index: end,
        })
    }

    /// Copies the timestamps where they can be read, at the end of the composite's commands.
    pub fn resolve(&mut self, enc: &mut wgpu::CommandEncoder) {
        enc.resolve_query_set(&self.set, 0..2, &self.resolve, 0);
        enc.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, 16);
        self.written = true;
    }

    /// The device time between the two timestamps of the last composite, once it has
    /// completed (`None` if it wrote none, or they cannot be read).
    pub fn device_time(&mut self, gpu: &Gpu) -> Option<Duration> {
        if !std::mem::take(&mut self.written) {
            return None;
        }
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        let _ = gpu.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: Some(Duration::from_secs(5)) });
        rx.try_recv().ok()?.ok()?;
        let ticks = {
            let data = slice.get_mapped_range().ok()?;
            let t: &[u64] = bytemuck::cast_slice(&data);
            t[1].saturating_sub(t[0])
        };
        self.readback.unmap();
        let ns = ticks as f64 * f64::from(gpu.timestamp_period());
        Some(Duration::from_nanos(ns as u64))
    }
}
