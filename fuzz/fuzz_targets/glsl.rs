//! The GLSL ES 1.00 translator as `glCompileShader` runs it: preprocessing and parsing with
//! glsl-lang, the ES checks, the rewrite to Vulkan-flavoured GLSL 450 and naga's parse and
//! validation of the stage against a stand-in for the other one.
//!
//! Input: one byte choosing the stage (even: vertex, odd: fragment), then the source (invalid
//! UTF-8 replaced, as a client's `Text` cannot carry it). Each compile runs on a thread with
//! the session thread's 2 MiB stack, where the daemon compiles. Panics in glsl-lang or naga
//! that `compile` catches (the shader then fails to compile) are reported, not fatal; see
//! `strata_fuzz::tolerate_caught_third_party_panics`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use strata_fuzz::{on_session_thread, tolerate_caught_third_party_panics};
use strata_gles::glsl::{compile, Stage};

fuzz_target!(|data: &[u8]| {
    let Some((&stage, source)) = data.split_first() else { return };
    let stage = if stage % 2 == 0 { Stage::Vertex } else { Stage::Fragment };
    let source = String::from_utf8_lossy(source).into_owned();
    tolerate_caught_third_party_panics();
    on_session_thread(move || {
        if let Ok(shader) = compile(stage, &source) {
            assert_eq!(shader.stage, stage);
        }
    });
});
