//! `GL_OES_mapbuffer` and `GL_EXT_map_buffer_range` against Mesa, through the C entry points an
//! application calls: one sequence of maps, writes, flushes, unmaps, queries and draws runs on
//! Mesa's libEGL/libGLESv2 (held to ES 2.0) and on the drop-in library talking to `stratad`, and
//! every observation (each return value, each error, the mapped bytes, the pointer's alignment,
//! the pixels drawn from mapped vertices) must be the same. Mapping is the drop-in library's
//! work as much as the daemon's, so it is compared here and not through the protocol.
//!
//! Its own test binary: it points the library at the daemon through the process environment.

mod support;

use std::ffi::{c_void, CString};

use libloading::Library;
use support::{Daemon, TempDir};

type Ptr = *mut c_void;

const NONE: i32 = 0x3038;
const ARRAY: u32 = 0x8892;
const WRITE_ONLY: u32 = 0x88B9;
const MAPPED: u32 = 0x88BC;
const ACCESS: u32 = 0x88BB;
const ACCESS_FLAGS: u32 = 0x911F;
const MAP_LENGTH: u32 = 0x9120;
const MAP_OFFSET: u32 = 0x9121;
const MAP_POINTER: u32 = 0x88BD;
const READ: u32 = 0x1;
const WRITE: u32 = 0x2;
const INVALIDATE_RANGE: u32 = 0x4;
const INVALIDATE_BUFFER: u32 = 0x8;
const FLUSH_EXPLICIT: u32 = 0x10;
const STATIC_DRAW: u32 = 0x88E4;

/// Declares [`Api`]: each entry point's field name, C name and prototype.
macro_rules! api {
    ($($field:ident = $name:literal : fn($($arg:ty),*) $(-> $ret:ty)?;)*) => {
        /// The GL entry points the sequence calls, resolved through `eglGetProcAddress`.
        #[derive(Clone, Copy)]
        struct Api {
            $($field: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
        }

        impl Api {
            /// Resolves every entry point; the name of the first that is missing.
            fn resolve(get_proc: GetProc<'_>) -> Result<Api, String> {
                Ok(Api {
                    $($field: {
                        let p = get_proc($name);
                        if p.is_null() {
                            return Err(format!("{} unresolved", $name));
                        }
                        // SAFETY: the entry point has the prototype gl2.h / gl2ext.h gives it.
                        unsafe { std::mem::transmute::<Ptr, unsafe extern "C" fn($($arg),*) $(-> $ret)?>(p) }
                    },)*
                })
            }
        }
    };
}

api! {
    get_error = "glGetError": fn() -> u32;
    gen_buffers = "glGenBuffers": fn(i32, *mut u32);
    bind_buffer = "glBindBuffer": fn(u32, u32);
    buffer_data = "glBufferData": fn(u32, isize, *const c_void, u32);
    buffer_sub_data = "glBufferSubData": fn(u32, isize, isize, *const c_void);
    delete_buffers = "glDeleteBuffers": fn(i32, *const u32);
    get_buffer_parameteriv = "glGetBufferParameteriv": fn(u32, u32, *mut i32);
    map = "glMapBufferOES": fn(u32, u32) -> Ptr;
    unmap = "glUnmapBufferOES": fn(u32) -> u8;
    get_pointer = "glGetBufferPointervOES": fn(u32, u32, *mut Ptr);
    map_range = "glMapBufferRangeEXT": fn(u32, isize, isize, u32) -> Ptr;
    flush_range = "glFlushMappedBufferRangeEXT": fn(u32, isize, isize);
    create_shader = "glCreateShader": fn(u32) -> u32;
    shader_source = "glShaderSource": fn(u32, i32, *const *const i8, *const i32);
    compile_shader = "glCompileShader": fn(u32);
    create_program = "glCreateProgram": fn() -> u32;
    attach_shader = "glAttachShader": fn(u32, u32);
    bind_attrib_location = "glBindAttribLocation": fn(u32, u32, *const i8);
    link_program = "glLinkProgram": fn(u32);
    use_program = "glUseProgram": fn(u32);
    vertex_attrib_pointer = "glVertexAttribPointer": fn(u32, i32, u32, u8, i32, *const c_void);
    enable_vertex_attrib_array = "glEnableVertexAttribArray": fn(u32);
    draw_arrays = "glDrawArrays": fn(u32, i32, i32);
    viewport = "glViewport": fn(i32, i32, i32, i32);
    clear_color = "glClearColor": fn(f32, f32, f32, f32);
    clear = "glClear": fn(u32);
    read_pixels = "glReadPixels": fn(i32, i32, i32, i32, u32, u32, *mut c_void);
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
    log: Log,
}

impl Run {
    /// Logs `what` with the error it left.
    fn note(&mut self, what: &str) {
        // SAFETY: a context is current.
        let e = unsafe { (self.gl.get_error)() };
        self.log.push(format!("{what}: error {e:#x}"));
    }

    /// Logs the buffer parameters of the array buffer.
    fn params(&mut self, when: &str) {
        for (name, pname) in [
            ("mapped", MAPPED),
            ("access", ACCESS),
            ("flags", ACCESS_FLAGS),
            ("length", MAP_LENGTH),
            ("offset", MAP_OFFSET),
        ] {
            let mut v = -7;
            // SAFETY: one GLint out.
            unsafe { (self.gl.get_buffer_parameteriv)(ARRAY, pname, &mut v) };
            self.log.push(format!("{when}: {name} = {v:#x}"));
        }
        self.note(&format!("{when}: parameters"));
    }

    /// Maps `len` bytes at `off` with `access` and logs the result: null or not, the pointer's
    /// alignment less the offset, whether it is the one `glGetBufferPointervOES` answers, and
    /// the bytes (for a map that reads).
    fn map_range(&mut self, off: isize, len: isize, access: u32) -> Ptr {
        // SAFETY: a context is current.
        let p = unsafe { (self.gl.map_range)(ARRAY, off, len, access) };
        self.mapped(&format!("map_range({off}, {len}, {access:#x})"), p, len, access & READ != 0);
        p
    }

    /// Logs a map's result (see [`Run::map_range`]).
    fn mapped(&mut self, what: &str, p: Ptr, len: isize, read: bool) {
        self.note(&format!("{what} null {}", p.is_null()));
        if p.is_null() {
            return;
        }
        let mut q: Ptr = std::ptr::null_mut();
        // SAFETY: one pointer out; a non-null map holds `len` bytes.
        unsafe { (self.gl.get_pointer)(ARRAY, MAP_POINTER, &mut q) };
        self.log.push(format!("  pointer: the same {}, off 64-byte alignment by {}", q == p, p as usize % 64));
        if read {
            // SAFETY: as above.
            let bytes = unsafe { std::slice::from_raw_parts(p as *const u8, len as usize) };
            self.log.push(format!("  bytes {bytes:?}"));
        }
    }

    /// Unmaps the array buffer and logs the answer.
    fn unmap(&mut self, what: &str) {
        // SAFETY: a context is current.
        let r = unsafe { (self.gl.unmap)(ARRAY) };
        self.note(&format!("unmap {what}: {r}"));
    }

    /// Reads the whole array buffer through a map that only reads.
    fn contents(&mut self, what: &str, len: isize) {
        self.log.push(format!("contents {what}:"));
        self.map_range(0, len, READ);
        self.unmap("after reading");
    }
}

/// Compiles the program the draws use: position and colour from attributes 0 and 1.
fn program(gl: &Api) -> u32 {
    let vs = "attribute vec2 pos; attribute vec4 color; varying vec4 v; \
              void main() { v = color; gl_Position = vec4(pos, 0.0, 1.0); }";
    let fs = "precision mediump float; varying vec4 v; void main() { gl_FragColor = v; }";
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
        p
    }
}

/// A quad from `x0` to `x1` across the whole height, in one colour: six vertices of position
/// (2 floats) then colour (4 unsigned bytes), 12 bytes each.
fn quad(x0: f32, x1: f32, rgba: [u8; 4]) -> Vec<u8> {
    let mut v = Vec::new();
    for (x, y) in [(x0, -1.0f32), (x1, -1.0), (x1, 1.0), (x0, -1.0), (x1, 1.0), (x0, 1.0)] {
        v.extend(x.to_ne_bytes());
        v.extend(y.to_ne_bytes());
        v.extend(rgba);
    }
    v
}

/// The sequence both sides run.
fn sequence(r: &mut Run) {
    let gl = r.gl;
    let init: Vec<u8> = (0..64).collect();
    // SAFETY: a context is current; every pointer passed holds what the call reads or writes,
    // and mapped pointers are used only within their mapped length while mapped.
    unsafe {
        let mut b = [0u32; 3];
        (gl.gen_buffers)(3, b.as_mut_ptr());
        // Nothing bound, no data store, accesses and targets that are not allowed.
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map with nothing bound", p, 0, false);
        (gl.bind_buffer)(ARRAY, b[0]);
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map of no data store", p, 0, false);
        (gl.buffer_data)(ARRAY, 64, init.as_ptr().cast(), STATIC_DRAW);
        for (what, target, access) in
            [("read only", ARRAY, 0x88B8), ("read-write", ARRAY, 0x88BA), ("bad target", 0x1234, WRITE_ONLY)]
        {
            let p = (gl.map)(target, access);
            r.mapped(&format!("map {what}"), p, 0, false);
        }
        r.params("before mapping");
        // The whole buffer, written in two places.
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map", p, 64, true);
        let again = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map again", again, 0, false);
        r.params("mapped");
        let mut q: Ptr = std::ptr::null_mut();
        (gl.get_pointer)(ARRAY, 0x1234, &mut q);
        r.note("pointer of a bad name");
        (gl.get_pointer)(0x1234, MAP_POINTER, &mut q);
        r.note("pointer of a bad target");
        (gl.buffer_sub_data)(ARRAY, 0, 4, init.as_ptr().cast());
        r.note("glBufferSubData while mapped");
        if !p.is_null() {
            *p.cast::<u8>().add(3) = 200;
            *p.cast::<u8>().add(60) = 0;
        }
        r.unmap("the map");
        r.unmap("again");
        let u = (gl.unmap)(0x1234);
        r.note(&format!("unmap of a bad target: {u}"));
        let mut q: Ptr = 1 as Ptr;
        (gl.get_pointer)(ARRAY, MAP_POINTER, &mut q);
        r.note(&format!("pointer after unmap: null {}", q.is_null()));
        r.params("unmapped");
        r.contents("after the whole-buffer map", 64);
        // Ranges in error, in Mesa's order of checks.
        for (off, len, access) in [
            (-1, 4, WRITE),
            (0, -1, WRITE),
            (0, 0, WRITE),
            (60, 8, WRITE),
            (0, 4, 0),
            (0, 4, READ | INVALIDATE_RANGE),
            (0, 4, READ | INVALIDATE_BUFFER),
            (0, 4, READ | 0x20),
            (0, 4, READ | FLUSH_EXPLICIT),
            (0, 4, WRITE | 0x40),
            (0, 4, WRITE | 0x80),
            (0, 4, WRITE | 0x100),
            (-1, 0, 0),
            (0, 0, 0x100),
            (60, 8, 0),
            (60, 8, READ | INVALIDATE_RANGE),
        ] {
            r.map_range(off, len, access);
        }
        // Explicit flushes: only the flushed bytes are written.
        let p = r.map_range(4, 8, WRITE | FLUSH_EXPLICIT);
        r.params("mapped for explicit flushes");
        for (off, len) in [(-1, 2), (0, -1), (0, 100), (6, 4), (0, 0)] {
            (gl.flush_range)(ARRAY, off, len);
            r.note(&format!("flush({off}, {len})"));
        }
        if !p.is_null() {
            *p.cast::<u8>() = 99;
            *p.cast::<u8>().add(7) = 98;
            (gl.flush_range)(ARRAY, 0, 1);
            r.note("flush(0, 1)");
            (gl.flush_range)(ARRAY, 7, 1);
            r.note("flush(7, 1)");
        }
        r.unmap("explicitly flushed");
        r.contents("after explicit flushes", 64);
        // A range that reads and writes, then one invalidated and rewritten whole (zeros too).
        let p = r.map_range(24, 8, READ | WRITE);
        r.params("mapped to read and write");
        if !p.is_null() {
            *p.cast::<u8>().add(1) = 7;
        }
        r.unmap("read and written");
        let p = r.map_range(8, 16, WRITE | INVALIDATE_RANGE);
        if !p.is_null() {
            std::ptr::write_bytes(p.cast::<u8>(), 0, 16);
            *p.cast::<u8>().add(15) = 5;
        }
        r.unmap("invalidated");
        r.map_range(0, 4, READ);
        r.params("mapped to read");
        (gl.flush_range)(ARRAY, 0, 1);
        r.note("flush of a map that reads");
        r.unmap("read only");
        r.params("after a map that reads");
        (gl.flush_range)(ARRAY, 0, 1);
        r.note("flush with nothing mapped");
        (gl.flush_range)(0x1234, 0, 1);
        r.note("flush of a bad target");
        r.contents("after the ranges", 64);
        // New contents and deletion end a mapping.
        r.map_range(0, 8, WRITE);
        (gl.buffer_data)(ARRAY, 32, std::ptr::null(), STATIC_DRAW);
        r.note("glBufferData while mapped");
        r.params("after glBufferData");
        r.map_range(0, 8, WRITE);
        (gl.delete_buffers)(1, b.as_ptr());
        r.note("glDeleteBuffers while mapped");
        (gl.bind_buffer)(ARRAY, b[1]);
        (gl.buffer_data)(ARRAY, 0, std::ptr::null(), STATIC_DRAW);
        let p = (gl.map)(ARRAY, WRITE_ONLY);
        r.mapped("map of an empty buffer", p, 0, false);
        r.unmap("never mapped");
        (gl.bind_buffer)(ARRAY, 0);
        let mut q: Ptr = 1 as Ptr;
        (gl.get_pointer)(ARRAY, MAP_POINTER, &mut q);
        r.note(&format!("pointer with nothing bound: untouched {}", q as usize == 1));
        r.map_range(0, 4, WRITE);
        // Vertices written through maps: the first draw keeps the vertices it was given when
        // the second draw's are written over them.
        program(&gl);
        (gl.viewport)(0, 0, 16, 16);
        (gl.clear_color)(0.0, 0.0, 1.0, 1.0);
        (gl.clear)(0x4000);
        (gl.bind_buffer)(ARRAY, b[2]);
        (gl.buffer_data)(ARRAY, 72, std::ptr::null(), 0x88E8);
        (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 12, std::ptr::null());
        (gl.vertex_attrib_pointer)(1, 4, 0x1401, 1, 12, 8 as *const c_void);
        (gl.enable_vertex_attrib_array)(0);
        (gl.enable_vertex_attrib_array)(1);
        for (x0, x1, rgba, access) in
            [(-1.0, 1.0, [255, 0, 0, 255], WRITE | INVALIDATE_BUFFER), (-1.0, 0.0, [0, 255, 0, 255], WRITE)]
        {
            let v = quad(x0, x1, rgba);
            let p = (gl.map_range)(ARRAY, 0, v.len() as isize, access);
            if !p.is_null() {
                std::ptr::copy_nonoverlapping(v.as_ptr(), p.cast::<u8>(), v.len());
            }
            r.unmap("vertices");
            (gl.draw_arrays)(0x0004, 0, 6);
            r.note("draw");
        }
        let mut px = [0u8; 16 * 4];
        (gl.read_pixels)(0, 8, 16, 1, 0x1908, 0x1401, px.as_mut_ptr().cast());
        r.note("read");
        r.log.push(format!("left {:?}, right {:?}", &px[..4], &px[60..]));
    }
}

/// An EGL library's `eglGetProcAddress`, by name.
type GetProc<'a> = &'a dyn Fn(&str) -> Ptr;

/// Makes a pbuffer context current on `lib`'s EGL and resolves the GL entry points.
///
/// # Safety
/// `lib` is an EGL library; `display` is what it answers for the display wanted.
unsafe fn current(lib: &Library, display: &dyn Fn(GetProc<'_>) -> Ptr) -> Result<Api, String> {
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
        let ctx = create(dpy, config, std::ptr::null_mut(), [0x3098, 2, NONE].as_ptr());
        if surface.is_null() || ctx.is_null() || make_current(dpy, surface, surface, ctx) == 0 {
            return Err("no current pbuffer context".into());
        }
        Api::resolve(&proc)
    }
}

#[test]
fn mapped_buffers_behave_as_on_mesa() {
    // Mesa held to ES 2.0, surfaceless.
    // SAFETY: set before this binary's only test loads either library or starts a thread.
    unsafe {
        std::env::set_var("MESA_GLES_VERSION_OVERRIDE", "2.0");
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
        Ok(gl) => {
            let mut r = Run { gl, log: Log(Vec::new()) };
            sequence(&mut r);
            r.log.0
        }
        Err(e) if support::oracles_required() => panic!("Mesa's GLES2 unavailable: {e}"),
        Err(e) => {
            eprintln!("SKIPPED: Mesa's GLES2 unavailable ({e})");
            return;
        }
    };

    let daemon = Daemon::start("map-buffer", &[]);
    // SAFETY: as above; the library reads it at eglInitialize.
    unsafe { std::env::set_var("STRATA_SOCKET", &daemon.socket) };
    let tmp = TempDir::new("map-buffer");
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
    let mut r = Run { gl, log: Log(Vec::new()) };
    sequence(&mut r);
    let actual = r.log.0;

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
