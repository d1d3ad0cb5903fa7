//! A live or simulated calibration session run in the calibration console: the console's
//! setup pane, the simulated user's glove on loopback beside the session, the session node
//! until the profile is written or the session ends otherwise.

use std::path::Path;

use calibration::SyntheticUser;
use retarget::HandModel;
use tokio::sync::watch;

use super::calibrate_report::proportions;
use super::calibrate_request::CalibrateRequest;
use super::calibrate_run_error::CalibrateRunError;
use super::calibration_console::ConsoleFront;
use super::fit_session::FitOptions;
use super::session_node::{SessionOptions, SessionReport, run_session};
use super::simulated_user::{
    SIMULATED_NOISE_M, SimulatedMistakes, loopback, publish_simulated_user,
};
use crate::clock::StationClock;

/// The console's setup pane; says on stderr which kind of session this is.
pub(super) fn console_setup(
    args: &CalibrateRequest,
    fit: &FitOptions,
    user: Option<&SyntheticUser>,
    domain: u16,
    session_out: &Path,
) -> Vec<(String, String)> {
    let mut setup = vec![
        ("user".to_string(), args.user.clone()),
        ("glove".to_string(), fit.glove.clone()),
        ("profile".to_string(), fit.out.display().to_string()),
        ("log".to_string(), session_out.display().to_string()),
    ];
    match user {
        Some(user) => {
            let intro = format!(
                "simulated user: hand scale {}{}, glove roll/pitch/yaw {:?}°, noise {} m, seed {}{}{}; loopback DDS, domain {domain}",
                user.hand_scale,
                proportions(user),
                args.glove_rpy.unwrap_or([0.0; 3]),
                SIMULATED_NOISE_M,
                user.seed,
                args.simulate_bad_pose
                    .as_deref()
                    .map(|p| format!(", shaking at the first capture of {p}"))
                    .unwrap_or_default(),
                args.simulate_wrong_pose
                    .as_deref()
                    .map(|p| format!(", holding the previous pose at the first capture of {p}"))
                    .unwrap_or_default()
            );
            eprintln!("{intro}");
            setup.push(("mode".to_string(), format!("simulated (domain {domain})")));
        }
        None => {
            eprintln!(
                "calibration session: stop the station first (both would drive the hand); recording to {}",
                session_out.display()
            );
            setup.push(("mode".to_string(), "live".to_string()));
        }
    }
    setup
}

/// A session to run in the console: live, or with a simulated user on loopback.
pub(super) struct ConsoleSession {
    /// The session node's options.
    pub(super) session: SessionOptions,
    /// `--simulate`: the synthetic user.
    pub(super) user: Option<SyntheticUser>,
    /// `--simulate-bad-pose`, `--simulate-wrong-pose`: what the simulated user gets wrong.
    pub(super) mistakes: SimulatedMistakes,
    /// The simulated session's loopback domain.
    pub(super) domain: u16,
    /// The fit, quiet (its progress shows in the console).
    pub(super) fit_in_console: FitOptions,
    /// Turns true on Ctrl-C.
    pub(super) ctrl_c: watch::Receiver<bool>,
}

/// Runs the session (and the simulated user's glove) until the profile is written or the
/// session ends otherwise.
pub(super) fn run_in_console(
    args: &CalibrateRequest,
    run: ConsoleSession,
    front: &mut ConsoleFront,
) -> Result<SessionReport, CalibrateRunError> {
    let ConsoleSession {
        session,
        user,
        mistakes,
        domain,
        fit_in_console,
        ctrl_c: shutdown,
    } = run;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(CalibrateRunError::Runtime)?;
    runtime.block_on(async {
        let clock = StationClock::new();
        let model = HandModel::orca_v1_right();
        match user {
            Some(user) => {
                let mut session = session;
                let network = loopback(domain);
                session.station.network = network.clone();
                let (cue_tx, cue_rx) = watch::channel(None);
                let (stop_tx, stop_rx) = watch::channel(false);
                let glove = tokio::spawn(publish_simulated_user(
                    user,
                    mistakes,
                    session.station.clone(),
                    network,
                    clock,
                    cue_rx,
                    stop_rx,
                ));
                let report = run_session(
                    session,
                    &model,
                    clock,
                    Some(cue_tx),
                    front,
                    fit_in_console,
                    shutdown,
                )
                .await;
                stop_tx.send(true).ok();
                glove.await.map_err(CalibrateRunError::GloveTask)??;
                Ok(report?)
            }
            None => {
                let mut session = session;
                if args.domain_id.is_some() {
                    session.station.network.domain_id = args.domain_id;
                }
                Ok(run_session(
                    session,
                    &model,
                    clock,
                    None,
                    front,
                    fit_in_console,
                    shutdown,
                )
                .await?)
            }
        }
    })
}
