//! `GL_EXT_disjoint_timer_query`, where the device has timestamp queries: `GL_TIME_ELAPSED_EXT`
//! queries and `GL_TIMESTAMP_EXT` counters, on the device's own clock. A timestamp is written
//! by an empty compute pass submitted on the client's queue after everything before it (the
//! open pass is submitted first), so the two of a begin/end bracket the device's work on the
//! commands between them. The values are read back once they have completed; in nanoseconds
//! (the device's ticks times its timestamp period). The device's clock never jumps here, so
//! `GL_GPU_DISJOINT_EXT` is always false. As on Mesa held to ES 2.0, `glGetInteger64vEXT` does
//! not answer `GL_TIMESTAMP_EXT` (`GL_INVALID_ENUM`); `glQueryCounterEXT` does.

use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Arc;
use std::time::Duration;

use super::context::Context;
use super::error::{GlError, GlResult};
use super::GlesExecutor;
use strata_device::Gpu;

/// `GL_TIME_ELAPSED_EXT`.
pub const TIME_ELAPSED: u32 = 0x88BF;
/// `GL_TIMESTAMP_EXT`.
pub const TIMESTAMP: u32 = 0x8E28;
/// `GL_QUERY_COUNTER_BITS_EXT`.
pub const QUERY_COUNTER_BITS: u32 = 0x8864;
/// `GL_GPU_DISJOINT_EXT`.
pub const GPU_DISJOINT: u32 = 0x8FBB;

/// The longest a result waits for the device.
const RESULT_WAIT: Duration = Duration::from_secs(5);

const PENDING: u8 = 0;
const MAPPED: u8 = 1;
const FAILED: u8 = 2;

/// One query's timestamps (two for an elapsed time, one for a counter) on their way back.
pub struct Timer {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    count: u32,
    /// Whether the timestamps were resolved and the read requested.
    state: Arc<AtomicU8>,
    requested: bool,
}

impl Timer {
    /// Room for `count` timestamps on `gpu`.
    fn new(gpu: &Gpu, count: u32) -> Timer {
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
    fn write(&self, gpu: &Gpu, index: u32) -> wgpu::CommandBuffer {
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
    fn request(&mut self) {
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
    fn values(&self, gpu: &Gpu, wait: bool) -> Option<Vec<u64>> {
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
    fn result(&self, gpu: &Gpu, wait: bool) -> Option<u64> {
        let v = self.values(gpu, wait)?;
        Some(match v.as_slice() {
            [t0, t1] => t1.saturating_sub(*t0),
            [t] => *t,
            _ => 0,
        })
    }
}

impl GlesExecutor {
    /// Whether the device has timestamps (the extension is offered only then).
    pub(super) fn has_timers(&self) -> bool {
        self.gpu.features.contains(wgpu::Features::TIMESTAMP_QUERY)
    }

    /// Writes `timer`'s timestamp `index` after what is pending, and asks for the read once
    /// it was the last.
    fn stamp(&mut self, timer: &mut Timer, index: u32) {
        let cmd = timer.write(&self.gpu, index);
        self.r.flush();
        self.gpu.submit(&self.r.lane, vec![cmd]);
        if index + 1 == timer.count {
            timer.request();
        }
    }

    /// `glBeginQueryEXT(GL_TIME_ELAPSED_EXT, id)`.
    pub(super) fn begin_timer(&mut self, ctx: &mut Context, id: u32) -> GlResult {
        if id == 0 || ctx.active_timer.is_some() {
            return Err(GlError::InvalidOperation);
        }
        let q = ctx.queries.get_mut(&id).ok_or(GlError::InvalidOperation)?;
        if q.target != 0 && q.target != TIME_ELAPSED {
            return Err(GlError::InvalidOperation);
        }
        let mut timer = Timer::new(&self.gpu, 2);
        self.stamp(&mut timer, 0);
        q.target = TIME_ELAPSED;
        q.timer = Some(timer);
        ctx.active_timer = Some(id);
        Ok(())
    }

    /// `glEndQueryEXT(GL_TIME_ELAPSED_EXT)`.
    pub(super) fn end_timer(&mut self, ctx: &mut Context) -> GlResult {
        let id = ctx.active_timer.take().ok_or(GlError::InvalidOperation)?;
        let Some(timer) = ctx.queries.get_mut(&id).and_then(|q| q.timer.as_mut()) else { return Ok(()) };
        self.stamp(timer, 1);
        Ok(())
    }

    #[allow(non_snake_case)]
    pub(super) fn glQueryCounterEXT(&mut self, ctx: &mut Context, id: u32, target: u32) -> GlResult {
        if target != TIMESTAMP || !self.has_timers() {
            return Err(GlError::InvalidEnum);
        }
        if ctx.active_timer == Some(id) || ctx.active_query.is_some_and(|a| a.name == id) {
            return Err(GlError::InvalidOperation);
        }
        if id == 0 {
            return Err(GlError::InvalidOperation);
        }
        // As on Mesa, a name never generated becomes a query here.
        if ctx.queries.get(&id).is_none() {
            if ctx.queries.len() as u64 >= super::occlusion::MAX_QUERIES {
                return Err(GlError::OutOfMemory);
            }
            ctx.queries.generate([id]);
        }
        let q = ctx.queries.get_mut(&id).ok_or(GlError::InvalidOperation)?;
        if q.target != 0 && q.target != TIMESTAMP {
            return Err(GlError::InvalidOperation);
        }
        let mut timer = Timer::new(&self.gpu, 1);
        self.stamp(&mut timer, 0);
        q.target = TIMESTAMP;
        q.timer = Some(timer);
        Ok(())
    }

    /// A timer query's `GL_QUERY_RESULT_EXT` (waiting) or `GL_QUERY_RESULT_AVAILABLE_EXT`.
    pub(super) fn timer_value(&mut self, ctx: &Context, id: u32, result: bool) -> Option<u64> {
        let timer = ctx.queries.get(&id)?.timer.as_ref()?;
        if result {
            timer.result(&self.gpu, true)
        } else {
            Some(u64::from(timer.result(&self.gpu, false).is_some()))
        }
    }
}
