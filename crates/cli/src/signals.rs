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
        let wanted = |&s: &i32| stop && (default || !reyes_render::cancel::ignored_at_start(s));
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

/// The stopping signal received, if any.
pub(crate) fn received() -> Option<Stop> {
    match RECEIVED.load(Ordering::SeqCst) {
        130 => Some(Stop { name: "SIGINT", code: 130 }),
        143 => Some(Stop { name: "SIGTERM", code: 143 }),
        _ => None,
    }
}
