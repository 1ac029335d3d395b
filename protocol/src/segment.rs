//! The per-client shared-memory segment: a header, then the command ring (client → daemon)
//! and the reply ring (daemon → client). The header also holds one word the daemon publishes
//! and the client reads, the newest fence mark whose work has completed ([`FenceWord`]), so that
//! polling a fence costs the client no round trip.
//!
//! The daemon creates it as an anonymous memory file (`memfd_create`) and hands the client its
//! descriptor over the socket (`SCM_RIGHTS`, [`crate::fd_passing`]). It never has a name, so
//! no other process, of any uid, can open it; and its size is sealed, so the client cannot
//! shrink it under the daemon's mapping.

use std::os::fd::{AsFd, BorrowedFd, OwnedFd};
use std::ptr::NonNull;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use rustix::fs::{MemfdFlags, SealFlags};
use rustix::mm::{MapFlags, ProtFlags};

use crate::ring::{Backing, RingError, RingRegion, CONTROL_BYTES, MAX_CAPACITY, MIN_CAPACITY};

const MAGIC: u64 = u64::from_le_bytes(*b"STRATA\x00\x01");
/// Where the header keeps the [`FenceWord`] (8-aligned, before the command ring's control).
const FENCE_WORD: usize = 16;
const CMD_CONTROL: usize = 64;
const REPLY_CONTROL: usize = CMD_CONTROL + CONTROL_BYTES;
const DATA: usize = 4096;

/// Why a segment could not be made or opened.
#[derive(Debug, thiserror::Error)]
pub enum SegmentError {
    /// Creating, sizing, sealing or mapping the memory failed.
    #[error("shared memory segment: {what}: {source}")]
    Memory {
        /// The step that failed.
        what: &'static str,
        /// The OS error.
        source: std::io::Error,
    },
    /// The mapping does not have the advertised layout.
    #[error("the segment is not a Strata segment of the advertised size: {0}")]
    Layout(String),
    /// A ring could not be laid out.
    #[error(transparent)]
    Ring(#[from] RingError),
}

fn os(what: &'static str) -> impl FnOnce(rustix::io::Errno) -> SegmentError {
    move |e| SegmentError::Memory { what, source: e.into() }
}

/// A shared mapping of a memory file, unmapped when the last ring drops it.
struct Mapping {
    base: *mut u8,
    len: usize,
}
// SAFETY: a mapping is plain shared memory; the rings coordinate all access through atomics,
// and unmapping is valid from any thread.
unsafe impl Send for Mapping {}
// SAFETY: as above; `&Mapping` exposes nothing but the base pointer.
unsafe impl Sync for Mapping {}
impl Backing for Mapping {}

impl Mapping {
    /// Maps `len` bytes of `fd`, shared and writable.
    fn new(fd: BorrowedFd<'_>, len: usize) -> Result<Mapping, SegmentError> {
        // SAFETY: a fresh shared mapping chosen by the kernel; nothing aliases it in this process.
        let base = unsafe {
            rustix::mm::mmap(std::ptr::null_mut(), len, ProtFlags::READ | ProtFlags::WRITE, MapFlags::SHARED, fd, 0)
        }
        .map_err(os("mapping"))?;
        Ok(Mapping { base: base.cast(), len })
    }
}

impl Drop for Mapping {
    fn drop(&mut self) {
        // SAFETY: our own mapping of `len` bytes; every ring that pointed into it is gone.
        let _ = unsafe { rustix::mm::munmap(self.base.cast(), self.len) };
    }
}

/// One client's mapped segment.
pub struct Segment {
    map: Arc<Mapping>,
    /// The memory file, until the daemon has handed it over ([`Segment::close_fd`]).
    fd: Option<OwnedFd>,
    cmd_capacity: u32,
    reply_capacity: u32,
}

/// Bytes a segment with these ring capacities occupies.
pub fn segment_size(cmd_capacity: u32, reply_capacity: u32) -> usize {
    DATA + cmd_capacity as usize + reply_capacity as usize
}

/// Makes every page of a fresh mapping resident by writing a zero to it.
///
/// A ring's pages otherwise become resident one at a time as its cursor first passes them,
/// so a long-lived client's segment would add to the daemon's memory for as long as its ring
/// takes to wrap once (minutes, for a client that streams little). Touching them at creation
/// makes a client's cost fixed from its first frame: the whole segment, freed when it leaves.
///
/// # Safety
/// `base` must point to `len` writable bytes that nothing else reads or writes yet.
unsafe fn populate(base: *mut u8, len: usize) {
    const PAGE: usize = 4096;
    for offset in (0..len).step_by(PAGE) {
        // SAFETY: offset < len, within the mapping the caller vouches for.
        unsafe { base.add(offset).write_volatile(0) };
    }
}

fn check_capacity(cap: u32) -> Result<(), SegmentError> {
    if cap.is_power_of_two() && (MIN_CAPACITY..=MAX_CAPACITY).contains(&cap) {
        Ok(())
    } else {
        Err(SegmentError::Layout(format!(
            "ring capacity {cap} is not a power of two in {MIN_CAPACITY}..={MAX_CAPACITY}"
        )))
    }
}

impl Segment {
    /// Creates a fresh segment (daemon side): an anonymous memory file of the segment's size,
    /// sealed against resizing, mapped and laid out.
    pub fn create(cmd_capacity: u32, reply_capacity: u32) -> Result<Segment, SegmentError> {
        check_capacity(cmd_capacity)?;
        check_capacity(reply_capacity)?;
        let len = segment_size(cmd_capacity, reply_capacity);
        let fd = rustix::fs::memfd_create("strata-segment", MemfdFlags::CLOEXEC | MemfdFlags::ALLOW_SEALING)
            .map_err(os("creating the memory file"))?;
        rustix::fs::ftruncate(&fd, len as u64).map_err(os("sizing the memory file"))?;
        // The client maps it too: neither side may shrink (SIGBUS in the other) or grow it.
        rustix::fs::fcntl_add_seals(&fd, SealFlags::SHRINK | SealFlags::GROW | SealFlags::SEAL)
            .map_err(os("sealing the memory file"))?;
        let map = Mapping::new(fd.as_fd(), len)?;
        let seg = Segment { map: Arc::new(map), fd: Some(fd), cmd_capacity, reply_capacity };
        // SAFETY: the header lies at the start of a fresh, page-aligned mapping of DATA+ bytes,
        // and `segment_size` bytes are mapped.
        unsafe {
            let p = seg.base();
            populate(p, len);
            p.cast::<u64>().write_volatile(MAGIC);
            p.add(8).cast::<u32>().write_volatile(cmd_capacity);
            p.add(12).cast::<u32>().write_volatile(reply_capacity);
        }
        seg.command_ring()?.reset();
        seg.reply_ring()?.reset();
        Ok(seg)
    }

    /// Maps the segment the daemon handed over as `fd` (client side) and checks its size, its
    /// seals and its header.
    pub fn open(fd: OwnedFd, cmd_capacity: u32, reply_capacity: u32) -> Result<Segment, SegmentError> {
        check_capacity(cmd_capacity)?;
        check_capacity(reply_capacity)?;
        let need = segment_size(cmd_capacity, reply_capacity);
        let size = rustix::fs::fstat(&fd).map_err(os("reading the memory file's size"))?.st_size;
        if u64::try_from(size).ok() != Some(need as u64) {
            return Err(SegmentError::Layout(format!("{size} bytes, {need} needed")));
        }
        let seals = rustix::fs::fcntl_get_seals(&fd).map_err(os("reading the memory file's seals"))?;
        if !seals.contains(SealFlags::SHRINK) {
            return Err(SegmentError::Layout("the memory file may shrink (no F_SEAL_SHRINK)".into()));
        }
        let map = Mapping::new(fd.as_fd(), need)?;
        let seg = Segment { map: Arc::new(map), fd: None, cmd_capacity, reply_capacity };
        // SAFETY: the mapping has at least DATA bytes.
        let (magic, c, r) = unsafe {
            let p = seg.base();
            (
                p.cast::<u64>().read_volatile(),
                p.add(8).cast::<u32>().read_volatile(),
                p.add(12).cast::<u32>().read_volatile(),
            )
        };
        if magic != MAGIC || c != cmd_capacity || r != reply_capacity {
            return Err(SegmentError::Layout(format!("header says magic {magic:#x}, rings {c}/{r}")));
        }
        Ok(seg)
    }

    /// The memory file to hand to the client, until [`Segment::close_fd`].
    pub fn fd(&self) -> Option<BorrowedFd<'_>> {
        self.fd.as_ref().map(AsFd::as_fd)
    }

    /// Closes the daemon's descriptor of the memory file once the client has mapped it; the
    /// mapping stays.
    pub fn close_fd(&mut self) {
        self.fd = None;
    }

    fn base(&self) -> *mut u8 {
        self.map.base
    }

    /// The header's word for the newest completed fence mark.
    pub fn fence_word(&self) -> FenceWord {
        // SAFETY: FENCE_WORD is 8-aligned within the header page of the mapping the Arc keeps
        // alive; it is only ever accessed atomically.
        let word = unsafe { NonNull::new_unchecked(self.base().add(FENCE_WORD).cast::<AtomicU64>()) };
        FenceWord { word, _map: self.map.clone() }
    }

    /// The client → daemon command ring.
    pub fn command_ring(&self) -> Result<RingRegion, SegmentError> {
        // SAFETY: control at 64-aligned offset 64, data at page offset 4096, both inside the
        // mapping of `segment_size` bytes that the Arc keeps alive.
        Ok(unsafe {
            RingRegion::new(self.base().add(CMD_CONTROL), self.base().add(DATA), self.cmd_capacity, self.map.clone())
        }?)
    }

    /// The daemon → client reply ring.
    pub fn reply_ring(&self) -> Result<RingRegion, SegmentError> {
        // SAFETY: as for the command ring; the reply data follows the command data.
        Ok(unsafe {
            RingRegion::new(
                self.base().add(REPLY_CONTROL),
                self.base().add(DATA + self.cmd_capacity as usize),
                self.reply_capacity,
                self.map.clone(),
            )
        }?)
    }
}

/// The newest fence mark whose work has completed, as the segment's header holds it: the daemon
/// publishes it as the client's work completes, and the client reads it to poll a fence without
/// a round trip. The daemon only ever writes it (it keeps its own count), so a client that
/// writes it misleads nobody but itself.
#[derive(Clone)]
pub struct FenceWord {
    word: NonNull<AtomicU64>,
    _map: Arc<Mapping>,
}

// SAFETY: the word is an atomic in a shared mapping that `_map` keeps alive.
unsafe impl Send for FenceWord {}
// SAFETY: as above; every access is atomic.
unsafe impl Sync for FenceWord {}

impl FenceWord {
    fn atomic(&self) -> &AtomicU64 {
        // SAFETY: an aligned atomic word inside the live mapping (see `Segment::fence_word`).
        unsafe { self.word.as_ref() }
    }

    /// Publishes `mark` as the newest completed one (daemon side; the caller keeps the values it
    /// publishes increasing).
    pub fn publish(&self, mark: u64) {
        self.atomic().store(mark, Ordering::Release);
    }

    /// The newest completed mark the daemon has published (client side).
    pub fn get(&self) -> u64 {
        self.atomic().load(Ordering::Acquire)
    }
}
