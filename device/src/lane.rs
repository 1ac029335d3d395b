//! A [`Lane`]: one client's class and its own submissions (the newest, the one of its previous
//! frame) and where its frames waited. Every submission names its lane at the one door through
//! which work reaches a queue, [`crate::Gpu::submit`] (each device also has a lane of its own,
//! `Gpu::lane`, for the work of the device's owner).

use std::sync::atomic::{AtomicU64, AtomicU8, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use strata_protocol::control::{Priority, Waits};
use tracing::warn;

use crate::marks::Marks;

/// The longest any wait for the device lasts before it is given up on (a wedged device must
/// not wedge the daemon's threads).
const GPU_WAIT_LIMIT: Duration = Duration::from_secs(5);

#[derive(Default)]
struct Counters {
    swap_us: AtomicU64,
    gpu_us: AtomicU64,
}

/// One client's class, its newest submission, and where its frames waited.
pub struct Lane {
    class: AtomicU8,
    /// The client's newest submission.
    last: Mutex<Option<wgpu::SubmissionIndex>>,
    /// Its newest submission at its previous swap.
    frame: Mutex<Option<wgpu::SubmissionIndex>>,
    counters: Counters,
    /// The client's fence marks (see [`crate::Gpu::mark`]).
    marks: Arc<Marks>,
}

impl std::fmt::Debug for Lane {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Lane").field("class", &self.class()).field("waits", &self.waits()).finish()
    }
}

fn micros(d: Duration) -> u64 {
    d.as_micros().min(u128::from(u64::MAX)) as u64
}

impl Lane {
    /// A lane in `class`.
    pub fn new(class: Priority) -> Arc<Lane> {
        Arc::new(Lane {
            class: AtomicU8::new(class as u8),
            last: Mutex::new(None),
            frame: Mutex::new(None),
            counters: Counters::default(),
            marks: Arc::default(),
        })
    }

    /// The client's class.
    pub fn class(&self) -> Priority {
        match self.class.load(Ordering::Relaxed) {
            0 => Priority::High,
            2 => Priority::Low,
            _ => Priority::Normal,
        }
    }

    /// Moves the client to `class` (what its EGL context asked for, when the configuration
    /// does not say).
    pub fn set_class(&self, class: Priority) {
        self.class.store(class as u8, Ordering::Relaxed);
    }

    /// Records `index` as the lane's newest submission ([`crate::Gpu::submit`] does).
    pub(crate) fn submitted(&self, index: wgpu::SubmissionIndex) {
        if let Ok(mut l) = self.last.lock() {
            *l = Some(index);
        }
    }

    /// The lane's fence marks.
    pub(crate) fn marks(&self) -> &Arc<Marks> {
        &self.marks
    }

    /// Publishes the newest fence mark reached on this lane to `word` (the client's segment),
    /// from now on.
    pub fn publish_marks(&self, word: strata_protocol::segment::FenceWord) {
        self.marks.publish_to(word);
    }

    /// Waits until `index` has completed, counting the time as device wait.
    fn wait_for(&self, device: &wgpu::Device, index: wgpu::SubmissionIndex) {
        let start = Instant::now();
        let poll = wgpu::PollType::Wait { submission_index: Some(index), timeout: Some(GPU_WAIT_LIMIT) };
        if let Err(e) = device.poll(poll) {
            warn!("waiting for the device: {e}");
        }
        self.counters.gpu_us.fetch_add(micros(start.elapsed()), Ordering::Relaxed);
    }

    /// Waits for everything this client has submitted on `device` (readbacks, `glFinish`).
    pub fn wait_idle(&self, device: &wgpu::Device) {
        let last = self.last.lock().ok().and_then(|l| l.clone());
        if let Some(index) = last {
            self.wait_for(device, index);
        }
    }

    /// At a swap: waits for the previous frame's work to complete, so that the client has at
    /// most one frame in flight on its device, and remembers this frame's.
    pub fn frame_boundary(&self, device: &wgpu::Device) {
        let now = self.last.lock().ok().and_then(|l| l.clone());
        let previous = self.frame.lock().ok().and_then(|mut f| std::mem::replace(&mut *f, now));
        if let Some(index) = previous {
            self.wait_for(device, index);
        }
    }

    /// Counts time spent blocked in a swap.
    pub fn add_swap_wait(&self, d: Duration) {
        self.counters.swap_us.fetch_add(micros(d), Ordering::Relaxed);
    }

    /// Where this client's frames have waited so far.
    pub fn waits(&self) -> Waits {
        let c = &self.counters;
        Waits { swap_us: c.swap_us.load(Ordering::Relaxed), gpu_us: c.gpu_us.load(Ordering::Relaxed) }
    }
}
