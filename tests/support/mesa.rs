//! The reference renderer: the system's Mesa GLES2 (llvmpipe), loaded at run time by absolute
//! path and driven through the same `Calls` trait as Strata, so a test program is written once.
//! Surfaceless EGL with a pbuffer needs no X server.
//!
//! Its dispatch is generated from the protocol's command table (`command_table!`), as the
//! daemon's is: every command calls the method of [`Arms`] named like it, so a command without
//! a reference arm does not compile. The arms live by GL family (`state`, `vertices`,
//! `textures`, `framebuffers`, `programs`, `ext`); those Mesa cannot run (EGL, Strata's own
//! calls) say why in `egl` and `ext`.
#![allow(dead_code, non_snake_case, clippy::too_many_arguments)]

use std::collections::HashMap;
use std::ffi::{c_void, CString};

use libloading::Library;
use strata_client::ClientError;
use strata_protocol::{Calls, Command, Reply};

type Ptr = *const c_void;

/// Mesa's libraries in the multiarch directory, by absolute path.
pub fn lib_dir() -> String {
    let triple = match std::env::consts::ARCH {
        "aarch64" => "aarch64-linux-gnu",
        _ => "x86_64-linux-gnu",
    };
    format!("/usr/lib/{triple}")
}

/// `glVertexAttribPointer`'s size, type, normalized and stride.
type PointerParams = (i32, u32, bool, i32);

/// The lines of `names` (a command's list of names) as C strings.
fn c_lines(names: &strata_protocol::Text<'_>) -> Result<Vec<std::ffi::CString>, strata_client::ClientError> {
    names
        .as_str()
        .lines()
        .map(|n| std::ffi::CString::new(n).map_err(|e| strata_client::ClientError::Unsupported(e.to_string())))
        .collect()
}

/// A current Mesa ES2 context on a pbuffer.
pub struct MesaGl {
    _egl: Library,
    gles: Library,
    fns: HashMap<&'static str, Ptr>,
    shaders: HashMap<u32, u32>,
    /// The client's vertex array names and Mesa's.
    vaos: HashMap<u32, u32>,
    /// The client's query names and Mesa's.
    queries: HashMap<u32, u32>,
    /// The client's program pipeline names and Mesa's.
    pipelines: HashMap<u32, u32>,
    /// The client's transform feedback names and Mesa's.
    xfbs: HashMap<u32, u32>,
    /// The client's sampler names and Mesa's.
    samplers: HashMap<u32, u32>,
    /// Per attribute: the last pointer parameters and the client bytes they point at.
    client: HashMap<u32, (PointerParams, Vec<u8>)>,
    display: Ptr,
    pub renderer: String,
}

const EGL_PLATFORM_SURFACELESS_MESA: u32 = 0x31DD;

/// What a `glGet*v` output array is filled with beforehand, to see how many values it wrote.
const INT_SENTINEL: i32 = 0x5EED_F00D;
/// A NaN no query returns.
const FLOAT_SENTINEL: u32 = 0x7FC0_5EED;
/// Neither GL_TRUE nor GL_FALSE.
const BOOL_SENTINEL: u8 = 0xA5;

macro_rules! call {
    ($self:ident, $name:expr, fn($($t:ty),*) -> $r:ty, $($a:expr),*) => {{
        let f = $self.sym($name)?;
        // SAFETY: the symbol is the GLES2 entry point of that name, with that C signature.
        let f: unsafe extern "C" fn($($t),*) -> $r = unsafe { std::mem::transmute::<Ptr, _>(f) };
        unsafe { f($($a),*) }
    }};
}

// After `call!`, which they use; `ext` first, for `ext!`.
#[macro_use]
mod ext;
mod egl;
mod framebuffers;
mod mapping;
mod pipelines;
#[macro_use]
mod programs;
// After `programs`, whose uniform macros it uses.
mod es3;
mod queries;
mod samplers;
mod scalars;
mod state;
mod texture3d;
mod textures;
mod vertices;
mod xfb;

fn unsupported(what: &str) -> ClientError {
    ClientError::Unsupported(format!("the Mesa reference backend does not forward {what}"))
}

impl MesaGl {
    /// Mesa for a test that needs it as its oracle: `None` where it is unavailable (the test
    /// then skips, saying why), unless oracles are required, where the test fails.
    pub fn open_or_skip(width: i32, height: i32) -> Option<MesaGl> {
        match MesaGl::open(width, height) {
            Ok(m) => Some(m),
            Err(e) if super::oracles_required() => panic!("Mesa GLES2 unavailable ({e}) and oracles are required"),
            Err(e) => {
                eprintln!("SKIPPED: Mesa GLES2 unavailable ({e})");
                None
            }
        }
    }

    /// Opens Mesa with an ES 2.0 context, or explains why not.
    pub fn open(width: i32, height: i32) -> Result<MesaGl, String> {
        MesaGl::open_version(width, height, 2)
    }

    /// Opens Mesa with an ES `major`.0 context, or explains why not. Mesa gives a context of
    /// at most the version `MESA_GLES_VERSION_OVERRIDE` holds it to, which it reads once in a
    /// process: a test of ES 3.0 sets it to 3.0 before its first context.
    pub fn open_version(width: i32, height: i32, major: i32) -> Result<MesaGl, String> {
        let dir = lib_dir();
        // SAFETY: loading the system's EGL/GLES libraries; their initialisers are benign.
        let egl = unsafe { Library::new(format!("{dir}/libEGL.so.1")) }.map_err(|e| format!("libEGL: {e}"))?;
        let gles = unsafe { Library::new(format!("{dir}/libGLESv2.so.2")) }.map_err(|e| format!("libGLESv2: {e}"))?;
        unsafe {
            let get_proc: libloading::Symbol<unsafe extern "C" fn(*const i8) -> Ptr> =
                egl.get(b"eglGetProcAddress\0").map_err(|e| e.to_string())?;
            let name = CString::new("eglGetPlatformDisplayEXT").expect("name");
            let gpd = get_proc(name.as_ptr());
            if gpd.is_null() {
                return Err("eglGetPlatformDisplayEXT unavailable".into());
            }
            let gpd: unsafe extern "C" fn(u32, Ptr, *const i32) -> Ptr = std::mem::transmute(gpd);
            let display = gpd(EGL_PLATFORM_SURFACELESS_MESA, std::ptr::null(), std::ptr::null());
            if display.is_null() {
                return Err("no surfaceless display".into());
            }
            let init: libloading::Symbol<unsafe extern "C" fn(Ptr, *mut i32, *mut i32) -> u32> =
                egl.get(b"eglInitialize\0").map_err(|e| e.to_string())?;
            if init(display, std::ptr::null_mut(), std::ptr::null_mut()) == 0 {
                return Err("eglInitialize failed".into());
            }
            let bind: libloading::Symbol<unsafe extern "C" fn(u32) -> u32> =
                egl.get(b"eglBindAPI\0").map_err(|e| e.to_string())?;
            bind(0x30A0);
            let choose: libloading::Symbol<unsafe extern "C" fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32> =
                egl.get(b"eglChooseConfig\0").map_err(|e| e.to_string())?;
            let attribs =
                [0x3033, 1, 0x3040, 4, 0x3024, 8, 0x3023, 8, 0x3022, 8, 0x3021, 8, 0x3025, 24, 0x3026, 8, 0x3038];
            let mut config: Ptr = std::ptr::null();
            let mut n = 0;
            if choose(display, attribs.as_ptr(), &mut config, 1, &mut n) == 0 || n < 1 {
                return Err("no RGBA8 D24S8 pbuffer config".into());
            }
            let pbuf: libloading::Symbol<unsafe extern "C" fn(Ptr, Ptr, *const i32) -> Ptr> =
                egl.get(b"eglCreatePbufferSurface\0").map_err(|e| e.to_string())?;
            let surface = pbuf(display, config, [0x3057, width, 0x3056, height, 0x3038].as_ptr());
            let ctx_fn: libloading::Symbol<unsafe extern "C" fn(Ptr, Ptr, Ptr, *const i32) -> Ptr> =
                egl.get(b"eglCreateContext\0").map_err(|e| e.to_string())?;
            let ctx = ctx_fn(display, config, std::ptr::null(), [0x3098, major, 0x3038].as_ptr());
            let make: libloading::Symbol<unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32> =
                egl.get(b"eglMakeCurrent\0").map_err(|e| e.to_string())?;
            if surface.is_null() || ctx.is_null() || make(display, surface, surface, ctx) == 0 {
                return Err(format!("could not make a pbuffer ES {major}.0 context current"));
            }
        }
        let mut m = MesaGl {
            _egl: egl,
            gles,
            fns: HashMap::new(),
            shaders: HashMap::new(),
            vaos: HashMap::new(),
            queries: HashMap::new(),
            pipelines: HashMap::new(),
            xfbs: HashMap::new(),
            samplers: HashMap::new(),
            client: HashMap::new(),
            display: std::ptr::null(),
            renderer: String::new(),
        };
        let r = m.glGetString(0x1F01).ok().flatten().unwrap_or_default();
        m.renderer = r;
        Ok(m)
    }

    fn sym(&mut self, name: &'static str) -> Result<Ptr, ClientError> {
        if let Some(p) = self.fns.get(name) {
            return Ok(*p);
        }
        let mut z = name.as_bytes().to_vec();
        z.push(0);
        // SAFETY: looking up a symbol; it is only called with its declared signature.
        let p = match unsafe { self.gles.get::<Ptr>(z.as_slice()) } {
            Ok(s) => *s,
            // Extension entry points are not exported: ask EGL for them.
            Err(_) => {
                // SAFETY: eglGetProcAddress takes a NUL-terminated name and returns a pointer.
                let p = unsafe {
                    let get: libloading::Symbol<unsafe extern "C" fn(*const u8) -> Ptr> =
                        self._egl.get(b"eglGetProcAddress\0").map_err(|_| unsupported(name))?;
                    get(z.as_ptr())
                };
                if p.is_null() {
                    return Err(unsupported(name));
                }
                p
            }
        };
        self.fns.insert(name, p);
        Ok(p)
    }

    fn shader(&self, n: u32) -> u32 {
        self.shaders.get(&n).copied().unwrap_or(if n == 0 { 0 } else { u32::MAX - n })
    }

    fn string(&mut self, p: *const u8) -> Option<String> {
        if p.is_null() {
            return None;
        }
        // SAFETY: GL returns NUL-terminated static strings.
        Some(unsafe { std::ffi::CStr::from_ptr(p.cast()) }.to_string_lossy().into_owned())
    }

    fn log(&mut self, obj: u32, program: bool) -> Result<String, ClientError> {
        let mut len = 0i32;
        if program {
            call!(self, "glGetProgramiv", fn(u32, u32, *mut i32) -> (), obj, 0x8B84, &mut len);
        } else {
            call!(self, "glGetShaderiv", fn(u32, u32, *mut i32) -> (), obj, 0x8B84, &mut len);
        }
        let mut buf = vec![0u8; len.max(1) as usize];
        let mut got = 0i32;
        if program {
            call!(
                self,
                "glGetProgramInfoLog",
                fn(u32, i32, *mut i32, *mut u8) -> (),
                obj,
                len.max(1),
                &mut got,
                buf.as_mut_ptr()
            );
        } else {
            call!(
                self,
                "glGetShaderInfoLog",
                fn(u32, i32, *mut i32, *mut u8) -> (),
                obj,
                len.max(1),
                &mut got,
                buf.as_mut_ptr()
            );
        }
        buf.truncate(got.max(0) as usize);
        Ok(String::from_utf8_lossy(&buf).into_owned())
    }
}

/// `s` as a C string (NULs dropped).
fn cstr(s: &str) -> CString {
    CString::new(s.replace('\0', "")).expect("no NUL")
}

/// A NULL-able data argument: `None` becomes NULL.
fn opt_ptr(b: &Option<strata_protocol::Blob<'_>>) -> *const u8 {
    b.as_ref().map_or(std::ptr::null(), |b| b.as_bytes().as_ptr())
}

/// The reference's handlers: one method per command, named like its `Calls` method, over the
/// Mesa context they drive (a type of their own, so that they never shadow `Calls`).
pub(crate) struct Arms<'m>(&'m mut MesaGl);

impl std::ops::Deref for Arms<'_> {
    type Target = MesaGl;
    fn deref(&self) -> &MesaGl {
        self.0
    }
}

impl std::ops::DerefMut for Arms<'_> {
    fn deref_mut(&mut self) -> &mut MesaGl {
        self.0
    }
}

/// Generates `Calls for MesaGl` from the command table: each command to its arm, named by
/// path (`Arms::glX`), so that a missing arm cannot resolve to `Calls::glX` through `Deref`.
macro_rules! mesa_dispatch {
    (
        async { $( $agl:ident [ $($aat:ident),+ ] => $av:ident { $( $af:ident : $aty:ty ),* } ; )* }
        sync { $( $sgl:ident [ $($sat:ident),+ ] => $sv:ident { $( $sf:ident : $sty:ty ),* } -> $ret:ty ; )* }
    ) => {
        impl Calls for MesaGl {
            type Error = ClientError;

            fn send(&mut self, cmd: &Command<'_>) -> Result<(), ClientError> {
                match cmd {
                    $( Command::$av { $( $af ),* } => Arms::$agl(&mut Arms(self), $( $af ),*), )*
                    $( Command::$sv { .. } => Err(unsupported(concat!(stringify!($sgl), " without its reply"))), )*
                }
            }

            fn call(&mut self, cmd: &Command<'_>) -> Result<Reply, ClientError> {
                match cmd {
                    $( Command::$sv { $( $sf ),* } => Arms::$sgl(&mut Arms(self), $( $sf ),*).map(Reply::$sv), )*
                    $( Command::$av { .. } => Err(unsupported(concat!(stringify!($agl), " as a call"))), )*
                }
            }
        }
    };
}

strata_protocol::command_table!(mesa_dispatch);
