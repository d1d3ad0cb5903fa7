//! `pomdar eval --outlier-study`: what a camera tracker's one-frame outliers do to the robot,
//! with the frame gate's outlier check and without it, on a real recording.
//!
//! The recording's distinct frames get [`Variant::Outliers`] (one point of a digit leaping
//! 3–6 cm for one frame, 20 times; every republished copy of such a frame carries it, as a
//! tracker's would). The station is re-simulated as the live path drives it four times:
//! clean and with outliers, each with the outlier check (the configuration's
//! `gate.outlier_jump_m`, or 2 cm where it is off) and without it. Reported:
//! - **toward the outliers**: how far the command in force with outliers went beyond the clean
//!   run's path on the side each outlier pulls each joint (the side the unchecked command
//!   moved to), at an outlier frame and the two after it: per joint, the distance beyond the
//!   span of the clean commands at that frame and the one before (a command held one frame
//!   stays inside it); the largest;
//! - **pinch closure delay**: per sustained human pinch of the clean recording
//!   ([`retarget::quality::sustained_pinch_runs`]), the frames from its start until the robot
//!   closes it (thumb-tip to fingertip under 15 mm), with the check against without it;
//! - how many frames the check caught (a point put back) on the clean recording: its false
//!   alarms on real motion, each of which makes that point one frame late.

use retarget::quality::{PINCH_CLOSED_M, human_pinch, sustained_pinch_runs};
use retarget::{Finger, HandModel, KeypointLayout};
use serde::Serialize;
use station::{StationConfig, StationInput};

use super::EvalError;
use super::variants::{TimedFrame, Variant};
use crate::mcap_log::TrialReader;
use crate::resim::{LogInputs, drive_station, log_inputs};
use crate::station_driver::setup::build_station;

/// Outliers injected, and their size (metres).
const OUTLIERS: usize = 20;
const LEAP_M: (f64, f64) = (0.03, 0.06);
/// The check's setting when the configuration has it off, metres.
const STUDY_JUMP_M: f64 = 0.02;
/// Frames after an outlier frame still compared.
const AFTER_FRAMES: usize = 2;

/// Per distinct frame, the command in force once it was taken (None before the first).
type Commands = Vec<Option<Vec<f64>>>;

/// The study's figures.
#[derive(Debug, Clone, Serialize)]
pub struct OutlierStudy {
    /// Outlier frames injected.
    pub outliers: usize,
    /// Largest move of any joint toward the outliers with the check: how far the command went
    /// beyond the clean run's path (the span of its commands at that frame and the one before)
    /// on the side the outlier pulls the joint, at an outlier frame and the two after it,
    /// radians.
    pub toward_outliers_rad: f64,
    /// The same without the check, radians.
    pub toward_outliers_unchecked_rad: f64,
    /// Sustained human pinches the robot closed without the check (those compared).
    pub pinches_compared: usize,
    /// Largest extra delay of a pinch's closure with the check, frames (0: none).
    pub closure_delay_max_frames: i64,
    /// Frames of the clean recording in which the check put a point back.
    pub clean_frames_caught: usize,
    /// Outlier frames the check caught (the leapt point put back).
    pub outlier_frames_caught: usize,
}

/// The study on `reader`'s recording, outliers drawn from `seed`.
pub fn outlier_study(
    reader: &TrialReader,
    config: &StationConfig,
    model: &HandModel,
    seed: u64,
) -> Result<OutlierStudy, EvalError> {
    let clean = log_inputs(reader, config)?;
    let layout = clean.config.retarget.layout;
    let frames = distinct_input_frames(&clean);
    let variant = Variant::Outliers {
        count: OUTLIERS,
        min_m: LEAP_M.0,
        max_m: LEAP_M.1,
        seed,
    };
    let injected_frames = variant.apply(&frames, layout);
    let outlier_at: Vec<usize> = (0..frames.len())
        .filter(|&k| frames[k].points != injected_frames[k].points)
        .collect();
    let injected = with_frames(&clean, &frames, &injected_frames);
    let run = |log: &LogInputs, checked: bool| commands_in_force(log, model, checked);
    let (clean_on, clean_caught) = run(&clean, true)?;
    let (clean_off, _) = run(&clean, false)?;
    let (injected_on, injected_caught) = run(&injected, true)?;
    let (injected_off, _) = run(&injected, false)?;
    // Which way each outlier pulls each joint: the unchecked run's command against the clean.
    let pulls: Vec<Vec<f64>> = outlier_at
        .iter()
        .map(|&k| match (&injected_off[k], &clean_off[k]) {
            (Some(a), Some(b)) => a.iter().zip(b).map(|(x, y)| x - y).collect(),
            _ => Vec::new(),
        })
        .collect();
    let pinches = closure_delays(model, layout, &frames, &clean_on, &clean_off)?;
    Ok(OutlierStudy {
        outliers: outlier_at.len(),
        toward_outliers_rad: toward_outliers(&outlier_at, &pulls, &injected_on, &clean_on),
        toward_outliers_unchecked_rad: toward_outliers(
            &outlier_at,
            &pulls,
            &injected_off,
            &clean_off,
        ),
        pinches_compared: pinches.len(),
        closure_delay_max_frames: pinches.into_iter().max().unwrap_or(0),
        clean_frames_caught: clean_caught.len(),
        outlier_frames_caught: outlier_at
            .iter()
            .filter(|k| injected_caught.contains(k))
            .count(),
    })
}

/// The distinct keypoint frames of a log's inputs, with their first receive time.
fn distinct_input_frames(log: &LogInputs) -> Vec<TimedFrame> {
    let mut frames: Vec<TimedFrame> = Vec::new();
    for timed in &log.inputs {
        if let StationInput::Keypoints(frame) = &timed.input
            && frames.last().is_none_or(|last| last.points != frame.points)
        {
            frames.push(TimedFrame {
                t_ns: timed.now_ns,
                points: frame.points.clone(),
            });
        }
    }
    frames
}

/// `log` with every copy of distinct frame `k` carrying `replaced[k]`'s points.
fn with_frames(log: &LogInputs, frames: &[TimedFrame], replaced: &[TimedFrame]) -> LogInputs {
    let mut out = log.clone();
    let mut k: Option<usize> = None;
    for timed in &mut out.inputs {
        if let StationInput::Keypoints(frame) = &mut timed.input {
            let next = k.map_or(0, |k| k + 1);
            if next < frames.len() && frames[next].points == frame.points {
                k = Some(next);
            }
            if let Some(k) = k {
                frame.points.clone_from(&replaced[k].points);
            }
        }
    }
    out
}

/// The command in force when each distinct frame has been taken (None before the first), and
/// the distinct frames the outlier check caught, with the check on or off.
fn commands_in_force(
    log: &LogInputs,
    model: &HandModel,
    checked: bool,
) -> Result<(Commands, Vec<usize>), EvalError> {
    let mut log = log.clone();
    let gate = &mut log.config.gate;
    gate.outlier_jump_m = match (checked, gate.outlier_jump_m) {
        (false, _) => 0.0,
        (true, off) if off <= 0.0 => STUDY_JUMP_M,
        (true, on) => on,
    };
    let (mut station, _) = build_station(&log.config, model.clone())?;
    let mut commands: Commands = Vec::new();
    let mut held = Vec::new();
    let mut previous: Option<Vec<nalgebra::Point3<f64>>> = None;
    let mut outliers = 0;
    drive_station(&mut station, log, |timed, _, station| {
        let command = station.command_in_force().map(|c| c.q.clone());
        match &timed.input {
            StationInput::Keypoints(frame) if previous.as_ref() != Some(&frame.points) => {
                previous = Some(frame.points.clone());
                commands.push(command);
                let now = station_outliers(station);
                if now > outliers {
                    held.push(commands.len() - 1);
                }
                outliers = now;
            }
            // A later step (a tick, a republished copy) updates the frame's command in force.
            _ => {
                if let Some(last) = commands.last_mut() {
                    *last = command;
                }
            }
        }
    });
    Ok((commands, held))
}

/// Frames the station's outlier check has caught so far.
fn station_outliers(station: &station::Station) -> u64 {
    station.counters().frames_repaired
}

/// How far `commands` moved toward the outliers, at each outlier frame and the
/// [`AFTER_FRAMES`] after it: per joint, the distance beyond the span between the `reference`
/// run's command at that frame and at the frame before, on the side the outlier pulls that
/// joint (`pulls`, per outlier: unchecked minus clean command at its frame). A command held
/// one frame stays inside the span; one pulled toward an outlier leaves it on the pull's
/// side. The largest, radians.
fn toward_outliers(
    outlier_at: &[usize],
    pulls: &[Vec<f64>],
    commands: &[Option<Vec<f64>>],
    reference: &[Option<Vec<f64>>],
) -> f64 {
    let mut largest: f64 = 0.0;
    for (&k, pull) in outlier_at.iter().zip(pulls) {
        for i in k.max(1)..=(k + AFTER_FRAMES).min(commands.len().saturating_sub(1)) {
            let (Some(Some(q)), Some(Some(before)), Some(Some(at))) =
                (commands.get(i), reference.get(i - 1), reference.get(i))
            else {
                continue;
            };
            for (((q, a), b), pull) in q.iter().zip(before).zip(at).zip(pull) {
                let beyond = if *pull > 0.0 {
                    q - a.max(*b)
                } else {
                    a.min(*b) - q
                };
                largest = largest.max(beyond);
            }
        }
    }
    largest
}

/// Per sustained human pinch the robot closes without the check, the frames the check adds
/// before it closes (0 or more; negative: earlier).
fn closure_delays(
    model: &HandModel,
    layout: KeypointLayout,
    frames: &[TimedFrame],
    checked: &[Option<Vec<f64>>],
    unchecked: &[Option<Vec<f64>>],
) -> Result<Vec<i64>, EvalError> {
    let fingers: Vec<Option<Finger>> = frames
        .iter()
        .map(|f| human_pinch(layout, &f.points).map(|(finger, _)| finger))
        .collect();
    let times: Vec<f64> = frames.iter().map(|f| f.t_ns as f64 * 1e-9).collect();
    let mut delays = Vec::new();
    for run in sustained_pinch_runs(&fingers, Some(&times)) {
        let closes_at = |commands: &[Option<Vec<f64>>]| -> Result<Option<usize>, EvalError> {
            for i in run.frames.clone() {
                if let Some(Some(q)) = commands.get(i)
                    && robot_gap_m(model, q, run.finger)? < PINCH_CLOSED_M
                {
                    return Ok(Some(i));
                }
            }
            Ok(None)
        };
        if let Some(unchecked_at) = closes_at(unchecked)? {
            let checked_at = closes_at(checked)?.unwrap_or(run.frames.end);
            delays.push(checked_at as i64 - unchecked_at as i64);
        }
    }
    Ok(delays)
}

/// The robot's thumb-tip to `finger`-tip distance for command `q`, metres.
fn robot_gap_m(model: &HandModel, q: &[f64], finger: Finger) -> Result<f64, EvalError> {
    let fk = model
        .forward_new(q)
        .map_err(|source| EvalError::Retargeter { source })?;
    let tip = |f: Finger| fk.position(model.frames().tip(f));
    Ok((tip(finger) - tip(Finger::Thumb)).norm())
}
