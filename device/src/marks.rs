//! Fence marks: points in a lane's work that a client's fences name ([`crate::Gpu::mark`]),
//! reached once the work before them completes, whether or not anyone asks. A device's
//! [`Watch`] polls the device while marks are outstanding, so that each lane's newest reached
//! mark is published (to the client's segment, [`FenceWord`]) within about a millisecond of the
//! work completing, with no request from the client and no wait that would hold the queue.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, OnceLock, PoisonError, Weak};
use std::thread::JoinHandle;
use std::time::Duration;

use strata_protocol::segment::FenceWord;
use tracing::warn;

/// How often the watch polls the device while marks are outstanding.
const POLL_EVERY: Duration = Duration::from_millis(1);
/// The longest an idle watch sleeps before it looks again (it is woken for new marks).
const IDLE_CHECK: Duration = Duration::from_secs(1);

/// A lane's fence marks: the newest handed out, the newest whose work has completed, and where
/// the latter is published.
#[derive(Default)]
pub(crate) struct Marks {
    /// The newest mark handed out.
    pub(crate) issued: AtomicU64,
    /// The newest mark whose work has completed (the daemon's own count).
    pub(crate) done: AtomicU64,
    /// Orders publications, so that the published value never goes back.
    publishing: Mutex<()>,
    /// Where `done` is published for the client.
    word: OnceLock<FenceWord>,
}

impl Marks {
    /// Records that the work before `mark` has completed, and publishes it.
    pub(crate) fn complete(&self, mark: u64) {
        let _order = self.publishing.lock().unwrap_or_else(PoisonError::into_inner);
        let done = self.done.fetch_max(mark, Ordering::AcqRel).max(mark);
        if let Some(word) = self.word.get() {
            word.publish(done);
        }
    }

    /// Publishes reached marks to `word` from now on (and the newest reached already).
    pub(crate) fn publish_to(&self, word: FenceWord) {
        let _order = self.publishing.lock().unwrap_or_else(PoisonError::into_inner);
        word.publish(self.done.load(Ordering::Acquire));
        let _ = self.word.set(word);
    }

    /// Whether every mark handed out has been reached.
    fn settled(&self) -> bool {
        self.done.load(Ordering::Acquire) >= self.issued.load(Ordering::Acquire)
    }

    /// Reaches every mark handed out (the device was lost: nothing before them will run).
    fn abandon(&self) {
        self.complete(self.issued.load(Ordering::Acquire));
    }
}

/// The lanes of one device with marks outstanding, shared with the thread that polls the
/// device for them.
#[derive(Default)]
struct Outstanding {
    lanes: Mutex<Vec<Weak<Marks>>>,
    wake: Condvar,
    /// Set when the device is dropped: the thread ends.
    closing: AtomicBool,
}

/// One device's watch: its thread starts with the first mark and ends with the device.
#[derive(Default)]
pub(crate) struct Watch {
    outstanding: Arc<Outstanding>,
    thread: Mutex<Option<JoinHandle<()>>>,
}

impl Drop for Watch {
    fn drop(&mut self) {
        {
            let _lanes = self.outstanding.lanes.lock().unwrap_or_else(PoisonError::into_inner);
            self.outstanding.closing.store(true, Ordering::Release);
            self.outstanding.wake.notify_all();
        }
        // Joined, so that its handle on the device is gone when the device is.
        if let Some(thread) = self.thread.lock().unwrap_or_else(PoisonError::into_inner).take() {
            let _ = thread.join();
        }
    }
}

impl Watch {
    /// Watches `marks` until every mark it has handed out is reached, polling `device`.
    pub(crate) fn watch(&self, marks: &Arc<Marks>, device: &wgpu::Device, lost: &Arc<AtomicBool>) {
        {
            let mut lanes = self.outstanding.lanes.lock().unwrap_or_else(PoisonError::into_inner);
            if !lanes.iter().any(|l| l.as_ptr() == Arc::as_ptr(marks)) {
                lanes.push(Arc::downgrade(marks));
            }
            self.outstanding.wake.notify_all();
        }
        let mut thread = self.thread.lock().unwrap_or_else(PoisonError::into_inner);
        if thread.is_none() {
            let (o, device, lost) = (self.outstanding.clone(), device.clone(), lost.clone());
            match std::thread::Builder::new().name("fence-watch".into()).spawn(move || run(&o, &device, &lost)) {
                Ok(t) => *thread = Some(t),
                Err(e) => warn!("starting the fence watch: {e}; fences signal only when waited for"),
            }
        }
    }
}

/// The watch's thread: while any lane has marks outstanding, polls the device every
/// [`POLL_EVERY`] (the marks' callbacks run inside the poll); otherwise sleeps until a mark is
/// handed out. A lost device reaches every mark. Ends when the device's watch is dropped.
fn run(o: &Outstanding, device: &wgpu::Device, lost: &AtomicBool) {
    loop {
        {
            let mut lanes = o.lanes.lock().unwrap_or_else(PoisonError::into_inner);
            if o.closing.load(Ordering::Acquire) {
                return;
            }
            let gone = lost.load(Ordering::Acquire);
            lanes.retain(|l| match l.upgrade() {
                Some(m) if gone => {
                    m.abandon();
                    false
                }
                Some(m) => !m.settled(),
                None => false,
            });
            if lanes.is_empty() {
                let _ = o.wake.wait_timeout(lanes, IDLE_CHECK);
                continue;
            }
        }
        let _ = device.poll(wgpu::PollType::Poll);
        std::thread::sleep(POLL_EVERY);
    }
}
