//! Surface IDs: stable ones that the layout, `STRATA_SURFACE_ID` or `EGL_SURFACE_ID_STRATA`
//! fix, and runtime ones for the rest, never shared by two live surfaces; the entries that
//! claim stable IDs for clients of given credentials; and the stacking order, which is
//! creation order whatever the IDs are.

use std::collections::BTreeMap;

use strata_protocol::control::{Peer, Requirement};

/// Why a stable ID asked for is not granted.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum IdRefused {
    /// A live surface holds it.
    #[error("surface id {id} is already held by a surface of client {holder:?}")]
    Taken {
        /// The ID asked for.
        id: u64,
        /// The name of the client whose surface holds it.
        holder: String,
    },
    /// A configuration entry reserves it for clients of other credentials.
    #[error("surface id {id} is reserved by the {entry} entry for clients with {requires}")]
    Reserved {
        /// The ID asked for.
        id: u64,
        /// The entry that reserves it (`[[layout]] "instrument-cluster"`, `[[surface]] 1000`).
        entry: String,
        /// The credentials that entry requires.
        requires: Requirement,
    },
}

impl IdRefused {
    /// The ID asked for.
    pub fn id(&self) -> u64 {
        match self {
            IdRefused::Taken { id, .. } | IdRefused::Reserved { id, .. } => *id,
        }
    }
}

/// Where IDs and stacking positions come from.
#[derive(Debug, Default)]
pub struct Ids {
    /// The last runtime ID handed out.
    last_runtime: u64,
    /// The last stacking position handed out.
    last_order: u64,
    /// IDs the configuration names: runtime IDs skip them, so that the client they are for
    /// finds them free; with the entries that claim each for clients of given credentials.
    reserved: BTreeMap<u64, Vec<(String, Requirement)>>,
}

impl Ids {
    /// Keeps `id` out of the runtime IDs; with `claim` (an entry's name and the credentials it
    /// requires), only clients whose credentials it admits may take `id` at all.
    pub fn reserve(&mut self, id: u64, claim: Option<(String, Requirement)>) {
        let claims = self.reserved.entry(id).or_default();
        claims.extend(claim.filter(|(_, r)| r.any()));
    }

    /// An ID and a stacking position for a new surface of a client connected with `peer`'s
    /// credentials: `asked`, unless an entry reserves it for other credentials or a live
    /// surface holds it (`holder` says which client's, if any); or else the next runtime ID
    /// that is neither live nor reserved.
    pub fn assign(
        &mut self,
        asked: Option<u64>,
        peer: Option<&Peer>,
        holder: impl Fn(u64) -> Option<String>,
    ) -> Result<(u64, u64), IdRefused> {
        let id = match asked {
            Some(id) => {
                let claims = self.reserved.get(&id).map_or(&[][..], Vec::as_slice);
                if let Some((entry, requires)) = claims.iter().find(|(_, r)| !peer.is_some_and(|p| r.admits(p))) {
                    return Err(IdRefused::Reserved { id, entry: entry.clone(), requires: *requires });
                }
                match holder(id) {
                    Some(holder) => return Err(IdRefused::Taken { id, holder }),
                    None => id,
                }
            }
            None => loop {
                self.last_runtime += 1;
                let id = self.last_runtime;
                if !self.reserved.contains_key(&id) && holder(id).is_none() {
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
        ids.reserve(2, None);
        let mut live: Vec<(u64, &str)> = Vec::new();
        let add = |ids: &mut Ids, live: &mut Vec<(u64, &str)>, asked, who| {
            let holder = |id| live.iter().find(|(l, _)| *l == id).map(|(_, w): &(u64, &str)| w.to_string());
            let got = ids.assign(asked, Some(&Peer::default()), holder);
            if let Ok((id, _)) = got {
                live.push((id, who));
            }
            got
        };
        assert_eq!(add(&mut ids, &mut live, None, "a"), Ok((1, 1)));
        assert_eq!(add(&mut ids, &mut live, Some(3), "ic"), Ok((3, 2)));
        assert_eq!(add(&mut ids, &mut live, None, "b"), Ok((4, 3)), "2 is the layout's, 3 is live");
        assert_eq!(add(&mut ids, &mut live, Some(3), "hu"), Err(IdRefused::Taken { id: 3, holder: "ic".into() }));
        assert_eq!(
            add(&mut ids, &mut live, Some(2), "c"),
            Ok((2, 4)),
            "a reserved id without credentials is free to claim"
        );
    }

    #[test]
    fn an_id_claimed_for_credentials_goes_only_to_clients_that_have_them() {
        let mut ids = Ids::default();
        let ic = Requirement { uid: Some(1), gid: None };
        ids.reserve(1000, Some(("[[layout]] \"ic\"".into(), ic)));
        ids.reserve(1000, Some(("[[surface]] 1000".into(), Requirement { uid: None, gid: Some(7) })));
        let peer = |uid, gid| Peer { pid: 9, uid, gid, unverified: false };
        let free = |_| None;
        let hu = ids.assign(Some(1000), Some(&peer(65534, 7)), free);
        let Err(IdRefused::Reserved { id: 1000, entry, requires }) = hu else { panic!("{hu:?}") };
        assert_eq!((entry.as_str(), requires), ("[[layout]] \"ic\"", ic));
        let wrong_group = ids.assign(Some(1000), Some(&peer(1, 8)), free);
        assert!(matches!(&wrong_group, Err(IdRefused::Reserved { entry, .. }) if entry == "[[surface]] 1000"));
        assert!(ids.assign(Some(1000), None, free).is_err(), "no credentials, no claimed id");
        assert_eq!(ids.assign(Some(1000), Some(&peer(1, 7)), free), Ok((1000, 1)));
        // Runtime IDs still skip it, and other IDs stay free to all.
        assert_eq!(ids.assign(Some(5), Some(&peer(65534, 0)), free), Ok((5, 2)));
    }
}
