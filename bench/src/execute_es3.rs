//! `strata-bench execute --scene es3`: an OpenGL ES 3.0 scene, nine horses drawn by one
//! instanced draw a frame, each placed and tinted by a uniform block read through
//! `gl_InstanceID`, the block's buffer rewritten every frame. (a) A client streams it through
//! `stratad --es3` (GLSL ES 3.00, `glBindBufferBase`, `glBufferSubData`,
//! `glDrawElementsInstanced`); (b) plain wgpu code in this process draws the same shader
//! (translated by Strata's front end), mesh and block with one instanced `draw_indexed`.

use std::collections::HashMap;

use anyhow::{anyhow, bail, Context, Result};
use glam::{Mat4, Vec3};
use strata_client::setup::{egl_context_es3, link_program, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_gles::glsl;
use strata_protocol::{Blob, Slice, Text};

use crate::mesh::Mesh;
use crate::side::{NativeTarget, Setup, Side, Sides};
use crate::transport::start_daemon_with;

/// The horses drawn, in a 3×3 grid.
const INSTANCES: u32 = 9;

const VS: &str = "#version 300 es
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(std140) uniform Scene { mat4 mvp[9]; mat4 model[9]; vec4 tint[9]; };
out vec4 color;
void main(void)
{
    vec3 N = normalize(mat3(model[gl_InstanceID]) * normal);
    float diffuse = max(dot(N, normalize(vec3(1.0, 1.0, 1.0))), 0.0);
    color = vec4(diffuse * tint[gl_InstanceID].rgb + vec3(0.1), 1.0);
    gl_Position = mvp[gl_InstanceID] * vec4(position, 1.0);
}";

const FS: &str = "#version 300 es
precision mediump float;
in vec4 color;
out vec4 frag;
void main(void)
{
    frag = color;
}";

/// The block's bytes for frame `f`: each horse's model-view-projection and model matrices,
/// then its tint (std140: matrices of four columns, vectors of four floats).
fn block(f: u32) -> Vec<u8> {
    let proj = glam::camera::rh::proj::opengl::perspective(60f32.to_radians(), 1.0, 1.0, 20.0);
    let view = Mat4::from_translation(Vec3::new(0.0, 0.0, -5.0));
    let (mut mvp, mut model, mut tint) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..INSTANCES {
        let (x, y) = ((i % 3) as f32 - 1.0, (i / 3) as f32 - 1.0);
        let angle = f as f32 * 0.02 + i as f32 * 0.7;
        let m = Mat4::from_translation(Vec3::new(x * 1.3, y * 1.3, 0.0))
            * Mat4::from_rotation_y(angle)
            * Mat4::from_rotation_x(-0.3)
            * Mat4::from_scale(Vec3::splat(0.8));
        mvp.extend((proj * view * m).to_cols_array());
        model.extend(m.to_cols_array());
        tint.extend([0.4 + 0.2 * (i % 3) as f32, 0.4 + 0.2 * (i / 3) as f32, 0.8 - 0.05 * i as f32, 1.0]);
    }
    bytemuck::cast_slice(&[mvp, model, tint].concat()).to_vec()
}

/// The client side: a connection to a benchmark daemon offering ES 3.0, current on a pbuffer.
struct StrataEs3 {
    gl: Connection,
    /// Kept alive while the side is.
    _daemon: crate::transport::DaemonProc,
    count: i32,
    size: i32,
}

impl StrataEs3 {
    fn open(mesh: &Mesh, args: &Setup) -> Result<StrataEs3> {
        let extra = ["--client-rasterizer-threads".to_string(), args.client_rasterizer_threads.to_string()];
        let extra = [&extra[..], &["--es3".to_string()]].concat();
        let daemon = start_daemon_with(strata_server::ExecutorKind::Gles, &extra, None)?;
        let opts =
            ConnectOptions { socket: daemon.1.clone(), name: "execute-bench-es3".into(), ..ConnectOptions::default() };
        let mut gl = Connection::connect(&opts).context("connecting to the benchmark daemon")?;
        let size = args.size as i32;
        egl_context_es3(&mut gl, 24, 0, SurfaceKind::Pbuffer { width: size, height: size })?;
        let p = link_program(&mut gl, (1, 2, 3), VS, FS, &[])?;
        let index = gl.glGetUniformBlockIndex(p, Text::borrowed("Scene"))?;
        gl.glUniformBlockBinding(p, index, 0)?;
        let vbytes: &[u8] = bytemuck::cast_slice(&mesh.vertices);
        let ibytes: &[u8] = bytemuck::cast_slice(&mesh.indices);
        let scene = block(0);
        gl.glGenBuffers(Slice::new(&[10, 11, 12]))?;
        gl.glBindBuffer(0x8892, 10)?;
        gl.glBufferData(0x8892, vbytes.len() as i64, Some(Blob::borrowed(vbytes)), 0x88E4)?;
        gl.glBindBuffer(0x8893, 11)?;
        gl.glBufferData(0x8893, ibytes.len() as i64, Some(Blob::borrowed(ibytes)), 0x88E4)?;
        gl.glBindBufferBase(0x8A11, 0, 12)?;
        gl.glBufferData(0x8A11, scene.len() as i64, None, 0x88E8)?;
        gl.glVertexAttribPointer(0, 3, 0x1406, false, 24, 0)?;
        gl.glVertexAttribPointer(1, 3, 0x1406, false, 24, 12)?;
        gl.glEnableVertexAttribArray(0)?;
        gl.glEnableVertexAttribArray(1)?;
        gl.glEnable(0x0B71)?;
        gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
        let mut side = StrataEs3 { gl, _daemon: daemon, count: mesh.indices.len() as i32, size };
        Side::frames(&mut side, 0..10, None)?;
        if side.gl.glGetError()? != 0 {
            bail!("GL error during the Strata frames");
        }
        Ok(side)
    }
}

impl Side for StrataEs3 {
    fn frame(&mut self, f: u32) -> Result<()> {
        let gl = &mut self.gl;
        // The frame's block first, then the frame: its clear and draw share one pass.
        gl.glBufferSubData(0x8A11, 0, Blob::borrowed(&block(f)))?;
        gl.glClear(0x4000 | 0x0100)?;
        gl.glDrawElementsInstancedEXT(0x0004, self.count, 0x1405, 0, INSTANCES as i32)?;
        // A pbuffer's swap, as the drop-in library sends it: a flush.
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

/// The baseline: the same stages and block drawn by wgpu code in this process, on a device of
/// its own.
struct NativeEs3 {
    target: NativeTarget,
    vbuf: wgpu::Buffer,
    ibuf: wgpu::Buffer,
    ubuf: wgpu::Buffer,
    group: wgpu::BindGroup,
    pipeline: wgpu::RenderPipeline,
    count: u32,
}

impl NativeEs3 {
    fn open(mesh: &Mesh, args: &Setup) -> Result<NativeEs3> {
        let vs = glsl::compile(glsl::Stage::Vertex, VS).map_err(|e| anyhow!("{e}"))?;
        let fs = glsl::compile(glsl::Stage::Fragment, FS).map_err(|e| anyhow!("{e}"))?;
        let linked = glsl::link(&vs, &fs, &HashMap::new(), 16).map_err(|e| anyhow!("{e}"))?;
        if linked.block_size != 0 || linked.blocks.len() != 1 {
            bail!("the scene's program should have its one block and no other uniforms");
        }
        let (binding, size) = (linked.blocks[0].binding, u64::from(linked.blocks[0].block.size));
        let target = NativeTarget::new(args.size)?;
        let vbuf = target.buffer(bytemuck::cast_slice(&mesh.vertices), wgpu::BufferUsages::VERTEX);
        let ibuf = target.buffer(bytemuck::cast_slice(&mesh.indices), wgpu::BufferUsages::INDEX);
        let ubuf = target.buffer(&vec![0u8; size as usize], wgpu::BufferUsages::UNIFORM);
        let d = &target.gpu.device;
        let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: None,
            entries: &[wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(size),
                },
                count: None,
            }],
        });
        let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &bgl,
            entries: &[wgpu::BindGroupEntry { binding, resource: ubuf.as_entire_binding() }],
        });
        let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&bgl)],
            immediate_size: 0,
        });
        let pipeline = target.pipeline(&layout, linked.vertex, linked.fragment);
        let count = mesh.indices.len() as u32;
        let mut side = NativeEs3 { target, vbuf, ibuf, ubuf, group, pipeline, count };
        Side::frames(&mut side, 0..10, None)?;
        Ok(side)
    }
}

impl Side for NativeEs3 {
    fn frame(&mut self, f: u32) -> Result<()> {
        self.target.gpu.write_buffer(&self.ubuf, 0, &block(f));
        self.target.frame(&self.pipeline, &self.group, (&self.vbuf, &self.ibuf), self.count, INSTANCES);
        Ok(())
    }

    fn wait(&mut self) -> Result<()> {
        self.target.wait()
    }

    fn read(&mut self) -> Result<Vec<u8>> {
        self.target.image()
    }
}

/// Both sides of the ES 3.0 scene, and what they draw.
pub(crate) fn open(mesh: &Mesh, args: &Setup) -> Result<Sides> {
    let what = format!(
        "{INSTANCES} instances of {} ({} triangles each), placed by a uniform buffer",
        mesh.source,
        mesh.indices.len() / 3
    );
    Ok((Box::new(StrataEs3::open(mesh, args)?), Box::new(NativeEs3::open(mesh, args)?), what))
}
