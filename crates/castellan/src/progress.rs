//! Progress on the terminal for every command: a bar for work counted in steps and a spinner
//! for one long step, both ticking on their own so the elapsed time moves while a stage runs
//! (a 40 Mpx image can take minutes). indicatif hides them when stderr is not a terminal.

use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

const TICK: Duration = Duration::from_millis(500);

/// A bar of `steps` steps with a message.
pub fn bar(steps: u64) -> ProgressBar {
    let bar = ProgressBar::new(steps);
    bar.set_style(
        ProgressStyle::with_template("{elapsed:>4} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.enable_steady_tick(TICK);
    bar
}

/// Runs `work` under a spinner named `what` (with its section), cleared when it ends however it
/// ends; `work` may rename the step on the spinner it is given.
pub fn with_spinner<T>(what: &str, work: impl FnOnce(&ProgressBar) -> T) -> T {
    let s = ProgressBar::new_spinner();
    s.set_style(
        ProgressStyle::with_template("{elapsed:>4} {spinner} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    s.set_message(what.to_string());
    s.enable_steady_tick(TICK);
    let result = work(&s);
    s.finish_and_clear();
    result
}
