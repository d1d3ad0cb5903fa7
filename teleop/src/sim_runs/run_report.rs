//! The small pieces of `pomdar sim`'s runs: the real-time run in one line, a run's moved start
//! and its note, and the shutdown after `--duration`.

use crate::physics::robot_node::PhysicsRobotReport;

/// The run in one line: time simulated, real-time factor, targets, progress.
pub(super) fn summary_line(r: &PhysicsRobotReport) -> String {
    let factor = if r.step_wall_s > 0.0 {
        r.sim_time_s / r.step_wall_s
    } else {
        0.0
    };
    format!(
        "simulated {:.1} s ({factor:.1}× real time while stepping, {:.2} s behind); {} hand and {} arm targets; progress {} ({} events)",
        r.sim_time_s,
        r.behind_s,
        r.hand_targets,
        r.arm_targets,
        r.progress_total,
        r.events.len()
    )
}

/// A shutdown signal that turns true after `seconds` or on Ctrl-C.
pub(super) fn timed_shutdown(seconds: f64) -> tokio::sync::watch::Receiver<bool> {
    let (tx, rx) = tokio::sync::watch::channel(false);
    let mut ctrl_c = crate::tui::terminal_shell::ctrl_c_shutdown();
    tokio::spawn(async move {
        let wait = std::time::Duration::from_secs_f64(seconds.max(0.0));
        tokio::select! {
            _ = tokio::time::sleep(wait) => {}
            _ = ctrl_c.changed() => {}
        }
        tx.send(true).ok();
    });
    rx
}

/// The move of a run's start: drawn from its seed with `--perturb-start`, else none.
pub(super) fn start_move(perturb: bool, seed: u64) -> simulation::scene::StartPerturbation {
    use simulation::scene::StartPerturbation;
    if perturb {
        StartPerturbation::from_seed(seed)
    } else {
        StartPerturbation::NONE
    }
}

/// `" (start +1.2, −4.0 mm, +0.8°)"` for a moved start, else nothing.
pub(super) fn start_note(perturb: bool, seed: u64) -> String {
    if !perturb {
        return String::new();
    }
    let start = start_move(true, seed);
    format!(
        " (start {:+.1}, {:+.1} mm, {:+.1}°)",
        start.offset_m[0] * 1e3,
        start.offset_m[1] * 1e3,
        start.yaw_rad.to_degrees()
    )
}
