//! A `pomdar` console run as a child process through its stdin (the line console), its
//! stderr collected as it comes: how the interrupt tests drive `pomdar trial` and `pomdar
//! study` as an operator would, then signal or kill them.

use std::io::{BufRead as _, BufReader, Write as _};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::pomdar_binary::pomdar_binary;

/// A child process, killed when dropped so a failing test leaves nothing running.
pub struct Process(pub Child);

impl Drop for Process {
    fn drop(&mut self) {
        self.0.kill().ok();
        self.0.wait().ok();
    }
}

/// A line console: its stdin, and its stderr collected as it comes.
pub struct LineConsole {
    /// The console's process.
    pub process: Process,
    /// Everything it wrote to stderr so far.
    pub stderr: Arc<Mutex<String>>,
}

impl LineConsole {
    /// Starts `pomdar ARGS` with piped stdin, stdout and stderr.
    ///
    /// # Panics
    /// When the binary cannot be found or started (a test's failure report).
    pub fn start(args: &[String]) -> LineConsole {
        LineConsole::start_with_env(args, &[])
    }

    /// Starts `pomdar ARGS` as [`LineConsole::start`] does, with `env` added to its
    /// environment (a test knob).
    ///
    /// # Panics
    /// When the binary cannot be found or started (a test's failure report).
    pub fn start_with_env(args: &[String], env: &[(&str, &str)]) -> LineConsole {
        let binary = pomdar_binary().unwrap_or_else(|e| panic!("{e}"));
        let mut child = Command::new(binary)
            .args(args)
            .envs(env.iter().copied())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start pomdar: {e}"));
        let stderr = Arc::new(Mutex::new(String::new()));
        let sink = stderr.clone();
        if let Some(pipe) = child.stderr.take() {
            std::thread::spawn(move || {
                for line in BufReader::new(pipe).lines() {
                    let Ok(line) = line else { break };
                    lock(&sink).push_str(&(line + "\n"));
                }
            });
        }
        LineConsole {
            process: Process(child),
            stderr,
        }
    }

    /// Types `command` and Enter.
    ///
    /// # Panics
    /// When the console's stdin is closed.
    pub fn say(&mut self, command: &str) {
        let stdin = self
            .process
            .0
            .stdin
            .as_mut()
            .unwrap_or_else(|| panic!("no stdin"));
        writeln!(stdin, "{command}").unwrap_or_else(|e| panic!("stdin: {e}"));
        stdin.flush().unwrap_or_else(|e| panic!("stdin: {e}"));
    }

    /// Waits until stderr holds `text`, `timeout_s` at most.
    ///
    /// # Panics
    /// On timeout, with everything the console printed.
    pub fn wait_for(&self, text: &str, timeout_s: f64) {
        let start = Instant::now();
        while !lock(&self.stderr).contains(text) {
            assert!(
                start.elapsed().as_secs_f64() < timeout_s,
                "waited {timeout_s} s for {text:?}; the console printed:\n{}",
                lock(&self.stderr)
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// How many times stderr holds `text` so far.
    pub fn count(&self, text: &str) -> usize {
        lock(&self.stderr).matches(text).count()
    }

    /// Waits until stderr holds `text` at least `times` times, `timeout_s` at most.
    ///
    /// # Panics
    /// On timeout, with everything the console printed.
    pub fn wait_for_nth(&self, text: &str, times: usize, timeout_s: f64) {
        let start = Instant::now();
        while self.count(text) < times {
            assert!(
                start.elapsed().as_secs_f64() < timeout_s,
                "waited {timeout_s} s for {text:?} ×{times}; the console printed:\n{}",
                lock(&self.stderr)
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// The process id, as `kill` takes it.
    pub fn pid(&self) -> String {
        self.process.0.id().to_string()
    }

    /// Sends SIGINT (Ctrl-C) and waits for the exit code.
    ///
    /// # Panics
    /// When `kill` fails.
    pub fn interrupt(&mut self) -> Option<i32> {
        let status = Command::new("kill")
            .args(["-INT", &self.pid()])
            .status()
            .unwrap_or_else(|e| panic!("kill: {e}"));
        assert!(status.success(), "kill -INT failed");
        self.process.0.wait().ok().and_then(|s| s.code())
    }

    /// Everything printed on stderr so far.
    pub fn printed(&self) -> String {
        lock(&self.stderr).clone()
    }
}

fn lock(text: &Mutex<String>) -> std::sync::MutexGuard<'_, String> {
    text.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}
