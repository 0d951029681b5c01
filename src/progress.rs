//! A progress line on stderr for renders that take more than about a second, only when stderr
//! is a terminal (never in pipes or CI logs).

use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Renders quicker than this show no progress line.
pub const DELAY: Duration = Duration::from_secs(1);

/// Runs `work` with a counter of finished units out of `total`, drawing a percentage on stderr
/// while it runs past [`DELAY`] (when stderr is a terminal), and erasing it at the end.
pub fn with_progress<T>(total: usize, work: impl FnOnce(&AtomicUsize) -> T) -> T {
    let done = AtomicUsize::new(0);
    if !std::io::stderr().is_terminal() {
        return work(&done);
    }
    let finished = AtomicBool::new(false);
    std::thread::scope(|scope| {
        scope.spawn(|| {
            let start = Instant::now();
            let mut drawn = false;
            while !finished.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(100));
                if start.elapsed() >= DELAY && !finished.load(Ordering::Relaxed) {
                    let pct = done.load(Ordering::Relaxed) * 100 / total.max(1);
                    // the line is only a courtesy: a stderr that fails is left alone
                    let mut err = std::io::stderr().lock();
                    let _ = write!(err, "\rlanecast: rendering {pct:>3}%");
                    let _ = err.flush();
                    drawn = true;
                }
            }
            if drawn {
                let _ = write!(std::io::stderr().lock(), "\r{:30}\r", "");
            }
        });
        let out = work(&done);
        finished.store(true, Ordering::Relaxed);
        out
    })
}
