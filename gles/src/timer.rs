//! `GL_EXT_disjoint_timer_query`, where the device has timestamp queries: `GL_TIME_ELAPSED_EXT`
//! queries and `GL_TIMESTAMP_EXT` counters, on the device's own clock. A timestamp is written
//! by an empty compute pass submitted on the client's queue after everything before it (the
//! open pass is submitted first), so the two of a begin/end bracket the device's work on the
//! commands between them. The values are read back once they have completed; in nanoseconds
//! (the device's ticks times its timestamp period). The device's clock never jumps here, so
//! `GL_GPU_DISJOINT_EXT` is always false. As on Mesa held to ES 2.0, `glGetInteger64vEXT` does
//! not answer `GL_TIMESTAMP_EXT` (`GL_INVALID_ENUM`); `glQueryCounterEXT` does.

use crate::context::Context;
use crate::enums::{TIMESTAMP, TIME_ELAPSED};
use crate::error::{GlError, GlResult};
use crate::objects::query::Timer;
use crate::GlesExecutor;

impl GlesExecutor {
    /// Whether the device has timestamps (the extension is offered only then).
    pub(super) fn has_timers(&self) -> bool {
        self.gpu.features.contains(wgpu::Features::TIMESTAMP_QUERY)
    }

    /// Writes `timer`'s timestamp `index` after what is pending, and asks for the read once
    /// it was the last.
    fn stamp(&mut self, timer: &mut Timer, index: u32) {
        let cmd = timer.write(&self.gpu, index);
        self.r.flush();
        self.gpu.submit(&self.r.lane, vec![cmd]);
        if index + 1 == timer.count {
            timer.request();
        }
    }

    /// `glBeginQueryEXT(GL_TIME_ELAPSED_EXT, id)`.
    pub(super) fn begin_timer(&mut self, ctx: &mut Context, id: u32) -> GlResult {
        if id == 0 || ctx.active_timer.is_some() {
            return Err(GlError::InvalidOperation);
        }
        let q = ctx.queries.get_mut(&id).ok_or(GlError::InvalidOperation)?;
        if q.target != 0 && q.target != TIME_ELAPSED {
            return Err(GlError::InvalidOperation);
        }
        let mut timer = Timer::new(&self.gpu, 2);
        self.stamp(&mut timer, 0);
        q.target = TIME_ELAPSED;
        q.timer = Some(timer);
        ctx.active_timer = Some(id);
        Ok(())
    }

    /// `glEndQueryEXT(GL_TIME_ELAPSED_EXT)`.
    pub(super) fn end_timer(&mut self, ctx: &mut Context) -> GlResult {
        let id = ctx.active_timer.take().ok_or(GlError::InvalidOperation)?;
        let Some(timer) = ctx.queries.get_mut(&id).and_then(|q| q.timer.as_mut()) else { return Ok(()) };
        self.stamp(timer, 1);
        Ok(())
    }

    #[allow(non_snake_case)]
    pub(super) fn glQueryCounterEXT(&mut self, ctx: &mut Context, id: u32, target: u32) -> GlResult {
        if target != TIMESTAMP || !self.has_timers() {
            return Err(GlError::InvalidEnum);
        }
        if ctx.active_timer == Some(id) || ctx.active_query.is_some_and(|a| a.name == id) {
            return Err(GlError::InvalidOperation);
        }
        if id == 0 {
            return Err(GlError::InvalidOperation);
        }
        // As on Mesa, a name never generated becomes a query here.
        if ctx.queries.get(&id).is_none() {
            if ctx.queries.len() as u64 >= crate::limits::MAX_QUERIES {
                return Err(GlError::OutOfMemory);
            }
            ctx.queries.generate([id]);
        }
        let q = ctx.queries.get_mut(&id).ok_or(GlError::InvalidOperation)?;
        if q.target != 0 && q.target != TIMESTAMP {
            return Err(GlError::InvalidOperation);
        }
        let mut timer = Timer::new(&self.gpu, 1);
        self.stamp(&mut timer, 0);
        q.target = TIMESTAMP;
        q.timer = Some(timer);
        Ok(())
    }

    /// A timer query's `GL_QUERY_RESULT_EXT` (waiting) or `GL_QUERY_RESULT_AVAILABLE_EXT`.
    pub(super) fn timer_value(&mut self, ctx: &Context, id: u32, result: bool) -> Option<u64> {
        let timer = ctx.queries.get(&id)?.timer.as_ref()?;
        if result {
            timer.result(&self.gpu, true)
        } else {
            Some(u64::from(timer.result(&self.gpu, false).is_some()))
        }
    }
}
