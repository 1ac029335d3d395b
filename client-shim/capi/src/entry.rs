//! How every entry point runs: the `extern "C"` functions that [`entry_points!`] defines set
//! up logging, catch panics (returning a neutral value instead of unwinding into C), and give
//! each module a lookup of its entry points by name for the registry.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

/// The value an entry point returns when it cannot run (a caught panic).
pub(crate) trait Fallback {
    /// The neutral value: zero, false or null.
    fn fallback() -> Self;
}

macro_rules! zero_fallback {
    ($($t:ty),*) => { $( impl Fallback for $t { fn fallback() -> Self { 0 as $t } } )* };
}
zero_fallback!(u8, u32, i32, f32, usize);

impl Fallback for () {
    fn fallback() -> Self {}
}

impl<T> Fallback for *const T {
    fn fallback() -> Self {
        std::ptr::null()
    }
}

impl<T> Fallback for *mut T {
    fn fallback() -> Self {
        std::ptr::null_mut()
    }
}

impl Fallback for Option<unsafe extern "C" fn()> {
    fn fallback() -> Self {
        None
    }
}

/// Runs an entry point's body: never lets a panic unwind into C.
pub(crate) fn guard<R: Fallback>(name: &'static str, body: impl FnOnce() -> R) -> R {
    init_logging();
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(r) => r,
        Err(_) => {
            tracing::error!("internal error (panic) in {name}; returning a neutral value");
            R::fallback()
        }
    }
}

/// Installs a stderr logger (level from `STRATA_LOG`, default `warn`) unless the process has one.
fn init_logging() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let filter = tracing_subscriber::EnvFilter::try_from_env("STRATA_LOG")
            .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("warn"));
        let _ = tracing_subscriber::fmt()
            .with_writer(std::io::stderr)
            .with_env_filter(filter)
            .with_ansi(false)
            .without_time()
            .with_target(false)
            .try_init();
    });
}

/// Defines `extern "C"` entry points whose bodies run inside [`guard`], and a lookup of their
/// addresses by name for the registry (`eglGetProcAddress`).
macro_rules! entry_points {
    ($( $(#[$attr:meta])* fn $name:ident ( $( $arg:ident : $ty:ty ),* $(,)? ) $( -> $ret:ty )? $body:block )*) => {
        $(
            $(#[$attr])*
            #[no_mangle]
            pub unsafe extern "C" fn $name( $( $arg : $ty ),* ) $( -> $ret )? {
                $crate::entry::guard(stringify!($name), move || $body)
            }
        )*

        /// The address of the entry point named `name`, if this module defines it.
        pub(crate) fn lookup(name: &[u8]) -> Option<*const std::ffi::c_void> {
            match name {
                $( n if n == stringify!($name).as_bytes() => Some($name as *const std::ffi::c_void), )*
                _ => None,
            }
        }

        /// The names of the entry points this module defines.
        #[allow(dead_code)]
        pub(crate) const NAMES: &[&str] = &[ $( stringify!($name) ),* ];
    };
}
pub(crate) use entry_points;
