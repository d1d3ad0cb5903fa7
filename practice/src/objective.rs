//! What practice maximises: a trial's POMDAR score.

use scoring::{Outcome, ScoringRules, TrialScore};

/// The score of one practice trial: its POMDAR score against the baseline, or — for a task the
/// baseline does not list — the same formula with `stand_in_baseline_s` (the length of the
/// task's script as written) in its place, so that practice still prefers the faster of two
/// strategies that both complete. An unfinished trial's speed is 0.
pub fn practice_score(trial: &TrialScore, rules: &ScoringRules, stand_in_baseline_s: f64) -> f64 {
    if let Some(score) = trial.score {
        return score;
    }
    let speed = if trial.outcome == Outcome::Completed && trial.time_s > 0.0 {
        stand_in_baseline_s / trial.time_s
    } else {
        0.0
    };
    rules.correctness_weight * trial.correctness + rules.speed_weight * speed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trial(correctness: f64, time_s: f64, outcome: Outcome, score: Option<f64>) -> TrialScore {
        TrialScore {
            file: "t.mcap".into(),
            task: "G4".into(),
            embodiment: "orca_2".into(),
            user: None,
            operator: None,
            trial_index: None,
            metadata: Default::default(),
            practice: true,
            outcome,
            time_s,
            progress: correctness,
            correctness,
            speed: None,
            score,
            counted: false,
            notes: Vec::new(),
        }
    }

    #[test]
    fn the_baseline_score_wins_and_the_stand_in_prefers_the_faster_finish() {
        let rules = ScoringRules::default();
        assert_eq!(
            practice_score(
                &trial(1.0, 10.0, Outcome::Completed, Some(0.93)),
                &rules,
                5.0
            ),
            0.93
        );
        let slow = practice_score(&trial(1.0, 10.0, Outcome::Completed, None), &rules, 10.0);
        let fast = practice_score(&trial(1.0, 8.0, Outcome::Completed, None), &rules, 10.0);
        assert!((slow - 1.0).abs() < 1e-12 && fast > slow, "{slow} {fast}");
        let aborted = practice_score(&trial(0.5, 3.0, Outcome::Aborted, None), &rules, 10.0);
        assert!((aborted - 0.4).abs() < 1e-12, "{aborted}");
    }
}
