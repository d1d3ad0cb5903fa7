#![allow(clippy::unwrap_used)] // in tests a panic is the failure report

use retarget::{HandModel, PalmFrame};

use super::*;

const MS: i64 = 1_000_000;

/// 50 frames of the robot's own keypoints closing its index, 40 ms apart.
fn frames() -> Vec<TimedFrame> {
    let model = HandModel::orca_v1_right();
    let index = model.dof_index("index_mcp").unwrap();
    (0..50)
        .map(|k| {
            let mut q = model.zero_pose();
            q[index] = 0.02 * f64::from(k);
            TimedFrame {
                t_ns: i64::from(k) * 40 * MS,
                points: model
                    .synthetic_keypoints(&model.forward_new(&q).unwrap(), KeypointLayout::Lab22),
            }
        })
        .collect()
}

fn palm_coordinates(frame: &TimedFrame, layout: KeypointLayout) -> Vec<Vector3<f64>> {
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(&frame.points)).unwrap();
    frame.points.iter().map(|p| palm.point_to_palm(p)).collect()
}

#[test]
fn scale_and_rotation_keep_the_hand_in_its_palm_frame() {
    let layout = KeypointLayout::Lab22;
    let original = frames();
    let scaled = Variant::Scale(0.85).apply(&original, layout);
    let turned = Variant::Rotate {
        axis: [1.0, 0.5, 0.2],
        degrees: 15.0,
    }
    .apply(&original, layout);
    for ((o, s), r) in original.iter().zip(&scaled).zip(&turned) {
        let (po, ps, pr) = (
            palm_coordinates(o, layout),
            palm_coordinates(s, layout),
            palm_coordinates(r, layout),
        );
        for i in 0..po.len() {
            assert!((ps[i] - po[i] * 0.85).norm() < 1e-12, "scaled point {i}");
            assert!((pr[i] - po[i]).norm() < 1e-12, "turned point {i}");
        }
        assert_eq!(s.points[layout.wrist()], o.points[layout.wrist()]);
        assert!(
            (r.points[layout.tip(Finger::Index)] - o.points[layout.tip(Finger::Index)]).norm()
                > 0.01
        );
    }
}

#[test]
fn noise_has_its_spread_and_drops_its_share() {
    let original = frames();
    let noisy = Variant::Noise {
        sigma_m: 0.002,
        drop: 0.2,
        seed: 7,
    }
    .apply(&original, KeypointLayout::Lab22);
    assert_eq!(noisy.first().unwrap().t_ns, 0);
    assert_eq!(noisy.last().unwrap().t_ns, 49 * 40 * MS);
    assert!(
        (30..=48).contains(&noisy.len()),
        "{} frames kept",
        noisy.len()
    );
    let mut deviations = Vec::new();
    for f in &noisy {
        let o = original.iter().find(|o| o.t_ns == f.t_ns).unwrap();
        for (p, q) in f.points.iter().zip(&o.points) {
            deviations.extend((p - q).iter().copied());
        }
    }
    let rms = (deviations.iter().map(|d| d * d).sum::<f64>() / deviations.len() as f64).sqrt();
    assert!((0.0017..0.0023).contains(&rms), "rms {rms} m");
    let again = Variant::Noise {
        sigma_m: 0.002,
        drop: 0.2,
        seed: 7,
    }
    .apply(&original, KeypointLayout::Lab22);
    assert_eq!(noisy, again, "the seed fixes the draws");
}

#[test]
fn resampling_interpolates_at_the_new_rate() {
    let original = frames();
    let fast = Variant::Rate(100.0).apply(&original, KeypointLayout::Lab22);
    // 1.96 s span at 10 ms: 197 frames.
    assert_eq!(fast.len(), 197);
    assert!(fast.windows(2).all(|w| w[1].t_ns - w[0].t_ns == 10 * MS));
    // 20 ms is halfway between the frames at 0 and 40 ms.
    let mid = &fast[2];
    for ((p, a), b) in mid
        .points
        .iter()
        .zip(&original[0].points)
        .zip(&original[1].points)
    {
        assert!((p - (a + (b - a) * 0.5)).norm() < 1e-12);
    }
    let slow = Variant::Rate(25.0).apply(&original, KeypointLayout::Lab22);
    assert_eq!(
        slow, original,
        "the recorded rate gives the recorded frames"
    );
}

#[test]
fn dropping_the_forearm_gives_the_21_point_layout() {
    let original = frames();
    let v = Variant::DropForearm;
    assert_eq!(v.layout_after(KeypointLayout::Lab22), KeypointLayout::Lab21);
    let dropped = v.apply(&original, KeypointLayout::Lab22);
    assert_eq!(dropped[0].points.len(), 21);
    assert_eq!(dropped[0].points[..], original[0].points[1..]);
    assert_eq!(standard_variants(KeypointLayout::Lab22, 1).len(), 6);
    assert_eq!(standard_variants(KeypointLayout::MediaPipe21, 1).len(), 5);
}

#[test]
fn outliers_move_one_digit_point_of_separate_frames_by_the_leap() {
    let original = frames();
    let v = Variant::Outliers {
        count: 5,
        min_m: 0.03,
        max_m: 0.06,
        seed: 7,
    };
    assert_eq!(v.label(), "outliers5");
    let layout = KeypointLayout::Lab22;
    let out = v.apply(&original, layout);
    assert_eq!(out.len(), original.len());
    let changed: Vec<usize> = (0..out.len())
        .filter(|&k| out[k].points != original[k].points)
        .collect();
    assert_eq!(changed.len(), 5, "{changed:?}");
    assert!(changed.windows(2).all(|w| w[1] - w[0] > 1), "{changed:?}");
    for &k in &changed {
        let moved: Vec<(usize, f64)> = (0..out[k].points.len())
            .map(|i| (i, (out[k].points[i] - original[k].points[i]).norm()))
            .filter(|(_, d)| *d > 0.0)
            .collect();
        assert_eq!(moved.len(), 1, "frame {k}: {moved:?}");
        let (point, leap) = moved[0];
        assert!((0.03..=0.06).contains(&leap), "frame {k}: {leap} m");
        assert_ne!(point, layout.wrist());
        assert_eq!(out[k].t_ns, original[k].t_ns);
    }
    assert_eq!(
        v.apply(&original, layout),
        out,
        "the same seed, the same outliers"
    );
}
