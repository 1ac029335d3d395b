//! Per-client resource limits and the accounting behind them: GPU memory bytes, object counts,
//! window surfaces and the size of one command, per client and in total across clients.
//!
//! Every allocation a client causes is reserved against its [`Account`] before it is made. A
//! [`Reservation`] returns what it holds when it is dropped, so an object deleted, a context
//! destroyed or a client gone gives its bytes back without bookkeeping at each site. A refused
//! reservation is the client's `GL_OUT_OF_MEMORY` or `EGL_BAD_ALLOC`, logged once per kind and
//! client, and changes nothing else.

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
}

impl Default for Limits {
    /// Generous: 2 GiB of GPU memory, 65,536 buffers, textures, renderbuffers, framebuffers,
    /// shaders, programs and vertex arrays, 64 contexts and 64 surfaces, and 256 MiB commands.
    fn default() -> Self {
        let mut counts = [65_536; 9];
        counts[Kind::Context.index()] = 64;
        counts[Kind::Surface.index()] = 64;
        Limits { gpu_bytes: 2 << 30, counts, command_bytes: 256 << 20 }
    }
}

impl Limits {
    /// No limit at all (tests and tools that run an executor alone).
    pub fn unlimited() -> Self {
        Limits { gpu_bytes: u64::MAX, counts: [u64::MAX; 9], command_bytes: u64::MAX }
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
    /// All clients together would exceed the daemon's total.
    #[error(
        "{need} more bytes of GPU memory would exceed the daemon's {limit}-byte total for all clients ({used} in use)"
    )]
    Total {
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

/// The GPU memory all clients together may hold.
#[derive(Debug)]
pub struct Pool {
    limit: u64,
    used: AtomicU64,
}

impl Pool {
    /// A pool of `limit` bytes.
    pub fn new(limit: u64) -> Arc<Self> {
        Arc::new(Pool { limit, used: AtomicU64::new(0) })
    }

    /// Bytes held by all clients.
    pub fn used(&self) -> u64 {
        self.used.load(Ordering::Relaxed)
    }

    /// The total limit.
    pub fn limit(&self) -> u64 {
        self.limit
    }

    fn take(&self, need: u64) -> Result<(), Exceeded> {
        self.used
            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |used| {
                used.checked_add(need).filter(|&total| total <= self.limit)
            })
            .map(|_| ())
            .map_err(|used| Exceeded::Total { need, used, limit: self.limit })
    }

    fn give(&self, bytes: u64) {
        self.used.fetch_sub(bytes, Ordering::AcqRel);
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
    bytes: AtomicU64,
    counts: [AtomicU64; 9],
    refusals: AtomicU64,
    /// Per kind of refusal (the object kinds, then bytes, total and command): logged yet.
    logged: [AtomicBool; 12],
}

impl Account {
    /// An account for client `client` under `limits`, drawing GPU memory from `pool`.
    pub fn new(client: &str, limits: Limits, pool: Arc<Pool>) -> Arc<Self> {
        Arc::new(Account {
            client: client.to_string(),
            limits,
            pool,
            bytes: AtomicU64::new(0),
            counts: Default::default(),
            refusals: AtomicU64::new(0),
            logged: Default::default(),
        })
    }

    /// An account without limits (an executor run alone, as tests and fuzzers do).
    pub fn unlimited() -> Arc<Self> {
        Account::new("", Limits::unlimited(), Pool::new(u64::MAX))
    }

    /// The limits in force.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// What the client holds now.
    pub fn usage(&self) -> Usage {
        Usage {
            gpu_bytes: self.bytes.load(Ordering::Relaxed),
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
        let limit = self.limits.gpu_bytes;
        let got = self.bytes.fetch_update(Ordering::AcqRel, Ordering::Acquire, |used| {
            used.checked_add(bytes).filter(|&total| total <= limit)
        });
        if let Err(used) = got {
            return Err(self.refused(9, Exceeded::Bytes { need: bytes, used, limit }));
        }
        if let Err(e) = self.pool.take(bytes) {
            self.bytes.fetch_sub(bytes, Ordering::AcqRel);
            return Err(self.refused(10, e));
        }
        Ok(Reservation { account: self.clone(), bytes })
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

/// GPU memory reserved for one object; given back when dropped.
#[derive(Debug)]
pub struct Reservation {
    account: Arc<Account>,
    bytes: u64,
}

impl Reservation {
    /// Bytes held.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }
}

impl Drop for Reservation {
    fn drop(&mut self) {
        self.account.bytes.fetch_sub(self.bytes, Ordering::AcqRel);
        self.account.pool.give(self.bytes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reservations_are_bounded_per_client_and_in_total_and_given_back() {
        let pool = Pool::new(100);
        let limits = Limits { gpu_bytes: 60, ..Limits::default() };
        let (a, b) = (Account::new("a", limits, pool.clone()), Account::new("b", limits, pool.clone()));
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
        let a = Account::new("a", limits, Pool::new(u64::MAX));
        assert!(a.admit(Kind::Texture, 2, 1).is_ok());
        assert_eq!(a.admit(Kind::Texture, 2, 2), Err(Exceeded::Count { kind: Kind::Texture, limit: 3 }));
        assert!(a.admit(Kind::Buffer, 1000, 1).is_ok());
        assert!(a.admit_command(1000).is_ok());
        assert!(a.admit_command(1001).is_err());
        assert!(Account::unlimited().reserve(u64::MAX / 2).is_ok());
    }
}
