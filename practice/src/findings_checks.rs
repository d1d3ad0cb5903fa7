//! [`check_findings`]: eight checks, one per finding of the paper's results text.

use scoring::Configuration;

use crate::findings::{Evidence, Finding, Verdict};

/// The paper's embodiments, fewest degrees of freedom first.
pub const PAPER_EMBODIMENTS: [&str; 4] = ["orca_2", "orca_3", "orca_5", "orca_full"];
/// Tasks the paper says need thumb or multi-finger abduction: chopsticks, squeeze, palmar.
pub const ABDUCTION_TASKS: [&str; 3] = ["H2", "H3", "H4"];
/// Tasks the paper says every embodiment does alike: scissors, thread, pinch.
pub const ALIKE_TASKS: [&str; 3] = ["H1", "C1", "H5"];
/// The continuous tasks behind a gravity clutch (C4, the spinner, has none).
pub const CLUTCH_TASKS: [&str; 3] = ["C1", "C2", "C3"];
/// Largest spread of a task's value across embodiments that still counts as alike.
pub const ALIKE_SPREAD: f64 = 0.1;
/// Smallest overall gain that counts as large; smaller differences count as little.
pub const LARGE_GAIN: f64 = 0.05;

/// Every finding, in the paper's order.
pub fn check_findings(evidence: &Evidence<'_>) -> Vec<Finding> {
    vec![
        abduction_tasks(evidence),
        done_alike(evidence),
        everyone_grasps(evidence),
        dexterity_on_small_objects(evidence),
        two_to_three_fingers(evidence),
        three_to_five_fingers(evidence),
        rotation_hardest(evidence),
        ranking_by_dof(evidence),
    ]
}

fn finding(id: &str, claim: &str, verdict: Verdict, why: String) -> Finding {
    Finding {
        id: id.to_string(),
        claim: claim.to_string(),
        verdict,
        why,
    }
}

fn not_tested(id: &str, claim: &str, missing: &str) -> Finding {
    finding(id, claim, Verdict::NotTested, format!("not run: {missing}"))
}

/// Tasks that need abduction are feasible only for the embodiments that have it.
pub fn abduction_tasks(e: &Evidence<'_>) -> Finding {
    const ID: &str = "abduction_tasks";
    const CLAIM: &str = "Tasks that need thumb or multi-finger abduction (H2 chopsticks, H3 squeeze, H4 palmar) are feasible only for the embodiments that have it.";
    let mut parts = Vec::new();
    let mut held = true;
    for task in ABDUCTION_TASKS {
        for embodiment in e.embodiments() {
            let Some(c) = e.cell(embodiment, task) else {
                continue;
            };
            let feasible = c.completed > 0;
            let with = e.abduction.contains(embodiment);
            held &= feasible == with;
            parts.push(format!(
                "{task} {embodiment} ({}): completed {}/{}",
                if with { "abduction" } else { "no abduction" },
                c.completed,
                c.runs
            ));
        }
    }
    let both_kinds = e.embodiments().iter().any(|x| e.abduction.contains(*x))
        && e.embodiments().iter().any(|x| !e.abduction.contains(*x));
    if parts.is_empty() || !both_kinds {
        return not_tested(
            ID,
            CLAIM,
            "H2–H4 with embodiments both with and without abduction",
        );
    }
    finding(ID, CLAIM, Verdict::of(held), parts.join("; "))
}

/// Scissors, thread and pinch are done alike by every embodiment and score alike.
pub fn done_alike(e: &Evidence<'_>) -> Finding {
    const ID: &str = "done_alike";
    const CLAIM: &str = "Scissors (H1), thread (C1) and pinch (H5) are done the same way by every embodiment and score alike.";
    let mut parts = Vec::new();
    let mut held = true;
    for task in ALIKE_TASKS {
        let values: Vec<(&str, f64)> = e
            .embodiments()
            .into_iter()
            .filter_map(|x| e.cell(x, task).map(|c| (x, c.value)))
            .collect();
        if values.len() < 2 {
            continue;
        }
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (_, v)| {
                (lo.min(*v), hi.max(*v))
            });
        held &= hi - lo <= ALIKE_SPREAD;
        let listed: Vec<String> = values.iter().map(|(x, v)| format!("{x} {v:.2}")).collect();
        parts.push(format!(
            "{task}: {} (spread {:.2})",
            listed.join(", "),
            hi - lo
        ));
    }
    if parts.is_empty() {
        return not_tested(ID, CLAIM, "H1, C1 or H5 with two embodiments or more");
    }
    let why = format!(
        "{} per task, alike within {ALIKE_SPREAD}: {}",
        e.measure,
        parts.join("; ")
    );
    finding(ID, CLAIM, Verdict::of(held), why)
}

/// Every embodiment grasps the G objects.
pub fn everyone_grasps(e: &Evidence<'_>) -> Finding {
    const ID: &str = "everyone_grasps";
    const CLAIM: &str = "Every embodiment grasps the G objects.";
    let mut failures = Vec::new();
    let mut cells = 0;
    for task in e.tasks_of(Configuration::Grasp) {
        for embodiment in e.embodiments() {
            if let Some(c) = e.cell(embodiment, task) {
                cells += 1;
                if c.completed == 0 {
                    failures.push(format!(
                        "{embodiment} never relocated {task} (0/{})",
                        c.runs
                    ));
                }
            }
        }
    }
    if cells == 0 {
        return not_tested(ID, CLAIM, "no G task");
    }
    let why = if failures.is_empty() {
        format!(
            "every embodiment relocated every G object it tried at least once ({cells} embodiment × task pairs)"
        )
    } else {
        failures.join("; ")
    };
    finding(ID, CLAIM, Verdict::of(failures.is_empty()), why)
}

/// More dexterity improves grasp stability and speed, most of all for small objects.
pub fn dexterity_on_small_objects(e: &Evidence<'_>) -> Finding {
    const ID: &str = "dexterity_on_small_objects";
    const CLAIM: &str = "More dexterity improves grasp stability and speed, most of all for small objects (G4, the small cylinder, against G6, the large one).";
    let ran: Vec<&str> = PAPER_EMBODIMENTS
        .into_iter()
        .filter(|x| e.embodiments().contains(x))
        .collect();
    let (Some(&least), Some(&most)) = (ran.first(), ran.last()) else {
        return not_tested(ID, CLAIM, "two of the paper's embodiments");
    };
    let gain =
        |task: &str| Some(e.cell(most, task)?.completion() - e.cell(least, task)?.completion());
    let time = |x: &str, task: &str| e.cell(x, task).and_then(|c| c.completed_time_s);
    let (Some(small), Some(large)) = (gain("G4"), gain("G6")) else {
        return not_tested(ID, CLAIM, &format!("G4 and G6 with {least} and {most}"));
    };
    if least == most {
        return not_tested(ID, CLAIM, "two of the paper's embodiments");
    }
    let faster = match (time(most, "G4"), time(least, "G4")) {
        (Some(m), Some(l)) => Some(m <= l),
        _ => None,
    };
    let held = small >= 0.0 && small >= large && faster != Some(false);
    let why = format!(
        "{most} − {least} completion: G4 {:+.0} points, G6 {:+.0} points; G4 completion time {most} {} / {least} {}",
        small * 100.0,
        large * 100.0,
        time(most, "G4").map_or("-".into(), |t| format!("{t:.1} s")),
        time(least, "G4").map_or("-".into(), |t| format!("{t:.1} s")),
    );
    finding(ID, CLAIM, Verdict::of(held), why)
}

fn overall_gain(e: &Evidence<'_>, from: &str, to: &str) -> Option<(f64, f64, usize)> {
    let common = e.common_tasks(&[from, to]);
    let grasp: Vec<&str> = common
        .iter()
        .copied()
        .filter(|t| e.tasks_of(Configuration::Grasp).contains(t))
        .collect();
    let gain = e.mean_value(to, &common)? - e.mean_value(from, &common)?;
    let grasp_gain = match (e.mean_value(to, &grasp), e.mean_value(from, &grasp)) {
        (Some(a), Some(b)) => (a - b) * grasp.len() as f64 / common.len() as f64,
        _ => 0.0,
    };
    Some((gain, grasp_gain, common.len()))
}

/// Two to three fingers: a large gain, mostly in grasp stability.
pub fn two_to_three_fingers(e: &Evidence<'_>) -> Finding {
    const ID: &str = "two_to_three_fingers";
    const CLAIM: &str = "Going from two to three fingers (orca_2 → orca_3) gives a large gain, mostly in grasp stability.";
    let Some((gain, grasp_gain, n)) = overall_gain(e, "orca_2", "orca_3") else {
        return not_tested(ID, CLAIM, "orca_2 and orca_3 on common tasks");
    };
    let held = gain >= LARGE_GAIN && grasp_gain >= gain / 2.0;
    let why = format!(
        "overall {} gain {gain:+.3} over {n} common tasks (large: ≥ {LARGE_GAIN}), of which the G tasks give {grasp_gain:+.3}",
        e.measure
    );
    finding(ID, CLAIM, Verdict::of(held), why)
}

/// Three to five fingers without abduction: little gain.
pub fn three_to_five_fingers(e: &Evidence<'_>) -> Finding {
    const ID: &str = "three_to_five_fingers";
    const CLAIM: &str =
        "Going from three to five fingers without abduction (orca_3 → orca_5) gives little.";
    let Some((gain, _, n)) = overall_gain(e, "orca_3", "orca_5") else {
        return not_tested(ID, CLAIM, "orca_3 and orca_5 on common tasks");
    };
    let why = format!(
        "overall {} change {gain:+.3} over {n} common tasks (little: under {LARGE_GAIN})",
        e.measure
    );
    finding(ID, CLAIM, Verdict::of(gain.abs() < LARGE_GAIN), why)
}

/// The continuous rotation tasks are the hardest, especially those with the gravity clutch.
pub fn rotation_hardest(e: &Evidence<'_>) -> Finding {
    const ID: &str = "rotation_hardest";
    const CLAIM: &str = "The continuous rotation tasks are the hardest, especially those with the gravity clutch (C1–C3).";
    let group = |tasks: Vec<&str>| {
        let values: Vec<f64> = e
            .embodiments()
            .into_iter()
            .flat_map(|x| tasks.iter().filter_map(move |t| e.cell(x, t)))
            .map(|c| c.value)
            .collect();
        (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
    };
    let Some(rotation) = group(e.tasks_of(Configuration::Continuous)) else {
        return not_tested(ID, CLAIM, "no C task");
    };
    let others: Vec<(&str, f64)> = [
        ("V", Configuration::Vertical),
        ("H", Configuration::Horizontal),
        ("G", Configuration::Grasp),
    ]
    .into_iter()
    .filter_map(|(name, c)| group(e.tasks_of(c)).map(|v| (name, v)))
    .collect();
    if others.is_empty() {
        return not_tested(ID, CLAIM, "a V, H or G task to compare with");
    }
    let clutch = group(CLUTCH_TASKS.to_vec());
    let spinner = group(vec!["C4"]);
    let hardest = others.iter().all(|(_, v)| rotation < *v);
    let clutch_harder = match (clutch, spinner) {
        (Some(c), Some(s)) => c <= s,
        _ => true,
    };
    let listed: Vec<String> = others.iter().map(|(n, v)| format!("{n} {v:.2}")).collect();
    let why = format!(
        "mean {}: C {rotation:.2} against {}; clutch C1–C3 {} against C4 {}",
        e.measure,
        listed.join(", "),
        clutch.map_or("-".into(), |v| format!("{v:.2}")),
        spinner.map_or("-".into(), |v| format!("{v:.2}")),
    );
    finding(ID, CLAIM, Verdict::of(hardest && clutch_harder), why)
}

/// The ranking follows the degrees of freedom.
pub fn ranking_by_dof(e: &Evidence<'_>) -> Finding {
    const ID: &str = "ranking_by_dof";
    const CLAIM: &str =
        "The ranking follows the degrees of freedom: orca_2 < orca_3 < orca_5 < orca_full.";
    let ran: Vec<&str> = PAPER_EMBODIMENTS
        .into_iter()
        .filter(|x| e.embodiments().contains(x))
        .collect();
    if ran.len() < 2 {
        return not_tested(ID, CLAIM, "two of the paper's embodiments");
    }
    let common = e.common_tasks(&ran);
    let values: Vec<Option<f64>> = ran.iter().map(|x| e.mean_value(x, &common)).collect();
    if common.is_empty() || values.iter().any(Option::is_none) {
        return not_tested(ID, CLAIM, "a task every embodiment ran");
    }
    let values: Vec<f64> = values.into_iter().flatten().collect();
    let held = values.windows(2).all(|w| w[0] < w[1]);
    let listed: Vec<String> = ran
        .iter()
        .zip(&values)
        .map(|(x, v)| format!("{x} {v:.3}"))
        .collect();
    let why = format!(
        "overall {} over the {} tasks all ran: {}",
        e.measure,
        common.len(),
        listed.join(" · ")
    );
    finding(ID, CLAIM, Verdict::of(held), why)
}
