//! Compositor throughput: k = 1…16 full-output surfaces at one z, composited per fragment
//! (lit by default), at a chaining limit (`--max-textures`, default 8 as on the thesis' i.MX6)
//! and at the device's limit.
//!
//! The floor is physical and measured in the same run: the time the same device needs to move
//! the bytes a composite must read and write, as `copy_texture_to_texture` of that many bytes
//! (in units of one output-sized RGBA8 image). A composite must write the output once and read,
//! per pixel, the one surface's colour where one surface covers it (plus its depth when
//! normals come from depth), and where k surfaces overlap every depth and the winner's colour.
//! CPU memcpy of the same bytes is printed beside it as a second reference.
//!
//! The shader floor is measured on the same device too (`floor`): one pass that loads every
//! surface's colour and depth and keeps the nearest. On a CPU rasterizer the copy floor says
//! little (the per-fragment shader is the cost); actual over the shader floor shows what
//! lighting, chaining and planning add.

mod floor;

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{bail, Result};
use indicatif::{ProgressBar, ProgressStyle};
use strata_compositor::{Compositor, CompositorError, Layer, Lighting, NormalSource};
use strata_device::Gpu;

use crate::plot::{line_plot, Series};

/// `strata-bench composite` options.
#[derive(clap::Args)]
pub struct Args {
    /// Output width.
    #[arg(long, default_value_t = 1920)]
    width: u32,
    /// Output height.
    #[arg(long, default_value_t = 720)]
    height: u32,
    /// Fewest surfaces.
    #[arg(long, default_value_t = 1)]
    min_surfaces: usize,
    /// Most surfaces.
    #[arg(long, default_value_t = 16)]
    max_surfaces: usize,
    /// The chaining limit measured beside the device's.
    #[arg(long, default_value_t = 8)]
    max_textures: u32,
    /// Timed frames per point.
    #[arg(long, default_value_t = 8)]
    frames: u32,
    /// Lighting off (the composite is then a select and a copy).
    #[arg(long)]
    unlit: bool,
    /// Normals reconstructed from depth instead of per surface.
    #[arg(long)]
    from_depth: bool,
    /// Where to write the curve (JSON) and its plot (PNG, same name).
    #[arg(long, default_value = "target/strata-bench/composite.json")]
    out: PathBuf,
    /// Print only the final JSON line.
    #[arg(long)]
    json: bool,
}

struct Surface {
    color: wgpu::TextureView,
    depth: wgpu::TextureView,
}

/// A `w`×`h` 2D texture of one level.
pub(crate) fn texture(
    gpu: &Gpu,
    w: u32,
    h: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    gpu.texture_2d("bench image", format, (w, h), usage)
}

/// Surface `i`: a colour gradient and a tilted depth plane, so the surfaces intersect.
fn make_surface(gpu: &Gpu, i: usize, w: u32, h: u32) -> Surface {
    let mut rgba = vec![0u8; (w * h * 4) as usize];
    let mut depth = vec![0f32; (w * h) as usize];
    let (a, b) = ((i as f32 * 0.7).sin() * 0.4, (i as f32 * 1.3).cos() * 0.4);
    for y in 0..h {
        for x in 0..w {
            let (u, v) = (x as f32 / w as f32, y as f32 / h as f32);
            let p = ((y * w + x) * 4) as usize;
            rgba[p..p + 4].copy_from_slice(&[(u * 255.0) as u8, (v * 255.0) as u8, (i * 15) as u8, 255]);
            depth[(y * w + x) as usize] = (0.5 + a * (u - 0.5) + b * (v - 0.5)).clamp(0.0, 1.0);
        }
    }
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let c = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    gpu.write_texture(
        c.as_image_copy(),
        &rgba,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * 4), rows_per_image: None },
        c.size(),
    );
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
    let d = texture(gpu, w, h, wgpu::TextureFormat::Depth32Float, usage);
    strata_scene::depth::Depth::of(gpu).write(&d, w, h, &depth);
    Surface { color: c.create_view(&Default::default()), depth: d.create_view(&Default::default()) }
}

/// The median of `frames` timings of `f` (after one warm-up), in milliseconds; the median
/// resists other load on a shared machine.
pub(crate) fn median_ms(frames: u32, mut f: impl FnMut()) -> f64 {
    f();
    let mut times: Vec<f64> = (0..frames)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// [`median_ms`] of a call that can fail: the first error instead, if any call failed.
pub(crate) fn try_median_ms<E>(frames: u32, mut f: impl FnMut() -> Result<(), E>) -> Result<f64, E> {
    let mut failed = None;
    let ms = median_ms(frames, || {
        if let Err(e) = f() {
            failed.get_or_insert(e);
        }
    });
    failed.map_or(Ok(ms), Err)
}

/// Milliseconds per composite of `surfaces`.
fn time_composite(
    gpu: &Gpu,
    comp: &mut Compositor,
    surfaces: &[Surface],
    out: &wgpu::Texture,
    light: &Lighting,
    frames: u32,
) -> Result<f64, CompositorError> {
    let (w, h) = (out.width() as i32, out.height() as i32);
    let layers: Vec<Layer<'_>> = surfaces
        .iter()
        .map(|s| Layer {
            rect: [0, 0, w, h],
            z: 0.5,
            color: &s.color,
            depth: Some(&s.depth),
            normal: [0.0, 0.0, 1.0],
            projection: strata_protocol::projection::Projection::RAW,
            opaque: false,
            props: Default::default(),
        })
        .collect();
    try_median_ms(frames, || {
        comp.composite(&layers, light, out, [0.0, 0.0, 0.0, 1.0], None)?;
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        Ok(())
    })
}

/// Milliseconds the device takes to copy one `w`×`h` RGBA8 image (`copy_texture_to_texture`,
/// eight per submission so that submitting costs little).
fn device_copy_ms(gpu: &Gpu, w: u32, h: u32, frames: u32) -> f64 {
    let usage = wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST;
    let a = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    let b = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    const PER_SUBMIT: u32 = 8;
    median_ms(frames, || {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        for i in 0..PER_SUBMIT {
            let (src, dst) = if i % 2 == 0 { (&a, &b) } else { (&b, &a) };
            enc.copy_texture_to_texture(src.as_image_copy(), dst.as_image_copy(), a.size());
        }
        gpu.submit(&gpu.lane, vec![enc.finish()]);
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
    }) / f64::from(PER_SUBMIT)
}

/// One measured point.
#[derive(serde::Serialize)]
struct Point {
    max_textures: u32,
    k: usize,
    passes: usize,
    ms_per_frame: f64,
    device_floor_ms: f64,
    memcpy_floor_ms: f64,
    /// The shader floor (`None` where the device cannot sample every surface in one pass).
    shader_floor_ms: Option<f64>,
}

/// Runs the benchmark and prints its report; the last line is JSON.
pub fn run(args: &Args) -> Result<()> {
    let (w, h) = (args.width, args.height);
    if args.max_surfaces == 0 || args.min_surfaces == 0 || args.frames == 0 || w == 0 || h == 0 {
        bail!("--min-surfaces, --max-surfaces, --frames and the output size must be positive");
    }
    let ks = args.min_surfaces..=args.max_surfaces.max(args.min_surfaces);
    let gpu: Arc<Gpu> = Gpu::open()?;
    let device_limit = gpu.limits.max_sampled_textures_per_shader_stage;
    let mut limits = vec![args.max_textures];
    if device_limit != args.max_textures {
        limits.push(device_limit);
    }
    let light = Lighting {
        enabled: !args.unlit,
        normals: if args.from_depth { NormalSource::FromDepth } else { NormalSource::PerSurface },
        ..Lighting::default()
    };
    let quiet = args.json;
    let bar = |len: u64, msg: &'static str| {
        let pb = if quiet { ProgressBar::hidden() } else { ProgressBar::new(len) };
        pb.set_style(
            ProgressStyle::with_template("{msg:>22} [{bar:40}] {pos}/{len} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        pb.set_message(msg);
        pb
    };
    let n = *ks.end();
    let pb = bar(n as u64, "uploading surfaces");
    let surfaces: Vec<Surface> = (0..n)
        .map(|i| {
            pb.inc(1);
            make_surface(&gpu, i, w, h)
        })
        .collect();
    pb.finish();
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let out = texture(&gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    // The floors: one output-sized RGBA8 image copied by the device, and by memcpy.
    let image = u64::from(w) * u64::from(h) * 4;
    let copy_ms = device_copy_ms(&gpu, w, h, 4 * args.frames);
    let memcpy_gbps = crate::transport::memcpy_gbps(image as usize, 40, &bar(40, "memcpy"));
    let memcpy_ms = image as f64 / (memcpy_gbps * 1e9) * 1e3;
    // Images a composite of k full-output surfaces must move: the output written, and read
    // the one colour (and depth, for normals from depth), or every depth and one colour.
    let lit_depth = light.enabled && light.normals == NormalSource::FromDepth;
    let images = |k: usize| -> u64 {
        if k == 1 {
            2 + u64::from(lit_depth)
        } else {
            k as u64 + 2
        }
    };
    // The shader floor of each k, on the same device.
    let pb = bar(ks.clone().count() as u64, "shader floor");
    let out_view = out.create_view(&Default::default());
    let shader_floor: Vec<Option<f64>> = ks
        .clone()
        .map(|k| {
            pb.inc(1);
            let f = floor::Floor::new(&gpu, k, wgpu::TextureFormat::Rgba8Unorm)?;
            let views: Vec<_> = surfaces[..k].iter().map(|s| (&s.color, &s.depth)).collect();
            Some(median_ms(args.frames, || f.run(&gpu, &views, &out_view)))
        })
        .collect();
    pb.finish();
    let shader = |k: usize| shader_floor.get(k - *ks.start()).copied().flatten();
    let mut points = Vec::new();
    for &m in &limits {
        let mut comp = Compositor::new(gpu.clone(), Some(m))?;
        let pb = bar(ks.clone().count() as u64, if m == device_limit { "device limit" } else { "--max-textures" });
        for k in ks.clone() {
            let ms = time_composite(&gpu, &mut comp, &surfaces[..k], &out, &light, args.frames)?;
            points.push(Point {
                max_textures: m,
                k,
                passes: comp.last_passes,
                ms_per_frame: ms,
                device_floor_ms: images(k) as f64 * copy_ms,
                memcpy_floor_ms: images(k) as f64 * memcpy_ms,
                shader_floor_ms: shader(k),
            });
            pb.inc(1);
        }
        pb.finish();
    }
    let lighting = match (light.enabled, lit_depth) {
        (false, _) => "unlit",
        (true, false) => "lit, per-surface normals",
        (true, true) => "lit, normals from depth",
    };
    if !quiet {
        println!("composite {w}x{h}, {lighting}, k surfaces at one z");
        println!(
            "device copy of one {w}x{h} RGBA8 image: {copy_ms:.3} ms; memcpy of it: {memcpy_ms:.3} ms ({memcpy_gbps:.2} GB/s), same run"
        );
        println!(
            "{:>5} {:>3} {:>7} {:>10} {:>10} {:>12} {:>10} {:>12} {:>10} {:>13}",
            "limit",
            "k",
            "passes",
            "ms/frame",
            "copy ms",
            "actual/copy",
            "memcpy ms",
            "memcpy/act.",
            "shader ms",
            "actual/shader"
        );
        for p in &points {
            let opt = |v: Option<f64>, d: usize| v.map_or_else(|| "-".to_string(), |v| format!("{v:.d$}"));
            println!(
                "{:>5} {:>3} {:>7} {:>10.2} {:>10.2} {:>12.2} {:>10.2} {:>12.3} {:>10} {:>13}",
                p.max_textures,
                p.k,
                p.passes,
                p.ms_per_frame,
                p.device_floor_ms,
                p.ms_per_frame / p.device_floor_ms,
                p.memcpy_floor_ms,
                p.memcpy_floor_ms / p.ms_per_frame,
                opt(p.shader_floor_ms, 2),
                opt(p.shader_floor_ms.map(|f| p.ms_per_frame / f), 2)
            );
        }
    }
    let at = |m: u32, k: usize| points.iter().find(|p| p.max_textures == m && p.k == k);
    let k10 = 10.clamp(*ks.start(), *ks.end());
    let chained = at(args.max_textures, k10).map(|p| p.ms_per_frame);
    let device = at(device_limit, k10).map(|p| p.ms_per_frame);
    let worst = |m: u32| {
        points.iter().filter(|p| p.max_textures == m).map(|p| p.device_floor_ms / p.ms_per_frame).min_by(f64::total_cmp)
    };
    let summary = serde_json::json!({
        "benchmark": "composite",
        "width": w,
        "height": h,
        "lighting": lighting,
        "k": k10,
        "device_max_textures": device_limit,
        "device_copy_ms_per_image": copy_ms,
        "memcpy_bandwidth_gb_per_s": memcpy_gbps,
        "images_moved_per_frame": images(k10),
        "device_floor_ms": images(k10) as f64 * copy_ms,
        "shader_floor_ms": shader(k10),
        "actual_over_shader_floor": {
            format!("max_textures_{}", args.max_textures): chained.zip(shader(k10)).map(|(c, f)| c / f),
            format!("device_{device_limit}"): device.zip(shader(k10)).map(|(d, f)| d / f),
        },
        "actual_over_copy_floor": {
            format!("max_textures_{}", args.max_textures): chained.map(|c| c / (images(k10) as f64 * copy_ms)),
            format!("device_{device_limit}"): device.map(|d| d / (images(k10) as f64 * copy_ms)),
        },
        "ms_per_frame": { format!("max_textures_{}", args.max_textures): chained, format!("device_{device_limit}"): device },
        "chained_over_single_pass": chained.zip(device).map(|(c, d)| c / d),
        "device_floor_over_actual": {
            format!("max_textures_{}", args.max_textures): chained.map(|c| images(k10) as f64 * copy_ms / c),
            format!("device_{device_limit}"): device.map(|d| images(k10) as f64 * copy_ms / d),
        },
        "worst_device_floor_over_actual": { format!("max_textures_{}", args.max_textures): worst(args.max_textures), format!("device_{device_limit}"): worst(device_limit) },
        "curve": args.out,
    });
    if let Some(dir) = args.out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(
        &args.out,
        serde_json::to_string_pretty(&serde_json::json!({ "summary": summary, "points": points }))?,
    )?;
    let series: Vec<Series> = limits
        .iter()
        .map(|&m| Series {
            name: if m == device_limit {
                format!("device limit ({m} textures)")
            } else {
                format!("--max-textures {m}")
            },
            points: points.iter().filter(|p| p.max_textures == m).map(|p| (p.k as f64, p.ms_per_frame)).collect(),
            reference: false,
        })
        .chain(std::iter::once(Series {
            name: "floor: the same bytes copied by the device".into(),
            points: ks.clone().map(|k| (k as f64, images(k) as f64 * copy_ms)).collect(),
            reference: true,
        }))
        .chain(std::iter::once(Series {
            name: "floor: one pass loading every colour and depth, nearest kept".into(),
            points: ks.clone().filter_map(|k| Some((k as f64, shader(k)?))).collect(),
            reference: true,
        }))
        .collect();
    let png = args.out.with_extension("png");
    match line_plot(
        &png,
        &format!("Per-fragment depth compositing, {w}x{h}, {lighting}"),
        "surfaces at one z (k)",
        "ms per output frame",
        &series,
    ) {
        Ok(()) if !quiet => println!("curve: {} and {}", args.out.display(), png.display()),
        Ok(()) => {}
        Err(e) => eprintln!("plot not written: {e:#}"),
    }
    println!("{summary}");
    Ok(())
}
