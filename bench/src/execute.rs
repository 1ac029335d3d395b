//! The execute benchmark: the glmark2 horse at 540×540 for a fixed number of frames, drawn
//! (a) by a client streaming GLES2 through `stratad`, and (b) by plain wgpu code in this process
//! using the very same shader (translated by Strata's GLSL ES front end) and mesh.

use std::collections::HashMap;
use std::time::Instant;

use anyhow::{anyhow, bail, Context, Result};
use glam::{Mat4, Vec3};
use strata_client::setup::{egl_context, link_program, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::{Blob, Slice, Text};
use strata_server::gles::glsl;

use crate::mesh::{self, Mesh};
use crate::transport::{bar, start_daemon_with};

/// Options of `strata-bench execute`.
#[derive(clap::Args)]
pub struct Args {
    /// Print one JSON object as the last line.
    #[arg(long)]
    json: bool,
    /// Frames to time on each side (after warm-up).
    #[arg(long, default_value_t = 600)]
    frames: u32,
    /// Square framebuffer size.
    #[arg(long, default_value_t = 540)]
    size: u32,
    /// Rasterizer threads of the client's device on lavapipe, as for `stratad serve
    /// --client-rasterizer-threads` [default: 0, the driver's one per core, as the baseline's
    /// device has: the two sides then differ only in the path the commands take].
    #[arg(long, default_value_t = 0)]
    client_rasterizer_threads: u32,
}

const VS: &str = "attribute vec3 position;
attribute vec3 normal;
uniform mat4 ModelViewProjectionMatrix;
uniform mat4 NormalMatrix;
varying vec4 Color;
void main(void)
{
    vec3 N = normalize(vec3(NormalMatrix * vec4(normal, 1.0)));
    vec3 L = normalize(vec3(1.0, 1.0, 1.0));
    float diffuse = max(dot(N, L), 0.0);
    Color = vec4(diffuse * vec3(0.7, 0.7, 0.7) + vec3(0.1), 1.0);
    gl_Position = ModelViewProjectionMatrix * vec4(position, 1.0);
}";

const FS: &str = "#ifdef GL_ES
precision mediump float;
#endif
varying vec4 Color;
void main(void)
{
    gl_FragColor = Color;
}";

/// The model-view-projection and normal matrices of frame `f` (a slow turn, as glmark2's build).
fn matrices(f: u32, aspect: f32) -> ([f32; 16], [f32; 16]) {
    let angle = f as f32 * 0.02;
    let model = Mat4::from_rotation_y(angle) * Mat4::from_rotation_x(-0.3);
    let view = Mat4::from_translation(Vec3::new(0.0, 0.0, -3.0));
    let proj = glam::camera::rh::proj::opengl::perspective(60f32.to_radians(), aspect, 1.0, 10.0);
    let mv = view * model;
    ((proj * mv).to_cols_array(), mv.inverse().transpose().to_cols_array())
}

/// Frames per second, the executor's counters, and the last frame (RGBA8, bottom row first).
type StrataRun = (f64, strata_protocol::ExecStats, Vec<u8>);

fn strata(mesh: &Mesh, args: &Args) -> Result<StrataRun> {
    let threads = ["--client-rasterizer-threads".to_string(), args.client_rasterizer_threads.to_string()];
    let daemon = start_daemon_with(strata_server::ExecutorKind::Gles, &threads, None)?;
    let opts = ConnectOptions { socket: daemon.1.clone(), name: "execute-bench".into(), ..ConnectOptions::default() };
    let mut gl = Connection::connect(&opts).context("connecting to the benchmark daemon")?;
    let size = args.size as i32;
    let cur = egl_context(&mut gl, 24, 0, SurfaceKind::Pbuffer { width: size, height: size })?;
    let (d, s) = (cur.display, cur.surface);
    let p = link_program(&mut gl, (1, 2, 3), VS, FS, &["position", "normal"])?;
    let mvp_loc = gl.glGetUniformLocation(p, Text::borrowed("ModelViewProjectionMatrix"))?;
    let nm_loc = gl.glGetUniformLocation(p, Text::borrowed("NormalMatrix"))?;
    let vbytes: &[u8] = bytemuck::cast_slice(&mesh.vertices);
    let ibytes: &[u8] = bytemuck::cast_slice(&mesh.indices);
    gl.glGenBuffers(Slice::new(&[10, 11]))?;
    gl.glBindBuffer(0x8892, 10)?;
    gl.glBufferData(0x8892, vbytes.len() as i64, Some(Blob::borrowed(vbytes)), 0x88E4)?;
    gl.glBindBuffer(0x8893, 11)?;
    gl.glBufferData(0x8893, ibytes.len() as i64, Some(Blob::borrowed(ibytes)), 0x88E4)?;
    gl.glVertexAttribPointer(0, 3, 0x1406, false, 24, 0)?;
    gl.glVertexAttribPointer(1, 3, 0x1406, false, 24, 12)?;
    gl.glEnableVertexAttribArray(0)?;
    gl.glEnableVertexAttribArray(1)?;
    gl.glEnable(0x0B71)?;
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    let count = mesh.indices.len() as i32;
    let frame = |gl: &mut Connection, f: u32| -> Result<()> {
        let (mvp, nm) = matrices(f, 1.0);
        gl.glClear(0x4000 | 0x0100)?;
        gl.glUniformMatrix4fv(mvp_loc, false, Slice::new(&mvp))?;
        gl.glUniformMatrix4fv(nm_loc, false, Slice::new(&nm))?;
        gl.glDrawElements(0x0004, count, 0x1405, 0)?;
        gl.eglSwapBuffers(d, s)?.map_err(|e| anyhow::anyhow!("eglSwapBuffers failed with EGL error {e:#x}"))?;
        Ok(())
    };
    for f in 0..10 {
        frame(&mut gl, f)?;
    }
    gl.glFinish()?;
    if gl.glGetError()? != 0 {
        bail!("GL error during the Strata frames");
    }
    let pb = bar(u64::from(args.frames), "strata");
    let start = Instant::now();
    for f in 0..args.frames {
        frame(&mut gl, f)?;
        pb.set_position(u64::from(f));
    }
    gl.glFinish()?;
    let secs = start.elapsed().as_secs_f64();
    pb.finish();
    let stats = gl.strataStats()?;
    // The last frame again, read back for the image check.
    frame(&mut gl, args.frames - 1)?;
    let image = gl.glReadPixels(0, 0, size, size, 0x1908, 0x1401)?.0;
    Ok((f64::from(args.frames) / secs, stats, image))
}

fn native(mesh: &Mesh, args: &Args) -> Result<(f64, Vec<u8>)> {
    let vs = glsl::compile(glsl::Stage::Vertex, VS).map_err(|e| anyhow!("{e}"))?;
    let fs = glsl::compile(glsl::Stage::Fragment, FS).map_err(|e| anyhow!("{e}"))?;
    let mut bindings = HashMap::new();
    bindings.insert("position".to_string(), 0);
    bindings.insert("normal".to_string(), 1);
    let linked = glsl::link(&vs, &fs, &bindings, 16).map_err(|e| anyhow!("{e}"))?;
    let gpu = strata_server::gpu::Gpu::open()?;
    let d = &gpu.device;
    let square = (args.size, args.size);
    let target =
        |format, usage| gpu.texture_2d("execute target", format, square, usage).create_view(&Default::default());
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let color_tex = gpu.texture_2d("execute colour", wgpu::TextureFormat::Rgba8Unorm, square, usage);
    let color = color_tex.create_view(&Default::default());
    let depth = target(wgpu::TextureFormat::Depth24PlusStencil8, wgpu::TextureUsages::RENDER_ATTACHMENT);
    let buffer = |bytes: &[u8], usage: wgpu::BufferUsages| {
        let b = d.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: bytes.len() as u64,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        gpu.queue.write_buffer(&b, 0, bytes);
        b
    };
    let vbuf = buffer(bytemuck::cast_slice(&mesh.vertices), wgpu::BufferUsages::VERTEX);
    let ibuf = buffer(bytemuck::cast_slice(&mesh.indices), wgpu::BufferUsages::INDEX);
    let ubuf = buffer(&vec![0u8; linked.block_size as usize], wgpu::BufferUsages::UNIFORM);
    let offset_of = |name: &str| {
        linked
            .uniforms
            .iter()
            .find(|u| u.name == name)
            .map(|u| u.offset as u64)
            .ok_or_else(|| anyhow!("no uniform {name}"))
    };
    let (mvp_off, nm_off) = (offset_of("ModelViewProjectionMatrix")?, offset_of("NormalMatrix")?);
    let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: None,
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    });
    let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &bgl,
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: ubuf.as_entire_binding() }],
    });
    let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&bgl)],
        immediate_size: 0,
    });
    let vmod = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(linked.vertex)),
    });
    let fmod = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(linked.fragment)),
    });
    let attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
    let pipeline = d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &vmod,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 24,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &attrs,
            })],
        },
        primitive: wgpu::PrimitiveState { front_face: wgpu::FrontFace::Cw, ..Default::default() },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth24PlusStencil8,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &fmod,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::TextureFormat::Rgba8Unorm.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let count = mesh.indices.len() as u32;
    let frame = |f: u32| {
        let (mvp, nm) = matrices(f, 1.0);
        gpu.queue.write_buffer(&ubuf, mvp_off, bytemuck::cast_slice(&mvp));
        gpu.queue.write_buffer(&ubuf, nm_off, bytemuck::cast_slice(&nm));
        let mut enc = d.create_command_encoder(&Default::default());
        {
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &color,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            rp.set_pipeline(&pipeline);
            rp.set_bind_group(0, &group, &[]);
            rp.set_vertex_buffer(0, vbuf.slice(..));
            rp.set_index_buffer(ibuf.slice(..), wgpu::IndexFormat::Uint32);
            rp.draw_indexed(0..count, 0, 0..1);
        }
        gpu.queue.submit([enc.finish()]);
    };
    let wait = || d.poll(wgpu::PollType::Wait { submission_index: None, timeout: None });
    for f in 0..10 {
        frame(f);
    }
    wait()?;
    let pb = bar(u64::from(args.frames), "native wgpu");
    let start = Instant::now();
    for f in 0..args.frames {
        frame(f);
        pb.set_position(u64::from(f));
    }
    wait()?;
    let secs = start.elapsed().as_secs_f64();
    pb.finish();
    frame(args.frames - 1);
    let image = gpu
        .read_rgba8(&color_tex, [0, 0, args.size, args.size])
        .ok_or_else(|| anyhow!("reading the frame back failed"))?;
    Ok((f64::from(args.frames) / secs, image))
}

/// Fraction of pixels whose channels all agree within 2/255.
fn agreement(a: &[u8], b: &[u8]) -> f64 {
    if a.len() != b.len() || a.is_empty() {
        return 0.0;
    }
    let same =
        a.chunks(4).zip(b.chunks(4)).filter(|(x, y)| x.iter().zip(y.iter()).all(|(p, q)| p.abs_diff(*q) <= 2)).count();
    same as f64 / (a.len() / 4) as f64
}

/// Fraction of pixels that are not the black background.
fn coverage(a: &[u8]) -> f64 {
    a.chunks(4).filter(|p| p[0] > 0 || p[1] > 0 || p[2] > 0).count() as f64 / (a.len() / 4).max(1) as f64
}

/// Runs the benchmark and prints its report.
pub fn run(args: &Args) -> Result<()> {
    let mesh = mesh::glmark2_model("horse.3ds", 7000);
    let triangles = mesh.indices.len() / 3;
    let (strata_fps, stats, strata_image) = strata(&mesh, args)?;
    let (native_wgpu_fps, native_image) = native(&mesh, args)?;
    let ratio = strata_fps / native_wgpu_fps;
    let image_agreement = agreement(&strata_image, &native_image);
    let covered = coverage(&native_image);
    if image_agreement < 0.99 || covered < 0.01 {
        bail!(
            "the two sides did not draw the same image (agreement {:.2}%, model covers {:.2}%): the timing would be meaningless",
            image_agreement * 100.0,
            covered * 100.0
        );
    }
    println!(
        "execute: {} ({} triangles) at {}x{}, {} frames each; the client's device has {} rasterizer threads",
        mesh.source,
        triangles,
        args.size,
        args.size,
        args.frames,
        if args.client_rasterizer_threads == 0 {
            "the driver's".to_string()
        } else {
            args.client_rasterizer_threads.to_string()
        }
    );
    println!("  through stratad:     {strata_fps:>8.1} fps");
    println!("  native wgpu:         {native_wgpu_fps:>8.1} fps");
    println!("  ratio:               {ratio:>8.3}");
    println!(
        "  pipeline cache misses: {} (render passes {}, draws {})",
        stats.pipeline_cache_misses, stats.render_passes, stats.draws
    );
    println!(
        "  last frames agree on {:.2}% of pixels; the model covers {:.1}%",
        image_agreement * 100.0,
        covered * 100.0
    );
    if args.json {
        let report = serde_json::json!({
            "strata_fps": strata_fps,
            "native_wgpu_fps": native_wgpu_fps,
            "ratio": ratio,
            "pipeline_cache_misses": stats.pipeline_cache_misses,
            "render_passes": stats.render_passes,
            "image_agreement": image_agreement,
            "frames": args.frames,
            "size": args.size,
            "triangles": triangles,
            "mesh": mesh.source,
        });
        println!("{report}");
    }
    Ok(())
}
