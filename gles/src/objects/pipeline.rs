//! Program pipeline objects (`GL_EXT_separate_shader_objects`): the program of each stage and
//! the active program.

use std::sync::Arc;

use crate::glsl::types::Stage;
use crate::objects::program::{LinkedProgram, Program};

/// A program pipeline object.
#[derive(Default)]
pub struct Pipeline {
    /// The program whose vertex stage it runs (0: none).
    pub vertex: u32,
    /// The program whose fragment stage it runs (0: none).
    pub fragment: u32,
    /// The program `glUniform*` writes while it draws (`GL_ACTIVE_PROGRAM_EXT`).
    pub active: u32,
    /// Whether it has been bound or given stages (`glIsProgramPipelineEXT` is false before).
    pub ever_bound: bool,
    /// `GL_VALIDATE_STATUS` of the last `glValidateProgramPipelineEXT`.
    pub validated: bool,
    /// Its info log.
    pub log: String,
    /// What it draws with, as of the last draw.
    pub(crate) ready: Option<Ready>,
}

impl Pipeline {
    /// Whether it refers to `program` (a stage's or the active program).
    pub fn uses(&self, program: u32) -> bool {
        program != 0 && (self.vertex == program || self.fragment == program || self.active == program)
    }
}

/// What a pipeline draws with.
pub(crate) enum Ready {
    /// One program's own executable.
    Own(u32),
    /// Two programs' stages linked together.
    Combined(Combined),
}

/// The vertex stage of one program and the fragment stage of another, linked together.
pub(crate) struct Combined {
    /// The two programs' executables' ids it was linked from.
    pub(crate) key: (u64, u64),
    /// The executable.
    pub(crate) program: Arc<LinkedProgram>,
    /// Where each of its uniforms' values live: the stage whose program holds them, and the
    /// uniform's index in that program.
    pub(crate) sources: Vec<(Stage, usize)>,
}

impl Combined {
    /// The block and units from the two programs' values.
    pub(crate) fn feed(&self, vertex: &Program, fragment: &Program) -> Option<(Vec<u8>, Vec<u32>)> {
        let info = &self.program.info;
        let mut data = vec![0; info.block_size as usize];
        let mut units = vec![0; info.samplers.len()];
        for (u, &(stage, index)) in info.uniforms.iter().zip(&self.sources) {
            let from = if stage == Stage::Vertex { vertex } else { fragment };
            let src = from.linked.as_ref()?.info.uniforms.get(index)?;
            match (u.sampler, src.sampler) {
                (Some(d), Some(s)) => {
                    let n = u.len as usize;
                    units.get_mut(d..d + n)?.copy_from_slice(from.units.get(s..s + n)?);
                }
                _ => {
                    let n = (u.stride * u.len) as usize;
                    let (d, s) = (u.offset as usize, src.offset as usize);
                    data.get_mut(d..d + n)?.copy_from_slice(from.data.get(s..s + n)?);
                }
            }
        }
        Some((data, units))
    }
}
