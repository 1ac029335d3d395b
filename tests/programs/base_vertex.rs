//! `GL_OES_draw_elements_base_vertex`: one index list drawn at several base vertices, from an
//! element buffer and from a client-side index array.

use super::*;

/// Three coloured quads' corners in one buffer (position xyz, colour rgba), four vertices each.
pub(super) fn quads_buffer(gl: Gl<'_>, n: &mut Names) -> R {
    let quad = |x0: f32, y0: f32, c: [f32; 4]| -> Vec<f32> {
        [(x0, y0), (x0 + 0.6, y0), (x0, y0 + 0.6), (x0 + 0.6, y0 + 0.6)]
            .iter()
            .flat_map(|&(x, y)| [x, y, 0.0, c[0], c[1], c[2], c[3]])
            .collect()
    };
    let v: Vec<f32> = [
        quad(-0.9, -0.9, [1.0, 0.0, 0.0, 1.0]),
        quad(0.1, -0.9, [0.0, 1.0, 0.0, 1.0]),
        quad(-0.9, 0.1, [0.0, 0.0, 1.0, 1.0]),
        quad(0.1, 0.1, [1.0, 1.0, 0.0, 1.0]),
    ]
    .concat();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)
}

/// Quads 1 and 3 from an element buffer at bases 4 and 12, quad 2 from a client-side index
/// array at base 8; quad 0 (base 0) is left out, so a base ignored draws it instead.
fn draw_elements_base_vertex(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    quads_buffer(gl, n)?;
    let indices: Vec<u8> = [0u16, 1, 2, 1, 3, 2].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &indices)?;
    gl.glDrawElementsBaseVertexOES(TRIANGLES, 6, UNSIGNED_SHORT, 0, 4)?;
    gl.glDrawElementsBaseVertexOES(TRIANGLES, 6, UNSIGNED_SHORT, 0, 12)?;
    gl.glBindBuffer(ELEMENT_ARRAY_BUFFER, 0)?;
    let bytes: Vec<u8> = [0u8, 1, 2, 1, 3, 2].to_vec();
    gl.strataDrawElementsBaseVertexData(TRIANGLES, 6, UNSIGNED_BYTE, Blob::borrowed(&bytes), 8)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "draw_elements_base_vertex", run: draw_elements_base_vertex, tol: DEFAULT, expects_error: false }]
}
