//! Per-client quotas against a real daemon: a client that exceeds one of its limits (GPU
//! memory, object counts, surfaces, the size of one command, the daemon's total) gets
//! `GL_OUT_OF_MEMORY` or `EGL_BAD_ALLOC` for that call alone, logged once; it keeps working, the
//! daemon stays up, and another client drawing at the same time sees nothing of it.

mod support;

use std::path::Path;

use strata_client::setup::{egl_context, Current, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::{Blob, Slice};
use support::Daemon;

const GL_NO_ERROR: u32 = 0;
const GL_OUT_OF_MEMORY: u32 = 0x0505;
const GL_TEXTURE_2D: u32 = 0x0DE1;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;
const GL_ARRAY_BUFFER: u32 = 0x8892;
const GL_STATIC_DRAW: u32 = 0x88E4;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const EGL_BAD_ALLOC: i32 = 0x3003;

fn connect(socket: &Path, name: &str) -> (Connection, Current) {
    let mut gl =
        Connection::connect(&ConnectOptions { socket: socket.into(), name: name.into(), ..Default::default() })
            .expect("connect");
    let cur = egl_context(&mut gl, 0, 0, SurfaceKind::Pbuffer { width: 16, height: 16 }).expect("context");
    (gl, cur)
}

fn error(gl: &mut Connection) -> u32 {
    gl.glGetError().expect("io")
}

/// Clears to `c` and reads a pixel back: the client still renders correctly.
fn draws(gl: &mut Connection, c: [u8; 3]) -> bool {
    let f = |v: u8| f32::from(v) / 255.0;
    gl.glClearColor(f(c[0]), f(c[1]), f(c[2]), 1.0).expect("io");
    gl.glClear(GL_COLOR_BUFFER_BIT).expect("io");
    let px = gl.glReadPixels(8, 8, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE).expect("io");
    px.0 == [c[0], c[1], c[2], 255]
}

/// Gives texture `name` a `size`² RGBA8 image (with its mip chain, a third more).
fn texture(gl: &mut Connection, name: u32, size: i32) -> u32 {
    gl.glBindTexture(GL_TEXTURE_2D, name).expect("io");
    gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, size, size, 0, GL_RGBA, GL_UNSIGNED_BYTE, None).expect("io");
    error(gl)
}

fn refusals_logged(daemon: &Daemon, client: &str) -> usize {
    daemon.log_text().lines().filter(|l| l.contains("quota exceeded") && l.contains(client)).count()
}

#[test]
fn a_client_beyond_its_gpu_memory_gets_out_of_memory_and_a_bystander_notices_nothing() {
    let mut daemon = Daemon::start("quota-bytes", &["--quota-gpu-bytes", "8M"]);
    let (mut bystander, _) = connect(&daemon.socket, "bystander");
    let (mut greedy, _) = connect(&daemon.socket, "greedy");
    assert!(draws(&mut bystander, [10, 200, 30]));
    // A 1024² RGBA8 image with its mip chain is about 5.3 MiB: the first fits in 8 MiB.
    assert_eq!(texture(&mut greedy, 1, 1024), GL_NO_ERROR);
    for name in 2..6 {
        assert_eq!(texture(&mut greedy, name, 1024), GL_OUT_OF_MEMORY, "texture {name} is beyond 8 MiB");
        assert!(draws(&mut bystander, [name as u8 * 20, 100, 50]), "the bystander is disturbed");
    }
    // Nothing else changed: the greedy client still renders, and what it holds is within its limit.
    assert!(draws(&mut greedy, [250, 5, 5]));
    let s = support::stats(&daemon.socket);
    let g = s.clients.iter().find(|c| c.name == "greedy").expect("greedy listed");
    assert!(g.gpu_bytes <= 8 << 20 && g.gpu_bytes >= 4 << 20, "greedy holds {} bytes", g.gpu_bytes);
    assert_eq!((g.refusals, g.objects["textures"]), (4, 5));
    // Deleting the texture gives its memory back, and the next allocation fits again.
    greedy.glDeleteTextures(Slice::new(&[1])).expect("io");
    assert_eq!(texture(&mut greedy, 7, 1024), GL_NO_ERROR);
    assert_eq!(refusals_logged(&daemon, "greedy"), 1, "logged once:\n{}", daemon.log_text());
    assert_eq!(refusals_logged(&daemon, "bystander"), 0);
    daemon.assert_running();
}

#[test]
fn object_counts_and_surfaces_are_limited_per_client() {
    let mut daemon = Daemon::start("quota-counts", &["--quota-textures", "4", "--quota-surfaces", "2"]);
    let (mut gl, cur) = connect(&daemon.socket, "counted");
    gl.glGenTextures(Slice::new(&[1, 2, 3])).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR);
    gl.glBindTexture(GL_TEXTURE_2D, 4).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR, "the fourth texture fits");
    gl.glBindTexture(GL_TEXTURE_2D, 5).expect("io");
    assert_eq!(error(&mut gl), GL_OUT_OF_MEMORY, "a fifth texture is beyond the limit");
    assert!(!gl.glIsTexture(5).expect("io"), "the refused texture was not made");
    gl.glGenTextures(Slice::new(&[6, 7])).expect("io");
    assert_eq!(error(&mut gl), GL_OUT_OF_MEMORY);
    gl.glDeleteTextures(Slice::new(&[4])).expect("io");
    gl.glBindTexture(GL_TEXTURE_2D, 5).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR, "deleting one makes room for one");
    // The pbuffer of `connect` is the first surface; a second fits, a third does not.
    let choose = [0x3033, 0x0001, 0x3040, 0x0004, 0x3038];
    let config = gl.eglChooseConfig(cur.display, Slice::new(&choose), 1).expect("io").expect("configs")[0];
    let attribs = [0x3057, 8, 0x3056, 8, 0x3038];
    assert!(gl.eglCreatePbufferSurface(cur.display, config, Slice::new(&attribs)).expect("io").is_ok());
    let third = gl.eglCreatePbufferSurface(cur.display, config, Slice::new(&attribs)).expect("io");
    assert_eq!(third, Err(EGL_BAD_ALLOC));
    assert!(draws(&mut gl, [1, 2, 3]));
    daemon.assert_running();
}

#[test]
fn the_config_file_gives_one_client_more_than_another() {
    let dir = support::TempDir::new("quota-config");
    let config = dir.0.join("stratad.toml");
    std::fs::write(&config, "[[quota]]\nclient = \"ic\"\ntextures = 8\n\n[[quota]]\nclient = \"hu\"\ntextures = 2\n")
        .expect("config");
    let daemon = Daemon::start("quota-config", &["--config", config.to_str().expect("utf-8")]);
    let (mut ic, _) = connect(&daemon.socket, "ic");
    let (mut hu, _) = connect(&daemon.socket, "hu");
    for name in 1..=3 {
        ic.glBindTexture(GL_TEXTURE_2D, name).expect("io");
        hu.glBindTexture(GL_TEXTURE_2D, name).expect("io");
    }
    assert_eq!(error(&mut ic), GL_NO_ERROR, "the IC may have 8");
    assert_eq!(error(&mut hu), GL_OUT_OF_MEMORY, "the HU may have 2");
    let bad = dir.0.join("bad.toml");
    std::fs::write(&bad, "[[quota]]\nclient = \"hu\"\ngpu_bytes = \"lots\"\n").expect("config");
    let out = std::process::Command::new(support::stratad())
        .args(["serve", "--socket"])
        .arg(dir.0.join("unused.sock"))
        .arg("--config")
        .arg(&bad)
        .output()
        .expect("run stratad");
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && text.contains("\"lots\" is not a size"), "{text}");
}

#[test]
fn a_command_beyond_the_size_limit_is_refused_and_the_stream_goes_on() {
    let mut daemon = Daemon::start("quota-command", &["--quota-command-bytes", "64K"]);
    let (mut gl, _) = connect(&daemon.socket, "uploader");
    gl.glBindBuffer(GL_ARRAY_BUFFER, 1).expect("io");
    // One frame of the ring (100 KB), and a message chunked across the 8 MiB ring (20 MB).
    for size in [100_000usize, 20_000_000] {
        let data = vec![7u8; size];
        gl.glBufferData(GL_ARRAY_BUFFER, size as i64, Some(Blob::borrowed(&data)), GL_STATIC_DRAW).expect("io");
        assert_eq!(error(&mut gl), GL_OUT_OF_MEMORY, "{size} bytes exceed 64 KiB");
        assert!(draws(&mut gl, [size as u8, 9, 9]), "the stream goes on after {size} bytes");
    }
    let data = vec![7u8; 60_000];
    gl.glBufferData(GL_ARRAY_BUFFER, 60_000, Some(Blob::borrowed(&data)), GL_STATIC_DRAW).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR, "60 KB fit");
    assert_eq!(refusals_logged(&daemon, "uploader"), 1);
    daemon.assert_running();
}

#[test]
fn all_clients_together_stay_within_the_daemons_total() {
    let daemon = Daemon::start("quota-total", &["--quota-gpu-bytes", "12M", "--quota-total-gpu-bytes", "16M"]);
    let (mut a, _) = connect(&daemon.socket, "first");
    let (mut b, _) = connect(&daemon.socket, "second");
    assert_eq!(texture(&mut a, 1, 1024), GL_NO_ERROR);
    assert_eq!(texture(&mut b, 1, 1024), GL_NO_ERROR);
    assert_eq!(texture(&mut b, 2, 1024), GL_OUT_OF_MEMORY, "within its own 12 MiB, beyond the 16 MiB total");
    let s = support::stats(&daemon.socket);
    assert!(s.gpu_bytes <= 16 << 20, "{} bytes held in all", s.gpu_bytes);
    assert_eq!(s.gpu_bytes_limit, 16 << 20);
    assert!(daemon.log_text().contains("daemon's"), "the refusal names the total");
    drop(a);
    // The first client's memory returns to the pool when it leaves.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
    while support::stats(&daemon.socket).clients.len() > 1 {
        assert!(std::time::Instant::now() < deadline, "the first client never left");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    assert_eq!(texture(&mut b, 2, 1024), GL_NO_ERROR);
}

#[test]
fn query_objects_are_limited_per_context() {
    const MAX_QUERIES: u32 = 16_384;
    const TIMESTAMP: u32 = 0x8E28;
    let mut daemon = Daemon::start("quota-queries", &[]);
    let (mut gl, _) = connect(&daemon.socket, "queries");
    let names: Vec<u32> = (1..=MAX_QUERIES).collect();
    gl.glGenQueriesEXT(Slice::new(&names)).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR, "the limit's worth of names");
    gl.glGenQueriesEXT(Slice::new(&[MAX_QUERIES + 1])).expect("io");
    assert_eq!(error(&mut gl), GL_OUT_OF_MEMORY, "one name more");
    // A counter on a name never generated makes a query, as on Mesa, within the same limit
    // (where the device has timestamps, and so the extension).
    let extensions = gl.glGetString(0x1F03).expect("io").unwrap_or_default();
    if !extensions.contains("GL_EXT_disjoint_timer_query") {
        eprintln!("SKIPPED: the counters (the device has no timestamp queries)");
        return;
    }
    gl.glQueryCounterEXT(MAX_QUERIES + 2, TIMESTAMP).expect("io");
    assert_eq!(error(&mut gl), GL_OUT_OF_MEMORY, "a counter beyond the limit");
    gl.glDeleteQueriesEXT(Slice::new(&[1])).expect("io");
    gl.glQueryCounterEXT(MAX_QUERIES + 2, TIMESTAMP).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR, "room again after a deletion");
    assert!(draws(&mut gl, [40, 80, 120]));
    daemon.assert_running();
}

/// Program pipelines are limited per context (each may keep an executable linked from two
/// programs' stages): `GL_OUT_OF_MEMORY` beyond, and nothing else disturbed.
#[test]
fn program_pipelines_are_limited_per_context() {
    const MAX_PIPELINES: u32 = 4096;
    let mut daemon = Daemon::start("quota-pipelines", &[]);
    let (mut gl, _) = connect(&daemon.socket, "pipelines");
    let names: Vec<u32> = (1..=MAX_PIPELINES).collect();
    gl.glGenProgramPipelinesEXT(Slice::new(&names)).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR, "the limit's worth of names");
    gl.glGenProgramPipelinesEXT(Slice::new(&[MAX_PIPELINES + 1])).expect("io");
    assert_eq!(error(&mut gl), GL_OUT_OF_MEMORY, "one name more");
    gl.glDeleteProgramPipelinesEXT(Slice::new(&[1])).expect("io");
    gl.glGenProgramPipelinesEXT(Slice::new(&[MAX_PIPELINES + 1])).expect("io");
    assert_eq!(error(&mut gl), GL_NO_ERROR, "room again after a deletion");
    assert!(draws(&mut gl, [40, 80, 120]));
    daemon.assert_running();
}

/// A 3D image (`GL_OES_texture_3D`) holds every slice of every level against the quota: a
/// 128×128×64 RGBA8 image with its mip chain (about 4.6 MiB) fits in 8 MiB, a second does not,
/// and the first still draws into a slice.
#[test]
fn three_d_images_count_every_slice() {
    const TEXTURE_3D: u32 = 0x806F;
    let mut daemon = Daemon::start("quota-3d", &["--quota-gpu-bytes", "8M"]);
    let (mut gl, _) = connect(&daemon.socket, "volumes");
    let volume = |gl: &mut Connection, name: u32| {
        gl.glBindTexture(TEXTURE_3D, name).expect("io");
        gl.glTexImage3DOES(TEXTURE_3D, 0, GL_RGBA, 128, 128, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, None).expect("io");
        error(gl)
    };
    assert_eq!(volume(&mut gl, 1), GL_NO_ERROR);
    let s = support::stats(&daemon.socket);
    let c = s.clients.iter().find(|c| c.name == "volumes").expect("listed");
    let levels: u64 = (0..8).map(|l| (128u64 >> l).max(1).pow(2) * (64u64 >> l).max(1) * 4).sum();
    assert!(c.gpu_bytes >= levels && c.gpu_bytes < levels + (1 << 20), "holds {} bytes for {levels}", c.gpu_bytes);
    assert_eq!(volume(&mut gl, 2), GL_OUT_OF_MEMORY, "a second is beyond 8 MiB");
    gl.glBindFramebuffer(0x8D40, 3).expect("io");
    gl.glFramebufferTexture3DOES(0x8D40, 0x8CE0, TEXTURE_3D, 1, 0, 63).expect("io");
    assert_eq!(gl.glCheckFramebufferStatus(0x8D40).expect("io"), 0x8CD5, "the last slice of the first");
    gl.glBindFramebuffer(0x8D40, 0).expect("io");
    assert!(draws(&mut gl, [40, 80, 120]));
    daemon.assert_running();
}

/// Immutable storage (`glTexStorage3D`) reserves every level of every slice before it
/// allocates: two levels of a 128×128×64 RGBA8 image (about 5 MiB) fit in 8 MiB, a second
/// such texture does not and is left without storage (a sub-image into it is refused), and
/// one whose size the device could never hold is refused the same way, the first still a
/// framebuffer attachment that draws.
#[test]
fn immutable_storage_counts_every_level_and_slice_first() {
    const TEXTURE_3D: u32 = 0x806F;
    const RGBA8: u32 = 0x8058;
    const RGBA32F: u32 = 0x8814;
    let mut daemon = Daemon::start("quota-storage", &["--es3", "--quota-gpu-bytes", "8M"]);
    let mut gl = Connection::connect(&ConnectOptions {
        socket: daemon.socket.clone(),
        name: "storage".into(),
        ..Default::default()
    })
    .expect("connect");
    let _cur = strata_client::setup::egl_context_es3(&mut gl, 0, 0, SurfaceKind::Pbuffer { width: 16, height: 16 })
        .expect("an ES 3.0 context");
    let storage = |gl: &mut Connection, name: u32, format: u32, size: i32| {
        gl.glBindTexture(TEXTURE_3D, name).expect("io");
        gl.glTexStorage3D(TEXTURE_3D, 2, format, size, size, 64).expect("io");
        error(gl)
    };
    assert_eq!(storage(&mut gl, 1, RGBA8, 128), GL_NO_ERROR);
    let s = support::stats(&daemon.socket);
    let c = s.clients.iter().find(|c| c.name == "storage").expect("listed");
    let levels: u64 = 128 * 128 * 64 * 4 + 64 * 64 * 32 * 4;
    assert!(c.gpu_bytes >= levels && c.gpu_bytes < levels + (1 << 20), "holds {} bytes for {levels}", c.gpu_bytes);
    assert_eq!(storage(&mut gl, 2, RGBA8, 128), GL_OUT_OF_MEMORY, "a second is beyond 8 MiB");
    gl.glTexSubImage3DOES(TEXTURE_3D, 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, Blob::borrowed(&[0; 4]))
        .expect("io");
    assert_eq!(error(&mut gl), 0x0502, "the refused texture has no levels to write");
    assert_eq!(storage(&mut gl, 3, RGBA32F, 2048), GL_OUT_OF_MEMORY, "2048×2048×64 float texels");
    gl.glBindFramebuffer(0x8D40, 3).expect("io");
    gl.glFramebufferTexture3DOES(0x8D40, 0x8CE0, TEXTURE_3D, 1, 1, 31).expect("io");
    assert_eq!(gl.glCheckFramebufferStatus(0x8D40).expect("io"), 0x8CD5, "the last slice of the second level");
    gl.glBindFramebuffer(0x8D40, 0).expect("io");
    assert!(draws(&mut gl, [40, 80, 120]));
    daemon.assert_running();
}
