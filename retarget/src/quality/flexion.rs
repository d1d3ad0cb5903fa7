//! Flexion of each digit, the human–robot correlation of it, and the frame shift that best
//! aligns the robot's flexion with the human's (see [`super`] for the definitions).
//!
//! Flexion is the distance from the palm-frame origin to the fingertip, each side in its own
//! palm frame: it shrinks as a finger curls and, for the thumb, as it opposes. A Pearson
//! correlation ignores each side's offset and scale, so a smaller or larger human hand does
//! not change it.

use super::FrameSample;
use crate::finger::Finger;

/// Largest shift tried when aligning the robot's flexion with the human's, frames either way
/// (0.125 s at 120 Hz, 0.25 s at 60 Hz).
pub const LAG_MAX_FRAMES: usize = 15;

/// Fewest frame pairs a correlation is computed from.
pub const CORRELATION_MIN_FRAMES: usize = 3;

/// Standard deviation under which a flexion series counts as constant (correlation `None`),
/// metres. Well above rounding (a finger the robot holds still varies by ~1e-17 m when the
/// wrist moves), well below any real motion.
pub const FLEXION_MIN_STD_M: f64 = 1e-6;

/// The best alignment of the robot's flexion with the human's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Lag {
    /// Shift `k`: human at frame `t` pairs with robot at frame `t + k`; positive = robot behind.
    pub frames: i64,
    /// Mean of `t_{t+k} − t_t` over the paired frames, seconds, when every frame has a time.
    pub seconds: Option<f64>,
    /// Mean of the digits' correlations at that shift.
    pub correlation: f64,
}

/// The flexion metrics of a recording.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Flexion {
    /// Correlation per digit without shift, indexed by [`Finger::index`].
    pub per_digit: [Option<f64>; 5],
    /// Mean of the defined per-digit correlations.
    pub mean: Option<f64>,
    /// The best shift, when some digit has a defined correlation at some shift.
    pub lag: Option<Lag>,
}

/// Human flexion (every frame) and robot flexion (`None` where the command was not finite) of
/// one digit, metres.
fn series(samples: &[FrameSample], digit: Finger) -> (Vec<f64>, Vec<Option<f64>>) {
    let i = digit.index();
    samples
        .iter()
        .map(|s| (s.human_tips[i].norm(), s.robot_tips.map(|r| r[i].norm())))
        .unzip()
}

/// Pearson correlation of `human[t]` with `robot[t + k]` over the frames where both exist;
/// `None` with fewer than [`CORRELATION_MIN_FRAMES`] pairs or when either side is constant
/// (standard deviation under [`FLEXION_MIN_STD_M`]).
fn shifted_correlation(human: &[f64], robot: &[Option<f64>], k: i64) -> Option<f64> {
    let pairs: Vec<(f64, f64)> = human
        .iter()
        .enumerate()
        .filter_map(|(t, &h)| {
            let u = usize::try_from(t as i64 + k).ok()?;
            robot.get(u).copied().flatten().map(|r| (h, r))
        })
        .collect();
    if pairs.len() < CORRELATION_MIN_FRAMES {
        return None;
    }
    let n = pairs.len() as f64;
    let (mh, mr) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), (h, r)| (a + h / n, b + r / n));
    let (mut shh, mut srr, mut shr) = (0.0, 0.0, 0.0);
    for (h, r) in &pairs {
        shh += (h - mh) * (h - mh);
        srr += (r - mr) * (r - mr);
        shr += (h - mh) * (r - mr);
    }
    let constant = |s: f64| (s / n).sqrt() < FLEXION_MIN_STD_M;
    if constant(shh) || constant(srr) {
        return None;
    }
    Some((shr / (shh * srr).sqrt()).clamp(-1.0, 1.0))
}

fn mean_defined(values: impl IntoIterator<Item = Option<f64>>) -> Option<f64> {
    let defined: Vec<f64> = values.into_iter().flatten().collect();
    (!defined.is_empty()).then(|| defined.iter().sum::<f64>() / defined.len() as f64)
}

/// Shifts tried, nearest to zero first (so a tie keeps the smaller shift): `0, 1, −1, 2, …`
/// up to [`LAG_MAX_FRAMES`] and at most half the frames, so every correlation pairs at least
/// half the recording.
fn shifts(frames: usize) -> impl Iterator<Item = i64> {
    let max = LAG_MAX_FRAMES.min(frames / 2) as i64;
    std::iter::once(0).chain((1..=max).flat_map(|k| [k, -k]))
}

/// Mean of `t_{t+k} − t_t` over the frames paired by shift `k`, when every frame has a time.
fn shift_seconds(samples: &[FrameSample], k: i64) -> Option<f64> {
    let times: Vec<f64> = samples.iter().map(|s| s.t_s).collect::<Option<_>>()?;
    let steps: Vec<f64> = (0..times.len())
        .filter_map(|t| {
            let u = usize::try_from(t as i64 + k).ok()?;
            times.get(u).map(|tu| tu - times[t])
        })
        .collect();
    (!steps.is_empty()).then(|| steps.iter().sum::<f64>() / steps.len() as f64)
}

/// The flexion correlations and the lag of a recording.
pub(super) fn compute(samples: &[FrameSample]) -> Flexion {
    let series = Finger::ALL.map(|f| series(samples, f));
    let at = |k: i64| series.each_ref().map(|(h, r)| shifted_correlation(h, r, k));
    let per_digit = at(0);
    let mut lag: Option<Lag> = None;
    for k in shifts(samples.len()) {
        let Some(correlation) = mean_defined(at(k)) else {
            continue;
        };
        if lag.is_none_or(|best| correlation > best.correlation) {
            lag = Some(Lag {
                frames: k,
                seconds: None,
                correlation,
            });
        }
    }
    Flexion {
        per_digit,
        mean: mean_defined(per_digit),
        lag: lag.map(|l| Lag {
            seconds: shift_seconds(samples, l.frames),
            ..l
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn correlation_follows_pearson_and_its_shift() {
        let human: Vec<f64> = (0..10).map(|t| 0.05 + 0.001 * f64::from(t)).collect();
        let doubled: Vec<Option<f64>> = human.iter().map(|h| Some(2.0 * h)).collect();
        let r = shifted_correlation(&human, &doubled, 0).unwrap();
        assert!((r - 1.0).abs() < 1e-12);
        let reversed: Vec<Option<f64>> = human.iter().rev().map(|h| Some(*h)).collect();
        let r = shifted_correlation(&human, &reversed, 0).unwrap();
        assert!((r + 1.0).abs() < 1e-12);
        // Shifted by 2 the pairs are (h_t, 2 h_{t+2}) over 8 frames: still a line.
        let r = shifted_correlation(&human, &doubled, 2).unwrap();
        assert!((r - 1.0).abs() < 1e-12);
        // Hand-computed: (1,1), (2,3), (3,2) → r = 0.5.
        let r = shifted_correlation(&[1.0, 2.0, 3.0], &[Some(1.0), Some(3.0), Some(2.0)], 0);
        assert!((r.unwrap() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn correlation_is_undefined_when_constant_or_short() {
        let human = [0.05, 0.06, 0.07, 0.08];
        let still = [Some(0.07); 4];
        assert_eq!(shifted_correlation(&human, &still, 0), None);
        let barely = [Some(0.07), Some(0.07 + 1e-9), Some(0.07), Some(0.07)];
        assert_eq!(shifted_correlation(&human, &barely, 0), None);
        let moving = [Some(0.05), None, None, Some(0.08)];
        assert_eq!(shifted_correlation(&human, &moving, 0), None);
        assert_eq!(shifted_correlation(&human, &[Some(1.0); 4], 9), None);
    }

    #[test]
    fn shifts_go_outwards_and_keep_half_the_frames() {
        assert_eq!(shifts(5).collect::<Vec<_>>(), [0, 1, -1, 2, -2]);
        assert_eq!(shifts(1000).count(), 2 * LAG_MAX_FRAMES + 1);
    }
}
