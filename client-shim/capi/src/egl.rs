//! The EGL 1.4 entry points (plus `eglGetPlatformDisplay` and `EGL_EXT_platform_base`).
//!
//! Displays are the shim's own (so that `eglGetDisplay` works before the daemon is reached);
//! `eglInitialize` connects to `stratad`, and connects again after it went away (see
//! [`crate::display`]). Configs are the daemon's handles; contexts and surfaces are the shim's,
//! each backed by a daemon object (see [`crate::context`] and [`crate::surface`]). Each thread
//! has its own current context and EGL error. `eglGetProcAddress` is in `registry.rs`, beside
//! the list of entry points it answers from.

use std::ffi::{c_char, c_void, CStr};

use strata_protocol::{Calls, Slice};

use crate::context::{create_context, destroy_context, make_current, query_context, release_current};
use crate::display::{daemon, get_display, initialize, initialized, platform_display, terminate};
use crate::gl::debug_callback::sync_point;
use crate::state::{self, answer, process};
use crate::surface::{self, window_id, x_display};
use crate::sync::glFinish;
use crate::types::*;
use crate::x11;

/// `EGL_SWAP_BEHAVIOR`.
const EGL_SWAP_BEHAVIOR: EGLint = 0x3093;
/// `EGL_BUFFER_DESTROYED`.
const EGL_BUFFER_DESTROYED: EGLint = 0x3095;
/// `EGL_HEIGHT`.
const EGL_HEIGHT: EGLint = 0x3056;
/// `EGL_WIDTH`.
const EGL_WIDTH: EGLint = 0x3057;

/// Client extensions (`eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS)`): only what is implemented.
const CLIENT_EXTENSIONS: &CStr =
    c"EGL_EXT_client_extensions EGL_EXT_platform_base EGL_KHR_platform_x11 EGL_EXT_platform_x11 EGL_KHR_client_get_all_proc_addresses";

/// Longest attribute list read from the application (pairs), against unterminated lists.
const MAX_ATTRIBS: usize = 256;

/// Sets the thread's EGL error from `r` and converts it to an `EGLBoolean`.
fn boolean(r: Result<(), EGLint>) -> EGLBoolean {
    answer(r.map(|()| EGL_TRUE), EGL_FALSE)
}

/// Sets the thread's EGL error from `r` and converts a handle to a pointer (null on error).
fn handle_ptr(r: Result<u32, EGLint>) -> *mut c_void {
    answer(r.map(|h| h as usize as *mut c_void), std::ptr::null_mut())
}

/// A handle the application passed back, as the daemon's number.
fn handle(p: *mut c_void) -> u32 {
    u32::try_from(p as usize).unwrap_or(u32::MAX)
}

/// Reads an `EGL_NONE`-terminated list of `EGLint` pairs (a null list is empty).
unsafe fn attrib_list(list: *const EGLint) -> Result<Vec<EGLint>, EGLint> {
    let mut out = Vec::new();
    if list.is_null() {
        out.push(EGL_NONE);
        return Ok(out);
    }
    for i in 0..MAX_ATTRIBS {
        // SAFETY: the application promises an EGL_NONE-terminated list of pairs.
        let a = unsafe { *list.add(2 * i) };
        out.push(a);
        if a == EGL_NONE {
            return Ok(out);
        }
        // SAFETY: as above; a non-NONE attribute is followed by its value.
        out.push(unsafe { *list.add(2 * i + 1) });
    }
    Err(EGL_BAD_ATTRIBUTE)
}

/// Reads an `EGL_NONE`-terminated list of `EGLAttrib` pairs as `EGLint`s. A value may also be
/// a 32-bit pattern widened without its sign (the bits of a `float`, as
/// `EGL_STRATA_surface_projection`'s planes are, cast from an unsigned type).
unsafe fn attrib_list_wide(list: *const EGLAttrib) -> Result<Vec<EGLint>, EGLint> {
    let mut out = Vec::new();
    if list.is_null() {
        out.push(EGL_NONE);
        return Ok(out);
    }
    for i in 0..2 * MAX_ATTRIBS {
        // SAFETY: the application promises an EGL_NONE-terminated list of pairs.
        let a = unsafe { *list.add(i) };
        let a = match EGLint::try_from(a) {
            Ok(a) => a,
            Err(_) if i % 2 == 1 => u32::try_from(a).map_err(|_| EGL_BAD_ATTRIBUTE)? as EGLint,
            Err(_) => return Err(EGL_BAD_ATTRIBUTE),
        };
        out.push(a);
        if i % 2 == 0 && a == EGL_NONE {
            return Ok(out);
        }
    }
    Err(EGL_BAD_ATTRIBUTE)
}

fn choose_config(
    dpy: EGLDisplay,
    attribs: Vec<EGLint>,
    configs: *mut EGLConfig,
    size: EGLint,
    num: *mut EGLint,
) -> Result<(), EGLint> {
    if num.is_null() {
        return Err(EGL_BAD_PARAMETER);
    }
    let mut p = process();
    initialized(&mut p, dpy)?;
    let limit = if configs.is_null() { -1 } else { size.max(0) };
    let ids = daemon(&mut p, |c, dd| c.eglChooseConfig(dd, Slice::new(&attribs), limit))?;
    // SAFETY: `configs` (when non-null) has room for `size` handles; `num` is non-null.
    unsafe {
        if !configs.is_null() {
            for (i, id) in ids.iter().take(size.max(0) as usize).enumerate() {
                *configs.add(i) = *id as usize as EGLConfig;
            }
        }
        *num = ids.len().min(if configs.is_null() { usize::MAX } else { size.max(0) as usize }) as EGLint;
    }
    Ok(())
}

fn config_attrib(dpy: EGLDisplay, config: EGLConfig, attribute: EGLint, value: *mut EGLint) -> Result<(), EGLint> {
    if value.is_null() {
        return Err(EGL_BAD_PARAMETER);
    }
    let mut p = process();
    let d = initialized(&mut p, dpy)?;
    let config = handle(config);
    let v = if attribute == EGL_NATIVE_VISUAL_ID {
        // The daemon has no native visuals; the X server's depth-24 TrueColor visual is what
        // X clients create the window with.
        daemon(&mut p, |c, dd| c.eglGetConfigAttrib(dd, config, EGL_CONFIG_ID))?;
        x_display(&mut p, d).and_then(x11::visual_id).map(|v| v as EGLint).unwrap_or(0)
    } else {
        daemon(&mut p, |c, dd| c.eglGetConfigAttrib(dd, config, attribute))?
    };
    // SAFETY: checked non-null above.
    unsafe { *value = v };
    Ok(())
}

/// `eglSwapBuffers` of pbuffer `s` (daemon surface `d`) while it is the daemon's current draw
/// surface: a swap that shows nothing, sent as a flush with no reply to wait for (`true`);
/// other surfaces take the daemon's swap (`false`).
fn swap_pbuffer(p: &mut state::Process, s: u32, d: u32) -> Result<bool, EGLint> {
    let pbuffer = p.surfaces.get(&s).is_some_and(|i| i.pbuffer);
    if !pbuffer || p.daemon_current.is_none_or(|(_, draw, _)| draw != d) {
        return Ok(false);
    }
    let Some(conn) = p.conn.as_mut() else { return Err(EGL_CONTEXT_LOST) };
    if let Err(e) = conn.glFlush() {
        p.lose(&e);
        return Err(EGL_CONTEXT_LOST);
    }
    Ok(true)
}

fn unsupported(name: &str, error: EGLint) -> EGLint {
    state::log_once(&format!("{name} is not supported; it fails with EGL error {error:#x}"));
    error
}

fn wait_client() -> EGLBoolean {
    if state::current().is_some() {
        // SAFETY: glFinish takes no arguments.
        unsafe { glFinish() };
    }
    state::set_egl_error(EGL_SUCCESS);
    EGL_TRUE
}

crate::entry::entry_points! {
    /// Returns and clears the calling thread's EGL error.
    fn eglGetError() -> EGLint {
        state::take_egl_error()
    }

    /// A display for a native (X11) display; `EGL_DEFAULT_DISPLAY` opens `$DISPLAY` when needed.
    fn eglGetDisplay(native: EGLNativeDisplayType) -> EGLDisplay {
        get_display(native as usize)
    }

    /// EGL 1.5 platform display; only `EGL_PLATFORM_X11_KHR` is supported.
    fn eglGetPlatformDisplay(platform: EGLenum, native: *mut c_void, _attribs: *const EGLAttrib) -> EGLDisplay {
        platform_display(platform, native)
    }

    /// `EGL_EXT_platform_base`; only `EGL_PLATFORM_X11_EXT` is supported.
    fn eglGetPlatformDisplayEXT(platform: EGLenum, native: *mut c_void, _attribs: *const EGLint) -> EGLDisplay {
        platform_display(platform, native)
    }

    /// Connects to stratad (once per process, and again after losing it) and initializes the display.
    fn eglInitialize(dpy: EGLDisplay, major: *mut EGLint, minor: *mut EGLint) -> EGLBoolean {
        boolean(initialize(dpy, major, minor))
    }

    /// Marks the display uninitialized.
    fn eglTerminate(dpy: EGLDisplay) -> EGLBoolean {
        boolean(terminate(dpy))
    }

    /// Vendor, version, client APIs and extensions; with `EGL_NO_DISPLAY`, client extensions.
    fn eglQueryString(dpy: EGLDisplay, name: EGLint) -> *const c_char {
        if dpy.is_null() {
            if name == EGL_EXTENSIONS {
                state::set_egl_error(EGL_SUCCESS);
                return CLIENT_EXTENSIONS.as_ptr();
            }
            state::set_egl_error(EGL_BAD_DISPLAY);
            return std::ptr::null();
        }
        if let Err(e) = initialized(&mut process(), dpy) {
            state::set_egl_error(e);
            return std::ptr::null();
        }
        let s: &CStr = match name {
            EGL_VENDOR => c"Strata",
            EGL_VERSION => c"1.4 Strata",
            EGL_CLIENT_APIS => c"OpenGL_ES",
            // The daemon answers them (`EGL_STRATA_surface_id` and `EGL_STRATA_surface_projection`: surface attributes the
            // library passes through, see docs/projection.md).
            EGL_EXTENSIONS => c"EGL_KHR_create_context EGL_KHR_create_context_no_error EGL_EXT_create_context_robustness EGL_KHR_no_config_context EGL_KHR_context_flush_control EGL_KHR_surfaceless_context EGL_KHR_fence_sync EGL_KHR_reusable_sync EGL_KHR_wait_sync EGL_KHR_image_base EGL_KHR_gl_texture_2D_image EGL_KHR_gl_texture_cubemap_image EGL_KHR_gl_renderbuffer_image EGL_KHR_gl_colorspace EGL_EXT_pixel_format_float EGL_EXT_buffer_age EGL_KHR_swap_buffers_with_damage EGL_KHR_get_all_proc_addresses EGL_IMG_context_priority EGL_STRATA_surface_id EGL_STRATA_surface_projection",
            _ => {
                state::set_egl_error(EGL_BAD_PARAMETER);
                return std::ptr::null();
            }
        };
        state::set_egl_error(EGL_SUCCESS);
        s.as_ptr()
    }

    /// Every config the daemon offers.
    fn eglGetConfigs(dpy: EGLDisplay, configs: *mut EGLConfig, size: EGLint, num: *mut EGLint) -> EGLBoolean {
        boolean(choose_config(dpy, vec![EGL_NONE], configs, size, num))
    }

    /// Configs matching `attribs`, best first, as the daemon orders them.
    fn eglChooseConfig(
        dpy: EGLDisplay,
        attribs: *const EGLint,
        configs: *mut EGLConfig,
        size: EGLint,
        num: *mut EGLint,
    ) -> EGLBoolean {
        // SAFETY: the application passes an EGL_NONE-terminated list or null.
        boolean(unsafe { attrib_list(attribs) }.and_then(|a| choose_config(dpy, a, configs, size, num)))
    }

    /// One attribute of a config; `EGL_NATIVE_VISUAL_ID` names the X screen's TrueColor visual.
    fn eglGetConfigAttrib(dpy: EGLDisplay, config: EGLConfig, attribute: EGLint, value: *mut EGLint) -> EGLBoolean {
        boolean(config_attrib(dpy, config, attribute, value))
    }

    /// A composited window surface sized like the X window, placed by `STRATA_WINDOW`.
    fn eglCreateWindowSurface(
        dpy: EGLDisplay,
        config: EGLConfig,
        win: EGLNativeWindowType,
        attribs: *const EGLint,
    ) -> EGLSurface {
        // SAFETY: the application passes an EGL_NONE-terminated list or null.
        handle_ptr(unsafe { attrib_list(attribs) }.and_then(|a| surface::create_window(dpy, handle(config), window_id(win), a)))
    }

    /// EGL 1.5 form of `eglCreateWindowSurface`: `native_window` points at an X11 `Window`.
    fn eglCreatePlatformWindowSurface(
        dpy: EGLDisplay,
        config: EGLConfig,
        native_window: *mut c_void,
        attribs: *const EGLAttrib,
    ) -> EGLSurface {
        if native_window.is_null() {
            return handle_ptr(Err(EGL_BAD_NATIVE_WINDOW));
        }
        // SAFETY: on X11 the native window argument points at a `Window`.
        let win = window_id(unsafe { *(native_window as *const EGLNativeWindowType) });
        // SAFETY: the application passes an EGL_NONE-terminated list or null.
        handle_ptr(unsafe { attrib_list_wide(attribs) }.and_then(|a| surface::create_window(dpy, handle(config), win, a)))
    }

    /// `EGL_EXT_platform_base` form of `eglCreateWindowSurface`.
    fn eglCreatePlatformWindowSurfaceEXT(
        dpy: EGLDisplay,
        config: EGLConfig,
        native_window: *mut c_void,
        attribs: *const EGLint,
    ) -> EGLSurface {
        if native_window.is_null() {
            return handle_ptr(Err(EGL_BAD_NATIVE_WINDOW));
        }
        // SAFETY: on X11 the native window argument points at a `Window`.
        let win = window_id(unsafe { *(native_window as *const EGLNativeWindowType) });
        // SAFETY: the application passes an EGL_NONE-terminated list or null.
        handle_ptr(unsafe { attrib_list(attribs) }.and_then(|a| surface::create_window(dpy, handle(config), win, a)))
    }

    /// An off-screen surface in the daemon.
    fn eglCreatePbufferSurface(dpy: EGLDisplay, config: EGLConfig, attribs: *const EGLint) -> EGLSurface {
        // SAFETY: the application passes an EGL_NONE-terminated list or null.
        let r = unsafe { attrib_list(attribs) }.and_then(|a| {
            let mut p = process();
            let d = initialized(&mut p, dpy)?;
            let config = handle(config);
            let s = daemon(&mut p, |c, dd| c.eglCreatePbufferSurface(dd, config, Slice::new(&a)))?;
            Ok(p.add_surface(d, s, None, true))
        });
        handle_ptr(r)
    }

    /// A pixmap surface: a daemon pbuffer whose pixels `glFinish` puts into the X pixmap.
    fn eglCreatePixmapSurface(
        dpy: EGLDisplay,
        config: EGLConfig,
        pixmap: EGLNativePixmapType,
        attribs: *const EGLint,
    ) -> EGLSurface {
        // SAFETY: the application passes an EGL_NONE-terminated list or null.
        #[allow(clippy::useless_conversion)]
        handle_ptr(unsafe { attrib_list(attribs) }.and_then(|a| crate::pixmap::create(dpy, handle(config), u64::from(pixmap), a)))
    }

    /// EGL 1.5 form of `eglCreatePixmapSurface`: `pixmap` points at an X11 `Pixmap`.
    fn eglCreatePlatformPixmapSurface(
        dpy: EGLDisplay,
        config: EGLConfig,
        pixmap: *mut c_void,
        attribs: *const EGLAttrib,
    ) -> EGLSurface {
        // SAFETY: on X11 the native pixmap argument points at a `Pixmap`; the application passes
        // an EGL_NONE-terminated list or null.
        let r = unsafe { crate::pixmap::pointed_at(pixmap).and_then(|n| attrib_list_wide(attribs).map(|a| (n, a))) };
        handle_ptr(r.and_then(|(native, a)| crate::pixmap::create(dpy, handle(config), native, a)))
    }

    /// `EGL_EXT_platform_base` form of `eglCreatePixmapSurface`: `pixmap` points at an X11
    /// `Pixmap`.
    fn eglCreatePlatformPixmapSurfaceEXT(
        dpy: EGLDisplay,
        config: EGLConfig,
        pixmap: *mut c_void,
        attribs: *const EGLint,
    ) -> EGLSurface {
        // SAFETY: on X11 the native pixmap argument points at a `Pixmap`; the application passes
        // an EGL_NONE-terminated list or null.
        let r = unsafe { crate::pixmap::pointed_at(pixmap).and_then(|n| attrib_list(attribs).map(|a| (n, a))) };
        handle_ptr(r.and_then(|(native, a)| crate::pixmap::create(dpy, handle(config), native, a)))
    }

    /// Not supported: there are no client buffer types.
    fn eglCreatePbufferFromClientBuffer(
        _dpy: EGLDisplay,
        _buftype: EGLenum,
        _buffer: EGLClientBuffer,
        _config: EGLConfig,
        _attribs: *const EGLint,
    ) -> EGLSurface {
        handle_ptr(Err(unsupported("eglCreatePbufferFromClientBuffer", EGL_BAD_PARAMETER)))
    }

    /// Destroys a surface in the daemon.
    fn eglDestroySurface(dpy: EGLDisplay, surface: EGLSurface) -> EGLBoolean {
        let r = (|| {
            let mut p = process();
            initialized(&mut p, dpy)?;
            let s = handle(surface);
            let d = p.daemon_surface(s).ok_or(EGL_BAD_SURFACE)?;
            daemon(&mut p, |c, dd| c.eglDestroySurface(dd, d))?;
            p.surfaces.remove(&s);
            Ok(())
        })();
        boolean(r)
    }

    /// Width, height, config id, render buffer and swap behaviour of a surface, and (the daemon
    /// answers) its `EGL_STRATA_surface_id` and `EGL_STRATA_surface_projection` attributes.
    fn eglQuerySurface(dpy: EGLDisplay, surface: EGLSurface, attribute: EGLint, value: *mut EGLint) -> EGLBoolean {
        let r = (|| {
            if value.is_null() {
                return Err(EGL_BAD_PARAMETER);
            }
            let mut p = process();
            initialized(&mut p, dpy)?;
            let s = handle(surface);
            if attribute == EGL_WIDTH || attribute == EGL_HEIGHT {
                surface::follow_window(&mut p, s);
            }
            let d = p.daemon_surface(s).ok_or(EGL_BAD_SURFACE)?;
            let v = daemon(&mut p, |c, dd| c.eglQuerySurface(dd, d, attribute))?;
            // SAFETY: checked non-null above.
            unsafe { *value = v };
            Ok(())
        })();
        boolean(r)
    }

    /// Only `EGL_SWAP_BEHAVIOR = EGL_BUFFER_DESTROYED` (what surfaces do anyway) is accepted.
    fn eglSurfaceAttrib(dpy: EGLDisplay, surface: EGLSurface, attribute: EGLint, value: EGLint) -> EGLBoolean {
        let r = (|| {
            let mut p = process();
            initialized(&mut p, dpy)?;
            if !p.surfaces.contains_key(&handle(surface)) {
                return Err(EGL_BAD_SURFACE);
            }
            match (attribute, value) {
                (EGL_SWAP_BEHAVIOR, EGL_BUFFER_DESTROYED) => Ok(()),
                _ => Err(unsupported(&format!("eglSurfaceAttrib({attribute:#x}, {value:#x})"), EGL_BAD_MATCH)),
            }
        })();
        boolean(r)
    }

    /// Not supported: no config binds to textures.
    fn eglBindTexImage(_dpy: EGLDisplay, _surface: EGLSurface, _buffer: EGLint) -> EGLBoolean {
        boolean(Err(unsupported("eglBindTexImage", EGL_BAD_MATCH)))
    }

    /// Not supported: no config binds to textures.
    fn eglReleaseTexImage(_dpy: EGLDisplay, _surface: EGLSurface, _buffer: EGLint) -> EGLBoolean {
        boolean(Err(unsupported("eglReleaseTexImage", EGL_BAD_MATCH)))
    }

    /// Sets the swap interval of the current surface.
    fn eglSwapInterval(dpy: EGLDisplay, interval: EGLint) -> EGLBoolean {
        let r = (|| {
            let mut p = process();
            initialized(&mut p, dpy)?;
            let cur = state::current().ok_or(EGL_BAD_CONTEXT)?;
            // The daemon applies it to its current surface: make that this thread's.
            surface::ensure_bound(&mut p, &cur)?;
            daemon(&mut p, |c, dd| c.eglSwapInterval(dd, interval))
        })();
        boolean(r)
    }

    /// Creates an ES 2.0 context in the daemon.
    fn eglCreateContext(dpy: EGLDisplay, config: EGLConfig, share: EGLContext, attribs: *const EGLint) -> EGLContext {
        // SAFETY: the application passes an EGL_NONE-terminated list or null.
        handle_ptr(unsafe { attrib_list(attribs) }.and_then(|a| create_context(dpy, handle(config), handle(share), a)))
    }

    /// Destroys a context in the daemon.
    fn eglDestroyContext(dpy: EGLDisplay, ctx: EGLContext) -> EGLBoolean {
        boolean(destroy_context(dpy, handle(ctx)))
    }

    /// Binds a context to the calling thread (one current context per thread).
    fn eglMakeCurrent(dpy: EGLDisplay, draw: EGLSurface, read: EGLSurface, ctx: EGLContext) -> EGLBoolean {
        boolean(make_current(dpy, handle(draw), handle(read), handle(ctx)))
    }

    /// The calling thread's current context.
    fn eglGetCurrentContext() -> EGLContext {
        state::current().map_or(std::ptr::null_mut(), |c| c.context as usize as EGLContext)
    }

    /// The calling thread's current display.
    fn eglGetCurrentDisplay() -> EGLDisplay {
        state::current().map_or(std::ptr::null_mut(), |c| c.display as EGLDisplay)
    }

    /// The calling thread's current draw or read surface.
    fn eglGetCurrentSurface(readdraw: EGLint) -> EGLSurface {
        match (state::current(), readdraw) {
            (Some(c), EGL_DRAW) => c.draw as usize as EGLSurface,
            (Some(c), EGL_READ) => c.read as usize as EGLSurface,
            (_, EGL_DRAW | EGL_READ) => std::ptr::null_mut(),
            _ => {
                state::set_egl_error(EGL_BAD_PARAMETER);
                std::ptr::null_mut()
            }
        }
    }

    /// Config id, client type, client version, render buffer and (`EGL_IMG_context_priority`)
    /// the priority level of a context.
    fn eglQueryContext(dpy: EGLDisplay, ctx: EGLContext, attribute: EGLint, value: *mut EGLint) -> EGLBoolean {
        boolean(query_context(dpy, handle(ctx), attribute, value))
    }

    /// Waits for the current context's GL commands (`glFinish`).
    fn eglWaitGL() -> EGLBoolean {
        wait_client()
    }

    /// Waits for the current context's client API commands (`glFinish`).
    fn eglWaitClient() -> EGLBoolean {
        wait_client()
    }

    /// Nothing to wait for: the shim never renders through the native window system.
    fn eglWaitNative(_engine: EGLint) -> EGLBoolean {
        state::set_egl_error(EGL_SUCCESS);
        EGL_TRUE
    }

    /// Presents the back buffer to the compositor (synchronous: applies back-pressure).
    fn eglSwapBuffers(dpy: EGLDisplay, surface: EGLSurface) -> EGLBoolean {
        let r = (|| {
            let mut p = process();
            initialized(&mut p, dpy)?;
            let s = handle(surface);
            let d = p.daemon_surface(s).ok_or(EGL_BAD_SURFACE)?;
            if swap_pbuffer(&mut p, s, d)? {
                return Ok(());
            }
            daemon(&mut p, |c, dd| c.eglSwapBuffers(dd, d))?;
            // The next frame is drawn at the window's size.
            surface::follow_window(&mut p, s);
            Ok(())
        })();
        sync_point("eglSwapBuffers");
        boolean(r)
    }

    /// `EGL_KHR_swap_buffers_with_damage`: `eglSwapBuffers`, the frame having changed only
    /// within the `n_rects` rectangles (x, y, width, height from the bottom left), which the
    /// compositor alone redraws. None is the whole surface.
    fn eglSwapBuffersWithDamageKHR(dpy: EGLDisplay, surface: EGLSurface, rects: *const EGLint, n_rects: EGLint) -> EGLBoolean {
        let r = (|| {
            if n_rects < 0 || (n_rects > 0 && rects.is_null()) {
                return Err(EGL_BAD_PARAMETER);
            }
            let mut p = process();
            initialized(&mut p, dpy)?;
            let s = handle(surface);
            let d = p.daemon_surface(s).ok_or(EGL_BAD_SURFACE)?;
            let n = usize::try_from(n_rects).unwrap_or(0).saturating_mul(4);
            // SAFETY: the application passes `n_rects` rectangles of four integers.
            let list = if n == 0 { &[][..] } else { unsafe { std::slice::from_raw_parts(rects, n) } };
            daemon(&mut p, |c, dd| c.eglSwapBuffersWithDamageKHR(dd, d, Slice::new(list)))?;
            surface::follow_window(&mut p, s);
            Ok(())
        })();
        sync_point("eglSwapBuffersWithDamageKHR");
        boolean(r)
    }

    /// Puts a surface's pixels into an X pixmap of its size.
    fn eglCopyBuffers(dpy: EGLDisplay, surface: EGLSurface, target: EGLNativePixmapType) -> EGLBoolean {
        #[allow(clippy::useless_conversion)]
        boolean(crate::pixmap::copy_buffers(dpy, handle(surface), u64::from(target)))
    }

    /// Only `EGL_OPENGL_ES_API` can be bound.
    fn eglBindAPI(api: EGLenum) -> EGLBoolean {
        if api == EGL_OPENGL_ES_API {
            state::set_api(api);
            boolean(Ok(()))
        } else {
            boolean(Err(EGL_BAD_PARAMETER))
        }
    }

    /// The calling thread's bound API.
    fn eglQueryAPI() -> EGLenum {
        state::api()
    }

    /// Releases the calling thread's current context and resets its EGL state.
    fn eglReleaseThread() -> EGLBoolean {
        let r = release_current(&mut process());
        state::set_api(EGL_OPENGL_ES_API);
        let _ = r;
        boolean(Ok(()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wide_attribute_values_may_be_unsigned_bit_patterns() {
        let bits = (-1.0f32).to_bits();
        let list: [EGLAttrib; 5] = [0x3F03, bits as EGLAttrib, 0x3F04, -5, EGL_NONE as EGLAttrib];
        // SAFETY: an EGL_NONE-terminated list of pairs.
        let got = unsafe { attrib_list_wide(list.as_ptr()) }.expect("reads");
        assert_eq!(got, vec![0x3F03, bits as EGLint, 0x3F04, -5, EGL_NONE]);
        // An attribute name, or a value beyond 32 bits, is refused.
        let list: [EGLAttrib; 3] = [1 << 32, 0, EGL_NONE as EGLAttrib];
        // SAFETY: as above.
        assert_eq!(unsafe { attrib_list_wide(list.as_ptr()) }, Err(EGL_BAD_ATTRIBUTE));
        let list: [EGLAttrib; 3] = [0x3F03, 1 << 33, EGL_NONE as EGLAttrib];
        // SAFETY: as above.
        assert_eq!(unsafe { attrib_list_wide(list.as_ptr()) }, Err(EGL_BAD_ATTRIBUTE));
    }
}
