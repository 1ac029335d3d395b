//! The frame waiter of one client's device: a thread that waits for each swapped frame's work
//! to complete on that device and then publishes the frame, so that neither the client's
//! session nor the compositor ever waits for it.

use std::sync::{mpsc, Arc};
use std::time::Duration;

use strata_device::Gpu;
use tracing::warn;

/// The longest the frame waiter waits for one frame's work (a wedged device must not wedge it).
const FRAME_WAIT_LIMIT: Duration = Duration::from_secs(5);

type Job = (wgpu::SubmissionIndex, std::time::Instant, Box<dyn FnOnce() + Send>);

/// The frame waiter of one client's device: a thread (started at the first swap) that waits
/// for each swapped frame's work to complete and then publishes it, so that neither the
/// client's session nor the compositor ever waits for it.
pub struct FrameWaiter {
    gpu: Arc<Gpu>,
    tx: Option<mpsc::Sender<Job>>,
    thread: Option<std::thread::JoinHandle<()>>,
    name: String,
}

impl FrameWaiter {
    /// The waiter of `gpu`'s frames; its thread is named `name`.
    pub fn new(gpu: Arc<Gpu>, name: String) -> FrameWaiter {
        FrameWaiter { gpu, tx: None, thread: None, name }
    }

    /// Runs `job` once the work up to `index` has completed on the device.
    pub(crate) fn after(&mut self, index: wgpu::SubmissionIndex, job: Box<dyn FnOnce() + Send>) {
        if self.tx.is_none() {
            let (tx, rx) = mpsc::channel::<Job>();
            let gpu = self.gpu.clone();
            let span = tracing::Span::current();
            match std::thread::Builder::new().name(self.name.clone()).spawn(move || {
                let _span = span.enter();
                let mut last_done = std::time::Instant::now();
                for (index, submitted, job) in rx {
                    let wait = wgpu::PollType::Wait { submission_index: Some(index), timeout: Some(FRAME_WAIT_LIMIT) };
                    match gpu.device.poll(wait) {
                        Ok(_) => {
                            let done = std::time::Instant::now();
                            let busy = done.saturating_duration_since(submitted.max(last_done));
                            gpu.add_waited(busy);
                            last_done = done;
                            job()
                        }
                        Err(e) => warn!("a frame's work did not complete, so it is not shown: {e}"),
                    }
                }
            }) {
                Ok(t) => {
                    self.tx = Some(tx);
                    self.thread = Some(t);
                }
                Err(e) => warn!("could not start the frame waiter ({e}); frames are published at the swap"),
            }
        }
        let job = match &self.tx {
            Some(tx) => match tx.send((index, std::time::Instant::now(), job)) {
                Ok(()) => return,
                Err(mpsc::SendError((_, _, job))) => job,
            },
            None => job,
        };
        // No waiter: wait here.
        let _ = self.gpu.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: Some(FRAME_WAIT_LIMIT) });
        job();
    }
}

impl Drop for FrameWaiter {
    fn drop(&mut self) {
        self.tx = None;
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}
