//! Priority classes. Each client renders on a device of its own, so priority is the
//! platform's job: the class decides the nice value (and, for `low`, the idle scheduling
//! policy) of the client's session thread and of the driver threads of its device, which
//! inherit it from the thread that opens the device, and the queue's global priority where a
//! GPU offers one (`strata_device::DeviceOptions`). Nothing is cut into slices or held back in the daemon: a
//! low-priority client's work runs whole, on what the others leave.
//! Each client's submissions go through its `strata_device::Lane`.

use strata_protocol::control::Priority;

/// `stratad serve`'s priority options.
#[derive(Debug, Clone, clap::Args)]
pub struct ScheduleArgs {
    /// The class of clients the configuration does not name and whose EGL contexts do not ask
    /// for one: high, normal or low.
    #[arg(long, default_value = "normal")]
    pub default_priority: Priority,
}
