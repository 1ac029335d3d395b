//! `eglCreateContext`'s attribute list: EGL 1.4's client version, `EGL_KHR_create_context`'s
//! minor version, flags and reset strategy, `EGL_EXT_create_context_robustness`'s robust
//! access and reset strategy, `EGL_KHR_create_context_no_error`,
//! `EGL_KHR_context_flush_control` and `EGL_IMG_context_priority`, validated as Mesa validates
//! them.

use strata_protocol::control::Priority;
use strata_protocol::EglResult;

use crate::enums::*;

/// What an `eglCreateContext` attribute list asks for.
#[derive(Debug, Default, PartialEq)]
pub(super) struct ContextAttribs {
    /// A debug context (`EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR`).
    pub(super) debug: bool,
    /// `EGL_CONTEXT_PRIORITY_LEVEL_IMG`'s class.
    pub(super) priority: Option<Priority>,
    /// A context that reports no errors (`EGL_CONTEXT_OPENGL_NO_ERROR_KHR`, any value but 0).
    pub(super) no_error: bool,
    /// No flush when the context is released (`EGL_CONTEXT_RELEASE_BEHAVIOR_NONE_KHR`).
    pub(super) release_none: bool,
    /// `EGL_LOSE_CONTEXT_ON_RESET_KHR` asked for (`GL_RESET_NOTIFICATION_STRATEGY_EXT`).
    pub(super) lose_on_reset: bool,
    /// Robust buffer access (`EGL_CONTEXT_OPENGL_ROBUST_ACCESS_EXT` of `EGL_TRUE`).
    pub(super) robust: bool,
    /// The OpenGL ES major version given: 2, or 3.
    pub(super) major: u8,
}

/// `EGL_EXT_create_context_robustness`'s attributes (its reset strategy's values are
/// `EGL_KHR_create_context`'s).
const EGL_CONTEXT_OPENGL_ROBUST_ACCESS_EXT: i32 = 0x30BF;
const EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_EXT: i32 = 0x3138;

/// `EGL_KHR_create_context_no_error`'s attribute.
const EGL_CONTEXT_OPENGL_NO_ERROR_KHR: i32 = 0x31B3;
/// `EGL_KHR_context_flush_control`'s attribute and its two values.
const EGL_CONTEXT_RELEASE_BEHAVIOR_KHR: i32 = 0x2097;
const EGL_CONTEXT_RELEASE_BEHAVIOR_NONE_KHR: i32 = 0;
const EGL_CONTEXT_RELEASE_BEHAVIOR_FLUSH_KHR: i32 = 0x2098;

/// Validates an OpenGL ES context's attribute list as EGL 1.4 with `EGL_KHR_create_context`
/// and `EGL_IMG_context_priority` define it, and as Mesa answers it: version 2.0, and 3.0 where
/// `es3` offers it (to 2.0 requests too with `Es3Contexts::ForEs2`, as Mesa does) (ES 1 has no config here: `EGL_BAD_CONFIG`; another version, or a minor
/// version above 0: `EGL_BAD_MATCH`, as Mesa held to ES 2.0 or 3.0 answers); the debug flag;
/// either reset notification strategy; the profile mask and the forward-compatible flag
/// (desktop OpenGL's), robust access, and unknown attributes, values or flag bits:
/// `EGL_BAD_ATTRIBUTE`. A no-error context may not be a debug context (`EGL_BAD_MATCH`); the
/// release behaviour is flush or none.
pub(super) fn parse(list: &[i32], es3: crate::Es3Contexts) -> EglResult<ContextAttribs> {
    use crate::Es3Contexts::{Asked, ForEs2};
    let (mut major, mut minor, mut out) = (1, 0, ContextAttribs::default());
    for pair in list.chunks(2) {
        match *pair {
            [EGL_NONE, ..] => break,
            [EGL_CONTEXT_CLIENT_VERSION, v] => major = v,
            [EGL_CONTEXT_MINOR_VERSION_KHR, v] => minor = v,
            [EGL_CONTEXT_FLAGS_KHR, v] => {
                if v & !EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR != 0 {
                    // Forward-compatible is desktop OpenGL's; robust access needs
                    // EGL_EXT_create_context_robustness; other bits are undefined.
                    return Err(EGL_BAD_ATTRIBUTE);
                }
                out.debug = v & EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR != 0;
            }
            [EGL_CONTEXT_PRIORITY_LEVEL_IMG, v] => {
                out.priority = Some(Priority::from_egl_level(v).ok_or(EGL_BAD_ATTRIBUTE)?)
            }
            // Kept for GL_RESET_NOTIFICATION_STRATEGY_EXT (EXT_robustness, KHR_robustness).
            [EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_KHR | EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_EXT, v @ (EGL_NO_RESET_NOTIFICATION_KHR | EGL_LOSE_CONTEXT_ON_RESET_KHR)] => {
                out.lose_on_reset = v == EGL_LOSE_CONTEXT_ON_RESET_KHR
            }
            [EGL_CONTEXT_OPENGL_NO_ERROR_KHR, v] => out.no_error = v != 0,
            // As Mesa: only EGL_TRUE asks for it; any other value is taken, and asks nothing.
            [EGL_CONTEXT_OPENGL_ROBUST_ACCESS_EXT, v] => out.robust = v == EGL_TRUE,
            [EGL_CONTEXT_RELEASE_BEHAVIOR_KHR, v @ (EGL_CONTEXT_RELEASE_BEHAVIOR_NONE_KHR | EGL_CONTEXT_RELEASE_BEHAVIOR_FLUSH_KHR)] => {
                out.release_none = v == EGL_CONTEXT_RELEASE_BEHAVIOR_NONE_KHR
            }
            [EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, _] => return Err(EGL_BAD_ATTRIBUTE),
            _ => return Err(EGL_BAD_ATTRIBUTE),
        }
    }
    if out.no_error && out.debug {
        return Err(EGL_BAD_MATCH);
    }
    match (major, minor) {
        (2, 0) if es3 == ForEs2 => Ok(ContextAttribs { major: 3, ..out }),
        (2, 0) => Ok(ContextAttribs { major: 2, ..out }),
        (3, 0) if matches!(es3, Asked | ForEs2) => Ok(ContextAttribs { major: 3, ..out }),
        (1, _) => Err(EGL_BAD_CONFIG),
        _ => Err(EGL_BAD_MATCH),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Es3Contexts::{Asked, ForEs2, Off};

    #[test]
    fn create_context_attributes_are_validated_as_mesa_validates_them() {
        let debug = EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR;
        assert_eq!(
            parse(&[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE], Off),
            Ok(ContextAttribs { major: 2, ..Default::default() })
        );
        let asked = parse(&[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_CONTEXT_FLAGS_KHR, debug, EGL_NONE], Off);
        assert_eq!(asked, Ok(ContextAttribs { debug: true, major: 2, ..Default::default() }));
        let three = [EGL_CONTEXT_CLIENT_VERSION, 3, EGL_NONE];
        assert_eq!(parse(&three, Asked), Ok(ContextAttribs { major: 3, ..Default::default() }));
        assert_eq!(parse(&three, Off), Err(EGL_BAD_MATCH), "ES 3.0 only where offered");
        let two = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
        assert_eq!(parse(&two, Asked).map(|a| a.major), Ok(2), "2.0 asked for, 2.0 given");
        assert_eq!(parse(&two, ForEs2).map(|a| a.major), Ok(3), "2.0 asked for, 3.0 given, as on Mesa");
        let three_one = [EGL_CONTEXT_CLIENT_VERSION, 3, EGL_CONTEXT_MINOR_VERSION_KHR, 1, EGL_NONE];
        assert_eq!(parse(&three_one, Asked), Err(EGL_BAD_MATCH), "ES 3.1 is not offered");
        for (list, err) in [
            (&[EGL_NONE][..], EGL_BAD_CONFIG),
            (&[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_CONTEXT_MINOR_VERSION_KHR, 1, EGL_NONE], EGL_BAD_MATCH),
            (&[EGL_CONTEXT_CLIENT_VERSION, 4, EGL_NONE], EGL_BAD_MATCH),
            (&[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_CONTEXT_FLAGS_KHR, 0x2, EGL_NONE], EGL_BAD_ATTRIBUTE),
            (&[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_CONTEXT_FLAGS_KHR, 0x4, EGL_NONE], EGL_BAD_ATTRIBUTE),
            (&[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_CONTEXT_FLAGS_KHR, 0x8, EGL_NONE], EGL_BAD_ATTRIBUTE),
            (&[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, 1, EGL_NONE], EGL_BAD_ATTRIBUTE),
            (&[EGL_CONTEXT_CLIENT_VERSION, 2, 0x1234, 0, EGL_NONE], EGL_BAD_ATTRIBUTE),
            (
                &[EGL_CONTEXT_CLIENT_VERSION, 2, EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_KHR, 5, EGL_NONE],
                EGL_BAD_ATTRIBUTE,
            ),
        ] {
            assert_eq!(parse(list, Asked).and(parse(list, Off)), Err(err), "{list:x?}");
        }
    }
}
