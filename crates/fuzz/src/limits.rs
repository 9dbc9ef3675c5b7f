//! Resource caps of a render child: address space (the memory cap), CPU time (a second guard
//! behind the parent's wall-clock limit) and no core files.

#![allow(unsafe_code)]

/// Caps this process's address space at `bytes` and its CPU time at `cpu_seconds`, and turns
/// core files off. Children inherit the caps.
pub fn cap(bytes: u64, cpu_seconds: u64) -> std::io::Result<()> {
    set(libc::RLIMIT_AS, bytes)?;
    set(libc::RLIMIT_CPU, cpu_seconds)?;
    set(libc::RLIMIT_CORE, 0)
}

fn set(resource: libc::__rlimit_resource_t, value: u64) -> std::io::Result<()> {
    let limit = libc::rlimit { rlim_cur: value, rlim_max: value };
    // SAFETY: setrlimit only reads the struct passed by reference.
    if unsafe { libc::setrlimit(resource, &limit) } == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}
