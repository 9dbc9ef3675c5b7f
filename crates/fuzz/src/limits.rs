//! Resource caps of a render child: address space (the memory cap), CPU time (what makes a
//! hang: on a loaded machine wall-clock time says little) and no core files; and the CPU
//! time this process has used, for the in-process watchdog.

#![allow(unsafe_code)]

/// Caps this process's address space at `bytes` and its CPU time at `cpu_seconds` (SIGXCPU
/// then), and turns core files off. Children inherit the caps.
pub fn cap(bytes: u64, cpu_seconds: u64) -> std::io::Result<()> {
    set(libc::RLIMIT_AS, bytes, bytes)?;
    set(libc::RLIMIT_CPU, cpu_seconds, cpu_seconds + 1)?;
    set(libc::RLIMIT_CORE, 0, 0)
}

fn set(resource: libc::__rlimit_resource_t, soft: u64, hard: u64) -> std::io::Result<()> {
    let limit = libc::rlimit { rlim_cur: soft, rlim_max: hard };
    // SAFETY: setrlimit only reads the struct passed by reference.
    if unsafe { libc::setrlimit(resource, &limit) } == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

/// The CPU time used so far by all threads of this process.
pub fn cpu_time() -> std::time::Duration {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the struct passed by pointer, nothing else.
    if unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) } != 0 {
        return std::time::Duration::ZERO;
    }
    std::time::Duration::new(t.tv_sec as u64, t.tv_nsec as u32)
}

#[cfg(test)]
mod tests {
    #[test]
    fn cpu_time_grows_with_work() {
        let a = super::cpu_time();
        let mut x = 0u64;
        for i in 0..50_000_000u64 {
            x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(i));
        }
        assert!(super::cpu_time() > a, "{x}");
    }
}
