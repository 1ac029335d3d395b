//! A surface's declared projection: how its window-space depth maps back to eye-space
//! distance, so that the compositor can compare depth between clients whose projections
//! differ. Declared through `EGL_STRATA_surface_projection` (the EGL values below) or the
//! daemon's layout (`projection = { kind = "perspective", near = 0.1, far = 100.0 }`).
//!
//! Window depth `d` is GL's: 0 at the near plane and 1 at the far plane (the default depth
//! range), or the other way round with `reversed`. A surface that declares nothing is
//! compared by its raw depth, which is exactly orthographic with near 0 and far 1.

use serde::{Deserialize, Serialize};

/// `eglQueryString(dpy, EGL_EXTENSIONS)` names this when the attributes below are accepted.
pub const EXTENSION: &str = "EGL_STRATA_surface_projection";
/// Surface attribute: the projection's kind, one of the two values that follow (or
/// `EGL_NONE`, the default: undeclared).
pub const EGL_PROJECTION_STRATA: i32 = 0x3F00;
/// `EGL_PROJECTION_STRATA` value: a perspective projection (`glFrustum`, `gluPerspective`).
pub const EGL_PROJECTION_PERSPECTIVE_STRATA: i32 = 0x3F01;
/// `EGL_PROJECTION_STRATA` value: an orthographic projection (`glOrtho`).
pub const EGL_PROJECTION_ORTHOGRAPHIC_STRATA: i32 = 0x3F02;
/// Surface attribute: the near plane's distance, the bits of an IEEE-754 `float`.
pub const EGL_PROJECTION_NEAR_STRATA: i32 = 0x3F03;
/// Surface attribute: the far plane's distance, the bits of an IEEE-754 `float`
/// (`+inf` allowed for a perspective projection).
pub const EGL_PROJECTION_FAR_STRATA: i32 = 0x3F04;
/// Surface attribute: `EGL_TRUE` when depth is reversed (1 at the near plane, 0 at the far).
pub const EGL_PROJECTION_REVERSED_Z_STRATA: i32 = 0x3F05;

/// The kind of projection a surface declares.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ProjectionKind {
    /// Depth is hyperbolic in eye distance.
    Perspective,
    /// Depth is linear in eye distance.
    Orthographic,
}

/// A declared projection: kind, near and far plane distances (eye space), and whether depth
/// is reversed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Projection {
    /// Perspective or orthographic.
    pub kind: ProjectionKind,
    /// Distance to the near plane.
    pub near: f32,
    /// Distance to the far plane (`inf` for an infinite perspective; JSON, which has no
    /// infinity, writes it as `null`, which reads back as `inf`).
    #[serde(deserialize_with = "far_or_infinity")]
    pub far: f32,
    /// Depth 1 at the near plane and 0 at the far plane.
    #[serde(default)]
    pub reversed: bool,
}

/// Reads a far plane, taking `null` (what JSON writes for an infinite float) as `+inf` in
/// human-readable formats; binary ones (the control socket's) carry the float as it is.
fn far_or_infinity<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    if d.is_human_readable() {
        Ok(Option::<f32>::deserialize(d)?.unwrap_or(f32::INFINITY))
    } else {
        f32::deserialize(d)
    }
}

/// A projection that cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProjectionError {
    /// Near or far is NaN, or far is infinite for an orthographic projection.
    #[error("near {near} and far {far} must be finite (far may be +inf for a perspective projection)")]
    NotFinite {
        /// Near.
        near: f32,
        /// Far.
        far: f32,
    },
    /// A perspective projection needs `0 < near`.
    #[error("a perspective projection needs near > 0, not {0}")]
    NearNotPositive(f32),
    /// `near < far` is needed.
    #[error("near {near} must be less than far {far}")]
    Order {
        /// Near.
        near: f32,
        /// Far.
        far: f32,
    },
    /// A kind was declared without both planes.
    #[error("EGL_PROJECTION_STRATA needs both EGL_PROJECTION_NEAR_STRATA and EGL_PROJECTION_FAR_STRATA")]
    MissingPlanes,
    /// An attribute value that names no kind.
    #[error("EGL_PROJECTION_STRATA {0:#x} is neither EGL_PROJECTION_PERSPECTIVE_STRATA nor EGL_PROJECTION_ORTHOGRAPHIC_STRATA")]
    UnknownKind(i32),
}

impl Projection {
    /// Checks the planes: finite (far may be `+inf` in perspective), `near < far`, and
    /// `near > 0` in perspective.
    pub fn validate(&self) -> Result<(), ProjectionError> {
        let (near, far) = (self.near, self.far);
        let far_ok = far.is_finite() || (far == f32::INFINITY && self.kind == ProjectionKind::Perspective);
        if !near.is_finite() || !far_ok {
            return Err(ProjectionError::NotFinite { near, far });
        }
        if self.kind == ProjectionKind::Perspective && near <= 0.0 {
            return Err(ProjectionError::NearNotPositive(near));
        }
        if near >= far {
            return Err(ProjectionError::Order { near, far });
        }
        Ok(())
    }

    /// The eye-space distance of window depth `d` (clamped to [0, 1]), in f64.
    pub fn eye_depth(&self, d: f64) -> f64 {
        let d = d.clamp(0.0, 1.0);
        let (n, f) = (f64::from(self.near), f64::from(self.far));
        // Reversed depth is used as it is (not as 1 - d), as the shader does.
        match (self.kind, self.reversed) {
            (ProjectionKind::Orthographic, false) => n + d * (f - n),
            (ProjectionKind::Orthographic, true) => f - d * (f - n),
            (ProjectionKind::Perspective, false) if f.is_infinite() => n / (1.0 - d),
            (ProjectionKind::Perspective, true) if f.is_infinite() => n / d,
            (ProjectionKind::Perspective, false) => n * f / (f - d * (f - n)),
            (ProjectionKind::Perspective, true) => n * f / (n + d * (f - n)),
        }
    }

    /// The four numbers the compositor's shader linearises with: kind (0 orthographic, 1
    /// perspective), near, far, reversed (0 or 1). An undeclared surface passes
    /// [`Projection::RAW`], for which the shader's eye depth is the raw depth itself.
    pub fn shader_params(p: Option<&Projection>) -> [f32; 4] {
        match p {
            None => Projection::RAW,
            Some(p) => [
                if p.kind == ProjectionKind::Perspective { 1.0 } else { 0.0 },
                p.near,
                p.far,
                if p.reversed { 1.0 } else { 0.0 },
            ],
        }
    }

    /// Shader parameters under which depth is compared raw: orthographic, near 0, far 1.
    pub const RAW: [f32; 4] = [0.0, 0.0, 1.0, 0.0];

    /// The projection an EGL attribute list declares, if any (`Ok(None)`: none).
    pub fn from_egl_attribs(attribs: &[i32]) -> Result<Option<Projection>, ProjectionError> {
        let (mut kind, mut near, mut far, mut reversed) = (None, None, None, false);
        for pair in attribs.chunks_exact(2) {
            match pair[0] {
                EGL_PROJECTION_STRATA => kind = Some(pair[1]),
                EGL_PROJECTION_NEAR_STRATA => near = Some(f32::from_bits(pair[1] as u32)),
                EGL_PROJECTION_FAR_STRATA => far = Some(f32::from_bits(pair[1] as u32)),
                EGL_PROJECTION_REVERSED_Z_STRATA => reversed = pair[1] != 0,
                0x3038 => break, // EGL_NONE
                _ => {}
            }
        }
        let kind = match kind {
            None | Some(0x3038) => return Ok(None),
            Some(EGL_PROJECTION_PERSPECTIVE_STRATA) => ProjectionKind::Perspective,
            Some(EGL_PROJECTION_ORTHOGRAPHIC_STRATA) => ProjectionKind::Orthographic,
            Some(other) => return Err(ProjectionError::UnknownKind(other)),
        };
        let (Some(near), Some(far)) = (near, far) else { return Err(ProjectionError::MissingPlanes) };
        let p = Projection { kind, near, far, reversed };
        p.validate()?;
        Ok(Some(p))
    }
}

impl Projection {
    /// The attribute list (pairs, without the terminating `EGL_NONE`) that declares this
    /// projection through `EGL_STRATA_surface_projection`.
    pub fn to_egl_attribs(&self) -> [i32; 8] {
        [
            EGL_PROJECTION_STRATA,
            match self.kind {
                ProjectionKind::Perspective => EGL_PROJECTION_PERSPECTIVE_STRATA,
                ProjectionKind::Orthographic => EGL_PROJECTION_ORTHOGRAPHIC_STRATA,
            },
            EGL_PROJECTION_NEAR_STRATA,
            self.near.to_bits() as i32,
            EGL_PROJECTION_FAR_STRATA,
            self.far.to_bits() as i32,
            EGL_PROJECTION_REVERSED_Z_STRATA,
            i32::from(self.reversed),
        ]
    }

    /// What `eglQuerySurface` answers for `attribute` on a surface whose projection in effect
    /// is `p`, or `None` if `attribute` is not one of this extension's. An undeclared surface
    /// answers `EGL_NONE` for the kind and the raw-depth planes (near 0, far 1, not reversed).
    pub fn egl_query(p: Option<&Projection>, attribute: i32) -> Option<i32> {
        let raw = Projection { kind: ProjectionKind::Orthographic, near: 0.0, far: 1.0, reversed: false };
        let q = p.unwrap_or(&raw);
        Some(match attribute {
            EGL_PROJECTION_STRATA => match p.map(|p| p.kind) {
                None => 0x3038, // EGL_NONE
                Some(ProjectionKind::Perspective) => EGL_PROJECTION_PERSPECTIVE_STRATA,
                Some(ProjectionKind::Orthographic) => EGL_PROJECTION_ORTHOGRAPHIC_STRATA,
            },
            EGL_PROJECTION_NEAR_STRATA => q.near.to_bits() as i32,
            EGL_PROJECTION_FAR_STRATA => q.far.to_bits() as i32,
            EGL_PROJECTION_REVERSED_Z_STRATA => i32::from(q.reversed),
            _ => return None,
        })
    }
}

/// Compact, for `stratad ctl list`: `persp 0.1..100`, `ortho 0..1 rev`.
impl std::fmt::Display for Projection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let kind = match self.kind {
            ProjectionKind::Perspective => "persp",
            ProjectionKind::Orthographic => "ortho",
        };
        write!(f, "{kind} {}..{}{}", self.near, self.far, if self.reversed { " rev" } else { "" })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eye_depth_inverts_the_gl_projections() {
        // Eye distance z maps to window depth d by the GL matrices; eye_depth inverts it.
        let (n, f) = (0.5f64, 40.0f64);
        for z in [0.5, 1.0, 3.0, 17.0, 40.0] {
            let persp = (f + n) / (f - n) - 2.0 * f * n / ((f - n) * z); // NDC z
            let ortho = 2.0 * (z - n) / (f - n) - 1.0;
            for (kind, ndc) in [(ProjectionKind::Perspective, persp), (ProjectionKind::Orthographic, ortho)] {
                let p = Projection { kind, near: n as f32, far: f as f32, reversed: false };
                let d = (ndc + 1.0) / 2.0;
                assert!((p.eye_depth(d) - z).abs() < 1e-9 * z, "{kind:?} {z}");
                let r = Projection { reversed: true, ..p };
                assert!((r.eye_depth(1.0 - d) - z).abs() < 1e-9 * z, "reversed {kind:?} {z}");
            }
        }
        let inf = Projection { kind: ProjectionKind::Perspective, near: 1.0, far: f32::INFINITY, reversed: true };
        assert_eq!(inf.eye_depth(1.0), 1.0);
        assert!(inf.eye_depth(0.0).is_infinite());
        assert_eq!(inf.eye_depth(0.5), 2.0);
    }

    #[test]
    fn attribs_parse_and_bad_planes_are_refused() {
        let bits = |v: f32| v.to_bits() as i32;
        let a = [
            EGL_PROJECTION_STRATA,
            EGL_PROJECTION_PERSPECTIVE_STRATA,
            EGL_PROJECTION_NEAR_STRATA,
            bits(0.1),
            EGL_PROJECTION_FAR_STRATA,
            bits(100.0),
            0x3038,
        ];
        let p = Projection::from_egl_attribs(&a).expect("valid").expect("declared");
        assert_eq!((p.kind, p.near, p.far, p.reversed), (ProjectionKind::Perspective, 0.1, 100.0, false));
        assert_eq!(Projection::from_egl_attribs(&[0x3038]), Ok(None));
        assert!(matches!(
            Projection::from_egl_attribs(&[EGL_PROJECTION_STRATA, 7, 0x3038]),
            Err(ProjectionError::UnknownKind(7))
        ));
        assert_eq!(
            Projection::from_egl_attribs(&[EGL_PROJECTION_STRATA, EGL_PROJECTION_ORTHOGRAPHIC_STRATA, 0x3038]),
            Err(ProjectionError::MissingPlanes)
        );
        let bad = |kind, near: f32, far: f32| Projection { kind, near, far, reversed: false }.validate().is_err();
        assert!(bad(ProjectionKind::Perspective, 0.0, 1.0));
        assert!(bad(ProjectionKind::Perspective, 2.0, 1.0));
        assert!(bad(ProjectionKind::Orthographic, 0.0, f32::INFINITY));
        assert!(bad(ProjectionKind::Orthographic, f32::NAN, 1.0));
        assert!(!bad(ProjectionKind::Perspective, 1.0, f32::INFINITY));
        assert!(!bad(ProjectionKind::Orthographic, -1.0, 1.0));
    }

    #[test]
    fn attribs_round_trip_queries_answer_and_rows_print_compactly() {
        let p = Projection { kind: ProjectionKind::Orthographic, near: -1.0, far: 1.0, reversed: true };
        let mut a = p.to_egl_attribs().to_vec();
        a.push(0x3038);
        assert_eq!(Projection::from_egl_attribs(&a), Ok(Some(p)));
        assert_eq!(p.to_string(), "ortho -1..1 rev");
        let inf = Projection { kind: ProjectionKind::Perspective, near: 0.1, far: f32::INFINITY, reversed: false };
        assert_eq!(inf.to_string(), "persp 0.1..inf");
        assert_eq!(Projection::egl_query(Some(&p), EGL_PROJECTION_STRATA), Some(EGL_PROJECTION_ORTHOGRAPHIC_STRATA));
        assert_eq!(Projection::egl_query(Some(&p), EGL_PROJECTION_NEAR_STRATA), Some((-1.0f32).to_bits() as i32));
        assert_eq!(Projection::egl_query(Some(&p), EGL_PROJECTION_REVERSED_Z_STRATA), Some(1));
        assert_eq!(Projection::egl_query(Some(&inf), EGL_PROJECTION_FAR_STRATA), Some(f32::INFINITY.to_bits() as i32));
        assert_eq!(Projection::egl_query(None, EGL_PROJECTION_STRATA), Some(0x3038));
        assert_eq!(Projection::egl_query(None, EGL_PROJECTION_FAR_STRATA), Some(1.0f32.to_bits() as i32));
        assert_eq!(Projection::egl_query(None, EGL_PROJECTION_REVERSED_Z_STRATA), Some(0));
        assert_eq!(Projection::egl_query(Some(&p), 0x3057), None);
        // The control socket's binary encoding carries the planes as they are.
        for q in [p, inf] {
            let bytes = crate::codec::encode_to_vec(&Some(q)).expect("encodes");
            assert_eq!(
                crate::codec::decode_owned::<Option<Projection>>(&bytes, "projection").expect("decodes"),
                Some(q)
            );
        }
    }
}
