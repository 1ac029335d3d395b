//! Threads' scheduling: each class's nice value, slice and idle policy, applied to the
//! calling thread or to a device's driver threads (which inherit the opening thread's).

use strata_protocol::control::Priority;
use tracing::debug;

/// The nice value the threads of a class's device run at on a CPU rasterizer: high-priority
/// clients and the compositor 0 (or better where the daemon may raise itself), low-priority
/// clients 19, so that on a machine short of cores they take only what the others leave.
pub fn nice_for(class: Priority) -> i32 {
    match class {
        Priority::High => -5,
        Priority::Normal => 0,
        Priority::Low => 19,
    }
}

/// Sets the calling thread's nice value (threads it creates inherit it). Raising priority
/// (a negative value) needs `CAP_SYS_NICE`; without it the thread stays where it is, and this
/// returns the value in force.
pub fn set_thread_nice(nice: i32) -> i32 {
    #[cfg(target_os = "linux")]
    // SAFETY: gettid, setpriority and getpriority on the calling thread only.
    unsafe {
        let tid = libc::gettid() as libc::id_t;
        if libc::setpriority(libc::PRIO_PROCESS, tid, nice) != 0 {
            debug!(nice, "could not set the thread's nice value: {}", std::io::Error::last_os_error());
        }
        *libc::__errno_location() = 0;
        libc::getpriority(libc::PRIO_PROCESS, tid)
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = nice;
        0
    }
}

/// The slice the high class's threads ask the scheduler for (EEVDF's request size; the
/// kernel's default is 0.75 ms times 1 + log2 of the cores, up to 3 ms). A thread with a
/// shorter slice gets an earlier deadline when it wakes, and so preempts a thread with a longer
/// one sooner (Linux 6.12's `PREEMPT_SHORT`): each hop on the instrument cluster's path (the
/// compositor's refresh, the session's reply, the client's next frame) waits less behind work
/// of the same or a lower class that is running. Needs no privilege.
pub const HIGH_SLICE: std::time::Duration = std::time::Duration::from_micros(300);

/// The slice `class`'s threads ask for ([`HIGH_SLICE`] for the high class; the kernel's
/// default otherwise).
pub fn slice_for(class: Priority) -> Option<std::time::Duration> {
    (class == Priority::High).then_some(HIGH_SLICE)
}

/// Sets thread `tid`'s (0: the calling thread) scheduler slice to `slice`, or back to the
/// kernel's default with `None`, keeping its nice value; for threads in `SCHED_OTHER` only.
/// Returns whether the kernel took it (Linux 6.12 or later).
pub fn set_thread_slice(tid: i32, slice: Option<std::time::Duration>) -> bool {
    #[cfg(target_os = "linux")]
    {
        /// `struct sched_attr` as of its first version (48 bytes).
        #[repr(C)]
        struct SchedAttr {
            size: u32,
            policy: u32,
            flags: u64,
            nice: i32,
            priority: u32,
            runtime: u64,
            deadline: u64,
            period: u64,
        }
        // SAFETY: sched_getscheduler, getpriority and sched_setattr on one of this process's
        // threads, with a sched_attr of the size the call is told.
        unsafe {
            let id = if tid == 0 { libc::gettid() } else { tid };
            if libc::sched_getscheduler(id) != libc::SCHED_OTHER {
                return false;
            }
            *libc::__errno_location() = 0;
            let nice = libc::getpriority(libc::PRIO_PROCESS, id as libc::id_t);
            let attr = SchedAttr {
                size: std::mem::size_of::<SchedAttr>() as u32,
                policy: libc::SCHED_OTHER as u32,
                flags: 0,
                nice,
                priority: 0,
                runtime: slice.map_or(0, |s| s.as_nanos().min(u128::from(u64::MAX)) as u64),
                deadline: 0,
                period: 0,
            };
            libc::syscall(libc::SYS_sched_setattr, id, &attr as *const SchedAttr, 0u32) == 0
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (tid, slice);
        false
    }
}

/// Puts the calling thread at `class`'s CPU priority: its nice value ([`nice_for`]) and slice
/// ([`slice_for`]). Returns the nice value in force (see [`set_thread_nice`]).
pub fn set_thread_class(class: Priority) -> i32 {
    let nice = set_thread_nice(nice_for(class));
    set_thread_slice(0, slice_for(class));
    nice
}

/// Puts the calling thread in the real-time class (`SCHED_FIFO`) at `priority` (1–99), so
/// that it runs as soon as it wakes, ahead of every ordinary thread (threads it creates
/// inherit it). Needs `CAP_SYS_NICE` or an `RLIMIT_RTPRIO` of at least `priority`; the error
/// says why it was refused, and the thread then stays where it is.
pub fn set_thread_realtime(priority: i32) -> std::io::Result<()> {
    #[cfg(target_os = "linux")]
    // SAFETY: sched_setscheduler on the calling thread with a valid sched_param.
    unsafe {
        let param = libc::sched_param { sched_priority: priority };
        if libc::sched_setscheduler(0, libc::SCHED_FIFO, &param) != 0 {
            return Err(std::io::Error::last_os_error());
        }
        Ok(())
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = priority;
        Err(std::io::Error::from(std::io::ErrorKind::Unsupported))
    }
}

/// The ids of this process's threads.
pub(crate) fn task_ids() -> std::collections::HashSet<i32> {
    std::fs::read_dir("/proc/self/task")
        .map(|d| d.filter_map(|e| e.ok()?.file_name().to_str()?.parse().ok()).collect())
        .unwrap_or_default()
}

/// Whether thread `tid` is one of the daemon's own (sessions, frame waiters, the runtime's),
/// which may start while a device opens but are not the device's.
pub(crate) fn ours(tid: i32) -> bool {
    let comm = std::fs::read_to_string(format!("/proc/self/task/{tid}/comm")).unwrap_or_default();
    let comm = comm.trim_end();
    comm == "compositor" || ["session-", "frames-", "tokio"].iter().any(|p| comm.starts_with(p))
}

/// Moves thread `tid` (0: the calling thread) to `SCHED_IDLE` when `idle` (Linux): it runs
/// only when no other thread wants the core, and threads it creates inherit that; otherwise
/// back to `SCHED_OTHER`. Needs no privilege within the thread's nice limit.
pub fn set_thread_idle(tid: i32, idle: bool) -> bool {
    #[cfg(target_os = "linux")]
    // SAFETY: sched_setscheduler on one of this process's threads with a valid parameter.
    unsafe {
        let param = libc::sched_param { sched_priority: 0 };
        libc::sched_setscheduler(tid, if idle { libc::SCHED_IDLE } else { libc::SCHED_OTHER }, &param) == 0
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (tid, idle);
        false
    }
}
