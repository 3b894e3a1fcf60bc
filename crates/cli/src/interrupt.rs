//! Ctrl-C: the first press asks the running simulation to stop cleanly (its events so far are
//! written and the report says it was interrupted); a second press ends the process at once.

use std::sync::atomic::{AtomicBool, Ordering};

static STOP: AtomicBool = AtomicBool::new(false);

/// Installs the handler (once; a failure to install only means Ctrl-C kills the process as usual).
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!("\ninterrupted: stopping the simulation cleanly (Ctrl-C again to quit at once)");
    });
}

/// True once Ctrl-C was pressed.
pub fn requested() -> bool {
    STOP.load(Ordering::SeqCst)
}
