//! The scene's side of input routing: which surfaces could be under a point (shown, accepting
//! input, with a frame, their rectangle holding it), the texel of each that shows there, and
//! where a point lies in a surface's own pixels.

use std::sync::Arc;

use strata_protocol::projection::Projection;

use strata_device::Gpu;

use crate::mailbox::Images;
use crate::state::{Scene, SceneSurface};

/// A surface that may be shown under a point, with what decides whether it is.
pub struct Candidate {
    /// Surface ID.
    pub id: u64,
    /// Its client's number.
    pub client: u64,
    /// Stacking order (later wins equal depths).
    pub order: u64,
    /// Depth layer.
    pub z: f32,
    /// The texel shown at the point: x from the image's left, y from its bottom (GL order),
    /// the one the compositor's depth select reads.
    pub texel: [u32; 2],
    /// The point in the surface's image pixels (from its top-left corner).
    pub local: [f32; 2],
    /// Its newest frame's colour and depth on the compositor's device.
    pub shown: Images,
    /// The same frame on the pick device, where it imported it.
    pub pick: Option<Images>,
    /// Its colour's alpha reads as 1.
    pub opaque: bool,
    /// Its opacity, its layers' taken in.
    pub opacity: f32,
    /// Its declared projection.
    pub projection: Option<Projection>,
}

/// `a / b` rounded down (b > 0).
fn fdiv(a: i64, b: i64) -> i64 {
    a.div_euclid(b)
}

impl SceneSurface {
    /// Point `p` (output space) in its image's pixels, from the image's top-left corner: its
    /// destination region's offset and scale undone.
    pub fn local_point(&self, p: [f32; 2]) -> Option<[f32; 2]> {
        let r = self.source_region()?;
        let sx = (f64::from(p[0]) - f64::from(self.rect[0])) * f64::from(r[2]) / f64::from(self.rect[2].max(1));
        let sy = (f64::from(p[1]) - f64::from(self.rect[1])) * f64::from(r[3]) / f64::from(self.rect[3].max(1));
        Some([(f64::from(r[0]) + sx) as f32, (f64::from(r[1]) + sy) as f32])
    }

    /// The texel shown at output pixel `px` (x, y in the output space), as the compositor's
    /// depth select finds it: x from the image's left, y from its bottom; `None` outside its
    /// rectangle.
    fn texel_at(&self, px: [i64; 2]) -> Option<[u32; 2]> {
        let (lx, ly) = (px[0] - i64::from(self.rect[0]), px[1] - i64::from(self.rect[1]));
        if lx < 0 || ly < 0 || lx >= i64::from(self.rect[2]) || ly >= i64::from(self.rect[3]) {
            return None;
        }
        let r = self.source_region()?;
        // The source texel whose area holds the pixel's centre (`compositor::reference`).
        let nearest =
            |l: i64, o: i32, src: i32, n: i32| i64::from(o) + fdiv((2 * l + 1) * i64::from(src), 2 * i64::from(n));
        let sx = nearest(lx, r[0], r[2], self.rect[2]);
        let sy = i64::from(self.image[1]) - 1 - nearest(ly, r[1], r[3], self.rect[3]);
        Some([u32::try_from(sx).ok()?, u32::try_from(sy).ok()?])
    }
}

impl Scene {
    /// Names input routing's pick device (once): clients' shared buffers are imported on it
    /// too, so that a pick never waits behind the compositor's work.
    pub fn set_pick_device(&self, gpu: Arc<Gpu>) {
        let _ = self.pick_device.set(gpu);
    }

    /// Input routing's pick device, if one was named.
    pub fn pick_device(&self) -> Option<Arc<Gpu>> {
        self.pick_device.get().cloned()
    }

    /// The surfaces that may be shown at point `p` of the output space and accept input, in
    /// stacking order: visible (with their layers), opacity above 0, with a frame, their
    /// rectangle holding the point. Their frames are marked as picked until
    /// [`Scene::end_input_read`], so that no client draws into them meanwhile. With them, the
    /// damage count of the scene they belong to.
    pub fn input_candidates(&self, p: [f32; 2]) -> (u64, Vec<Candidate>) {
        let Some(mut g) = self.lock() else { return (0, Vec::new()) };
        let px = [f64::from(p[0]).floor() as i64, f64::from(p[1]).floor() as i64];
        let layers = g.layers.clone();
        let mut out = Vec::new();
        for s in g.surfaces.values_mut() {
            let (visible, opacity) = s.shown_in(&layers);
            if !visible || opacity <= 0.0 || !s.props.input || !s.can_show() {
                continue;
            }
            let (Some(color), Some(texel), Some(local)) = (s.color.clone(), s.texel_at(px), s.local_point(p)) else {
                continue;
            };
            s.buffers.pick_latest();
            out.push(Candidate {
                id: s.id,
                client: s.client_id,
                order: s.order,
                z: s.z,
                texel,
                local,
                shown: Images { color, depth: s.depth.clone() },
                pick: s.pick.clone(),
                opaque: s.opaque,
                opacity,
                projection: s.projection,
            });
        }
        out.sort_by_key(|c| c.order);
        (g.damage, out)
    }

    /// The reads [`Scene::input_candidates`] began on `candidates` are done.
    pub fn end_input_read(&self, candidates: &[Candidate]) {
        if let Some(mut g) = self.lock() {
            for s in g.surfaces.values_mut().filter(|s| candidates.iter().any(|c| c.id == s.id)) {
                s.buffers.done_picking();
            }
        }
        self.changed.notify_all();
    }

    /// Surface `id`'s client and point `p` (output space) in its image's pixels, if it exists.
    pub fn surface_point(&self, id: u64, p: [f32; 2]) -> Option<(u64, [f32; 2])> {
        let g = self.lock()?;
        let s = g.surfaces.values().find(|s| s.id == id)?;
        Some((s.client_id, s.local_point(p).unwrap_or([0.0, 0.0])))
    }

    /// Surface `id`'s client, if the surface exists and accepts input.
    pub fn input_client(&self, id: u64) -> Option<u64> {
        let g = self.lock()?;
        g.surfaces.values().find(|s| s.id == id && s.props.input).map(|s| s.client_id)
    }
}
