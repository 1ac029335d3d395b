//! Processes under other users: the users the tests run clients as, and whether the test may
//! start them (it must be root).

/// The user and group `nobody`/`nogroup` (65534 on Debian): the head unit's virtual machine.
pub const NOBODY: (u32, u32) = (65534, 65534);
/// User `daemon` (1 on Debian) in group `nogroup`, which may use the client socket: the
/// instrument cluster's virtual machine.
pub const IC_USER: (u32, u32) = (1, 65534);

/// Whether this test runs as root (needed to start processes as other users); says so when
/// it does not.
pub fn root() -> bool {
    // SAFETY: geteuid cannot fail.
    let root = unsafe { libc::geteuid() } == 0;
    if !root {
        eprintln!("skipped: starting clients as other users needs root");
    }
    root
}
