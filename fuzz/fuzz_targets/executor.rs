//! The GLES executor on the real device (lavapipe where there is no GPU), fed arbitrary
//! well-formed command sequences.
//!
//! Each input is one client: a fresh executor, a prologue (`eglInitialize`, a config the input
//! picks, a small pbuffer, an ES 2 context made current, and, when the input asks, a linked
//! program with a vertex buffer, a texture and attribute 0 set up, so that draws reach the GPU),
//! then up to [`MAX_COMMANDS`] arbitrary commands, then the executor is dropped. The whole case
//! runs on a thread with the session thread's 2 MiB stack. Panics in glsl-lang or naga that the
//! shader compiler and linker catch are reported, not fatal (as in the `glsl` target).
//!
//! Skipped or bounded, to keep one case small and short, never because the daemon would fail:
//! - images (surfaces, textures, renderbuffers, copies, read-backs) larger than
//!   [`MAX_PIXELS`]: the daemon allows 8192×8192, up to 1 GiB for an RGBA32F texture;
//! - `glBufferData` sizes above [`MAX_BUFFER`]: the daemon allows 1 GiB;
//! - draws of more than [`MAX_VERTICES`] vertices: a real GPU draws millions in a moment,
//!   lavapipe takes seconds.
//!
//! No command blocks here: swaps wait for the compositor only when a scene shows the surface,
//! and a lone executor has none.
#![no_main]

use std::sync::{Arc, OnceLock};

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use strata_fuzz::{on_session_thread, tolerate_caught_third_party_panics};
use strata_protocol::{Blob, Command, Slice, Text};
use strata_gles::execute::Executor;
use strata_gles::enums::*;
use strata_gles::GlesExecutor;
use strata_device::Gpu;

/// Commands after the prologue.
const MAX_COMMANDS: usize = 64;
/// Texels of the largest image a command may ask for.
const MAX_PIXELS: i64 = 256 * 256;
/// Bytes of the largest buffer `glBufferData` may allocate.
const MAX_BUFFER: i64 = 1 << 20;
/// Vertices (or indices) of the largest draw.
const MAX_VERTICES: i64 = 1 << 16;

const VS: &str = "attribute vec4 pos; uniform mat4 mvp; varying vec2 uv;
void main() { uv = pos.xy; gl_Position = mvp * pos; gl_PointSize = 4.0; }";
const FS: &str = "precision mediump float; uniform sampler2D tex; uniform vec4 color; varying vec2 uv;
void main() { gl_FragColor = texture2D(tex, uv) * color; }";

/// The device, opened once per process as the daemon does.
fn gpu() -> Arc<Gpu> {
    static GPU: OnceLock<Arc<Gpu>> = OnceLock::new();
    GPU.get_or_init(|| Gpu::open().expect("a Vulkan device (lavapipe: mesa-vulkan-drivers)")).clone()
}

/// Whether a `width`×`height` image is within the target's bound (negative sizes pass: they
/// are the daemon's to refuse).
fn small(width: i32, height: i32) -> bool {
    i64::from(width) * i64::from(height) <= MAX_PIXELS && width <= 8192 && height <= 8192
}

/// Whether `cmd` stays within the bounds listed in the module documentation.
fn bounded(cmd: &Command<'_>) -> bool {
    match cmd {
        Command::CreatePbufferSurface { attribs, .. } => {
            let a = attribs.to_vec();
            // As the daemon reads the list: up to EGL_NONE, the last value of a key wins.
            let get = |key| {
                a.chunks_exact(2).take_while(|p| p[0] != EGL_NONE).filter(|p| p[0] == key).last().map_or(0, |p| p[1])
            };
            small(get(EGL_WIDTH), get(EGL_HEIGHT))
        }
        Command::CreateWindowSurface { width, height, .. }
        | Command::ResizeSurface { width, height, .. }
        | Command::TexImage2D { width, height, .. }
        | Command::TexSubImage2D { width, height, .. }
        | Command::CompressedTexImage2D { width, height, .. }
        | Command::CompressedTexSubImage2D { width, height, .. }
        | Command::CopyTexImage2D { width, height, .. }
        | Command::CopyTexSubImage2D { width, height, .. }
        | Command::RenderbufferStorage { width, height, .. }
        | Command::ReadPixels { width, height, .. } => small(*width, *height),
        Command::BufferData { size, .. } => *size <= MAX_BUFFER,
        Command::DrawArrays { first, count, .. } => i64::from(*first) + i64::from(*count) <= MAX_VERTICES,
        Command::DrawElements { count, .. } | Command::DrawElementsData { count, .. } => {
            i64::from(*count) <= MAX_VERTICES
        }
        _ => true,
    }
}

/// Runs `cmd`, which must succeed: the prologue's commands are all valid.
fn run(x: &mut GlesExecutor, cmd: Command<'_>) {
    let what = format!("{cmd:?}");
    x.execute(cmd).unwrap_or_else(|e| panic!("prologue command {what} failed: {e}"));
}

/// A program drawing with attribute 0, a vertex buffer of one triangle and a 2×2 texture.
fn draw_kit(x: &mut GlesExecutor) {
    run(x, Command::CreateShader { shader_type: VERTEX_SHADER, name: 1 });
    run(x, Command::ShaderSource { shader: 1, source: Text::borrowed(VS) });
    run(x, Command::CompileShader { shader: 1 });
    run(x, Command::CreateShader { shader_type: FRAGMENT_SHADER, name: 2 });
    run(x, Command::ShaderSource { shader: 2, source: Text::borrowed(FS) });
    run(x, Command::CompileShader { shader: 2 });
    run(x, Command::CreateProgram { name: 3 });
    run(x, Command::AttachShader { program: 3, shader: 1 });
    run(x, Command::AttachShader { program: 3, shader: 2 });
    run(x, Command::BindAttribLocation { program: 3, index: 0, name: Text::borrowed("pos") });
    run(x, Command::LinkProgram { program: 3 });
    run(x, Command::UseProgram { program: 3 });
    let tri: [f32; 12] = [-1.0, -1.0, 0.0, 1.0, 1.0, -1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0];
    let bytes: &[u8] = bytemuck::cast_slice(&tri);
    run(x, Command::GenBuffers { names: Slice::new(&[1]) });
    run(x, Command::BindBuffer { target: ARRAY_BUFFER, buffer: 1 });
    run(
        x,
        Command::BufferData {
            target: ARRAY_BUFFER,
            size: bytes.len() as i64,
            data: Some(Blob::borrowed(bytes)),
            usage: STATIC_DRAW,
        },
    );
    run(
        x,
        Command::VertexAttribPointer { index: 0, size: 4, attrib_type: FLOAT, normalized: false, stride: 0, offset: 0 },
    );
    run(x, Command::EnableVertexAttribArray { index: 0 });
    run(x, Command::GenTextures { names: Slice::new(&[1]) });
    run(x, Command::BindTexture { target: TEXTURE_2D, texture: 1 });
    let texels = [255u8; 16];
    run(
        x,
        Command::TexImage2D {
            target: TEXTURE_2D,
            level: 0,
            internalformat: RGBA as i32,
            width: 2,
            height: 2,
            border: 0,
            format: RGBA,
            pixel_type: UNSIGNED_BYTE,
            pixels: Some(Blob::borrowed(&texels)),
        },
    );
}

/// One client: the prologue, then the input's commands.
fn client(data: &[u8]) -> arbitrary::Result<()> {
    let mut u = Unstructured::new(data);
    let config = 1 + u32::from(u.int_in_range(0..=4u8)?);
    let (w, h) = (i32::from(u.int_in_range(1..=64u8)?), i32::from(u.int_in_range(1..=64u8)?));
    let with_program = bool::arbitrary(&mut u)?;
    let mut x = GlesExecutor::new(gpu());
    run(&mut x, Command::GetDisplay { native_display: 0 });
    run(&mut x, Command::Initialize { display: 1 });
    let attribs = [EGL_WIDTH, w, EGL_HEIGHT, h, EGL_NONE];
    let reply = x.execute(Command::CreatePbufferSurface { display: 1, config, attribs: Slice::new(&attribs) });
    let surface = match reply {
        Ok(Some(strata_protocol::Reply::CreatePbufferSurface(Ok(s)))) => s,
        other => panic!("pbuffer: {other:?}"),
    };
    let ctx_attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
    let reply =
        x.execute(Command::CreateContext { display: 1, config, share_context: 0, attribs: Slice::new(&ctx_attribs) });
    let context = match reply {
        Ok(Some(strata_protocol::Reply::CreateContext(Ok(c)))) => c,
        other => panic!("context: {other:?}"),
    };
    run(&mut x, Command::MakeCurrent { display: 1, draw: surface, read: surface, context });
    if with_program {
        draw_kit(&mut x);
    }
    for _ in 0..MAX_COMMANDS {
        if u.is_empty() {
            break;
        }
        let cmd = Command::arbitrary(&mut u)?;
        if bounded(&cmd) {
            // An error here ends a session (the daemon disconnects the client); GL misuse is not one.
            if x.execute(cmd).is_err() {
                break;
            }
        }
    }
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let data = data.to_vec();
    tolerate_caught_third_party_panics();
    on_session_thread(move || {
        let _ = client(&data);
    });
});
