//! `GL_EXT_occlusion_query_boolean`: queries over draws hidden behind a nearer quad, partly
//! visible, clipped away by the scissor, absent, and spread over two passes (a framebuffer
//! object drawn between); both targets; the names, the current query and the errors. Every
//! answer is marked as a colour beside the drawn scene. Then `GL_NV_conditional_render` on
//! such answers.

use super::multi_draw::mark_all;
use super::*;

const ANY_SAMPLES_PASSED: u32 = 0x8C2F;
const ANY_SAMPLES_PASSED_CONSERVATIVE: u32 = 0x8D6A;
const CURRENT_QUERY: u32 = 0x8865;
const QUERY_RESULT: u32 = 0x8866;
const QUERY_RESULT_AVAILABLE: u32 = 0x8867;
const LESS: u32 = 0x0201;

/// Something drawn while a query is active.
type Scene<'a> = &'a dyn Fn(Gl<'_>, &mut Names) -> R;
/// A call whose answer (if it has one) and error are marked.
type Call<'a> = &'a dyn Fn(Gl<'_>) -> Result<Vec<u32>, strata_client::ClientError>;

/// A quad over `rect` at depth `z` in one colour.
fn quad(gl: Gl<'_>, n: &mut Names, rect: [f32; 4], z: f32, rgb: [f32; 3]) -> R {
    vertex_quad(gl, n, rect, |x, y| [x, y, z, rgb[0], rgb[1], rgb[2], 1.0])
}

/// The first value of a query, or a sentinel where it answers none.
fn first(v: Vec<u32>) -> u32 {
    v.first().copied().unwrap_or(0xBEEF)
}

fn occlusion(gl: Gl<'_>, n: &mut Names, marks: &mut Vec<u32>) -> R {
    let q: Vec<u32> = (0..6).map(|_| n.next()).collect();
    gl.glGenQueriesEXT(Slice::new(&q))?;
    marks.push(u32::from(gl.glIsQueryEXT(q[0])?));
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(LESS)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    // The occluder: the middle of the window, near.
    quad(gl, n, [-0.5, -0.5, 0.5, 0.5], -0.5, [1.0, 0.0, 0.0])?;
    let scenes: [(u32, Scene<'_>); 5] = [
        // Wholly behind the occluder.
        (ANY_SAMPLES_PASSED, &|gl, n| quad(gl, n, [-0.4, -0.4, 0.4, 0.4], 0.5, [0.0, 1.0, 0.0])),
        // Partly beside it.
        (ANY_SAMPLES_PASSED, &|gl, n| quad(gl, n, [0.3, -0.2, 0.7, 0.2], 0.5, [0.0, 0.0, 1.0])),
        // Nothing drawn.
        (ANY_SAMPLES_PASSED_CONSERVATIVE, &|_, _| Ok(())),
        // Visible, but scissored away.
        (ANY_SAMPLES_PASSED, &|gl, n| {
            gl.glEnable(SCISSOR_TEST)?;
            gl.glScissor(0, 0, 0, 0)?;
            quad(gl, n, [-0.9, -0.9, -0.6, -0.6], 0.0, [1.0, 1.0, 0.0])?;
            gl.glDisable(SCISSOR_TEST)
        }),
        // Hidden in one pass, visible in the next, a framebuffer object drawn between.
        (ANY_SAMPLES_PASSED_CONSERVATIVE, &|gl, n| {
            quad(gl, n, [-0.2, -0.2, 0.2, 0.2], 0.9, [0.0, 1.0, 1.0])?;
            let (fb, tex) = (n.next(), n.next());
            gl.glBindTexture(TEXTURE_2D, tex)?;
            gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, None)?;
            gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
            gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
            gl.glDisable(DEPTH_TEST)?;
            gl.glClear(COLOR_BUFFER_BIT)?;
            gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
            gl.glEnable(DEPTH_TEST)?;
            quad(gl, n, [-0.9, 0.6, -0.6, 0.9], 0.0, [1.0, 0.0, 1.0])
        }),
    ];
    for (i, (target, scene)) in scenes.iter().enumerate() {
        gl.glBeginQueryEXT(*target, q[i])?;
        marks.push(gl.glGetError()?);
        marks.push(first(gl.glGetQueryivEXT(*target, CURRENT_QUERY)?.iter().map(|&v| v as u32).collect()));
        scene(gl, n)?;
        // Its answer cannot be had while it is active.
        marks.push(first(gl.glGetQueryObjectuivEXT(q[i], QUERY_RESULT)?));
        marks.push(gl.glGetError()?);
        gl.glEndQueryEXT(*target)?;
        marks.push(gl.glGetError()?);
    }
    for &id in &q[..5] {
        marks.push(first(gl.glGetQueryObjectuivEXT(id, QUERY_RESULT)?));
        marks.push(first(gl.glGetQueryObjectuivEXT(id, QUERY_RESULT_AVAILABLE)?));
        marks.push(u32::from(gl.glIsQueryEXT(id)?));
    }
    Ok(())
}

/// The errors Mesa answers, in its order.
fn misuse(gl: Gl<'_>, n: &mut Names, marks: &mut Vec<u32>) -> R {
    let (a, b) = (n.next(), n.next());
    gl.glGenQueriesEXT(Slice::new(&[a, b]))?;
    let calls: [Call<'_>; 14] = [
        &|gl| gl.glBeginQueryEXT(0x1234, a).map(|_| vec![]),
        &|gl| gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, 0).map(|_| vec![]),
        &|gl| gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, 777).map(|_| vec![]),
        &|gl| gl.glGetQueryObjectuivEXT(a, QUERY_RESULT),
        &|gl| gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, a).map(|_| vec![]),
        &|gl| gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, b).map(|_| vec![]),
        &|gl| gl.glBeginQueryEXT(ANY_SAMPLES_PASSED_CONSERVATIVE, b).map(|_| vec![]),
        &|gl| {
            gl.glGetQueryivEXT(ANY_SAMPLES_PASSED_CONSERVATIVE, CURRENT_QUERY)
                .map(|v| v.iter().map(|&x| x as u32).collect())
        },
        &|gl| gl.glGetQueryivEXT(ANY_SAMPLES_PASSED, 0x1234).map(|v| v.iter().map(|&x| x as u32).collect()),
        &|gl| gl.glEndQueryEXT(ANY_SAMPLES_PASSED_CONSERVATIVE).map(|_| vec![]),
        &|gl| gl.glEndQueryEXT(ANY_SAMPLES_PASSED).map(|_| vec![]),
        &|gl| gl.glEndQueryEXT(ANY_SAMPLES_PASSED).map(|_| vec![]),
        &|gl| gl.glGetQueryObjectuivEXT(a, 0x1234),
        &|gl| gl.glBeginQueryEXT(ANY_SAMPLES_PASSED_CONSERVATIVE, a).map(|_| vec![]),
    ];
    for call in calls {
        let v = call(gl)?;
        marks.push(first(v));
        marks.push(gl.glGetError()?);
    }
    // Deleting the active query ends it.
    gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, b)?;
    gl.glDeleteQueriesEXT(Slice::new(&[b]))?;
    marks.push(gl.glGetError()?);
    marks.push(first(gl.glGetQueryivEXT(ANY_SAMPLES_PASSED, CURRENT_QUERY)?.iter().map(|&v| v as u32).collect()));
    gl.glEndQueryEXT(ANY_SAMPLES_PASSED)?;
    marks.push(gl.glGetError()?);
    marks.push(u32::from(gl.glIsQueryEXT(b)?));
    Ok(())
}

fn occlusion_queries(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    occlusion(gl, n, &mut marks)?;
    misuse(gl, n, &mut marks)?;
    gl.glDisable(DEPTH_TEST)?;
    mark_all(gl, &marks)?;
    Ok(())
}

/// `GL_NV_conditional_render`: draws and clears on the answers of a hidden and a visible draw's
/// queries, in each mode; the errors marked as colours.
fn conditional_render(gl: Gl<'_>, n: &mut Names) -> R {
    let (hidden, visible, never, idle) = (n.next(), n.next(), n.next(), n.next());
    gl.glGenQueriesEXT(Slice::new(&[hidden, visible, never, idle]))?;
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(LESS)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    quad(gl, n, [-1.0, -1.0, 1.0, 0.0], -0.5, [0.3, 0.3, 0.3])?;
    gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, hidden)?;
    quad(gl, n, [-0.5, -0.9, 0.5, -0.1], 0.5, [1.0, 0.0, 0.0])?;
    gl.glEndQueryEXT(ANY_SAMPLES_PASSED)?;
    gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, visible)?;
    quad(gl, n, [-0.5, 0.1, 0.5, 0.5], 0.5, [0.0, 0.0, 1.0])?;
    gl.glEndQueryEXT(ANY_SAMPLES_PASSED)?;
    gl.glDisable(DEPTH_TEST)?;
    let mut marks = Vec::new();
    // Each mode, on each answer: a quad across the window, and a scissored clear.
    for (i, mode) in (0x8E13..=0x8E16).enumerate() {
        for (j, id) in [hidden, visible].into_iter().enumerate() {
            gl.glBeginConditionalRenderNV(id, mode)?;
            marks.push(gl.glGetError()?);
            let x = -1.0 + (i * 2 + j) as f32 * 0.25;
            quad(gl, n, [x, -1.0, x + 0.2, 1.0], 0.0, [0.0, 1.0, 0.0])?;
            gl.glEnable(SCISSOR_TEST)?;
            gl.glScissor((i * 2 + j) as i32 * 8, 40, 4, 4)?;
            gl.glClearColor(1.0, 1.0, 0.0, 1.0)?;
            gl.glClear(COLOR_BUFFER_BIT)?;
            gl.glDisable(SCISSOR_TEST)?;
            gl.glEndConditionalRenderNV()?;
            marks.push(gl.glGetError()?);
        }
    }
    // A name that is no query, 0, one never begun, a bad mode, one active, twice, and an end
    // with none begun.
    gl.glBeginConditionalRenderNV(999, 0x8E13)?;
    marks.push(gl.glGetError()?);
    gl.glBeginConditionalRenderNV(0, 0x8E13)?;
    marks.push(gl.glGetError()?);
    gl.glBeginConditionalRenderNV(never, 0x8E13)?;
    marks.push(gl.glGetError()?);
    gl.glBeginConditionalRenderNV(visible, 0x1234)?;
    marks.push(gl.glGetError()?);
    gl.glBeginQueryEXT(ANY_SAMPLES_PASSED, idle)?;
    gl.glBeginConditionalRenderNV(idle, 0x8E13)?;
    marks.push(gl.glGetError()?);
    gl.glEndQueryEXT(ANY_SAMPLES_PASSED)?;
    gl.glBeginConditionalRenderNV(visible, 0x8E13)?;
    gl.glBeginConditionalRenderNV(visible, 0x8E13)?;
    marks.push(gl.glGetError()?);
    gl.glEndConditionalRenderNV()?;
    gl.glEndConditionalRenderNV()?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)?;
    Ok(())
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    let c = |name, run| Case { name, run, tol: DEFAULT, expects_error: false };
    vec![c("occlusion_queries", occlusion_queries), c("conditional_render", conditional_render)]
}
