//! Per-client resource limits and the accounting behind them: GPU memory bytes, object counts,
//! window surfaces and the size of one command, per client and in total across clients.
//!
//! Every allocation a client causes is reserved against its [`Account`] before it is made. A
//! [`Reservation`] returns what it holds when it is dropped, so an object deleted, a context
//! destroyed or a client gone gives its bytes back without bookkeeping at each site. A refused
//! reservation is the client's `GL_OUT_OF_MEMORY` or `EGL_BAD_ALLOC`, logged once per kind and
//! client, and changes nothing else.
//!
//! What the daemon holds in its own memory for a client (its segment, a command being
//! assembled from chunks) is charged the same way ([`Account::hold`]), before it is
//! allocated, to a limit and a pool of its own: system memory, not the GPU's.
//!
//! The pool may hold back a reserve that only accounts of the reserved class draw on
//! ([`Pool::with_reserve`]), so that lower classes together never take what the instrument
//! cluster needs.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;

use serde::{Deserialize, Serialize};
use tracing::warn;

/// What is counted per client.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Kind {
    /// Buffer objects.
    Buffer,
    /// Texture objects.
    Texture,
    /// Renderbuffer objects.
    Renderbuffer,
    /// Framebuffer objects.
    Framebuffer,
    /// Shader objects.
    Shader,
    /// Program objects.
    Program,
    /// Vertex array objects.
    VertexArray,
    /// EGL contexts.
    Context,
    /// EGL surfaces (window and pbuffer).
    Surface,
}

impl Kind {
    /// Every kind, in the order of [`Usage::counts`].
    pub const ALL: [Kind; 9] = [
        Kind::Buffer,
        Kind::Texture,
        Kind::Renderbuffer,
        Kind::Framebuffer,
        Kind::Shader,
        Kind::Program,
        Kind::VertexArray,
        Kind::Context,
        Kind::Surface,
    ];

    /// The plural name used in options, configuration and `ctl stats`.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Buffer => "buffers",
            Kind::Texture => "textures",
            Kind::Renderbuffer => "renderbuffers",
            Kind::Framebuffer => "framebuffers",
            Kind::Shader => "shaders",
            Kind::Program => "programs",
            Kind::VertexArray => "vertex_arrays",
            Kind::Context => "contexts",
            Kind::Surface => "surfaces",
        }
    }

    fn index(self) -> usize {
        self as usize
    }
}

/// One client's limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Limits {
    /// GPU memory: buffers, texture and renderbuffer images, surfaces' colour and depth.
    pub gpu_bytes: u64,
    /// Objects of each kind, in the order of [`Kind::ALL`].
    pub counts: [u64; 9],
    /// The largest single command (an upload included), encoded.
    pub command_bytes: u64,
    /// Memory the daemon holds for the client in its own process: its segment, and a command
    /// being assembled from chunks.
    #[serde(default = "default_daemon_bytes")]
    pub daemon_bytes: u64,
}

/// 512 MiB: a segment and the largest default command, with room to spare.
fn default_daemon_bytes() -> u64 {
    512 << 20
}

impl Default for Limits {
    /// Generous: 2 GiB of GPU memory, 65,536 buffers, textures, renderbuffers, framebuffers,
    /// shaders, programs and vertex arrays, 64 contexts and 64 surfaces, 256 MiB commands and
    /// 512 MiB of the daemon's memory.
    fn default() -> Self {
        let mut counts = [65_536; 9];
        counts[Kind::Context.index()] = 64;
        counts[Kind::Surface.index()] = 64;
        Limits { gpu_bytes: 2 << 30, counts, command_bytes: 256 << 20, daemon_bytes: default_daemon_bytes() }
    }
}

impl Limits {
    /// No limit at all (tests and tools that run an executor alone).
    pub fn unlimited() -> Self {
        Limits { gpu_bytes: u64::MAX, counts: [u64::MAX; 9], command_bytes: u64::MAX, daemon_bytes: u64::MAX }
    }

    /// The limit on `kind`.
    pub fn count(&self, kind: Kind) -> u64 {
        self.counts[kind.index()]
    }

    /// Sets the limit on `kind`.
    pub fn set_count(&mut self, kind: Kind, limit: u64) {
        self.counts[kind.index()] = limit;
    }
}

/// A reservation that does not fit.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Exceeded {
    /// The client has as many objects of a kind as it may.
    #[error("{limit} {} is the most this client may have", .kind.name())]
    Count {
        /// The kind.
        kind: Kind,
        /// Its limit.
        limit: u64,
    },
    /// The client's GPU memory would exceed its limit.
    #[error("{need} more bytes of GPU memory would exceed this client's {limit}-byte limit ({used} in use)")]
    Bytes {
        /// Bytes asked for.
        need: u64,
        /// Bytes the client holds.
        used: u64,
        /// Its limit.
        limit: u64,
    },
    /// The daemon's memory held for the client would exceed its limit.
    #[error("{need} more bytes of the daemon's memory would exceed this client's {limit}-byte limit ({used} in use)")]
    Daemon {
        /// Bytes asked for.
        need: u64,
        /// Bytes held for the client.
        used: u64,
        /// Its limit.
        limit: u64,
    },
    /// All clients together would exceed the daemon's total (or, for a class without the
    /// reserve, the total less the reserve).
    #[error(
        "{need} more bytes of {what} would exceed the daemon's {limit}-byte total for all clients of its class ({used} in \
         use)"
    )]
    Total {
        /// `GPU memory` or `the daemon's memory`.
        what: &'static str,
        /// Bytes asked for.
        need: u64,
        /// Bytes all clients hold.
        used: u64,
        /// The daemon's total.
        limit: u64,
    },
    /// One command is larger than the client may send.
    #[error("a command of {len} bytes exceeds this client's {limit}-byte limit on one command")]
    Command {
        /// The command's encoded size.
        len: u64,
        /// The limit.
        limit: u64,
    },
}

/// The memory all clients together may hold, and the reserve of it that only the reserved
/// class draws on.
#[derive(Debug)]
pub struct Pool {
    /// What it holds (`GPU memory`), for refusals.
    what: &'static str,
    limit: u64,
    used: AtomicU64,
    /// Bytes that accounts without access to the reserve may not take.
    reserve: u64,
    /// Bytes held by accounts without access to the reserve.
    used_unreserved: AtomicU64,
}

impl Pool {
    /// A pool of `limit` bytes of GPU memory.
    pub fn new(limit: u64) -> Arc<Self> {
        Pool::with_reserve(limit, 0)
    }

    /// A pool of `limit` bytes of the daemon's own memory.
    pub fn daemon(limit: u64) -> Arc<Self> {
        let (used, used_unreserved) = (AtomicU64::new(0), AtomicU64::new(0));
        Arc::new(Pool { what: "the daemon's memory", limit, used, reserve: 0, used_unreserved })
    }

    /// A pool of `limit` bytes of which accounts without access to the reserve (see
    /// [`Account::new`]) together hold at most `limit - reserve`.
    pub fn with_reserve(limit: u64, reserve: u64) -> Arc<Self> {
        let (used, used_unreserved) = (AtomicU64::new(0), AtomicU64::new(0));
        Arc::new(Pool { what: "GPU memory", limit, used, reserve: reserve.min(limit), used_unreserved })
    }

    /// The reserve.
    pub fn reserve(&self) -> u64 {
        self.reserve
    }

    /// Bytes held by all clients.
    pub fn used(&self) -> u64 {
        self.used.load(Ordering::Relaxed)
    }

    /// The total limit.
    pub fn limit(&self) -> u64 {
        self.limit
    }

    fn take(&self, need: u64, reserved: bool) -> Result<(), Exceeded> {
        let take = |counter: &AtomicU64, limit: u64| {
            counter
                .fetch_update(Ordering::AcqRel, Ordering::Acquire, |used| {
                    used.checked_add(need).filter(|&total| total <= limit)
                })
                .map(|_| ())
                .map_err(|used| Exceeded::Total { what: self.what, need, used, limit })
        };
        if !reserved {
            take(&self.used_unreserved, self.limit - self.reserve)?;
        }
        take(&self.used, self.limit).inspect_err(|_| {
            if !reserved {
                self.used_unreserved.fetch_sub(need, Ordering::AcqRel);
            }
        })
    }

    fn give(&self, bytes: u64, reserved: bool) {
        self.used.fetch_sub(bytes, Ordering::AcqRel);
        if !reserved {
            self.used_unreserved.fetch_sub(bytes, Ordering::AcqRel);
        }
    }
}

/// Half of the machine's physical memory: the default total for all clients, so that the
/// daemon's clients can never make it the process the kernel kills for memory.
pub fn default_total() -> u64 {
    let kib = std::fs::read_to_string("/proc/meminfo").ok().and_then(|m| {
        m.lines()
            .find_map(|l| l.strip_prefix("MemTotal:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
    });
    kib.map_or(8 << 30, |k| k * 1024 / 2)
}

/// What one client holds, as `ctl stats` shows it.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Usage {
    /// GPU memory bytes held.
    pub gpu_bytes: u64,
    /// Bytes the daemon holds in its own memory for the client (its segment, a command being
    /// assembled).
    pub daemon_bytes: u64,
    /// Objects of each kind, in the order of [`Kind::ALL`].
    pub counts: [u64; 9],
    /// Reservations refused so far.
    pub refusals: u64,
}

/// One client's account: its limits, what it holds, and the pool it draws from.
#[derive(Debug)]
pub struct Account {
    client: String,
    limits: Limits,
    pool: Arc<Pool>,
    /// The pool of the daemon's own memory.
    daemon_pool: Arc<Pool>,
    /// Whether it draws on the pool's reserve.
    reserved: bool,
    /// GPU memory held.
    bytes: AtomicU64,
    /// The daemon's memory held for it.
    daemon_bytes: AtomicU64,
    counts: [AtomicU64; 9],
    refusals: AtomicU64,
    /// Per kind of refusal (the object kinds, then bytes, total, command, daemon bytes and
    /// daemon total): logged yet.
    logged: [AtomicBool; 14],
}

impl Account {
    /// An account for client `client` under `limits`, drawing GPU memory from `pools.0`
    /// (and from its reserve if `reserved`) and the daemon's memory from `pools.1`.
    pub fn new(client: &str, limits: Limits, pools: (Arc<Pool>, Arc<Pool>), reserved: bool) -> Arc<Self> {
        Arc::new(Account {
            client: client.to_string(),
            limits,
            pool: pools.0,
            daemon_pool: pools.1,
            reserved,
            bytes: AtomicU64::new(0),
            daemon_bytes: AtomicU64::new(0),
            counts: Default::default(),
            refusals: AtomicU64::new(0),
            logged: Default::default(),
        })
    }

    /// An account without limits (an executor run alone, as tests and fuzzers do).
    pub fn unlimited() -> Arc<Self> {
        Account::new("", Limits::unlimited(), (Pool::new(u64::MAX), Pool::daemon(u64::MAX)), true)
    }

    /// The limits in force.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// What the client holds now.
    pub fn usage(&self) -> Usage {
        Usage {
            gpu_bytes: self.bytes.load(Ordering::Relaxed),
            daemon_bytes: self.daemon_bytes.load(Ordering::Relaxed),
            counts: std::array::from_fn(|i| self.counts[i].load(Ordering::Relaxed)),
            refusals: self.refusals.load(Ordering::Relaxed),
        }
    }

    /// Records that the client now has `n` objects of `kind` (the executor counts its name
    /// tables; the account only reports them).
    pub fn set_count(&self, kind: Kind, n: u64) {
        self.counts[kind.index()].store(n, Ordering::Relaxed);
    }

    /// Whether the client, holding `have` objects of `kind`, may create `more`.
    pub fn admit(&self, kind: Kind, have: u64, more: u64) -> Result<(), Exceeded> {
        let limit = self.limits.count(kind);
        if have.saturating_add(more) > limit {
            return Err(self.refused(kind.index(), Exceeded::Count { kind, limit }));
        }
        Ok(())
    }

    /// Whether one command of `len` encoded bytes may be executed.
    pub fn admit_command(&self, len: u64) -> Result<(), Exceeded> {
        let limit = self.limits.command_bytes;
        if len > limit {
            return Err(self.refused(11, Exceeded::Command { len, limit }));
        }
        Ok(())
    }

    /// Reserves `bytes` of GPU memory, from the client's limit and the daemon's pool.
    pub fn reserve(self: &Arc<Self>, bytes: u64) -> Result<Reservation, Exceeded> {
        self.take(bytes, false)?;
        Ok(Reservation { account: self.clone(), bytes, daemon: false })
    }

    /// Charges `bytes` that the daemon holds in its own memory for the client, to its limit
    /// and pool of the daemon's memory, before the daemon allocates them.
    pub fn hold(self: &Arc<Self>, bytes: u64) -> Result<Reservation, Exceeded> {
        self.take(bytes, true)?;
        Ok(Reservation { account: self.clone(), bytes, daemon: true })
    }

    /// The counter, limit, pool, whether it draws on the pool's reserve, and the refusal
    /// slots of GPU memory or of the daemon's.
    fn side(&self, daemon: bool) -> (&AtomicU64, u64, &Pool, bool, usize) {
        match daemon {
            false => (&self.bytes, self.limits.gpu_bytes, &self.pool, self.reserved, 9),
            true => (&self.daemon_bytes, self.limits.daemon_bytes, &self.daemon_pool, true, 12),
        }
    }

    fn take(&self, bytes: u64, daemon: bool) -> Result<(), Exceeded> {
        let (counter, limit, pool, reserved, slot) = self.side(daemon);
        let got = counter.fetch_update(Ordering::AcqRel, Ordering::Acquire, |used| {
            used.checked_add(bytes).filter(|&total| total <= limit)
        });
        if let Err(used) = got {
            let e = match daemon {
                false => Exceeded::Bytes { need: bytes, used, limit },
                true => Exceeded::Daemon { need: bytes, used, limit },
            };
            return Err(self.refused(slot, e));
        }
        if let Err(e) = pool.take(bytes, reserved) {
            counter.fetch_sub(bytes, Ordering::AcqRel);
            return Err(self.refused(slot + 1, e));
        }
        Ok(())
    }

    fn give(&self, bytes: u64, daemon: bool) {
        let (counter, _, pool, reserved, _) = self.side(daemon);
        counter.fetch_sub(bytes, Ordering::AcqRel);
        pool.give(bytes, reserved);
    }

    fn refused(&self, slot: usize, e: Exceeded) -> Exceeded {
        self.refusals.fetch_add(1, Ordering::Relaxed);
        if !self.logged[slot].swap(true, Ordering::Relaxed) {
            warn!(
                client = %self.client,
                "quota exceeded: {e}; the client's call fails with GL_OUT_OF_MEMORY or EGL_BAD_ALLOC \
                 (logged once per limit and client)"
            );
        }
        e
    }
}

/// Memory reserved for one object; given back when dropped.
#[derive(Debug)]
pub struct Reservation {
    account: Arc<Account>,
    bytes: u64,
    /// Daemon-side bytes rather than GPU memory.
    daemon: bool,
}

impl Reservation {
    /// Bytes held.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// Holds `bytes` instead: more is charged first (and refused as [`Account::reserve`]
    /// refuses, holding what it held), less is given back.
    pub fn resize(&mut self, bytes: u64) -> Result<(), Exceeded> {
        if bytes > self.bytes {
            self.account.take(bytes - self.bytes, self.daemon)?;
        } else {
            self.account.give(self.bytes - bytes, self.daemon);
        }
        self.bytes = bytes;
        Ok(())
    }
}

impl Drop for Reservation {
    fn drop(&mut self) {
        self.account.give(self.bytes, self.daemon);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reservations_are_bounded_per_client_and_in_total_and_given_back() {
        let pool = Pool::new(100);
        let limits = Limits { gpu_bytes: 60, ..Limits::default() };
        let (a, b) = (
            Account::new("a", limits, (pool.clone(), Pool::daemon(0)), false),
            Account::new("b", limits, (pool.clone(), Pool::daemon(0)), false),
        );
        let r1 = a.reserve(50).expect("fits");
        assert!(matches!(a.reserve(11), Err(Exceeded::Bytes { need: 11, used: 50, limit: 60 })));
        let r2 = b.reserve(50).expect("fits b's own limit and the pool");
        assert!(matches!(b.reserve(1), Err(Exceeded::Total { .. })), "the pool of 100 is full");
        assert_eq!((a.usage().gpu_bytes, b.usage().gpu_bytes, pool.used()), (50, 50, 100));
        assert_eq!(b.usage().gpu_bytes, 50, "a refused reservation holds nothing");
        drop(r1);
        assert_eq!((a.usage().gpu_bytes, pool.used()), (0, 50));
        let _r3 = b.reserve(10).expect("the pool has room again");
        drop(r2);
        assert_eq!(a.usage().refusals + b.usage().refusals, 2);
    }

    #[test]
    fn counts_and_commands_are_admitted_up_to_their_limits() {
        let mut limits = Limits::default();
        limits.set_count(Kind::Texture, 3);
        limits.command_bytes = 1000;
        let a = Account::new("a", limits, (Pool::new(u64::MAX), Pool::daemon(0)), false);
        assert!(a.admit(Kind::Texture, 2, 1).is_ok());
        assert_eq!(a.admit(Kind::Texture, 2, 2), Err(Exceeded::Count { kind: Kind::Texture, limit: 3 }));
        assert!(a.admit(Kind::Buffer, 1000, 1).is_ok());
        assert!(a.admit_command(1000).is_ok());
        assert!(a.admit_command(1001).is_err());
        assert!(Account::unlimited().reserve(u64::MAX / 2).is_ok());
    }

    #[test]
    fn the_daemons_memory_is_charged_apart_from_gpu_memory() {
        let (gpu, daemon) = (Pool::new(1000), Pool::daemon(120));
        let limits = Limits { gpu_bytes: 100, daemon_bytes: 100, ..Limits::default() };
        let a = Account::new("a", limits, (gpu.clone(), daemon.clone()), false);
        let _gpu = a.reserve(100).expect("all its GPU memory");
        let mut held = a.hold(50).expect("the daemon's memory is another limit");
        assert_eq!((a.usage().gpu_bytes, a.usage().daemon_bytes, gpu.used(), daemon.used()), (100, 50, 100, 50));
        assert!(matches!(held.resize(101), Err(Exceeded::Daemon { need: 51, used: 50, limit: 100 })));
        assert_eq!((held.bytes(), a.usage().daemon_bytes), (50, 50), "a refused resize holds what it held");
        let b = Account::new("b", limits, (gpu.clone(), daemon.clone()), false);
        let e = b.hold(71).expect_err("the daemon's pool of 120 holds 50");
        assert!(e.to_string().contains("the daemon's memory") && e.to_string().contains("120-byte total"), "{e}");
        held.resize(10).expect("shrinks");
        let _b = b.hold(71).expect("fits now");
        assert_eq!((a.usage().daemon_bytes, daemon.used()), (10, 81));
        drop(held);
        assert_eq!((a.usage().gpu_bytes, a.usage().daemon_bytes, daemon.used()), (100, 0, 71));
    }

    #[test]
    fn the_reserve_is_left_to_the_reserved_class() {
        let pool = Pool::with_reserve(100, 40);
        let limits = Limits { gpu_bytes: 100, ..Limits::default() };
        let pools = || (pool.clone(), Pool::daemon(0));
        let (hu, hu2) = (Account::new("hu", limits, pools(), false), Account::new("hu2", limits, pools(), false));
        let ic = Account::new("ic", limits, pools(), true);
        let _a = hu.reserve(50).expect("below the unreserved 60");
        assert!(matches!(hu2.reserve(11), Err(Exceeded::Total { limit: 60, .. })), "lower classes share 60");
        let _b = hu2.reserve(10).expect("up to 60");
        let _c = ic.reserve(40).expect("the reserve is the IC's");
        assert!(ic.reserve(1).is_err() && hu.reserve(1).is_err(), "the pool is full");
        assert_eq!(pool.used(), 100);
    }
}
