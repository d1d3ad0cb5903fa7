//! Synthetic glove recordings: a 22-point lab hand (forearm, wrist, four points per digit)
//! built from a rigid palm and finger chains whose flexion and abduction follow one of three
//! task motions, for participants of different hand sizes, each trial placed at a random
//! pose in the glove's frame with millimetre noise.

#![allow(dead_code)] // each test file uses part of the generator

use std::f64::consts::TAU;

use nalgebra::{Point3, Rotation3, Unit, Vector3};
use retarget::KeypointLayout;
use study::{MotionFrame, TrialMotion};

/// Deterministic pseudo-random numbers (SplitMix64), so the tests need no dependency.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let u = self.range(f64::MIN_POSITIVE, 1.0);
        let v = self.range(0.0, 1.0);
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    }
}

/// The three task motions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// All fingers and the thumb open and close together.
    PowerGrasp,
    /// Thumb and index close on each other; the other fingers stay tucked.
    Pinch,
    /// Fingers nearly straight, spreading apart and back.
    Spread,
}

/// A participant: hand size and a personal posture bias.
#[derive(Debug, Clone)]
pub struct Participant {
    pub name: String,
    /// Hand size relative to the model hand.
    pub scale: f64,
    /// Per digit (thumb … little) length factor.
    pub lengths: [f64; 5],
    /// Added to every flexion angle, rad.
    pub flex_bias: f64,
    /// Added to every finger's abduction, rad.
    pub spread_bias: f64,
}

impl Participant {
    pub fn new(name: &str, scale: f64, rng: &mut Rng) -> Self {
        Self {
            name: name.into(),
            scale,
            lengths: [(); 5].map(|()| rng.range(0.95, 1.05)),
            flex_bias: rng.range(-0.1, 0.1),
            spread_bias: rng.range(-0.03, 0.03),
        }
    }
}

/// Joint angles of one frame: per digit (thumb … little) three flexions, an abduction, and
/// the wrist's flexion.
struct Pose {
    flex: [[f64; 3]; 5],
    abduction: [f64; 5],
    wrist_flex: f64,
}

const BASES: [[f64; 3]; 5] = [
    [0.022, 0.025, 0.012],
    [0.024, 0.088, 0.0],
    [0.002, 0.092, 0.0],
    [-0.018, 0.087, 0.0],
    [-0.036, 0.078, 0.0],
];
const PHALANGES: [[f64; 3]; 5] = [
    [0.040, 0.032, 0.027],
    [0.044, 0.025, 0.020],
    [0.048, 0.029, 0.021],
    [0.045, 0.027, 0.020],
    [0.035, 0.020, 0.018],
];
const REST_ABDUCTION: [f64; 5] = [0.0, 0.08, 0.0, -0.08, -0.16];

/// The pose of `motion` at closure `g` in [0, 1].
fn pose(motion: Motion, g: f64, who: &Participant) -> Pose {
    let scale3 = |a: [f64; 3], k: f64| a.map(|v| v * k);
    let (flex, mut abduction, wrist_flex) = match motion {
        Motion::PowerGrasp => {
            let f = scale3([1.1, 1.3, 0.7], 0.15 + 0.85 * g);
            let thumb = scale3([0.4, 0.5, 0.4], 0.2 + 0.8 * g);
            ([thumb, f, f, f, f], REST_ABDUCTION, 0.1 * g)
        }
        Motion::Pinch => {
            let index = scale3([0.5, 0.8, 0.4], 0.2 + 0.8 * g);
            let tucked = [0.9, 1.1, 0.5];
            let thumb = scale3([0.5, 0.6, 0.4], 0.3 + 0.7 * g);
            let middle = scale3([0.6, 0.8, 0.4], 0.5 + 0.5 * g);
            ([thumb, index, middle, tucked, tucked], REST_ABDUCTION, -0.1)
        }
        Motion::Spread => {
            let straight = [0.1, 0.1, 0.05];
            let thumb = [0.1, 0.15, 0.1];
            let a = REST_ABDUCTION;
            let spread = [
                0.5 * g,
                a[1] + 0.3 * g,
                0.05 * g,
                a[3] - 0.2 * g,
                a[4] - 0.4 * g,
            ];
            ([thumb, straight, straight, straight, straight], spread, 0.0)
        }
    };
    abduction[1..]
        .iter_mut()
        .for_each(|a| *a += who.spread_bias);
    Pose {
        flex: flex.map(|f| f.map(|v| v + who.flex_bias)),
        abduction,
        wrist_flex,
    }
}

/// The 22 lab points of `pose` in the hand's own frame (y to the fingers, x to the thumb
/// side, z palmar), metres.
fn hand_points(pose: &Pose, who: &Participant) -> Vec<Point3<f64>> {
    let s = who.scale;
    let wrist = Point3::origin();
    let w = pose.wrist_flex;
    let forearm = Point3::new(0.0, -0.24 * w.cos(), 0.24 * w.sin()) * s;
    let mut points = vec![forearm, wrist];
    for digit in 0..5 {
        let base = Point3::from(Vector3::from(BASES[digit]) * s);
        let a = pose.abduction[digit];
        let (u, across) = if digit == 0 {
            let u = Vector3::new((0.9 + a).sin(), 0.8 * (0.9 + a).cos(), 0.35).normalize();
            let w = Vector3::new(-0.6, 0.3, 0.75);
            (u, (w - u * w.dot(&u)).normalize())
        } else {
            (Vector3::new(a.sin(), a.cos(), 0.0), Vector3::z())
        };
        points.push(base);
        let (mut p, mut phi) = (base, 0.0);
        for (flex, length) in pose.flex[digit].iter().zip(PHALANGES[digit]) {
            phi += flex;
            p += (u * phi.cos() + across * phi.sin()) * length * who.lengths[digit] * s;
            points.push(p);
        }
    }
    points
}

/// One trial of `motion` by `who`: `duration_s` at `rate_hz`, a random cycle frequency,
/// amplitude and phase, a random pose in the glove's frame, Gaussian noise of `noise_m`.
pub fn trial(
    who: &Participant,
    motion: Motion,
    task: &str,
    label: &str,
    (duration_s, rate_hz, noise_m): (f64, f64, f64),
    rng: &mut Rng,
) -> TrialMotion {
    let frequency_hz = rng.range(0.6, 0.9);
    let amplitude = rng.range(0.85, 1.1);
    let phase = rng.range(0.0, TAU);
    let axis = Vector3::new(rng.normal(), rng.normal(), rng.normal());
    let rotation = Rotation3::from_axis_angle(&Unit::new_normalize(axis), rng.range(0.0, 3.1));
    let offset = Vector3::new(
        rng.range(-0.5, 0.5),
        rng.range(-0.5, 0.5),
        rng.range(0.5, 1.5),
    );
    let frames = (0..(duration_s * rate_hz).round() as usize)
        .map(|i| {
            let t_s = i as f64 / rate_hz;
            let g = amplitude * (0.5 - 0.5 * (TAU * frequency_hz * t_s + phase).cos());
            let noise =
                |rng: &mut Rng| Vector3::new(rng.normal(), rng.normal(), rng.normal()) * noise_m;
            let points = (hand_points(&pose(motion, g, who), who).into_iter())
                .map(|p| rotation * p + offset + noise(rng))
                .collect();
            MotionFrame { t_s, points }
        })
        .collect();
    TrialMotion {
        participant: who.name.clone(),
        task: task.into(),
        trial: label.into(),
        layout: KeypointLayout::Lab22,
        frames,
    }
}

/// Three participants (hand scales 0.85, 1.0, 1.15) doing each of `tasks` three times,
/// 6 s at 60 Hz with 1 mm noise.
pub fn study_trials(tasks: &[(&str, Motion)], seed: u64) -> Vec<TrialMotion> {
    let mut rng = Rng::new(seed);
    let people: Vec<Participant> = [("P1", 0.85), ("P2", 1.0), ("P3", 1.15)]
        .iter()
        .map(|&(name, scale)| Participant::new(name, scale, &mut rng))
        .collect();
    let mut trials = Vec::new();
    for who in &people {
        for &(task, motion) in tasks {
            for k in 1..=3 {
                let label = format!("{}_{task}_{k}.mcap", who.name);
                trials.push(trial(
                    who,
                    motion,
                    task,
                    &label,
                    (6.0, 60.0, 0.001),
                    &mut rng,
                ));
            }
        }
    }
    trials
}
