//! The benchmark's work: one item per embodiment and task, in a fixed order, and the share of
//! it a shard (`K/N`) does, so that a batch scheduler can spread it over machines.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// One embodiment on one task: practice, then the recorded runs.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct WorkItem {
    /// Its place in the whole plan (0-based).
    pub index: usize,
    /// The embodiment.
    pub embodiment: String,
    /// The task ID.
    pub task: String,
}

/// The whole plan: embodiments in the order given, each over the tasks in the order given.
pub fn plan(embodiments: &[String], tasks: &[String]) -> Vec<WorkItem> {
    embodiments
        .iter()
        .flat_map(|e| tasks.iter().map(move |t| (e, t)))
        .enumerate()
        .map(|(index, (e, t))| WorkItem {
            index,
            embodiment: e.clone(),
            task: t.clone(),
        })
        .collect()
}

/// Shard `k` of `n` (1-based): the items whose index is `k − 1` modulo `n`, so every shard
/// gets a mix of embodiments and tasks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// This shard, 1 ≤ k ≤ n.
    pub k: usize,
    /// The number of shards.
    pub n: usize,
}

impl Shard {
    /// The whole plan.
    pub const WHOLE: Shard = Shard { k: 1, n: 1 };

    /// Whether `item` is this shard's.
    pub fn takes(&self, item: &WorkItem) -> bool {
        item.index % self.n == self.k - 1
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl FromStr for Shard {
    type Err = String;

    fn from_str(text: &str) -> Result<Shard, String> {
        let bad = || format!("'{text}': a shard is K/N with 1 ≤ K ≤ N ≤ 10000, e.g. 2/4");
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if k == 0 || k > n || n > 10_000 {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn shards_split_the_plan_into_disjoint_parts_that_cover_it() {
        let items = plan(
            &names(&["orca_2", "orca_full"]),
            &names(&["G4", "H5", "C1"]),
        );
        assert_eq!(items.len(), 6);
        assert_eq!(
            (items[4].embodiment.as_str(), items[4].task.as_str()),
            ("orca_full", "H5")
        );
        for n in 1..=7 {
            let mut seen = vec![0; items.len()];
            for k in 1..=n {
                let shard: Shard = format!("{k}/{n}").parse().unwrap();
                for item in items.iter().filter(|i| shard.takes(i)) {
                    seen[item.index] += 1;
                }
            }
            assert!(seen.iter().all(|&c| c == 1), "{n} shards: {seen:?}");
        }
    }

    #[test]
    fn a_shard_is_k_of_n() {
        assert_eq!("2/4".parse::<Shard>(), Ok(Shard { k: 2, n: 4 }));
        for bad in ["0/2", "3/2", "2", "a/b", "1/0", "1/20000"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        assert_eq!(Shard { k: 2, n: 4 }.to_string(), "2/4");
    }
}
