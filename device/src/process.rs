//! Process-wide settings a device depends on: the rasterizer's thread count, read from the
//! environment when an instance is created, and the C allocator's thresholds.

/// The variable llvmpipe (lavapipe's rasterizer) reads its thread count from when an instance
/// enumerates its devices.
pub const RASTERIZER_THREADS: &str = "LP_NUM_THREADS";

/// An environment variable set while a device opens, and restored after.
///
/// `stratad` sets the variable once at start-up, before it starts any thread, so that setting
/// it here only replaces a value and never grows the environment that other threads may read.
pub(crate) struct EnvOverride {
    name: &'static str,
    old: Option<std::ffi::OsString>,
}

impl EnvOverride {
    pub(crate) fn set(name: &'static str, value: &str) -> EnvOverride {
        let old = std::env::var_os(name);
        std::env::set_var(name, value);
        EnvOverride { name, old }
    }
}

impl Drop for EnvOverride {
    fn drop(&mut self) {
        match &self.old {
            Some(v) => std::env::set_var(self.name, v),
            None => std::env::remove_var(self.name),
        }
    }
}

/// Gives [`RASTERIZER_THREADS`] its default value (one thread per core) if the environment
/// does not set it, and keeps the C allocator from returning memory on every free (see
/// [`keep_freed_memory`]). Call it before starting any thread: later devices then only replace
/// its value.
pub fn settle_environment() {
    if std::env::var_os(RASTERIZER_THREADS).is_none() {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        std::env::set_var(RASTERIZER_THREADS, cores.to_string());
    }
    keep_freed_memory();
}

/// Above this much free memory at the top of one of the C allocator's heaps, it is returned
/// to the system (glibc's `M_TRIM_THRESHOLD`; glibc's heaps are at most 64 MiB).
pub const TRIM_THRESHOLD: i32 = 64 << 20;

/// Allocations above this size get a mapping of their own (`M_MMAP_THRESHOLD`, glibc's most).
pub const MMAP_THRESHOLD: i32 = 32 << 20;

/// Sets glibc's trim and mapping thresholds ([`TRIM_THRESHOLD`], [`MMAP_THRESHOLD`]) unless
/// `GLIBC_TUNABLES` sets malloc's own; returns whether it set them. lavapipe allocates and
/// frees its vertex and binning memory on its own threads every draw. With glibc's defaults
/// each free of a thread's heap top gives the pages back, and the next draw faults them in
/// again (zeroed): glmark2's bunny drew at 17 fps through the daemon against 62 with these
/// thresholds (docs/architecture.md, "Devices and frames"). The cost is that the daemon's
/// resident memory stays at its high-water mark per heap rather than shrinking after a peak.
pub fn keep_freed_memory() -> bool {
    let tuned = std::env::var("GLIBC_TUNABLES").is_ok_and(|t| t.contains("glibc.malloc."));
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if !tuned {
        // SAFETY: mallopt with documented parameters; it only changes allocator settings.
        return unsafe {
            libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD) == 1
                && libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD) == 1
        };
    }
    let _ = tuned;
    false
}
