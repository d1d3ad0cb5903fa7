//! `pomdar`'s command line: its subcommands with their help, and the process's exit status.
//! It lives in the library, and `main.rs` only calls [`main`]: the binary then compiles in a
//! second, where it took about 20 s of a cold release build's serial tail (the generic code
//! it instantiated).

use std::process::ExitCode;

use crate::command;
use clap::{Parser, Subcommand};

/// The POMDAR station: teleoperate a robot hand through the POMDAR dexterity benchmark and
/// score the trials.
///
/// Today: the ROS 2 station (glove keypoints in, ORCA joint targets and a constrained Franka
/// pose out), trial recording to MCAP, re-simulation, recovery and replay, a simulated
/// glove, mock robot nodes, the all-in-one demo, hand model inspection, the per-user glove
/// calibration, scoring trial logs against a human baseline, the Rokoko Studio and Apple
/// Vision Pro ingresses, a DDS discovery probe and the robot PC's command relay for
/// multi-host set-ups (docs/DEPLOYMENT.md), a
/// retargeting quality report for a recording, commanded vs measured joint angles of a trial,
/// and the operator console for timed trials.
#[derive(Debug, Parser)]
#[command(name = "pomdar", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// The whole pipeline on loopback DDS: simulated glove → station → mock hand and arm.
    ///
    /// Runs in one process on its own ROS domain id (never the lab's 0 by default), prints a
    /// status line every second and a summary at the end: input and output rates, end-to-end
    /// latency (glove publish → joint target received) p50/p99, solver time, rejected frames,
    /// fingertip error.
    ///
    /// Examples:
    ///   pomdar demo
    ///   pomdar demo --duration 60 --motion pinches
    ///   pomdar demo --duration 5 --json
    ///   pomdar demo --out logs/        # also record the run to logs/demo-<time>.mcap
    #[command(verbatim_doc_comment)]
    Demo(command::demo::DemoArgs),
    /// Run the station node (no simulated parts) until Ctrl-C.
    ///
    /// Subscribes to the glove keypoints and wrist pose, publishes hand joint targets, the
    /// lab's /hand/policy_output, the arm target and a JSON status, as the config file says
    /// (launch_configs/station/*.toml). --engage engages once glove input is fresh
    /// (`pomdar trial`, the operator console, runs its own station and engages on the
    /// operator's key); --record logs the run (inputs, outputs, status, events) to an MCAP
    /// file; --profile applies a user's calibration (from `pomdar calibrate`).
    ///
    /// Example:
    ///   pomdar station --config launch_configs/station/eth_lab.toml --engage --record run.mcap --profile profiles/alice.toml
    #[command(verbatim_doc_comment)]
    Station(command::station::StationArgs),
    /// Publish simulated glove keypoints and wrist pose (the lab's topics) until Ctrl-C.
    SimGlove(command::sim_glove::SimGloveArgs),
    /// A mock ORCA hand: follows joint targets with a first-order lag, publishes its state
    /// (and with --policy-config, a policy output topic through the inverse of its table).
    MockHand(command::mock_hand::MockHandArgs),
    /// A mock Franka: follows pose commands at limited speed, publishes its pose.
    MockFranka(command::mock_franka::MockFrankaArgs),
    /// The simulated robot in a MuJoCo task scene (needs the `physics` build).
    ///
    /// The ORCA hand and the arm's mount in the task's scene, stepped in real time, on the real
    /// robot's topics: follows hand and arm targets, publishes the hand's measured joint states,
    /// the arm's pose, the task object's pose and the task's progress as the physics measures
    /// it (/pomdar/sim/progress, JSON). The scene is the project's scaffold for --task or a
    /// lab's own MJCF (--scene). Set-up: `bash sim/setup_mujoco.sh`, then build with
    /// `--features physics` (README, "The simulated benchmark").
    ///
    /// Example:
    ///   pomdar sim --task G4 --config launch_configs/station/eth_lab.toml
    ///   pomdar sim --task G4 --write-scene g4.xml
    #[command(verbatim_doc_comment)]
    Sim(command::sim::SimArgs),
    /// The benchmark without a teleoperator: every embodiment scored in simulation (needs the
    /// `physics` build).
    ///
    /// Per embodiment and task, programmed practice: a seeded cross-entropy search over the
    /// task's family of glove strategies (its script with the start placement, the approach,
    /// the reach, which digits close and how far, and the timing varied), each practice trial
    /// a lock-step run through the station core (retargeting to the embodiment, its other
    /// joints locked) into the physics, scored the POMDAR way. Then recorded runs of the best
    /// strategy at the glove's noise with moved starts, timed by the physics' completion
    /// event. Writes the report `pomdar score` writes, the strategies chosen and the paper's
    /// findings checked; shows a line per task and embodiment; same seed, same report.
    ///
    /// Examples:
    ///   pomdar sim-bench --embodiment all --out reports/sim_bench/
    ///   pomdar sim-bench --embodiment orca_2,orca_full --tasks G4,H5,C1 --budget 12 --out quick/
    ///   pomdar sim-bench --shard 2/4 --out shard2/   (then: pomdar sim-bench --merge shard*/ --out all/)
    #[command(verbatim_doc_comment)]
    SimBench(command::sim_bench::SimBenchArgs),
    /// Re-simulate a recorded log's glove input through the station, deterministically.
    ///
    /// The station's processing is fed from the log with the log's clock, in process; the
    /// outputs (joint targets, policy output, arm targets) are written to a new MCAP. Use it to
    /// re-retarget recorded glove data with a new configuration. A log the station recorded
    /// carries its timer ticks and the operator's engage/disengage (/pomdar/station_control):
    /// with the run's configuration it reproduces the run's commands byte for byte. A plain
    /// glove recording gets ticks on the log's clock and engages on its first fresh frame.
    /// Accepts the lab's 22- and 21-point layouts. Same log + same config = byte-identical
    /// output.
    ///
    /// Example:
    ///   pomdar resim trial.mcap --config launch_configs/station/eth_lab.toml --out resim.mcap --stats-json stats.json
    #[command(verbatim_doc_comment)]
    Resim(command::resim::ResimArgs),
    /// Retargeting quality on recordings' glove keypoints: how closely the hand follows.
    ///
    /// Several recordings (files, or directories searched for .mcap files: an evaluation
    /// set) give a report per recording, then a summary table (live path and retargeter alone,
    /// one row per recording, the worst of each column).
    ///
    /// Each distinct keypoint frame (repeats of the ingress's re-publishing are dropped) goes
    /// through the station's retargeter, configured by --config and calibrated by --profile,
    /// with the recording's time between frames as the time step (the station's input gate
    /// and control loop are left out: every glove frame is scored, comparable with other
    /// retargeters). Then the live path: the recording re-simulated through the station as
    /// `pomdar resim` runs it, and the command in force at each distinct frame scored the same
    /// way, with its difference from the retargeter alone. Prints, overall and per finger: fingertip error after one global scale s* of the human hand (mean, p95;
    /// fingertip-to-palm-centre vectors in each hand's palm frame), pinches (human thumb tip
    /// within 2 cm of a fingertip) and the share the robot closes under 15 mm, jerk (mean
    /// absolute third difference per joint and frame), the largest per-frame joint step,
    /// frames outside the joint limits, and the time per frame. Any layout the station
    /// accepts. Then the metrics without the global scale (a smaller-looking hand does not
    /// score better): per finger the tip error after that finger's own scale, the correlation
    /// of human and robot flexion (palm-centre-to-tip distance), pinches closed with their
    /// frame counts, and the lag (the shift that best aligns robot to human flexion).
    /// --commands TOPIC scores another retargeter's recorded JointState commands instead.
    ///
    /// Examples:
    ///   pomdar eval ../shared/reference/rokoko_orca_2024-11-20.mcap
    ///   pomdar eval trial.mcap --config launch_configs/station/eth_lab.toml --profile profiles/alice.toml --json
    ///   pomdar eval ../shared/reference/ eval_set/
    #[command(verbatim_doc_comment)]
    Eval(command::eval::EvalArgs),
    /// How closely the hand followed its commands in a trial log: commanded vs measured, per
    /// joint.
    ///
    /// Reads the station's joint targets ([output] joint_targets_topic) and the hand's
    /// measured state ([input] hand_state_topic), both sensor_msgs/JointState as the station
    /// recorded them, with their names mapped onto the model's joints. Per joint: commands and
    /// measured samples, the RMS and largest |command in force − measured| (degrees; the
    /// command in force is the last one sent at or before the measurement), the lag that best
    /// aligns the measured angle with the command (the highest correlation over 0–300 ms, in
    /// whole milliseconds) and the share of time the error exceeds --threshold-deg (5°).
    /// Prints a table (or JSON with --json); --out DIR writes tracking.svg and tracking.png
    /// (one panel per joint: commanded and measured angle over time, titled with the joint
    /// and its RMS error) and tracking.json, each atomically. A log without measured states
    /// is an error naming the file and the topic looked at.
    ///
    /// Examples:
    ///   pomdar tracking sessions/alice/orca_full/V1/V1-t03.mcap
    ///   pomdar tracking run.mcap --out report/tracking --json > tracking.json
    ///   pomdar tracking run.mcap --config launch_configs/station/eth_lab.toml --threshold-deg 3
    #[command(verbatim_doc_comment)]
    Tracking(command::tracking::TrackingArgs),
    /// What happened in a trial, for the operator: one figure and a short JSON per log, and
    /// feedback sentences.
    ///
    /// The figure (NAME.review.png and .svg, beside the log or in --out) shows on one time
    /// axis from the trial's start to its stop: the station's drive state (engaged, held on a
    /// stalled glove with the glove's gap, disengaged), the arm's clutch and refused steps,
    /// the human's pinches (green: the robot closed it, under 15 mm; red: it did not); the
    /// progress marks and drops; the glove's rate; the input age with the hold timeout and
    /// the rejected frames; the thumb–finger distances, human (dashed) and robot; and, when
    /// the hand's measured state was logged, the tracking error per digit. NAME.review.json
    /// holds the same facts and the feedback: short sentences said only past a threshold
    /// ("held 2× (glove gaps 180–420 ms)", "index pinch did not close in 4 of 6 attempts
    /// (robot 18 mm apart)", "wrist at its limit 22 % of the time", "2.4 s without progress
    /// before the drop at 9.1 s"), none for a clean trial; the thresholds are README's table
    /// (--feedback FILE overrides them). The operator console does the same after each trial.
    ///
    /// Examples:
    ///   pomdar review sessions/alice/orca_full/G4/G4-t03.mcap
    ///   pomdar review sessions/alice/orca_full/G4/*.mcap --out review/
    ///   pomdar review run.mcap --json | jq .feedback
    #[command(verbatim_doc_comment)]
    Review(command::review::ReviewArgs),
    /// Build an evaluation set: transformed copies of real recordings for `pomdar eval`.
    ///
    /// Each recording's distinct keypoint frames are written again as they would come from
    /// other users and gloves: a smaller hand (0.85×) with the glove turned 15°, a larger hand
    /// (1.2×) turned −12°, a noisy glove (2 mm per coordinate) dropping 10 % of its frames,
    /// 30 Hz and 120 Hz (re-sampled linearly), and, for the lab's 22 points, its 21-point
    /// layout. Besides, --synthetic-users (4 by default) users of the project's simulated
    /// glove, each hand with its own proportions (thumb ±15 %, index and middle ±10 %, palm
    /// breadth ±10 %, the thumb's base moved, the glove's tip markers ±5 mm off the tips),
    /// whose pinches are real contacts of the simulated hand and on whom nothing was tuned
    /// (a seed no one looked at gives users no one tuned on). One MCAP per recording in --out
    /// and set.json listing them; the sources are not copied (evaluate them beside the set).
    ///
    /// Example:
    ///   pomdar eval-set ../shared/reference/ --out eval_set/
    ///   pomdar eval ../shared/reference/ eval_set/
    ///   pomdar eval-set --synthetic-users 8 --seed 2027 --out held_out/   (users only)
    #[command(verbatim_doc_comment)]
    EvalSet(command::eval_set::EvalSetArgs),
    /// Repair an interrupted log (NAME.mcap.part) up to its last flushed chunk.
    ///
    /// Prints what was recovered and what was lost; never modifies the input.
    Recover(command::recover::RecoverArgs),
    /// Republish a log's recorded topics over ROS 2 with their original timing.
    ///
    /// Example:
    ///   pomdar replay rokoko_orca_2024-11-20.mcap --topics /ingress/mano,/ingress/wrist --rate 1
    #[command(verbatim_doc_comment)]
    Replay(command::replay::ReplayArgs),
    /// Check DDS discovery from this host: which publishers it sees, and at what rate.
    ///
    /// Joins the domain on the given interfaces, waits for a publisher of each topic, counts
    /// its samples for --duration seconds and prints every discovered publisher with the
    /// addresses it announced (its host) and each topic's rate; for stamped messages also
    /// how old they were on arrival (receive time − header stamp) and how many were older
    /// than --age-limit-ms, and the topic's silences (pauses of 250 ms or more). With
    /// --reliable it subscribes as a robot driver does. Exit status 0 when every topic was
    /// heard, 2 when one was not discovered or not heard (docs/DEPLOYMENT.md says what to
    /// check).
    ///
    /// Example:
    ///   pomdar probe --topics /pomdar/hand/joint_targets,/franka/end_effector_pose_cmd --interface 10.251.0.3
    #[command(verbatim_doc_comment)]
    Probe(command::probe::ProbeArgs),
    /// On the robot's computer: the station's commands onto the robot's own topics.
    ///
    /// With `[robot_link] relay_prefix` set, the station sends its robot commands best effort
    /// on relay topics (the prefix + the robot's topic): a cut cable loses what was sent into
    /// it and nothing old is resent when it returns. The relay republishes each command on the
    /// robot's topic with the configuration's output.qos (reliable for the lab's drivers), on
    /// this computer, and drops any command older than `[robot_link] max_age_ms` (100 ms) on
    /// arrival, by the older of its send time and its header stamp (a hand command's glove
    /// frame): the lab's clocks must be kept in step (chrony). It
    /// estimates the offset between the two clocks from the smallest command ages and warns,
    /// naming it, once it takes a quarter of that limit. Drops and refused publishes are
    /// reported every 5 s at most; a summary on Ctrl-C. Twice a second it publishes its status
    /// on `<relay_prefix>/relay_status` (the robot's drivers listening, the offset), which the
    /// station reads. docs/DEPLOYMENT.md, "When a link fails".
    ///
    /// Example:
    ///   pomdar relay --config launch_configs/station/deploy_station.toml --interface 10.251.0.3
    #[command(verbatim_doc_comment)]
    Relay(command::relay::RelayArgs),
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
    #[command(verbatim_doc_comment)]
    Calibrate(command::calibrate::CalibrateArgs),
    /// Check a hand's command conventions on the hand, joint by joint, and write the table
    /// verified.
    ///
    /// The table is the station configuration's [[policy_output.joints]]: for each slot of
    /// the array the consumer of the policy output topic reads (the ETH lab's hand-control
    /// node in launch_configs/station/eth_lab.toml, orca_core in orca_core.toml), the
    /// station joint, sign, offset, clamp range and units, where each number comes from and
    /// whether it was checked. Stop the station first: both would drive the hand.
    ///
    /// The hand goes to a neutral pose (each joint at the value nearest the URDF zero inside
    /// its URDF limits and the consumer's range), then each joint in the table's order moves
    /// a small step (--step-rad, at most 0.15 rad) slowly (--move-s each way, at least 1 s),
    /// holds, and comes back, sent at --rate-hz through the table on the consumer's topic,
    /// while the others hold still. The terminal shows the progress ("joint 6 of 17:
    /// index_abd") and what the operator should see ("the index finger moves towards the
    /// middle finger"), then asks. Answers, typed on stdin (one a line) or from --script:
    ///   yes (y)     it moved as named: the next joint
    ///   no (n)      it moved the other way; then
    ///     flip (f)  flip its sign in the table and move it again (confirm it with yes)
    ///     keep (k)  keep the sign and move it again
    ///   repeat (r)  move it again
    ///   quit (q)    stop
    /// The check settles directions (signs) only: a wrong offset or zero (orca_core's
    /// ref_zero) shows in the neutral pose, which the operator should look at first; a
    /// flipped joint keeps its offset and range.
    ///
    /// When every joint is confirmed, --out is written atomically: the configuration file
    /// with its [policy_output] replaced by the table with every row verified = true (and
    /// any flipped sign, noted), verified_by = --user and verified_at (UTC); other tables
    /// and comments are kept. If any joint is not confirmed (quit, Ctrl-C, stdin or the
    /// script ended) nothing is written and the exit status is 1, naming the joints left.
    ///
    /// --script FILE: answers one a line, optionally after a time (seconds since the start,
    /// or +S after the previous line), and `wait PHASE [TIMEOUT_S]` with PHASE one of
    /// settling, moving, asking, offer_flip, complete, quit (default timeout 30 s):
    ///   wait asking 30
    ///   yes
    ///   wait asking 30
    ///   no
    ///   flip
    ///
    /// Try it without a hand: `pomdar mock-hand --policy-config FILE` follows the same
    /// topic through the inverse of the table.
    ///
    /// Examples:
    ///   pomdar hand-check --config launch_configs/station/eth_lab.toml --user ana --out lab/eth_lab_verified.toml
    ///   pomdar hand-check --config launch_configs/station/orca_core.toml --user ana --out /tmp/orca.toml --script check.script
    #[command(verbatim_doc_comment)]
    HandCheck(command::hand_check::HandCheckArgs),
    /// The operator console for timed trials: practice, then a recorded series, per task.
    ///
    /// Runs the station in this process and shows, full-screen: the task and what to mark,
    /// the embodiment, the calibration profile, live health (glove rate, input age, latency,
    /// engaged/held, watchdog, rejected frames, arm), the countdown and the running timer, and
    /// after each trial its time, correctness, score (with a baseline), the series' mean ±
    /// std and the trial's feedback (`pomdar review`: holds, pinches the robot did not close,
    /// the wrist at its limit, …; nothing for a clean trial). Each trial is its own MCAP log
    /// in the session directory (<out>/<user>/<embodiment>/<task>), its review figure and
    /// JSON in review/, with session.json (the manifest) written after every change and
    /// report/ (as `pomdar score --out`, ending with the trials worst first and their
    /// feedback) when the plan is done. Run the same
    /// command again to resume an interrupted session: a trial cut short by quit, Ctrl-C or a
    /// crash is kept aside (*.interrupted) and run again.
    ///
    /// --embodiment human is a human-study session (see `pomdar study`): no robot, no
    /// retargeting, the glove's keypoints and wrist recorded; the start checks only the glove;
    /// no practice and 3 trials unless --practice / --trials say otherwise.
    ///
    /// Keys: e engage / clutch out · space start (after the countdown) / stop · + one notch or
    /// curve · - take one back · p type a value (degrees, mm, grasp level 0 / 0.5 / 1) · d drop
    /// · a abort (scored as aborted) · r redo (abort and run again, or set the last trial
    /// aside) · n note · q quit (twice during a trial) · Ctrl-C quit now. A trial does not
    /// start while the station is not engaged, the glove input is stale or slower than
    /// --min-glove-rate.
    ///
    /// Without a terminal (or with --plain) it prints a line per change and reads commands
    /// from stdin, one per line: engage, disengage, start, stop, progress [V], unmark, drop,
    /// abort, redo, note TEXT, quit. --script FILE plays timed commands instead:
    ///   # seconds since the start, or +S after the previous line
    ///   1.0  engage
    ///   wait ready 10        # wait (at most 10 s) for a state: waiting_engage, ready,
    ///   +0.5 start           #   countdown, running, finishing, summary, complete
    ///   wait running 10
    ///   +2   progress
    ///   +1   stop
    ///   wait summary 10
    /// Exit status: 0 when the console ends normally, 130 after Ctrl-C or SIGTERM, 1 on an
    /// error (a script's wait timing out, a bad file).
    ///
    /// Examples:
    ///   pomdar trial --task V1 --embodiment orca_full --user alice --operator bob --profile profiles/alice.toml --baseline baselines/eth_2026.toml
    ///   pomdar trial --task G2 --user sim --operator me --simulate --practice 1 --trials 3
    ///   pomdar trial --task V1 --embodiment human --user p01 --operator bob
    #[command(verbatim_doc_comment)]
    Trial(command::trial::TrialArgs),
    /// The human study: a participant does each task of a plan with their own hand.
    ///
    /// The baseline a robot's speed is scored against comes from people: in the POMDAR study
    /// each participant does every task 3 times with their right hand, wearing the glove.
    /// For each task in --tasks, in order, this runs the trial console as `pomdar trial
    /// --embodiment human` would: the task's instruction and where the participant is in the
    /// plan are shown; no robot, no retargeting; the glove's keypoints and wrist pose are
    /// recorded with the trial's timing and events (one MCAP per trial, embodiment "human",
    /// the participant as the user) in <out>/<participant>/human/<task>; a trial starts once
    /// the glove is fresh and fast enough (space, or `start` in a script). Defaults: no
    /// practice, 3 trials per task. Run the same command again to resume: complete tasks are
    /// skipped, the interrupted one resumes at its next trial. Then `pomdar baseline` makes
    /// the baseline table and `pomdar study-report` checks the participants' strategies.
    /// Exit status: 0 study complete, 130 stopped (Ctrl-C, SIGTERM, q) before the end, 1 on
    /// an error.
    ///
    /// Examples:
    ///   pomdar study --participant p01 --operator bob --tasks V1,H2,C1,G2
    ///   pomdar study --participant sim1 --operator me --tasks V1,C1,G2 --simulate --simulate-motion open-close,pinches,abduction
    #[command(verbatim_doc_comment)]
    Study(command::study::StudyArgs),
    /// The human study's strategy check: do participants do each task the same way?
    ///
    /// Reads the recorded human trials (embodiment "human"; practice and aborted trials left
    /// out) and cuts each trial's glove keypoints into 1.5 s segments. Each frame's keypoints
    /// are expressed in the palm frame and divided by the participant's hand length (so hand
    /// size, glove placement and where the hand is in the room do not count); a segment's
    /// features are the mean and the standard deviation of those coordinates (the posture and
    /// the movement). A PCA of the standardised features gives the first 3 principal
    /// components. Writes to --out: strategy_pc1_pc2 and strategy_pc1_pc3 (.svg and .png: one
    /// point per segment, coloured by task), report.md (variance explained, per-task
    /// separation, the trial files used and left out) and strategy.json. The separation is
    /// the silhouette of the segments' task labels on the kept components, read with Kaufman
    /// & Rousseeuw's bands: > 0.70 strong, > 0.50 reasonable, > 0.25 weak, otherwise no
    /// substantial structure. Exit status: 0 every file read; 3 some files could not be read
    /// (the report is still written from the rest); 1 nothing to analyse (fewer than 2 tasks,
    /// too few segments), or a file could not be written.
    ///
    /// Example:
    ///   pomdar study-report sessions/ --out reports/study_strategy
    #[command(verbatim_doc_comment)]
    StudyReport(command::study_report::StudyReportArgs),
    /// Score trial logs the POMDAR way: 0.8 · correctness + 0.2 · speed, per trial, task and
    /// embodiment.
    ///
    /// Reads each trial's pomdar_trial metadata (task, embodiment, practice, user, ...) and its
    /// events on /pomdar/trial_events, through the MCAP summary (only the chunks holding events
    /// are decompressed). Per trial: time = stop − start (aborted: abort − start); correctness
    /// from the progress events per the task's kind (notches or curves passed / total,
    /// degrees / 360, millimetres / 200 for H4 and H5, grasp level 0 / 0.5 / 1, a drop = 0.5);
    /// speed = baseline time / trial time (unbounded above). Aborted or timed-out trials follow
    /// the rules file (default: correctness reached, speed term 0). Practice trials are shown
    /// but never averaged. Per task × embodiment: mean ± sample std over recorded trials; per
    /// embodiment: the overall score as the mean over attempted tasks and as the mean over all
    /// 18 with missing tasks = 0, with the embodiment's DoF.
    ///
    /// Without --baseline, or for a task the baseline lacks, there is no score, only
    /// correctness, and every report says so; a baseline marked example = true is flagged in
    /// every report. A file that cannot be scored (not MCAP, truncated, no pomdar_trial record,
    /// missing start or stop, events out of order, unknown task, a progress value the task does
    /// not allow, ...) is named with its reason on stderr and in the reports; the other files
    /// are still scored. Interrupted recordings (*.mcap.part) are skipped with a note.
    ///
    /// Prints the table on stdout (or the JSON report with --json); progress on stderr for
    /// large sets. Exit status: 0 every file scored; 3 some files rejected (reports still
    /// written); 1 the run failed (bad catalog, rules or baseline file, no trial files, a
    /// report or figure could not be written).
    ///
    /// --compare FIELD puts groups of trials side by side instead (the source ablation: the
    /// same station, controller and robot with keypoints from Rokoko gloves or from Apple
    /// Vision Pro): the groups are the values of the trials' pomdar_trial metadata entry FIELD
    /// (keypoint_source, user, station_version, ...; trials without it form "(missing)", and
    /// the report says how many). Per task × embodiment × group: n and mean ± sample std of
    /// correctness, time and score (score only with a baseline), over the same recorded
    /// trials and scores as the report; per group the difference from the reference group
    /// (the first value in sorted order, or --compare-reference VALUE) with Welch's 95 %
    /// interval (none when a group has fewer than 2 trials there). With --out it writes
    /// compare.md, compare.csv, compare.json and the grouped-bar figures compare_score and
    /// compare_correctness (.svg, .png) instead of the report's files. Fewer than two groups,
    /// or a reference that is not a group, stops the run (status 1).
    ///
    /// Examples:
    ///   pomdar score trials/ --baseline baselines/eth_2026.toml
    ///   pomdar score trials/orca_full trials/orca_5 --baseline baselines/eth_2026.toml --out report/
    ///   pomdar score trials/ --rules launch_configs/scoring/default_rules.toml --json > scores.json
    ///   pomdar score trials/ --baseline baselines/eth_2026.toml --compare keypoint_source --out reports/ablation/
    ///   pomdar score trials/ --baseline baselines/eth_2026.toml --compare keypoint_source --compare-reference rokoko --json
    #[command(verbatim_doc_comment)]
    Score(command::score::ScoreArgs),
    /// Compute the human baseline table from recorded human trials (embodiment "human").
    ///
    /// Per task: the mean and sample standard deviation of the trial time (start → stop) over
    /// recorded trials that were stopped, not aborted, and within the rules' time limit;
    /// practice, aborted and timed-out trials are listed and left out. Trials of another
    /// embodiment are refused by name. Writes the table atomically as TOML (example = false,
    /// a source note with --source, the trial count and the users; per task the number of
    /// participants when every trial names its user), for `pomdar score --baseline`.
    ///
    /// Prints the study: per task the trials, mean, std, min–max and participants, then per
    /// participant × task (the trials' user; "(unnamed)" without one) the trial times in
    /// trial-index order. Tasks with fewer than --min-trials trials (default 18: the POMDAR
    /// study's 6 participants × 3 trials) are flagged FEW and warned about on stderr; the
    /// table is still written and the exit status is unchanged. --report FILE also writes the
    /// study as Markdown (atomically; an existing file needs --overwrite, like --out).
    ///
    /// Exit status: 0 every file used or left out for a stated reason; 3 some files were
    /// rejected or refused (the table is still written from the rest); 1 nothing usable, or
    /// a file could not be read or written.
    ///
    /// Examples:
    ///   pomdar baseline trials/human/ --source "ETH lab, 6 participants, Nov 2026" --out baselines/eth_2026.toml
    ///   pomdar baseline trials/human/ --out baselines/pilot.toml --min-trials 6 --report baselines/pilot_study.md
    #[command(verbatim_doc_comment)]
    Baseline(command::baseline::BaselineArgs),
    /// Hand-tracking ingress: a glove (Rokoko) or headset (Apple Vision Pro) stream in, the lab's ROS 2 keypoint topics out.
    #[command(subcommand)]
    Ingress(command::ingress::IngressCommand),
    /// Load a hand model, validate it and print its joints, limits, frames and embodiments.
    ///
    /// Without options it shows the built-in ORCA v1 right hand. Use it to check a new hand's
    /// URDF before running the station with it: errors name the file, element and problem.
    ///
    /// Examples:
    ///   pomdar model
    ///   pomdar model --urdf orcahand_v1_right.urdf --import launch_configs/hands/orca_v1_right_urdf.toml
    ///   pomdar model --pose index_mcp=0.8,thumb_mcp=0.3 --json
    #[command(verbatim_doc_comment)]
    Model(command::model::ModelArgs),
}

/// The `pomdar` process: parse the command line, run the command, return its exit status.
pub fn main() -> ExitCode {
    crate::library_log::install();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Model(args) => command::model::model(args),
        Command::Score(args) => return exit_code(command::score::score(args)),
        Command::Baseline(args) => {
            return exit_code(command::baseline::baseline(args));
        }
        Command::Trial(args) => {
            return exit_code(command::common::run_async(command::trial::trial(args)));
        }
        Command::Study(args) => {
            return exit_code(command::common::run_async(command::study::study(args)));
        }
        Command::StudyReport(args) => {
            return exit_code(command::study_report::study_report(args));
        }
        Command::Demo(args) => command::common::run_async(command::demo::demo(args)),
        Command::Calibrate(args) => return exit_code(command::calibrate::calibrate(args)),
        Command::Resim(args) => command::resim::resim(args),
        Command::Eval(args) => command::eval::eval(args),
        Command::Tracking(args) => command::tracking::tracking(args),
        Command::Review(args) => command::review::review(args),
        Command::EvalSet(args) => command::eval_set::eval_set(args),
        Command::Recover(args) => command::recover::recover(args),
        Command::Replay(args) => command::common::run_async(command::replay::replay(args)),
        Command::Probe(args) => {
            return exit_code(command::common::run_async(command::probe::run(args)));
        }
        Command::Relay(args) => command::common::run_async(command::relay::relay(args)),
        Command::Ingress(command) => command::common::run_async(command::ingress::run(command)),
        Command::Station(args) => command::common::run_async(command::station::station(args)),
        Command::SimGlove(args) => command::common::run_async(command::sim_glove::sim_glove(args)),
        Command::HandCheck(args) => {
            command::common::run_async(command::hand_check::hand_check(args))
        }
        Command::MockHand(args) => command::common::run_async(command::mock_hand::mock_hand(args)),
        Command::Sim(args) => command::common::run_async(command::sim::sim(args)),
        Command::SimBench(args) => return exit_code(command::sim_bench::sim_bench(args)),
        Command::MockFranka(args) => {
            command::common::run_async(command::mock_franka::mock_franka(args))
        }
    };
    exit_code(result.map(|()| ExitCode::SUCCESS))
}

/// The process's exit status: the command's, or 1 after printing the error.
fn exit_code(result: anyhow::Result<ExitCode>) -> ExitCode {
    match result {
        Ok(code) => code,
        Err(error) => {
            eprintln!("error: {}", error_message(&error));
            ExitCode::FAILURE
        }
    }
}

/// The error and its causes on one line, `outer: inner: …`. A typed error's message already
/// carries its cause's text (the project's rule, ARCHITECTURE.md "Conventions"), so a cause
/// whose text the line holds already is not repeated.
fn error_message(error: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in error.chain() {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("profile /p.toml: {source}")]
    struct Outer {
        #[source]
        source: std::io::Error,
    }

    #[test]
    fn the_whole_command_line_is_consistent() {
        use clap::CommandFactory as _;
        Cli::command().debug_assert();
        let cli = Cli::try_parse_from([
            "pomdar",
            "score",
            "trials/",
            "--compare",
            "keypoint_source",
            "--compare-reference",
            "rokoko",
        ])
        .unwrap();
        let Command::Score(args) = cli.command else {
            panic!("not score");
        };
        assert_eq!(args.compare.as_deref(), Some("keypoint_source"));
    }

    #[test]
    fn a_cause_already_in_the_message_is_not_repeated_and_a_context_is_kept() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "no such file");
        let error = anyhow::Error::new(Outer { source: io }).context("pomdar resim");
        assert_eq!(
            error_message(&error),
            "pomdar resim: profile /p.toml: no such file"
        );
        let plain = anyhow::anyhow!("inner").context("outer");
        assert_eq!(error_message(&plain), "outer: inner");
    }
}
