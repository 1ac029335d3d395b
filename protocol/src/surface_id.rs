//! Stable surface IDs (`EGL_STRATA_surface_id`): the number an integrator fixes for a window
//! surface, as ivi-shell's `ivi-id`, so that a script written today addresses the same
//! surface after a restart. A surface gets one from the daemon's layout (`id = 1000`, or
//! `id = [1000, 1001]` for a client's first, second… window surface), from `STRATA_SURFACE_ID`
//! in the client's environment (the drop-in libEGL turns it into the attribute below), or from
//! the attribute itself; without one it gets a runtime ID. Two live surfaces never share one.

/// `eglQueryString(dpy, EGL_EXTENSIONS)` names this when the attribute below is accepted.
pub const EXTENSION: &str = "EGL_STRATA_surface_id";
/// Window surface attribute: the surface's stable ID, 1 to [`MAX`].
pub const EGL_SURFACE_ID_STRATA: i32 = 0x3F06;
/// The largest stable ID (IDs travel as positive `EGLint`s).
pub const MAX: u32 = i32::MAX as u32;
/// The environment variable the drop-in libEGL reads a stable ID from.
pub const ENV: &str = "STRATA_SURFACE_ID";

/// Why a stable ID was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SurfaceIdError {
    /// Outside 1..=[`MAX`].
    #[error("surface id {0} is outside 1..={MAX}")]
    OutOfRange(i64),
    /// Not a number.
    #[error("surface id {0:?} is not a number")]
    NotANumber(String),
}

/// Checks a stable ID.
pub fn check(id: i64) -> Result<u32, SurfaceIdError> {
    u32::try_from(id).ok().filter(|&v| (1..=MAX).contains(&v)).ok_or(SurfaceIdError::OutOfRange(id))
}

/// Parses a stable ID as `STRATA_SURFACE_ID` writes it.
pub fn parse(text: &str) -> Result<u32, SurfaceIdError> {
    let n: i64 = text.trim().parse().map_err(|_| SurfaceIdError::NotANumber(text.to_string()))?;
    check(n)
}

/// The stable ID an `EGL_NONE`-terminated attribute list asks for, if any.
pub fn from_egl_attribs(attribs: &[i32]) -> Result<Option<u32>, SurfaceIdError> {
    for pair in attribs.chunks_exact(2) {
        match pair[0] {
            EGL_SURFACE_ID_STRATA => return check(i64::from(pair[1])).map(Some),
            0x3038 => break, // EGL_NONE
            _ => {}
        }
    }
    Ok(None)
}

/// `attribs` (`EGL_NONE`-terminated or not) with its stable ID set to `id`, replacing one it
/// names: how the drop-in libEGL applies `STRATA_SURFACE_ID`.
pub fn with_id(attribs: &[i32], id: u32) -> Vec<i32> {
    let mut out = Vec::with_capacity(attribs.len() + 3);
    for pair in attribs.chunks_exact(2) {
        match pair[0] {
            0x3038 => break,
            EGL_SURFACE_ID_STRATA => {}
            _ => out.extend_from_slice(pair),
        }
    }
    out.extend_from_slice(&[EGL_SURFACE_ID_STRATA, id as i32, 0x3038]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_from_attributes_and_the_environment() {
        assert_eq!(from_egl_attribs(&[0x3038]), Ok(None));
        assert_eq!(from_egl_attribs(&[0x3057, 64, EGL_SURFACE_ID_STRATA, 1000, 0x3038]), Ok(Some(1000)));
        assert_eq!(from_egl_attribs(&[0x3038, EGL_SURFACE_ID_STRATA, 5]), Ok(None), "after EGL_NONE");
        assert_eq!(from_egl_attribs(&[EGL_SURFACE_ID_STRATA, 0, 0x3038]), Err(SurfaceIdError::OutOfRange(0)));
        assert_eq!(from_egl_attribs(&[EGL_SURFACE_ID_STRATA, -4, 0x3038]), Err(SurfaceIdError::OutOfRange(-4)));
        assert_eq!(parse(" 1001 "), Ok(1001));
        assert_eq!(parse("ic"), Err(SurfaceIdError::NotANumber("ic".into())));
        assert_eq!(parse("4294967296"), Err(SurfaceIdError::OutOfRange(4294967296)));
        let a = with_id(&[EGL_SURFACE_ID_STRATA, 3, 0x3057, 64, 0x3038], 1000);
        assert_eq!(a, vec![0x3057, 64, EGL_SURFACE_ID_STRATA, 1000, 0x3038]);
        assert_eq!(from_egl_attribs(&a), Ok(Some(1000)));
    }
}
