//! A client of the daemon through the protocol's Rust client: connecting, a window surface,
//! clearing it, and control requests.

use std::path::Path;

use strata_client::setup::{egl_context, Current, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_protocol::handshake::{ControlReply, ControlRequest};

/// `GL_COLOR_BUFFER_BIT`.
pub const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
/// `GL_SCISSOR_TEST`.
pub const GL_SCISSOR_TEST: u32 = 0x0C11;

/// A client named `name` of the daemon at `socket`.
pub fn connect(socket: &Path, name: &str) -> Connection {
    Connection::connect(&ConnectOptions { socket: socket.into(), name: name.into(), ..Default::default() })
        .expect("connect")
}

/// A context current on a window surface at `rect` (z 0.5) with swap interval `interval`.
pub fn window(gl: &mut Connection, rect: [i32; 4], interval: i32) -> Current {
    let cur = egl_context(gl, 24, 0, SurfaceKind::Window { rect, z: 0.5 }).expect("context");
    gl.eglSwapInterval(cur.display, interval).expect("io").expect("eglSwapInterval");
    cur
}

/// Clears the colour buffer to `c`.
pub fn clear(gl: &mut Connection, c: [u8; 3]) {
    let f = |v: u8| f32::from(v) / 255.0;
    gl.glClearColor(f(c[0]), f(c[1]), f(c[2]), 1.0).expect("io");
    gl.glClear(GL_COLOR_BUFFER_BIT).expect("io");
}

/// The daemon's answer to one control request.
pub fn control(socket: &Path, req: ControlRequest) -> ControlReply {
    ControlConnection::connect_beside(socket).expect("control").request(&req).expect("control request")
}
