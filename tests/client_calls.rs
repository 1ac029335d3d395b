//! The drop-in library's own work against Mesa, through the C entry points an application
//! calls: each sequence below runs on Mesa's libEGL/libGLESv2 (held to ES 2.0) and on the
//! drop-in library talking to `stratad`, and every observation (each return value, each error,
//! the bytes written to the application's memory and the pixels drawn) must be the same. What
//! the library does itself cannot be compared through the protocol:
//! - `mapping`: `GL_OES_mapbuffer` and `GL_EXT_map_buffer_range`, whose memory is the
//!   library's;
//! - `pack`: where `glReadPixels` puts its rows (`GL_PACK_ALIGNMENT`, `GL_NV_pack_subimage`,
//!   `GL_ANGLE_pack_reverse_row_order`), and how many bytes uploads of each format read;
//! - `surfaceless`: contexts current with no surface (`EGL_KHR_surfaceless_context`,
//!   `GL_OES_surfaceless_context`), which the library passes on;
//! - `robustness`: the reset status and the reads bounded by the application's buffer size
//!   (`GL_EXT_robustness`, `GL_KHR_robustness`);
//! - `draw_buffers`: the counts the library refuses before reading the list, both names of
//!   `glDrawBuffers*`, and a draw into two attachments (`GL_EXT_draw_buffers`,
//!   `GL_NV_draw_buffers`);
//! - `fence_sync`: fences and reusable syncs, which are the library's (`EGL_KHR_fence_sync`,
//!   `EGL_KHR_reusable_sync`, `EGL_KHR_wait_sync`);
//! - `program_binary`: where the library writes a program binary and its length
//!   (`GL_OES_get_program_binary`);
//! - `robust_access`: robust contexts and the draws that read past their arrays
//!   (`EGL_EXT_create_context_robustness`, `GL_KHR_robust_buffer_access_behavior`), which
//!   need a context of their own;
//! - `no_config`: a context made with no config (`EGL_KHR_no_config_context`), which the
//!   library passes on;
//! - `separate`: program pipelines and their programs (`GL_EXT_separate_shader_objects`),
//!   whose one-stage programs the library makes from source;
//! - `border`: the border colour's four values, and the integer forms the library refuses
//!   (`GL_EXT_texture_border_clamp`, `GL_OES_texture_border_clamp`);
//! - `colorspace`: sRGB and linear pbuffers (`EGL_KHR_gl_colorspace`);
//! - `pixel_format_float`: the configs' component type (`EGL_EXT_pixel_format_float`);
//! - `texture_3d`: 3D images, whose slices the library lays out by the unpack state
//!   (`GL_OES_texture_3D`);
//! - `image_shapes`: the one image path's order of checks for every shape, two faults a call;
//! - `debug_callback`: `GL_KHR_debug`'s callback, which the library calls, in a debug context
//!   and in a plain one;
//! - `share_group`: contexts that share objects (`eglCreateContext`'s `share_context`), whose
//!   buffers' contents the library keeps for the whole group;
//! - `base_vertex`: `glDrawElementsBaseVertexEXT` and `...OES`, the entry points themselves
//!   (`GL_EXT_draw_elements_base_vertex`, `GL_OES_draw_elements_base_vertex`), with client
//!   indices the library sends;
//! - `versions`: an ES 2.0 context's answers to ES 3.0's entry points, queries and language.
//!
//! Its own test binary: it points the library at the daemon through the process environment.
//! `tests/client_calls_es3.rs` builds it again as `client_calls_es3`, which runs `es3_core`,
//! `pixel_buffer`, `mapping` and `pack` (pack and unpack buffers, mapped ranges and pixel
//! storage, core in ES 3.0),
//! `es3_clears` (`glClearBuffer*`, `glGetFragDataLocation`), `es3_sync` (sync objects),
//! `es3_xfb` (transform feedback) and `es3_blocks` (active uniforms with blocks) instead, in ES 3.0 contexts on both sides (Mesa held to ES 3.0, the daemon started with
//! `--es3`): Mesa reads its version override once per process, so each version needs a process
//! of its own. [`ES3`] says which.

mod support;

use std::ffi::{c_void, CString};

use libloading::Library;
use support::{Daemon, TempDir};

type Ptr = *mut c_void;

/// Whether this build is `client_calls_es3` (ES 3.0 contexts and sequences), from the test
/// target's crate name.
const ES3: bool = same(env!("CARGO_CRATE_NAME").as_bytes(), b"client_calls_es3");

/// Byte-string equality, for a constant.
const fn same(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}
/// `GLDEBUGPROCKHR`.
type DebugProc = Option<unsafe extern "C" fn(u32, u32, u32, u32, i32, *const i8, *const c_void)>;

const NONE: i32 = 0x3038;
const ARRAY: u32 = 0x8892;
const STATIC_DRAW: u32 = 0x88E4;

#[path = "client_calls/api.rs"]
mod api;
#[path = "client_calls/base_vertex.rs"]
mod base_vertex;
#[path = "client_calls/border.rs"]
mod border;
#[path = "client_calls/colorspace.rs"]
mod colorspace;
#[path = "client_calls/debug_callback.rs"]
mod debug_callback;
#[path = "client_calls/draw_buffers.rs"]
mod draw_buffers;
#[path = "client_calls/egl_image.rs"]
mod egl_image;
#[path = "client_calls/es3_blocks.rs"]
mod es3_blocks;
#[path = "client_calls/es3_clears.rs"]
mod es3_clears;
#[path = "client_calls/es3_core.rs"]
mod es3_core;
#[path = "client_calls/es3_sync.rs"]
mod es3_sync;
#[path = "client_calls/es3_xfb.rs"]
mod es3_xfb;
#[path = "client_calls/fence_sync.rs"]
mod fence_sync;
#[path = "client_calls/image_shapes.rs"]
mod image_shapes;
#[path = "client_calls/mapping.rs"]
mod mapping;
#[path = "client_calls/no_config.rs"]
mod no_config;
#[path = "client_calls/pack.rs"]
mod pack;
#[path = "client_calls/pixel_buffer.rs"]
mod pixel_buffer;
#[path = "client_calls/pixel_format_float.rs"]
mod pixel_format_float;
#[path = "client_calls/program_binary.rs"]
mod program_binary;
#[path = "client_calls/robust_access.rs"]
mod robust_access;
#[path = "client_calls/robustness.rs"]
mod robustness;
#[path = "client_calls/separate.rs"]
mod separate;
#[path = "client_calls/share_group.rs"]
mod share_group;
#[path = "client_calls/surfaceless.rs"]
mod surfaceless;
#[path = "client_calls/texture_3d.rs"]
mod texture_3d;
#[path = "client_calls/timer_query.rs"]
mod timer_query;
#[path = "client_calls/versions.rs"]
mod versions;
use api::Api;

/// The EGL objects the sequences start with: the display, the config, and the pbuffer and
/// context current on it.
#[derive(Clone, Copy)]
struct Binding {
    display: Ptr,
    config: Ptr,
    surface: Ptr,
    context: Ptr,
}

/// What the sequence saw, one line per observation.
struct Log(Vec<String>);

impl Log {
    fn push(&mut self, line: String) {
        self.0.push(line);
    }
}

/// One side's state as the sequence runs.
struct Run {
    gl: Api,
    egl: Binding,
    log: Log,
}

impl Run {
    /// Logs `what` with the error it left.
    fn note(&mut self, what: &str) {
        // SAFETY: a context is current.
        let e = unsafe { (self.gl.get_error)() };
        self.log.push(format!("{what}: error {e:#x}"));
    }

    /// Compiles and uses a program from `vs` and `fs`, attributes 0 and 1 named `pos` and
    /// `color` (the second may be unused).
    fn program(&mut self, vs: &str, fs: &str) -> u32 {
        let gl = self.gl;
        // SAFETY: a context is current; the strings are NUL-terminated.
        unsafe {
            let p = (gl.create_program)();
            for (ty, src) in [(0x8B31, vs), (0x8B30, fs)] {
                let s = (gl.create_shader)(ty);
                let src = CString::new(src).expect("source");
                (gl.shader_source)(s, 1, &src.as_ptr(), std::ptr::null());
                (gl.compile_shader)(s);
                (gl.attach_shader)(p, s);
            }
            for (i, name) in [(0, c"pos"), (1, c"color")] {
                (gl.bind_attrib_location)(p, i, name.as_ptr());
            }
            (gl.link_program)(p);
            (gl.use_program)(p);
            self.note("program");
            p
        }
    }
}

/// An EGL library's `eglGetProcAddress`, by name.
type GetProc<'a> = &'a dyn Fn(&str) -> Ptr;

/// Makes a pbuffer context current on `lib`'s EGL and resolves the GL entry points.
///
/// # Safety
/// `lib` is an EGL library; `display` is what it answers for the display wanted.
unsafe fn current(lib: &Library, display: &dyn Fn(GetProc<'_>) -> Ptr) -> Result<(Api, Binding), String> {
    // SAFETY: EGL's prototypes (egl.h); every out-pointer is valid.
    unsafe {
        let get_proc: unsafe extern "C" fn(*const i8) -> Ptr =
            *lib.get(b"eglGetProcAddress\0").map_err(|e| e.to_string())?;
        let proc = |name: &str| -> Ptr {
            let c = CString::new(name).expect("a name");
            get_proc(c.as_ptr())
        };
        let f = |name: &str| -> Result<Ptr, String> {
            let p = proc(name);
            if p.is_null() {
                Err(format!("{name} unresolved"))
            } else {
                Ok(p)
            }
        };
        let dpy = display(&proc);
        if dpy.is_null() {
            return Err("no display".into());
        }
        let init: unsafe extern "C" fn(Ptr, *mut i32, *mut i32) -> u32 = std::mem::transmute(f("eglInitialize")?);
        let bind: unsafe extern "C" fn(u32) -> u32 = std::mem::transmute(f("eglBindAPI")?);
        let choose: unsafe extern "C" fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32 =
            std::mem::transmute(f("eglChooseConfig")?);
        let pbuffer: unsafe extern "C" fn(Ptr, Ptr, *const i32) -> Ptr =
            std::mem::transmute(f("eglCreatePbufferSurface")?);
        let create: unsafe extern "C" fn(Ptr, Ptr, Ptr, *const i32) -> Ptr =
            std::mem::transmute(f("eglCreateContext")?);
        let make_current: unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32 = std::mem::transmute(f("eglMakeCurrent")?);
        if init(dpy, std::ptr::null_mut(), std::ptr::null_mut()) == 0 || bind(0x30A0) == 0 {
            return Err("eglInitialize".into());
        }
        let attribs = [0x3033, 1, 0x3040, 4, 0x3024, 8, 0x3023, 8, 0x3022, 8, 0x3021, 8, NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        if choose(dpy, attribs.as_ptr(), &mut config, 1, &mut n) == 0 || n < 1 {
            return Err("no RGBA8 pbuffer config".into());
        }
        let surface = pbuffer(dpy, config, [0x3057, 16, 0x3056, 16, NONE].as_ptr());
        let major = if ES3 { 3 } else { 2 };
        let ctx = create(dpy, config, std::ptr::null_mut(), [0x3098, major, NONE].as_ptr());
        if surface.is_null() || ctx.is_null() || make_current(dpy, surface, surface, ctx) == 0 {
            return Err("no current pbuffer context".into());
        }
        Ok((Api::resolve(&proc)?, Binding { display: dpy, config, surface, context: ctx }))
    }
}

/// A vertex stage passing a window-filling quad's texture coordinates (attribute `pos`).
const TEXTURED_VS: &str = "attribute vec2 pos; varying vec2 uv;
    void main() { uv = pos * 0.5 + 0.5; gl_Position = vec4(pos, 0.0, 1.0); }";
/// A fragment stage sampling unit 0's 2D texture there.
const TEXTURED_FS: &str = "precision mediump float; uniform sampler2D s; varying vec2 uv;
    void main() { gl_FragColor = texture2D(s, uv); }";

/// A sequence of calls, by name.
type Sequence = (&'static str, fn(&mut Run));

/// Runs every sequence; what each observed, one line each, under the sequence's name.
fn run_all((gl, egl): (Api, Binding)) -> Vec<String> {
    let sequences: [Sequence; 22] = [
        ("mapping", mapping::sequence),
        ("pack", pack::sequence),
        ("surfaceless", surfaceless::sequence),
        ("robustness", robustness::sequence),
        ("draw_buffers", draw_buffers::sequence),
        ("fence_sync", fence_sync::sequence),
        ("program_binary", program_binary::sequence),
        ("robust_access", robust_access::sequence),
        ("no_config", no_config::sequence),
        ("egl_image", egl_image::sequence),
        ("pixel_buffer", pixel_buffer::sequence),
        ("timer_query", timer_query::sequence),
        ("separate", separate::sequence),
        ("border", border::sequence),
        ("texture_3d", texture_3d::sequence),
        ("image_shapes", image_shapes::sequence),
        ("pixel_format_float", pixel_format_float::sequence),
        ("colorspace", colorspace::sequence),
        ("debug_callback", debug_callback::sequence),
        ("share_group", share_group::sequence),
        ("base_vertex", base_vertex::sequence),
        ("versions", versions::sequence),
    ];
    let es3: [Sequence; 8] = [
        ("es3_core", es3_core::sequence),
        ("pixel_buffer", pixel_buffer::sequence),
        ("mapping", mapping::sequence),
        ("pack", pack::sequence),
        ("es3_clears", es3_clears::sequence),
        ("es3_sync", es3_sync::sequence),
        ("es3_xfb", es3_xfb::sequence),
        ("es3_blocks", es3_blocks::sequence),
    ];
    let chosen = if ES3 { es3.to_vec() } else { sequences.to_vec() };
    let mut lines = Vec::new();
    for (name, sequence) in support::only(chosen, |s| s.0) {
        let mut r = Run { gl, egl, log: Log(Vec::new()) };
        sequence(&mut r);
        lines.extend(r.log.0.into_iter().map(|l| format!("{name}: {l}")));
    }
    lines
}

#[test]
fn client_calls_behave_as_on_mesa() {
    // Mesa held to ES 2.0 (ES 3.0 in `client_calls_es3`), surfaceless.
    // SAFETY: set before this binary's only test loads either library or starts a thread.
    unsafe {
        std::env::set_var("MESA_GLES_VERSION_OVERRIDE", if ES3 { "3.0" } else { "2.0" });
        std::env::remove_var("DISPLAY");
    }
    let dir = support::mesa::lib_dir();
    // SAFETY: the system's EGL; its initialisers are benign.
    let mesa = match unsafe { Library::new(format!("{dir}/libEGL.so.1")) } {
        Ok(l) => l,
        Err(e) if support::oracles_required() => panic!("Mesa's libEGL unavailable: {e}"),
        Err(e) => {
            eprintln!("SKIPPED: Mesa's libEGL unavailable ({e})");
            return;
        }
    };
    // SAFETY: EGL_EXT_platform_base's prototype; the surfaceless platform takes no display.
    let expected = unsafe {
        current(&mesa, &|proc| {
            let gpd = proc("eglGetPlatformDisplayEXT");
            if gpd.is_null() {
                return gpd;
            }
            let gpd: unsafe extern "C" fn(u32, Ptr, *const i32) -> Ptr = std::mem::transmute(gpd);
            gpd(0x31DD, std::ptr::null_mut(), std::ptr::null())
        })
    };
    let expected = match expected {
        Ok(gl) => run_all(gl),
        Err(e) if support::oracles_required() => panic!("Mesa's GLES2 unavailable: {e}"),
        Err(e) => {
            eprintln!("SKIPPED: Mesa's GLES2 unavailable ({e})");
            return;
        }
    };

    let daemon = Daemon::start("client-calls", if ES3 { &["--es3"] } else { &[] });
    // SAFETY: as above; the library reads it at eglInitialize.
    unsafe { std::env::set_var("STRATA_SOCKET", &daemon.socket) };
    let tmp = TempDir::new("client-calls");
    // SAFETY: loading the drop-in library runs no initialisers that need anything from the test.
    let shim =
        unsafe { Library::new(support::shim_dir(&tmp).join("libEGL.so.1")) }.expect("dlopen the drop-in library");
    // SAFETY: eglGetDisplay's prototype.
    let gl = unsafe {
        current(&shim, &|proc| {
            let gd: unsafe extern "C" fn(Ptr) -> Ptr = std::mem::transmute(proc("eglGetDisplay"));
            gd(std::ptr::null_mut())
        })
    }
    .expect("a current context through the drop-in library");
    let actual = run_all(gl);

    let differ: Vec<String> = expected
        .iter()
        .zip(&actual)
        .filter(|(e, a)| e != a)
        .map(|(e, a)| format!("  Mesa:   {e}\n  Strata: {a}"))
        .collect();
    assert!(
        differ.is_empty() && expected.len() == actual.len(),
        "{} of {} observations differ ({} against {} lines):\n{}",
        differ.len(),
        expected.len(),
        expected.len(),
        actual.len(),
        differ.join("\n")
    );
    eprintln!("{} observations agree", expected.len());
    if std::env::var_os("STRATA_SHOW_OBSERVATIONS").is_some() {
        eprintln!("{}", actual.join("\n"));
    }
}
