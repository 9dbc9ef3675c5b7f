//! Signal handling: SIGINT and SIGTERM ask the render to stop, SIGXFSZ is caught.
//!
//! SIGINT and SIGTERM record which signal came and set [`reyes_render::cancel::flag`], which
//! the bucket loop polls before each bucket and the image writer before each chunk; the
//! command then removes its temporary file and exits 130 (SIGINT) or 143 (SIGTERM) with one
//! line. SIGXFSZ (a write past `ulimit -f`) would end the process with a core dump; caught, it
//! lets the write fail with EFBIG, which is reported as the I/O error it is. SIGPIPE needs
//! nothing here: the Rust runtime ignores it, so a write to a closed pipe returns EPIPE.

use std::sync::atomic::{AtomicUsize, Ordering};

use crate::Exit;

/// The exit code of the last stopping signal received (0: none).
static RECEIVED: AtomicUsize = AtomicUsize::new(0);

/// A stopping signal that was received.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stop {
    /// `SIGINT` or `SIGTERM`.
    pub name: &'static str,
    /// The exit code: 128 plus the signal number, as a shell reports a process it ended.
    pub code: u8,
}

/// Install the handlers: SIGXFSZ always; SIGINT and SIGTERM when `stop` (for commands that
/// poll the cancel flag; the others keep the default, which ends them at once, cleanly, as
/// they write no file), unless the signal was ignored at start, which it then stays.
pub(crate) fn install(stop: bool) -> Result<(), Exit> {
    #[cfg(unix)]
    {
        use signal_hook::consts::{SIGINT, SIGTERM, SIGXFSZ};
        use signal_hook::flag::{register, register_usize};
        static XFSZ: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
        let failed = |e: std::io::Error| Exit::error(1, format_args!("signals: {e}"));
        register(SIGXFSZ, &XFSZ).map_err(failed)?;
        let default = reyes_farm::testing::signals_default();
        let wanted = |&s: &i32| stop && (default || !ignored_at_start(s));
        for signal in [SIGINT, SIGTERM].into_iter().filter(wanted) {
            // In this order: whoever sees the cancel flag finds the signal recorded.
            register_usize(signal, &RECEIVED, 128 + signal as usize).map_err(failed)?;
            register(signal, reyes_render::cancel::flag()).map_err(failed)?;
        }
    }
    #[cfg(not(unix))]
    let _ = stop;
    Ok(())
}

/// Whether `signal` was already ignored when the process started: a shell starts background
/// jobs with SIGINT ignored so that Ctrl-C spares them, and such a signal stays ignored.
/// Linux tells through the `SigIgn` mask of `/proc/self/status`; without it, not ignored.
#[cfg(unix)]
fn ignored_at_start(signal: i32) -> bool {
    let Ok(status) = std::fs::read_to_string("/proc/self/status") else { return false };
    let mask = status.lines().find_map(|l| l.strip_prefix("SigIgn:"));
    let mask = mask.and_then(|m| u64::from_str_radix(m.trim(), 16).ok());
    match (mask, u32::try_from(signal - 1)) {
        (Some(mask), Ok(bit)) if bit < 64 => mask >> bit & 1 == 1,
        _ => false,
    }
}

/// The stopping signal received, if any.
pub(crate) fn received() -> Option<Stop> {
    match RECEIVED.load(Ordering::SeqCst) {
        130 => Some(Stop { name: "SIGINT", code: 130 }),
        143 => Some(Stop { name: "SIGTERM", code: 143 }),
        _ => None,
    }
}
