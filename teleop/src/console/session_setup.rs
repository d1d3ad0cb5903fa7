//! A trial console session set up and run: the options checked against the catalog and the
//! station's configuration, the session directory opened (or resumed), the live view, the
//! station (and the simulation) started, then the console's loop until it quits.

use std::path::Path;

use retarget::HandModel;
use scoring::TaskSpec;
use station::StationConfig;

use super::health::{Health, StartLimits};
use super::in_process_station::spawn_station;
use super::manifest::MANIFEST_FILE;
use super::message_log::MessageLog;
use super::operator_side::OperatorSide;
use super::runner::{ConsoleEnd, SessionEnd, TrialConsole};
use super::session_check::check_options;
use super::session_dir::{SessionPlan, open_session, session_dir};
use super::session_error::SessionError;
use super::session_info::session_info;
use super::session_options::SessionOptions;
use super::session_state::Session;
use super::trial_flow::TrialFlow;
use super::trial_script::load_script;
use crate::clock::StationClock;
use crate::ros::{NetworkConfig, default_domain_id};
use crate::score::score_inputs::ScoringInputs;
use crate::stand_ins::glove_script_file::load_glove_script;
use crate::station_node::recorder::config_digest;
use crate::tui::terminal_shell::{Wakeups, run_turns};
use crate::view::live_view::start_live_view;

/// One task's console session; `study` lines are added to the setting shown (the study's
/// plan and where the participant is in it).
pub async fn run_session(
    args: &SessionOptions,
    study: Vec<(String, String)>,
) -> Result<SessionEnd, SessionError> {
    check_options(args)?;
    let inputs = args.scoring.load()?;
    let task = task_of(args, &inputs)?;
    let config = station_config_for(args, &task)?;
    let model = HandModel::orca_v1_right();
    // The profile and the embodiment are checked before any log or node exists.
    crate::station_driver::setup::build_station(&config, model.clone())?;
    let script = args
        .console
        .script
        .as_deref()
        .map(load_script)
        .transpose()?;
    let glove_script = args
        .simulation
        .as_ref()
        .and_then(|s| s.glove_script.as_deref())
        .map(load_glove_script)
        .transpose()?;

    let plan = session_plan(args, &task, &config);
    let dir = session_dir(&args.out, &plan);
    let score = |path: &Path| inputs.score_file(path).map_err(|e| e.to_string());
    let (manifest, opened) = open_session(&dir, &plan, &score)?;
    let limits = StartLimits {
        min_glove_rate_hz: args.console.min_glove_rate,
        max_input_age_ms: args.console.max_input_age,
        max_status_age_ms: StartLimits::default().max_status_age_ms,
        drives_robot: !args.human(),
    };
    let mut flow = TrialFlow::new(manifest, task.correctness, args.console.countdown, limits);
    for line in opened {
        flow.say(line);
    }
    let mut info = session_info(args, &plan, &config, &dir, &inputs, task.clone(), limits)?;
    info.setup.splice(0..0, study);

    // The live view, then the station (and, with --simulate, the glove and the robot).
    let view = start_live_view(args.view).await?;
    if let Some(view) = &view {
        flow.say(view.announcement());
    }
    let clock = StationClock::new();
    let tap = view.as_ref().map(|v| v.tap.clone());
    let station = spawn_station(args, (&config, &task), &model, clock, tap, glove_script)?;
    let operator = OperatorSide::open(args.console.plain, script)?;
    let mut console = TrialConsole {
        operator,
        wakeups: Wakeups::with_signals()?,
        session: Session {
            flow,
            health: Health::default(),
            info,
            inputs,
            manifest_path: dir.join(MANIFEST_FILE),
            message_log: MessageLog::new(&dir),
            dir,
            report_written: false,
            config: config.clone(),
        },
        station,
        clock,
        end: ConsoleEnd::default(),
    };
    run_turns(&mut console).await?;
    let end = console.finish().await;
    if let Some(view) = view {
        view.stop().await;
    }
    end
}

/// The `--task` in the catalog.
fn task_of(args: &SessionOptions, inputs: &ScoringInputs) -> Result<TaskSpec, SessionError> {
    inputs
        .catalog
        .get(&args.task)
        .cloned()
        .ok_or_else(|| SessionError::UnknownTask {
            task: args.task.clone(),
            origin: inputs.catalog.origin.to_string(),
            ids: inputs.catalog.ids().to_string(),
        })
}

/// The station's configuration for this session: the file (or the preset) with the profile,
/// the network (loopback with `--simulate`), the embodiment and the task's arm constraint;
/// engaged by the operator only.
fn station_config_for(
    args: &SessionOptions,
    task: &TaskSpec,
) -> Result<StationConfig, SessionError> {
    let mut config = crate::station_driver::setup::load_station_config(
        args.config.as_deref(),
        args.profile.as_deref(),
    )?;
    config.network = args.network.apply(&config.network);
    if args.simulation.is_some() {
        config.network = NetworkConfig {
            domain_id: Some(args.network.domain_id.unwrap_or_else(default_domain_id)),
            interfaces: vec![std::net::IpAddr::from([127, 0, 0, 1])],
        };
    }
    config.retarget.embodiment.clone_from(&args.embodiment);
    if args.human() {
        // No robot: nothing is retargeted, so no user's calibration applies.
        config.calibration_profile = None;
    }
    crate::station_driver::constrain_for_task(&mut config, task);
    crate::station_driver::set_engage(&mut config, crate::station_driver::Engage::ByOperator);
    config.validate()?;
    Ok(config)
}

/// What the session is: its task, embodiment, people, plan and the files it depends on.
fn session_plan(args: &SessionOptions, task: &TaskSpec, config: &StationConfig) -> SessionPlan {
    let (practice, trials) = args.plan_counts();
    SessionPlan {
        task: task.id.clone(),
        embodiment: args.embodiment.clone(),
        user: args.user.clone(),
        operator: args.operator.clone(),
        practice,
        trials,
        calibration_profile: config
            .calibration_profile
            .as_ref()
            .map(|p| p.display().to_string()),
        config_digest: config_digest(config),
        baseline: args
            .scoring
            .baseline
            .as_ref()
            .map(|p| p.display().to_string()),
    }
}
