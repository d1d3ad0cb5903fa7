use super::*;

fn space() -> SearchSpace {
    SearchSpace {
        dimensions: vec![
            Dimension::new(-1.0, 1.0, 0.0),
            Dimension::new(0.5, 1.5, 1.0),
        ],
        categories: 3,
    }
}

/// A noisy objective with its best at x = (0.6, 0.7) in category 2.
fn objective(c: &Candidate, noise: f64) -> f64 {
    let d = (c.x[0] - 0.6).powi(2) + (c.x[1] - 0.7).powi(2);
    let bonus = if c.category == 2 { 0.3 } else { 0.0 };
    1.0 - d + bonus + noise
}

fn run(budget: usize, seed: u64) -> (CrossEntropySearch, usize) {
    let mut search = CrossEntropySearch::new(space(), budget, seed);
    let mut noise = SplitMix64::new(seed ^ 99);
    let mut asked = 0;
    while let Some(c) = search.ask() {
        asked += 1;
        for (x, d) in c.x.iter().zip(&space().dimensions) {
            assert!((d.low..=d.high).contains(x), "{x} outside");
        }
        search.tell(objective(&c, 0.05 * noise.next_gaussian()));
    }
    (search, asked)
}

#[test]
fn the_budget_is_spent_exactly_and_the_start_point_is_tried_first() {
    for budget in [1, 4, 7, 8, 24, 41] {
        let (search, asked) = run(budget, 3);
        assert_eq!(asked, budget);
        assert_eq!(
            search.tried()[0].candidate,
            Candidate {
                x: vec![0.0, 1.0],
                category: 0
            }
        );
    }
}

#[test]
fn it_improves_on_the_start_point_of_a_noisy_objective() {
    let start = objective(
        &Candidate {
            x: vec![0.0, 1.0],
            category: 0,
        },
        0.0,
    );
    let mut better = 0;
    for seed in 1..=10 {
        let (search, _) = run(40, seed);
        let best = search.best().unwrap();
        if objective(&best.candidate, 0.0) > start + 0.3 {
            better += 1;
        }
    }
    assert!(better >= 8, "improved in {better} of 10 seeds");
}

#[test]
fn the_same_seed_and_scores_give_the_same_search() {
    let (a, _) = run(24, 5);
    let (b, _) = run(24, 5);
    assert_eq!(a.tried(), b.tried());
    let (c, _) = run(24, 6);
    assert_ne!(a.tried(), c.tried());
}

#[test]
fn confirmation_retries_the_start_point_and_the_best_other_and_answers_the_best_mean() {
    let (search, _) = run(24, 2);
    let confirmed: Vec<&Tried> = search
        .tried()
        .iter()
        .filter(|t| t.scores.len() == 7)
        .collect();
    assert_eq!(
        confirmed.len(),
        2,
        "half of 24 confirms two candidates, six more trials each"
    );
    assert_eq!(
        confirmed[0].candidate,
        search.tried()[0].candidate,
        "the start point is one"
    );
    let best = search.best().unwrap();
    assert_eq!(best.scores.len(), 7, "the answer is a confirmed candidate");
    assert!(confirmed.iter().all(|t| t.mean() <= best.mean()));
}
