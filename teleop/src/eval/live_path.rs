//! The live path of `pomdar eval`: the recording re-simulated through the [`station::Station`]
//! exactly as `pomdar resim` drives it (its gate, watchdog, control mode and timer), and the
//! command in force after each distinct glove frame scored with the same metrics as the
//! retargeter alone. Where the two differ, the station's control loop (a tick beating against
//! the glove, a rejected frame) costs what the figures say.

use std::collections::BTreeMap;
use std::time::Instant;

use nalgebra::Point3;
use retarget::{HandModel, QualityRecorder, QualityReport};
use serde::Serialize;
use station::{Station, StationConfig, StationInput};

use super::EvalError;
use crate::mcap_log::TrialReader;
use crate::resim::{LogInputs, drive_station, log_inputs};
use crate::samples::Samples;
use crate::station_driver::build_station;

/// The live path's figures.
#[derive(Debug, Clone, Serialize)]
pub struct LivePathReport {
    /// The metrics of the command in force after each distinct glove frame.
    #[serde(flatten)]
    pub quality: QualityReport,
    /// Distinct glove frames that had no command in force (before the station engaged).
    pub frames_without_command: usize,
    /// Distinct glove frames with a command in force that the metrics cannot measure (malformed
    /// keypoints, as the retargeter-alone figures' rejected frames; the station's gate rejects
    /// them too), or, scored against the hand as held, that have no such hand: left out of the
    /// metrics.
    pub frames_not_measured: usize,
    /// Hand commands computed from a new frame.
    pub fresh_commands: u64,
    /// Wall time of a station step that retargeted a new frame, microseconds: p50.
    pub step_us_p50: Option<f64>,
    /// Wall time of a station step that retargeted a new frame, microseconds: p99.
    pub step_us_p99: Option<f64>,
}

/// The hand each frame is scored against, by the frame's stamp (ns): for a synthetic user, the
/// hand as held (no glove misalignment, tip-marker offset or jitter), which a calibration
/// should make the robot copy. A frame without one is left out and counted as not measured.
pub type HandAsHeld = BTreeMap<i64, Vec<Point3<f64>>>;

/// Scores what the station commands at each distinct frame of a log.
struct LivePathScore<'a> {
    recorder: QualityRecorder,
    as_held: Option<&'a HandAsHeld>,
    previous: Option<Vec<Point3<f64>>>,
    without_command: usize,
    not_measured: usize,
    fresh: u64,
    step_us: Samples,
}

impl LivePathScore<'_> {
    fn after_step(&mut self, input: &StationInput, now_ns: i64, station: &Station, fresh: bool) {
        self.fresh += u64::from(fresh);
        let StationInput::Keypoints(frame) = input else {
            return;
        };
        if station::repeats(self.previous.as_deref(), &frame.points) {
            return;
        }
        self.previous = Some(frame.points.clone());
        match station.command_in_force() {
            Some(command) => {
                // A frame the recorder cannot measure (collapsed palm) is left out, as the
                // retargeter-alone figures leave it out, and counted.
                let t_s = now_ns as f64 * 1e-9;
                let human = match self.as_held {
                    Some(held) => held.get(&frame.source_ns),
                    None => Some(&frame.points),
                };
                let measured =
                    human.is_some_and(|h| self.recorder.push_at(t_s, h, &command.q).is_ok());
                self.not_measured += usize::from(!measured);
            }
            None => self.without_command += 1,
        }
    }
}

/// The live path of `reader`'s log through a station configured by `config`.
pub fn live_path(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
) -> Result<LivePathReport, EvalError> {
    live_path_against(reader, config, model, None)
}

/// The same, each frame scored against the hand as held in `as_held` when it is given.
pub fn live_path_against(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
    as_held: Option<&HandAsHeld>,
) -> Result<LivePathReport, EvalError> {
    let (mut station, log) = live_station(reader, config, model.clone())?;
    let mut score = LivePathScore {
        recorder: QualityRecorder::new(model, log.config.retarget.layout),
        as_held,
        previous: None,
        without_command: 0,
        not_measured: 0,
        fresh: 0,
        step_us: Samples::default(),
    };
    let mut started = Instant::now();
    drive_station(&mut station, log, |timed, outputs, station| {
        let fresh = outputs.fresh_frame_received_ns.is_some();
        if fresh {
            score.step_us.push(started.elapsed().as_secs_f64() * 1e6);
        }
        score.after_step(&timed.input, timed.now_ns, station, fresh);
        started = Instant::now();
    });
    Ok(LivePathReport {
        quality: score.recorder.report(),
        frames_without_command: score.without_command,
        frames_not_measured: score.not_measured,
        fresh_commands: score.fresh,
        step_us_p50: score.step_us.percentile(0.5),
        step_us_p99: score.step_us.percentile(0.99),
    })
}

/// The station of the live path and the log's inputs for it: built as `pomdar resim` builds
/// it (the log's layout, its calibration profile, engaging on the first fresh frame for a
/// glove recording).
fn live_station(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
) -> Result<(Station, LogInputs), EvalError> {
    let log = log_inputs(reader, config)?;
    let (station, _) = build_station(&log.config, model)?;
    Ok((station, log))
}

/// A glove frame's log time (ns) and the hand command in force after it (joint angles, the
/// model's order; `None` before the station engaged).
pub type CommandAtFrame = (i64, Option<Vec<f64>>);

/// The hand command in force (joint angles, the model's order) after each glove frame of
/// `reader`'s log that the live path scores, with the frame's log time (ns); a frame before the
/// station engaged has none.
pub fn commands_in_force(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
) -> Result<Vec<CommandAtFrame>, EvalError> {
    let (mut station, log) = live_station(reader, config, model)?;
    let mut commands = Vec::new();
    drive_station(&mut station, log, |timed, _, station| {
        if matches!(timed.input, StationInput::Keypoints(_)) {
            let q = station.command_in_force().map(|c| c.q.clone());
            commands.push((timed.now_ns, q));
        }
    });
    Ok(commands)
}
