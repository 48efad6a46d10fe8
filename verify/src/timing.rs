//! The calling thread's CPU time, for timing one search or query on its own: other
//! processes on the cores do not inflate it (the machines these campaigns run on are shared).

use std::time::Duration;

/// CPU time consumed so far by the calling thread (`CLOCK_THREAD_CPUTIME_ID`), or `None` when
/// the clock is unavailable.
pub fn thread_cpu() -> Option<Duration> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid timespec the call writes to; the clock id is a constant.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    (rc == 0).then(|| Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32))
}

/// [`thread_cpu`] in microseconds, NaN when the clock is unavailable.
pub fn thread_cpu_us() -> f64 {
    thread_cpu().map_or(f64::NAN, |d| d.as_secs_f64() * 1e6)
}
