//! EGL on the daemon side: displays, contexts, and the EGL calls on surfaces (which `surface`
//! holds); the configs offered and their matching are in `egl_config`.
//! Surfaces may declare their depth's projection (`EGL_STRATA_surface_projection`, see
//! `docs/projection.md`); the daemon's layout entry for the client wins over a window
//! surface's declaration.

use strata_protocol::projection::Projection;
use strata_protocol::surface_id;
use strata_protocol::wire::EglHandle;
use strata_protocol::{EglResult, Slice};

use crate::context::Context;
use crate::egl_config::{choose, Config, CONFIGS};
use crate::enums::*;
use crate::GlesExecutor;

/// The projection a surface attribute list declares (`EGL_STRATA_surface_projection`), if
/// any; an invalid declaration is `EGL_BAD_ATTRIBUTE`, logged with what is wrong with it: at
/// warn the first time (`first`), at debug after that, since a client may repeat it every
/// frame.
fn declared_projection(call: &str, attribs: &[i32], first: bool) -> Result<Option<Projection>, i32> {
    Projection::from_egl_attribs(attribs).map_err(|e| {
        let what = "EGL_BAD_ATTRIBUTE: invalid EGL_STRATA_surface_projection declaration";
        if first {
            tracing::warn!(error = ?e, "{call}: {what}: {e} (this client's further ones are logged at debug)");
        } else {
            tracing::debug!(error = ?e, "{call}: {what}: {e}");
        }
        EGL_BAD_ATTRIBUTE
    })
}

/// Whether a surface attribute list asks for sRGB colour (`EGL_KHR_gl_colorspace`): its
/// `EGL_GL_COLORSPACE_KHR` is `EGL_GL_COLORSPACE_SRGB_KHR`; a value that is neither that nor
/// `EGL_GL_COLORSPACE_LINEAR_KHR` is `EGL_BAD_ATTRIBUTE`.
pub fn colorspace(attribs: &[i32]) -> Result<bool, i32> {
    let mut srgb = false;
    for pair in attribs.chunks(2) {
        match *pair {
            [EGL_NONE, ..] => break,
            [EGL_GL_COLORSPACE_KHR, EGL_GL_COLORSPACE_SRGB_KHR] => srgb = true,
            [EGL_GL_COLORSPACE_KHR, EGL_GL_COLORSPACE_LINEAR_KHR] => srgb = false,
            [EGL_GL_COLORSPACE_KHR, _] => return Err(EGL_BAD_ATTRIBUTE),
            _ => {}
        }
    }
    Ok(srgb)
}

/// Reads `EGL_WIDTH`/`EGL_HEIGHT` from a pbuffer attribute list.
pub fn pbuffer_size(attribs: &[i32]) -> Result<(i32, i32), i32> {
    let (mut w, mut h) = (0, 0);
    for pair in attribs.chunks(2) {
        match *pair {
            [EGL_NONE, ..] => break,
            [EGL_WIDTH, v] => w = v,
            [EGL_HEIGHT, v] => h = v,
            [_, _] => {}
            _ => return Err(EGL_BAD_ATTRIBUTE),
        }
    }
    Ok((w, h))
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// [`declared_projection`], counting this client's invalid declarations.
    fn declared_projection(&mut self, call: &str, attribs: &[i32]) -> Result<Option<Projection>, i32> {
        let first = self.bad_projections == 0;
        declared_projection(call, attribs, first)
            .inspect_err(|_| self.bad_projections = self.bad_projections.saturating_add(1))
    }

    /// `Ok` for the one display once initialised.
    pub(super) fn check_display(&self, display: u32) -> Result<(), i32> {
        if display != 1 {
            Err(EGL_BAD_DISPLAY)
        } else if !self.initialized {
            Err(EGL_NOT_INITIALIZED)
        } else {
            Ok(())
        }
    }

    pub(super) fn eglGetDisplay(&mut self, _native_display: u64) -> EglHandle {
        1
    }

    pub(super) fn eglGetPlatformDisplay(
        &mut self,
        _platform: u32,
        _native_display: u64,
        _attribs: Slice<'_, i32>,
    ) -> EglHandle {
        1
    }

    pub(super) fn eglInitialize(&mut self, display: EglHandle) -> EglResult<(i32, i32)> {
        if display != 1 {
            return Err(EGL_BAD_DISPLAY);
        }
        self.initialized = true;
        Ok((1, 4))
    }

    pub(super) fn eglTerminate(&mut self, display: EglHandle) -> EglResult<()> {
        if display != 1 {
            return Err(EGL_BAD_DISPLAY);
        }
        self.initialized = false;
        Ok(())
    }

    pub(super) fn eglChooseConfig(
        &mut self,
        display: EglHandle,
        attribs: Slice<'_, i32>,
        config_size: i32,
    ) -> EglResult<Vec<EglHandle>> {
        self.check_display(display)?;
        let mut ids = choose(&attribs.to_vec())?;
        if config_size >= 0 {
            ids.truncate(config_size as usize);
        }
        Ok(ids)
    }

    pub(super) fn eglGetConfigAttrib(
        &mut self,
        display: EglHandle,
        config: EglHandle,
        attribute: i32,
    ) -> EglResult<i32> {
        self.check_display(display)?;
        Config::get(config).ok_or(EGL_BAD_CONFIG)?.attrib(attribute).ok_or(EGL_BAD_ATTRIBUTE)
    }

    pub(super) fn eglCreatePbufferSurface(
        &mut self,
        display: EglHandle,
        config: EglHandle,
        attribs: Slice<'_, i32>,
    ) -> EglResult<EglHandle> {
        self.check_display(display)?;
        let c = Config::get(config).ok_or(EGL_BAD_CONFIG)?;
        let attribs = attribs.to_vec();
        let (w, h) = pbuffer_size(&attribs)?;
        // Not composited, so the layout's projection is not for it: it keeps its own.
        let projection = self.declared_projection("eglCreatePbufferSurface", &attribs)?;
        let srgb = colorspace(&attribs)?;
        self.make_surface(c, w, h, false, projection, srgb).map(|(id, _)| id)
    }

    /// The daemon's layout entry for this client, if any, overrides the placement asked for,
    /// and its projection the one the attributes declare.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn eglCreateWindowSurface(
        &mut self,
        display: EglHandle,
        config: EglHandle,
        _native_window: u64,
        mut x: i32,
        mut y: i32,
        mut z: f32,
        mut width: i32,
        mut height: i32,
        attribs: Slice<'_, i32>,
    ) -> EglResult<EglHandle> {
        if let Some(p) = &self.placement {
            (x, y, z) = (p.x, p.y, p.z);
            if let Some((w, h)) = p.size {
                (width, height) = (w as i32, h as i32);
            }
        }
        self.check_display(display)?;
        let c = Config::get(config).ok_or(EGL_BAD_CONFIG)?;
        let attribs = attribs.to_vec();
        let declared = self.declared_projection("eglCreateWindowSurface", &attribs)?;
        // The layout's stable ID for this client's next window wins over the one it asks for.
        let from_layout = self.surface_ids.get(self.windows_made).copied();
        let asked = match from_layout {
            Some(id) => Some(id),
            None => surface_id::from_egl_attribs(&attribs)
                .map_err(|e| {
                    tracing::warn!("eglCreateWindowSurface: EGL_BAD_ATTRIBUTE: {e}");
                    EGL_BAD_ATTRIBUTE
                })?
                .map(u64::from),
        };
        if !z.is_finite() || width <= 0 || height <= 0 {
            return Err(EGL_BAD_NATIVE_WINDOW);
        }
        // The daemon's configuration wins over the surface's declaration.
        let projection = self.projection.or(declared);
        if let (Some(fixed), Some(asked)) = (self.projection, declared) {
            if fixed != asked {
                tracing::debug!(%asked, %fixed, "the surface's projection is overridden by the daemon's layout");
            }
        }
        let srgb = colorspace(&attribs)?;
        let (id, views) = self.make_surface(c, width, height, true, projection, srgb)?;
        if let Some((scene, client, name)) = &self.scene {
            match scene.add(*client, id, name, [x, y, width, height], z, asked) {
                Ok(scene_id) => {
                    self.windows_made += 1;
                    if let Some(s) = self.surfaces.get_mut(&id) {
                        s.scene_id = Some(scene_id);
                    }
                }
                Err(refused) => {
                    // The second surface to claim an ID is refused, and so is one whose
                    // client lacks the credentials an entry reserves it for; logged once per
                    // ID and client, so that a client asking again floods nothing.
                    if self.refused_ids.insert(refused.id()) {
                        tracing::warn!("eglCreateWindowSurface: EGL_BAD_MATCH: {refused} (logged once)");
                    }
                    self.surfaces.remove(&id);
                    return Err(EGL_BAD_MATCH);
                }
            }
            self.register_buffers(id, views);
            // The compositor reads the depth as stored: reversed where the daemon reverses it
            // (`--reversed-z`); `eglQuerySurface` keeps answering what was declared.
            let reversed = self.surfaces.get(&id).and_then(|s| s.reversed);
            let stored = projection.map(|p| reversed.map_or(p, |r| r.stored(p)));
            if stored.is_some() {
                scene.set_projection(*client, id, stored);
            }
        }
        Ok(id)
    }

    pub(super) fn eglCreateContext(
        &mut self,
        display: EglHandle,
        config: EglHandle,
        share_context: EglHandle,
        attribs: Slice<'_, i32>,
    ) -> EglResult<EglHandle> {
        self.check_display(display)?;
        // EGL: a share context that is not a context of this display is EGL_BAD_CONTEXT.
        let group = match share_context {
            0 => None,
            s => Some(self.contexts.get(&s).ok_or(EGL_BAD_CONTEXT)?.group),
        };
        // EGL_KHR_no_config_context: EGL_NO_CONFIG_KHR takes each surface's config.
        let c = if config == 0 { CONFIGS[0] } else { Config::get(config).ok_or(EGL_BAD_CONFIG)? };
        let asked = crate::context_attribs::parse(&attribs.to_vec(), self.es3)?;
        self.account
            .admit(strata_device::account::Kind::Context, self.contexts.len() as u64, 1)
            .map_err(|_| EGL_BAD_ALLOC)?;
        let id = self.next_handle;
        self.next_handle += 1;
        let mut ctx = Context::new(c);
        // Its own share group, or `share_context`'s, whose tables another context keeps.
        ctx.group = group.unwrap_or(id);
        if group.is_none() {
            self.holders.insert(id, id);
        }
        // KHR_debug: a debug context starts with debug output enabled.
        ctx.debug.output = asked.debug;
        ctx.no_error = asked.no_error;
        ctx.release_none = asked.release_none;
        ctx.lose_on_reset = asked.lose_on_reset;
        ctx.robust = asked.robust;
        ctx.major = asked.major;
        self.contexts.insert(id, ctx);
        let asked = asked.priority;
        // The class applies to the whole client; the daemon's configuration wins over it.
        if let (Some(class), false) = (asked, self.policy_fixed) {
            self.r.lane.set_class(class);
            self.apply_class_priority(class);
            if let Some((scene, client, _)) = &self.scene {
                scene.set_policy(*client, class, self.deadline);
            }
        }
        Ok(id)
    }

    /// `eglQueryContext` for what only the daemon knows: `EGL_CONTEXT_PRIORITY_LEVEL_IMG`, the
    /// class the client is scheduled in (the configuration's, if it names one).
    pub(super) fn eglQueryContext(&mut self, display: EglHandle, context: EglHandle, attribute: i32) -> EglResult<i32> {
        self.check_display(display)?;
        let Some(ctx) = self.contexts.get(&context) else { return Err(EGL_BAD_CONTEXT) };
        match attribute {
            EGL_CONTEXT_PRIORITY_LEVEL_IMG => Ok(self.r.lane.class().egl_level()),
            // The version it was given, which may be above the one asked for.
            EGL_CONTEXT_CLIENT_VERSION => Ok(i32::from(ctx.major)),
            _ => Err(EGL_BAD_ATTRIBUTE),
        }
    }

    pub(super) fn eglMakeCurrent(
        &mut self,
        display: EglHandle,
        draw: EglHandle,
        read: EglHandle,
        context: EglHandle,
    ) -> EglResult<()> {
        self.check_display(display)?;
        if context == 0 {
            if draw != 0 || read != 0 {
                return Err(EGL_BAD_MATCH);
            }
            self.r.flush();
            self.current = None;
            self.r.occlusion = None;
            return Ok(());
        }
        if draw != read {
            return Err(EGL_BAD_MATCH);
        }
        if draw == 0 {
            // EGL_KHR_surfaceless_context: current with no default framebuffer.
            self.hold_shared(context);
            let ctx = self.contexts.get_mut(&context).ok_or(EGL_BAD_CONTEXT)?;
            ctx.surfaceless = true;
            self.r.flush();
            self.r.occlusion = ctx.active_query.and_then(|a| ctx.queries.get(&a.name)).and_then(|q| q.last.clone());
            self.current = Some((context, 0));
            return Ok(());
        }
        let surface = self.surfaces.get(&draw).ok_or(EGL_BAD_SURFACE)?;
        let (w, h) = (surface.target.width as i32, surface.target.height as i32);
        let config = surface.config;
        self.hold_shared(context);
        let ctx = self.contexts.get_mut(&context).ok_or(EGL_BAD_CONTEXT)?;
        ctx.surfaceless = false;
        ctx.config = config;
        if !ctx.made_current {
            ctx.made_current = true;
            ctx.raster.viewport = [0, 0, w, h];
            ctx.raster.scissor = [0, 0, w, h];
        }
        self.r.flush();
        // Draws count for the occlusion query this context has active.
        self.r.occlusion = ctx.active_query.and_then(|a| ctx.queries.get(&a.name)).and_then(|q| q.last.clone());
        self.current = Some((context, draw));
        Ok(())
    }

    pub(super) fn eglSwapInterval(&mut self, display: EglHandle, interval: i32) -> EglResult<()> {
        self.check_display(display)?;
        // EGL: the interval applies to the window surface bound to the current context.
        let (_, surface) = self.current.ok_or(EGL_BAD_CONTEXT)?;
        if surface == 0 {
            return Err(EGL_BAD_SURFACE);
        }
        if let Some((scene, client, _)) = &self.scene {
            scene.set_interval(*client, surface, interval);
        }
        Ok(())
    }

    pub(super) fn eglQuerySurface(&mut self, display: EglHandle, surface: EglHandle, attribute: i32) -> EglResult<i32> {
        self.check_display(display)?;
        let s = self.surfaces.get(&surface).ok_or(EGL_BAD_SURFACE)?;
        match attribute {
            EGL_WIDTH => Ok(s.target.width as i32),
            EGL_HEIGHT => Ok(s.target.height as i32),
            EGL_CONFIG_ID => Ok(s.config.id as i32),
            EGL_RENDER_BUFFER => Ok(EGL_BACK_BUFFER),
            EGL_SWAP_BEHAVIOR => Ok(EGL_BUFFER_DESTROYED),
            EGL_GL_COLORSPACE_KHR => Ok(if s.srgb { EGL_GL_COLORSPACE_SRGB_KHR } else { EGL_GL_COLORSPACE_LINEAR_KHR }),
            // `EGL_EXT_buffer_age`: of the current draw surface only.
            EGL_BUFFER_AGE_EXT => {
                if self.current.map(|(_, s)| s) != Some(surface) {
                    return Err(EGL_BAD_SURFACE);
                }
                Ok(s.frames.as_ref().map_or(0, |w| w.age().min(i32::MAX as u64) as i32))
            }
            // `EGL_STRATA_surface_id`: the window surface's ID in the scene.
            surface_id::EGL_SURFACE_ID_STRATA if s.window => {
                s.scene_id.and_then(|id| i32::try_from(id).ok()).ok_or(EGL_BAD_ATTRIBUTE)
            }
            // `EGL_STRATA_surface_projection`: the projection in effect.
            a => Projection::egl_query(s.projection.as_ref(), a).ok_or(EGL_BAD_ATTRIBUTE),
        }
    }

    pub(super) fn eglDestroySurface(&mut self, display: EglHandle, surface: EglHandle) -> EglResult<()> {
        self.check_display(display)?;
        self.surfaces.remove(&surface).ok_or(EGL_BAD_SURFACE)?;
        if let Some((scene, client, _)) = &self.scene {
            scene.remove(*client, Some(surface));
        }
        Ok(())
    }

    pub(super) fn eglDestroyContext(&mut self, display: EglHandle, context: EglHandle) -> EglResult<()> {
        self.check_display(display)?;
        if self.current.is_some_and(|(c, _)| c == context) {
            self.r.flush();
            self.current = None;
            self.r.occlusion = None;
        }
        let mut gone = self.contexts.remove(&context).ok_or(EGL_BAD_CONTEXT)?;
        if self.holders.get(&gone.group) == Some(&context) {
            // The group's tables go to another of its contexts; with none left, they go.
            match self.contexts.iter_mut().find(|(_, c)| c.group == gone.group) {
                Some((&other, ctx)) => {
                    ctx.objects.take_shared(&mut gone.objects);
                    self.holders.insert(gone.group, other);
                    self.refresh_uses(other);
                }
                None => {
                    self.holders.remove(&gone.group);
                }
            }
        }
        Ok(())
    }

    /// Moves `context`'s share group's shared tables (buffers, textures, renderbuffers,
    /// framebuffers, shaders, programs) to it from the context that keeps them, so that it sees every object
    /// of the group while it is current.
    fn hold_shared(&mut self, context: EglHandle) {
        let Some(group) = self.contexts.get(&context).map(|c| c.group) else { return };
        match self.holders.insert(group, context) {
            Some(holder) if holder != context => {
                if let Some(mut from) = self.contexts.remove(&holder) {
                    if let Some(to) = self.contexts.get_mut(&context) {
                        to.objects.take_shared(&mut from.objects);
                    }
                    self.contexts.insert(holder, from);
                }
            }
            _ => {}
        }
        self.refresh_uses(context);
    }

    /// Notes, in `context`, which programs the other contexts of its group use, and deletes
    /// those whose deletion was pending and that no context uses any more.
    fn refresh_uses(&mut self, context: EglHandle) {
        let Some(group) = self.contexts.get(&context).map(|c| c.group) else { return };
        let others_use = self
            .contexts
            .iter()
            .filter(|(&id, c)| id != context && c.group == group)
            .flat_map(|(_, c)| {
                let pipelines = c.objects.pipelines.values().flat_map(|pl| [pl.vertex, pl.fragment, pl.active]);
                std::iter::once(c.bindings.program).chain(pipelines)
            })
            .filter(|&p| p != 0)
            .collect();
        let Some(ctx) = self.contexts.get_mut(&context) else { return };
        ctx.others_use = others_use;
        let pending: Vec<u32> =
            ctx.objects.programs.iter().filter(|(_, p)| p.delete_pending).map(|(&n, _)| n).collect();
        for program in pending {
            crate::linking::release_if_unused(ctx, program);
        }
    }

    /// The context that keeps `context`'s share group's shared tables.
    pub(super) fn holder(&self, context: EglHandle) -> EglHandle {
        self.contexts.get(&context).and_then(|c| self.holders.get(&c.group)).copied().unwrap_or(context)
    }

    pub(super) fn eglSwapBuffers(&mut self, display: EglHandle, surface: EglHandle) -> EglResult<()> {
        self.check_display(display)?;
        self.swap(surface, None)
    }

    /// `EGL_KHR_swap_buffers_with_damage`: a swap whose frame changed only within `rects`
    /// (x, y, width, height quadruples, GL coordinates): the compositor redraws only what they
    /// cover. No rectangles is the whole surface; a negative size is `EGL_BAD_PARAMETER`.
    pub(super) fn eglSwapBuffersWithDamageKHR(
        &mut self,
        display: EglHandle,
        surface: EglHandle,
        rects: Slice<'_, i32>,
    ) -> EglResult<()> {
        self.check_display(display)?;
        let rects = rects.to_vec();
        if !rects.len().is_multiple_of(4) || rects.chunks_exact(4).any(|r| r[2] < 0 || r[3] < 0) {
            return Err(EGL_BAD_PARAMETER);
        }
        let damage = (!rects.is_empty()).then(|| rects.chunks_exact(4).map(|r| [r[0], r[1], r[2], r[3]]).collect());
        self.swap(surface, damage)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_projection_declarations_are_bad_attributes() {
        use strata_protocol::projection::*;
        let near = (0.0f32).to_bits() as i32;
        let far = (1.0f32).to_bits() as i32;
        let attribs = |kind| {
            [
                EGL_WIDTH,
                4,
                EGL_PROJECTION_STRATA,
                kind,
                EGL_PROJECTION_NEAR_STRATA,
                near,
                EGL_PROJECTION_FAR_STRATA,
                far,
                EGL_NONE,
            ]
        };
        // Near 0 is fine for an orthographic projection, not for a perspective one.
        let p = declared_projection("test", &attribs(EGL_PROJECTION_ORTHOGRAPHIC_STRATA), true).expect("valid");
        assert_eq!(p.map(|p| (p.near, p.far)), Some((0.0, 1.0)));
        assert_eq!(
            declared_projection("test", &attribs(EGL_PROJECTION_PERSPECTIVE_STRATA), true),
            Err(EGL_BAD_ATTRIBUTE)
        );
        assert_eq!(declared_projection("test", &attribs(0x1234), false), Err(EGL_BAD_ATTRIBUTE));
        // Unknown attributes are not this extension's business; nothing declared is `None`.
        assert_eq!(declared_projection("test", &[0x7777, 1, EGL_NONE], true), Ok(None));
    }
}
