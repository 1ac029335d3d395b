//! Which OpenGL ES a context is: its version strings, ES 3.0's version queries
//! (`GL_MAJOR_VERSION`, `GL_MINOR_VERSION`, `GL_NUM_EXTENSIONS`, `glGetStringi`), and what an
//! ES 3.0 entry point does in an ES 2.0 context (records `GL_INVALID_OPERATION`, as Mesa's
//! dispatch does for an entry point the context's API lacks).

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::typed::TextureTarget;
use crate::GlesExecutor;

/// `GL_MAJOR_VERSION`, `GL_MINOR_VERSION` and `GL_NUM_EXTENSIONS` (ES 3.0).
const MAJOR_VERSION: u32 = 0x821B;
const MINOR_VERSION: u32 = 0x821C;
const NUM_EXTENSIONS: u32 = 0x821D;
/// `GL_MAX_SERVER_WAIT_TIMEOUT`.
const MAX_SERVER_WAIT_TIMEOUT: u32 = 0x9111;

/// What an ES 3.0 call answers in an ES 2.0 context, where it does nothing.
pub(crate) trait Es2Answer {
    /// The value: nothing, empty or false.
    fn es2_answer() -> Self;
}

impl Es2Answer for GlResult<()> {
    fn es2_answer() -> Self {
        Ok(())
    }
}

impl<T> Es2Answer for Option<T> {
    fn es2_answer() -> Self {
        None
    }
}

impl<T> Es2Answer for Vec<T> {
    fn es2_answer() -> Self {
        Vec::new()
    }
}

macro_rules! zero_answer {
    ($($t:ty),*) => { $( impl Es2Answer for $t { fn es2_answer() -> Self { <$t>::default() } } )* };
}
zero_answer!(bool, i32, u32, i64, u64);

/// An ES 3.0 call in an ES 2.0 context: `GL_INVALID_OPERATION`, and nothing done.
pub(crate) fn not_in_es2<T: Es2Answer>(ctx: &mut Context) -> T {
    ctx.record(GlError::InvalidOperation);
    T::es2_answer()
}

/// `GL_VERSION` for `ctx`'s version.
pub(crate) fn version_string(ctx: &Context) -> String {
    let version = if ctx.es3() { "3.0" } else { "2.0" };
    format!("OpenGL ES {version} Strata {}", env!("CARGO_PKG_VERSION"))
}

/// `GL_SHADING_LANGUAGE_VERSION` for `ctx`'s version.
pub(crate) fn language_string(ctx: &Context) -> &'static str {
    if ctx.es3() {
        "OpenGL ES GLSL ES 3.00"
    } else {
        "OpenGL ES GLSL ES 1.00"
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// ES 3.0's state, which an ES 2.0 context does not have (`None`: not one of it, or not in
    /// this context, and the ordinary table answers).
    pub(crate) fn version_state(&self, ctx: &Context, pname: u32) -> Option<Vec<i32>> {
        if !ctx.es3() {
            return None;
        }
        if let Some(v) = self.uniform_block_state(ctx, pname).or_else(|| self.xfb_state(ctx, pname)) {
            return Some(v);
        }
        Some(vec![match pname {
            MAJOR_VERSION => 3,
            MINOR_VERSION => 0,
            NUM_EXTENSIONS => self.extensions(ctx).split_whitespace().count() as i32,
            // Server waits (`glWaitSync`) take no timeout: the daemon runs commands in order.
            MAX_SERVER_WAIT_TIMEOUT => 0,
            MAX_SAMPLES => crate::limits::SAMPLES as i32,
            // The draw framebuffer's samples, 0 for single-sampled (or incomplete) ones.
            SAMPLES | SAMPLE_BUFFERS => {
                let n = self.draw_target(ctx).map_or(1, |t| t.samples);
                match pname {
                    SAMPLES if n > 1 => n as i32,
                    SAMPLE_BUFFERS => i32::from(n > 1),
                    _ => 0,
                }
            }
            // GL_SAMPLER_BINDING: the active unit's sampler object.
            0x8919 => ctx.bindings.samplers[ctx.bindings.active_unit] as i32,
            // GL_TEXTURE_BINDING_2D_ARRAY: the active unit's 2D array.
            0x8C1D => ctx.bindings.units[ctx.bindings.active_unit][TextureTarget::TwoDArray.slot()] as i32,
            // GL_MAX_ARRAY_TEXTURE_LAYERS.
            0x88FF => crate::limits::max_array_layers(&self.gpu) as i32,
            // GL_MAX_VERTEX_UNIFORM_COMPONENTS, GL_MAX_FRAGMENT_UNIFORM_COMPONENTS: the default
            // block's 256 vectors.
            0x8B4A | 0x8B49 => 4 * 256,
            // GL_MAX_VARYING_COMPONENTS and GL_MAX_FRAGMENT_INPUT_COMPONENTS: the varyings;
            // GL_MAX_VERTEX_OUTPUT_COMPONENTS: with the position (ES 3.0's minimums).
            0x8B4B | 0x9125 => 4 * crate::limits::MAX_VARYING_VECTORS as i32,
            0x9122 => 4 * crate::limits::MAX_VARYING_VECTORS as i32 + 4,
            // GL_MAX_ELEMENTS_VERTICES, GL_MAX_ELEMENTS_INDICES: the counts drawn best, as Mesa
            // recommends them.
            0x80E8 | 0x80E9 => 3000,
            // GL_MIN_PROGRAM_TEXEL_OFFSET, GL_MAX_PROGRAM_TEXEL_OFFSET: ES 3.0's range, which
            // the shaders' offsets are held to.
            0x8904 => -8,
            0x8905 => 7,
            _ => return None,
        }])
    }

    /// `glGetStringi`: one of `GL_EXTENSIONS` by index (`GL_INVALID_ENUM` for another name,
    /// `GL_INVALID_VALUE` for an index past the last).
    pub(crate) fn glGetStringi(&mut self, ctx: &mut Context, name: u32, index: u32) -> Option<String> {
        if name != EXTENSIONS {
            ctx.record(GlError::InvalidEnum);
            return None;
        }
        let all = self.extensions(ctx);
        let one = all.split_whitespace().nth(index as usize).map(str::to_string);
        if one.is_none() {
            ctx.record(GlError::InvalidValue);
        }
        one
    }
}
