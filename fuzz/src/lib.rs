//! What the fuzz targets share: running an input on a thread like a client's session thread,
//! and the panic policy for the GLSL ES front end's third-party code.

use std::collections::HashSet;
use std::sync::{Mutex, Once};

/// The stack of a session thread (Rust's default for spawned threads).
pub const SESSION_STACK: usize = 2 << 20;

/// Runs `f` on a thread with a session thread's stack, so that recursion the daemon could not
/// afford fails here too; a panic that escapes `f` is re-raised (and so fails the input).
pub fn on_session_thread(f: impl FnOnce() + Send + 'static) {
    let session = std::thread::Builder::new()
        .name("session".into())
        .stack_size(SESSION_STACK)
        .spawn(f)
        .expect("spawn a session thread");
    if let Err(panic) = session.join() {
        std::panic::resume_unwind(panic);
    }
}

/// Lets panics raised inside third-party crates (glsl-lang, naga) unwind instead of aborting
/// at once, as libFuzzer's hook would: `glsl::compile` and `glsl::link` catch them and fail the
/// compile or link, which is what the daemon does with such a shader. Each such panic site is
/// reported once. A panic in Strata's code or std still aborts, and so does a third-party
/// panic that nothing catches (libFuzzer's harness aborts on any panic that reaches it).
pub fn tolerate_caught_third_party_panics() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let fuzzer_hook = std::panic::take_hook();
        let seen: Mutex<HashSet<String>> = Mutex::new(HashSet::new());
        std::panic::set_hook(Box::new(move |info| {
            let Some(at) = info.location().filter(|l| l.file().contains("/.cargo/registry/")) else {
                return fuzzer_hook(info);
            };
            let site = format!("{}:{}", at.file(), at.line());
            if seen.lock().map(|mut s| s.insert(site.clone())).unwrap_or(false) {
                eprintln!("third-party panic at {site} (unwinding to the front end's catch): {info}");
            }
        }));
    });
}
