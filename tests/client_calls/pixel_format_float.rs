//! `EGL_EXT_pixel_format_float`: the component type of the config in use, that the configs
//! chosen by a type have it (fixed-point ones among those of either), and a type that is
//! neither, through the library's `eglChooseConfig`.

use super::*;

const COMPONENT_TYPE: i32 = 0x3339;
const FIXED: i32 = 0x333A;
const FLOAT: i32 = 0x333B;

/// The pixel format float sequence.
pub fn sequence(r: &mut Run) {
    let (gl, dpy) = (r.gl, r.egl.display);
    // SAFETY: EGL's prototypes; NONE-terminated lists, room for the configs asked for.
    unsafe {
        let mut v = -1;
        let ok = (gl.egl_get_config_attrib)(dpy, r.egl.config, COMPONENT_TYPE, &mut v);
        r.log.push(format!("the config in use: {ok} type {v:#x}, error {:#x}", (gl.egl_get_error)()));
        let mut configs = [std::ptr::null_mut(); 64];
        for (what, kind) in [("fixed", FIXED), ("float", FLOAT), ("don't care", -1)] {
            let want = [0x3033, 1, 0x3040, 4, 0x3024, 8, COMPONENT_TYPE, kind, NONE];
            let mut n = -1;
            let ok = (gl.egl_choose_config)(dpy, want.as_ptr(), configs.as_mut_ptr(), 64, &mut n);
            let mut types = Vec::new();
            for c in &configs[..n.clamp(0, 64) as usize] {
                (gl.egl_get_config_attrib)(dpy, *c, COMPONENT_TYPE, &mut v);
                types.push(v);
            }
            // Mesa's surfaceless platform also has float pbuffer configs, which its X11
            // platform (and Strata) has none of: only the filtering is compared.
            let only_asked = types.iter().all(|t| kind == -1 || *t == kind);
            let fixed = types.contains(&FIXED);
            r.log.push(format!(
                "{what} RGBA8 pbuffer configs: {ok}, only that type {only_asked}, fixed among them {fixed}"
            ));
        }
        let mut n = -1;
        let ok = (gl.egl_choose_config)(dpy, [COMPONENT_TYPE, 0x1234, NONE].as_ptr(), configs.as_mut_ptr(), 64, &mut n);
        r.log.push(format!("a type that is neither: {ok}, error {:#x}", (gl.egl_get_error)()));
    }
}
