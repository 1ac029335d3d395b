//! Compositor throughput: k = 1…16 full-output surfaces at one z, composited per fragment
//! with lighting, at a chaining limit (`--max-textures`, default 8 as on the thesis' i.MX6)
//! and at the device's limit. The floor is physical: the bytes a composite must at least
//! touch (every surface's colour and depth read once, the output written once) at the
//! memcpy bandwidth measured in the same run.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{bail, Result};
use indicatif::{ProgressBar, ProgressStyle};
use strata_server::compositor::{Compositor, Layer, Lighting};
use strata_server::gpu::Gpu;

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
    /// Most surfaces.
    #[arg(long, default_value_t = 16)]
    max_surfaces: usize,
    /// The chaining limit measured beside the device's.
    #[arg(long, default_value_t = 8)]
    max_textures: u32,
    /// Timed frames per point.
    #[arg(long, default_value_t = 8)]
    frames: u32,
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

/// Surface `i`: a colour gradient and a tilted depth plane, so the surfaces intersect.
fn make_surface(gpu: &Gpu, i: usize, w: u32, h: u32) -> Surface {
    let mk = |format, usage| {
        gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("bench surface"),
            size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
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
    let c = mk(wgpu::TextureFormat::Rgba8Unorm, wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST);
    gpu.queue.write_texture(
        c.as_image_copy(),
        &rgba,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * 4), rows_per_image: None },
        c.size(),
    );
    let d = mk(
        wgpu::TextureFormat::Depth32Float,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    gpu.write_depth(&d, w, h, &depth);
    Surface { color: c.create_view(&Default::default()), depth: d.create_view(&Default::default()) }
}

/// Milliseconds per composite of `surfaces`: the median of `frames` timed frames after one
/// warm-up (the median resists other load on a shared machine).
fn time_composite(gpu: &Gpu, comp: &mut Compositor, surfaces: &[Surface], out: &wgpu::Texture, frames: u32) -> f64 {
    let (w, h) = (out.width() as i32, out.height() as i32);
    let layers: Vec<Layer<'_>> = surfaces
        .iter()
        .map(|s| Layer { rect: [0, 0, w, h], z: 0.5, color: &s.color, depth: Some(&s.depth), normal: [0.0, 0.0, 1.0] })
        .collect();
    let light = Lighting::default();
    let mut frame = || {
        comp.composite(&layers, &light, out, [0.0, 0.0, 0.0, 1.0], None);
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
    };
    frame();
    let mut times: Vec<f64> = (0..frames)
        .map(|_| {
            let start = Instant::now();
            frame();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// One measured point.
#[derive(serde::Serialize)]
struct Point {
    max_textures: u32,
    k: usize,
    passes: usize,
    ms_per_frame: f64,
    floor_ms: f64,
}

/// Runs the benchmark and prints its report; the last line is JSON.
pub fn run(args: &Args) -> Result<()> {
    let (w, h) = (args.width, args.height);
    if args.max_surfaces == 0 || args.frames == 0 || w == 0 || h == 0 {
        bail!("--max-surfaces, --frames and the output size must be positive");
    }
    let gpu: Arc<Gpu> = Gpu::open()?;
    let device_limit = gpu.limits.max_sampled_textures_per_shader_stage;
    let mut limits = vec![args.max_textures];
    if device_limit != args.max_textures {
        limits.push(device_limit);
    }
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
    let pb = bar(args.max_surfaces as u64, "uploading surfaces");
    let surfaces: Vec<Surface> = (0..args.max_surfaces)
        .map(|i| {
            pb.inc(1);
            make_surface(&gpu, i, w, h)
        })
        .collect();
    pb.finish();
    let out = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("bench output"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    // The floor's bandwidth: memcpy of a frame-sized buffer, far beyond the caches.
    let payload = (w * h * 8) as usize;
    let memcpy_gbps = crate::transport::memcpy_gbps(payload, 40, &bar(40, "memcpy"));
    let floor_bytes = |k: usize| (k as u64 * u64::from(w) * u64::from(h) * 8 + u64::from(w) * u64::from(h) * 4) as f64;
    let mut points = Vec::new();
    for &m in &limits {
        let mut comp = Compositor::new(gpu.clone(), Some(m))?;
        let pb = bar(args.max_surfaces as u64, if m == device_limit { "device limit" } else { "--max-textures" });
        for k in 1..=args.max_surfaces {
            let ms = time_composite(&gpu, &mut comp, &surfaces[..k], &out, args.frames);
            points.push(Point {
                max_textures: m,
                k,
                passes: comp.last_passes,
                ms_per_frame: ms,
                floor_ms: floor_bytes(k) / (memcpy_gbps * 1e9) * 1e3,
            });
            pb.inc(1);
        }
        pb.finish();
    }
    if !quiet {
        println!("composite {w}x{h}, lit, k surfaces at one z; memcpy {memcpy_gbps:.2} GB/s (same run)");
        println!(
            "{:>5} {:>3} {:>7} {:>12} {:>10} {:>12}",
            "limit", "k", "passes", "ms/frame", "floor ms", "floor/actual"
        );
        for p in &points {
            println!(
                "{:>5} {:>3} {:>7} {:>12.2} {:>10.2} {:>12.3}",
                p.max_textures,
                p.k,
                p.passes,
                p.ms_per_frame,
                p.floor_ms,
                p.floor_ms / p.ms_per_frame
            );
        }
    }
    let at = |m: u32, k: usize| points.iter().find(|p| p.max_textures == m && p.k == k);
    let k10 = 10.min(args.max_surfaces);
    let chained = at(args.max_textures, k10).map(|p| p.ms_per_frame);
    let device = at(device_limit, k10).map(|p| p.ms_per_frame);
    let floor_ms = floor_bytes(k10) / (memcpy_gbps * 1e9) * 1e3;
    let summary = serde_json::json!({
        "benchmark": "composite",
        "width": w,
        "height": h,
        "k": k10,
        "device_max_textures": device_limit,
        "memcpy_bandwidth_gb_per_s": memcpy_gbps,
        "bytes_per_frame_lower_bound": floor_bytes(k10),
        "bytes_per_frame_lower_bound / memcpy_bandwidth_ms": floor_ms,
        "ms_per_frame": { format!("max_textures_{}", args.max_textures): chained, format!("device_{device_limit}"): device },
        "chained_over_single_pass": chained.zip(device).map(|(c, d)| c / d),
        "floor_over_actual": { format!("max_textures_{}", args.max_textures): chained.map(|c| floor_ms / c), format!("device_{device_limit}"): device.map(|d| floor_ms / d) },
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
            name: "floor: bytes / memcpy bandwidth".into(),
            points: (1..=args.max_surfaces).map(|k| (k as f64, floor_bytes(k) / (memcpy_gbps * 1e9) * 1e3)).collect(),
            reference: true,
        }))
        .collect();
    let png = args.out.with_extension("png");
    match line_plot(
        &png,
        &format!("Per-fragment depth compositing, {w}x{h}, lit"),
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
