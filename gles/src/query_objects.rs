//! `GL_EXT_occlusion_query_boolean`: query objects, one active occlusion query per context,
//! and its answer, validated in Mesa's order; `GL_NV_conditional_render` on its answers, which
//! every mode waits for (the no-wait modes may, and then never draw what should not be drawn). Each begin/end is a [`render::occlusion::Occlusion`]
//! that the draws recorded meanwhile count for; the answer waits only for the passes those
//! draws went into.
//!
//! `GL_EXT_disjoint_timer_query`, where the device has timestamp queries: `GL_TIME_ELAPSED_EXT`
//! queries and `GL_TIMESTAMP_EXT` counters, on the device's own clock. A timestamp is written
//! by an empty compute pass submitted on the client's queue after everything before it (the
//! open pass is submitted first), so the two of a begin/end bracket the device's work on the
//! commands between them. The values are read back once they have completed; in nanoseconds
//! (the device's ticks times its timestamp period). The device's clock never jumps here, so
//! `GL_GPU_DISJOINT_EXT` is always false. As on Mesa held to ES 2.0, `glGetInteger64vEXT` does
//! not answer `GL_TIMESTAMP_EXT` (`GL_INVALID_ENUM`); `glQueryCounterEXT` does.

use crate::context::Context;
use crate::enums::{QUERY_COUNTER_BITS, TIMESTAMP, TIME_ELAPSED};
use crate::error::{GlError, GlResult};
use crate::limits::MAX_QUERIES;
use crate::objects::query::Active;
use crate::objects::query::Timer;
use crate::render::occlusion::Occlusion;
use crate::GlesExecutor;
use strata_protocol::Slice;

/// `GL_ANY_SAMPLES_PASSED_EXT`.
const ANY_SAMPLES_PASSED: u32 = 0x8C2F;
/// `GL_ANY_SAMPLES_PASSED_CONSERVATIVE_EXT`.
const ANY_SAMPLES_PASSED_CONSERVATIVE: u32 = 0x8D6A;
/// `GL_CURRENT_QUERY_EXT`.
const CURRENT_QUERY: u32 = 0x8865;
/// `GL_QUERY_RESULT_EXT`.
const QUERY_RESULT: u32 = 0x8866;
/// `GL_QUERY_RESULT_AVAILABLE_EXT`.
const QUERY_RESULT_AVAILABLE: u32 = 0x8867;
/// `GL_QUERY_WAIT_NV` … `GL_QUERY_BY_REGION_NO_WAIT_NV`: conditional render modes.
const CONDITIONAL_MODES: std::ops::RangeInclusive<u32> = 0x8E13..=0x8E16;

/// `GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN` (ES 3.0): the primitives transform feedback
/// captured between the begin and the end, counted as the draws are.
const PRIMITIVES_WRITTEN: u32 = 0x8C88;

/// Checks an occlusion query target.
fn target(t: u32) -> GlResult<u32> {
    match t {
        ANY_SAMPLES_PASSED | ANY_SAMPLES_PASSED_CONSERVATIVE => Ok(t),
        _ => Err(GlError::InvalidEnum),
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenQueriesEXT(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        if ctx.queries.len() as u64 + ctx.queries.fresh(names.iter()) > MAX_QUERIES {
            return Err(GlError::OutOfMemory);
        }
        ctx.queries.generate(names.iter());
        Ok(())
    }

    pub(super) fn glDeleteQueriesEXT(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in ctx.queries.delete(names.iter()) {
            // Deleting the active query ends it.
            if ctx.active_query.is_some_and(|a| a.name == n) {
                ctx.active_query = None;
                self.r.occlusion = None;
            }
            if ctx.xfb.query.is_some_and(|q| q.0 == n) {
                ctx.xfb.query = None;
            }
            if ctx.active_timer == Some(n) {
                ctx.active_timer = None;
            }
        }
        Ok(())
    }

    pub(super) fn glIsQueryEXT(&mut self, ctx: &mut Context, id: u32) -> bool {
        ctx.queries.get(&id).is_some_and(|q| q.target != 0)
    }

    pub(super) fn glBeginQueryEXT(&mut self, ctx: &mut Context, target_: u32, id: u32) -> GlResult {
        if target_ == TIME_ELAPSED && self.has_timers() {
            return self.begin_timer(ctx, id);
        }
        if target_ == PRIMITIVES_WRITTEN && ctx.es3() {
            if id == 0 || ctx.xfb.query.is_some() {
                return Err(GlError::InvalidOperation);
            }
            let q = ctx.queries.get_mut(&id).ok_or(GlError::InvalidOperation)?;
            if q.target != 0 && q.target != target_ {
                return Err(GlError::InvalidOperation);
            }
            q.target = target_;
            ctx.xfb.query = Some((id, 0));
            return Ok(());
        }
        let target = target(target_)?;
        // Both targets share one slot: one occlusion query at a time.
        if id == 0 || ctx.active_query.is_some() {
            return Err(GlError::InvalidOperation);
        }
        let q = ctx.queries.get_mut(&id).ok_or(GlError::InvalidOperation)?;
        if q.target != 0 && q.target != target {
            return Err(GlError::InvalidOperation);
        }
        let occlusion = Occlusion::new();
        q.target = target;
        q.last = Some(occlusion.clone());
        ctx.active_query = Some(Active { name: id, target });
        self.r.occlusion = Some(occlusion);
        Ok(())
    }

    pub(super) fn glEndQueryEXT(&mut self, ctx: &mut Context, target_: u32) -> GlResult {
        if target_ == TIME_ELAPSED && self.has_timers() {
            return self.end_timer(ctx);
        }
        if target_ == PRIMITIVES_WRITTEN && ctx.es3() {
            let (id, n) = ctx.xfb.query.take().ok_or(GlError::InvalidOperation)?;
            if let Some(q) = ctx.queries.get_mut(&id) {
                q.primitives = n;
            }
            return Ok(());
        }
        let target = target(target_)?;
        if ctx.active_query.is_none_or(|a| a.target != target) {
            return Err(GlError::InvalidOperation);
        }
        ctx.active_query = None;
        self.r.occlusion = None;
        Ok(())
    }

    pub(super) fn glBeginConditionalRenderNV(&mut self, ctx: &mut Context, id: u32, mode: u32) -> GlResult {
        let q = ctx.queries.get(&id).filter(|_| id != 0).ok_or(GlError::InvalidValue)?;
        if !CONDITIONAL_MODES.contains(&mode) {
            return Err(GlError::InvalidEnum);
        }
        let active = ctx.active_query.is_some_and(|a| a.name == id);
        let last = q.last.clone().filter(|_| q.target != 0 && !active);
        if ctx.conditional.is_some() {
            return Err(GlError::InvalidOperation);
        }
        let occlusion = last.ok_or(GlError::InvalidOperation)?;
        if self.r.counts_for(&occlusion) {
            self.r.flush();
        }
        ctx.conditional = Some(occlusion.result(&self.gpu));
        Ok(())
    }

    pub(super) fn glEndConditionalRenderNV(&mut self, ctx: &mut Context) -> GlResult {
        ctx.conditional.take().map(|_| ()).ok_or(GlError::InvalidOperation)
    }

    pub(super) fn glGetQueryivEXT(&mut self, ctx: &mut Context, target_: u32, pname: u32) -> Vec<i32> {
        let timers = self.has_timers();
        let r = match (target_, pname) {
            (TIME_ELAPSED, CURRENT_QUERY) if timers => Ok(ctx.active_timer.map_or(0, |n| n as i32)),
            (TIMESTAMP, CURRENT_QUERY) if timers => Ok(0),
            (TIME_ELAPSED | TIMESTAMP, QUERY_COUNTER_BITS) if timers => Ok(64),
            (PRIMITIVES_WRITTEN, CURRENT_QUERY) if ctx.es3() => Ok(ctx.xfb.query.map_or(0, |q| q.0 as i32)),
            _ => target(target_).and_then(|t| match pname {
                CURRENT_QUERY => Ok(ctx.active_query.filter(|a| a.target == t).map_or(0, |a| a.name as i32)),
                _ => Err(GlError::InvalidEnum),
            }),
        };
        match r {
            Ok(v) => vec![v],
            Err(e) => {
                ctx.record(e);
                Vec::new()
            }
        }
    }

    pub(super) fn glGetQueryObjectuivEXT(&mut self, ctx: &mut Context, id: u32, pname: u32) -> Vec<u32> {
        self.query_object(ctx, id, pname).map(|v| u32::try_from(v).unwrap_or(u32::MAX)).into_iter().collect()
    }

    pub(super) fn glGetQueryObjectivEXT(&mut self, ctx: &mut Context, id: u32, pname: u32) -> Vec<i32> {
        self.query_object(ctx, id, pname).map(|v| i32::try_from(v).unwrap_or(i32::MAX)).into_iter().collect()
    }

    pub(super) fn glGetQueryObjecti64vEXT(&mut self, ctx: &mut Context, id: u32, pname: u32) -> Vec<i64> {
        self.query_object(ctx, id, pname).map(|v| i64::try_from(v).unwrap_or(i64::MAX)).into_iter().collect()
    }

    pub(super) fn glGetQueryObjectui64vEXT(&mut self, ctx: &mut Context, id: u32, pname: u32) -> Vec<u64> {
        self.query_object(ctx, id, pname).into_iter().collect()
    }

    /// A query's result or its availability (recording the error, and answering nothing, for
    /// an unknown or active query or a bad `pname`); a larger result than the caller's type
    /// holds is saturated.
    fn query_object(&mut self, ctx: &mut Context, id: u32, pname: u32) -> Option<u64> {
        let active = ctx.active_query.is_some_and(|a| a.name == id)
            || ctx.active_timer == Some(id)
            || ctx.xfb.query.is_some_and(|q| q.0 == id);
        let Some(q) = ctx.queries.get(&id).filter(|q| q.target != 0 && !active) else {
            ctx.record(GlError::InvalidOperation);
            return None;
        };
        if !matches!(pname, QUERY_RESULT | QUERY_RESULT_AVAILABLE) {
            ctx.record(GlError::InvalidEnum);
            return None;
        }
        if q.timer.is_some() {
            return self.timer_value(ctx, id, pname == QUERY_RESULT);
        }
        if q.target == PRIMITIVES_WRITTEN {
            return Some(if pname == QUERY_RESULT { q.primitives } else { 1 });
        }
        let occlusion = q.last.clone()?;
        // Its draws still in the open pass are submitted first: asked repeatedly, the answer
        // must become available.
        if self.r.counts_for(&occlusion) {
            self.r.flush();
        }
        let v = if pname == QUERY_RESULT { occlusion.result(&self.gpu) } else { occlusion.available(&self.gpu) };
        Some(u64::from(v))
    }
}

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
