//! `pomdar calibrate`: its flags and the three ways it runs — a live session with the glove
//! and the hand, a recorded session (`--from`), or a simulated user on loopback
//! (`--simulate`). Live and simulated sessions run in the calibration console
//! ([`crate::calibrate::calibration_console`]).

use std::path::PathBuf;
use std::process::ExitCode;

use calibration::CalibrationModel;
use clap::Args;
use retarget::human_hand::HandVariation;

use super::shared_args::GuardArgs;
use crate::calibrate::calibrate_request::CalibrateRequest;
use crate::calibrate::calibrate_run::calibrate_until_interrupted;
use crate::calibrate::simulated_user::parse_simulated_hand;
use crate::tui::terminal_shell::EXIT_INTERRUPTED;

/// Calibrate a user's glove to the robot hand: seven poses, a fitted scale and rotation.
///
/// Three ways to run it:
///   live       the calibration console: pose by pose, the hand is sent to the pose and
///              the console shows its instruction; the user copies it and settles
///              (1.5 s), 1 s of glove keypoints is captured and judged; every capture is
///              recorded to an MCAP with its quality, then the accepted ones are fitted.
///              Stop the station first: both would drive the hand.
///   --from     fit a recorded session again (e.g. with other --settings); sessions
///              recorded before captures were judged are read as before.
///   --simulate the whole session on loopback DDS with a synthetic user (hand size,
///              glove misalignment, 1.5 mm noise) who copies each pose; prints the
///              recovered and true parameters. --simulate-bad-pose POSE makes the user
///              shake through that pose's first capture (to see a retry);
///              --simulate-wrong-pose POSE makes the user stay in the previous pose
///              through it (to see the fit name it and a redo);
///              --simulate-hand gives the user a hand unlike the average in proportion.
///   --model    global (one scale and one rotation, the default) or per-digit (also a
///              length factor per digit, kept only where it lowers the objective).
///
/// The capture-quality meter: jitter (the largest keypoint RMS deviation in the palm
/// frame, mm), invalid frames (wrong count, non-finite, no palm frame), and frames
/// received vs expected from the glove's rate while the user settled.
///   bad   the fit would refuse it: fewer than 20 valid frames, over 20 % invalid, or
///         jitter over 12 mm (the [capture] settings); the pose must be captured again
///   poor  usable, but jitter over 85 % of the limit, an invalid frame, or under 80 % of
///         the expected frames
///   good  otherwise: accepted at once, the next pose follows
///
/// The console is full-screen when stdin and stdout are terminals (else, or with
/// --plain, lines on stderr). Keys: r captures the pose under review again, space or
/// Enter accepts a poor capture (a bad one can only be retried), q quits (a session in
/// progress is abandoned, its log kept), Ctrl-C interrupts. Without a terminal and
/// without --script nobody decides: poor captures are accepted, bad ones retried
/// automatically, at most 3 times per pose.
///
/// --script FILE plays timed actions instead of keys, one per line, optionally after a
/// time (seconds since the start, or +S after the previous line): accept, retry, quit,
/// and `wait STATE [TIMEOUT_S]` with STATE one of waiting_glove, settling, capturing,
/// review, fitting, complete, failed (default timeout 30 s; a wait that times out stops
/// the session with an error naming the line). When the script has ended, a complete or
/// failed session ends the console; a capture left under review is an error.
///
/// Once every pose has an accepted capture, the log is finished and fitted (Bayesian
/// optimisation, then two Nelder–Mead polishes) with its progress in the console; each
/// pose's error before and after is shown and printed on stdout, and the profile TOML is
/// written atomically (nothing is written if a capture is refused or the fit fails).
/// Each pose the fit could not match (a pinch gap over 40 mm or joints over 0.38 rad from
/// the pose after the fit: [fit_check] in the settings) is then named in words, worst
/// first; r captures that pose alone again (the session log is continued) and the fit
/// runs again and says how it changed; q keeps the fit. Without an operator the poses
/// are only named.
/// Load the profile with `pomdar station --profile FILE` or `calibration_profile =
/// "FILE"` in the station configuration.
///
/// Exit status: 0 when the profile is written, 130 after Ctrl-C (the session or the fit
/// stopped: no profile is written, an existing one is left as it was, the session log is
/// kept), 1 on an error.
///
/// Examples:
///   pomdar calibrate --user alice --glove "rokoko #12" --config launch_configs/station/eth_lab.toml
///   pomdar calibrate --from profiles/alice-session-20261121T103205Z.mcap --user alice
///   pomdar calibrate --simulate --hand-scale 1.15 --glove-rpy 10,-5,8 --seed 3 --user sim --out /tmp/sim.toml
///   pomdar calibrate --simulate --simulate-bad-pose pinch_ring --user sim --out /tmp/sim.toml
///   pomdar calibrate --simulate --simulate-wrong-pose pinch_ring --user sim --out /tmp/sim.toml
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct CalibrateArgs {
    /// The user's name: written into the profile, and names the default profile file
    /// (profiles/<NAME>.toml).
    #[arg(long, value_name = "NAME")]
    pub user: String,
    /// Fit a recorded session (an MCAP written by an earlier `pomdar calibrate`) instead of
    /// running one.
    #[arg(long, value_name = "SESSION.mcap", conflicts_with_all = ["simulate", "session_out", "domain_id"])]
    pub from: Option<PathBuf>,
    /// Run the whole session with a simulated glove on loopback DDS (no robot or glove needed).
    #[arg(long)]
    pub simulate: bool,
    /// --simulate: the user's hand size relative to the average hand (0.5–2).
    #[arg(long, value_name = "S", default_value_t = 1.0, requires = "simulate")]
    pub hand_scale: f64,
    /// --simulate: the glove's misalignment with the palm as roll,pitch,yaw about the palm
    /// axes, degrees, each within ±45 (default 0,0,0).
    #[arg(long, value_name = "R,P,Y", allow_hyphen_values = true, value_parser = parse_rpy, requires = "simulate")]
    pub glove_rpy: Option<[f64; 3]>,
    /// --simulate: seed of the simulated keypoint noise (1.5 mm per axis).
    #[arg(long, value_name = "N", default_value_t = 1, requires = "simulate")]
    pub seed: u64,
    /// --simulate: the simulated user shakes during the first capture of this pose (one of
    /// pinch_index, pinch_middle, pinch_ring, pinch_little, open, open_spread, closed), so it
    /// is judged bad and captured again.
    #[arg(long, value_name = "POSE", requires = "simulate", value_parser = parse_pose)]
    pub simulate_bad_pose: Option<String>,
    /// --simulate: the simulated user stays in the previous pose (at the first pose, the open
    /// hand) through the first capture of this pose: a steady capture of the wrong pose, which
    /// the fit cannot match, so the console names it after the fit and offers to capture it
    /// again.
    #[arg(long, value_name = "POSE", requires = "simulate", value_parser = parse_pose)]
    pub simulate_wrong_pose: Option<String>,
    /// --simulate: a hand unlike the average in proportion, not only in size:
    /// `thumb=F,index=F,middle=F,palm=F` (any of them, factors 0.7–1.3, e.g. thumb=1.12,index=0.95)
    /// or `random:SEED` (thumb ±15 %, index and middle ±10 %, palm breadth ±10 %, thumb base
    /// ±5 mm and ±5°, glove tip markers ±5 mm). No global transform calibrates such a hand
    /// exactly; the comparison with the truth then says so.
    #[arg(long, value_name = "SPEC", requires = "simulate", value_parser = parse_simulated_hand)]
    pub simulate_hand: Option<HandVariation>,
    /// Timed operator actions instead of keys (accept, retry, quit, wait STATE [TIMEOUT_S]);
    /// see `pomdar calibrate --help`.
    #[arg(long, value_name = "FILE", conflicts_with = "from")]
    pub script: Option<PathBuf>,
    /// The line console even on a terminal.
    #[arg(long, conflicts_with = "from")]
    pub plain: bool,
    /// The glove, free text for the profile (e.g. its model and serial; default
    /// "unspecified", or "simulated" with --simulate).
    #[arg(long, value_name = "TEXT")]
    pub glove: Option<String>,
    /// Where to write the profile (default profiles/<NAME>.toml). Written atomically; an
    /// existing profile is replaced only when the fit succeeds.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Where to record the session (default: beside the profile,
    /// <profile name>-session-<UTC time>.mcap). Not with --from.
    #[arg(long, value_name = "FILE.mcap")]
    pub session_out: Option<PathBuf>,
    /// The station configuration the profile is for: topics, keypoint layout, retargeting,
    /// network (default: the built-in ETH lab preset).
    #[arg(long, value_name = "STATION.toml")]
    pub config: Option<PathBuf>,
    /// Calibration settings (TOML: [bounds], [optimiser], [capture], [fit_check],
    /// pinch_weight_rad_per_m, model;
    /// default: 60 Bayesian-optimisation evaluations + 2 × 40 polish, seed 42).
    #[arg(long, value_name = "CALIBRATION.toml")]
    pub settings: Option<PathBuf>,
    /// The transform to fit: `global` (one scale and one rotation, the paper's) or `per-digit`
    /// (then a length factor per digit about its base, searched on the objective, 40
    /// evaluations more; kept only where it lowers it). Overrides the settings file's `model`.
    #[arg(long, value_name = "MODEL", value_parser = parse_model)]
    pub model: Option<CalibrationModel>,
    /// ROS domain id of the session (live: default the config's, else ROS_DOMAIN_ID, else 0;
    /// --simulate: default one of 150–229 no other run on this machine holds, on loopback only).
    #[arg(long)]
    pub domain_id: Option<u16>,
    /// The RTPS datagram guard.
    #[command(flatten)]
    pub guard: GuardArgs,
    /// Live session: how long to wait for the glove's first keypoints, seconds.
    #[arg(long, value_name = "S", default_value_t = 10.0)]
    pub glove_wait_s: f64,
}

fn parse_rpy(text: &str) -> Result<[f64; 3], String> {
    let values: Vec<f64> = text
        .split(',')
        .map(|v| v.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("'{text}': {e} (expected R,P,Y in degrees, e.g. 10,-5,3)"))?;
    <[f64; 3]>::try_from(values)
        .map_err(|_| format!("'{text}': expected three angles R,P,Y in degrees, e.g. 10,-5,3"))
}

fn parse_model(text: &str) -> Result<CalibrationModel, String> {
    match text {
        "global" => Ok(CalibrationModel::Global),
        "per-digit" | "per_digit" => Ok(CalibrationModel::PerDigit),
        other => Err(format!(
            "unknown model '{other}' (known: global, per-digit)"
        )),
    }
}

fn parse_pose(text: &str) -> Result<String, String> {
    if calibration::POSE_NAMES.contains(&text) {
        Ok(text.to_string())
    } else {
        Err(format!(
            "unknown pose '{text}' (known: {})",
            calibration::POSE_NAMES.join(", ")
        ))
    }
}

impl CalibrateArgs {
    /// The calibration these flags ask for.
    fn request(self) -> CalibrateRequest {
        CalibrateRequest {
            user: self.user,
            from: self.from,
            simulate: self.simulate,
            hand_scale: self.hand_scale,
            glove_rpy: self.glove_rpy,
            seed: self.seed,
            simulate_bad_pose: self.simulate_bad_pose,
            simulate_wrong_pose: self.simulate_wrong_pose,
            simulate_hand: self.simulate_hand,
            script: self.script,
            plain: self.plain,
            glove: self.glove,
            out: self.out,
            session_out: self.session_out,
            config: self.config,
            settings: self.settings,
            model: self.model,
            domain_id: self.domain_id,
            glove_wait_s: self.glove_wait_s,
        }
    }
}

/// `pomdar calibrate`. Exit status 0 when the profile is written, 130 after Ctrl-C (or the
/// shutdown) stopped the session or its fit, saying so on stderr (no profile is written then),
/// 1 on an error.
pub fn calibrate(args: CalibrateArgs) -> anyhow::Result<ExitCode> {
    // The session drives the robot hand: crafted DATA_FRAG datagrams must not exhaust its memory.
    args.guard.apply();
    match calibrate_until_interrupted(args.request()) {
        Err(e) if e.is_interrupted() => {
            eprintln!("{e}");
            Ok(ExitCode::from(EXIT_INTERRUPTED))
        }
        result => Ok(result.map(|()| ExitCode::SUCCESS)?),
    }
}
