//! Transformed copies of a recording that stand for other users and gloves (the evaluation set
//! of `pomdar eval-set`): the same hand motion with another hand size, another glove
//! mounting, a noisier glove that drops frames, another frame rate, or another layout. Pure:
//! frames in, frames out, every random draw from a seed.
//!
//! | variant | what changes | stands for |
//! |---|---|---|
//! | `scale` | every point moved from the wrist by the factor | a smaller or larger hand |
//! | `rotate` | every point turned about the wrist (axis and angle) | the glove worn or mounted turned |
//! | `noise` | Gaussian noise per coordinate, and frames dropped at random | a noisier glove, lost packets |
//! | `rate` | frames re-sampled (linear between the recorded ones) | a glove at another rate |
//! | `drop_forearm` | the lab's 22 points without the forearm | the lab's 21-point layout |
//! | `outliers` | one point of a digit leaping 3–6 cm for one frame, at spread frames | a camera tracker misplacing a point (`pomdar eval --outlier-study` only: the human keypoints it scores against would carry the outliers) |

use nalgebra::{Point3, Rotation3, Unit, Vector3};
use retarget::human_hand::SplitMix64;
use retarget::{Finger, KeypointLayout};

/// One distinct keypoint frame and its capture time.
#[derive(Debug, Clone, PartialEq)]
pub struct TimedFrame {
    /// Capture time, nanoseconds.
    pub t_ns: i64,
    /// Keypoints, metres, in the recording's layout.
    pub points: Vec<Point3<f64>>,
}

/// A transformation of a recording.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Variant {
    /// Hand size: points moved from the wrist by this factor.
    Scale(f64),
    /// Glove mounting: points turned about the wrist by `degrees` about `axis`.
    Rotate {
        /// Rotation axis (any length but zero).
        axis: [f64; 3],
        /// Angle, degrees.
        degrees: f64,
    },
    /// Glove noise: `sigma_m` Gaussian noise on every coordinate, each frame dropped with
    /// probability `drop`, drawn from `seed`.
    Noise {
        /// Standard deviation per coordinate, metres.
        sigma_m: f64,
        /// Probability of dropping a frame.
        drop: f64,
        /// Seed of the draws.
        seed: u64,
    },
    /// Another frame rate: frames re-sampled at `hz` by linear interpolation.
    Rate(f64),
    /// The lab's 21-point layout from its 22 points.
    DropForearm,
    /// A tracker's one-frame outliers: at `count` frames spread over the recording, one point
    /// of a digit (drawn from `seed`) moved `min_m`–`max_m` in a random direction for that
    /// frame alone.
    Outliers {
        /// Outlier frames.
        count: usize,
        /// Shortest leap, metres.
        min_m: f64,
        /// Longest leap, metres.
        max_m: f64,
        /// Seed of the draws.
        seed: u64,
    },
}

impl Variant {
    /// A short name for file names, e.g. `scale0.85`, `rot15`, `noise2mm-drop10`, `rate30hz`.
    pub fn label(&self) -> String {
        match self {
            Variant::Scale(s) => format!("scale{s:.2}"),
            Variant::Rotate { degrees, .. } => format!("rot{degrees:+.0}"),
            Variant::Noise { sigma_m, drop, .. } => {
                format!("noise{:.0}mm-drop{:.0}", sigma_m * 1e3, drop * 100.0)
            }
            Variant::Rate(hz) => format!("rate{hz:.0}hz"),
            Variant::DropForearm => "21pt".into(),
            Variant::Outliers { count, .. } => format!("outliers{count}"),
        }
    }

    /// The layout of the frames after the variant.
    pub fn layout_after(&self, layout: KeypointLayout) -> KeypointLayout {
        match (self, layout) {
            (Variant::DropForearm, KeypointLayout::Lab22) => KeypointLayout::Lab21,
            _ => layout,
        }
    }

    /// The frames after the variant.
    pub fn apply(&self, frames: &[TimedFrame], layout: KeypointLayout) -> Vec<TimedFrame> {
        let wrist = layout.wrist();
        let about_wrist = |f: &TimedFrame, map: &dyn Fn(Vector3<f64>) -> Vector3<f64>| {
            let w = f.points[wrist];
            TimedFrame {
                t_ns: f.t_ns,
                points: f.points.iter().map(|p| w + map(p - w)).collect(),
            }
        };
        match *self {
            Variant::Scale(s) => frames.iter().map(|f| about_wrist(f, &|v| v * s)).collect(),
            Variant::Rotate { axis, degrees } => {
                let axis = Unit::new_normalize(Vector3::from(axis));
                let r = Rotation3::from_axis_angle(&axis, degrees.to_radians());
                frames.iter().map(|f| about_wrist(f, &|v| r * v)).collect()
            }
            Variant::Noise {
                sigma_m,
                drop,
                seed,
            } => noisy(frames, sigma_m, drop, seed),
            Variant::Rate(hz) => resampled(frames, hz),
            Variant::DropForearm => match layout.forearm() {
                Some(forearm) => frames
                    .iter()
                    .map(|f| TimedFrame {
                        t_ns: f.t_ns,
                        points: f
                            .points
                            .iter()
                            .enumerate()
                            .filter(|(i, _)| *i != forearm)
                            .map(|(_, p)| *p)
                            .collect(),
                    })
                    .collect(),
                None => frames.to_vec(),
            },
            Variant::Outliers {
                count,
                min_m,
                max_m,
                seed,
            } => with_outliers(frames, layout, count, (min_m, max_m), seed),
        }
    }
}

/// The workspace's one SplitMix64, drawn as this set always drew it: uniform in (0, 1] and
/// standard normal by Box–Muller over two such draws, so a seed gives the same set everywhere.
struct SplitMix(SplitMix64);

impl SplitMix {
    fn new(seed: u64) -> Self {
        Self(SplitMix64::new(seed))
    }

    /// Uniform in (0, 1].
    fn uniform(&mut self) -> f64 {
        ((self.0.next_u64() >> 11) as f64 + 1.0) / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller).
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

fn noisy(frames: &[TimedFrame], sigma_m: f64, drop: f64, seed: u64) -> Vec<TimedFrame> {
    let mut rng = SplitMix::new(seed);
    let mut out = Vec::with_capacity(frames.len());
    for (i, f) in frames.iter().enumerate() {
        let dropped = rng.uniform() <= drop;
        // Never drop the first or the last frame: the recording keeps its span.
        if dropped && i != 0 && i + 1 != frames.len() {
            continue;
        }
        let mut jitter = || Vector3::new(rng.normal(), rng.normal(), rng.normal()) * sigma_m;
        out.push(TimedFrame {
            t_ns: f.t_ns,
            points: f.points.iter().map(|p| p + jitter()).collect(),
        });
    }
    out
}

/// `frames` with `count` one-frame outliers, one per stretch of `frames.len() / count` frames
/// (the first and last two frames of each stretch left alone, so no two are adjacent).
fn with_outliers(
    frames: &[TimedFrame],
    layout: KeypointLayout,
    count: usize,
    (min_m, max_m): (f64, f64),
    seed: u64,
) -> Vec<TimedFrame> {
    let mut rng = SplitMix::new(seed);
    let mut out = frames.to_vec();
    let stretch = frames.len() / count.max(1);
    if stretch < 5 {
        return out;
    }
    let digit_points: Vec<usize> = Finger::ALL.iter().flat_map(|f| layout.chain(*f)).collect();
    let draw = |rng: &mut SplitMix, n: usize| ((rng.uniform() * n as f64) as usize).min(n - 1);
    for k in 0..count {
        let at = k * stretch + 2 + draw(&mut rng, stretch - 4);
        let point = digit_points[draw(&mut rng, digit_points.len())];
        let direction = Vector3::new(rng.normal(), rng.normal(), rng.normal()).normalize();
        let leap = min_m + (max_m - min_m) * rng.uniform();
        out[at].points[point] += direction * leap;
    }
    out
}

fn resampled(frames: &[TimedFrame], hz: f64) -> Vec<TimedFrame> {
    let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
        return Vec::new();
    };
    let step_ns = (1e9 / hz).round() as i64;
    let mut out = Vec::new();
    let mut k = 0;
    let mut t = first.t_ns;
    while t <= last.t_ns {
        // The recorded frames around t: the last at or before it and the next.
        let after = frames.partition_point(|f| f.t_ns <= t);
        let a = &frames[after - 1];
        let points = match frames.get(after) {
            Some(b) if b.t_ns > a.t_ns => {
                let w = (t - a.t_ns) as f64 / (b.t_ns - a.t_ns) as f64;
                a.points
                    .iter()
                    .zip(&b.points)
                    .map(|(p, q)| p + (q - p) * w)
                    .collect()
            }
            _ => a.points.clone(),
        };
        out.push(TimedFrame { t_ns: t, points });
        k += 1;
        t = first.t_ns + k * step_ns;
    }
    out
}

/// The set's variants of one recording in `layout`: two hand sizes with a turned glove each,
/// a noisy glove dropping frames, two other rates, and the 21-point layout where there is a
/// forearm point. `seed` makes the noise.
pub fn standard_variants(layout: KeypointLayout, seed: u64) -> Vec<Vec<Variant>> {
    let mut set = vec![
        vec![
            Variant::Scale(0.85),
            Variant::Rotate {
                axis: [1.0, 0.5, 0.2],
                degrees: 15.0,
            },
        ],
        vec![
            Variant::Scale(1.2),
            Variant::Rotate {
                axis: [-0.3, 1.0, 0.4],
                degrees: -12.0,
            },
        ],
        vec![Variant::Noise {
            sigma_m: 0.002,
            drop: 0.1,
            seed,
        }],
        vec![Variant::Rate(30.0)],
        vec![Variant::Rate(120.0)],
    ];
    if layout.forearm().is_some() {
        set.push(vec![Variant::DropForearm]);
    }
    set
}

#[cfg(test)]
#[path = "variants_tests.rs"]
mod tests;
