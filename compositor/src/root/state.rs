//! The compositor thread's state: the compositor, the outputs and what is being drawn band by
//! band, shared under one lock with control requests; and how the root surface can fail to start.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use strata_device::Gpu;
use strata_scene::Scene;

use super::bands::{BandOptions, Banded, Cost};
use super::outputs::Output;
use super::pick::Picker;
use crate::{Compositor, CompositorError};

pub(crate) struct Inner {
    pub(crate) compositor: Compositor,
    pub(crate) outputs: Vec<Output>,
    /// The damage count the outputs reflect (`None`: never composited).
    pub(crate) composited: Option<u64>,
    /// A composite in progress band by band over several refreshes.
    pub(crate) bands: Option<Banded>,
    /// The compositor's time per pixel, which decides what is banded and how.
    pub(crate) cost: Cost,
}

/// A service manager's watchdog the compositor loop keeps alive.
#[derive(Debug, Clone, Copy)]
pub struct Watchdog {
    /// How often it must hear from the loop.
    pub period: Duration,
    /// Tells it the loop is alive.
    pub ping: fn(),
}

/// The compositor thread's state, shared with control requests (screenshots, listings).
pub struct Root {
    pub(crate) gpu: Arc<Gpu>,
    pub(crate) scene: Arc<Scene>,
    pub(crate) inner: Mutex<Inner>,
    /// When changes are drawn band by band.
    pub(crate) bands: BandOptions,
    /// Fault injection: the compositor thread is stuck, as in a composite that never returns.
    pub(crate) wedged: std::sync::atomic::AtomicBool,
    /// Input routing's reads of the surfaces under a point (made when first needed).
    pub(crate) picker: Mutex<Option<Picker>>,
    /// Each output's name and rectangle in the output space, fixed at start; read without the
    /// compositor's lock, so that input routing never waits for a composite.
    pub(crate) places: Vec<(String, [i32; 4])>,
    /// The output windows' input, until the daemon takes it to route it.
    pub(crate) window_input: Mutex<Option<std::sync::mpsc::Receiver<strata_protocol::input::InputRequest>>>,
}

/// Why the root surface could not start.
#[derive(Debug, thiserror::Error)]
pub enum RootError {
    /// The compositor cannot run as configured.
    #[error(transparent)]
    Compositor(#[from] CompositorError),
    /// A window output could not open.
    #[error(transparent)]
    Window(#[from] crate::window::WindowError),
}

/// The longest the compositor waits for one composite (a wedged device must not wedge it).
pub(crate) const COMPOSITE_WAIT_LIMIT: Duration = Duration::from_secs(5);

/// Background of every output: opaque black.
pub(crate) const BACKGROUND: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
