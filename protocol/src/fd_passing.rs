//! Descriptors over the Unix socket (`SCM_RIGHTS`): the daemon hands each client its segment
//! this way, and refuses any ancillary data a client sends it.

use std::io::{IoSlice, IoSliceMut};
use std::mem::MaybeUninit;
use std::os::fd::{BorrowedFd, OwnedFd};

use rustix::net::{
    RecvAncillaryBuffer, RecvAncillaryMessage, RecvFlags, ReturnFlags, SendAncillaryBuffer, SendAncillaryMessage,
    SendFlags,
};

/// Most descriptors one read takes in (more are discarded by the kernel and reported).
const MAX_FDS: usize = 4;

/// What one read from the socket brought.
#[derive(Debug)]
pub struct Received {
    /// Bytes read into the buffer (0: the peer closed).
    pub bytes: usize,
    /// Descriptors that came with them.
    pub fds: Vec<OwnedFd>,
    /// Whether other ancillary data came with them (credentials, or more than fit).
    pub other: bool,
}

impl Received {
    /// Whether anything but plain bytes arrived.
    pub fn has_ancillary(&self) -> bool {
        !self.fds.is_empty() || self.other
    }
}

/// Sends `bytes` with `fd` attached to the first of them; returns how many bytes went (the
/// caller writes the rest as plain bytes). `WouldBlock` on a non-blocking socket that is full.
pub fn send_with_fd(socket: BorrowedFd<'_>, bytes: &[u8], fd: BorrowedFd<'_>) -> std::io::Result<usize> {
    let mut space = [MaybeUninit::<u8>::uninit(); rustix::cmsg_space!(ScmRights(1))];
    let mut control = SendAncillaryBuffer::new(&mut space);
    let fds = [fd];
    if !control.push(SendAncillaryMessage::ScmRights(&fds)) {
        return Err(std::io::Error::other("no room for one descriptor in the control buffer"));
    }
    Ok(rustix::net::sendmsg(socket, &[IoSlice::new(bytes)], &mut control, SendFlags::NOSIGNAL)?)
}

/// Reads into `buf`, keeping whatever descriptors and ancillary data arrive with the bytes
/// (descriptors close-on-exec). `WouldBlock` on a non-blocking socket with nothing to read.
pub fn recv(socket: BorrowedFd<'_>, buf: &mut [u8]) -> std::io::Result<Received> {
    let mut space = [MaybeUninit::<u8>::uninit(); rustix::cmsg_space!(ScmRights(MAX_FDS))];
    let mut control = RecvAncillaryBuffer::new(&mut space);
    let msg = rustix::net::recvmsg(socket, &mut [IoSliceMut::new(buf)], &mut control, RecvFlags::CMSG_CLOEXEC)?;
    let mut got = Received { bytes: msg.bytes, fds: Vec::new(), other: msg.flags.contains(ReturnFlags::CTRUNC) };
    for m in control.drain() {
        match m {
            RecvAncillaryMessage::ScmRights(fds) => got.fds.extend(fds),
            _ => got.other = true,
        }
    }
    Ok(got)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::{Read, Write};
    use std::os::fd::AsFd;
    use std::os::unix::net::UnixStream;

    #[test]
    fn a_descriptor_travels_with_its_bytes_and_plain_bytes_carry_none() {
        let (a, b) = UnixStream::pair().expect("pair");
        let (mut file_w, file_r) = UnixStream::pair().expect("a descriptor to pass");
        assert_eq!(send_with_fd(a.as_fd(), b"hello", file_r.as_fd()).expect("send"), 5);
        let mut buf = [0u8; 16];
        let got = recv(b.as_fd(), &mut buf).expect("recv");
        assert_eq!((&buf[..got.bytes], got.fds.len(), got.other), (&b"hello"[..], 1, false));
        // The passed descriptor is the same socket: what one end writes, the passed one reads.
        file_w.write_all(b"x").expect("write");
        let mut passed = UnixStream::from(got.fds.into_iter().next().expect("fd"));
        let mut one = [0u8; 1];
        passed.read_exact(&mut one).expect("read through the passed descriptor");
        assert_eq!(&one, b"x");
        (&a).write_all(b"plain").expect("write");
        let got = recv(b.as_fd(), &mut buf).expect("recv");
        assert!(!got.has_ancillary() && got.bytes == 5, "{got:?}");
    }
}
