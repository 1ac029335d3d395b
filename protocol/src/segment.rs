//! The per-client shared-memory segment: a header, then the command ring (client → daemon)
//! and the reply ring (daemon → client).
//!
//! The daemon creates it with a random name and owner-only permissions, sends the name over
//! the control socket, and unlinks it as soon as the client reports it mapped, so that no third
//! process can open it afterwards.

use std::sync::Arc;

use shared_memory::{Shmem, ShmemConf};

use crate::ring::{Backing, RingError, RingRegion, CONTROL_BYTES, MAX_CAPACITY, MIN_CAPACITY};

const MAGIC: u64 = u64::from_le_bytes(*b"STRATA\x00\x01");
const CMD_CONTROL: usize = 64;
const REPLY_CONTROL: usize = CMD_CONTROL + CONTROL_BYTES;
const DATA: usize = 4096;

/// Why a segment could not be made or opened.
#[derive(Debug, thiserror::Error)]
pub enum SegmentError {
    /// Creating or opening the shared memory failed.
    #[error("shared memory {name}: {source}")]
    Shmem {
        /// Segment name.
        name: String,
        /// The underlying error.
        source: shared_memory::ShmemError,
    },
    /// The mapping does not have the advertised layout.
    #[error("segment {name} is not a Strata segment of the advertised size: {reason}")]
    Layout {
        /// Segment name.
        name: String,
        /// What did not match.
        reason: String,
    },
    /// Unlinking failed.
    #[error("unlinking {name}: {source}")]
    Unlink {
        /// Segment name.
        name: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// A ring could not be laid out.
    #[error(transparent)]
    Ring(#[from] RingError),
}

struct Mapping(Shmem);
// SAFETY: a mapping is plain shared memory; the rings coordinate all access through atomics,
// and `Shmem`'s drop only unmaps and closes, which is valid from any thread.
unsafe impl Send for Mapping {}
// SAFETY: as above; `&Mapping` exposes nothing but the base pointer.
unsafe impl Sync for Mapping {}
impl Backing for Mapping {}

/// One client's mapped segment.
pub struct Segment {
    name: String,
    map: Arc<Mapping>,
    cmd_capacity: u32,
    reply_capacity: u32,
    linked: bool,
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

fn check_capacity(name: &str, cap: u32) -> Result<(), SegmentError> {
    if cap.is_power_of_two() && (MIN_CAPACITY..=MAX_CAPACITY).contains(&cap) {
        Ok(())
    } else {
        Err(SegmentError::Layout {
            name: name.into(),
            reason: format!("ring capacity {cap} is not a power of two in {MIN_CAPACITY}..={MAX_CAPACITY}"),
        })
    }
}

impl Segment {
    /// Creates a fresh segment with a random name (daemon side).
    pub fn create(cmd_capacity: u32, reply_capacity: u32) -> Result<Segment, SegmentError> {
        let name = format!("/strata-{}-{:016x}", std::process::id(), rand::random::<u64>());
        check_capacity(&name, cmd_capacity)?;
        check_capacity(&name, reply_capacity)?;
        let mut shmem = ShmemConf::new()
            .size(segment_size(cmd_capacity, reply_capacity))
            .os_id(&name)
            .create()
            .map_err(|source| SegmentError::Shmem { name: name.clone(), source })?;
        // Unlinking is ours (see `unlink`), never the mapping's drop.
        shmem.set_owner(false);
        let seg = Segment { name, map: Arc::new(Mapping(shmem)), cmd_capacity, reply_capacity, linked: true };
        // SAFETY: the header lies at the start of a fresh, page-aligned mapping of DATA+ bytes,
        // and `segment_size` bytes are mapped.
        unsafe {
            let p = seg.base();
            populate(p, segment_size(cmd_capacity, reply_capacity));
            p.cast::<u64>().write_volatile(MAGIC);
            p.add(8).cast::<u32>().write_volatile(cmd_capacity);
            p.add(12).cast::<u32>().write_volatile(reply_capacity);
        }
        seg.command_ring()?.reset();
        seg.reply_ring()?.reset();
        Ok(seg)
    }

    /// Opens a segment the daemon announced (client side) and checks its layout.
    pub fn open(name: &str, cmd_capacity: u32, reply_capacity: u32) -> Result<Segment, SegmentError> {
        check_capacity(name, cmd_capacity)?;
        check_capacity(name, reply_capacity)?;
        let shmem =
            ShmemConf::new().os_id(name).open().map_err(|source| SegmentError::Shmem { name: name.into(), source })?;
        let need = segment_size(cmd_capacity, reply_capacity);
        if shmem.len() < need {
            return Err(SegmentError::Layout {
                name: name.into(),
                reason: format!("{} bytes mapped, {need} needed", shmem.len()),
            });
        }
        let seg =
            Segment { name: name.into(), map: Arc::new(Mapping(shmem)), cmd_capacity, reply_capacity, linked: false };
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
            return Err(SegmentError::Layout {
                name: name.into(),
                reason: format!("header says magic {magic:#x}, rings {c}/{r}"),
            });
        }
        Ok(seg)
    }

    fn base(&self) -> *mut u8 {
        self.map.0.as_ptr()
    }

    /// The segment's name in the shared-memory namespace.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Removes the name so no other process can open the segment; the mapping stays valid.
    pub fn unlink(&mut self) -> Result<(), SegmentError> {
        if !self.linked {
            return Ok(());
        }
        let cname = std::ffi::CString::new(self.name.as_str()).map_err(|e| SegmentError::Unlink {
            name: self.name.clone(),
            source: std::io::Error::new(std::io::ErrorKind::InvalidInput, e),
        })?;
        // SAFETY: a valid NUL-terminated name.
        if unsafe { libc::shm_unlink(cname.as_ptr()) } != 0 {
            return Err(SegmentError::Unlink { name: self.name.clone(), source: std::io::Error::last_os_error() });
        }
        self.linked = false;
        Ok(())
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

impl Drop for Segment {
    fn drop(&mut self) {
        if self.linked {
            if let Err(e) = self.unlink() {
                tracing::warn!("{e}");
            }
        }
    }
}
