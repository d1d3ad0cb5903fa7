//! The Cyclone DDS peers of the interop suite (`tests/interop/cyclone_*.py`), run beside a
//! production station node: start, read their JSON lines, compare what they report with the
//! station's own log.

#![allow(clippy::unwrap_used, clippy::expect_used)] // test helpers: a panic is the failure report

use std::io::{BufRead as _, BufReader, Write as _};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::time::Duration;

use retarget::HandModel;
use serde_json::Value;
use station::StationConfig;
use teleop::clock::StationClock;
use teleop::station_node::recorder::RecordingOptions;
use teleop::station_node::ros_node::run_station;
use tokio::sync::{mpsc, watch};

use crate::interop::interop_script;

/// The running peer: its stdin (closing it ends the peer) and its stdout lines.
pub struct Peer {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: mpsc::UnboundedReceiver<String>,
}

impl Peer {
    /// Start `tests/interop/SCRIPT PLAN` with the interop Python.
    pub fn start(python: &Path, script: &str, plan_path: &Path) -> Peer {
        let mut child = Command::new(python)
            .arg(interop_script(script))
            .arg(plan_path)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {script}: {e}"));
        let stdout = child.stdout.take().unwrap();
        let (tx, lines) = mpsc::unbounded_channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let stdin = child.stdin.take();
        Peer {
            child,
            stdin,
            lines,
        }
    }

    /// The peer's next JSON line of `kind`; panics on its error line, its exit or a timeout.
    pub async fn next(&mut self, kind: &str, timeout: Duration) -> Value {
        let line = tokio::time::timeout(timeout, self.lines.recv())
            .await
            .unwrap_or_else(|_| panic!("no '{kind}' from the Cyclone peer within {timeout:?}"))
            .unwrap_or_else(|| {
                let status = self.child.wait().unwrap();
                panic!("the Cyclone peer exited ({status}) before '{kind}'")
            });
        let value: Value =
            serde_json::from_str(&line).unwrap_or_else(|_| panic!("Cyclone peer printed {line}"));
        assert_eq!(
            value["kind"],
            kind,
            "Cyclone peer: {}",
            value["message"].as_str().unwrap_or(&line)
        );
        value
    }

    /// Close the peer's stdin: it stops receiving and prints its report.
    pub fn close_stdin(&mut self) {
        if let Some(mut stdin) = self.stdin.take() {
            stdin.flush().ok();
        }
    }
}

/// The peer's messages of one kind, as `msgs` values.
#[track_caller]
pub fn decode<T: serde::de::DeserializeOwned>(report: &Value, pointer: &str) -> Vec<T> {
    let value = report.pointer(pointer).unwrap_or(&Value::Null);
    serde_json::from_value(value.clone()).unwrap_or_else(|e| {
        let text: String = value.to_string().chars().take(300).collect();
        panic!("the peer's {pointer} ({text}...): {e}")
    })
}

/// Cyclone received, message for message, exactly what the station sent (its log). After the
/// last frame's target the station sends nothing more (every-frame control, watchdog far off),
/// and the peer keeps receiving until the station has stopped.
pub fn assert_same_messages<T: PartialEq + std::fmt::Debug>(
    what: &str,
    received: &[T],
    sent: &[T],
) {
    for (i, (r, s)) in received.iter().zip(sent).enumerate() {
        assert_eq!(
            r, s,
            "{what} {i}: as Cyclone decoded it vs as the station sent it"
        );
    }
    assert_eq!(
        received.len(),
        sent.len(),
        "{what}s: Cyclone received {}, the station sent {}",
        received.len(),
        sent.len()
    );
}

/// Runs the station, recording to `log_path`, then the peer, until the peer has sent every
/// frame; stops the station and collects the peer's report. Checks the station recorded that
/// one log and found each of the `frames` new.
pub async fn run_station_with_peer(
    python: &Path,
    script: &str,
    config: &StationConfig,
    plan_path: &Path,
    log_path: &Path,
    frames: usize,
) -> Value {
    let (shutdown, shutdown_rx) = watch::channel(false);
    let (_operator, operator_rx) = mpsc::unbounded_channel();
    let station = tokio::spawn(run_station(
        config.clone(),
        HandModel::orca_v1_right(),
        StationClock::new(),
        shutdown_rx,
        operator_rx,
        Some(RecordingOptions {
            path: log_path.to_path_buf(),
            metadata: Default::default(),
        }),
    ));
    let mut peer = Peer::start(python, script, plan_path);
    let done = peer.next("done", Duration::from_secs(40)).await;
    println!("Cyclone peer: {done}");
    shutdown.send(true).unwrap();
    let summary = station.await.unwrap().unwrap();
    peer.close_stdin();
    let report = peer.next("report", Duration::from_secs(10)).await;
    assert!(peer.child.wait().unwrap().success());
    assert_eq!(summary.recorded, vec![log_path.to_path_buf()]);
    assert_eq!(
        summary.counters.frames_new, frames as u64,
        "every frame new (no repeats in this motion, none rejected): {:?}",
        summary.counters
    );
    report
}
