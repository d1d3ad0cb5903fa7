//! Disk work done from inside a tokio task without holding up the runtime's other tasks.
//!
//! A task that waits on the disk (an `fsync`, a rename on a busy disk: measured up to 0.75 s
//! on a loaded 2-core machine) blocks its worker thread. On the multi-threaded runtime the
//! other workers steal most queued tasks, but not the one in the blocked worker's "next task"
//! slot: the task it has just woken, such as the in-process station after the console sent
//! it a command. That task then waits as long as the disk, and a station that waits half a
//! second takes its glove for stale. [`without_holding_the_runtime`] hands the worker's
//! queue to another thread first (`tokio::task::block_in_place`).

use tokio::runtime::{Handle, RuntimeFlavor};

/// Runs `f`, which may wait on the disk. Inside a multi-threaded runtime the tasks queued on
/// this worker move to another thread while `f` runs; elsewhere (a current-thread runtime, a
/// blocking thread, no runtime) `f` simply runs.
pub fn without_holding_the_runtime<T>(f: impl FnOnce() -> T) -> T {
    match Handle::try_current() {
        Ok(handle) if handle.runtime_flavor() == RuntimeFlavor::MultiThread => {
            tokio::task::block_in_place(f)
        }
        _ => f(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_outside_a_runtime() {
        assert_eq!(without_holding_the_runtime(|| 7), 7);
    }

    #[tokio::test]
    async fn runs_on_a_current_thread_runtime() {
        assert_eq!(without_holding_the_runtime(|| 8), 8);
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn runs_on_a_worker_and_on_a_blocking_thread() {
        assert_eq!(without_holding_the_runtime(|| 9), 9);
        let on_blocking = tokio::task::spawn_blocking(|| without_holding_the_runtime(|| 10));
        assert_eq!(on_blocking.await.unwrap(), 10);
    }

    /// While one worker waits in `f`, a task it woke just before runs on another thread.
    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_task_woken_before_the_wait_runs_during_it() {
        let (tx, rx) = tokio::sync::oneshot::channel::<()>();
        let (done_tx, done_rx) = std::sync::mpsc::channel::<()>();
        let woken = tokio::spawn(async move {
            rx.await.ok();
            done_tx.send(()).ok();
        });
        tokio::task::yield_now().await;
        let waited = tokio::spawn(async move {
            tx.send(()).ok();
            // The woken task sits in this worker's next-task slot; the wait ends when it ran.
            without_holding_the_runtime(|| {
                done_rx
                    .recv_timeout(std::time::Duration::from_secs(10))
                    .is_ok()
            })
        });
        assert!(
            waited.await.unwrap(),
            "the woken task did not run during the wait"
        );
        woken.await.unwrap();
    }
}
