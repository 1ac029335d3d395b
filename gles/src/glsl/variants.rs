//! Variants of a linked program's stages that a draw's state selects, made by replacing the
//! generated steps at the end of `main`: the window origin and clip z of `GL_EXT_clip_control`,
//! and a reversed-Z surface's depth. The shader's own code is never touched: the generated
//! steps come last, so each is found as its last occurrence.

use crate::glsl::linked::{Linked, CONVENTIONS, FRAG_DEPTH_OUT, POINT_SIZE_STEP, VERTEX_ID_STEP};
use crate::glsl::translate::{naga_module, Body, Placed};
use crate::glsl::types::Stage;

/// The y step of the conventions: GL's window origin is the lower left, wgpu's the upper left.
const FLIP_Y: &str = "    gl_Position.y = -gl_Position.y;\n";

/// The clip z step of the conventions: GL's clip z range [-w, w] mapped to wgpu's [0, w].
const FORWARD_Z: &str = "    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;\n";

/// The points stage's `gl_PointCoord` for GL's origin: t grows downwards in the window, which
/// is clip y's opposite.
const POINT_T: &str = "strata_PointCoord = vec2(strata_corner.x, 1.0 - strata_corner.y);";

/// `POINT_T` with the upper-left origin, where clip y grows downwards in the window.
const POINT_T_UPPER_LEFT: &str = "strata_PointCoord = vec2(strata_corner.x, strata_corner.y);";

/// [`FRAG_DEPTH_OUT`] for a reversed-Z framebuffer, which stores 1 − GL's window depth.
const FRAG_DEPTH_OUT_REVERSED: &str = "    gl_FragDepth = 1.0 - clamp(strata_FragDepth, 0.0, 1.0);\n";

/// The clip z step a draw's vertex stage ends with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClipZ {
    /// GL's default, `GL_NEGATIVE_ONE_TO_ONE_EXT`: z mapped from [-w, w] to [0, w].
    Forward,
    /// `GL_ZERO_TO_ONE_EXT`: z kept, the clip volume being [0, w] already.
    Direct,
    /// A reversed-Z surface's perspective projection with `near` and `far`.
    Reversed {
        /// The near plane.
        near: f32,
        /// The far plane (`inf` allowed).
        far: f32,
    },
}

/// The clip z of a reversed-Z surface's vertex stage for a perspective projection with
/// `near` and `far` (`inf` allowed): `n·(f − w)/(f − n)`, so that z/w is 1 − the forward
/// window depth for the standard perspective z row, where w is the eye distance. Computed
/// from w alone, it has no cancellation near the far plane, where reversed float depth is
/// most precise. Both clip depth modes give that window depth for their own standard
/// projections, so it serves either.
fn reversed_z(near: f32, far: f32) -> String {
    if far.is_infinite() {
        // The limit f → ∞: z = n, z/w = n/w.
        return format!("    gl_Position.z = {near:?};\n");
    }
    let span = (f64::from(far) - f64::from(near)) as f32;
    format!("    gl_Position.z = {near:?} * ({far:?} - gl_Position.w) / {span:?};\n")
}

/// Translates a generated stage.
fn translate(stage: Stage, text: &str, what: &str) -> Result<naga::Module, String> {
    let none = Body { text: String::new(), lines: Vec::new() };
    std::panic::catch_unwind(|| naga_module(stage, text, &Placed { first_line: usize::MAX, body: &none }))
        .unwrap_or_else(|_| Err(format!("internal error: translating the {what} failed")))
}

impl Linked {
    /// The vertex stage (the points variant with `points`) ending with the given steps: with
    /// `upper_left` (`GL_UPPER_LEFT_EXT`) clip y is not negated, so y points down the window,
    /// and point sprites' t follows; `z` is the clip z step. It trusts a reversed-Z
    /// declaration: the program's projection must have the standard perspective z row for
    /// `near` and `far`.
    pub fn vertex_variant(&self, points: bool, upper_left: bool, z: ClipZ) -> Result<naga::Module, String> {
        self.capturing_variant(points, upper_left, z, None)
    }

    /// Whether the vertex stage reads `gl_VertexID`.
    pub fn reads_vertex_id(&self) -> bool {
        self.vertex_source.contains(VERTEX_ID_STEP)
    }

    /// [`Linked::vertex_variant`], storing the captured varyings first where `capture` is
    /// `Some((discard, unrolled))` (with `discard`, `GL_RASTERIZER_DISCARD`: nothing is
    /// rasterized; `unrolled`: the draw's vertices are gathered in the order they are recorded,
    /// and `gl_VertexID` is the vertex input at [`Linked::point_input`], the vertex's number).
    pub fn capturing_variant(
        &self,
        points: bool,
        upper_left: bool,
        z: ClipZ,
        capture: Option<(bool, bool)>,
    ) -> Result<naga::Module, String> {
        let mut source = if points { self.points_source.clone() } else { self.vertex_source.clone() };
        if let (Some((discard, unrolled)), Some(c)) = (capture, &self.capture) {
            if unrolled && source.contains(VERTEX_ID_STEP) {
                source = source.replacen(VERTEX_ID_STEP, "    strata_VertexID = int(strata_unrolled_id);\n", 1);
                let top = source.find('\n').map_or(0, |n| n + 1);
                let input = format!("layout(location = {}) in uint strata_unrolled_id;\n", self.point_input);
                source.insert_str(top, &input);
            }
            let step = if points { POINT_SIZE_STEP } else { CONVENTIONS };
            let at = source.rfind(step).ok_or("internal error: no place to capture in the vertex stage")?;
            source.insert_str(at, &crate::glsl::capture::statements(c, points, discard));
            let top = source.find('\n').map_or(0, |n| n + 1);
            source.insert_str(top, &crate::glsl::capture::declarations(c));
        }
        let at = source.rfind(CONVENTIONS).ok_or("internal error: no conventions in the vertex stage")?;
        let mut head = source[..at].to_string();
        if upper_left && points {
            if let Some(t) = head.rfind(POINT_T) {
                head.replace_range(t..t + POINT_T.len(), POINT_T_UPPER_LEFT);
            }
        }
        if !upper_left {
            head.push_str(FLIP_Y);
        }
        match z {
            ClipZ::Forward => head.push_str(FORWARD_Z),
            ClipZ::Direct => {}
            ClipZ::Reversed { near, far } => head.push_str(&reversed_z(near, far)),
        }
        head.push_str(&source[at + CONVENTIONS.len()..]);
        translate(Stage::Vertex, &head, "vertex stage's variant")
    }

    /// The fragment stage for a reversed-Z framebuffer when it reads `gl_FragCoord` (whose z
    /// is then 1 − the stored depth, as GL defines it) or writes `gl_FragDepthEXT` (stored as
    /// 1 − it), else `None`: the program's own serves.
    pub fn reversed_fragment(&self) -> Option<Result<naga::Module, String>> {
        let source = self.reversed_fragment_source.as_ref()?;
        Some(translate(Stage::Fragment, source, "reversed-Z fragment stage"))
    }
}

/// The fragment stage `fsrc` (whose shader's own code starts at line `body_line`) for a
/// reversed-Z framebuffer, if it reads `gl_FragCoord` or writes `gl_FragDepthEXT`: the shader
/// reads a copy of `gl_FragCoord` whose z is 1 − the stored depth, GL's window depth, and the
/// depth it writes is stored as 1 − it.
pub(super) fn reversed_fragment_source(fsrc: &str, body_line: usize) -> Option<String> {
    let writes_depth = fsrc.contains(FRAG_DEPTH_OUT);
    if !fsrc.contains("gl_FragCoord") && !writes_depth {
        return None;
    }
    let at = fsrc.match_indices('\n').nth(body_line.checked_sub(1)?)?.0 + 1;
    let body = fsrc[at..].replace("gl_FragCoord", "strata_FragCoord").replace(FRAG_DEPTH_OUT, FRAG_DEPTH_OUT_REVERSED);
    let call = "    strata_main();\n";
    let main = body.rfind(call)?;
    Some(format!(
        "{}vec4 strata_FragCoord;\n{}    strata_FragCoord = vec4(gl_FragCoord.xy, 1.0 - gl_FragCoord.z, \
         gl_FragCoord.w);\n{}",
        &fsrc[..at],
        &body[..main],
        &body[main..]
    ))
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::super::{compile, link};
    use super::*;

    /// A program whose vertex shader writes the forward z step itself.
    fn linked(fs: &str) -> Linked {
        let vs = "attribute vec4 p; void main() { gl_Position = p;
            gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5; gl_PointSize = 2.0; }";
        link(&compile(Stage::Vertex, vs).expect("vs"), &compile(Stage::Fragment, fs).expect("fs"), &HashMap::new(), 16)
            .expect("link")
    }

    #[test]
    fn variants_replace_only_the_generated_steps() {
        assert_eq!(CONVENTIONS, format!("{FLIP_Y}{FORWARD_Z}"));
        let l = linked("precision mediump float; void main() { gl_FragColor = vec4(gl_PointCoord, 0.0, 1.0); }");
        assert!(l.vertex_source.ends_with(&format!("{CONVENTIONS}}}\n")));
        assert!(l.points_source.contains(POINT_T));
        for points in [false, true] {
            for upper_left in [false, true] {
                for z in [
                    ClipZ::Forward,
                    ClipZ::Direct,
                    ClipZ::Reversed { near: 0.1, far: 100.0 },
                    ClipZ::Reversed { near: 0.1, far: f32::INFINITY },
                ] {
                    l.vertex_variant(points, upper_left, z).expect("a variant");
                }
            }
        }
        assert_eq!(reversed_z(0.5, 20.0), "    gl_Position.z = 0.5 * (20.0 - gl_Position.w) / 19.5;\n");
        assert_eq!(reversed_z(0.5, f32::INFINITY), "    gl_Position.z = 0.5;\n");
        assert!(l.reversed_fragment().is_none(), "no gl_FragCoord, no fragment variant");
        let l = linked(
            "precision mediump float; vec4 f() { return vec4(gl_FragCoord.z); } void main() { gl_FragColor = f(); }",
        );
        l.reversed_fragment().expect("a fragment variant").expect("it translates");
    }
}
