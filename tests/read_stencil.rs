//! `GL_NV_read_stencil` on Strata: `glReadPixels` of `GL_STENCIL_INDEX_OES` as
//! `GL_UNSIGNED_BYTE` answers what the stencil byte of a `GL_DEPTH_STENCIL_OES` read of the
//! same pixels answers. Mesa, the oracle of the depth-stencil read (`tests/programs/
//! read_depth.rs`), refuses stencil reads on ES 2.0 with `GL_INVALID_VALUE`, so this one is
//! checked against that read instead, and against the values drawn.

mod programs;
mod support;

use programs::harness::strata_context;
use programs::{program, vertex_quad, Names, FS_VARY, VS_COLOR};
use strata_client::Calls;
use support::Daemon;

const STENCIL_INDEX: u32 = 0x1901;
const DEPTH_STENCIL: u32 = 0x84F9;
const UNSIGNED_INT_24_8: u32 = 0x84FA;

#[test]
fn stencil_reads_answer_the_stencil_of_depth_stencil_reads() {
    let daemon = Daemon::start("read-stencil", &[]);
    let mut c = strata_context(&daemon.socket, "read-stencil").expect("context");
    let gl = &mut c;
    let mut n = Names::default();
    gl.glClearStencil(0x5a).expect("call");
    gl.glClear(0x0400).expect("call");
    program(gl, &mut n, VS_COLOR, FS_VARY, &["pos", "col"]).expect("program");
    gl.glEnable(0x0B90).expect("call");
    gl.glStencilFunc(0x0207, 0x33, 0xFF).expect("call");
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E01).expect("call");
    // The left half drawn with reference 0x33, the right half left at the clear value.
    vertex_quad(gl, &mut n, [-1.0, -1.0, 0.0, 1.0], |x, y| [x, y, 0.0, 1.0, 1.0, 1.0, 1.0]).expect("draw");
    gl.glPixelStorei(0x0D05, 1).expect("call");
    let stencil = gl.glReadPixels(0, 10, 64, 1, STENCIL_INDEX, 0x1401).expect("read");
    assert_eq!(gl.glGetError().expect("error"), 0);
    let packed = gl.glReadPixels(0, 10, 64, 1, DEPTH_STENCIL, UNSIGNED_INT_24_8).expect("read");
    assert_eq!(gl.glGetError().expect("error"), 0);
    let from_packed: Vec<u8> = packed.0.chunks_exact(4).map(|p| p[0]).collect();
    assert_eq!(stencil.0, from_packed, "the two reads' stencil");
    assert_eq!(&stencil.0[..32], &[0x33; 32][..], "the drawn half");
    assert_eq!(&stencil.0[32..], &[0x5a; 32][..], "the cleared half");
    // Other types are refused, and so is a framebuffer with no stencil.
    let _ = gl.glReadPixels(0, 0, 1, 1, STENCIL_INDEX, 0x1403).expect("read");
    assert_eq!(gl.glGetError().expect("error"), 0x0502);
}
