//! Surface IDs: stable ones that the layout, `STRATA_SURFACE_ID` or `EGL_SURFACE_ID_STRATA`
//! fix, and runtime ones for the rest, never shared by two live surfaces; and the stacking
//! order, which is creation order whatever the IDs are.

use std::collections::BTreeSet;

/// A stable ID already held by a live surface.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("surface id {id} is already held by a surface of client {holder:?}")]
pub struct IdTaken {
    /// The ID asked for.
    pub id: u64,
    /// The name of the client whose surface holds it.
    pub holder: String,
}

/// Where IDs and stacking positions come from.
#[derive(Debug, Default)]
pub struct Ids {
    /// The last runtime ID handed out.
    last_runtime: u64,
    /// The last stacking position handed out.
    last_order: u64,
    /// IDs the layout assigns: runtime IDs skip them, so that the client they are for finds
    /// them free.
    reserved: BTreeSet<u64>,
}

impl Ids {
    /// Keeps `ids` (the layout's) out of the runtime IDs.
    pub fn reserve(&mut self, ids: impl IntoIterator<Item = u64>) {
        self.reserved.extend(ids);
    }

    /// An ID and a stacking position for a new surface: `asked`, unless a live surface holds
    /// it (`holder` says which client's, if any), or else the next runtime ID that is neither
    /// live nor reserved.
    pub fn assign(
        &mut self,
        asked: Option<u64>,
        holder: impl Fn(u64) -> Option<String>,
    ) -> Result<(u64, u64), IdTaken> {
        let id = match asked {
            Some(id) => match holder(id) {
                Some(holder) => return Err(IdTaken { id, holder }),
                None => id,
            },
            None => loop {
                self.last_runtime += 1;
                let id = self.last_runtime;
                if !self.reserved.contains(&id) && holder(id).is_none() {
                    break id;
                }
            },
        };
        self.last_order += 1;
        Ok((id, self.last_order))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stable_ids_and_runtime_ids_never_collide() {
        let mut ids = Ids::default();
        ids.reserve([2]);
        let mut live: Vec<(u64, &str)> = Vec::new();
        let add = |ids: &mut Ids, live: &mut Vec<(u64, &str)>, asked, who| {
            let holder = |id| live.iter().find(|(l, _)| *l == id).map(|(_, w): &(u64, &str)| w.to_string());
            let got = ids.assign(asked, holder);
            if let Ok((id, _)) = got {
                live.push((id, who));
            }
            got
        };
        assert_eq!(add(&mut ids, &mut live, None, "a"), Ok((1, 1)));
        assert_eq!(add(&mut ids, &mut live, Some(3), "ic"), Ok((3, 2)));
        assert_eq!(add(&mut ids, &mut live, None, "b"), Ok((4, 3)), "2 is the layout's, 3 is live");
        assert_eq!(add(&mut ids, &mut live, Some(3), "hu"), Err(IdTaken { id: 3, holder: "ic".into() }));
        assert_eq!(add(&mut ids, &mut live, Some(2), "c"), Ok((2, 4)), "a reserved id is free to claim");
    }
}
