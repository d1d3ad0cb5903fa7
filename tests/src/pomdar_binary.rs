//! The `pomdar` binary for tests that run it as the operator does. It lives in the `teleop`
//! package, so Cargo does not build it for this crate's tests: the helper builds it (a no-op
//! when it is up to date) into the target directory of the running test, so a test never runs
//! a stale binary.
//!
//! The build is `cargo test --workspace --no-run` itself, with the running test's profile: the
//! same selection, features and profiles (the test profile for the test targets, the dev
//! profile for the libraries and binaries) as the README's test command, so under that command
//! Cargo finds everything fresh. A narrower `-p teleop --bin pomdar` resolved other features
//! (hyper, tonic and teleop built a second time, about 1.5 min of every test run), and a
//! `cargo build --profile dev --tests` built every test target again in the dev profile.

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

static BINARY: OnceLock<Result<PathBuf, String>> = OnceLock::new();

fn build() -> Result<PathBuf, String> {
    let exe = std::env::current_exe().map_err(|e| format!("current_exe: {e}"))?;
    // target/<profile>/deps/<test binary>
    let profile_dir = exe
        .parent()
        .and_then(|deps| deps.parent())
        .ok_or_else(|| format!("unexpected test binary location {}", exe.display()))?;
    let target_dir = profile_dir
        .parent()
        .ok_or_else(|| format!("unexpected profile directory {}", profile_dir.display()))?;
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut command = Command::new(cargo);
    command.args(["test", "--no-run", "--quiet", "--workspace"]);
    match profile_dir.file_name().and_then(|n| n.to_str()) {
        // `cargo test`'s own profiles.
        Some("debug") => {}
        Some("release") => {
            command.arg("--release");
        }
        Some(name) => {
            command.args(["--profile", name]);
        }
        None => return Err(format!("no profile in {}", profile_dir.display())),
    }
    let output = command
        .arg("--target-dir")
        .arg(target_dir)
        .current_dir(crate::workspace_root())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "cargo build of pomdar failed: {}",
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let binary = profile_dir.join(format!("pomdar{}", std::env::consts::EXE_SUFFIX));
    if binary.exists() {
        Ok(binary)
    } else {
        Err(format!("{} missing after the build", binary.display()))
    }
}

/// The freshly built `pomdar` binary (built once per test process).
pub fn pomdar_binary() -> Result<PathBuf, String> {
    BINARY.get_or_init(build).clone()
}

/// Run the built `pomdar` with `args`, wait for it, and print the command line with its
/// stdout and stderr (shown when a test fails). Panics when the binary cannot be built or run.
#[allow(clippy::expect_used)] // a test helper: a panic is the failure report
pub fn run_pomdar(args: &[&str]) -> std::process::Output {
    let binary = pomdar_binary().expect("the pomdar binary builds");
    let output = Command::new(binary)
        .args(args)
        .output()
        .expect("pomdar runs");
    println!(
        "$ pomdar {}\n--- stdout\n{}--- stderr\n{}",
        args.join(" "),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// Let `child` run for `seconds`, then stop it with SIGINT (Ctrl-C) and collect its output.
/// Panics if it ended before the signal, or the signal could not be sent.
#[allow(clippy::expect_used)] // a test helper: a panic is the failure report
pub fn ctrl_c_after(mut child: std::process::Child, seconds: f64) -> std::process::Output {
    std::thread::sleep(std::time::Duration::from_secs_f64(seconds));
    if let Some(status) = child.try_wait().expect("the child's state") {
        let output = child.wait_with_output().expect("the child's output");
        panic!(
            "it ended ({status}) before the Ctrl-C after {seconds} s:\n{}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let pid = child.id().to_string();
    let signalled = Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .expect("kill runs");
    assert!(signalled.success(), "kill -INT {pid} failed");
    child.wait_with_output().expect("the child's output")
}
