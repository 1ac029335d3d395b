//! `GL_EXT_blend_func_extended`: a second colour per fragment (`gl_SecondaryFragColorEXT`,
//! `gl_SecondaryFragDataEXT`) that the blend factors `GL_SRC1_*` read, over a gradient; the
//! factors in both places and `GL_SRC_ALPHA_SATURATE` as a destination; the built-ins' rules;
//! all as colours.

use super::draw_buffers::compiles;
use super::multi_draw::mark_all;
use super::*;

const SRC1_ALPHA: u32 = 0x8589;
const SRC1_COLOR: u32 = 0x88F9;
const ONE_MINUS_SRC1_COLOR: u32 = 0x88FA;
const ONE_MINUS_SRC1_ALPHA: u32 = 0x88FB;
const MAX_DUAL_SOURCE_DRAW_BUFFERS: u32 = 0x88FC;
const SRC_COLOR: u32 = 0x0300;
const SRC_ALPHA: u32 = 0x0302;
const SRC_ALPHA_SATURATE: u32 = 0x0308;
const ZERO: u32 = 0;
const ONE: u32 = 1;
const FRAGMENT_SHADER: u32 = 0x8B30;
const VERTEX_SHADER: u32 = 0x8B31;

/// The primary colour from the varying, the second one its own pattern.
const FS_DUAL: &str = "#extension GL_EXT_blend_func_extended : require
    precision mediump float; varying vec4 v;
    void main() {
        gl_FragColor = v;
        gl_SecondaryFragColorEXT = vec4(v.g, v.r, 0.5, v.r);
    }";

/// The same through the array forms.
const FS_DUAL_DATA: &str = "#extension GL_EXT_blend_func_extended : enable
    precision mediump float; varying vec4 v;
    void main() {
        gl_FragData[0] = v.bgra;
        gl_SecondaryFragDataEXT[0] = vec4(0.25, v.g, v.b, 1.0 - v.r);
    }";

/// Sets the blend factors, marking the error.
fn func(gl: Gl<'_>, marks: &mut Vec<u32>, f: [u32; 4]) -> R {
    gl.glBlendFuncSeparate(f[0], f[1], f[2], f[3])?;
    marks.push(gl.glGetError()?);
    Ok(())
}

/// A colour gradient over `rect`, unblended.
fn gradient(gl: Gl<'_>, n: &mut Names, rect: [f32; 4]) -> R {
    gl.glDisable(BLEND)?;
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    vertex_quad(gl, n, rect, |x, y| [x, y, 0.0, (x + 1.0) / 2.0, 0.75, (y + 1.0) / 2.0, 0.5])
}

fn blend_func_extended(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = vec![gl.glGetIntegerv(MAX_DUAL_SOURCE_DRAW_BUFFERS)?.first().copied().unwrap_or(-1) as u32];
    marks.push(gl.glGetError()?);
    for f in [
        [SRC1_COLOR, ZERO, SRC1_ALPHA, ZERO],
        [ONE_MINUS_SRC1_COLOR, ZERO, ONE_MINUS_SRC1_ALPHA, ZERO],
        [ZERO, SRC1_COLOR, ZERO, SRC1_ALPHA],
        [ZERO, ONE_MINUS_SRC1_COLOR, ZERO, ONE_MINUS_SRC1_ALPHA],
        [ZERO, SRC_ALPHA_SATURATE, ONE, SRC_ALPHA_SATURATE],
        [0x1234, ZERO, ONE, ZERO],
    ] {
        func(gl, &mut marks, f)?;
    }
    // The built-ins: each colour form pairs with its own second form, only where enabled,
    // only in fragment shaders, and the array has one element.
    let ext = "#extension GL_EXT_blend_func_extended : enable\n";
    for (ty, body) in [
        (FRAGMENT_SHADER, "void main() { gl_FragColor = vec4(0); gl_SecondaryFragColorEXT = vec4(0); }"),
        (FRAGMENT_SHADER, "void main() { gl_FragData[0] = vec4(0); gl_SecondaryFragDataEXT[0] = vec4(0); }"),
        (FRAGMENT_SHADER, "void main() { gl_FragColor = vec4(0); gl_SecondaryFragDataEXT[0] = vec4(0); }"),
        (FRAGMENT_SHADER, "void main() { gl_FragData[0] = vec4(0); gl_SecondaryFragColorEXT = vec4(0); }"),
        (FRAGMENT_SHADER, "void main() { gl_SecondaryFragDataEXT[1] = vec4(0); }"),
        (FRAGMENT_SHADER, "uniform mediump float a[gl_MaxDualSourceDrawBuffersEXT == 1 ? 1 : -1];\nvoid main() { gl_FragColor = vec4(a[0]); }"),
        (VERTEX_SHADER, "void main() { gl_SecondaryFragColorEXT = vec4(0); gl_Position = vec4(0); }"),
    ] {
        marks.push(compiles(gl, n, ty, &format!("{ext}{body}"))?);
    }
    marks.push(compiles(gl, n, FRAGMENT_SHADER, "void main() { gl_SecondaryFragColorEXT = vec4(0); }")?);
    marks.push(compiles(
        gl,
        n,
        FRAGMENT_SHADER,
        "#ifndef GL_EXT_blend_func_extended\n#error x\n#endif\nvoid main() {}",
    )?);
    // Four blends of the second colour over the gradient, one per quadrant.
    gradient(gl, n, [-1.0, -1.0, 1.0, 1.0])?;
    let quadrants = [[-1.0, -1.0, 0.0, 0.0], [0.0, -1.0, 1.0, 0.0], [-1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]];
    let blends = [
        (FS_DUAL, [SRC_COLOR, SRC1_COLOR, ONE, ZERO]),
        (FS_DUAL, [SRC1_ALPHA, ONE_MINUS_SRC1_COLOR, ONE_MINUS_SRC1_ALPHA, SRC1_ALPHA]),
        (FS_DUAL_DATA, [ONE, SRC1_COLOR, ZERO, ONE_MINUS_SRC1_ALPHA]),
        // A dual program blended without its second colour.
        (FS_DUAL_DATA, [SRC_ALPHA, 0x0303, ONE, ONE]),
    ];
    for (rect, (fs, f)) in quadrants.iter().zip(blends) {
        program(gl, n, VS_COLOR, fs, &["pos", "col"])?;
        gl.glEnable(BLEND)?;
        func(gl, &mut marks, f)?;
        vertex_quad(gl, n, *rect, |x, y| [x, y, 0.0, 0.9, (y + 1.0) / 2.0, (x + 1.0) / 2.0, 0.6])?;
        marks.push(gl.glGetError()?);
    }
    // Blending with the second colour into more than one draw buffer is not compared: Mesa's
    // ES 2.0 answers it differently from one call sequence to the next (see the note in
    // docs/architecture.md).
    gl.glDisable(BLEND)?;
    mark_all(gl, &marks)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "blend_func_extended", run: blend_func_extended, tol: DEFAULT, expects_error: false }]
}
