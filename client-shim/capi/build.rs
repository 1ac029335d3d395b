//! Binds the library's references to its own entry points locally (`-Bsymbolic`), as system
//! EGL/GL libraries do: `eglGetProcAddress` then returns the shim's functions even when a
//! tracing layer preloaded into the process exports the same names.

fn main() {
    println!("cargo:rustc-cdylib-link-arg=-Wl,-Bsymbolic");
}
