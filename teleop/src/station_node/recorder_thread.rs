//! The trial log written on a thread of its own, so the control loop never waits on the disk.
//!
//! The station's loop only hands each write to [`LogQueue`]: a copy of the message and where
//! it goes, queued for the recorder thread, which owns the [`StationRecorder`] and does every
//! encoding, write, flush, `fsync` and the rename at a trial's end. What the thread did comes
//! back as a [`LogReport`] on a channel the loop selects on (a trial's log created or not,
//! finished and renamed or not, a write error).
//!
//! The queue holds at most [`LogQueue::CAPACITY`] message writes. Past that a write is
//! dropped and counted, never waited for: the count goes into the status (`node.log_dropped`),
//! the trial's stop event and summary (`log_dropped`), and the console's fault row. Starts,
//! trial events and finishes are never dropped, and keep their order with the writes around
//! them.
//!
//! What a crash loses: the messages still in the queue (at most [`LogQueue::CAPACITY`], about
//! 4 s at the station's usual 500 messages/s, and while the disk keeps up only the last
//! [`DRAIN_PERIOD`], 5 ms, the thread has not taken yet), plus those
//! the thread wrote after the log's last flush (at most one flush interval, 1 s of log time,
//! or the console's shorter interval). A trial event is flushed as soon as the thread reaches
//! it.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::thread::JoinHandle;

use station::StationConfig;
use tokio::sync::mpsc as async_mpsc;

use crate::mcap_log::FinishedTrial;
use crate::station_node::error::NodeError;
use crate::station_node::recorder::{RecordingOptions, StationRecorder};

/// How often the recorder thread takes what was queued: a write reaches the log at most this
/// late (and a crash loses at most this much more than the queue and the last flush).
const DRAIN_PERIOD: std::time::Duration = std::time::Duration::from_millis(5);

/// A write to apply to the open log.
type Write = Box<dyn FnOnce(&mut StationRecorder) + Send>;

/// What the loop asks of the recorder thread.
enum Job {
    /// Record into this log, already created (the station's `--out` log, opened at start-up).
    Adopt(Box<StationRecorder>),
    /// Create a trial's log and record into it.
    Start {
        options: RecordingOptions,
        config: Arc<StationConfig>,
        now_ns: i64,
        flush_interval_ns: Option<i64>,
        /// Which start this is (the queue's count).
        started: u64,
    },
    /// A message or a flush check: may be dropped when the queue is full.
    Write(Write),
    /// A trial event (flushed at once): never dropped.
    Event(Write),
    /// Write the stop event with this summary and rename the log.
    Finish {
        now_ns: i64,
        summary: serde_json::Value,
    },
}

/// What the recorder thread did, for the station's loop.
#[derive(Debug)]
pub enum LogReport {
    /// A trial's log was created (its final path).
    Started(PathBuf),
    /// A trial's log could not be created.
    StartFailed {
        /// The log asked for.
        path: PathBuf,
        /// Which start it was ([`LogQueue::start_failed`]).
        started: u64,
        /// Why.
        error: NodeError,
    },
    /// A write failed (the first of a log's failures); recording goes on where it can.
    WriteFailed(NodeError),
    /// A log was finished and renamed.
    Finished(FinishedTrial),
    /// A log could not be finished: its `.part` stays for `pomdar recover`.
    FinishFailed {
        /// The log's final path.
        path: PathBuf,
        /// Why.
        error: NodeError,
    },
}

/// The loop's end of the recorder thread.
pub struct LogQueue {
    jobs: Option<std::sync::mpsc::Sender<Job>>,
    /// Message writes queued and not yet done by the thread.
    pending: Arc<AtomicUsize>,
    thread: Option<JoinHandle<()>>,
    /// Whether a log is open (writes are queued only then).
    open: bool,
    /// Logs started so far: a failed start closes the log only if no later one began.
    starts: u64,
    /// Writes dropped on a full queue: since the station started, and in the open log.
    dropped_total: u64,
    dropped_in_log: u64,
}

impl LogQueue {
    /// Message writes the queue holds before it drops them (about 4 s of a station's
    /// messages: a disk that stalls longer loses messages, counted, not control steps).
    pub const CAPACITY: usize = 2048;

    /// Starts the recorder thread (recording into `initial` from the start, if given); what it
    /// did comes back on the returned receiver.
    pub fn spawn(
        initial: Option<StationRecorder>,
    ) -> Result<(LogQueue, async_mpsc::UnboundedReceiver<LogReport>), NodeError> {
        let (jobs, inbox) = std::sync::mpsc::channel();
        let (reports, reports_rx) = async_mpsc::unbounded_channel();
        let pending = Arc::new(AtomicUsize::new(0));
        let worker = RecorderWorker {
            recorder: None,
            pending: Arc::clone(&pending),
            reports,
        };
        let thread = std::thread::Builder::new()
            .name("pomdar-recorder".into())
            .spawn(move || worker.run(&inbox))
            .map_err(|source| NodeError::RecorderThread { source })?;
        let mut queue = LogQueue {
            jobs: Some(jobs),
            pending,
            thread: Some(thread),
            open: false,
            starts: 0,
            dropped_total: 0,
            dropped_in_log: 0,
        };
        if let Some(recorder) = initial {
            queue.open = true;
            queue.send(Job::Adopt(Box::new(recorder)));
        }
        Ok((queue, reports_rx))
    }

    /// Whether a log is open.
    pub fn is_open(&self) -> bool {
        self.open
    }

    /// Writes dropped on a full queue since the station started.
    pub fn dropped_total(&self) -> u64 {
        self.dropped_total
    }

    /// Writes dropped on a full queue in the open log.
    pub fn dropped_in_log(&self) -> u64 {
        self.dropped_in_log
    }

    /// Opens a trial's log (the thread creates it; [`LogReport::Started`] or
    /// [`LogReport::StartFailed`] says how that went).
    pub fn start(
        &mut self,
        options: RecordingOptions,
        config: Arc<StationConfig>,
        now_ns: i64,
        flush_interval_ns: Option<i64>,
    ) {
        self.open = true;
        self.starts += 1;
        self.dropped_in_log = 0;
        self.send(Job::Start {
            options,
            config,
            now_ns,
            flush_interval_ns,
            started: self.starts,
        });
    }

    /// The thread could not create a log: stop queueing writes for it, unless another log
    /// was started since (`started` is [`LogReport::StartFailed`]'s count).
    pub fn start_failed(&mut self, started: u64) {
        if started == self.starts {
            self.open = false;
        }
    }

    /// Queues a write to the open log (nothing when none is open); a full queue drops it and
    /// counts it.
    pub fn write(&mut self, write: impl FnOnce(&mut StationRecorder) + Send + 'static) {
        if !self.open {
            return;
        }
        if self.pending.load(Ordering::Acquire) >= Self::CAPACITY {
            self.dropped_total += 1;
            self.dropped_in_log += 1;
            return;
        }
        self.pending.fetch_add(1, Ordering::AcqRel);
        self.send(Job::Write(Box::new(write)));
    }

    /// Queues a trial event for the open log: never dropped.
    pub fn event(&mut self, now_ns: i64, event: serde_json::Value) {
        if self.open {
            self.send(Job::Event(Box::new(move |r| r.event(now_ns, &event))));
        }
    }

    /// Finishes the open log (stop event with `summary`, summary section, rename).
    pub fn finish(&mut self, now_ns: i64, summary: serde_json::Value) {
        if std::mem::take(&mut self.open) {
            self.send(Job::Finish { now_ns, summary });
        }
    }

    /// Closes the queue: the thread ends once it has done everything queued. Join the
    /// returned thread to wait for that (`None` once closed).
    pub fn close(&mut self) -> Option<JoinHandle<()>> {
        self.jobs = None;
        self.thread.take()
    }

    fn send(&mut self, job: Job) {
        if let Some(jobs) = &self.jobs {
            // The thread only stops when the queue is closed (or it panicked: then the log is
            // a `.part` for `pomdar recover`, and nothing more can be written).
            let _ = jobs.send(job);
        }
    }
}

impl Drop for LogQueue {
    fn drop(&mut self) {
        if let Some(thread) = self.close() {
            // A panic in the thread has already been printed; its logs stay `.part`.
            let _ = thread.join();
        }
    }
}

/// The recorder thread: the open log, and where its reports go.
struct RecorderWorker {
    recorder: Option<StationRecorder>,
    pending: Arc<AtomicUsize>,
    reports: async_mpsc::UnboundedSender<LogReport>,
}

impl RecorderWorker {
    /// Take the queued jobs every [`DRAIN_PERIOD`] until the loop's end of the queue is gone.
    /// The thread polls rather than blocking on the queue: a send to a receiver blocked in
    /// `recv` wakes it with a system call in the sender, which was the control loop, once per
    /// message. (It keeps the station's priority: at nice +10, a simulated trial whose physics
    /// kept both cores busy starved it, and its queue could fill and drop messages.)
    fn run(mut self, inbox: &std::sync::mpsc::Receiver<Job>) {
        loop {
            loop {
                match inbox.try_recv() {
                    Ok(job) => self.take(job),
                    Err(std::sync::mpsc::TryRecvError::Empty) => break,
                    Err(std::sync::mpsc::TryRecvError::Disconnected) => return,
                }
            }
            std::thread::sleep(DRAIN_PERIOD);
        }
    }

    fn take(&mut self, job: Job) {
        match job {
            Job::Adopt(recorder) => self.recorder = Some(*recorder),
            Job::Start {
                options,
                config,
                now_ns,
                flush_interval_ns,
                started,
            } => self.start(&options, &config, (now_ns, flush_interval_ns), started),
            Job::Write(write) => {
                self.apply(write);
                self.pending.fetch_sub(1, Ordering::AcqRel);
            }
            Job::Event(write) => self.apply(write),
            Job::Finish { now_ns, summary } => self.finish(now_ns, summary),
        }
    }

    fn apply(&mut self, write: Write) {
        if let Some(recorder) = self.recorder.as_mut() {
            write(recorder);
            if let Some(error) = recorder.take_error() {
                self.report(LogReport::WriteFailed(error));
            }
        }
    }

    fn start(
        &mut self,
        options: &RecordingOptions,
        config: &StationConfig,
        (now_ns, flush_interval_ns): (i64, Option<i64>),
        started: u64,
    ) {
        match StationRecorder::start_flushing(options, config, now_ns, flush_interval_ns) {
            Ok(recorder) => {
                self.recorder = Some(recorder);
                self.report(LogReport::Started(options.path.clone()));
            }
            Err(error) => {
                self.recorder = None;
                self.report(LogReport::StartFailed {
                    path: options.path.clone(),
                    started,
                    error,
                });
            }
        }
    }

    fn finish(&mut self, now_ns: i64, summary: serde_json::Value) {
        let Some(mut recorder) = self.recorder.take() else {
            return;
        };
        if let Some(error) = recorder.take_error() {
            self.report(LogReport::WriteFailed(error));
        }
        let path = recorder.path().to_path_buf();
        match recorder.finish(now_ns, summary) {
            Ok(finished) => self.report(LogReport::Finished(finished)),
            Err(error) => self.report(LogReport::FinishFailed { path, error }),
        }
    }

    fn report(&self, report: LogReport) {
        // The loop has stopped listening only when the station is shutting down; the logs
        // are on disk all the same.
        let _ = self.reports.send(report);
    }
}
