//! Two processes share one segment (the child inherits its memory file as descriptor 3): the child writes messages of random sizes (some larger
//! than the ring, so chunked) across many wrap-arounds; the parent checks that every message
//! arrives once, in order, with a matching CRC-32.

use std::process::{Command, ExitCode};

use rand::{Rng, SeedableRng};
use strata_protocol::ring::{Reader, RingError, Writer};
use strata_protocol::segment::Segment;

const MESSAGES: u64 = 50_000;
const RING: u32 = 1 << 16;

fn message(seq: u64, rng: &mut rand::rngs::StdRng) -> Vec<u8> {
    let len = if seq.is_multiple_of(1009) {
        rng.random_range(RING as usize..3 * RING as usize)
    } else {
        rng.random_range(0..5000)
    };
    let mut m = seq.to_le_bytes().to_vec();
    m.extend((0..len).map(|_| rng.random::<u8>()));
    m
}

fn child() -> ExitCode {
    use std::os::fd::FromRawFd;
    // SAFETY: the parent placed the segment's memory file at descriptor 3, which nothing else
    // in this process owns.
    let fd = unsafe { std::os::fd::OwnedFd::from_raw_fd(3) };
    let seg = Segment::open(fd, RING, 4096).expect("open segment");
    let mut w = Writer::new(seg.command_ring().expect("ring"), 8192);
    let mut rng = rand::rngs::StdRng::seed_from_u64(99);
    for seq in 0..MESSAGES {
        let m = message(seq, &mut rng);
        w.write::<RingError>(m.len(), &|| true, |buf| {
            buf.copy_from_slice(&m);
            Ok(())
        })
        .expect("write");
    }
    w.publish();
    ExitCode::SUCCESS
}

fn parent() -> ExitCode {
    use std::os::fd::AsRawFd;
    use std::os::unix::process::CommandExt;
    let mut seg = Segment::create(RING, 4096).expect("create segment");
    let exe = std::env::current_exe().expect("current exe");
    let fd = seg.fd().expect("the memory file").as_raw_fd();
    let mut cmd = Command::new(exe);
    cmd.arg("--child");
    // SAFETY: only dup2 and fcntl (async-signal-safe) between fork and exec; descriptor 3 is
    // left open across exec (dup2 onto itself would keep its close-on-exec flag).
    unsafe {
        cmd.pre_exec(move || {
            let r = if fd == 3 { libc::fcntl(3, libc::F_SETFD, 0) } else { libc::dup2(fd, 3) };
            if r < 0 {
                Err(std::io::Error::last_os_error())
            } else {
                Ok(())
            }
        });
    }
    let mut proc = cmd.spawn().expect("spawn writer");
    seg.close_fd();
    let mut r = Reader::new(seg.command_ring().expect("ring"), 1 << 24);
    let mut expect_rng = rand::rngs::StdRng::seed_from_u64(99);
    let mut next = 0u64;
    let mut bytes = 0usize;
    let pid = proc.id();
    let alive = move || std::path::Path::new(&format!("/proc/{pid}")).exists();
    while next < MESSAGES {
        let res = r.recv_batch::<RingError>(&alive, |m| {
            let want = message(next, &mut expect_rng);
            assert_eq!(&m[..8], &want[..8], "message {next}: lost or reordered");
            assert_eq!(crc32fast::hash(m), crc32fast::hash(&want), "message {next}: checksum");
            bytes += m.len();
            next += 1;
            Ok(())
        });
        if let Err(e) = res {
            eprintln!("ring_two_process: reader failed after {next} messages: {e}");
            let _ = proc.kill();
            let _ = proc.wait();
            return ExitCode::FAILURE;
        }
    }
    let status = proc.wait().expect("wait writer");
    if !status.success() {
        eprintln!("ring_two_process: writer exited with {status}");
        return ExitCode::FAILURE;
    }
    println!("ring_two_process: {next} messages, {bytes} bytes through a {RING}-byte ring: in order, checksums match");
    println!("1 passed, 0 failed");
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    match args.iter().position(|a| a == "--child") {
        Some(_) => child(),
        None => parent(),
    }
}
