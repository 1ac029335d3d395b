//! Who a client is: the credentials the kernel gives for its connection (`SO_PEERCRED`), and
//! the configuration entries they earn it. An entry either names a client (`client = "ic"`)
//! or, without a name, matches by credentials alone (`user = "hu-vm"`), so that an integrator
//! binds a virtual machine's user to its limits whatever that machine calls its clients.
//!
//! Credentials bind before names: a client gets the first entry that requires credentials,
//! admits its own, and either names it or has no name; only without one, the first entry that
//! names it and requires nothing. So a user bound to an entry cannot escape it by calling
//! itself after another. A name is only what a client says: a client that claims the name of
//! entries whose credentials it lacks is treated as unnamed, and gets only entries matched by
//! credentials.

use strata_protocol::control::Peer;

use crate::credentials::Requirement;
use crate::layout::LayoutEntry;
use crate::quota::QuotaEntry;

/// A configuration entry a client may get.
pub trait Entry {
    /// The client name it applies to; empty: by credentials alone.
    fn name(&self) -> &str;
    /// The credentials a client needs to get it.
    fn requirement(&self) -> Requirement;
    /// How log lines and refusals name it: `"ic"`, or the credentials of a nameless entry.
    fn label(&self) -> String {
        match self.name() {
            "" => format!("for {}", self.requirement()),
            name => format!("{name:?}"),
        }
    }
}

impl Entry for LayoutEntry {
    fn name(&self) -> &str {
        &self.client
    }
    fn requirement(&self) -> Requirement {
        LayoutEntry::requirement(self)
    }
}

impl Entry for QuotaEntry {
    fn name(&self) -> &str {
        &self.client
    }
    fn requirement(&self) -> Requirement {
        QuotaEntry::requirement(self)
    }
}

/// The configuration entries a client gets.
#[derive(Debug, Clone, Copy, Default)]
pub struct Identity<'a> {
    /// Its layout entry.
    pub layout: Option<&'a LayoutEntry>,
    /// Its quota entry, and that entry's place among the `[[quota]]` entries.
    pub quota: Option<(usize, &'a QuotaEntry)>,
    /// Why it is treated as unnamed although it claims an entry's name: the section and the
    /// credentials that entry requires.
    pub refused: Option<(&'static str, Requirement)>,
}

impl Identity<'_> {
    /// The client's limits: its quota entry's over `base`.
    pub fn limits(&self, base: strata_device::account::Limits) -> strata_device::account::Limits {
        self.quota.map_or(base, |(_, q)| q.apply(base))
    }
}

/// Whether some entry names `name` and none of those that do admits `peer`.
fn claims_without_credentials<E: Entry>(entries: &[E], name: &str, peer: &Peer) -> Option<Requirement> {
    let mut named = entries.iter().filter(|e| !name.is_empty() && e.name() == name).peekable();
    let first = named.peek().map(|e| e.requirement());
    if named.any(|e| e.requirement().admits(peer)) {
        return None;
    }
    first
}

/// The entry `peer` gets (see the module): `name` counts unless `named` is false. A nameless
/// entry always requires credentials (the configuration refuses one that does not).
fn pick<'a, E: Entry>(entries: &'a [E], name: &str, peer: &Peer, named: bool) -> Option<(usize, &'a E)> {
    let names = |e: &E| named && !name.is_empty() && e.name() == name;
    let bound = entries.iter().enumerate().find(|(_, e)| {
        let r = e.requirement();
        r.any() && r.admits(peer) && (e.name().is_empty() || names(e))
    });
    bound.or_else(|| entries.iter().enumerate().find(|(_, e)| !e.requirement().any() && names(e)))
}

/// The entries client `name`, connected with `peer`'s credentials, gets (see the module).
pub fn identify<'a>(layout: &'a [LayoutEntry], quotas: &'a [QuotaEntry], name: &str, peer: &Peer) -> Identity<'a> {
    let refused = claims_without_credentials(layout, name, peer)
        .map(|r| ("[[layout]]", r))
        .or_else(|| claims_without_credentials(quotas, name, peer).map(|r| ("[[quota]]", r)));
    let named = refused.is_none();
    Identity {
        layout: pick(layout, name, peer, named).map(|(_, e)| e),
        quota: pick(quotas, name, peer, named),
        refused,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn peer(uid: u32) -> Peer {
        Peer { pid: 1, uid, gid: uid, unverified: false }
    }

    #[test]
    fn a_claimed_name_without_its_credentials_gets_no_entry() {
        let mut ic: LayoutEntry = "ic=0,0,0.5".parse().expect("entry");
        ic.uid = Some(1000);
        let quota = QuotaEntry { client: "ic".into(), textures: Some(10), ..Default::default() };
        let (layout, quotas) = (vec![ic], vec![quota]);
        let genuine = peer(1000);
        let id = identify(&layout, &quotas, "ic", &genuine);
        assert!(id.layout.is_some() && id.quota.is_some() && id.refused.is_none());
        let impostor = peer(1001);
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

    #[test]
    fn an_entry_without_a_name_binds_its_user_whatever_the_client_calls_itself() {
        let mut ic: LayoutEntry = "ic=0,0,0.5".parse().expect("entry");
        ic.uid = Some(1000);
        let mut hu: LayoutEntry = "hu=100,0,1".parse().expect("entry");
        (hu.client, hu.uid, hu.priority) = (String::new(), Some(2000), Some(strata_protocol::control::Priority::Low));
        let hu_quota =
            QuotaEntry { uid: Some(2000), gpu_bytes: Some(crate::quota::ByteSize(1 << 20)), ..Default::default() };
        let named_quota =
            QuotaEntry { client: "x".into(), gpu_bytes: Some(crate::quota::ByteSize(8 << 30)), ..Default::default() };
        let (layout, quotas) = (vec![ic, hu], vec![named_quota, hu_quota]);
        let base = strata_device::account::Limits::default();
        // Whatever the head unit's user calls itself (nothing, another name, the IC's name),
        // it gets its own entries.
        for name in ["", "x", "ic", "hu"] {
            let id = identify(&layout, &quotas, name, &peer(2000));
            assert_eq!(id.layout.map(|e| e.x), Some(100), "{name:?}");
            assert_eq!(id.quota.map(|(i, _)| i), Some(1), "{name:?}");
            assert_eq!(id.limits(base).gpu_bytes, 1 << 20, "{name:?}");
            assert_eq!(id.refused.is_some(), name == "ic", "{name:?}");
        }
        // Other users are not matched by it; the IC keeps its own entry.
        let other = identify(&layout, &quotas, "x", &peer(3000));
        assert!(other.layout.is_none() && other.quota.map(|(i, _)| i) == Some(0), "{other:?}");
        assert_eq!(identify(&layout, &quotas, "ic", &peer(1000)).layout.map(|e| e.x), Some(0));
        assert_eq!(layout[1].label(), "for uid 2000");
        // Two entries may give one name to two users.
        let mut second: LayoutEntry = "ic=7,0,0.5".parse().expect("entry");
        second.uid = Some(1001);
        let layout = vec![layout[0].clone(), second];
        let id = identify(&layout, &[], "ic", &peer(1001));
        assert!(id.refused.is_none() && id.layout.map(|e| e.x) == Some(7), "{id:?}");
    }
}
