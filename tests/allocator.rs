//! The daemon's allocator settings (`strata_device::settle_environment`): memory freed on a worker
//! thread is kept for the next allocation rather than given back and faulted in again. The
//! pattern is lavapipe's per draw: one thread allocating, writing and freeing a few
//! megabyte-sized blocks over and over (glmark2's bunny: 1,265,664-byte blocks).

/// A block's size.
const BLOCK: usize = 1 << 20;
/// Blocks held at once in a round.
const BLOCKS: usize = 4;
/// Rounds before the faults are counted (the heap grows to hold the block).
const WARM_UP: usize = 8;
/// Rounds counted.
const ROUNDS: usize = 64;

/// Minor page faults of the calling thread so far.
fn thread_faults() -> i64 {
    // SAFETY: getrusage fills the zeroed struct it is given.
    unsafe {
        let mut u: libc::rusage = std::mem::zeroed();
        assert_eq!(libc::getrusage(libc::RUSAGE_THREAD, &mut u), 0, "getrusage");
        u.ru_minflt
    }
}

/// Faults per round of allocating and writing every page of `BLOCKS` blocks, then freeing them,
/// on a new thread.
fn faults_per_round() -> f64 {
    std::thread::spawn(|| {
        let round = || {
            // SAFETY: fresh allocations of BLOCK bytes, written within their bounds, then freed.
            unsafe {
                let blocks: Vec<*mut u8> = (0..BLOCKS).map(|_| libc::malloc(BLOCK).cast::<u8>()).collect();
                for &p in &blocks {
                    assert!(!p.is_null(), "malloc");
                    for at in (0..BLOCK).step_by(4096) {
                        p.add(at).write_volatile(1);
                    }
                }
                for p in blocks {
                    libc::free(p.cast());
                }
            }
        };
        (0..WARM_UP).for_each(|_| round());
        let before = thread_faults();
        (0..ROUNDS).for_each(|_| round());
        (thread_faults() - before) as f64 / ROUNDS as f64
    })
    .join()
    .expect("allocating thread")
}

#[test]
fn freed_memory_is_kept_for_the_next_draw() {
    if std::env::var("GLIBC_TUNABLES").is_ok_and(|t| t.contains("glibc.malloc.")) {
        eprintln!("skipped: GLIBC_TUNABLES sets malloc's thresholds, which the daemon then leaves alone");
        return;
    }
    if !cfg!(all(target_os = "linux", target_env = "gnu")) {
        eprintln!("skipped: the thresholds are glibc's");
        return;
    }
    strata_device::settle_environment();
    // A round writes 1,024 pages: with glibc's defaults the heap's top goes back to the system
    // after every round, and every page faults in again.
    let pages = (BLOCKS * BLOCK).div_ceil(4096) as f64;
    let faults = faults_per_round();
    assert!(
        faults < pages / 20.0,
        "{faults:.1} page faults per round of {BLOCKS} {BLOCK}-byte blocks ({pages} pages): freed memory went back to the system"
    );
    // A second thread keeps it as well.
    let faults = faults_per_round();
    assert!(faults < pages / 20.0, "{faults:.1} page faults per round on a second thread");
}
