//! `pomdar sim --lockstep`: a glove script through the station core into the task's scene in
//! simulated time, once (its events and a summary) or over `--runs` consecutive seeds (a line
//! each and the spread of completion times).

use super::run_report::start_note;
use super::{SimRequest, SimRunError};
use crate::physics::lockstep::run_lockstep;
use crate::stand_ins::glove_script_file::load_glove_script;
use crate::stand_ins::sim_glove_node::SimGloveConfig;

/// One lock-step run: the task, what happened, and its correctness.
pub(super) struct LockstepRun {
    pub(super) task: scoring::TaskSpec,
    pub(super) outcome: crate::physics::lockstep::LockstepOutcome,
    pub(super) correctness: f64,
}

/// `--lockstep`: the script through the station core into the scene, in simulated time, once
/// or `--runs` times over consecutive seeds.
pub(super) fn lockstep(
    station: &station::StationConfig,
    model: &retarget::HandModel,
    load: &dyn Fn(
        u64,
    ) -> Result<
        crate::physics::setup::SimulatedTask,
        crate::physics::error::PhysicsError,
    >,
    script: &std::path::Path,
    args: &SimRequest,
) -> Result<(), SimRunError> {
    if !(1..=1000).contains(&args.runs) {
        return Err(SimRunError::Runs { runs: args.runs });
    }
    let script = load_glove_script(script)?;
    let jitter_m = crate::stand_ins::glove_jitter::glove_jitter_m(args.glove_jitter_mm, true)?;
    if args.runs == 1 {
        let run = lockstep_run(
            station,
            model,
            load(args.seed)?,
            &script,
            (jitter_m, args.seed),
            args,
        )?;
        print_run(&run);
        return Ok(());
    }
    let mut completions = Vec::new();
    for seed in (0..args.runs).map(|k| args.seed.wrapping_add(k)) {
        let run = lockstep_run(station, model, load(seed)?, &script, (jitter_m, seed), args)?;
        let completion = (run.correctness >= 1.0)
            .then(|| run.outcome.events.last().map(|e| e.sim_time_s))
            .flatten();
        println!(
            "seed {seed}: correctness {:.3}, progress {} {}{}{}",
            run.correctness,
            run.outcome.progress,
            run.task.correctness.progress_unit(),
            completion.map_or(String::new(), |t| format!(", done at {t:.2} s")),
            start_note(args.perturb_start, seed)
        );
        completions.push(completion);
    }
    print_spread(&completions, args, jitter_m);
    Ok(())
}

/// The script played once at `seed` with `jitter_m` of glove noise, scored.
fn lockstep_run(
    station: &station::StationConfig,
    model: &retarget::HandModel,
    loaded: crate::physics::setup::SimulatedTask,
    script: &retarget::human_hand::GloveScript,
    (jitter_m, seed): (f64, u64),
    args: &SimRequest,
) -> Result<LockstepRun, SimRunError> {
    let task = loaded.task.clone();
    let glove_config = SimGloveConfig {
        script: Some(script.clone()),
        jitter_m,
        seed,
        layout: station.retarget.layout,
        ..SimGloveConfig::default()
    };
    let duration_s = args.duration.unwrap_or(script.duration_s() + 2.0);
    let glove = glove_config.glove()?;
    let mut config = station.clone();
    crate::station_driver::constrain_for_task(&mut config, &task);
    let outcome = run_lockstep(
        &config,
        model,
        &glove,
        loaded,
        glove_config.rate_hz,
        duration_s,
    )?;
    let correctness = crate::demo::robot::physics_correctness(&task, &outcome.events)
        .map_err(|reason| SimRunError::Marks { reason })?;
    Ok(LockstepRun {
        task,
        outcome,
        correctness,
    })
}

/// A single run: its events and a summary line.
fn print_run(run: &LockstepRun) {
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
fn print_spread(completions: &[Option<f64>], args: &SimRequest, jitter_m: f64) {
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
