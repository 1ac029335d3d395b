//! Culling: what an opaque nearer z-group covers is not sampled, and the image is the same, bit
//! for bit, as without culling, and equal to the f64 reference. And the fact it rests on: a
//! surface whose EGL config has no alpha is opaque (GLES 2.0 §4.3.1: without alpha in the
//! framebuffer, the A read back is 1), whatever alpha it was cleared with.

use std::sync::Arc;

use strata_compositor::reference::{self, upload, RefLayer, Uploaded};
use strata_compositor::{Compositor, Layer, Lighting, Mode, NormalSource};
use strata_device::Gpu;
use strata_gles::execute::Executor;
use strata_gles::GlesExecutor;
use strata_protocol::{Calls, Command, Reply};

use super::{check, gpu, output, surface, BACKGROUND, OUT_H, OUT_W};

/// A scene over which `near` lies at z 0.1: a far group (z 0.6) of three overlapping surfaces,
/// one without depth and one a "phantom" (alpha 0 everywhere, depth written near: it hides what
/// lies behind it within its group and shows the background), and a middle group (z 0.3) of
/// two. The near surfaces cover some of these entirely and others in part.
fn scene(near: &[RefLayer]) -> Vec<RefLayer> {
    let mut phantom = surface(3, [30, 14, 30, 30], 0.6, 0, true);
    if let Some(d) = &mut phantom.depth {
        d.iter_mut().for_each(|v| *v = 0.05);
    }
    let mut v = vec![
        surface(0, [0, 0, 70, 50], 0.6, 255, true),
        surface(1, [20, 10, 50, 40], 0.6, 255, false),
        phantom,
        surface(4, [6, 4, 30, 24], 0.3, 200, true),
        surface(5, [60, 30, 30, 30], 0.3, 255, true),
    ];
    v.extend(near.iter().cloned());
    v
}

/// Two opaque surfaces at z 0.1 whose depth planes cross: surface 4's rectangle lies inside
/// their union, the others only in part.
fn near_opaque() -> Vec<RefLayer> {
    vec![surface(7, [2, 2, 30, 30], 0.1, 255, true), surface(8, [20, 0, 30, 36], 0.1, 255, true)]
}

/// Composites `layers` (those flagged in `opaque` marked opaque) with `comp`.
fn run(gpu: &Arc<Gpu>, comp: &mut Compositor, layers: &[RefLayer], opaque: &[bool], light: &Lighting) -> Vec<u8> {
    let up: Vec<Uploaded> = layers.iter().map(|l| upload(gpu, l)).collect();
    let gl: Vec<Layer<'_>> = layers
        .iter()
        .zip(&up)
        .enumerate()
        .map(|(i, (l, u))| Layer { opaque: opaque.get(i).copied().unwrap_or(false), ..u.layer(l) })
        .collect();
    let out = output(gpu);
    comp.composite(&gl, light, &out, BACKGROUND, None).expect("composite");
    gpu.read_rgba8(&out, [0, 0, OUT_W, OUT_H]).expect("readback")
}

#[test]
fn culling_changes_nothing_but_the_work() {
    let Some(gpu) = gpu() else { return };
    let layers = scene(&near_opaque());
    // Every surface whose alpha is 255 everywhere may be marked opaque; the phantom (alpha 0)
    // and surface 4 (alpha 200) may not.
    let opaque: Vec<bool> = layers.iter().map(|l| l.color.chunks(4).all(|p| p[3] == 255)).collect();
    assert_eq!(opaque, [true, true, false, false, true, true, true]);
    let unlit = Lighting { enabled: false, ..Lighting::default() };
    let per_surface = Lighting::default();
    let from_depth = Lighting { normals: NormalSource::FromDepth, ..Lighting::default() };
    for (name, light, tol) in [("unlit", unlit, 0), ("lit", per_surface, 1), ("lit from depth", from_depth, 1)] {
        let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
        // 4 textures a pass: the far group chains where its three surfaces overlap.
        for limit in [None, Some(4)] {
            let mut off = Compositor::new(gpu.clone(), limit).expect("compositor").with_culling(false);
            let mut on = Compositor::new(gpu.clone(), limit).expect("compositor");
            assert!(on.culling() && !off.culling(), "culling is on by default");
            let img_off = run(&gpu, &mut off, &layers, &opaque, &light);
            let img_on = run(&gpu, &mut on, &layers, &opaque, &light);
            check(&format!("{name}, {limit:?}, culling off"), &img_off, &want, tol);
            assert!(img_on == img_off, "{name}, {limit:?}: culling changed the image");
            assert_eq!(off.last_stats.culled, 0, "{name}: nothing culled with culling off");
            assert!(on.last_stats.culled > 0, "{name}, {limit:?}: nothing culled: {:?}", on.last_stats);
            assert_eq!(on.last_passes, off.last_passes, "the thesis' pass count is the scene's");
        }
    }
    // The 2D baseline copies only what is on top already: the switch changes nothing there.
    let mut on = Compositor::new(gpu.clone(), None).expect("compositor").with_mode(Mode::TwoD);
    let mut off = Compositor::new(gpu.clone(), None).expect("compositor").with_mode(Mode::TwoD).with_culling(false);
    let unlit = Lighting { enabled: false, ..Lighting::default() };
    assert!(run(&gpu, &mut on, &layers, &opaque, &unlit) == run(&gpu, &mut off, &layers, &opaque, &unlit));
}

#[test]
fn transparent_nearer_surfaces_do_not_cull() {
    let Some(gpu) = gpu() else { return };
    let light = Lighting::default();
    // The same near surfaces with alpha 150: what lies beneath shows through them.
    let near: Vec<RefLayer> =
        [(7, [2, 2, 30, 30]), (8, [20, 0, 30, 36])].into_iter().map(|(i, r)| surface(i, r, 0.1, 150, true)).collect();
    let layers = scene(&near);
    let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
    // Only the farthest group's surfaces are opaque: nothing lies beneath them.
    let img = run(&gpu, &mut comp, &layers, &[true, true, false, false, false, false, false], &light);
    check("transparent near group", &img, &reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light), 1);
    assert_eq!(comp.last_stats.culled, 0, "a transparent group hides nothing: {:?}", comp.last_stats);
    // One opaque and one transparent near surface: culling only where the opaque one alone
    // covers (x 2..20), never where the transparent one may be selected.
    let mixed = vec![near_opaque()[0].clone(), near[1].clone()];
    let layers = scene(&mixed);
    let opaque = [true, true, false, false, true, true, false];
    let want = reference::composite(&layers, OUT_W, OUT_H, BACKGROUND, &light);
    let img = run(&gpu, &mut comp, &layers, &opaque, &light);
    assert!(comp.last_stats.culled > 0);
    check("mixed near group", &img, &want, 1);
    let mut off = Compositor::new(gpu.clone(), None).expect("compositor").with_culling(false);
    assert!(run(&gpu, &mut off, &layers, &opaque, &light) == img, "mixed near group: culling changed the image");
}

/// Runs commands on a `GlesExecutor` as the daemon does for a client.
struct Client(GlesExecutor);

/// Why a call of [`Client`] failed.
struct CallError(String);

impl std::fmt::Debug for CallError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<strata_protocol::ReplyMismatch> for CallError {
    fn from(e: strata_protocol::ReplyMismatch) -> CallError {
        CallError(e.to_string())
    }
}

impl Calls for Client {
    type Error = CallError;

    fn send(&mut self, cmd: &Command<'_>) -> Result<(), CallError> {
        self.0.execute(cmd.clone()).map(|_| ()).map_err(|e| CallError(e.0))
    }

    fn call(&mut self, cmd: &Command<'_>) -> Result<Reply, CallError> {
        self.0.execute(cmd.clone()).map_err(|e| CallError(e.0))?.ok_or_else(|| CallError("no reply".into()))
    }
}

#[test]
fn a_surface_without_alpha_is_opaque() {
    let Some(gpu) = gpu() else { return };
    use strata_protocol::Slice;
    let scene = Arc::new(strata_scene::Scene::new(2, Lighting::default()));
    let mut c = Client(GlesExecutor::new(gpu.clone()).with_scene(scene.clone(), 1, "alpha"));
    let d = c.eglGetDisplay(0).expect("display");
    c.eglInitialize(d).expect("call").expect("initialise");
    let ctx_attribs = [0x3098, 2, 0x3038];
    // Config 2 has 8 alpha bits, config 5 none (both without depth). Each is cleared to
    // transparent red; surface 5 lies nearer, over the left half of surface 2.
    let mut read = Vec::new();
    for (config, x, z) in [(2u32, 0, 0.5f32), (5, -48, 0.2)] {
        let s = c
            .eglCreateWindowSurface(d, config, 0, x, 0, z, OUT_W as i32, OUT_H as i32, Slice::new(&[0x3038]))
            .expect("call")
            .expect("window surface");
        let ctx = c.eglCreateContext(d, config, 0, Slice::new(&ctx_attribs)).expect("call").expect("context");
        c.eglMakeCurrent(d, s, s, ctx).expect("call").expect("current");
        c.glClearColor(1.0, 0.0, 0.0, 0.0).expect("clear colour");
        c.glClear(0x4000).expect("clear");
        let px = c.glReadPixels(0, 0, 1, 1, 0x1908, 0x1401).expect("read pixels");
        read.push(px.0);
        c.eglSwapBuffers(d, s).expect("call").expect("swap");
    }
    // GLES 2.0 §4.3.1: reading a colour buffer without alpha gives A = 1.
    assert_eq!(read, [vec![255, 0, 0, 0], vec![255, 0, 0, 255]], "glReadPixels after the clear");
    // A frame is published once its work has completed on the client's device.
    let start = std::time::Instant::now();
    while scene.rows().iter().any(|r| r.frames == 0) {
        assert!(start.elapsed() < std::time::Duration::from_secs(10), "the swapped frames were never published");
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    let out = output(&gpu);
    let ((img, opaque, culled), _, _) = scene
        .compose(strata_scene::Part::All, |surfaces, _, _| {
            let layers: Vec<Layer<'_>> = surfaces
                .iter()
                .map(|s| Layer {
                    rect: s.rect,
                    z: s.z,
                    color: s.color.as_ref().expect("presented"),
                    depth: s.depth.as_ref(),
                    normal: s.normal,
                    projection: strata_protocol::projection::Projection::RAW,
                    opaque: s.opaque,
                    props: Default::default(),
                })
                .collect();
            let mut comp = Compositor::new(gpu.clone(), None).expect("compositor");
            let unlit = Lighting { enabled: false, ..Lighting::default() };
            comp.composite(&layers, &unlit, &out, BACKGROUND, None).expect("composite");
            let opaque: Vec<bool> = surfaces.iter().map(|s| s.opaque).collect();
            (gpu.read_rgba8(&out, [0, 0, OUT_W, OUT_H]).expect("readback"), opaque, comp.last_stats.culled)
        })
        .expect("scene");
    assert_eq!(opaque, [false, true], "only the surface of the alpha-less config is opaque");
    assert_eq!(culled, 1, "surface 2 is left out where surface 5 covers it");
    // Where surface 5 lies (x < 48): opaque red. Elsewhere surface 2's transparent red shows
    // the background (51, 102, 153).
    for (x, want) in
        [(0u32, [255, 0, 0, 255]), (47, [255, 0, 0, 255]), (48, [51, 102, 153, 255]), (95, [51, 102, 153, 255])]
    {
        let at = ((10 * OUT_W + x) * 4) as usize;
        assert_eq!(img[at..at + 4], want, "x {x}");
    }
}
