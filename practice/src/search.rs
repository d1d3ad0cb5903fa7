//! [`CrossEntropySearch`]: the seeded cross-entropy method over a box of continuous parameters
//! and one categorical choice, with a fixed budget of noisy evaluations.
//!
//! Each evaluation is one practice trial: one seed of glove noise and start pose, so one score
//! is one noisy draw. The search
//!
//! 1. explores in generations: the first candidate of the first generation is the start point
//!    (the script as written), the rest are drawn from a Gaussian per dimension (clamped to the
//!    box) and a categorical distribution; after each generation the distributions move 70 %
//!    of the way to the elite (the best 30 % of the generation and the best so far);
//! 2. confirms (a budget of 6 or more): half the budget goes to more trials, in turn, of the
//!    start point and of the best other candidate found, so that a few lucky draws do not win
//!    alone: the start point (the script as written, found by a person over many runs) is the
//!    yardstick a new strategy must beat over as many trials as it has;
//! 3. answers with the confirmed candidate of the highest mean score (without confirmation:
//!    the candidate of the highest score; ties: the one tried first).
//!
//! The caller asks for a candidate, plays it, and tells the score, until `ask` says `None`.
//! The same seed and the same scores give the same candidates.

use retarget::human_hand::SplitMix64;

/// One continuous dimension: its range and the start point's value in it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dimension {
    /// Lowest value.
    pub low: f64,
    /// Highest value.
    pub high: f64,
    /// The start point's value.
    pub start: f64,
}

impl Dimension {
    /// `[low, high]` starting at `start` (clamped into it).
    pub fn new(low: f64, high: f64, start: f64) -> Dimension {
        Dimension {
            low,
            high,
            start: start.clamp(low, high),
        }
    }

    fn width(&self) -> f64 {
        self.high - self.low
    }
}

/// The continuous box and the number of categories (category 0 is the start point's).
#[derive(Debug, Clone, PartialEq)]
pub struct SearchSpace {
    /// The continuous dimensions.
    pub dimensions: Vec<Dimension>,
    /// Number of categories, at least 1.
    pub categories: usize,
}

/// A point of the space.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// One value per dimension.
    pub x: Vec<f64>,
    /// The category.
    pub category: usize,
}

/// A candidate tried, with its scores.
#[derive(Debug, Clone, PartialEq)]
pub struct Tried {
    /// The candidate.
    pub candidate: Candidate,
    /// Its trials' scores, in order.
    pub scores: Vec<f64>,
}

impl Tried {
    /// The mean score.
    pub fn mean(&self) -> f64 {
        self.scores.iter().sum::<f64>() / self.scores.len().max(1) as f64
    }
}

/// Share of a distribution's move towards the elite per generation.
const STEP: f64 = 0.7;
/// Share of a generation in the elite.
const ELITE_SHARE: f64 = 0.3;
/// The smallest spread, as a share of a dimension's width.
const MIN_SPREAD: f64 = 0.02;
/// The smallest probability of a category.
const MIN_PROBABILITY: f64 = 0.05;

/// The search (see the module documentation).
#[derive(Debug, Clone)]
pub struct CrossEntropySearch {
    space: SearchSpace,
    rng: SplitMix64,
    mean: Vec<f64>,
    spread: Vec<f64>,
    probabilities: Vec<f64>,
    population: usize,
    explore_left: usize,
    confirm: usize,
    /// Indices into `tried` of the current generation, and the next to hand out.
    generation: Vec<usize>,
    pending: Option<usize>,
    queue: Vec<usize>,
    confirming: bool,
    confirmed: Vec<usize>,
    tried: Vec<Tried>,
}

impl CrossEntropySearch {
    /// A search of `budget` trials over `space`, drawn from `seed`.
    pub fn new(space: SearchSpace, budget: usize, seed: u64) -> CrossEntropySearch {
        let confirm = if budget >= 6 { budget / 2 } else { 0 };
        let explore = budget - confirm;
        let categories = space.categories.max(1);
        let mut probabilities = vec![0.5 / (categories - 1).max(1) as f64; categories];
        probabilities[0] = if categories == 1 { 1.0 } else { 0.5 };
        CrossEntropySearch {
            mean: space.dimensions.iter().map(|d| d.start).collect(),
            spread: space.dimensions.iter().map(|d| d.width() / 4.0).collect(),
            probabilities,
            population: (explore / 3).clamp(4, 10),
            explore_left: explore,
            confirm,
            rng: SplitMix64::new(seed),
            space,
            generation: Vec::new(),
            pending: None,
            queue: Vec::new(),
            confirming: false,
            confirmed: Vec::new(),
            tried: Vec::new(),
        }
    }

    /// The next candidate to try, or `None` when the budget is spent. Each candidate asked
    /// must be told its score before the next is asked.
    pub fn ask(&mut self) -> Option<Candidate> {
        if self.pending.is_some() {
            return None;
        }
        if self.queue.is_empty() {
            self.refill();
        }
        let index = self.queue.pop()?;
        self.pending = Some(index);
        Some(self.tried[index].candidate.clone())
    }

    /// The score of the candidate last asked.
    pub fn tell(&mut self, score: f64) {
        let Some(index) = self.pending.take() else {
            return;
        };
        self.tried[index].scores.push(score);
        if !self.confirming && self.queue.is_empty() {
            self.update_distributions();
        }
    }

    /// Everything tried, in the order first tried.
    pub fn tried(&self) -> &[Tried] {
        &self.tried
    }

    /// The best candidate so far: the highest mean score among the confirmed candidates once
    /// there are some, else among all (ties: the one tried first).
    pub fn best(&self) -> Option<&Tried> {
        self.tried
            .iter()
            .enumerate()
            .filter(|(i, t)| {
                !t.scores.is_empty() && (self.confirmed.is_empty() || self.confirmed.contains(i))
            })
            .map(|(_, t)| t)
            .fold(None, |best: Option<&Tried>, t| match best {
                Some(b) if b.mean() >= t.mean() => Some(b),
                _ => Some(t),
            })
    }

    /// Queues the next generation, or the confirmations once exploring is done.
    fn refill(&mut self) {
        if self.explore_left > 0 {
            let size = self.population.min(self.explore_left);
            self.explore_left -= size;
            let first = self.tried.is_empty();
            self.generation.clear();
            for k in 0..size {
                let candidate = if first && k == 0 {
                    self.start_point()
                } else {
                    self.draw()
                };
                self.generation.push(self.tried.len());
                self.tried.push(Tried {
                    candidate,
                    scores: Vec::new(),
                });
            }
            // Handed out in order: the start point first.
            self.queue = self.generation.iter().rev().copied().collect();
        } else if !self.confirming && self.confirm > 0 {
            self.confirming = true;
            // The start point (tried first) and the best of the others.
            let mut others: Vec<usize> = (1..self.tried.len()).collect();
            others.sort_by(|&a, &b| self.tried[b].mean().total_cmp(&self.tried[a].mean()));
            let mut confirmed = vec![0];
            confirmed.extend(others.first());
            let turns: Vec<usize> = confirmed
                .iter()
                .copied()
                .cycle()
                .take(self.confirm)
                .collect();
            self.confirmed = confirmed;
            self.queue = turns.into_iter().rev().collect();
        }
    }

    fn start_point(&self) -> Candidate {
        Candidate {
            x: self.space.dimensions.iter().map(|d| d.start).collect(),
            category: 0,
        }
    }

    fn draw(&mut self) -> Candidate {
        let x = (0..self.space.dimensions.len())
            .map(|i| {
                let d = self.space.dimensions[i];
                (self.mean[i] + self.spread[i] * self.rng.next_gaussian()).clamp(d.low, d.high)
            })
            .collect();
        let u = self.rng.next_f64();
        let mut sum = 0.0;
        let mut category = self.probabilities.len() - 1;
        for (k, p) in self.probabilities.iter().enumerate() {
            sum += p;
            if u < sum {
                category = k;
                break;
            }
        }
        Candidate { x, category }
    }

    /// Moves the distributions towards the elite of the generation just scored.
    fn update_distributions(&mut self) {
        let mut elite: Vec<usize> = self.generation.clone();
        if let Some(best) = self.best_index()
            && !elite.contains(&best)
        {
            elite.push(best);
        }
        elite.sort_by(|&a, &b| self.tried[b].mean().total_cmp(&self.tried[a].mean()));
        let keep = ((self.generation.len() as f64 * ELITE_SHARE).ceil() as usize).max(2);
        elite.truncate(keep);
        let n = elite.len() as f64;
        for (i, d) in self.space.dimensions.iter().enumerate() {
            let values: Vec<f64> = elite
                .iter()
                .map(|&e| self.tried[e].candidate.x[i])
                .collect();
            let mean = values.iter().sum::<f64>() / n;
            let sd = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
            self.mean[i] += STEP * (mean - self.mean[i]);
            self.spread[i] =
                (self.spread[i] + STEP * (sd - self.spread[i])).max(MIN_SPREAD * d.width());
        }
        for (k, p) in self.probabilities.iter_mut().enumerate() {
            let share = elite
                .iter()
                .filter(|&&e| self.tried[e].candidate.category == k)
                .count() as f64
                / n;
            *p = (*p + STEP * (share - *p)).max(MIN_PROBABILITY);
        }
        let total: f64 = self.probabilities.iter().sum();
        self.probabilities.iter_mut().for_each(|p| *p /= total);
    }

    fn best_index(&self) -> Option<usize> {
        let best = self.best()?;
        self.tried.iter().position(|t| std::ptr::eq(t, best))
    }
}

#[cfg(test)]
#[path = "search_tests.rs"]
mod tests;
