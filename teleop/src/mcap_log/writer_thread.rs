//! A [`TrialWriter`] owned by a thread of its own, for a loop that must never wait on the disk
//! (the calibration console: its captures are judged by when frames arrive, so a loop held
//! by a flush would take a burst of late frames for a still hand).
//!
//! The loop hands each write over as a closure ([`WriterThread::write`]) and goes on; the
//! thread applies them in order. The first write that fails is kept and returned by the next
//! call, so an error still ends the session, one write later. [`WriterThread::finish`] waits
//! for the queued writes, finishes the log and returns it.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

use super::{FinishedTrial, LogError, TrialWriter};

/// One write to apply to the log.
type Write = Box<dyn FnOnce(&mut TrialWriter) -> Result<(), LogError> + Send>;

/// The loop's end of a log written on its own thread.
pub struct WriterThread {
    writes: Option<Sender<Write>>,
    thread: Option<JoinHandle<Result<FinishedTrial, LogError>>>,
    /// The first write that failed, until reported.
    failed: Arc<Mutex<Option<LogError>>>,
    /// Writes queued and not yet applied.
    pending: Arc<AtomicUsize>,
}

impl WriterThread {
    /// Moves `writer` to a thread of its own.
    pub fn spawn(writer: TrialWriter) -> std::io::Result<WriterThread> {
        let (writes, inbox) = channel();
        let failed = Arc::new(Mutex::new(None));
        let pending = Arc::new(AtomicUsize::new(0));
        let queue = Queue {
            inbox,
            failed: Arc::clone(&failed),
            pending: Arc::clone(&pending),
        };
        let thread = std::thread::Builder::new()
            .name("pomdar-log-writer".into())
            .spawn(move || queue.apply_to(writer))?;
        Ok(WriterThread {
            writes: Some(writes),
            thread: Some(thread),
            failed,
            pending,
        })
    }

    /// Queues `write` (returns at once). Errs with an earlier write's failure, if one failed.
    pub fn write(
        &self,
        write: impl FnOnce(&mut TrialWriter) -> Result<(), LogError> + Send + 'static,
    ) -> Result<(), LogError> {
        if let Some(error) = self.take_failure() {
            return Err(error);
        }
        if let Some(writes) = &self.writes {
            self.pending.fetch_add(1, Ordering::Relaxed);
            // The thread stops only when this side closes.
            let _ = writes.send(Box::new(write));
        }
        Ok(())
    }

    /// Writes queued and not yet applied (what [`finish`](WriterThread::finish) will wait for).
    pub fn pending(&self) -> usize {
        self.pending.load(Ordering::Relaxed)
    }

    /// Waits for every queued write, then finishes the log (summary, sync, rename). The first
    /// failed write, if any, is the error.
    pub fn finish(mut self) -> Result<FinishedTrial, LogError> {
        self.writes = None;
        let finished = match self.thread.take().map(JoinHandle::join) {
            Some(Ok(finished)) => finished,
            Some(Err(panic)) => std::panic::resume_unwind(panic),
            None => unreachable!("the thread is joined only here"),
        };
        match self.take_failure() {
            Some(error) => Err(error),
            None => finished,
        }
    }

    fn take_failure(&self) -> Option<LogError> {
        self.failed
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take()
    }
}

impl Drop for WriterThread {
    /// Dropped without [`finish`](WriterThread::finish): the queued writes are applied and
    /// the log finished, so it is complete on disk.
    fn drop(&mut self) {
        self.writes = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// The thread's end: the writes to apply, where a failure and the count go.
struct Queue {
    inbox: Receiver<Write>,
    failed: Arc<Mutex<Option<LogError>>>,
    pending: Arc<AtomicUsize>,
}

impl Queue {
    /// Applies the writes in order until the loop's end closes, then finishes the log.
    fn apply_to(self, mut writer: TrialWriter) -> Result<FinishedTrial, LogError> {
        while let Ok(write) = self.inbox.recv() {
            if let Err(error) = write(&mut writer) {
                self.failed
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .get_or_insert(error);
            }
            self.pending.fetch_sub(1, Ordering::Relaxed);
        }
        writer.finish()
    }
}

#[cfg(test)]
mod tests {
    use msgs::Float32MultiArray;

    use super::*;
    use crate::mcap_log::test_dir::TestDir;
    use crate::mcap_log::{OfferedQos, TrialReader, TrialWriterOptions};

    fn keypoints(x: f32) -> Float32MultiArray {
        Float32MultiArray::from_points(&[[x, 0.0, 0.0]]).unwrap()
    }

    #[test]
    fn queued_writes_are_all_in_the_finished_log_in_order() {
        let dir = TestDir::new("writer-thread-order");
        let thread = spawned(&dir, "session.mcap");
        for k in 0..500_i64 {
            let message = keypoints(k as f32);
            thread
                .write(move |w| w.write("/k", 1_000 + k, 1_000 + k, &message))
                .unwrap();
        }
        let finished = thread.finish().unwrap();
        let log = TrialReader::open(&finished.path).unwrap();
        let xs: Vec<f32> = log
            .messages_on("/k")
            .map(|m| m.decode::<Float32MultiArray>().unwrap().data[0])
            .collect();
        assert_eq!(xs, (0..500).map(|k| k as f32).collect::<Vec<_>>());
    }

    /// A writer with a keypoint channel on `/k`, on its thread.
    fn spawned(dir: &TestDir, name: &str) -> WriterThread {
        let mut writer =
            TrialWriter::create(&dir.path().join(name), TrialWriterOptions::default()).unwrap();
        writer
            .add_channel::<Float32MultiArray>("/k", &[OfferedQos::best_effort(10)])
            .unwrap();
        WriterThread::spawn(writer).unwrap()
    }

    /// A write that fails in the thread: another type on the keypoint topic.
    fn conflicting(w: &mut TrialWriter) -> Result<(), LogError> {
        w.write("/k", 1, 1, &msgs::JointState::default())
    }

    #[test]
    fn a_failed_write_is_returned_by_the_next_call_and_by_finish() {
        let dir = TestDir::new("writer-thread-failure");
        let thread = spawned(&dir, "a.mcap");
        thread.write(conflicting).unwrap();
        let mut reported = None;
        for _ in 0..1000 {
            match thread.write(|_| Ok(())) {
                Ok(()) => std::thread::sleep(std::time::Duration::from_millis(1)),
                Err(e) => {
                    reported = Some(e);
                    break;
                }
            }
        }
        assert!(
            matches!(reported, Some(LogError::ChannelConflict { .. })),
            "{reported:?}"
        );
        let failing = spawned(&dir, "b.mcap");
        failing.write(conflicting).unwrap();
        assert!(failing.finish().is_err());
    }
}
