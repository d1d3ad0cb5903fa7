//! What `pomdar sim` prints and the small pieces of its runs: the real-time run in one line,
//! a lock-step run's events, several runs' spread, a run's moved start, and the shutdown after
//! `--duration`.

use super::SimRequest;
use super::lockstep_runs::LockstepRun;
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

/// A single run: its events and a summary line.
pub(super) fn print_run(run: &LockstepRun) {
    let (task, outcome) = (&run.task, &run.outcome);
    for event in &outcome.events {
        let value = event.value.map_or(String::new(), |v| format!(" {v}"));
        println!(
            "{:>7.2} s  {}{value} {}",
            event.sim_time_s, event.event, event.unit
        );
    }
    println!(
        "{} ({}): progress {} {}, correctness {:.3} over {:.1} simulated s ({} hand commands, {} arm targets)",
        task.id,
        task.name,
        outcome.progress,
        task.correctness.progress_unit(),
        run.correctness,
        outcome.sim_time_s,
        outcome.hand_commands,
        outcome.arm_targets
    );
}

/// Several runs: how many scored correctness 1, and when the successful ones were done.
pub(super) fn print_spread(completions: &[Option<f64>], args: &SimRequest, jitter_m: f64) {
    let mut done: Vec<f64> = completions.iter().flatten().copied().collect();
    done.sort_by(f64::total_cmp);
    let spread = match (done.first(), done.last()) {
        (Some(min), Some(max)) => format!(
            "; done at {min:.2} / {:.2} / {max:.2} s (min / median / max)",
            done[done.len() / 2]
        ),
        _ => String::new(),
    };
    let starts = if args.perturb_start {
        ", starts moved up to 5 mm and 3°"
    } else {
        ""
    };
    println!(
        "correctness 1 in {} of {} runs (seeds {}–{}, glove noise {:.1} mm{starts}){spread}",
        done.len(),
        completions.len(),
        args.seed,
        args.seed.wrapping_add(args.runs - 1),
        jitter_m * 1e3
    );
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
