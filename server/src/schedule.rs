//! Scheduling on the one GPU queue. wgpu has no queue priorities, so the daemon decides when
//! each client's recorded work goes onto the queue:
//!
//! - `high` work (an instrument cluster, and the compositor) is submitted at once;
//! - `normal` work is submitted as it comes, as before classes existed;
//! - `low` work waits while high work is being submitted, goes onto the queue one slice at a
//!   time (the next waits until the previous has finished, so high work finds at most one
//!   slice ahead of it), and while a high client is connected it may use only a share of each
//!   refresh period, measured as the time each slice takes to complete. A low client over its
//!   share is deferred, never dropped: its decoder thread waits, so its frames arrive later
//!   and whole.
//!
//! Every client, whatever its class, has at most one frame on the queue when it swaps: the
//! swap waits for the previous frame's work, so an unpaced client cannot pile up a backlog
//! that everything submitted after it must wait behind.
//!
//! Slicing a pass (by draws, or by bands of the target when it has fewer draws than slices)
//! is the renderer's part (`gles::render::passes`); this module sizes slices and times them.

use std::sync::atomic::{AtomicU64, AtomicU8, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use strata_protocol::control::{Priority, Waits};
use tracing::{debug, warn};

/// The longest any wait for the device lasts before it is given up on (a wedged device must
/// not wedge the daemon's threads).
const GPU_WAIT_LIMIT: Duration = Duration::from_secs(5);

/// The nice value of a low-priority client's session thread.
#[cfg(target_os = "linux")]
const LOW_NICE: libc::c_int = 10;

/// How the scheduler runs, from `stratad serve`'s options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Policy {
    /// Whether classes are honoured at all (`false`: every client is submitted as it comes,
    /// the behaviour without a scheduler, for comparison).
    pub enabled: bool,
    /// The GPU time one low-priority slice aims at.
    pub slice: Duration,
    /// The share of each refresh period low-priority work may use while a high client is
    /// connected.
    pub low_share: f64,
    /// The refresh period the share is of.
    pub period: Duration,
    /// The class of clients the configuration does not name and whose contexts do not ask.
    pub default_class: Priority,
    /// Cut every low-priority pass into this many pieces, whatever it cost (for testing that
    /// slicing leaves the image unchanged).
    pub force_pieces: Option<usize>,
    /// While a high client is connected, no low slice starts within this long after a
    /// composite (when the compositor and the clients whose frames it took run), nor within
    /// a slice and a millisecond before the next.
    pub guard: Duration,
}

impl Default for Policy {
    fn default() -> Self {
        Policy {
            enabled: true,
            slice: Duration::from_millis(2),
            low_share: 0.5,
            period: Duration::from_secs(1) / 60,
            default_class: Priority::Normal,
            force_pieces: None,
            guard: Duration::from_millis(4),
        }
    }
}

/// `stratad serve`'s scheduling options.
#[derive(Debug, Clone, clap::Args)]
pub struct ScheduleArgs {
    /// Submit every client's work as it comes, whatever its class (for comparison).
    #[arg(long)]
    pub no_scheduler: bool,
    /// GPU time one low-priority slice aims at, milliseconds.
    #[arg(long, default_value_t = 2.0)]
    pub slice_ms: f64,
    /// Share of each refresh period low-priority work may use while a high-priority client
    /// is connected.
    #[arg(long, default_value_t = 0.5)]
    pub low_share: f64,
    /// The class of clients the configuration does not name and whose EGL contexts do not ask
    /// for one: high, normal or low.
    #[arg(long, default_value = "normal")]
    pub default_priority: Priority,
    /// Milliseconds after each composite in which no low-priority slice starts while a
    /// high-priority client is connected (0: none).
    #[arg(long, default_value_t = 4.0)]
    pub guard_ms: f64,
    /// Cut every low-priority pass into this many pieces whatever it costs (testing).
    #[arg(long, hide = true, value_parser = clap::value_parser!(u32).range(1..=512))]
    pub force_pieces: Option<u32>,
}

/// A scheduling option out of range.
#[derive(Debug, thiserror::Error)]
pub enum ScheduleError {
    /// `--slice-ms` outside 0.1..=100.
    #[error("--slice-ms {0} must lie in 0.1..=100")]
    Slice(f64),
    /// `--low-share` outside 0.05..=1.
    #[error("--low-share {0} must lie in 0.05..=1")]
    Share(f64),
    /// `--guard-ms` outside 0..=10.
    #[error("--guard-ms {0} must lie in 0..=10")]
    Guard(f64),
}

impl ScheduleArgs {
    /// The policy the options give (its period is set from the refresh rate at start-up).
    pub fn policy(&self) -> Result<Policy, ScheduleError> {
        if !(self.slice_ms.is_finite() && (0.1..=100.0).contains(&self.slice_ms)) {
            return Err(ScheduleError::Slice(self.slice_ms));
        }
        if !(self.low_share.is_finite() && (0.05..=1.0).contains(&self.low_share)) {
            return Err(ScheduleError::Share(self.low_share));
        }
        if !(self.guard_ms.is_finite() && (0.0..=10.0).contains(&self.guard_ms)) {
            return Err(ScheduleError::Guard(self.guard_ms));
        }
        Ok(Policy {
            enabled: !self.no_scheduler,
            guard: Duration::from_secs_f64(self.guard_ms / 1000.0),
            slice: Duration::from_secs_f64(self.slice_ms / 1000.0),
            low_share: self.low_share,
            default_class: self.default_priority,
            force_pieces: self.force_pieces.map(|n| n as usize),
            ..Policy::default()
        })
    }
}

struct State {
    /// High-class submissions under way.
    high_submitting: usize,
    /// Whether a low slice is on the queue.
    low_busy: bool,
    /// Low GPU time left in the current budget, seconds (negative: overdrawn).
    tokens: f64,
    refilled: Instant,
    /// When the compositor last composited, and when it will next.
    composited: Option<Instant>,
    next_composite: Option<Instant>,
}

/// The daemon's scheduler: one per device.
pub struct Scheduler {
    policy: Mutex<Policy>,
    state: Mutex<State>,
    turn: Condvar,
    /// Lanes of high-class clients alive now.
    high_lanes: AtomicUsize,
}

impl Default for Scheduler {
    fn default() -> Self {
        Scheduler {
            policy: Mutex::new(Policy::default()),
            state: Mutex::new(State {
                high_submitting: 0,
                low_busy: false,
                tokens: 0.0,
                refilled: Instant::now(),
                composited: None,
                next_composite: None,
            }),
            turn: Condvar::new(),
            high_lanes: AtomicUsize::new(0),
        }
    }
}

impl Scheduler {
    /// Sets the policy (at start-up).
    pub fn configure(&self, policy: Policy) {
        if let Ok(mut p) = self.policy.lock() {
            *p = policy;
        }
    }

    /// The policy in force.
    pub fn policy(&self) -> Policy {
        self.policy.lock().map(|p| *p).unwrap_or_default()
    }

    /// A lane for a new client in `class`.
    pub fn lane(self: &Arc<Self>, class: Priority) -> Arc<Lane> {
        let lane = Arc::new(Lane {
            scheduler: self.clone(),
            class: AtomicU8::new(class as u8),
            last: Mutex::new(None),
            frame: Mutex::new(None),
            counters: Counters::default(),
        });
        if class == Priority::High {
            self.high_lanes.fetch_add(1, Ordering::Relaxed);
        }
        lane
    }

    /// Submits high-class work: at once, and low slices wait while it does.
    fn submit_high(&self, queue: &wgpu::Queue, bufs: Vec<wgpu::CommandBuffer>) -> wgpu::SubmissionIndex {
        if let Ok(mut s) = self.state.lock() {
            s.high_submitting += 1;
        }
        let index = queue.submit(bufs);
        if let Ok(mut s) = self.state.lock() {
            s.high_submitting -= 1;
        }
        self.turn.notify_all();
        index
    }

    /// Notes a composite now and when the next is due (the compositor's loop calls this).
    pub fn composited(&self, next: Instant) {
        if let Ok(mut s) = self.state.lock() {
            s.composited = Some(Instant::now());
            s.next_composite = Some(next);
        }
        self.turn.notify_all();
    }

    /// How long a low slice must wait now to stay out of the guard around composites.
    fn guarded(s: &State, policy: &Policy, now: Instant) -> Option<Duration> {
        if policy.guard.is_zero() {
            return None;
        }
        if let Some(at) = s.composited.filter(|&at| now < at + policy.guard) {
            return Some(at + policy.guard - now);
        }
        let before = policy.slice + Duration::from_millis(1);
        let next = s.next_composite.filter(|&next| now < next && next - now < before)?;
        Some(next - now + policy.guard)
    }

    /// Waits until a low slice may go onto the queue and marks it there; returns whether it
    /// was deferred for want of budget.
    fn admit_low(&self) -> bool {
        let policy = self.policy();
        let budgeted = self.high_lanes.load(Ordering::Relaxed) > 0;
        let cap = policy.low_share * policy.period.as_secs_f64() * 2.0;
        let mut deferred = false;
        let Ok(mut s) = self.state.lock() else { return false };
        loop {
            let now = Instant::now();
            let dt = now.duration_since(s.refilled).as_secs_f64();
            s.refilled = now;
            s.tokens = (s.tokens + dt * policy.low_share).min(cap);
            let over = budgeted && s.tokens <= 0.0;
            let guard = if budgeted { Scheduler::guarded(&s, &policy, now) } else { None };
            if s.high_submitting == 0 && !s.low_busy && !over && guard.is_none() {
                s.low_busy = true;
                return deferred;
            }
            deferred |= over;
            let wait = if over {
                Duration::from_secs_f64((-s.tokens / policy.low_share.max(1e-3)).clamp(1e-4, 0.1))
            } else if let Some(g) = guard {
                g.max(Duration::from_micros(100))
            } else {
                Duration::from_millis(100)
            };
            s = match self.turn.wait_timeout(s, wait) {
                Ok((s, _)) => s,
                Err(_) => return deferred,
            };
        }
    }

    /// Ends a low slice that took `took` to complete.
    fn release_low(&self, took: Duration) {
        if let Ok(mut s) = self.state.lock() {
            s.low_busy = false;
            if self.high_lanes.load(Ordering::Relaxed) > 0 {
                s.tokens -= took.as_secs_f64();
            }
        }
        self.turn.notify_all();
    }
}

#[derive(Default)]
struct Counters {
    swap_us: AtomicU64,
    queue_us: AtomicU64,
    gpu_us: AtomicU64,
    slices: AtomicU64,
    deferred: AtomicU64,
    longest_us: AtomicU64,
}

/// One client's way onto the queue: its class, its newest submission, and where it waited.
pub struct Lane {
    scheduler: Arc<Scheduler>,
    class: AtomicU8,
    /// The client's newest submission.
    last: Mutex<Option<wgpu::SubmissionIndex>>,
    /// Its newest submission at its previous swap.
    frame: Mutex<Option<wgpu::SubmissionIndex>>,
    counters: Counters,
}

impl std::fmt::Debug for Lane {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Lane").field("class", &self.class()).field("waits", &self.waits()).finish()
    }
}

impl Drop for Lane {
    fn drop(&mut self) {
        if self.class() == Priority::High {
            self.scheduler.high_lanes.fetch_sub(1, Ordering::Relaxed);
        }
    }
}

fn micros(d: Duration) -> u64 {
    d.as_micros().min(u128::from(u64::MAX)) as u64
}

impl Lane {
    /// A lane outside any scheduler (tests, tools): normal class.
    pub fn standalone() -> Arc<Lane> {
        Arc::new(Scheduler::default()).lane(Priority::Normal)
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
        let old = self.class();
        if old == class {
            return;
        }
        self.class.store(class as u8, Ordering::Relaxed);
        let high = &self.scheduler.high_lanes;
        if old == Priority::High {
            high.fetch_sub(1, Ordering::Relaxed);
        }
        if class == Priority::High {
            high.fetch_add(1, Ordering::Relaxed);
        }
    }

    /// On the client's session thread: a low-priority client's decoding, translation and
    /// uploads run at a lower CPU priority (nice 10) than everyone else's, so that on a
    /// machine short of cores they yield to the high-priority client's and the compositor's.
    /// (Raising a thread back needs a privilege the daemon does not ask for, so a client
    /// moved out of `low` keeps it.)
    pub fn lower_thread(&self) {
        if !self.scheduler.policy().enabled {
            return;
        }
        #[cfg(target_os = "linux")]
        // SAFETY: gettid and setpriority on the calling thread only read and set its nice value.
        unsafe {
            let tid = libc::gettid();
            if libc::setpriority(libc::PRIO_PROCESS, tid as libc::id_t, LOW_NICE) != 0 {
                warn!("could not lower the session thread's CPU priority: {}", std::io::Error::last_os_error());
            }
        }
    }

    /// Whether this lane's passes are cut into slices.
    pub fn sliced(&self) -> bool {
        self.class() == Priority::Low && self.scheduler.policy().enabled
    }

    /// The GPU time a slice aims at.
    pub fn slice_target(&self) -> Duration {
        self.scheduler.policy().slice
    }

    /// Pieces every sliced pass is cut into regardless of cost, if the policy forces them.
    pub fn forced_pieces(&self) -> Option<usize> {
        self.scheduler.policy().force_pieces
    }

    /// Submits `bufs` (`what` they do, for the log) in the lane's class. High and normal work
    /// go onto the queue at once; low work waits its turn and its budget, and this returns
    /// once it has completed, with the time it took (`None` for the others).
    pub fn submit(&self, gpu: &crate::gpu::Gpu, bufs: Vec<wgpu::CommandBuffer>, what: &str) -> Option<Duration> {
        let policy = self.scheduler.policy();
        let class = if policy.enabled { self.class() } else { Priority::Normal };
        match class {
            Priority::High => {
                let index = self.scheduler.submit_high(&gpu.queue, bufs);
                self.note(index);
                None
            }
            Priority::Normal => {
                let index = gpu.queue.submit(bufs);
                self.note(index);
                None
            }
            Priority::Low => {
                let asked = Instant::now();
                if self.scheduler.admit_low() {
                    self.counters.deferred.fetch_add(1, Ordering::Relaxed);
                }
                self.counters.queue_us.fetch_add(micros(asked.elapsed()), Ordering::Relaxed);
                let start = Instant::now();
                let index = gpu.queue.submit(bufs);
                self.note(index.clone());
                self.wait_for(gpu, index);
                let took = start.elapsed();
                self.scheduler.release_low(took);
                self.counters.slices.fetch_add(1, Ordering::Relaxed);
                self.counters.longest_us.fetch_max(micros(took), Ordering::Relaxed);
                if took > policy.slice * 4 {
                    debug!(ms = took.as_secs_f64() * 1e3, what, "a low-priority slice ran long");
                }
                Some(took)
            }
        }
    }

    fn note(&self, index: wgpu::SubmissionIndex) {
        if let Ok(mut l) = self.last.lock() {
            *l = Some(index);
        }
    }

    /// Waits until `index` has completed, counting the time as GPU wait.
    fn wait_for(&self, gpu: &crate::gpu::Gpu, index: wgpu::SubmissionIndex) {
        let start = Instant::now();
        let poll = wgpu::PollType::Wait { submission_index: Some(index), timeout: Some(GPU_WAIT_LIMIT) };
        if let Err(e) = gpu.device.poll(poll) {
            warn!("waiting for the device: {e}");
        }
        self.counters.gpu_us.fetch_add(micros(start.elapsed()), Ordering::Relaxed);
    }

    /// Waits for everything this client has submitted (readbacks, `glFinish`).
    pub fn wait_idle(&self, gpu: &crate::gpu::Gpu) {
        let last = self.last.lock().ok().and_then(|l| l.clone());
        if let Some(index) = last {
            self.wait_for(gpu, index);
        }
    }

    /// At a swap: waits for the previous frame's work to complete, so that the client has at
    /// most one frame on the queue, and remembers this frame's.
    pub fn frame_boundary(&self, gpu: &crate::gpu::Gpu) {
        let now = self.last.lock().ok().and_then(|l| l.clone());
        let previous = self.frame.lock().ok().and_then(|mut f| std::mem::replace(&mut *f, now));
        if let Some(index) = previous {
            self.wait_for(gpu, index);
        }
    }

    /// Counts time spent blocked in a swap.
    pub fn add_swap_wait(&self, d: Duration) {
        self.counters.swap_us.fetch_add(micros(d), Ordering::Relaxed);
    }

    /// Where this client's frames have waited so far.
    pub fn waits(&self) -> Waits {
        let c = &self.counters;
        Waits {
            swap_us: c.swap_us.load(Ordering::Relaxed),
            queue_us: c.queue_us.load(Ordering::Relaxed),
            gpu_us: c.gpu_us.load(Ordering::Relaxed),
            slices: c.slices.load(Ordering::Relaxed),
            deferred: c.deferred.load(Ordering::Relaxed),
            longest_slice_us: c.longest_us.load(Ordering::Relaxed),
        }
    }
}

/// Submits the compositor's work: high class, whatever the clients do.
pub fn submit_compositor(gpu: &crate::gpu::Gpu, bufs: Vec<wgpu::CommandBuffer>) -> wgpu::SubmissionIndex {
    gpu.scheduler.submit_high(&gpu.queue, bufs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn low_slices_keep_out_of_the_guard_around_composites() {
        let ms = Duration::from_millis;
        let policy = Policy::default();
        let t0 = Instant::now();
        let s = State {
            high_submitting: 0,
            low_busy: false,
            tokens: 0.0,
            refilled: t0,
            composited: Some(t0),
            next_composite: Some(t0 + ms(16)),
        };
        // Just after a composite: wait out the guard (4 ms).
        assert_eq!(Scheduler::guarded(&s, &policy, t0 + ms(1)), Some(ms(3)));
        // Between composites: go.
        assert_eq!(Scheduler::guarded(&s, &policy, t0 + ms(8)), None);
        // Within a slice and a millisecond (3 ms) of the next: wait until after its guard.
        assert_eq!(Scheduler::guarded(&s, &policy, t0 + ms(14)), Some(ms(2) + ms(4)));
        // No guard configured, or no compositor yet: go.
        let off = Policy { guard: Duration::ZERO, ..policy };
        assert_eq!(Scheduler::guarded(&s, &off, t0 + ms(1)), None);
        let idle = State { composited: None, next_composite: None, ..s };
        assert_eq!(Scheduler::guarded(&idle, &policy, t0 + ms(1)), None);
    }
}
