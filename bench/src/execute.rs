//! The execute benchmark: the glmark2 horse at 540×540 for a fixed number of frames, drawn
//! (a) by a client streaming GLES2 through `stratad`, and (b) by plain wgpu code in this process
//! using the very same shader (translated by Strata's GLSL ES front end) and mesh. Both sides
//! are set up first and then take turns, round by round, so that each round compares them
//! under the same load. `--scene es3` draws an OpenGL ES 3.0 scene instead
//! (`execute_es3.rs`): instanced horses placed by a uniform buffer.

use std::collections::HashMap;

use anyhow::{anyhow, bail, Context, Result};
use glam::{Mat4, Vec3};
use strata_client::setup::{egl_context, link_program, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_gles::glsl;
use strata_protocol::{Blob, Slice, Text};

use crate::mesh::{self, Mesh};
use crate::side::{NativeTarget, Setup, Side, Sides};

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
    /// Rounds the frames are timed in, the two sides taking turns in each; the ratio is the
    /// median of the rounds' ratios.
    #[arg(long, default_value_t = 6)]
    rounds: u32,
    /// Square framebuffer size.
    #[arg(long, default_value_t = 540)]
    size: u32,
    /// Rasterizer threads of the client's device on lavapipe, as for `stratad serve
    /// --client-rasterizer-threads` [default: 0, the driver's one per core, as the baseline's
    /// device has: the two sides then differ only in the path the commands take].
    #[arg(long, default_value_t = 0)]
    client_rasterizer_threads: u32,
    /// What is drawn: the horse through ES 2.0, or instanced horses reading a uniform buffer
    /// through ES 3.0.
    #[arg(long, value_enum, default_value_t = Scene::Horse)]
    scene: Scene,
}

/// The scenes `strata-bench execute` draws.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Scene {
    /// The glmark2 horse, one draw a frame (OpenGL ES 2.0).
    Horse,
    /// Instanced horses, each placed and tinted by a uniform buffer (OpenGL ES 3.0).
    Es3,
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

/// The client side: a connection to a benchmark daemon, current on a pbuffer, with the
/// horse's program and buffers bound.
struct StrataSide {
    gl: Connection,
    /// Kept alive while the side is.
    _daemon: crate::transport::DaemonProc,
    locations: (i32, i32),
    count: i32,
    size: i32,
}

impl StrataSide {
    fn open(mesh: &Mesh, args: &Args) -> Result<StrataSide> {
        let threads = ["--client-rasterizer-threads".to_string(), args.client_rasterizer_threads.to_string()];
        let daemon = start_daemon_with(strata_server::ExecutorKind::Gles, &threads, None)?;
        let opts =
            ConnectOptions { socket: daemon.1.clone(), name: "execute-bench".into(), ..ConnectOptions::default() };
        let mut gl = Connection::connect(&opts).context("connecting to the benchmark daemon")?;
        let size = args.size as i32;
        egl_context(&mut gl, 24, 0, SurfaceKind::Pbuffer { width: size, height: size })?;
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
        let locations = (mvp_loc, nm_loc);
        let mut side = StrataSide { gl, _daemon: daemon, locations, count, size };
        Side::frames(&mut side, 0..10, None)?;
        if side.gl.glGetError()? != 0 {
            bail!("GL error during the Strata frames");
        }
        Ok(side)
    }
}

/// The baseline: the same shader (through Strata's GLSL ES front end) and mesh drawn by wgpu
/// code in this process, on a device of its own.
struct NativeSide {
    target: NativeTarget,
    vbuf: wgpu::Buffer,
    ibuf: wgpu::Buffer,
    ubuf: wgpu::Buffer,
    group: wgpu::BindGroup,
    pipeline: wgpu::RenderPipeline,
    /// Where the two matrices lie in the uniform block.
    offsets: (u64, u64),
    count: u32,
}

impl Side for StrataSide {
    fn frame(&mut self, f: u32) -> Result<()> {
        let gl = &mut self.gl;
        let (mvp, nm) = matrices(f, 1.0);
        gl.glClear(0x4000 | 0x0100)?;
        gl.glUniformMatrix4fv(self.locations.0, false, Slice::new(&mvp))?;
        gl.glUniformMatrix4fv(self.locations.1, false, Slice::new(&nm))?;
        gl.glDrawElements(0x0004, self.count, 0x1405, 0)?;
        // eglSwapBuffers of the current pbuffer, as the drop-in library sends it: a flush,
        // with no reply to wait for (a pbuffer's swap shows nothing).
        gl.glFlush()?;
        Ok(())
    }

    fn wait(&mut self) -> Result<()> {
        Ok(self.gl.glFinish()?)
    }

    fn read(&mut self) -> Result<Vec<u8>> {
        Ok(self.gl.glReadPixels(0, 0, self.size, self.size, 0x1908, 0x1401)?.0)
    }

    fn stats(&mut self) -> Result<Option<strata_protocol::ExecStats>> {
        Ok(Some(self.gl.strataStats()?))
    }
}

impl Side for NativeSide {
    fn frame(&mut self, f: u32) -> Result<()> {
        let (mvp, nm) = matrices(f, 1.0);
        let gpu = &self.target.gpu;
        gpu.write_buffer(&self.ubuf, self.offsets.0, bytemuck::cast_slice(&mvp));
        gpu.write_buffer(&self.ubuf, self.offsets.1, bytemuck::cast_slice(&nm));
        self.target.frame(&self.pipeline, &self.group, (&self.vbuf, &self.ibuf), self.count, 1);
        Ok(())
    }

    fn wait(&mut self) -> Result<()> {
        self.target.wait()
    }

    fn read(&mut self) -> Result<Vec<u8>> {
        self.target.image()
    }
}

impl NativeSide {
    fn open(mesh: &Mesh, args: &Args) -> Result<NativeSide> {
        let vs = glsl::compile(glsl::Stage::Vertex, VS).map_err(|e| anyhow!("{e}"))?;
        let fs = glsl::compile(glsl::Stage::Fragment, FS).map_err(|e| anyhow!("{e}"))?;
        let mut bindings = HashMap::new();
        bindings.insert("position".to_string(), 0);
        bindings.insert("normal".to_string(), 1);
        let linked = glsl::link(&vs, &fs, &bindings, 16).map_err(|e| anyhow!("{e}"))?;
        let target = NativeTarget::new(args.size)?;
        let vbuf = target.buffer(bytemuck::cast_slice(&mesh.vertices), wgpu::BufferUsages::VERTEX);
        let ibuf = target.buffer(bytemuck::cast_slice(&mesh.indices), wgpu::BufferUsages::INDEX);
        let ubuf = target.buffer(&vec![0u8; linked.block_size as usize], wgpu::BufferUsages::UNIFORM);
        let offset_of = |name: &str| {
            linked
                .uniforms
                .iter()
                .find(|u| u.name == name)
                .map(|u| u.offset as u64)
                .ok_or_else(|| anyhow!("no uniform {name}"))
        };
        let (mvp_off, nm_off) = (offset_of("ModelViewProjectionMatrix")?, offset_of("NormalMatrix")?);
        let d = &target.gpu.device;
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
        let pipeline = target.pipeline(&layout, linked.vertex, linked.fragment);
        let count = mesh.indices.len() as u32;
        let offsets = (mvp_off, nm_off);
        let mut side = NativeSide { target, vbuf, ibuf, ubuf, group, pipeline, offsets, count };
        Side::frames(&mut side, 0..10, None)?;
        Ok(side)
    }
}

/// Fraction of pixels whose channels all agree within 2/255.
pub(crate) fn agreement(a: &[u8], b: &[u8]) -> f64 {
    if a.len() != b.len() || a.is_empty() {
        return 0.0;
    }
    let same =
        a.chunks(4).zip(b.chunks(4)).filter(|(x, y)| x.iter().zip(y.iter()).all(|(p, q)| p.abs_diff(*q) <= 2)).count();
    same as f64 / (a.len() / 4) as f64
}

/// Fraction of pixels that are not the black background.
pub(crate) fn coverage(a: &[u8]) -> f64 {
    a.chunks(4).filter(|p| p[0] > 0 || p[1] > 0 || p[2] > 0).count() as f64 / (a.len() / 4).max(1) as f64
}

/// Runs the benchmark and prints its report.
pub fn run(args: &Args) -> Result<()> {
    let mesh = mesh::glmark2_model("horse.3ds", 7000);
    let triangles = mesh.indices.len() / 3;
    if args.rounds == 0 || args.frames < args.rounds {
        bail!("--rounds must be positive and at most --frames");
    }
    let (mut strata, mut native, what): Sides = match args.scene {
        Scene::Horse => (
            Box::new(StrataSide::open(&mesh, args)?),
            Box::new(NativeSide::open(&mesh, args)?),
            format!("{} ({triangles} triangles)", mesh.source),
        ),
        Scene::Es3 => {
            let setup = Setup { size: args.size, client_rasterizer_threads: args.client_rasterizer_threads };
            crate::execute_es3::open(&mesh, &setup)?
        }
    };
    // The frames in rounds, each side in turn (the order alternating), so that a change in
    // the machine's load falls on both sides alike; each round's ratio compares the two
    // sides under the same load.
    let per = args.frames / args.rounds;
    let (mut strata_secs, mut native_secs, mut ratios) = (0.0, 0.0, Vec::new());
    let pb = bar(u64::from(per * args.rounds * 2), "execute");
    for r in 0..args.rounds {
        let frames = 10 + r * per..10 + (r + 1) * per;
        let (a, b) = if r % 2 == 0 {
            let a = strata.frames(frames.clone(), Some(&pb))?;
            (a, native.frames(frames, Some(&pb))?)
        } else {
            let b = native.frames(frames.clone(), Some(&pb))?;
            (strata.frames(frames, Some(&pb))?, b)
        };
        strata_secs += a;
        native_secs += b;
        // Frames per second through stratad over those of native wgpu.
        ratios.push(b / a);
    }
    pb.finish();
    let timed = f64::from(per * args.rounds);
    let (strata_fps, native_wgpu_fps) = (timed / strata_secs, timed / native_secs);
    let last = 10 + per * args.rounds - 1;
    let stats = strata.stats()?.unwrap_or_default();
    let strata_image = strata.image(last)?;
    let native_image = native.image(last)?;
    let ratio_of_totals = strata_fps / native_wgpu_fps;
    let mut sorted = ratios.clone();
    sorted.sort_by(f64::total_cmp);
    let ratio = sorted[sorted.len() / 2];
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
        "execute: {what} at {}x{}, {} frames each; the client's device has {} rasterizer threads",
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
    println!(
        "  ratio:               {ratio:>8.3}  (median of {} rounds, {:.3} to {:.3}; of the totals {ratio_of_totals:.3})",
        args.rounds,
        sorted[0],
        sorted[sorted.len() - 1]
    );
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
            "round_ratios": ratios,
            "ratio_of_totals": ratio_of_totals,
            "rounds": args.rounds,
            "pipeline_cache_misses": stats.pipeline_cache_misses,
            "render_passes": stats.render_passes,
            "image_agreement": image_agreement,
            "frames": args.frames,
            "size": args.size,
            "triangles": triangles,
            "mesh": mesh.source,
            "scene": what,
        });
        println!("{report}");
    }
    Ok(())
}
