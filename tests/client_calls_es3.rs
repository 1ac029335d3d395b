//! `tests/client_calls.rs` built for OpenGL ES 3.0 (see its `ES3`, which this target's name
//! sets): its ES 3.0 sequences in ES 3.0 contexts, against Mesa held to ES 3.0, in a process of
//! their own.

#[path = "client_calls.rs"]
mod client_calls;
