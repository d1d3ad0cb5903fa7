//! The console's messages, appended with their UTC time to [`MESSAGE_LOG_FILE`] in the session
//! directory: what the operator was told (refusals, cancelled countdowns, faults, results)
//! stays with the session after the screen is gone, whole, where the screen shows one line of
//! each. One line per message: `20261129T222233Z countdown cancelled: …`.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::console::trial_flow::TrialFlow;
use crate::disk_wait::without_holding_the_runtime;
use crate::utc_date::{compact_utc, now_unix_s};

/// The file in the session directory.
pub const MESSAGE_LOG_FILE: &str = "console.log";

/// Where the messages go, and how many were written.
#[derive(Debug)]
pub struct MessageLog {
    path: PathBuf,
    /// Messages of the flow written so far.
    logged: u64,
    /// Whether a write failed (said once, then the log is given up).
    failed: bool,
}

impl MessageLog {
    /// The log of the session in `dir` (appended to: a resumed session continues it).
    pub fn new(dir: &Path) -> MessageLog {
        MessageLog {
            path: dir.join(MESSAGE_LOG_FILE),
            logged: 0,
            failed: false,
        }
    }

    /// Appends what `flow` said since the last call; a write that fails is said once.
    pub fn append_new(&mut self, flow: &mut TrialFlow) {
        let said = flow.said();
        if said == self.logged || self.failed {
            return;
        }
        let kept: Vec<&str> = flow.messages().collect();
        let new = ((said - self.logged) as usize).min(kept.len());
        let stamp = compact_utc(now_unix_s());
        let text: String = kept[kept.len() - new..]
            .iter()
            .map(|m| format!("{stamp} {}\n", m.replace('\n', " | ")))
            .collect();
        self.logged = said;
        let path = &self.path;
        let written = without_holding_the_runtime(|| {
            std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(path)
                .and_then(|mut f| f.write_all(text.as_bytes()))
        });
        if let Err(e) = written {
            self.failed = true;
            flow.say(format!(
                "error: cannot write the console's messages to {}: {e}",
                path.display()
            ));
        }
    }
}
