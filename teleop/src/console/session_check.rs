//! A session's options checked before anything is loaded: the names that go into file names,
//! the ranges of the console's settings and the simulated hand, and no calibration profile
//! for a human-study session.

use super::session_dir::check_name;
use super::session_error::SessionError;
use super::session_options::SessionOptions;

/// The names and ranges of the options (named by their flags).
pub(super) fn check_options(args: &SessionOptions) -> Result<(), SessionError> {
    check_name("--user", &args.user)?;
    check_name("--operator", &args.operator)?;
    check_name("--embodiment", &args.embodiment)?;
    if args.human() && args.profile.is_some() {
        return Err(SessionError::ProfileForHuman);
    }
    if let Some(scale) = args.simulated_hand_scale {
        check_range(
            "--simulate-hand-scale",
            scale,
            (0.5, 2.0),
            "(relative hand size)",
        )?;
    }
    let console = &args.console;
    check_range("--countdown", console.countdown, (0.0, 30.0), "s")?;
    check_range(
        "--min-glove-rate",
        console.min_glove_rate,
        (0.0, 1000.0),
        "Hz",
    )?;
    check_range(
        "--max-input-age",
        console.max_input_age,
        (10.0, 10_000.0),
        "ms",
    )
}

/// `value` finite and within `[low, high]`.
fn check_range(
    flag: &'static str,
    value: f64,
    (low, high): (f64, f64),
    unit: &'static str,
) -> Result<(), SessionError> {
    if value.is_finite() && value >= low && value <= high {
        Ok(())
    } else {
        Err(SessionError::OutOfRange {
            flag,
            value,
            low,
            high,
            unit,
        })
    }
}
