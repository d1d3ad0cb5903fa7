//! The line console: without a terminal (or with `--plain`), the console prints a line for
//! each change of state, each message and each trial result, on stderr.

use super::view::ConsoleView;

/// What was printed already.
#[derive(Debug, Default)]
pub struct PlainOutput {
    banner: Option<String>,
    said: u64,
    results: Vec<String>,
}

impl PlainOutput {
    /// Prints what changed since the last call, with the console's time `t_s`; `said` is the
    /// number of messages said so far (the view shows the newest of them).
    pub fn update(&mut self, view: &ConsoleView, said: u64, t_s: f64) {
        let state = view.screen.banner().to_string();
        if self.banner.as_deref() != Some(state.as_str()) {
            let detail = view.detail.first().cloned().unwrap_or_default();
            eprintln!(
                "[{t_s:7.1} s] {state}{}",
                if detail.is_empty() {
                    String::new()
                } else {
                    format!(" · {detail}")
                }
            );
            self.banner = Some(state);
        }
        let new = usize::try_from(said.saturating_sub(self.said)).unwrap_or(usize::MAX);
        let shown = view.messages.len();
        for message in &view.messages[shown.saturating_sub(new)..] {
            eprintln!("[{t_s:7.1} s]   {message}");
        }
        self.said = said;
        if view.results != self.results {
            if view.results.first().is_some_and(|r| r.starts_with("last ")) {
                for line in &view.results {
                    eprintln!("[{t_s:7.1} s]   {line}");
                }
            }
            self.results.clone_from(&view.results);
        }
    }
}
