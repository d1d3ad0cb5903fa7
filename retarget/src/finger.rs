//! The five digits, shared by human keypoint layouts and robot hand models.

use serde::{Deserialize, Serialize};

/// A digit of the hand. The robot's "pinky" is the human's [`Finger::Little`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Finger {
    /// The thumb.
    Thumb,
    /// The index finger.
    Index,
    /// The middle finger.
    Middle,
    /// The ring finger.
    Ring,
    /// The little finger (ORCA: pinky).
    Little,
}

impl Finger {
    /// All five digits, thumb first, in anatomical order.
    pub const ALL: [Finger; 5] = [
        Finger::Thumb,
        Finger::Index,
        Finger::Middle,
        Finger::Ring,
        Finger::Little,
    ];

    /// The four fingers that oppose the thumb.
    pub const OPPOSING: [Finger; 4] = [Finger::Index, Finger::Middle, Finger::Ring, Finger::Little];

    /// Position in [`Finger::ALL`].
    pub const fn index(self) -> usize {
        match self {
            Finger::Thumb => 0,
            Finger::Index => 1,
            Finger::Middle => 2,
            Finger::Ring => 3,
            Finger::Little => 4,
        }
    }

    /// Lower-case name, as used in configuration and model files.
    pub const fn name(self) -> &'static str {
        match self {
            Finger::Thumb => "thumb",
            Finger::Index => "index",
            Finger::Middle => "middle",
            Finger::Ring => "ring",
            Finger::Little => "little",
        }
    }
}

impl std::fmt::Display for Finger {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_matches_position_in_all() {
        for (i, finger) in Finger::ALL.iter().enumerate() {
            assert_eq!(finger.index(), i, "{finger}");
        }
        assert!(!Finger::OPPOSING.contains(&Finger::Thumb));
    }
}
