//! What a fuzz run did and found: per invariant, how often it was checked and violated; per
//! kind of event, how often it happened; the first violations in words.

use std::collections::BTreeMap;
use std::fmt;

/// Violations kept in words (the counts go on).
const KEPT_VIOLATIONS: usize = 20;

/// Checks and violations of one invariant.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CheckCount {
    /// Times it was checked.
    pub checks: u64,
    /// Times it did not hold.
    pub violations: u64,
}

/// The counts of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tally {
    /// Per invariant.
    pub invariants: BTreeMap<&'static str, CheckCount>,
    /// Per kind of event (inputs fed, verdicts, outputs, state changes).
    pub events: BTreeMap<String, u64>,
    /// The first violations, in words (step number, invariant, detail).
    pub first_violations: Vec<String>,
}

impl Tally {
    /// Check `invariant` once: `holds`, or a violation described by `detail` (called only
    /// then).
    pub fn check(
        &mut self,
        step: u64,
        invariant: &'static str,
        holds: bool,
        detail: impl FnOnce() -> String,
    ) {
        let count = self.invariants.entry(invariant).or_default();
        count.checks += 1;
        if !holds {
            count.violations += 1;
            if self.first_violations.len() < KEPT_VIOLATIONS {
                self.first_violations
                    .push(format!("step {step}: {invariant}: {}", detail()));
            }
        }
    }

    /// Count one event of kind `kind`.
    pub fn count(&mut self, kind: &str) {
        self.add(kind, 1);
    }

    /// Count `n` events of kind `kind`.
    pub fn add(&mut self, kind: &str, n: u64) {
        if let Some(v) = self.events.get_mut(kind) {
            *v += n;
        } else {
            self.events.insert(kind.to_string(), n);
        }
    }

    /// How many events of kind `kind` happened.
    pub fn event(&self, kind: &str) -> u64 {
        self.events.get(kind).copied().unwrap_or(0)
    }

    /// Violations of every invariant together.
    pub fn violations(&self) -> u64 {
        self.invariants.values().map(|c| c.violations).sum()
    }

    /// Checks of every invariant together.
    pub fn checks(&self) -> u64 {
        self.invariants.values().map(|c| c.checks).sum()
    }

    /// Add another run's counts to these.
    pub fn merge(&mut self, other: &Tally) {
        for (name, c) in &other.invariants {
            let mine = self.invariants.entry(name).or_default();
            mine.checks += c.checks;
            mine.violations += c.violations;
        }
        for (kind, n) in &other.events {
            self.add(kind, *n);
        }
        let room = KEPT_VIOLATIONS.saturating_sub(self.first_violations.len());
        self.first_violations
            .extend(other.first_violations.iter().take(room).cloned());
    }
}

impl fmt::Display for Tally {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "invariants (checks, violations):")?;
        for (name, c) in &self.invariants {
            writeln!(f, "  {name:<28} {:>10} {:>6}", c.checks, c.violations)?;
        }
        writeln!(f, "events:")?;
        for (kind, n) in &self.events {
            writeln!(f, "  {kind:<40} {n:>10}")?;
        }
        writeln!(
            f,
            "total: {} checks, {} violations",
            self.checks(),
            self.violations()
        )?;
        for v in &self.first_violations {
            writeln!(f, "VIOLATION {v}")?;
        }
        Ok(())
    }
}
