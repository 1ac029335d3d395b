//! The reference renderer: the system's Mesa GLES2 (llvmpipe), loaded at run time by absolute
//! path and driven through the same `Calls` trait as Strata, so a test program is written once.
//! Surfaceless EGL with a pbuffer needs no X server.
#![allow(dead_code, non_snake_case)]

use std::collections::HashMap;
use std::ffi::{c_void, CString};

use libloading::Library;
use strata_client::ClientError;
use strata_protocol::{ActiveVariable, Bytes, Calls, Command, Reply};

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

/// A current Mesa ES2 context on a pbuffer.
pub struct MesaGl {
    _egl: Library,
    gles: Library,
    fns: HashMap<&'static str, Ptr>,
    shaders: HashMap<u32, u32>,
    /// The client's vertex array names and Mesa's.
    vaos: HashMap<u32, u32>,
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
    ($self:ident, $name:literal, fn($($t:ty),*) -> $r:ty, $($a:expr),*) => {{
        let f = $self.sym($name)?;
        // SAFETY: the symbol is the GLES2 entry point of that name, with that C signature.
        let f: unsafe extern "C" fn($($t),*) -> $r = unsafe { std::mem::transmute::<Ptr, _>(f) };
        unsafe { f($($a),*) }
    }};
}

// After `call!`, which it uses.
mod ext;

fn unsupported(what: &str) -> ClientError {
    ClientError::Unsupported(format!("the Mesa reference backend does not forward {what}"))
}

impl MesaGl {
    /// Opens Mesa, or explains why not.
    pub fn open(width: i32, height: i32) -> Result<MesaGl, String> {
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
            let ctx = ctx_fn(display, config, std::ptr::null(), [0x3098, 2, 0x3038].as_ptr());
            let make: libloading::Symbol<unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32> =
                egl.get(b"eglMakeCurrent\0").map_err(|e| e.to_string())?;
            if surface.is_null() || ctx.is_null() || make(display, surface, surface, ctx) == 0 {
                return Err("could not make a pbuffer ES2 context current".into());
            }
        }
        let mut m = MesaGl {
            _egl: egl,
            gles,
            fns: HashMap::new(),
            shaders: HashMap::new(),
            vaos: HashMap::new(),
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

fn cstr(s: &str) -> CString {
    CString::new(s.replace('\0', "")).expect("no NUL")
}

fn opt_ptr(b: &Option<strata_protocol::Blob<'_>>) -> *const u8 {
    b.as_ref().map_or(std::ptr::null(), |b| b.as_bytes().as_ptr())
}

impl Calls for MesaGl {
    type Error = ClientError;

    fn send(&mut self, cmd: &Command<'_>) -> Result<(), ClientError> {
        use Command as C;
        match cmd {
            C::ActiveTexture { texture } => call!(self, "glActiveTexture", fn(u32) -> (), *texture),
            C::AttachShader { program, shader } => {
                let (p, s) = (self.shader(*program), self.shader(*shader));
                call!(self, "glAttachShader", fn(u32, u32) -> (), p, s)
            }
            C::DetachShader { program, shader } => {
                let (p, s) = (self.shader(*program), self.shader(*shader));
                call!(self, "glDetachShader", fn(u32, u32) -> (), p, s)
            }
            C::BindAttribLocation { program, index, name } => {
                let p = self.shader(*program);
                let n = cstr(name.as_str());
                call!(self, "glBindAttribLocation", fn(u32, u32, *const i8) -> (), p, *index, n.as_ptr())
            }
            C::BindBuffer { target, buffer } => call!(self, "glBindBuffer", fn(u32, u32) -> (), *target, *buffer),
            C::BindFramebuffer { target, framebuffer } => {
                call!(self, "glBindFramebuffer", fn(u32, u32) -> (), *target, *framebuffer)
            }
            C::BindRenderbuffer { target, renderbuffer } => {
                call!(self, "glBindRenderbuffer", fn(u32, u32) -> (), *target, *renderbuffer)
            }
            C::BindTexture { target, texture } => call!(self, "glBindTexture", fn(u32, u32) -> (), *target, *texture),
            C::BlendColor { red, green, blue, alpha } => {
                call!(self, "glBlendColor", fn(f32, f32, f32, f32) -> (), *red, *green, *blue, *alpha)
            }
            C::BlendEquation { mode } => call!(self, "glBlendEquation", fn(u32) -> (), *mode),
            C::BlendEquationSeparate { mode_rgb, mode_alpha } => {
                call!(self, "glBlendEquationSeparate", fn(u32, u32) -> (), *mode_rgb, *mode_alpha)
            }
            C::BlendFunc { sfactor, dfactor } => call!(self, "glBlendFunc", fn(u32, u32) -> (), *sfactor, *dfactor),
            C::BlendFuncSeparate { src_rgb, dst_rgb, src_alpha, dst_alpha } => {
                call!(
                    self,
                    "glBlendFuncSeparate",
                    fn(u32, u32, u32, u32) -> (),
                    *src_rgb,
                    *dst_rgb,
                    *src_alpha,
                    *dst_alpha
                )
            }
            C::BufferData { target, size, data, usage } => {
                let p = opt_ptr(data);
                call!(self, "glBufferData", fn(u32, isize, *const u8, u32) -> (), *target, *size as isize, p, *usage)
            }
            C::BufferSubData { target, offset, data } => {
                call!(
                    self,
                    "glBufferSubData",
                    fn(u32, isize, isize, *const u8) -> (),
                    *target,
                    *offset as isize,
                    data.len() as isize,
                    data.as_bytes().as_ptr()
                )
            }
            C::Clear { mask } => call!(self, "glClear", fn(u32) -> (), *mask),
            C::ClearColor { red, green, blue, alpha } => {
                call!(self, "glClearColor", fn(f32, f32, f32, f32) -> (), *red, *green, *blue, *alpha)
            }
            C::ClearDepthf { depth } => call!(self, "glClearDepthf", fn(f32) -> (), *depth),
            C::ClearStencil { s } => call!(self, "glClearStencil", fn(i32) -> (), *s),
            C::ColorMask { red, green, blue, alpha } => {
                call!(
                    self,
                    "glColorMask",
                    fn(u8, u8, u8, u8) -> (),
                    u8::from(*red),
                    u8::from(*green),
                    u8::from(*blue),
                    u8::from(*alpha)
                )
            }
            C::CompileShader { shader } => {
                let s = self.shader(*shader);
                call!(self, "glCompileShader", fn(u32) -> (), s)
            }
            C::CopyTexImage2D { target, level, internalformat, x, y, width, height, border } => call!(
                self,
                "glCopyTexImage2D",
                fn(u32, i32, u32, i32, i32, i32, i32, i32) -> (),
                *target,
                *level,
                *internalformat,
                *x,
                *y,
                *width,
                *height,
                *border
            ),
            C::CopyTexSubImage2D { target, level, xoffset, yoffset, x, y, width, height } => call!(
                self,
                "glCopyTexSubImage2D",
                fn(u32, i32, i32, i32, i32, i32, i32, i32) -> (),
                *target,
                *level,
                *xoffset,
                *yoffset,
                *x,
                *y,
                *width,
                *height
            ),
            C::CreateProgram { name } => {
                let real = call!(self, "glCreateProgram", fn() -> u32,);
                self.shaders.insert(*name, real);
            }
            C::CreateShader { shader_type, name } => {
                let real = call!(self, "glCreateShader", fn(u32) -> u32, *shader_type);
                self.shaders.insert(*name, real);
            }
            C::CullFace { mode } => call!(self, "glCullFace", fn(u32) -> (), *mode),
            C::DeleteBuffers { names } => {
                let v = names.to_vec();
                call!(self, "glDeleteBuffers", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr())
            }
            C::DeleteTextures { names } => {
                let v = names.to_vec();
                call!(self, "glDeleteTextures", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr())
            }
            C::DeleteFramebuffers { names } => {
                let v = names.to_vec();
                call!(self, "glDeleteFramebuffers", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr())
            }
            C::DeleteRenderbuffers { names } => {
                let v = names.to_vec();
                call!(self, "glDeleteRenderbuffers", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr())
            }
            C::DeleteProgram { program } => {
                let p = self.shader(*program);
                call!(self, "glDeleteProgram", fn(u32) -> (), p)
            }
            C::DeleteShader { shader } => {
                let s = self.shader(*shader);
                call!(self, "glDeleteShader", fn(u32) -> (), s)
            }
            C::DepthFunc { func } => call!(self, "glDepthFunc", fn(u32) -> (), *func),
            C::DepthMask { flag } => call!(self, "glDepthMask", fn(u8) -> (), u8::from(*flag)),
            C::DepthRangef { near, far } => call!(self, "glDepthRangef", fn(f32, f32) -> (), *near, *far),
            C::Disable { cap } => call!(self, "glDisable", fn(u32) -> (), *cap),
            C::DisableVertexAttribArray { index } => call!(self, "glDisableVertexAttribArray", fn(u32) -> (), *index),
            C::DrawArrays { mode, first, count } => {
                call!(self, "glDrawArrays", fn(u32, i32, i32) -> (), *mode, *first, *count)
            }
            C::DrawElements { mode, count, index_type, offset } => {
                call!(
                    self,
                    "glDrawElements",
                    fn(u32, i32, u32, usize) -> (),
                    *mode,
                    *count,
                    *index_type,
                    *offset as usize
                )
            }
            C::Enable { cap } => call!(self, "glEnable", fn(u32) -> (), *cap),
            C::EnableVertexAttribArray { index } => call!(self, "glEnableVertexAttribArray", fn(u32) -> (), *index),
            C::Flush {} => call!(self, "glFlush", fn() -> (),),
            C::FramebufferRenderbuffer { target, attachment, renderbuffertarget, renderbuffer } => call!(
                self,
                "glFramebufferRenderbuffer",
                fn(u32, u32, u32, u32) -> (),
                *target,
                *attachment,
                *renderbuffertarget,
                *renderbuffer
            ),
            C::FramebufferTexture2D { target, attachment, textarget, texture, level } => call!(
                self,
                "glFramebufferTexture2D",
                fn(u32, u32, u32, u32, i32) -> (),
                *target,
                *attachment,
                *textarget,
                *texture,
                *level
            ),
            C::FrontFace { mode } => call!(self, "glFrontFace", fn(u32) -> (), *mode),
            // Names are the client's own: binding an unused name creates the object in ES 2.0.
            C::GenBuffers { .. } | C::GenTextures { .. } | C::GenFramebuffers { .. } | C::GenRenderbuffers { .. } => {}
            C::GenerateMipmap { target } => call!(self, "glGenerateMipmap", fn(u32) -> (), *target),
            C::Hint { target, mode } => call!(self, "glHint", fn(u32, u32) -> (), *target, *mode),
            C::LineWidth { width } => call!(self, "glLineWidth", fn(f32) -> (), *width),
            C::LinkProgram { program } => {
                let p = self.shader(*program);
                call!(self, "glLinkProgram", fn(u32) -> (), p)
            }
            C::PixelStorei { pname, param } => call!(self, "glPixelStorei", fn(u32, i32) -> (), *pname, *param),
            C::PolygonOffset { factor, units } => call!(self, "glPolygonOffset", fn(f32, f32) -> (), *factor, *units),
            C::RenderbufferStorage { target, internalformat, width, height } => {
                call!(
                    self,
                    "glRenderbufferStorage",
                    fn(u32, u32, i32, i32) -> (),
                    *target,
                    *internalformat,
                    *width,
                    *height
                )
            }
            C::Scissor { x, y, width, height } => {
                call!(self, "glScissor", fn(i32, i32, i32, i32) -> (), *x, *y, *width, *height)
            }
            C::ShaderSource { shader, source } => {
                let s = self.shader(*shader);
                let src = cstr(source.as_str());
                let p = src.as_ptr();
                call!(
                    self,
                    "glShaderSource",
                    fn(u32, i32, *const *const i8, *const i32) -> (),
                    s,
                    1,
                    &p,
                    std::ptr::null()
                )
            }
            C::StencilFunc { func, reference, mask } => {
                call!(self, "glStencilFunc", fn(u32, i32, u32) -> (), *func, *reference, *mask)
            }
            C::StencilFuncSeparate { face, func, reference, mask } => {
                call!(self, "glStencilFuncSeparate", fn(u32, u32, i32, u32) -> (), *face, *func, *reference, *mask)
            }
            C::StencilMask { mask } => call!(self, "glStencilMask", fn(u32) -> (), *mask),
            C::StencilMaskSeparate { face, mask } => {
                call!(self, "glStencilMaskSeparate", fn(u32, u32) -> (), *face, *mask)
            }
            C::StencilOp { fail, zfail, zpass } => {
                call!(self, "glStencilOp", fn(u32, u32, u32) -> (), *fail, *zfail, *zpass)
            }
            C::StencilOpSeparate { face, fail, zfail, zpass } => {
                call!(self, "glStencilOpSeparate", fn(u32, u32, u32, u32) -> (), *face, *fail, *zfail, *zpass)
            }
            C::TexImage2D { target, level, internalformat, width, height, border, format, pixel_type, pixels } => {
                let p = opt_ptr(pixels);
                call!(
                    self,
                    "glTexImage2D",
                    fn(u32, i32, i32, i32, i32, i32, u32, u32, *const u8) -> (),
                    *target,
                    *level,
                    *internalformat,
                    *width,
                    *height,
                    *border,
                    *format,
                    *pixel_type,
                    p
                )
            }
            C::TexSubImage2D { target, level, xoffset, yoffset, width, height, format, pixel_type, pixels } => call!(
                self,
                "glTexSubImage2D",
                fn(u32, i32, i32, i32, i32, i32, u32, u32, *const u8) -> (),
                *target,
                *level,
                *xoffset,
                *yoffset,
                *width,
                *height,
                *format,
                *pixel_type,
                pixels.as_bytes().as_ptr()
            ),
            C::CompressedTexImage2D { target, level, internalformat, width, height, border, data } => call!(
                self,
                "glCompressedTexImage2D",
                fn(u32, i32, u32, i32, i32, i32, i32, *const u8) -> (),
                *target,
                *level,
                *internalformat,
                *width,
                *height,
                *border,
                data.len() as i32,
                data.as_bytes().as_ptr()
            ),
            C::CompressedTexSubImage2D { target, level, xoffset, yoffset, width, height, format, data } => call!(
                self,
                "glCompressedTexSubImage2D",
                fn(u32, i32, i32, i32, i32, i32, u32, i32, *const u8) -> (),
                *target,
                *level,
                *xoffset,
                *yoffset,
                *width,
                *height,
                *format,
                data.len() as i32,
                data.as_bytes().as_ptr()
            ),
            C::TexParameteri { target, pname, param } => {
                call!(self, "glTexParameteri", fn(u32, u32, i32) -> (), *target, *pname, *param)
            }
            C::TexParameterf { target, pname, param } => {
                call!(self, "glTexParameterf", fn(u32, u32, f32) -> (), *target, *pname, *param)
            }
            C::Uniform1f { location, x } => call!(self, "glUniform1f", fn(i32, f32) -> (), *location, *x),
            C::Uniform2f { location, x, y } => call!(self, "glUniform2f", fn(i32, f32, f32) -> (), *location, *x, *y),
            C::Uniform3f { location, x, y, z } => {
                call!(self, "glUniform3f", fn(i32, f32, f32, f32) -> (), *location, *x, *y, *z)
            }
            C::Uniform4f { location, x, y, z, w } => {
                call!(self, "glUniform4f", fn(i32, f32, f32, f32, f32) -> (), *location, *x, *y, *z, *w)
            }
            C::Uniform1i { location, x } => call!(self, "glUniform1i", fn(i32, i32) -> (), *location, *x),
            C::Uniform2i { location, x, y } => call!(self, "glUniform2i", fn(i32, i32, i32) -> (), *location, *x, *y),
            C::Uniform3i { location, x, y, z } => {
                call!(self, "glUniform3i", fn(i32, i32, i32, i32) -> (), *location, *x, *y, *z)
            }
            C::Uniform4i { location, x, y, z, w } => {
                call!(self, "glUniform4i", fn(i32, i32, i32, i32, i32) -> (), *location, *x, *y, *z, *w)
            }
            C::Uniform1fv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform1fv", fn(i32, i32, *const f32) -> (), *location, v.len() as i32, v.as_ptr())
            }
            C::Uniform2fv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform2fv", fn(i32, i32, *const f32) -> (), *location, v.len() as i32 / 2, v.as_ptr())
            }
            C::Uniform3fv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform3fv", fn(i32, i32, *const f32) -> (), *location, v.len() as i32 / 3, v.as_ptr())
            }
            C::Uniform4fv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform4fv", fn(i32, i32, *const f32) -> (), *location, v.len() as i32 / 4, v.as_ptr())
            }
            C::Uniform1iv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform1iv", fn(i32, i32, *const i32) -> (), *location, v.len() as i32, v.as_ptr())
            }
            C::Uniform2iv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform2iv", fn(i32, i32, *const i32) -> (), *location, v.len() as i32 / 2, v.as_ptr())
            }
            C::Uniform3iv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform3iv", fn(i32, i32, *const i32) -> (), *location, v.len() as i32 / 3, v.as_ptr())
            }
            C::Uniform4iv { location, values } => {
                let v = values.to_vec();
                call!(self, "glUniform4iv", fn(i32, i32, *const i32) -> (), *location, v.len() as i32 / 4, v.as_ptr())
            }
            C::UniformMatrix2fv { location, transpose, values } => {
                let v = values.to_vec();
                call!(
                    self,
                    "glUniformMatrix2fv",
                    fn(i32, i32, u8, *const f32) -> (),
                    *location,
                    v.len() as i32 / 4,
                    u8::from(*transpose),
                    v.as_ptr()
                )
            }
            C::UniformMatrix3fv { location, transpose, values } => {
                let v = values.to_vec();
                call!(
                    self,
                    "glUniformMatrix3fv",
                    fn(i32, i32, u8, *const f32) -> (),
                    *location,
                    v.len() as i32 / 9,
                    u8::from(*transpose),
                    v.as_ptr()
                )
            }
            C::UniformMatrix4fv { location, transpose, values } => {
                let v = values.to_vec();
                call!(
                    self,
                    "glUniformMatrix4fv",
                    fn(i32, i32, u8, *const f32) -> (),
                    *location,
                    v.len() as i32 / 16,
                    u8::from(*transpose),
                    v.as_ptr()
                )
            }
            C::UseProgram { program } => {
                let p = self.shader(*program);
                call!(self, "glUseProgram", fn(u32) -> (), p)
            }
            C::VertexAttrib1f { index, x } => call!(self, "glVertexAttrib1f", fn(u32, f32) -> (), *index, *x),
            C::VertexAttrib2f { index, x, y } => {
                call!(self, "glVertexAttrib2f", fn(u32, f32, f32) -> (), *index, *x, *y)
            }
            C::VertexAttrib3f { index, x, y, z } => {
                call!(self, "glVertexAttrib3f", fn(u32, f32, f32, f32) -> (), *index, *x, *y, *z)
            }
            C::VertexAttrib4f { index, x, y, z, w } => {
                call!(self, "glVertexAttrib4f", fn(u32, f32, f32, f32, f32) -> (), *index, *x, *y, *z, *w)
            }
            C::VertexAttribData { index, data } => {
                let Some(((size, ty, norm, stride), bytes)) = self.client.get_mut(index) else {
                    return Err(unsupported("client data for an attribute without a pointer"));
                };
                *bytes = data.as_bytes().to_vec();
                let (size, ty, norm, stride, ptr) = (*size, *ty, *norm, *stride, bytes.as_ptr());
                call!(
                    self,
                    "glVertexAttribPointer",
                    fn(u32, i32, u32, u8, i32, *const u8) -> (),
                    *index,
                    size,
                    ty,
                    u8::from(norm),
                    stride,
                    ptr
                )
            }
            C::DrawElementsData { mode, count, index_type, indices } => {
                call!(
                    self,
                    "glDrawElements",
                    fn(u32, i32, u32, *const u8) -> (),
                    *mode,
                    *count,
                    *index_type,
                    indices.as_bytes().as_ptr()
                )
            }
            C::VertexAttribPointer { index, size, attrib_type, normalized, stride, offset } => {
                self.client.insert(*index, ((*size, *attrib_type, *normalized, *stride), Vec::new()));
                call!(
                    self,
                    "glVertexAttribPointer",
                    fn(u32, i32, u32, u8, i32, usize) -> (),
                    *index,
                    *size,
                    *attrib_type,
                    u8::from(*normalized),
                    *stride,
                    *offset as usize
                )
            }
            C::Viewport { x, y, width, height } => {
                call!(self, "glViewport", fn(i32, i32, i32, i32) -> (), *x, *y, *width, *height)
            }
            C::SampleCoverage { value, invert } => {
                call!(self, "glSampleCoverage", fn(f32, u8) -> (), *value, u8::from(*invert))
            }
            C::DiscardFramebufferEXT { target, attachments } => {
                let list: Vec<u32> = attachments.iter().collect();
                let n = list.len() as i32;
                call!(self, "glDiscardFramebufferEXT", fn(u32, i32, *const u32) -> (), *target, n, list.as_ptr())
            }
            other => return ext::send(self, other),
        }
        Ok(())
    }

    fn call(&mut self, cmd: &Command<'_>) -> Result<Reply, ClientError> {
        use Command as C;
        if let Some(r) = ext::call(self, cmd) {
            return r;
        }
        Ok(match cmd {
            C::GetError {} => Reply::GetError(call!(self, "glGetError", fn() -> u32,)),
            C::Finish {} => {
                call!(self, "glFinish", fn() -> (),);
                Reply::Finish(())
            }
            C::CheckFramebufferStatus { target } => {
                Reply::CheckFramebufferStatus(call!(self, "glCheckFramebufferStatus", fn(u32) -> u32, *target))
            }
            C::GetUniformLocation { program, name } => {
                let p = self.shader(*program);
                let n = cstr(name.as_str());
                Reply::GetUniformLocation(call!(self, "glGetUniformLocation", fn(u32, *const i8) -> i32, p, n.as_ptr()))
            }
            C::GetAttribLocation { program, name } => {
                let p = self.shader(*program);
                let n = cstr(name.as_str());
                Reply::GetAttribLocation(call!(self, "glGetAttribLocation", fn(u32, *const i8) -> i32, p, n.as_ptr()))
            }
            C::GetShaderiv { shader, pname } => {
                let s = self.shader(*shader);
                let mut v = 0;
                call!(self, "glGetShaderiv", fn(u32, u32, *mut i32) -> (), s, *pname, &mut v);
                Reply::GetShaderiv(v)
            }
            C::GetProgramiv { program, pname } => {
                let p = self.shader(*program);
                let mut v = 0;
                call!(self, "glGetProgramiv", fn(u32, u32, *mut i32) -> (), p, *pname, &mut v);
                Reply::GetProgramiv(v)
            }
            C::GetShaderInfoLog { shader } => {
                let s = self.shader(*shader);
                Reply::GetShaderInfoLog(self.log(s, false)?)
            }
            C::GetProgramInfoLog { program } => {
                let p = self.shader(*program);
                Reply::GetProgramInfoLog(self.log(p, true)?)
            }
            // The values a query writes: everything before the first untouched sentinel.
            C::GetIntegerv { pname } => {
                let mut v = [INT_SENTINEL; 16];
                call!(self, "glGetIntegerv", fn(u32, *mut i32) -> (), *pname, v.as_mut_ptr());
                Reply::GetIntegerv(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
            }
            C::GetFloatv { pname } => {
                let mut v = [f32::from_bits(FLOAT_SENTINEL); 16];
                call!(self, "glGetFloatv", fn(u32, *mut f32) -> (), *pname, v.as_mut_ptr());
                Reply::GetFloatv(v.iter().copied().take_while(|x| x.to_bits() != FLOAT_SENTINEL).collect())
            }
            C::GetBooleanv { pname } => {
                let mut v = [BOOL_SENTINEL; 16];
                call!(self, "glGetBooleanv", fn(u32, *mut u8) -> (), *pname, v.as_mut_ptr());
                Reply::GetBooleanv(v.iter().take_while(|x| **x != BOOL_SENTINEL).map(|x| *x != 0).collect())
            }
            C::GetString { name } => {
                let p = call!(self, "glGetString", fn(u32) -> *const u8, *name);
                Reply::GetString(self.string(p))
            }
            C::IsEnabled { cap } => Reply::IsEnabled(call!(self, "glIsEnabled", fn(u32) -> u8, *cap) != 0),
            C::GetActiveUniform { program, index } => {
                let p = self.shader(*program);
                let (mut len, mut size, mut ty) = (0i32, 0i32, 0u32);
                let mut buf = [0u8; 256];
                call!(
                    self,
                    "glGetActiveUniform",
                    fn(u32, u32, i32, *mut i32, *mut i32, *mut u32, *mut u8) -> (),
                    p,
                    *index,
                    256,
                    &mut len,
                    &mut size,
                    &mut ty,
                    buf.as_mut_ptr()
                );
                Reply::GetActiveUniform((len > 0).then(|| ActiveVariable {
                    size,
                    ty,
                    name: String::from_utf8_lossy(&buf[..len as usize]).into_owned(),
                }))
            }
            C::ReadPixels { x, y, width, height, format, pixel_type } => {
                let mut out = vec![0u8; (*width as usize) * (*height as usize) * 4 + 16];
                call!(
                    self,
                    "glReadPixels",
                    fn(i32, i32, i32, i32, u32, u32, *mut u8) -> (),
                    *x,
                    *y,
                    *width,
                    *height,
                    *format,
                    *pixel_type,
                    out.as_mut_ptr()
                );
                out.truncate((*width as usize) * (*height as usize) * 4);
                Reply::ReadPixels(Bytes(out))
            }
            other => {
                self.send(other)?;
                return Err(unsupported(other.opcode().name()));
            }
        })
    }
}
