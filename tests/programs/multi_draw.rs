//! `GL_EXT_multi_draw_arrays` (`glMultiDrawArraysEXT`, `glMultiDrawElementsEXT`) and, with
//! `GL_OES_draw_elements_base_vertex`, `glMultiDrawElementsBaseVertexEXT`: several draws from
//! one call, and the errors each call gives, drawn as colours. `GL_EXT_draw_elements_base_vertex`
//! gives the base-vertex draws EXT names; the drop-in library sends them as the same commands.

use super::base_vertex::quads_buffer;
use super::*;

/// Marks `e`, the error (or value) after call `i`, as a colour in a 4×4 cell: 16 cells a row,
/// rows down from the top edge.
pub(super) fn mark_error(gl: Gl<'_>, i: i32, e: u32) -> R {
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(i % 16 * 4, H - 4 - i / 16 * 4, 4, 4)?;
    // The low 16 bits, 6 + 6 + 4 to a channel and spread out, so that values differing in
    // their last bit differ by more than the comparison's tolerance.
    let (r, g, b) = ((e & 0x3F) << 2, ((e >> 6) & 0x3F) << 2, ((e >> 12) & 0xF) << 4);
    gl.glClearColor(r as f32 / 255.0, g as f32 / 255.0, b as f32 / 255.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glDisable(SCISSOR_TEST)
}

/// Marks each of `marks` (errors or values) in its cell, in order.
pub(super) fn mark_all(gl: Gl<'_>, marks: &[u32]) -> R {
    for (i, &e) in marks.iter().enumerate() {
        mark_error(gl, i as i32, e)?;
    }
    Ok(())
}

/// Quads 0, 2 and 3 as strips from one call (quad 1's draw has count 0, and a draw count of
/// two leaves a third entry unread).
fn multi_draw_arrays(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    quads_buffer(gl, n)?;
    gl.glMultiDrawArraysEXT(TRIANGLE_STRIP, Slice::new(&[0, 4, 8]), Slice::new(&[4, 0, 4]), 3)?;
    gl.glMultiDrawArraysEXT(TRIANGLE_STRIP, Slice::new(&[12, 4]), Slice::new(&[4, 4]), 1)
}

/// Two index lists at two offsets in one element buffer, drawn in one call, then again at
/// base vertices 4 and 8 (the second list is quad 0's upper triangle).
fn multi_draw_elements(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    quads_buffer(gl, n)?;
    let indices: Vec<u8> = [0u16, 1, 2, 1, 3, 2, 1, 3, 2].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &indices)?;
    gl.glMultiDrawElementsEXT(TRIANGLES, Slice::new(&[3, 3]), UNSIGNED_SHORT, Slice::new(&[0, 12]), 2)?;
    let (counts, offsets) = (Slice::new(&[6, 3]), Slice::new(&[0u64, 12]));
    gl.glMultiDrawElementsBaseVertexEXT(TRIANGLES, counts, UNSIGNED_SHORT, offsets, 2, Slice::new(&[12, 8]))
}

/// Every multi-draw's errors: a negative draw count (before a bad mode), a bad mode or index
/// type, a negative count in any entry. (A negative first is no error either, and what Mesa
/// then draws is undefined, so it is not compared.)
fn multi_draw_errors(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    quads_buffer(gl, n)?;
    let indices: Vec<u8> = [0u16, 1, 2].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &indices)?;
    let (first, count, bad) = (Slice::new(&[0, 4]), Slice::new(&[3, 3]), Slice::new(&[3, -1]));
    let offsets = Slice::new(&[0u64, 0]);
    let bases = Slice::new(&[4, 8]);
    let mut i = 0;
    let mut check = |gl: Gl<'_>| -> R {
        let e = gl.glGetError()?;
        mark_error(gl, i, e)?;
        i += 1;
        Ok(())
    };
    for (mode, drawcount) in [(TRIANGLES, 2), (TRIANGLES, -1), (0x20, 1), (0x20, -1), (0x20, 0)] {
        gl.glMultiDrawArraysEXT(mode, first.clone(), count.clone(), drawcount)?;
        check(gl)?;
        gl.glMultiDrawElementsEXT(mode, count.clone(), UNSIGNED_SHORT, offsets.clone(), drawcount)?;
        check(gl)?;
        gl.glMultiDrawElementsBaseVertexEXT(
            mode,
            count.clone(),
            UNSIGNED_SHORT,
            offsets.clone(),
            drawcount,
            bases.clone(),
        )?;
        check(gl)?;
    }
    gl.glMultiDrawArraysEXT(TRIANGLES, first.clone(), bad.clone(), 2)?;
    check(gl)?;
    gl.glMultiDrawArraysEXT(TRIANGLES, first.clone(), bad.clone(), 1)?;
    check(gl)?;
    for ty in [UNSIGNED_SHORT, FLOAT] {
        gl.glMultiDrawElementsEXT(TRIANGLES, bad.clone(), ty, offsets.clone(), 2)?;
        check(gl)?;
        gl.glMultiDrawElementsBaseVertexEXT(TRIANGLES, bad.clone(), ty, offsets.clone(), 2, bases.clone())?;
        check(gl)?;
        gl.glMultiDrawElementsEXT(TRIANGLES, count.clone(), ty, offsets.clone(), 0)?;
        check(gl)?;
    }
    Ok(())
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![
        Case { name: "multi_draw_arrays", run: multi_draw_arrays, tol: DEFAULT, expects_error: false },
        Case { name: "multi_draw_elements", run: multi_draw_elements, tol: DEFAULT, expects_error: false },
        Case { name: "multi_draw_errors", run: multi_draw_errors, tol: DEFAULT, expects_error: false },
    ]
}
