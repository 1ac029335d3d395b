//! The credentials a configuration entry requires (`uid`/`user`/`gid`/`group`), resolved from
//! the names the configuration gives, and whether a connection's credentials meet them.

/// A user or group name in the configuration that this machine does not have.
#[derive(Debug, thiserror::Error)]
pub enum IdentityError {
    /// No such user.
    #[error("no user named {0:?} on this machine")]
    UnknownUser(String),
    /// No such group.
    #[error("no group named {0:?} on this machine")]
    UnknownGroup(String),
    /// A name and a number that disagree.
    #[error("{what} {name:?} is {id}, not {given} as the entry also says")]
    Disagree {
        /// `user` or `group`.
        what: &'static str,
        /// The name.
        name: String,
        /// Its number on this machine.
        id: u32,
        /// The number the entry gives.
        given: u32,
    },
}

/// Looks a name up in the passwd (`group = false`) or group database.
fn lookup(name: &str, group: bool) -> Option<u32> {
    let cname = std::ffi::CString::new(name).ok()?;
    let mut buf = vec![0u8; 16 << 10];
    // SAFETY: the *_r lookups write only into the structs and `buf` we pass, with its length;
    // `found` is null or points at our struct.
    unsafe {
        if group {
            let mut grp: libc::group = std::mem::zeroed();
            let mut found = std::ptr::null_mut();
            let r = libc::getgrnam_r(cname.as_ptr(), &mut grp, buf.as_mut_ptr().cast(), buf.len(), &mut found);
            (r == 0 && !found.is_null()).then_some(grp.gr_gid)
        } else {
            let mut pwd: libc::passwd = std::mem::zeroed();
            let mut found = std::ptr::null_mut();
            let r = libc::getpwnam_r(cname.as_ptr(), &mut pwd, buf.as_mut_ptr().cast(), buf.len(), &mut found);
            (r == 0 && !found.is_null()).then_some(pwd.pw_uid)
        }
    }
}

/// The user ID of user `name`.
pub fn user_id(name: &str) -> Result<u32, IdentityError> {
    lookup(name, false).ok_or_else(|| IdentityError::UnknownUser(name.into()))
}

/// The group ID of group `name`.
pub fn group_id(name: &str) -> Result<u32, IdentityError> {
    lookup(name, true).ok_or_else(|| IdentityError::UnknownGroup(name.into()))
}

/// Resolves an entry's `user`/`group` names into its `uid`/`gid`, checking they agree where
/// both are given.
pub fn resolve(
    uid: &mut Option<u32>,
    user: Option<&str>,
    gid: &mut Option<u32>,
    group: Option<&str>,
) -> Result<(), IdentityError> {
    for (id, name, what) in [(uid, user, "user"), (gid, group, "group")] {
        let Some(name) = name else { continue };
        let found = if what == "user" { user_id(name)? } else { group_id(name)? };
        match *id {
            Some(given) if given != found => {
                return Err(IdentityError::Disagree { what, name: name.into(), id: found, given })
            }
            _ => *id = Some(found),
        }
    }
    Ok(())
}

pub use strata_protocol::control::Requirement;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn root_resolves_and_unknown_names_are_refused_by_name() {
        assert_eq!(user_id("root").expect("root"), 0);
        assert_eq!(group_id("root").expect("root"), 0);
        let e = user_id("no-such-user-strata").expect_err("unknown");
        assert!(e.to_string().contains("\"no-such-user-strata\""), "{e}");
        let (mut uid, mut gid) = (Some(5), None);
        let e = resolve(&mut uid, Some("root"), &mut gid, None).expect_err("disagree");
        assert!(e.to_string().contains("is 0, not 5"), "{e}");
        let (mut uid, mut gid) = (None, None);
        resolve(&mut uid, Some("root"), &mut gid, Some("root")).expect("resolves");
        assert_eq!((uid, gid), (Some(0), Some(0)));
    }

    #[test]
    fn a_requirement_admits_only_matching_credentials() {
        let peer = |uid, gid| strata_protocol::control::Peer { pid: 1, uid, gid, unverified: false };
        let r = Requirement { uid: Some(1000), gid: None };
        assert!(r.admits(&peer(1000, 5)) && !r.admits(&peer(1001, 5)));
        let r = Requirement { uid: None, gid: Some(7) };
        assert!(r.admits(&peer(3, 7)) && !r.admits(&peer(3, 8)));
        assert!(Requirement::default().admits(&peer(9, 9)) && !Requirement::default().any());
    }
}
