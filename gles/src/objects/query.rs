//! Query objects: occlusion queries' last results and timer queries' timestamps, and the
//! query active on each target.

use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Arc;
use std::time::Duration;

use strata_device::Gpu;

use crate::render::occlusion::Occlusion;

/// A query object: a name from `glGenQueriesEXT`, which becomes a query of one target when it
/// is first begun.
#[derive(Default)]
pub struct Query {
    /// Its target once begun (0 before).
    pub target: u32,
    /// Its last begin/end.
    pub last: Option<Arc<Occlusion>>,
    /// A timer query's timestamps (`GL_EXT_disjoint_timer_query`).
    pub timer: Option<crate::objects::query::Timer>,
    /// A `GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN` query's count (ES 3.0).
    pub primitives: u64,
}

/// The occlusion query a context has active: its name and target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Active {
    /// The query's name.
    pub name: u32,
    /// `GL_ANY_SAMPLES_PASSED_EXT` or `GL_ANY_SAMPLES_PASSED_CONSERVATIVE_EXT`.
    pub target: u32,
}

/// The longest a result waits for the device.
pub(crate) const RESULT_WAIT: Duration = Duration::from_secs(5);

pub(crate) const PENDING: u8 = 0;

pub(crate) const MAPPED: u8 = 1;

pub(crate) const FAILED: u8 = 2;

/// One query's timestamps (two for an elapsed time, one for a counter) on their way back.
pub struct Timer {
    pub(crate) set: wgpu::QuerySet,
    pub(crate) resolve: wgpu::Buffer,
    pub(crate) read: wgpu::Buffer,
    pub(crate) count: u32,
    /// Whether the timestamps were resolved and the read requested.
    pub(crate) state: Arc<AtomicU8>,
    pub(crate) requested: bool,
}

impl Timer {
    /// Room for `count` timestamps on `gpu`.
    pub(crate) fn new(gpu: &Gpu, count: u32) -> Timer {
        let d = &gpu.device;
        let size = 8 * u64::from(count);
        let buffer = |label, usage| {
            d.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size, usage, mapped_at_creation: false })
        };
        Timer {
            set: d.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("gl timer"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer("gl timer", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read: buffer("gl timer read", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
            count,
            state: Arc::new(AtomicU8::new(PENDING)),
            requested: false,
        }
    }

    /// Commands writing timestamp `index` (and, for the last one, copying them all to where
    /// they can be read).
    pub(crate) fn write(&self, gpu: &Gpu, index: u32) -> wgpu::CommandBuffer {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("gl timestamp"),
            timestamp_writes: Some(wgpu::ComputePassTimestampWrites {
                query_set: &self.set,
                beginning_of_pass_write_index: Some(index),
                end_of_pass_write_index: None,
            }),
        });
        if index + 1 == self.count {
            enc.resolve_query_set(&self.set, 0..self.count, &self.resolve, 0);
            enc.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 8 * u64::from(self.count));
        }
        enc.finish()
    }

    /// Asks for the read (after the last timestamp has been submitted: a buffer waiting to be
    /// mapped cannot be used by a submission).
    pub(crate) fn request(&mut self) {
        if !self.requested {
            self.requested = true;
            let state = self.state.clone();
            self.read.slice(..).map_async(wgpu::MapMode::Read, move |r| {
                state.store(if r.is_ok() { MAPPED } else { FAILED }, Ordering::Release)
            });
        }
    }

    /// The timestamps in nanoseconds, if they have been read (after a poll that waits with
    /// `wait`, at most [`RESULT_WAIT`]); a device that cannot read them answers zeros.
    pub(crate) fn values(&self, gpu: &Gpu, wait: bool) -> Option<Vec<u64>> {
        let deadline = std::time::Instant::now() + RESULT_WAIT;
        loop {
            let poll = if wait {
                wgpu::PollType::Wait { submission_index: None, timeout: Some(Duration::from_millis(100)) }
            } else {
                wgpu::PollType::Poll
            };
            let _ = gpu.device.poll(poll);
            match self.state.load(Ordering::Acquire) {
                MAPPED => break,
                FAILED => return Some(vec![0; self.count as usize]),
                _ if !wait => return None,
                _ if std::time::Instant::now() >= deadline => return Some(vec![0; self.count as usize]),
                _ => {}
            }
        }
        let period = f64::from(gpu.timestamp_period());
        let Ok(view) = self.read.slice(..).get_mapped_range() else { return Some(vec![0; self.count as usize]) };
        let bytes = view.to_vec();
        Some(
            bytes
                .chunks_exact(8)
                .map(|c| (u64::from_le_bytes(c.try_into().unwrap_or_default()) as f64 * period) as u64)
                .collect(),
        )
    }

    /// The query's result: the elapsed time, or the counter's time.
    pub(crate) fn result(&self, gpu: &Gpu, wait: bool) -> Option<u64> {
        let v = self.values(gpu, wait)?;
        Some(match v.as_slice() {
            [t0, t1] => t1.saturating_sub(*t0),
            [t] => *t,
            _ => 0,
        })
    }
}
