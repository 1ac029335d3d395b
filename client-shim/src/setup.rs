//! The EGL and GL set-up every client repeats: a display, a config, a surface and a current
//! ES 2.0 context, and a linked program.

use strata_protocol::{Calls, Slice, Text};

use crate::ClientError;

const EGL_NONE: i32 = 0x3038;

/// The surface a context renders to.
#[derive(Debug, Clone, Copy)]
pub enum SurfaceKind {
    /// An off-screen pbuffer of this size.
    Pbuffer {
        /// Width.
        width: i32,
        /// Height.
        height: i32,
    },
    /// A composited window: x, y (from the output's top), width, height, and its depth layer.
    Window {
        /// x, y, width, height in output pixels.
        rect: [i32; 4],
        /// Depth layer.
        z: f32,
    },
}

/// A current context: the display and surface handles `eglSwapBuffers` needs.
#[derive(Debug, Clone, Copy)]
pub struct Current {
    /// The display.
    pub display: u32,
    /// The surface.
    pub surface: u32,
}

fn egl<T>(r: Result<T, i32>, what: &str) -> Result<T, ClientError> {
    r.map_err(|e| ClientError::Unsupported(format!("{what} failed with EGL error {e:#x}")))
}

/// Initialises EGL, picks an RGBA8 config with at least `depth` depth bits and `stencil`
/// stencil bits, creates the surface and an ES 2.0 context, and makes it current.
pub fn egl_context<C>(gl: &mut C, depth: i32, stencil: i32, kind: SurfaceKind) -> Result<Current, ClientError>
where
    C: Calls<Error = ClientError> + ?Sized,
{
    egl_context_with(gl, depth, stencil, kind, &[])
}

/// As [`egl_context`], with an OpenGL ES 3.0 context (the daemon must offer ES 3.0).
pub fn egl_context_es3<C>(gl: &mut C, depth: i32, stencil: i32, kind: SurfaceKind) -> Result<Current, ClientError>
where
    C: Calls<Error = ClientError> + ?Sized,
{
    egl_context_version(gl, depth, stencil, kind, &[], 3)
}

/// As [`egl_context`], with extra window-surface attributes (name, value pairs, without the
/// closing `EGL_NONE`), such as a declared projection.
pub fn egl_context_with<C>(
    gl: &mut C,
    depth: i32,
    stencil: i32,
    kind: SurfaceKind,
    surface_attribs: &[i32],
) -> Result<Current, ClientError>
where
    C: Calls<Error = ClientError> + ?Sized,
{
    egl_context_version(gl, depth, stencil, kind, surface_attribs, 2)
}

/// The common body: an ES `major`.0 context.
fn egl_context_version<C>(
    gl: &mut C,
    depth: i32,
    stencil: i32,
    kind: SurfaceKind,
    surface_attribs: &[i32],
    major: i32,
) -> Result<Current, ClientError>
where
    C: Calls<Error = ClientError> + ?Sized,
{
    let d = gl.eglGetDisplay(0)?;
    egl(gl.eglInitialize(d)?, "eglInitialize")?;
    let surface_bit = match kind {
        SurfaceKind::Pbuffer { .. } => 0x0001,
        SurfaceKind::Window { .. } => 0x0004,
    };
    let attribs = [
        0x3033,
        surface_bit,
        0x3040,
        4,
        0x3024,
        8,
        0x3023,
        8,
        0x3022,
        8,
        0x3021,
        8,
        0x3025,
        depth,
        0x3026,
        stencil,
        EGL_NONE,
    ];
    let config = *egl(gl.eglChooseConfig(d, Slice::new(&attribs), 1)?, "eglChooseConfig")?
        .first()
        .ok_or_else(|| ClientError::Unsupported("no EGL config matches".into()))?;
    let s = match kind {
        SurfaceKind::Pbuffer { width, height } => egl(
            gl.eglCreatePbufferSurface(d, config, Slice::new(&[0x3057, width, 0x3056, height, EGL_NONE]))?,
            "eglCreatePbufferSurface",
        )?,
        SurfaceKind::Window { rect, z } => {
            let attribs: Vec<i32> = surface_attribs.iter().copied().chain([EGL_NONE]).collect();
            egl(
                gl.eglCreateWindowSurface(d, config, 0, rect[0], rect[1], z, rect[2], rect[3], Slice::new(&attribs))?,
                "eglCreateWindowSurface",
            )?
        }
    };
    let ctx = egl(gl.eglCreateContext(d, config, 0, Slice::new(&[0x3098, major, EGL_NONE]))?, "eglCreateContext")?;
    egl(gl.eglMakeCurrent(d, s, s, ctx)?, "eglMakeCurrent")?;
    Ok(Current { display: d, surface: s })
}

/// Compiles `vs` and `fs` into program `names.0` (shaders `names.1`, `names.2`), binds
/// `attribs` to locations 0, 1, …, links and uses it. Compile and link failures carry the log.
pub fn link_program<C>(
    gl: &mut C,
    names: (u32, u32, u32),
    vs: &str,
    fs: &str,
    attribs: &[&str],
) -> Result<u32, ClientError>
where
    C: Calls<Error = ClientError> + ?Sized,
{
    let (p, v, f) = names;
    gl.glCreateProgram(p)?;
    for (name, ty, src) in [(v, 0x8B31u32, vs), (f, 0x8B30, fs)] {
        gl.glCreateShader(ty, name)?;
        gl.glShaderSource(name, Text::borrowed(src))?;
        gl.glCompileShader(name)?;
        if gl.glGetShaderiv(name, 0x8B81)? == 0 {
            return Err(ClientError::Unsupported(format!("compile failed: {}", gl.glGetShaderInfoLog(name)?)));
        }
        gl.glAttachShader(p, name)?;
    }
    for (i, a) in attribs.iter().enumerate() {
        gl.glBindAttribLocation(p, i as u32, Text::borrowed(a))?;
    }
    gl.glLinkProgram(p)?;
    if gl.glGetProgramiv(p, 0x8B82)? == 0 {
        return Err(ClientError::Unsupported(format!("link failed: {}", gl.glGetProgramInfoLog(p)?)));
    }
    gl.glUseProgram(p)?;
    Ok(p)
}
