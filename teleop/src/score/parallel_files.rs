//! Processing many trial files on every core, in input order, with a progress bar.
//!
//! Files are handed out one at a time to `min(cores, 8)` worker threads; results come back
//! over a channel to the calling thread, which draws the progress and puts each result in
//! its file's place, so the output order never depends on timing.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;

use crate::progress_bar::{ProgressBar, ProgressStyle};

/// Sets of at least this many files get a bar on a terminal.
pub const BAR_ON_TERMINAL_FROM: usize = 20;
/// Sets of at least this many files get progress lines in logs (every 10 %).
pub const LINES_IN_LOGS_FROM: usize = 200;

/// The progress display for `total` files: a bar on a terminal for sets of
/// [`BAR_ON_TERMINAL_FROM`] or more, a line per 10 % in logs for sets of
/// [`LINES_IN_LOGS_FROM`] or more, else nothing.
pub fn progress_style(total: usize) -> ProgressStyle {
    let lines = if total >= LINES_IN_LOGS_FROM {
        ProgressStyle::Lines {
            every: total.div_ceil(10),
        }
    } else {
        ProgressStyle::Silent
    };
    match ProgressStyle::redraw_on_terminal(lines) {
        ProgressStyle::Redraw if total < BAR_ON_TERMINAL_FROM => ProgressStyle::Silent,
        style => style,
    }
}

/// `work` applied to every file, results in the order of `files`.
pub fn process_files<T: Send>(
    files: &[PathBuf],
    work: impl Fn(&Path) -> T + Sync,
    style: ProgressStyle,
    label: &str,
) -> Vec<T> {
    let total = files.len();
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, 8)
        .min(total.max(1));
    let next = AtomicUsize::new(0);
    let mut results: Vec<Option<T>> = (0..total).map(|_| None).collect();
    let mut bar = ProgressBar::new(style);
    std::thread::scope(|scope| {
        let (tx, rx) = mpsc::channel();
        for _ in 0..workers {
            let tx = tx.clone();
            let (next, work) = (&next, &work);
            scope.spawn(move || {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(file) = files.get(i) else { break };
                    if tx.send((i, work(file))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        for (done, (i, result)) in rx.into_iter().enumerate() {
            results[i] = Some(result);
            bar.update(done + 1, total, label);
        }
    });
    bar.finish();
    results.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_keep_the_input_order() {
        let files: Vec<PathBuf> = (0..100).map(|i| PathBuf::from(format!("{i}"))).collect();
        let out = process_files(
            &files,
            |p| {
                p.display()
                    .to_string()
                    .parse::<usize>()
                    .unwrap_or(usize::MAX)
                    * 2
            },
            ProgressStyle::Silent,
            "",
        );
        assert_eq!(out, (0..100).map(|i| i * 2).collect::<Vec<_>>());
    }
}
