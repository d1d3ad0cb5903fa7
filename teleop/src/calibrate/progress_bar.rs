//! The fit's progress on stderr, with the shared [`crate::progress_bar`]: a bar redrawn in
//! place on a terminal (`[#####.....] 52/100 best 0.213 rad`), a plain line every 10
//! evaluations otherwise (logs, pipes, tests).

use calibration::FitProgress;

use crate::progress_bar::{ProgressStyle, render as render_bar};

/// Evaluations between lines when stderr is not a terminal.
const LINE_EVERY: usize = 10;

/// Progress display for one fit.
#[derive(Debug)]
pub struct ProgressBar {
    bar: crate::progress_bar::ProgressBar,
}

impl Default for ProgressBar {
    fn default() -> Self {
        ProgressBar::new()
    }
}

/// `[#####.....] 52/100 best 0.213 rad`.
pub fn render(p: FitProgress) -> String {
    render_bar(p.done, p.budget, &detail(p))
}

fn detail(p: FitProgress) -> String {
    format!("best {:.3} rad", p.best)
}

impl ProgressBar {
    /// A bar for stderr (redrawn in place only if stderr is a terminal).
    pub fn new() -> ProgressBar {
        ProgressBar {
            bar: crate::progress_bar::ProgressBar::new(ProgressStyle::redraw_on_terminal(
                ProgressStyle::Lines { every: LINE_EVERY },
            )),
        }
    }

    /// Show `p`.
    pub fn update(&mut self, p: FitProgress) {
        self.bar.update(p.done, p.budget, &detail(p));
    }

    /// End the bar's line.
    pub fn finish(&mut self) {
        self.bar.finish();
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
