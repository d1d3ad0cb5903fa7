//! How far the hand was from its commands, per digit: at each measured state, the command in
//! force (the last one sent at or before it), the absolute difference per joint, and per digit
//! the mean over its joints, in degrees.

use retarget::{Finger, HandModel};
use serde::Serialize;

use crate::input::JointSample;
use crate::joints::JointOrder;
use crate::window::TrialWindow;

/// Per-digit tracking error over the trial.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct DigitTracking {
    /// Times of the measured states, seconds into the trial.
    pub t_s: Vec<f64>,
    /// Per digit (thumb … little), degrees, one per time (NaN for a digit without joints).
    pub error_deg: [Vec<f64>; 5],
    /// Per digit, the mean over the trial, degrees (None without samples).
    pub mean_deg: [Option<f64>; 5],
}

/// The tracking error of `states` against `commands` inside the trial; empty without states.
pub fn digit_tracking(
    commands: &[JointSample],
    states: &[JointSample],
    (model, prefix): (&HandModel, Option<&str>),
    window: &TrialWindow,
) -> Result<DigitTracking, String> {
    let digits = model.dof_digits();
    let mut tracking = DigitTracking::default();
    let (mut command_order, mut state_order): (Option<JointOrder>, Option<JointOrder>) =
        (None, None);
    let mut next = 0;
    for state in states.iter().filter(|s| window.contains(s.t_ns)) {
        while next < commands.len() && commands[next].t_ns <= state.t_ns {
            next += 1;
        }
        let Some(command) = next.checked_sub(1).map(|k| &commands[k]) else {
            continue;
        };
        let c = reordered((model, prefix), &mut command_order, command)?;
        let m = reordered((model, prefix), &mut state_order, state)?;
        tracking.t_s.push(window.secs(state.t_ns));
        for finger in Finger::ALL {
            let errors: Vec<f64> = (0..model.dof())
                .filter(|&i| digits[i] == Some(finger))
                .map(|i| (c[i] - m[i]).abs().to_degrees())
                .collect();
            let mean = errors.iter().sum::<f64>() / errors.len() as f64;
            tracking.error_deg[finger.index()].push(mean);
        }
    }
    for (k, series) in tracking.error_deg.iter().enumerate() {
        let finite: Vec<f64> = series.iter().copied().filter(|v| v.is_finite()).collect();
        tracking.mean_deg[k] =
            (!finite.is_empty()).then(|| finite.iter().sum::<f64>() / finite.len() as f64);
    }
    Ok(tracking)
}

/// `sample`'s values in the model's order, its order built or reused.
fn reordered(
    (model, prefix): (&HandModel, Option<&str>),
    order: &mut Option<JointOrder>,
    sample: &JointSample,
) -> Result<Vec<f64>, String> {
    if !order.as_ref().is_some_and(|o| o.fits(&sample.names)) {
        *order = Some(JointOrder::new(
            model,
            &sample.names,
            sample.position.len(),
            prefix,
        )?);
    }
    Ok(order
        .as_ref()
        .map(|o| o.reorder(&sample.position))
        .unwrap_or_default())
}
