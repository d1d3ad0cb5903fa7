//! Progress on stderr: a bar redrawn in place on a terminal
//! (`[#####...............] 285/1140 scoring`), plain lines at a fixed step otherwise (logs,
//! pipes, tests), or nothing. Never control characters in a log.

use std::io::{IsTerminal as _, Write as _};

/// Width of the bar in characters.
const WIDTH: usize = 20;

/// How progress is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgressStyle {
    /// Redraw one line in place (stderr is a terminal).
    Redraw,
    /// A plain line whenever `done` is a multiple of `every`, and at the end.
    Lines {
        /// Steps between lines.
        every: usize,
    },
    /// Show nothing.
    Silent,
}

impl ProgressStyle {
    /// [`Redraw`](ProgressStyle::Redraw) if stderr is a terminal, else `otherwise`.
    pub fn redraw_on_terminal(otherwise: ProgressStyle) -> ProgressStyle {
        if std::io::stderr().is_terminal() {
            ProgressStyle::Redraw
        } else {
            otherwise
        }
    }
}

/// `[#####.....] done/total detail`.
pub fn render(done: usize, total: usize, detail: &str) -> String {
    let filled = (done * WIDTH)
        .checked_div(total)
        .unwrap_or(WIDTH)
        .min(WIDTH);
    let mut line = format!(
        "[{}{}] {done}/{total}",
        "#".repeat(filled),
        ".".repeat(WIDTH - filled)
    );
    if !detail.is_empty() {
        line.push(' ');
        line.push_str(detail);
    }
    line
}

/// A progress display on stderr.
#[derive(Debug)]
pub struct ProgressBar {
    style: ProgressStyle,
    drawn: bool,
    /// Permille shown by the last redraw, so a terminal is not rewritten for every step.
    last_drawn: Option<usize>,
}

impl ProgressBar {
    /// A bar in `style`.
    pub fn new(style: ProgressStyle) -> ProgressBar {
        ProgressBar {
            style,
            drawn: false,
            last_drawn: None,
        }
    }

    /// Show that `done` of `total` steps are done.
    pub fn update(&mut self, done: usize, total: usize, detail: &str) {
        let mut err = std::io::stderr().lock();
        match self.style {
            ProgressStyle::Redraw => {
                // Redraw when the shown permille changes (at most ~1000 writes per run).
                let key = (done * 1000).checked_div(total).unwrap_or(1000);
                if self.last_drawn == Some(key) {
                    return;
                }
                self.last_drawn = Some(key);
                write!(err, "\r{}\x1b[K", render(done, total, detail)).ok();
                err.flush().ok();
                self.drawn = true;
            }
            ProgressStyle::Lines { every } => {
                if done == total || (every > 0 && done.is_multiple_of(every)) {
                    writeln!(err, "{}", render(done, total, detail)).ok();
                }
            }
            ProgressStyle::Silent => {}
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
        assert_eq!(
            render(285, 1140, "scoring"),
            "[#####...............] 285/1140 scoring"
        );
        assert_eq!(render(0, 0, ""), "[####################] 0/0");
    }
}
