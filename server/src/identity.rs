//! Who a client is: the credentials the kernel gives for its connection (`SO_PEERCRED`), and
//! the configuration entries that require them. A name is what a client says; only an entry
//! whose `uid`/`user`/`gid`/`group` its credentials match gives it that entry's placement,
//! class, deadline, projection, surface IDs and quota. A client that claims such an entry's
//! name without them is treated as unnamed.

use strata_protocol::control::Peer;

use crate::credentials::Requirement;
use crate::layout::LayoutEntry;
use crate::quota::QuotaEntry;

/// The configuration entries a client gets.
#[derive(Debug, Clone, Copy, Default)]
pub struct Identity<'a> {
    /// Its layout entry.
    pub layout: Option<&'a LayoutEntry>,
    /// Its quota entry.
    pub quota: Option<&'a QuotaEntry>,
    /// Why it gets none although it claims an entry's name (its credentials do not match).
    pub refused: Option<(&'static str, Requirement)>,
}

impl Identity<'_> {
    /// The client's limits: its quota entry's over `base`.
    pub fn limits(&self, base: strata_device::account::Limits) -> strata_device::account::Limits {
        self.quota.map_or(base, |q| q.apply(base))
    }
}

/// The entries client `name`, connected with `peer`'s credentials, gets: the first layout and
/// the first quota entry naming it, unless either requires credentials that `peer` lacks, in
/// which case it gets neither (it is treated as unnamed).
pub fn identify<'a>(layout: &'a [LayoutEntry], quotas: &'a [QuotaEntry], name: &str, peer: &Peer) -> Identity<'a> {
    let l = crate::layout::find(layout, name);
    let q = quotas.iter().find(|e| e.client == name);
    let checks = [("[[layout]]", l.map(LayoutEntry::requirement)), ("[[quota]]", q.map(QuotaEntry::requirement))];
    for (what, req) in checks {
        if let Some(req) = req.filter(|r| !r.admits(peer)) {
            return Identity { layout: None, quota: None, refused: Some((what, req)) };
        }
    }
    Identity { layout: l, quota: q, refused: None }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_claimed_name_without_its_credentials_gets_no_entry() {
        let mut ic: LayoutEntry = "ic=0,0,0.5".parse().expect("entry");
        ic.uid = Some(1000);
        let quota = QuotaEntry { client: "ic".into(), textures: Some(10), ..Default::default() };
        let (layout, quotas) = (vec![ic], vec![quota]);
        let genuine = Peer { pid: 1, uid: 1000, gid: 1000, unverified: false };
        let id = identify(&layout, &quotas, "ic", &genuine);
        assert!(id.layout.is_some() && id.quota.is_some() && id.refused.is_none());
        let impostor = Peer { uid: 1001, ..genuine };
        let id = identify(&layout, &quotas, "ic", &impostor);
        assert!(id.layout.is_none() && id.quota.is_none(), "{id:?}");
        assert_eq!(id.refused.map(|r| r.0), Some("[[layout]]"));
        // A quota entry's own requirement refuses the layout entry too.
        let (mut layout, mut quotas) = (layout, quotas);
        layout[0].uid = None;
        quotas[0].gid = Some(5);
        let id = identify(&layout, &quotas, "ic", &genuine);
        assert!(id.layout.is_none() && id.quota.is_none() && id.refused.is_some(), "{id:?}");
        assert!(identify(&layout, &quotas, "other", &impostor).refused.is_none());
    }
}
