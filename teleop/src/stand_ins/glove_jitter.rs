//! The simulated glove's keypoint noise as the commands that run it ask for it
//! (`--glove-jitter-mm`, `--simulate-glove-jitter-mm`): checked, in metres, with the default for
//! a periodic motion or a task script.

use super::SimError;
use super::sim_glove_node::{REST_JITTER_M, SimGloveConfig};

/// The glove's keypoint noise, metres: `jitter_mm`, else 1 mm, or the noise of a hand at rest
/// for a script.
pub fn glove_jitter_m(jitter_mm: Option<f64>, scripted: bool) -> Result<f64, SimError> {
    match jitter_mm {
        Some(mm) if !(0.0..=50.0).contains(&mm) => Err(SimError::GloveJitter { mm }),
        Some(mm) => Ok(mm * 1e-3),
        // A worn glove is never perfectly still: a script's still phases carry the noise of a
        // hand at rest, or the station would take their identical frames for a stalled stream
        // and release the arm after its disengage timeout.
        None if scripted => Ok(REST_JITTER_M),
        None => Ok(SimGloveConfig::default().jitter_m),
    }
}
