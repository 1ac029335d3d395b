//! `stratad serve --vertex-wire half|fixed` against Mesa: an application draws a quad from an
//! interleaved `GL_FLOAT` client-side array through the drop-in libraries (a child process of
//! this test, so that each daemon's option travels through its own handshake), and the image
//! must be Mesa's image of the same program whose array this test converted itself, from the
//! format's definition, to `GL_HALF_FLOAT_OES` (IEEE binary16, round to nearest even) or
//! `GL_FIXED` (16.16, round to nearest). The quad's corners are placed so that the rounding
//! moves two edges across a row or column of pixel centres: Mesa's image of the unconverted
//! floats must differ, so a daemon or library that skips the conversion fails; the other two
//! edges round up, where truncating would cross a row or column. The
//! application's own queries still report `GL_FLOAT` and its stride.
//!
//! Also: a malformed client naming an unknown wire type, or a packed array for a pointer that
//! is not `GL_FLOAT`, gets a GL error and the daemon carries on.
//!
//! Its own test binary: the child points the library at the daemon through its environment.

mod support;

use std::ffi::{c_void, CString};
use std::process::Command;

use strata_client::setup::{egl_context, link_program, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::{Blob, Text};
use support::egl::{load, Ptr};
use support::mesa::MesaGl;
use support::{Daemon, TempDir};

const W: i32 = 32;
const H: i32 = 32;
const FLOAT: u32 = 0x1406;
const FIXED: u32 = 0x140C;
const HALF_FLOAT_OES: u32 = 0x8D61;
const UNSIGNED_BYTE: u32 = 0x1401;
const RGBA: u32 = 0x1908;
const TRIANGLE_STRIP: u32 = 5;
const COLOR_BUFFER_BIT: u32 = 0x4000;
const VERTEX_ATTRIB_ARRAY_STRIDE: u32 = 0x8624;
const VERTEX_ATTRIB_ARRAY_TYPE: u32 = 0x8625;
const INVALID_ENUM: u32 = 0x0500;
const INVALID_OPERATION: u32 = 0x0502;
/// Bytes between the application's vertices: x, y and a float the draw does not read.
const STRIDE: i32 = 12;
/// Where the child writes its image and answers.
const CHILD_OUT: &str = "STRATA_VERTEX_WIRE_OUT";

const VS: &str = "attribute vec2 pos; uniform vec4 map;\n\
                  void main() { gl_Position = vec4(pos * map.xy + map.zw, 0.0, 1.0); }";
const FS: &str = "precision mediump float; void main() { gl_FragColor = vec4(1.0, 0.5, 0.0, 1.0); }";

/// One wire format as the test sees it: where its quantum is one pixel wide.
#[derive(Clone, Copy)]
struct Format {
    name: &'static str,
    gl_type: u32,
    /// Values at `base + k / per_unit` are representable for integer `k` (the quantum is
    /// `1 / per_unit`): binary16 in [1024, 2048) has a spacing of 1; 16.16 one of 2^-16.
    base: f32,
    per_unit: f32,
}

const HALF: Format = Format { name: "half", gl_type: HALF_FLOAT_OES, base: 1024.0, per_unit: 1.0 };
const FIXED_POINT: Format = Format { name: "fixed", gl_type: FIXED, base: 0.0, per_unit: 65536.0 };

impl Format {
    /// The quad's corner coordinates in quanta (x0, y0, x1, y1). Rounding to nearest moves the
    /// left and bottom edges down by 0.4, across a column or row of pixel centres, and the
    /// right and top edges up by 0.4 and 0.35, crossing none (rounding those down instead
    /// would cross one).
    const CORNERS: [f32; 4] = [4.4, 5.4, 27.6, 26.65];

    /// The application's interleaved array (x, y, unused), a triangle strip.
    fn floats(self) -> Vec<f32> {
        let v = |q: f32| self.base + q / self.per_unit;
        let [x0, y0, x1, y1] = Self::CORNERS.map(v);
        vec![x0, y0, 777.0, x1, y0, 777.0, x0, y1, 777.0, x1, y1, 777.0]
    }

    /// `map`: pixel = (value − base) · per_unit + 0.25, so representable values fall a quarter
    /// pixel past a pixel's left/bottom edge and the quad's float corners 0.15 past its centre.
    fn map(self) -> [f32; 4] {
        let s = self.per_unit * 2.0 / W as f32;
        let o = (0.25 - self.base * self.per_unit) * 2.0 / W as f32 - 1.0;
        [s, s, o, o]
    }

    /// The positions (x, y of each vertex) converted from the format's definition, as the
    /// bytes of a tightly packed `gl_type` array.
    fn converted(self) -> Vec<u8> {
        let xy = self.floats().chunks(3).flat_map(|v| [v[0], v[1]]).collect::<Vec<f32>>();
        match self.gl_type {
            // binary16 in [1024, 2048): sign 0, biased exponent 25 (0x6400), and the 10-bit
            // fraction is the distance from 1024 rounded to the nearest integer, ties to even.
            HALF_FLOAT_OES => xy
                .iter()
                .flat_map(|&x| {
                    assert!((1024.0..2047.0).contains(&x));
                    (0x6400u16 + (x - 1024.0).round_ties_even() as u16).to_ne_bytes()
                })
                .collect(),
            _ => xy.iter().flat_map(|&x| ((f64::from(x) * 65536.0).round() as i32).to_ne_bytes()).collect(),
        }
    }
}

/// Mesa's image of the program: the array as floats (`packed` = `None`), or already converted
/// to the format's type. Without `GL_OES_vertex_half_float`, binary16 values go as the floats
/// they stand for, which are the same values.
fn mesa_image(f: Format, packed: bool) -> Vec<u8> {
    let mut gl = MesaGl::open(W, H).expect("Mesa GLES2");
    let p = link_program(&mut gl, (1, 2, 3), VS, FS, &["pos"]).expect("program");
    gl.glUseProgram(p).expect("use");
    let loc = gl.glGetUniformLocation(p, Text::borrowed("map")).expect("location");
    let [a, b, c, d] = f.map();
    gl.glUniform4f(loc, a, b, c, d).expect("uniform");
    gl.glClearColor(0.0, 0.0, 0.0, 1.0).expect("clear colour");
    gl.glClear(COLOR_BUFFER_BIT).expect("clear");
    gl.glBindBuffer(0x8892, 0).expect("unbind");
    let half_ok = gl.glGetString(0x1F03).expect("extensions").is_some_and(|e| e.contains("GL_OES_vertex_half_float"));
    let (ty, stride, bytes): (u32, i32, Vec<u8>) = match (packed, f.gl_type) {
        (false, _) => (FLOAT, STRIDE, f.floats().iter().flat_map(|x| x.to_ne_bytes()).collect()),
        (true, HALF_FLOAT_OES) if !half_ok => {
            eprintln!("Mesa lacks GL_OES_vertex_half_float: binary16 values go as floats");
            let floats =
                f.converted().chunks(2).map(|b| half_to_f32(u16::from_ne_bytes([b[0], b[1]]))).collect::<Vec<_>>();
            (FLOAT, 0, floats.iter().flat_map(|x| x.to_ne_bytes()).collect())
        }
        (true, ty) => (ty, 0, f.converted()),
    };
    gl.glVertexAttribPointer(0, 2, ty, false, stride, 0).expect("pointer");
    gl.glEnableVertexAttribArray(0).expect("enable");
    gl.strataVertexAttribData(0, Blob::borrowed(&bytes)).expect("data");
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4).expect("draw");
    assert_eq!(gl.glGetError().expect("error"), 0, "Mesa GL error");
    gl.glReadPixels(0, 0, W, H, RGBA, UNSIGNED_BYTE).expect("read").0
}

/// A binary16 value in [1024, 2048) as f32.
fn half_to_f32(h: u16) -> f32 {
    1024.0 + f32::from(h - 0x6400)
}

/// Pixels whose channels differ by more than 2/255.
fn differing(a: &[u8], b: &[u8]) -> usize {
    a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p.iter().zip(*q).any(|(x, y)| x.abs_diff(*y) > 2)).count()
}

#[test]
fn float_arrays_cross_the_wire_as_half_and_fixed() {
    if let Err(e) = MesaGl::open(W, H) {
        assert!(!support::oracles_required(), "Mesa GLES2 unavailable ({e}) and oracles are required");
        eprintln!("SKIPPED: Mesa GLES2 unavailable ({e})");
        return;
    }
    for f in [HALF, FIXED_POINT] {
        let daemon = Daemon::start(&format!("vertex-wire-{}", f.name), &["--vertex-wire", f.name]);
        let tmp = TempDir::new(&format!("vertex-wire-child-{}", f.name));
        let out = tmp.0.join("image");
        let status = Command::new(std::env::current_exe().expect("test binary"))
            .args(["child_draws_through_the_shim", "--exact", "--nocapture", "--test-threads=1"])
            .env(CHILD_OUT, &out)
            .env("STRATA_SOCKET", &daemon.socket)
            .env("STRATA_SHIM_DIR", support::shim_dir(&tmp))
            .env_remove("DISPLAY")
            .status()
            .expect("run child");
        assert!(status.success(), "{}: the child failed ({status}); daemon log:\n{}", f.name, daemon.log_text());
        let got = std::fs::read(&out).expect("child output");
        let (image, answers) = got.split_at((W * H * 4) as usize);
        let answers: Vec<i32> = answers.chunks(4).map(|b| i32::from_ne_bytes([b[0], b[1], b[2], b[3]])).collect();
        assert_eq!(answers, [FLOAT as i32, STRIDE, 0], "{}: (type, stride, GL error) the application sees", f.name);

        let expected = mesa_image(f, true);
        let unconverted = mesa_image(f, false);
        let moved = differing(&expected, &unconverted);
        assert!(moved >= 40, "{}: the geometry must move edges ({moved} pixels differ)", f.name);
        assert_eq!(differing(image, &expected), 0, "{}: differs from Mesa's image of the converted array", f.name);
        assert!(differing(image, &unconverted) >= 40, "{}: the array was not converted", f.name);

        malformed_wire_types_are_gl_errors(&daemon);
        drop(daemon);
    }
}

/// A client naming an unknown wire type gets `GL_INVALID_ENUM`; one sending a packed array
/// for a pointer that is not `GL_FLOAT`, `GL_INVALID_OPERATION`; the daemon stays up.
fn malformed_wire_types_are_gl_errors(daemon: &Daemon) {
    let opts = ConnectOptions { socket: daemon.socket.clone(), name: "malformed".into(), ..Default::default() };
    let mut c = Connection::connect(&opts).expect("connect");
    egl_context(&mut c, 0, 0, SurfaceKind::Pbuffer { width: 8, height: 8 }).expect("context");
    c.glBindBuffer(0x8892, 0).expect("unbind");
    c.glVertexAttribPointer(0, 2, FLOAT, false, 0, 0).expect("pointer");
    c.strataVertexAttribDataPacked(0, 0x1234, Blob::borrowed(&[0u8; 16])).expect("send");
    assert_eq!(c.glGetError().expect("error"), INVALID_ENUM, "unknown wire type");
    c.glVertexAttribPointer(1, 2, UNSIGNED_BYTE, false, 0, 0).expect("pointer");
    c.strataVertexAttribDataPacked(1, HALF_FLOAT_OES, Blob::borrowed(&[0u8; 8])).expect("send");
    assert_eq!(c.glGetError().expect("error"), INVALID_OPERATION, "packed data for a byte array");
    c.strataVertexAttribDataPacked(99, HALF_FLOAT_OES, Blob::borrowed(&[0u8; 8])).expect("send");
    assert_eq!(c.glGetError().expect("error"), 0x0501, "attribute index out of range");
    assert_eq!(c.glGetVertexAttribiv(0, VERTEX_ATTRIB_ARRAY_TYPE).expect("query"), [FLOAT as i32]);
    c.glFinish().expect("the daemon is still serving");
}

/// The application: runs only as the child of the test above (with `STRATA_VERTEX_WIRE_OUT`),
/// drawing through the drop-in libraries and writing its pixels, then the attribute's type and
/// stride as it queries them and `glGetError`.
#[test]
fn child_draws_through_the_shim() {
    let Some(out) = std::env::var_os(CHILD_OUT) else { return };
    let dir = std::path::PathBuf::from(std::env::var_os("STRATA_SHIM_DIR").expect("shim dir"));
    let f = [HALF, FIXED_POINT]
        .into_iter()
        .find(|f| out.to_string_lossy().contains(&format!("child-{}", f.name)))
        .expect("format from the output path");
    // SAFETY: loading the shim runs no initialisers that need anything from the test.
    let lib = unsafe { libloading::Library::new(dir.join("libEGL.so.1")) }.expect("dlopen");
    let egl = load(&lib);
    let gles = Gles::load(&lib);
    let mut result = vec![0u8; (W * H * 4) as usize];
    // SAFETY: EGL/GLES calls with the arguments their headers describe; every pointer passed
    // is valid for what the call reads or writes, and `data` outlives the draw.
    unsafe {
        let dpy = (egl.get_display)(std::ptr::null_mut());
        assert_eq!((egl.initialize)(dpy, std::ptr::null_mut(), std::ptr::null_mut()), 1, "eglInitialize");
        let attribs = [0x3033, 0x0001, 0x3040, 0x0004, 0x3038]; // PBUFFER_BIT, OPENGL_ES2_BIT
        let (mut config, mut n): (Ptr, i32) = (std::ptr::null_mut(), 0);
        assert_eq!((egl.choose_config)(dpy, attribs.as_ptr(), &mut config, 1, &mut n), 1, "eglChooseConfig");
        let surface = (egl.create_pbuffer)(dpy, config, [0x3057, W, 0x3056, H, 0x3038].as_ptr());
        let ctx = (egl.create_context)(dpy, config, std::ptr::null_mut(), [0x3098, 2, 0x3038].as_ptr());
        assert_eq!((egl.make_current)(dpy, surface, surface, ctx), 1, "eglMakeCurrent");
        let program = gles.program();
        (gles.use_program)(program);
        let name = CString::new("map").expect("name");
        let [a, b, c, d] = f.map();
        (gles.uniform4f)((gles.uniform_location)(program, name.as_ptr()), a, b, c, d);
        (egl.clear_color)(0.0, 0.0, 0.0, 1.0);
        (egl.clear)(COLOR_BUFFER_BIT);
        let data = f.floats();
        (gles.attrib_pointer)(0, 2, FLOAT, 0, STRIDE, data.as_ptr().cast());
        (gles.enable_attrib)(0);
        (gles.draw_arrays)(TRIANGLE_STRIP, 0, 4);
        (egl.read_pixels)(0, 0, W, H, RGBA, UNSIGNED_BYTE, result.as_mut_ptr().cast());
        let (mut ty, mut stride) = (0, 0);
        (gles.get_attrib_iv)(0, VERTEX_ATTRIB_ARRAY_TYPE, &mut ty);
        (gles.get_attrib_iv)(0, VERTEX_ATTRIB_ARRAY_STRIDE, &mut stride);
        let error = (egl.gl_get_error)() as i32;
        for v in [ty, stride, error] {
            result.extend_from_slice(&v.to_ne_bytes());
        }
    }
    std::fs::write(out, result).expect("write output");
    // The library's thread-local state is torn down when this thread exits: keep it loaded.
    std::mem::forget(lib);
}

/// The GLES entry points the child needs beyond [`support::egl::Egl`].
struct Gles {
    create_shader: unsafe extern "C" fn(u32) -> u32,
    shader_source: unsafe extern "C" fn(u32, i32, *const *const i8, *const i32),
    compile_shader: unsafe extern "C" fn(u32),
    create_program: unsafe extern "C" fn() -> u32,
    attach_shader: unsafe extern "C" fn(u32, u32),
    bind_attrib: unsafe extern "C" fn(u32, u32, *const i8),
    link_program: unsafe extern "C" fn(u32),
    use_program: unsafe extern "C" fn(u32),
    uniform_location: unsafe extern "C" fn(u32, *const i8) -> i32,
    uniform4f: unsafe extern "C" fn(i32, f32, f32, f32, f32),
    attrib_pointer: unsafe extern "C" fn(u32, i32, u32, u8, i32, *const c_void),
    enable_attrib: unsafe extern "C" fn(u32),
    draw_arrays: unsafe extern "C" fn(u32, i32, i32),
    get_attrib_iv: unsafe extern "C" fn(u32, u32, *mut i32),
}

impl Gles {
    fn load(lib: &libloading::Library) -> Gles {
        // SAFETY: each symbol is declared with its C prototype from gl2.h.
        unsafe {
            Gles {
                create_shader: support::egl::sym(lib, b"glCreateShader"),
                shader_source: support::egl::sym(lib, b"glShaderSource"),
                compile_shader: support::egl::sym(lib, b"glCompileShader"),
                create_program: support::egl::sym(lib, b"glCreateProgram"),
                attach_shader: support::egl::sym(lib, b"glAttachShader"),
                bind_attrib: support::egl::sym(lib, b"glBindAttribLocation"),
                link_program: support::egl::sym(lib, b"glLinkProgram"),
                use_program: support::egl::sym(lib, b"glUseProgram"),
                uniform_location: support::egl::sym(lib, b"glGetUniformLocation"),
                uniform4f: support::egl::sym(lib, b"glUniform4f"),
                attrib_pointer: support::egl::sym(lib, b"glVertexAttribPointer"),
                enable_attrib: support::egl::sym(lib, b"glEnableVertexAttribArray"),
                draw_arrays: support::egl::sym(lib, b"glDrawArrays"),
                get_attrib_iv: support::egl::sym(lib, b"glGetVertexAttribiv"),
            }
        }
    }

    /// Compiles and links [`VS`] and [`FS`] with `pos` at location 0.
    ///
    /// # Safety
    /// A context must be current.
    unsafe fn program(&self) -> u32 {
        // SAFETY: see the function's contract; the sources outlive the calls.
        unsafe {
            let p = (self.create_program)();
            for (kind, src) in [(0x8B31, VS), (0x8B30, FS)] {
                let s = (self.create_shader)(kind);
                let src = CString::new(src).expect("source");
                (self.shader_source)(s, 1, &src.as_ptr(), std::ptr::null());
                (self.compile_shader)(s);
                (self.attach_shader)(p, s);
            }
            let pos = CString::new("pos").expect("name");
            (self.bind_attrib)(p, 0, pos.as_ptr());
            (self.link_program)(p);
            p
        }
    }
}
