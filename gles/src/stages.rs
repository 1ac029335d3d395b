//! The stages a draw runs: the linked program's own, or a variant its framebuffer or state
//! selects (a reversed-Z surface's depth, `GL_EXT_clip_control`'s origin and depth range, the
//! points stage), each created on first use and kept.

use crate::context::Context;

use crate::glsl::ClipZ;
use crate::limits::MAX_REVERSED_STAGES;
use crate::objects::program::Stages;
use crate::objects::program::{shader_module, LinkedProgram};
use crate::objects::surface::ReversedZ;
use crate::typed::ClipControl;
use crate::GlesExecutor;

impl GlesExecutor {
    /// The reversed-Z constants of the draw framebuffer when it is a reversed-Z surface's
    /// framebuffer 0.
    pub(super) fn reversed_target(&self, ctx: &Context) -> Option<ReversedZ> {
        self.reversed_framebuffer(ctx.bindings.framebuffer)
    }

    /// The reversed-Z constants of framebuffer `bound` (a draw or read binding) when it is a
    /// reversed-Z surface's framebuffer 0.
    pub(super) fn reversed_framebuffer(&self, bound: u32) -> Option<ReversedZ> {
        let (_, sid) = self.current?;
        if bound != 0 {
            return None;
        }
        self.surfaces.get(&sid)?.reversed
    }

    /// The stages of a draw of the current program (`points`: of `GL_POINTS`) into a
    /// framebuffer with `reversed` depth, when they are not the program's own; `None` without
    /// a linked program or where its own serve. The error says why a variant failed.
    pub(super) fn draw_stages(
        &mut self,
        ctx: &Context,
        reversed: Option<ReversedZ>,
        points: bool,
    ) -> Result<Option<Stages>, String> {
        let Some(program) = ctx.draw_program() else {
            return Ok(None);
        };
        let clip = ctx.raster.clip;
        if let Some(r) = reversed {
            return self.reversed_stages(&program, r, points, clip.upper_left).map(Some);
        }
        if clip != ClipControl::default() {
            return program.clip_vs(&self.gpu, points, clip).map(|vs| Some((vs, None)));
        }
        if points {
            return program.points_vs(&self.gpu).map(|vs| Some((vs, None)));
        }
        Ok(None)
    }

    /// `program`'s reversed-Z stages for the current surface `r`: the vertex stage
    /// (`points`: its points variant; `upper_left`: with that window origin) and, if it reads
    /// `gl_FragCoord`, the fragment stage; created on first use and kept by the surface.
    fn reversed_stages(
        &mut self,
        program: &LinkedProgram,
        r: ReversedZ,
        points: bool,
        upper_left: bool,
    ) -> Result<Stages, String> {
        let (_, sid) = self.current.ok_or("no current surface")?;
        let surface = self.surfaces.get_mut(&sid).ok_or("no current surface")?;
        let key = (program.id, points, upper_left);
        if let Some(stages) = surface.reversed_stages.get(&key) {
            return Ok(stages.clone());
        }
        let gpu = &self.gpu;
        let z = ClipZ::Reversed { near: r.near, far: r.far };
        let vs = shader_module(gpu, "vs reversed-z", program.info.vertex_variant(points, upper_left, z)?)?;
        let fs = match program.info.reversed_fragment() {
            Some(fs) => Some(shader_module(gpu, "fs reversed-z", fs?)?),
            None => None,
        };
        // Programs relinked frame after frame would otherwise grow the cache without end.
        if surface.reversed_stages.len() >= MAX_REVERSED_STAGES {
            surface.reversed_stages.clear();
        }
        surface.reversed_stages.insert(key, (vs.clone(), fs.clone()));
        Ok((vs, fs))
    }
}
