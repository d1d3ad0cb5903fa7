//! # teleop: the POMDAR station application
//!
//! The one crate that does I/O: files, ROS 2 (ros2-client + tokio), MCAP logs and the
//! consoles. The pure crates compute; this crate reads, writes and talks.
//!
//! Every loop drives the one core, `station::Station::step(input, now)`, through
//! [`station_driver`]: the live ROS node (`station_node::ros_node` stamps each input with its
//! receive time, records it, steps the station and publishes what it returns; the control
//! inputs go on `/pomdar/station_control`), the re-simulation of a log (`resim.rs`: a new
//! station stepped with exactly the recorded inputs reproduces the commands byte for byte),
//! `pomdar eval`'s live path, the lock step with the physics (`physics/lockstep.rs`) and the
//! consoles.
//!
//! ## Layers
//!
//! A module imports only from its own layer and the layers below it, and nothing imports from
//! `command/`: `tests/tests/suite/dependency_rule.rs` reads this table
//! (`tests/src/layer_rule.rs`) and fails on an upward import or a top-level module the table
//! does not name.
//!
//! | layer | module | what |
//! |---|---|---|
//! | wiring | `main.rs`, `command/` | one file a command, each with its own clap `Args` and the function that runs it (`cli.rs`: the command line and the exit status, which `main.rs` only calls; `shared_args.rs`, the one file every command may use: DDS, console and view flags, the glove's motions, the runtime, Ctrl-C); each holds its flags, their checks, its help and one call, at most 250 lines, and no command imports another (`tests/src/command_rule.rs`); the only place errors go untyped |
//! | sessions | `console/` | `pomdar trial`, the operator console (and each task of `pomdar study`, the human study: no robot, the start gated on the glove alone): the session as a state machine without I/O, the start gate and the fault counts, the view model and the manifest's data are the core crate `consoles` (`trial_flow`, `health`, `view` re-exported); here the manifest's file and resume (`manifest.rs`, `session_dir.rs`: `.part` logs of a crash recovered and set aside), the console's messages kept in the session (`message_log.rs`, `console.log`), the view drawn full-screen (`screen.rs`) or printed as lines (`plain_output.rs`), the words and keys (`keys.rs`), `--script` words (`trial_script.rs`); the runtime: the options and their checks (`session_options.rs`, `session_check.rs`), set-up (`session_setup.rs`), the event loop that carries out the effects (`runner.rs`, on the terminal shell's turn loop), the operator's side and prompt (`operator_side.rs`), the session's files and report (`session_state.rs`, `session_report.rs`, `session_info.rs`), the station node in process (`in_process_station.rs`), the simulated glove and robot (`simulated_world.rs`) and the physics' marks (`physics_link.rs`) |
//! | sessions | `calibrate/` | `pomdar calibrate`: the calibration console (the session pose by pose as a pure state machine, capture-quality meter and view model in the core crate `consoles`; accept / retry, after the fit a pose it could not match captured again alone, full-screen or line view, `--script`), the session node (poses to the hand, every capture window with its quality and decision as events, MCAP), frames per pose from a session file, the fit with its progress, atomic profile files, the simulated user; the command's run: its request and checks (`calibrate_request.rs`, `calibrate_run.rs`), the console session (`calibrate_console_run.rs`) and the printed report (`calibrate_report.rs`) |
//! | sessions | `hand_check/` | `pomdar hand-check`: the hand's command conventions checked joint by joint (the check as a pure state machine and what each joint's motion looks like, in the core crate `consoles`; `--script` words, the node sending through the table, the verified table written into a copy of the preset) |
//! | sessions | `demo/` | the whole pipeline in one process on loopback DDS (simulated glove, station node, and the robot: `robot.rs`, the mock robot or with `--physics` the simulated one, whose physics' progress becomes the summary's correctness; the printed summary, `summary_text.rs`) |
//! | sessions | `sim_bench/` (feature `physics`) | `pomdar sim-bench`, the benchmark without a teleoperator: the practice file with its scripts built in or a lab's (`families.rs`, a task's station file laid over the configuration), one run of a strategy in lock step with an early stop at the physics' completion (`play.rs`), a run as a trial (`trial_events.rs`) and as a trial log through the station's recorder (`trial_log.rs`), one task × embodiment's practice and recorded runs (`item.rs`), the items over the cores (`bench_run.rs`), the output directory, its item files, report, strategies, findings and the merge of shards (`outputs.rs`), the request with resume and the example baseline (`request.rs`) |
//! | sessions | `eval_modes.rs` | `pomdar eval`'s other modes: `--outlier-study`, `--commands`, `--profile-scales` |
//! | sessions | `sim_runs/` (feature `physics`) | `pomdar sim`'s runs: real time on the robot's topics, `--write-scene`, `--lockstep` runs and their printed report |
//! | sessions | `eval/` | `pomdar eval`: the retargeter alone on every distinct frame of a recording (`retarget::quality` metrics, time per frame; table or JSON) and the live path (`live_path.rs`: the re-simulated station's command in force at each distinct frame, scored against the frame or, for a synthetic user, against the hand as held); several recordings with a summary (`summary.rs`); another retargeter's recorded commands (`external.rs`, `--commands`); one-frame outliers injected and the station re-simulated with and without the frame gate's outlier check (`outlier_study.rs`, `--outlier-study`); the evaluation set (`variants.rs`: pure transformed copies — hand size, glove turned, noise and drops, rate, 21 points, and the outliers of the study; `synthetic_users.rs`: simulated-glove users with hands of their own proportions, never tuned on; `eval_set.rs`: `pomdar eval-set` writes them); `tracking.rs`: `pomdar tracking`, a trial log's commanded joint targets against the hand's recorded measured state, per joint, compared by `scoring::tracking_report` and drawn by `scoring::plot::tracking_grid`) |
//! | nodes and logs | `station_node/` | the ROS node around `station::Station` (`ros_node.rs`: the public API, the node's state and the select loop, whose named steps are `impl` blocks in `ros_node/`: the endpoints and input streams (`endpoints.rs`), the inputs and the step itself (`input_steps.rs`), the status with publish failures and unreadable samples counted (`status_steps.rs`), the trial log and the node's finish (`trial_steps.rs`); `loop_turns.rs`: the loop's longest turn and its handler, in the status), the recorder and its thread (`recorder_thread.rs`: the loop only queues copies; every write, flush, sync and rename happens on that thread, outcomes come back as reports; a full queue drops and counts), the control-input channel (`control_input_log.rs`), the operator commands and hooks (`operator.rs`); faults: [docs/FAULTS.md](docs/FAULTS.md); the ROS tools' endpoints (`ros_tools_node.rs`: `/tf`, markers, diagnostics, `/robot_description`, the hand's measured state, the Trigger services) and their steps (`ros_node/tool_steps.rs`); the outputs published in the router's order, recorded, counted and timed (`ros_node/output_steps.rs`); `tap.rs`, a copy of everything sent for a live viewer |
//! | nodes and logs | `relay_node/` | `pomdar relay` on the robot's computer: the station's commands from the relay topics (best effort across the network) onto the robot's topics (`output.qos`), each older than `[robot_link] max_age_ms` dropped by `station::robot_link::CommandAgeGate` (`legs.rs`, with the rate-limited warnings), the clock offset estimated by `station::link_clock::ClockOffsetMonitor`, and its status for the station (`status.rs`: the robot side's readers, the offset) that `station_node/relay_view.rs` reads ([docs/DEPLOYMENT.md](docs/DEPLOYMENT.md#when-a-link-fails)) |
//! | nodes and logs | `view/` | the live 3D view (`--view [ADDR:]PORT`, `live_view.rs`): the Foxglove SDK's WebSocket server (teleop feature `view`) fed from the station's tap (`station_node/tap.rs`) in its own task; a channel per topic on its first message (`cdr`, `ros2msg`), the last latched message of each topic replayed to a viewer that subscribes later; a view that falls behind drops the oldest messages, never slows the station |
//! | nodes and logs | `resim.rs`, `replay.rs` | re-simulation: a station stepped with a log's inputs (recorded control inputs, or ticks on the log clock for a glove recording); replay over ROS 2 with original timing |
//! | nodes and logs | `stand_ins/` | nodes that stand in for the devices: the simulated glove node (periodic motions or a task script, `glove_script_file.rs`), mock ORCA hand (optionally following a policy output topic through the inverse of its table), mock Franka; `progress_message.rs`, the simulated robot's progress events on the wire and as the console's marks; `glove_jitter.rs`, the simulated glove's noise flag |
//! | nodes and logs | `device_thread.rs` | a simulated device (the glove, the simulated robot) on a thread and runtime of its own, as a real one is a machine of its own |
//! | nodes and logs | `physics/` (feature `physics`) | the simulated robot: `engine.rs` (MuJoCo through mujoco-rs: a scene from text or file, the hand bound by joint and actuator names, URDF angles in and out across each joint's zero offset, the servo speed limit, the arm's mocap mount, readings), `setup.rs` (the one place a task is loaded: the project's scene, with the project's hand or the lab's `simulated_hand_mjcf`, the station file's `[simulated_physics]` contact, servo and mount settings, and a start moved or not, or a lab's task MJCF with the catalog's mapping), `sim_state.rs` (arm slew, physics step, progress tracker), `robot_node.rs` (`pomdar sim`: real time on the real robot's topics), `lockstep.rs` (glove script → `station::Station`, built and ticked through `station_driver` as every live path → physics in simulated time, no DDS); `console/physics_link.rs` hands its events to the console as marks |
//! | nodes and logs | `ingress/` | `pomdar ingress rokoko`: Rokoko Studio's JSON v3 over UDP → the lab's keypoint and wrist topics (frame conversion, parsing and ordering pure and tested; the UDP/ROS node). `pomdar ingress avp`: the Vision Pro app's gRPC stream → the same topics (`avp_proto.rs` the messages and codec by prost derive, `avp_frame.rs` ARKit y-up → ROS pure and tested, `avp_node.rs` the reconnecting tonic client and ROS publishers). Rokoko listens on 127.0.0.1 unless told `bind_address`, takes only `allowed_senders`, orders every packet and rate-limits its log lines (`log_limit.rs`, also the relay's). Each ingress names its source in its status; the station node writes it into every trial log (`keypoint_source`, `keypoint_device`) |
//! | nodes and logs | `score/` | `pomdar score` and `pomdar baseline`: trial files, a file → `scoring::TrialLog`, files on every core with progress, report files (atomic), the comparison's files (`compare_files.rs`, `--compare FIELD`), synthetic station-style trials for the benchmark and tests; `baseline_source.rs`, where a baseline came from |
//! | nodes and logs | `trial_review/` | `pomdar review` and the console's review after each trial: a trial log read into `review::TrialInput` (`read.rs`), reviewed, and `NAME.review.png`, `.svg`, `.json` written atomically |
//! | nodes and logs | `station_topics.rs` | the topics a station serves live and records, with their types and schema texts, for a configuration (what the Foxglove layouts in `launch_configs/foxglove/` are checked against) |
//! | nodes and logs | `study_logs.rs` | `pomdar study-report`: a human trial log → the `study` crate's motion (keypoint frames between start and stop by their source stamps, bad frames dropped and counted; practice, aborted and robot trials left out with the reason) |
//! | nodes and logs | `launch_config.rs`, `model_report.rs` | checking any launch configuration file by its kind; `pomdar model`'s report |
//! | infrastructure | `ros/` | DDS participant (domain id; `domain_lease.rs`: an unused id leased by a lock file, for the all-in-one commands and the tests, which share a machine; interfaces: what RustDDS allows, checked at start-up), QoS, typed endpoints for `msgs` types, conversions; the `--domain-id`/`--interface` override (`network_override.rs`); the shutdown order (`teardown.rs`: endpoints, node, participant; the one benign RustDDS teardown record); the discovery probe behind `pomdar probe` (`discovery_probe.rs`: discovered publishers and their addresses, per-topic rates; `probe_timing.rs`: ages on arrival and silences); `datagram_guard.rs`, a kernel socket filter against crafted DATA_FRAG sizes, and `participant_guard.rs`, which requires it on every socket of every participant built by the commands that run the station or talk to the robot (station, trial, study, relay, calibrate, hand-check, sim; start-up fails otherwise, `--no-datagram-guard` opts out) ([docs/SECURITY.md](docs/SECURITY.md)) for multi-host deployments ([docs/DEPLOYMENT.md](docs/DEPLOYMENT.md)) |
//! | infrastructure | `mcap_log/` | rosbag2-style MCAP writer (`.part`, flush policy), reader, recovery, QoS metadata; `event_reader.rs`: a trial's metadata and events through the MCAP summary (only event chunks decompressed); `decompression_budget.rs`: a chunk's and a file's declared uncompressed size checked before anything is decompressed; `slow_disk.rs`: the test-only slow-disk knob; `background_sync.rs`: the station's trial logs synced beside their writes; `writer_thread.rs`: a writer on a thread of its own (the calibration session log); `continue_log.rs`: a finished log copied into a writer that replaces it (a calibration pose captured again after the fit) |
//! | infrastructure | `station_driver/` | the one driver around `Station::step` that every loop uses: the task → configuration step (`task_config.rs`: **the task's arm constraint chosen**, who engages), `--config` or the default with `--profile` over it and the station built with its calibration profile (`setup.rs`), when the timer ticks (`ticks.rs`), where the outputs go (`sinks.rs`: a step's outputs in one order, `deliveries`, handed to a log, the simulated robot or the live node's publishers) |
//! | infrastructure | `fnv.rs` | the one FNV-1a hash (configuration digests, stable seeds from names) |
//! | infrastructure | `tui/` | what the consoles share: full-screen mode and keyboard input (`terminal.rs`), panels and level colours (`panels.rs`), the `--script` grammar and player, the terminal shell (`terminal_shell.rs`: the turn loop the trial console, the calibration console and the hand check run on, the tick, signals, Ctrl-C, the interrupted exit status) |
//! | infrastructure | `clock.rs`, `samples.rs`, `progress_bar.rs`, `atomic_file.rs`, `utc_date.rs`, `hand_source.rs`, `library_log.rs`, `test_knob.rs`, `disk_wait.rs` | the station's one clock (wall-anchored, monotonic); sample statistics; progress on stderr (bar on a terminal, lines in logs); temp + rename writes; dates; where a hand model comes from; the libraries' log records (errors, on stderr); test-only delays read from the environment; disk work inside a task without holding the runtime's other tasks |

pub mod atomic_file;
pub mod calibrate;
pub mod clock;
pub mod command;
pub mod console;
pub mod demo;
pub mod device_thread;
pub mod disk_wait;
pub mod eval;
pub mod eval_modes;
pub mod fnv;
pub mod hand_check;
pub mod hand_source;
pub mod ingress;
pub mod launch_config;
pub mod library_log;
pub mod mcap_log;
pub mod model_report;
#[cfg(feature = "physics")]
pub mod physics;
pub mod progress_bar;
pub mod relay_node;
pub mod replay;
pub mod resim;
pub mod ros;
pub mod samples;
pub mod score;
#[cfg(feature = "physics")]
pub mod sim_bench;
#[cfg(feature = "physics")]
pub mod sim_runs;
pub mod stand_ins;
pub mod station_driver;
pub mod station_node;
pub mod station_topics;
pub mod study_logs;
pub mod test_knob;
pub mod trial_review;
pub mod tui;
pub mod utc_date;
pub mod view;
