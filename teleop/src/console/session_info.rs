//! The setting the trial console shows all session long: who, the embodiment, the profile,
//! the baseline, the plan, the session directory and the domain; the task and the start
//! limits.

use std::path::Path;

use scoring::TaskSpec;
use station::StationConfig;

use super::health::StartLimits;
use super::session_dir::SessionPlan;
use super::session_error::SessionError;
use super::session_options::SessionOptions;
use super::view::SessionInfo;
use crate::score::score_inputs::ScoringInputs;

/// The setting the console shows all session long: the task, the setup, the baseline and
/// the start limits.
pub(super) fn session_info(
    args: &SessionOptions,
    plan: &SessionPlan,
    config: &StationConfig,
    dir: &Path,
    inputs: &ScoringInputs,
    task: TaskSpec,
    limits: StartLimits,
) -> Result<SessionInfo, SessionError> {
    let baseline_s = inputs
        .baseline
        .as_ref()
        .and_then(|b| b.get(&task.id))
        .map(|b| b.mean_s);
    let (who, embodiment, profile) = if args.human() {
        (
            "participant",
            "human (study: no robot, the glove is recorded)".to_string(),
            "none (no retargeting)".to_string(),
        )
    } else {
        (
            "user",
            args.embodiment.clone(),
            plan.calibration_profile
                .clone()
                .unwrap_or_else(|| "none (scale 1, no rotation)".into()),
        )
    };
    let simulated = match (args.simulation.is_some(), args.human()) {
        (false, _) => "",
        (true, true) => " (simulated glove)",
        (true, false) => " (simulated glove and robot)",
    };
    Ok(SessionInfo {
        setup: vec![
            (who.into(), args.user.clone()),
            ("operator".into(), args.operator.clone()),
            ("embodiment".into(), embodiment),
            ("profile".into(), profile),
            (
                "baseline".into(),
                match baseline_s {
                    Some(b) => format!("{b:.1} s ({})", plan.baseline.clone().unwrap_or_default()),
                    None => "none for this task: correctness only".into(),
                },
            ),
            (
                "plan".into(),
                format!("{} practice + {} recorded", plan.practice, plan.trials),
            ),
            ("session".into(), dir.display().to_string()),
            (
                "domain".into(),
                format!(
                    "{}{simulated}",
                    crate::ros::domain_id(config.network.domain_id)?
                ),
            ),
        ],
        task,
        baseline_s,
        limits,
        hand_convention: (!config.policy_output.topic.is_empty())
            .then(|| config.policy_output.verification()),
    })
}
