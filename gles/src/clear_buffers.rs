//! ES 3.0's `glClearBuffer{fv,iv,uiv,fi}`: one draw buffer's colour, or the depth, the stencil
//! or both, cleared to the values given rather than the clear state, through the same quads and
//! load operations as `glClear` (honouring the scissor, the write masks, a conditional render
//! and `GL_RASTERIZER_DISCARD`, under which clears do nothing). Checked in Mesa's order: the buffer, then the draw buffer's number.
//!
//! `glClearBufferiv` clears a signed integer colour buffer, `glClearBufferuiv` an unsigned
//! one, `glClearBufferfv` any other; a clear of the wrong kind is undefined in ES 3.0 and
//! does nothing here.

use strata_protocol::Slice;

use crate::context::Context;
use crate::conv::{clip_rect, color_writes, Mirror};
use crate::error::{GlError, GlResult};
use crate::limits::MAX_DRAW_BUFFERS;
use crate::GlesExecutor;

/// `GL_COLOR`, `GL_DEPTH`, `GL_STENCIL` and `GL_DEPTH_STENCIL` as `glClearBuffer*` names them.
const COLOR: u32 = 0x1800;
const DEPTH: u32 = 0x1801;
const STENCIL: u32 = 0x1802;
const DEPTH_STENCIL: u32 = 0x84F9;

/// What one `glClearBuffer*` clears.
enum Cleared {
    /// Draw buffer `slot`'s colour, to these values.
    Color { slot: usize, value: [f32; 4] },
    /// Draw buffer `slot`'s integer colour, to these values' bits, if it is signed (`signed`)
    /// or unsigned.
    IntColor { slot: usize, value: [u32; 4], signed: bool },
    /// The depth, the stencil, or both.
    DepthStencil { depth: Option<f32>, stencil: Option<i32> },
}

/// The draw buffer number of a colour clear (`GL_INVALID_VALUE` past the last).
fn color_slot(drawbuffer: i32) -> Result<usize, GlError> {
    usize::try_from(drawbuffer).ok().filter(|&d| d < MAX_DRAW_BUFFERS).ok_or(GlError::InvalidValue)
}

/// Checks that a depth or stencil clear names draw buffer 0.
fn zero(drawbuffer: i32) -> GlResult {
    if drawbuffer == 0 {
        Ok(())
    } else {
        Err(GlError::InvalidValue)
    }
}

/// The first `N` values the command carries (a shorter list is malformed: `GL_INVALID_VALUE`).
fn first<T: bytemuck::Pod + Default, const N: usize>(values: &Slice<'_, T>) -> Result<[T; N], GlError> {
    let mut out = [T::default(); N];
    let mut it = values.iter();
    for v in &mut out {
        *v = it.next().ok_or(GlError::InvalidValue)?;
    }
    Ok(out)
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glClearBufferfv(
        &mut self,
        ctx: &mut Context,
        buffer: u32,
        drawbuffer: i32,
        values: Slice<'_, f32>,
    ) -> GlResult {
        let cleared = match buffer {
            COLOR => Cleared::Color { slot: color_slot(drawbuffer)?, value: first::<f32, 4>(&values)? },
            DEPTH => {
                zero(drawbuffer)?;
                Cleared::DepthStencil { depth: Some(first::<f32, 1>(&values)?[0]), stencil: None }
            }
            _ => return Err(GlError::InvalidEnum),
        };
        self.clear_buffer(ctx, cleared)
    }

    pub(super) fn glClearBufferiv(
        &mut self,
        ctx: &mut Context,
        buffer: u32,
        drawbuffer: i32,
        values: Slice<'_, i32>,
    ) -> GlResult {
        let cleared = match buffer {
            COLOR => {
                let value = first::<i32, 4>(&values)?.map(|v| v as u32);
                Cleared::IntColor { slot: color_slot(drawbuffer)?, value, signed: true }
            }
            STENCIL => {
                zero(drawbuffer)?;
                Cleared::DepthStencil { depth: None, stencil: Some(first::<i32, 1>(&values)?[0]) }
            }
            _ => return Err(GlError::InvalidEnum),
        };
        self.clear_buffer(ctx, cleared)
    }

    pub(super) fn glClearBufferuiv(
        &mut self,
        ctx: &mut Context,
        buffer: u32,
        drawbuffer: i32,
        values: Slice<'_, u32>,
    ) -> GlResult {
        if buffer != COLOR {
            return Err(GlError::InvalidEnum);
        }
        let slot = color_slot(drawbuffer)?;
        self.clear_buffer(ctx, Cleared::IntColor { slot, value: first::<u32, 4>(&values)?, signed: false })
    }

    pub(super) fn glClearBufferfi(
        &mut self,
        ctx: &mut Context,
        buffer: u32,
        drawbuffer: i32,
        depth: f32,
        stencil: i32,
    ) -> GlResult {
        if buffer != DEPTH_STENCIL {
            return Err(GlError::InvalidEnum);
        }
        zero(drawbuffer)?;
        self.clear_buffer(ctx, Cleared::DepthStencil { depth: Some(depth), stencil: Some(stencil) })
    }

    /// Clears what `cleared` names in the draw framebuffer, as `glClear` would with those values.
    fn clear_buffer(&mut self, ctx: &mut Context, cleared: Cleared) -> GlResult {
        if ctx.conditional == Some(false) || ctx.raster.discard {
            return Ok(());
        }
        let target = self.draw_target(ctx).map_err(|_| GlError::InvalidFramebufferOperation)?;
        let reversed = self.reversed_target(ctx).is_some();
        let (ds, blend) = (&ctx.depth_stencil, &ctx.blend);
        let (mut color, mut depth, mut stencil) = (None, None, None);
        match cleared {
            Cleared::Color { slot, value } => {
                let writes = color_writes(blend.color_mask);
                let format = target.slots().get(slot).copied().flatten().map(|s| s.2);
                let float = matches!(
                    format.map(|f| f.sample_type(None, None)),
                    Some(Some(wgpu::TextureSampleType::Float { .. }))
                );
                // Fixed-point buffers clamp the value; float ones keep it (ES 3.0 §4.2.3).
                let unclamped = format.is_some_and(crate::formats::is_float_color);
                if float && !writes.is_empty() {
                    let value = if unclamped { value } else { value.map(|c| c.clamp(0.0, 1.0)) };
                    color = Some((value, writes, Some(slot)));
                }
            }
            Cleared::IntColor { slot, value, signed } => {
                let writes = color_writes(blend.color_mask);
                let kind = target.slots().get(slot).copied().flatten().and_then(|s| s.2.sample_type(None, None));
                let fits = match kind {
                    Some(wgpu::TextureSampleType::Sint) => signed,
                    Some(wgpu::TextureSampleType::Uint) => !signed,
                    _ => false,
                };
                if fits && !writes.is_empty() {
                    color = Some((value.map(f32::from_bits), writes, Some(slot)));
                }
            }
            Cleared::DepthStencil { depth: d, stencil: s } => {
                if let Some(d) = d.filter(|_| target.has_depth() && ds.depth_mask) {
                    let d = d.clamp(0.0, 1.0);
                    depth = Some((if reversed { Mirror::depth(d) } else { d }, true));
                }
                let write = ds.stencil[0].write & 0xff;
                if let Some(s) = s.filter(|_| target.has_stencil() && write != 0) {
                    stencil = Some((s as u32 & 0xff, write));
                }
            }
        }
        if color.is_none() && depth.is_none() && stencil.is_none() {
            return Ok(());
        }
        let scissor = ctx.raster.scissor_test.then(|| clip_rect(ctx.raster.scissor, &target));
        self.r.clear(&target, color, depth, stencil, scissor);
        Ok(())
    }
}
