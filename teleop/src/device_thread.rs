//! A simulated device (the glove of `pomdar trial --simulate` and `pomdar demo`) on a thread
//! of its own, with its own single-threaded tokio runtime.
//!
//! A real glove is a separate machine: nothing the station's process does delays its frames.
//! A simulated one spawned on the process's runtime shares its two worker threads with the
//! console, the station and their writes; a worker blocked in a terminal write or a disk
//! wait holds the task it has just woken in its "next task" slot, which the other worker
//! does not steal (`disk_wait`), and a glove task woken there falls silent for as long as
//! the wait. On a thread of its own the device keeps its rate whatever the rest of the
//! process waits on.
//!
//! What it does not escape is the CPU. On a loaded 2-core machine (two CPU hogs beside the
//! console tests) the glove's thread of `pomdar trial --simulate` under a pseudo-terminal,
//! runnable, waited up to 2.2 s on the kernel's run queue (its `schedstat`) while its
//! publishes took microseconds; a nice of −10 on the thread changed nothing. The process
//! was in a scheduling group of its own (the session the pseudo-terminal makes, with
//! `sched_autogroup_enabled`); with autogroups off the same runs saw no gap over 40 ms.

use std::future::Future;

use crate::stand_ins::SimError;

/// Runs `device` to its end on a new thread named `name` with its own runtime (timers and
/// I/O enabled); the returned task, on the caller's runtime, ends with its result.
pub fn spawn_device<T: Send + 'static>(
    name: &str,
    device: impl Future<Output = Result<T, SimError>> + Send + 'static,
) -> Result<tokio::task::JoinHandle<Result<T, SimError>>, SimError> {
    let failed = |source| SimError::DeviceThread {
        device: name.to_string(),
        source,
    };
    let (tx, rx) = tokio::sync::oneshot::channel();
    let thread_name = name.to_string();
    std::thread::Builder::new()
        .name(name.to_string())
        .spawn(move || {
            let result = match tokio::runtime::Builder::new_current_thread()
                .enable_all()
                .build()
            {
                Ok(runtime) => runtime.block_on(device),
                Err(source) => Err(SimError::DeviceThread {
                    device: thread_name,
                    source,
                }),
            };
            tx.send(result).ok();
        })
        .map_err(failed)?;
    let name = name.to_string();
    Ok(tokio::spawn(async move {
        rx.await.unwrap_or_else(|_| {
            Err(SimError::DeviceThread {
                device: name,
                source: std::io::Error::other("the thread ended without a result"),
            })
        })
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn the_device_runs_while_every_worker_of_the_caller_is_blocked() {
        use std::sync::Arc;
        use std::sync::atomic::{AtomicU32, Ordering};
        let ticks = Arc::new(AtomicU32::new(0));
        let (stop_tx, mut stop_rx) = tokio::sync::watch::channel(false);
        let counted = Arc::clone(&ticks);
        let device = spawn_device("test-device", async move {
            let mut interval = tokio::time::interval(std::time::Duration::from_millis(10));
            loop {
                tokio::select! {
                    _ = stop_rx.changed() => return Ok(()),
                    _ = interval.tick() => { counted.fetch_add(1, Ordering::Relaxed); }
                }
            }
        })
        .unwrap();
        // Both workers of this runtime block for 300 ms; each counts the device's ticks
        // meanwhile (a task on this runtime would tick not once).
        let blockers: Vec<_> = (0..2)
            .map(|_| {
                let ticks = Arc::clone(&ticks);
                tokio::spawn(async move {
                    let before = ticks.load(Ordering::Relaxed);
                    std::thread::sleep(std::time::Duration::from_millis(300));
                    ticks.load(Ordering::Relaxed) - before
                })
            })
            .collect();
        for b in blockers {
            assert!(
                b.await.unwrap() > 0,
                "the device did not tick while the workers were blocked"
            );
        }
        stop_tx.send(true).unwrap();
        device.await.unwrap().unwrap();
    }

    #[tokio::test]
    async fn a_failing_device_reports_its_error() {
        let device = spawn_device("failing-device", async {
            Err::<(), _>(SimError::Physics {
                message: "no scene".into(),
            })
        })
        .unwrap();
        let error = device.await.unwrap().unwrap_err();
        assert!(error.to_string().contains("no scene"), "{error}");
    }
}
