//! Transform feedback's capture (ES 3.0). wgpu has no transform feedback, so the vertex stage
//! writes the captured varyings itself: a variant of it ends, after the shader's `main` and
//! before Strata's conventions touch `gl_Position`, by storing each captured value's words into
//! storage buffers, one per buffer binding, at
//! `base + (vertex − first + instance · vertices per instance) · stride`. That is exact because
//! ES 3.0 captures only vertex ranges (no indices) and fixes the primitive mode at
//! `glBeginTransformFeedback`; vertices past the last whole primitive write nothing. The
//! draw's numbers come in a small uniform block of their own.

use std::fmt::Write as _;

use crate::glsl::types::{Scalar, Shader, Ty, Var};

/// The binding of the draw's capture numbers: `strata_capture` (first vertex, vertices per
/// instance, vertices captured per instance) and `strata_base` (each buffer's first word).
pub const PARAMS_BINDING: u32 = 130;
/// The binding of the first capture buffer; the others follow.
pub const FIRST_BUFFER_BINDING: u32 = 131;
/// `GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS`.
pub const MAX_SEPARATE_ATTRIBS: usize = 4;
/// `GL_MAX_TRANSFORM_FEEDBACK_INTERLEAVED_COMPONENTS`.
pub const MAX_INTERLEAVED_COMPONENTS: u32 = 64;
/// `GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_COMPONENTS`: what one varying of a separate capture may
/// have (ES 3.0 asks for 4; the capture stores any number of words, and Mesa offers 64).
pub const MAX_SEPARATE_COMPONENTS: u32 = 64;
/// The bytes of the capture numbers' block.
pub const PARAMS_SIZE: u64 = 32;

/// One captured varying.
#[derive(Debug, Clone, PartialEq)]
pub struct Captured {
    /// Its name as the program asked for it.
    pub name: String,
    /// Its type.
    pub ty: Ty,
    /// Its array length (1 for one value).
    pub size: u32,
    /// The buffer binding it goes to.
    pub buffer: usize,
    /// Its first word in each vertex's record.
    pub offset: u32,
    /// Per word, the GLSL expression of its bits as a `uint`.
    words: Vec<String>,
}

/// What a program captures.
#[derive(Debug, Clone, PartialEq)]
pub struct Capture {
    /// `GL_INTERLEAVED_ATTRIBS` (else `GL_SEPARATE_ATTRIBS`).
    pub interleaved: bool,
    /// The varyings, in the order asked for.
    pub varyings: Vec<Captured>,
    /// Per buffer binding used, the words of one vertex's record.
    pub strides: Vec<u32>,
}

/// A value's words as `uint` bits: `expr` of type `ty`.
fn words_of(expr: &str, ty: Ty) -> Vec<String> {
    let bits = |e: String| match ty.scalar() {
        Scalar::Float => format!("floatBitsToUint({e})"),
        Scalar::Int => format!("uint({e})"),
        _ => e,
    };
    if ty.columns() > 0 {
        let (c, r) = (ty.columns(), ty.rows());
        return (0..c)
            .flat_map(|i| (0..r).map(move |j| (i, j)))
            .map(|(i, j)| bits(format!("{expr}[{i}][{j}]")))
            .collect();
    }
    match ty.components() {
        1 => vec![bits(expr.to_string())],
        n => ["x", "y", "z", "w"][..n].iter().map(|c| bits(format!("{expr}.{c}"))).collect(),
    }
}

/// Resolves the varyings `names` of vertex shader `vs` (`interleaved` or separate): the
/// link's error where one is no output of the stage, is named twice, or they pass the limits.
pub fn resolve(names: &[String], interleaved: bool, vs: &Shader) -> Result<Option<Capture>, String> {
    if names.is_empty() {
        return Ok(None);
    }
    // Each takes a word at least: more cannot fit (and the checks below stay cheap). Separate
    // varyings take a buffer binding each; a program binary may ask for more than there are.
    if names.len() > MAX_INTERLEAVED_COMPONENTS as usize || (!interleaved && names.len() > MAX_SEPARATE_ATTRIBS) {
        return Err(format!("error: more transform feedback varyings than the buffers hold ({})", names.len()));
    }
    let mut varyings: Vec<Captured> = Vec::new();
    let mut strides: Vec<u32> = Vec::new();
    for (i, name) in names.iter().enumerate() {
        if names[..i].contains(name) {
            return Err(format!("error: transform feedback varying '{name}' is named twice"));
        }
        let (base, index) = match name.strip_suffix(']').and_then(|n| n.split_once('[')) {
            Some((b, ix)) => (b, Some(ix.parse::<u32>().map_err(|_| format!("error: '{name}' is no varying"))?)),
            None => (name.as_str(), None),
        };
        // A member of a structure varying is a varying of its own (`s.a` is `s__a`).
        let base = base.replace('.', "__");
        let var = if base == "gl_Position" {
            Some(Var { name: base.clone(), ty: Ty::Vec4, array: None, location: None, flat: false })
        } else {
            vs.varyings.iter().find(|v| v.name == base).cloned()
        };
        let Some(v) = var else {
            return Err(format!("error: transform feedback varying '{name}' is not an output of the vertex shader"));
        };
        let (size, words) = match (v.array, index) {
            (None, None) => (1, words_of(&v.name, v.ty)),
            (Some(n), None) => (n, (0..n).flat_map(|k| words_of(&format!("{}[{k}]", v.name), v.ty)).collect()),
            (Some(n), Some(k)) if k < n => (1, words_of(&format!("{}[{k}]", v.name), v.ty)),
            _ => return Err(format!("error: transform feedback varying '{name}' is out of range")),
        };
        let buffer = if interleaved { 0 } else { i };
        if strides.len() <= buffer {
            strides.resize(buffer + 1, 0);
        }
        let n = words.len() as u32;
        if !interleaved && n > MAX_SEPARATE_COMPONENTS {
            return Err(format!(
                "error: transform feedback varying '{name}' has more than {MAX_SEPARATE_COMPONENTS} components"
            ));
        }
        varyings.push(Captured { name: name.clone(), ty: v.ty, size, buffer, offset: strides[buffer], words });
        strides[buffer] += n;
    }
    if interleaved && strides[0] > MAX_INTERLEAVED_COMPONENTS {
        return Err(format!(
            "error: the transform feedback varyings have more than {MAX_INTERLEAVED_COMPONENTS} components"
        ));
    }
    Ok(Some(Capture { interleaved, varyings, strides }))
}

/// The declarations a capturing vertex stage adds: the numbers' block and the buffers.
pub fn declarations(c: &Capture) -> String {
    let mut s = format!(
        "layout(std140, set = 0, binding = {PARAMS_BINDING}) uniform StrataCapture {{ uvec4 strata_capture; uvec4 strata_base; }};\n"
    );
    for b in 0..c.strides.len() {
        let _ = writeln!(
            s,
            "layout(std430, set = 0, binding = {}) buffer StrataXfb{b} {{ uint strata_xfb{b}[]; }};",
            FIRST_BUFFER_BINDING + b as u32
        );
    }
    s
}

/// The statements that store one vertex's captured words (`points`: in the points stage, where
/// the instance is the vertex); after them, with `discard`, the vertex is put outside the clip
/// volume, so that nothing is rasterized (`GL_RASTERIZER_DISCARD`).
pub fn statements(c: &Capture, points: bool, discard: bool) -> String {
    let vertex = if points { "gl_InstanceIndex" } else { "gl_VertexIndex" };
    let mut s = format!("    {{\n        uint strata_v = uint({vertex}) - strata_capture.x;\n");
    s.push_str("        if (strata_v < strata_capture.z) {\n");
    if !points {
        s.push_str("            strata_v += uint(gl_InstanceIndex) * strata_capture.y;\n");
    }
    let bases = ["x", "y", "z", "w"];
    for v in &c.varyings {
        let (b, stride) = (v.buffer, c.strides[v.buffer]);
        for (k, w) in v.words.iter().enumerate() {
            let _ = writeln!(
                s,
                "            strata_xfb{b}[strata_base.{} + strata_v * {stride}u + {}u] = {w};",
                bases[b],
                v.offset + k as u32
            );
        }
    }
    s.push_str("        }\n    }\n");
    if discard {
        s.push_str("    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);\n");
    }
    s
}

impl Capture {
    /// The words one vertex's record takes in buffer binding `b` (0 where none goes there).
    pub fn stride(&self, b: usize) -> u32 {
        self.strides.get(b).copied().unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vertex shader with four outputs.
    fn shader() -> Shader {
        crate::glsl::compile(
            crate::glsl::Stage::Vertex,
            "#version 300 es\nout vec4 a; out float b; out float c; out float d;\n\
             void main() { a = vec4(1.0); b = 2.0; c = 3.0; d = 4.0; gl_Position = a; }",
        )
        .expect("compiles")
    }

    #[test]
    fn varyings_resolve_to_words_in_their_buffers() {
        let names: Vec<String> = ["a", "gl_Position", "b"].iter().map(|s| s.to_string()).collect();
        let c = resolve(&names, true, &shader()).expect("resolves").expect("captures");
        assert_eq!(c.strides, vec![9]);
        assert_eq!(c.varyings.iter().map(|v| v.offset).collect::<Vec<_>>(), vec![0, 4, 8]);
        let c = resolve(&names, false, &shader()).expect("resolves").expect("captures");
        assert_eq!(c.strides, vec![4, 4, 1]);
    }

    #[test]
    fn more_separate_varyings_than_bindings_fail_the_link() {
        // As a program binary could ask: five separate varyings, four buffer bindings.
        let names: Vec<String> = ["a", "b", "c", "d", "gl_Position"].iter().map(|s| s.to_string()).collect();
        assert!(resolve(&names, false, &shader()).is_err());
        assert!(resolve(&names[..4], false, &shader()).is_ok_and(|c| c.is_some()), "four fit");
        let unknown = vec!["nothing".to_string()];
        assert!(resolve(&unknown, true, &shader()).is_err());
        assert_eq!(resolve(&[], true, &shader()), Ok(None));
    }
}
