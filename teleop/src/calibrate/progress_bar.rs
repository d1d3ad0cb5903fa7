//! The fit's progress on stderr: a bar redrawn in place on a terminal
//! (`[#####.....] 52/100 best 0.213 rad`), a plain line every 10 evaluations otherwise (logs,
//! pipes, tests).

use std::io::{IsTerminal as _, Write as _};

use calibration::FitProgress;

/// Width of the bar in characters.
const WIDTH: usize = 20;
/// Evaluations between lines when stderr is not a terminal.
const LINE_EVERY: usize = 10;

/// Progress display for one fit.
#[derive(Debug)]
pub struct ProgressBar {
    terminal: bool,
    drawn: bool,
}

impl Default for ProgressBar {
    fn default() -> Self {
        ProgressBar::new()
    }
}

/// `[#####.....] 52/100 best 0.213 rad`.
pub fn render(p: FitProgress) -> String {
    let filled = (p.done * WIDTH)
        .checked_div(p.budget)
        .unwrap_or(WIDTH)
        .min(WIDTH);
    format!(
        "[{}{}] {}/{} best {:.3} rad",
        "#".repeat(filled),
        ".".repeat(WIDTH - filled),
        p.done,
        p.budget,
        p.best
    )
}

impl ProgressBar {
    /// A bar for stderr (redrawn in place only if stderr is a terminal).
    pub fn new() -> ProgressBar {
        ProgressBar {
            terminal: std::io::stderr().is_terminal(),
            drawn: false,
        }
    }

    /// Show `p`.
    pub fn update(&mut self, p: FitProgress) {
        let mut err = std::io::stderr().lock();
        if self.terminal {
            write!(err, "\r{}", render(p)).ok();
            err.flush().ok();
            self.drawn = true;
        } else if p.done.is_multiple_of(LINE_EVERY) || p.done == p.budget {
            writeln!(err, "{}", render(p)).ok();
        }
    }

    /// End the bar's line.
    pub fn finish(&mut self) {
        if self.drawn {
            eprintln!();
            self.drawn = false;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_the_fraction_done() {
        let line = render(FitProgress {
            done: 52,
            budget: 100,
            best: 0.2134,
        });
        assert_eq!(line, "[##########..........] 52/100 best 0.213 rad");
    }
}
