//! Pixmap surfaces (`eglCreatePixmapSurface` on X11): a pbuffer in the daemon of the X
//! pixmap's size, whose contents the library puts into the pixmap when the application waits
//! for its rendering: `glFinish`, and so `eglWaitClient` and `eglWaitGL` (EGL 1.4 §3.8: the
//! pixmap holds the client API's rendering once it has waited for it). A swap of a pixmap
//! surface does nothing, as EGL says. `eglCopyBuffers` puts any surface's pixels into a pixmap
//! of its size. The pixels come from the daemon's own read of the surface
//! (`strataReadSurface`), past the application's framebuffer bindings and pack state, and go to
//! the X server in one `XPutImage`.

use std::ffi::{c_ulong, c_void};

use strata_client::{ClientError, Connection};
use strata_protocol::{Calls, Slice};

use crate::display::{daemon, initialized};
use crate::state::{self, process, PixmapInfo, Process};
use crate::surface::x_display;
use crate::types::*;
use crate::x11;

const EGL_WIDTH: EGLint = 0x3057;
const EGL_HEIGHT: EGLint = 0x3056;
const EGL_GL_COLORSPACE: EGLint = 0x309D;
const EGL_VG_COLORSPACE: EGLint = 0x3087;
const EGL_VG_ALPHA_FORMAT: EGLint = 0x3088;

/// `eglCreatePixmapSurface`: a pixmap surface for X pixmap `pixmap` (of depth 24 or 32) on the
/// shim's display behind `dpy`. Its only attribute is the GL colour space (OpenVG's are taken
/// and ignored). Not a drawable of the display: `EGL_BAD_NATIVE_PIXMAP`, with the X error
/// trapped. Returns the application's handle.
pub(crate) fn create(dpy: EGLDisplay, config: u32, pixmap: u64, attribs: Vec<EGLint>) -> Result<u32, EGLint> {
    let mut colorspace = Vec::new();
    for pair in attribs.chunks(2) {
        match *pair {
            [EGL_NONE, ..] => break,
            [EGL_GL_COLORSPACE, v] => colorspace.extend([EGL_GL_COLORSPACE, v]),
            [EGL_VG_COLORSPACE | EGL_VG_ALPHA_FORMAT, _] => {}
            _ => return Err(EGL_BAD_ATTRIBUTE),
        }
    }
    let mut p = process();
    let d = initialized(&mut p, dpy)?;
    let px = look_up(&mut p, d, pixmap)?;
    let size = |v: u32| i32::try_from(v).map_err(|_| EGL_BAD_NATIVE_PIXMAP);
    let mut list = vec![EGL_WIDTH, size(px.width)?, EGL_HEIGHT, size(px.height)?];
    list.extend(colorspace);
    list.push(EGL_NONE);
    let s = daemon(&mut p, |c, dd| c.eglCreatePbufferSurface(dd, config, Slice::new(&list)))?;
    let handle = p.add_surface(d, s, None, true);
    if let Some(info) = p.surfaces.get_mut(&handle) {
        info.pixmap = Some(px);
    }
    Ok(handle)
}

/// X pixmap `pixmap` on the shim's display `d`: its size and depth, asked of the X server. Not
/// a drawable of the display: `EGL_BAD_NATIVE_PIXMAP` (the X error trapped); a depth other
/// than 24 or 32: `EGL_BAD_MATCH`.
fn look_up(p: &mut Process, d: usize, pixmap: u64) -> Result<PixmapInfo, EGLint> {
    let x_display = x_display(p, d).ok_or(EGL_BAD_NATIVE_PIXMAP)?;
    let native = c_ulong::try_from(pixmap).map_err(|_| EGL_BAD_NATIVE_PIXMAP)?;
    let (width, height, depth) = x11::drawable_geometry(x_display, native).ok_or(EGL_BAD_NATIVE_PIXMAP)?;
    if !matches!(depth, 24 | 32) {
        return Err(EGL_BAD_MATCH);
    }
    Ok(PixmapInfo { x_display, native: pixmap, width, height, depth })
}

/// Puts `rgba` (RGBA8 rows from the bottom, the pixmap's size) into pixmap `px`; whether the X
/// server took it.
fn put(px: &PixmapInfo, rgba: &[u8]) -> bool {
    let native = c_ulong::try_from(px.native).unwrap_or_default();
    x11::put_rgba(px.x_display, native, px.width, px.height, px.depth, rgba)
}

/// The X pixmap a platform form of `eglCreatePixmapSurface` points at (null:
/// `EGL_BAD_NATIVE_PIXMAP`).
///
/// # Safety
/// A non-null `pixmap` points at an X11 `Pixmap`, as EGL's X11 platform says.
pub(crate) unsafe fn pointed_at(pixmap: *mut c_void) -> Result<u64, EGLint> {
    if pixmap.is_null() {
        return Err(EGL_BAD_NATIVE_PIXMAP);
    }
    // SAFETY: see the function's contract.
    #[allow(clippy::useless_conversion)]
    Ok(u64::from(unsafe { *(pixmap as *const EGLNativePixmapType) }))
}

/// The pixmap behind the calling thread's draw surface, if that is a pixmap surface, with the
/// daemon's display and surface.
pub(crate) fn current() -> Option<(PixmapInfo, u32, u32)> {
    let cur = state::current()?;
    let p = process();
    let info = p.surfaces.get(&cur.draw)?;
    Some((info.pixmap?, p.daemon_display, info.daemon))
}

/// Puts daemon surface `surface`'s pixels into its pixmap `px` (after everything drawn to it).
/// A pixmap the X server no longer has is logged once, and the call goes on.
pub(crate) fn fill(conn: &mut Connection, (px, display, surface): (PixmapInfo, u32, u32)) -> Result<(), ClientError> {
    let put = conn.strataReadSurface(display, surface)?.is_ok_and(|pixels| put(&px, &pixels.0));
    if !put {
        state::log_once(&format!("a pixmap surface's pixmap {:#x} could not be filled", px.native));
    }
    Ok(())
}

/// `eglCopyBuffers`: surface `surface`'s pixels into X pixmap `target`, which must be its size
/// and of depth 24 or 32 (`EGL_BAD_MATCH`); not a drawable: `EGL_BAD_NATIVE_PIXMAP`.
pub(crate) fn copy_buffers(dpy: EGLDisplay, surface: u32, target: u64) -> Result<(), EGLint> {
    let mut p = process();
    let d = initialized(&mut p, dpy)?;
    let s = p.surfaces.get(&surface).filter(|i| i.display == d).map(|i| i.daemon).ok_or(EGL_BAD_SURFACE)?;
    let px = look_up(&mut p, d, target)?;
    let w = daemon(&mut p, |c, dd| c.eglQuerySurface(dd, s, EGL_WIDTH))?;
    let h = daemon(&mut p, |c, dd| c.eglQuerySurface(dd, s, EGL_HEIGHT))?;
    if i64::from(w) != i64::from(px.width) || i64::from(h) != i64::from(px.height) {
        return Err(EGL_BAD_MATCH);
    }
    let pixels = daemon(&mut p, |c, dd| c.strataReadSurface(dd, s))?;
    put(&px, &pixels.0).then_some(()).ok_or(EGL_BAD_NATIVE_PIXMAP)
}
