//! Surfaces' placement and compositing properties: position, depth layer and normal,
//! visibility, opacity, source and destination regions, and layers (named groups of surfaces with a visibility and an opacity of their
//! own). A batch of changes is checked whole and applied under the scene's lock with one
//! damage, so that a composite, which takes the scene under the same lock, shows all of it or
//! none of it.

use strata_protocol::control::SurfaceRow;
use strata_protocol::properties::{Change, ChangeError, LayerRow, Rect};

use crate::layers::{LayerState, Layers};
use crate::presets::{LayerEntry, SurfaceEntry};
use crate::region::{intersect, Region};
use crate::state::{Scene, SceneSurface, State};

impl SceneSurface {
    /// Whether it shows and its opacity, its layers taken in: visible only if it and every
    /// layer holding it are; the opacity is the product of its own and theirs.
    pub fn shown_in(&self, layers: &Layers) -> (bool, f32) {
        layers
            .values()
            .filter(|l| l.surfaces.contains(&self.id))
            .fold((self.props.visible, self.props.opacity), |(v, a), l| (v && l.visible, a * l.opacity))
    }

    /// The source region in effect: the one set, clipped to the image, else the whole image;
    /// `None` where nothing of the image is left.
    pub fn source_region(&self) -> Option<Rect> {
        let whole = [0, 0, self.image[0], self.image[1]];
        intersect(self.props.source.unwrap_or(whole), whole)
    }

    /// Whether anything of it can show: a rectangle and a source region that are not empty.
    pub fn can_show(&self) -> bool {
        self.rect[2] > 0 && self.rect[3] > 0 && self.source_region().is_some()
    }

    /// Whether it shows its image exactly as drawn: no source or destination region set.
    pub fn exact(&self) -> bool {
        self.props.source.is_none() && self.props.destination.is_none()
    }
}

/// Finds live surface `id`.
fn surface(st: &mut State, id: u64) -> Result<&mut SceneSurface, ChangeError> {
    st.surfaces.values_mut().find(|s| s.id == id).ok_or(ChangeError::NoSurface(id))
}

/// The rectangles of layer `name`'s live members.
fn member_rects(st: &State, name: &str) -> Region {
    let Some(l) = st.layers.get(name) else { return Region::None };
    st.surfaces.values().filter(|s| l.surfaces.contains(&s.id)).fold(Region::None, |r, s| r.with(s.rect))
}

/// Applies one checked change to `st`, adding what it changes on the output to `damage`.
fn apply_one(st: &mut State, c: &Change, damage: &mut Region) -> Result<(), ChangeError> {
    let layer = |st: &mut State, name: &str| -> Result<(), ChangeError> {
        st.layers.contains_key(name).then_some(()).ok_or_else(|| ChangeError::NoLayer(name.to_string()))
    };
    match c {
        Change::Visibility { surface: id, visible } => {
            let s = surface(st, *id)?;
            s.props.visible = *visible;
            *damage = damage.with(s.rect);
        }
        Change::Opacity { surface: id, opacity } => {
            let s = surface(st, *id)?;
            s.props.opacity = *opacity;
            *damage = damage.with(s.rect);
        }
        Change::InputAcceptance { surface: id, accepts } => {
            // Nothing changes on the output.
            surface(st, *id)?.props.input = *accepts;
        }
        Change::SourceRegion { surface: id, region } => {
            let s = surface(st, *id)?;
            s.props.source = Some(*region);
            *damage = damage.with(s.rect);
        }
        Change::DestinationRegion { surface: id, region } => {
            let s = surface(st, *id)?;
            *damage = damage.with(s.rect).with(*region);
            s.props.destination = Some(*region);
            s.rect = *region;
        }
        Change::LayerCreate { layer: name } => {
            if st.layers.contains_key(name) {
                return Err(ChangeError::LayerExists(name.clone()));
            }
            st.layers.insert(name.clone(), LayerState::default());
        }
        Change::LayerDestroy { layer: name } => {
            layer(st, name)?;
            *damage = damage.union(member_rects(st, name));
            st.layers.remove(name);
        }
        Change::LayerAdd { layer: name, surface: id } => {
            layer(st, name)?;
            let r = surface(st, *id)?.rect;
            *damage = damage.with(r);
            st.layers.entry(name.clone()).or_default().surfaces.insert(*id);
        }
        Change::LayerRemove { layer: name, surface: id } => {
            layer(st, name)?;
            if let Ok(s) = surface(st, *id) {
                *damage = damage.with(s.rect);
            }
            if !st.layers.entry(name.clone()).or_default().surfaces.remove(id) {
                return Err(ChangeError::NotMember { layer: name.clone(), surface: *id });
            }
        }
        Change::LayerVisibility { layer: name, visible } => {
            layer(st, name)?;
            *damage = damage.union(member_rects(st, name));
            st.layers.entry(name.clone()).or_default().visible = *visible;
        }
        Change::LayerOpacity { layer: name, opacity } => {
            layer(st, name)?;
            *damage = damage.union(member_rects(st, name));
            st.layers.entry(name.clone()).or_default().opacity = *opacity;
        }
    }
    Ok(())
}

impl State {
    /// Gives surface `id`, just added, what the configuration's `[[surface]]` entry for it says.
    pub(crate) fn apply_preset(&mut self, id: u64) {
        let st = self;
        let Some(e) = st.presets.get(&id).cloned() else { return };
        let mut damage = Region::None;
        if let Ok(s) = surface(st, id) {
            s.rect[0] = e.x.unwrap_or(s.rect[0]);
            s.rect[1] = e.y.unwrap_or(s.rect[1]);
            s.z = e.z.unwrap_or(s.z);
            s.normal = e.normal.unwrap_or(s.normal);
        }
        for c in e.changes() {
            // Checked when the configuration was read; a surface has no frame to damage yet.
            let _ = apply_one(st, &c, &mut damage);
        }
    }
}

impl Scene {
    /// Takes the configuration's surface entries (applied to each such surface when it
    /// appears) and creates its layers.
    pub fn configure(&self, surfaces: &[SurfaceEntry], layers: &[LayerEntry]) {
        let Some(mut g) = self.lock() else { return };
        g.presets = surfaces.iter().map(|e| (e.id, e.clone())).collect();
        for l in layers {
            let state =
                LayerState { visible: l.visible, opacity: l.opacity, surfaces: l.surfaces.iter().copied().collect() };
            g.layers.insert(l.name.clone(), state);
        }
    }

    /// Applies `changes` in order, in one step: every composite shows all of them or none. If
    /// any fails (a bad value, an unknown surface or layer), the scene is left as it was and
    /// the error names the change (a batch of one answers with its own error).
    pub fn apply(&self, changes: &[Change]) -> Result<(), ChangeError> {
        strata_protocol::properties::validate_batch(changes)?;
        let Some(mut g) = self.lock() else { return Err(ChangeError::Unavailable) };
        // What a change can alter, kept to put back if a later one fails.
        let kept: Vec<_> = g.surfaces.iter().map(|(k, s)| (*k, s.rect, s.props)).collect();
        let layers = g.layers.clone();
        let mut damage = Region::None;
        for (i, c) in changes.iter().enumerate() {
            if let Err(e) = apply_one(&mut g, c, &mut damage) {
                for (k, rect, props) in kept {
                    if let Some(s) = g.surfaces.get_mut(&k) {
                        s.rect = rect;
                        s.props = props;
                    }
                }
                g.layers = layers;
                return Err(e.at(i, changes.len()));
            }
        }
        if damage != Region::None {
            self.damaged(g, damage);
        } else {
            drop(g);
        }
        for c in changes {
            self.emit(strata_protocol::events::Event::Changed(c.clone()));
        }
        Ok(())
    }

    /// Moves surface `id`; returns its new row, or `None` if there is no such surface.
    pub fn move_surface(&self, id: u64, x: i32, y: i32, z: f32) -> Option<SurfaceRow> {
        let mut g = self.lock()?;
        let st = &mut *g;
        let s = st.surfaces.values_mut().find(|s| s.id == id)?;
        let old = s.rect;
        s.rect[0] = x;
        s.rect[1] = y;
        if let Some(d) = &mut s.props.destination {
            d[0] = x;
            d[1] = y;
        }
        s.z = z;
        let row = s.row(&st.layers);
        let region = Region::None.with(old).with(row.rect);
        self.damaged(g, region);
        Some(row)
    }

    /// Sets surface `id`'s normal; returns its new row, or `None` if there is no such surface.
    pub fn set_normal(&self, id: u64, normal: [f32; 3]) -> Option<SurfaceRow> {
        let mut g = self.lock()?;
        let st = &mut *g;
        let s = st.surfaces.values_mut().find(|s| s.id == id)?;
        s.normal = normal;
        let row = s.row(&st.layers);
        // Only lit pixels change, and only with per-surface normals; redraw the surface.
        self.damaged(g, Region::None.with(row.rect));
        Some(row)
    }

    /// Every layer, by name.
    pub fn layers(&self) -> Vec<LayerRow> {
        let Some(g) = self.lock() else { return Vec::new() };
        g.layers
            .iter()
            .map(|(name, l)| LayerRow {
                name: name.clone(),
                visible: l.visible,
                opacity: l.opacity,
                surfaces: l.surfaces.iter().copied().collect(),
            })
            .collect()
    }
}
