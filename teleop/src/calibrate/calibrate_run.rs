//! `pomdar calibrate` run: the values checked, the fit's options, and the session or the fit
//! of a recorded one (`--from`) to its end or its error; a live or simulated session runs in
//! the calibration console ([`super::calibrate_console_run`]).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Duration;

use calibration::{CalibrationSettings, CaptureSchedule, SyntheticUser};
use retarget::human_hand::HandVariation;
use tokio::sync::watch;

use super::calibrate_console_run::{ConsoleSession, console_setup, run_in_console};
use super::calibrate_report::{print_recovery, print_session_report, simulated_source};
use super::calibrate_request::CalibrateRequest;
use super::calibrate_run_error::CalibrateRunError;
use super::calibration_console::ConsoleFront;
use super::calibration_script::load_calibration_script;
use super::ctrl_c::watch_ctrl_c;
use super::fit_session::{FitOptions, default_profile_path, fit_session};
use super::session_node::SessionOptions;
use super::simulated_user::{SimulatedMistakes, synthetic_user};
use crate::utc_date::{compact_utc, now_unix_s};

/// The session or the fit, to its end or its error. The process's Ctrl-C handler is
/// installed first: from then on Ctrl-C is seen through `ctrl_c` only.
pub fn calibrate_until_interrupted(args: CalibrateRequest) -> Result<(), CalibrateRunError> {
    if args.user.trim().is_empty() {
        return Err(CalibrateRunError::NoUser);
    }
    let ctrl_c = watch_ctrl_c()?;
    let mut fit = fit_options(&args)?;
    if let Some(session) = &args.from {
        return fit_recorded(fit, session, &ctrl_c);
    }
    let session_out = session_log_path(&args, &fit.out)?;
    check_glove_wait(args.glove_wait_s)?;
    let script = args
        .script
        .as_deref()
        .map(load_calibration_script)
        .transpose()?;
    let session = session_options(&args, &fit, &session_out);
    let user = simulated_user(&args)?;
    let pose_index = |name: &Option<String>| {
        name.as_deref()
            .and_then(|name| calibration::POSE_NAMES.iter().position(|p| *p == name))
    };
    let mistakes = SimulatedMistakes {
        shaking: pose_index(&args.simulate_bad_pose),
        wrong: pose_index(&args.simulate_wrong_pose),
    };
    if let Some(user) = &user {
        fit.source = Some(simulated_source(&args, user, &session_out));
    }
    let domain = args.domain_id.unwrap_or_else(crate::ros::default_domain_id);
    let setup = console_setup(&args, &fit, user.as_ref(), domain, &session_out);
    let mut front = ConsoleFront::open(args.plain, script, setup)?;
    let fit_in_console = FitOptions {
        verbose: false,
        ..fit.clone()
    };
    let run = ConsoleSession {
        session,
        user,
        mistakes,
        domain,
        fit_in_console,
        ctrl_c,
    };
    let report = run_in_console(&args, run, &mut front);
    // Leave the full screen before printing.
    drop(front);
    let report = report?;
    print_session_report(&report, &fit.out);
    if let Some(user) = &user {
        print_recovery(user, &fit, &report.fit.profile)?;
    }
    Ok(())
}

/// The fit's options from the flags: the station configuration, the calibration settings,
/// the profile's path, the user and the glove (the session is set later).
fn fit_options(args: &CalibrateRequest) -> Result<FitOptions, CalibrateRunError> {
    let station = crate::station_driver::setup::load_station_config(args.config.as_deref(), None)?;
    let settings = match &args.settings {
        Some(path) => CalibrationSettings::from_toml_str(&read_text(path, "calibration settings")?)
            .map_err(|source| CalibrateRunError::Settings {
                path: path.clone(),
                source,
            })?,
        None => CalibrationSettings::default(),
    };
    let settings = CalibrationSettings {
        model: args.model.unwrap_or(settings.model),
        ..settings
    };
    let out = match &args.out {
        Some(path) => path.clone(),
        None => default_profile_path(&args.user)?,
    };
    Ok(FitOptions {
        session: PathBuf::new(),
        user: args.user.clone(),
        glove: args.glove.clone().unwrap_or_else(|| {
            if args.simulate {
                "simulated"
            } else {
                "unspecified"
            }
            .to_string()
        }),
        out,
        station,
        settings,
        source: None,
        verbose: true,
    })
}

/// `--from`: fits a recorded session; a Ctrl-C (`ctrl_c` turning true) stops the fit and
/// leaves the profile unwritten.
fn fit_recorded(
    mut fit: FitOptions,
    session: &Path,
    ctrl_c: &watch::Receiver<bool>,
) -> Result<(), CalibrateRunError> {
    fit.session = session.to_path_buf();
    let profile = fit_session(&fit, &|| *ctrl_c.borrow())?;
    println!("wrote {} (user {})", fit.out.display(), profile.user);
    Ok(())
}

/// Where the session is recorded (`--session-out`, or beside the profile `out`); its
/// directory is created.
fn session_log_path(args: &CalibrateRequest, out: &Path) -> Result<PathBuf, CalibrateRunError> {
    let session_out = args
        .session_out
        .clone()
        .unwrap_or_else(|| session_path(out));
    if let Some(dir) = session_out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| CalibrateRunError::CreateDir {
            dir: dir.to_path_buf(),
            source,
        })?;
    }
    Ok(session_out)
}

fn check_glove_wait(glove_wait_s: f64) -> Result<(), CalibrateRunError> {
    if !(glove_wait_s > 0.0 && glove_wait_s <= 600.0) {
        return Err(CalibrateRunError::GloveWait {
            seconds: glove_wait_s,
        });
    }
    Ok(())
}

/// The session node's options: the station, the capture schedule and thresholds, the log.
fn session_options(
    args: &CalibrateRequest,
    fit: &FitOptions,
    session_out: &Path,
) -> SessionOptions {
    SessionOptions {
        station: fit.station.clone(),
        schedule: CaptureSchedule::default(),
        thresholds: fit.settings.capture,
        out: session_out.to_path_buf(),
        glove_wait: Duration::from_secs_f64(args.glove_wait_s),
        metadata: BTreeMap::from([
            ("user".to_string(), args.user.clone()),
            ("glove".to_string(), fit.glove.clone()),
        ]),
    }
}

/// `--simulate`: the synthetic user of the flags.
fn simulated_user(args: &CalibrateRequest) -> Result<Option<SyntheticUser>, CalibrateRunError> {
    if args.simulate {
        Ok(Some(synthetic_user(
            args.hand_scale,
            args.glove_rpy.unwrap_or([0.0; 3]),
            args.seed,
            args.simulate_hand.unwrap_or(HandVariation::NONE),
        )?))
    } else {
        Ok(None)
    }
}

fn read_text(path: &Path, what: &'static str) -> Result<String, CalibrateRunError> {
    std::fs::read_to_string(path).map_err(|source| CalibrateRunError::Read {
        what,
        path: path.to_path_buf(),
        source,
    })
}

fn session_path(out: &Path) -> PathBuf {
    let stem = out.file_stem().map_or_else(
        || "calibration".into(),
        |s| s.to_string_lossy().into_owned(),
    );
    out.with_file_name(format!("{stem}-session-{}.mcap", compact_utc(now_unix_s())))
}
