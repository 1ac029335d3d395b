//! Occlusion queries on the GPU: each draw recorded while a query is active is wrapped in an
//! occlusion query of its pass's query set; after the pass the counts are resolved into a
//! buffer that is read back, and a query's answer is whether any of its draws passed a sample.

use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use strata_device::Gpu;

/// A readback's map has not completed.
const PENDING: u8 = 0;
/// A readback's buffer is mapped.
const MAPPED: u8 = 1;
/// A readback's map failed (a lost device): its draws count as passing no sample.
const FAILED: u8 = 2;

/// How long a result is waited for before the query answers with what it has.
const RESULT_WAIT: Duration = Duration::from_secs(5);

/// The counts of one pass, being read back, and which of them belong to a query.
struct Readback {
    /// The mapped (or mapping) buffer of the pass's counts, 8 bytes each.
    buffer: wgpu::Buffer,
    /// [`PENDING`] until the map completes, then [`MAPPED`] or [`FAILED`].
    state: Arc<AtomicU8>,
    /// The query's counts in it.
    slots: Vec<usize>,
}

/// One begin/end of an occlusion query: the passes its draws went into, and the answer once
/// they have all been read.
#[derive(Default)]
pub struct Occlusion {
    /// Passes not yet read.
    readbacks: Mutex<Vec<Readback>>,
    /// Whether a draw read so far passed a sample.
    any: AtomicBool,
}

impl Occlusion {
    /// A query with no draws yet.
    pub fn new() -> Arc<Occlusion> {
        Arc::default()
    }

    /// Reads the passes that are mapped; whether none is left to read.
    fn collect(&self) -> bool {
        let Ok(mut list) = self.readbacks.lock() else { return true };
        list.retain(|r| {
            match r.state.load(Ordering::Acquire) {
                PENDING => return true,
                FAILED => return false,
                _ => {}
            }
            if let Ok(data) = r.buffer.slice(..).get_mapped_range() {
                let counts: &[u64] = bytemuck::cast_slice(&data);
                if r.slots.iter().any(|&s| counts.get(s).is_some_and(|&c| c != 0)) {
                    self.any.store(true, Ordering::Release);
                }
            }
            false
        });
        list.is_empty()
    }

    /// Whether the answer is known, after a poll of `gpu` that does not wait.
    pub fn available(&self, gpu: &Gpu) -> bool {
        let _ = gpu.device.poll(wgpu::PollType::Poll);
        self.collect()
    }

    /// The answer, waiting for the passes it needs (at most [`RESULT_WAIT`]: a device that
    /// cannot finish answers with the draws read so far).
    pub fn result(&self, gpu: &Gpu) -> bool {
        let deadline = std::time::Instant::now() + RESULT_WAIT;
        while !self.collect() && std::time::Instant::now() < deadline {
            let wait = wgpu::PollType::Wait { submission_index: None, timeout: Some(Duration::from_millis(100)) };
            let _ = gpu.device.poll(wait);
        }
        self.any.load(Ordering::Acquire)
    }
}

/// The occlusion queries of one pass: its query set, and where the counts are resolved.
pub(super) struct PassQueries {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    /// The query each slot counts for, in the order of the pass's queried draws.
    slots: Vec<Arc<Occlusion>>,
}

impl PassQueries {
    /// A query set for the queried draws `slots` of a pass; `None` without any.
    pub(super) fn new(gpu: &Gpu, slots: Vec<Arc<Occlusion>>) -> Option<PassQueries> {
        if slots.is_empty() {
            return None;
        }
        let n = slots.len() as u32;
        let set = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("occlusion"),
            ty: wgpu::QueryType::Occlusion,
            count: n,
        });
        let size = u64::from(n) * 8;
        let buffer = |label, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let resolve = buffer("occlusion resolve", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC);
        let read = buffer("occlusion read", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST);
        Some(PassQueries { set, resolve, read, slots })
    }

    /// The query set the pass counts into.
    pub(super) fn set(&self) -> &wgpu::QuerySet {
        &self.set
    }

    /// Records the resolve of every count and its copy to the buffer read back.
    pub(super) fn resolve(&self, enc: &mut wgpu::CommandEncoder) {
        let n = self.slots.len() as u32;
        enc.resolve_query_set(&self.set, 0..n, &self.resolve, 0);
        enc.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, u64::from(n) * 8);
    }

    /// After the pass is submitted: maps the counts, and gives each query its slots.
    pub(super) fn read_back(self) {
        let state = Arc::new(AtomicU8::new(PENDING));
        let done = state.clone();
        self.read.slice(..).map_async(wgpu::MapMode::Read, move |r| {
            done.store(if r.is_ok() { MAPPED } else { FAILED }, Ordering::Release)
        });
        let mut seen: Vec<&Arc<Occlusion>> = Vec::new();
        for q in &self.slots {
            if seen.iter().any(|s| Arc::ptr_eq(s, q)) {
                continue;
            }
            seen.push(q);
            let slots = self.slots.iter().enumerate().filter(|(_, s)| Arc::ptr_eq(s, q)).map(|(i, _)| i).collect();
            if let Ok(mut list) = q.readbacks.lock() {
                list.push(Readback { buffer: self.read.clone(), state: state.clone(), slots });
            }
        }
    }
}
