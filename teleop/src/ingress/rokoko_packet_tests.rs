use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use retarget::KeypointLayout;
use serde_json::{Value, json};

use super::*;
use crate::ingress::rokoko_packet_builder::{HandPose, actor, packet, right_hand_packet};

fn selection(layout: KeypointLayout) -> Selection<'static> {
    Selection {
        actor: None,
        hand: Hand::Right,
        layout,
        max_packet_bytes: 65_507,
        position_scale_to_m: 1.0,
    }
}

fn hand_points(layout: KeypointLayout) -> Vec<Point3<f64>> {
    (0..layout.len())
        .map(|i| {
            Point3::new(
                0.3 + 0.01 * i as f64,
                -0.1 + 0.002 * i as f64,
                1.0 - 0.003 * i as f64,
            )
        })
        .collect()
}

/// A packet written by hand in Studio's frame, and its ROS values worked out by hand.
#[test]
fn a_hand_written_packet_converts_as_computed_by_hand() {
    let mut body = serde_json::Map::new();
    for (k, name) in bone_names(Hand::Right, KeypointLayout::Lab22)
        .iter()
        .enumerate()
    {
        let position = json!({"x": 0.1 * k as f64, "y": 1.5, "z": -0.2});
        body.insert(
            name.clone(),
            json!({"position": position, "rotation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}}),
        );
    }
    // The hand bone turned 90° about Studio's up axis (y).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    body.insert(
        "rightHand".into(),
        json!({"position": {"x": 0.1, "y": 1.5, "z": -0.2},
               "rotation": {"x": 0.0, "y": h, "z": 0.0, "w": h}}),
    );
    let text = json!({"version": "3,0", "scene": {"timestamp": 7.5,
        "actors": [{"name": "A", "body": body}]}})
    .to_string();
    let frame = parse_packet(text.as_bytes(), &selection(KeypointLayout::Lab22)).unwrap();
    assert_eq!(frame.timestamp_s, 7.5);
    assert_eq!(frame.keypoints.len(), 22);
    // Studio (x, y, z) = (0.1 k, 1.5, −0.2) → ROS (z, −x, y) = (−0.2, −0.1 k, 1.5).
    for (k, p) in frame.keypoints.iter().enumerate() {
        let expected = Point3::new(-0.2, -0.1 * k as f64, 1.5);
        assert!((p - expected).norm() < 1e-12, "point {k}: {p}");
    }
    // Forearm first, then the wrist (rightHand) at k = 1.
    assert!((frame.wrist.translation.vector - Vector3::new(-0.2, -0.1, 1.5)).norm() < 1e-12);
    // Studio forward (+z) turned to Studio right (+x): in ROS, forward (+x) to right (−y).
    let turned = frame.wrist.rotation * Vector3::x();
    assert!((turned - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-12);
}

#[test]
fn built_packets_round_trip_through_the_parser() {
    for layout in [KeypointLayout::Lab22, KeypointLayout::Lab21] {
        let points = hand_points(layout);
        let wrist = Isometry3::new(Vector3::new(0.3, -0.1, 1.0), Vector3::new(0.2, -0.5, 0.9));
        let bytes = right_hand_packet(3.25, layout, &points, &wrist);
        assert!(
            bytes.len() > 5_000,
            "real-shaped packets are large: {}",
            bytes.len()
        );
        let frame = parse_packet(&bytes, &selection(layout)).unwrap();
        for (a, b) in frame.keypoints.iter().zip(&points) {
            assert!((a - b).norm() < 1e-12);
        }
        assert!(frame.wrist.rotation.angle_to(&wrist.rotation) < 1e-12);
        assert_eq!(frame.timestamp_s, 3.25);
    }
}

#[test]
fn actors_are_picked_by_name_and_hands_by_side() {
    let layout = KeypointLayout::Lab22;
    let a = hand_points(layout);
    let b: Vec<Point3<f64>> = a.iter().map(|p| p + Vector3::new(1.0, 0.0, 0.0)).collect();
    let pose = |points| HandPose {
        layout,
        keypoints: points,
        wrist_rotation: UnitQuaternion::identity(),
    };
    let bytes = packet(
        1.0,
        vec![
            actor("First", Hand::Right, &pose(&a), 1.0),
            actor("Second", Hand::Left, &pose(&b), 1.0),
        ],
    );
    let first = parse_packet(&bytes, &selection(layout)).unwrap();
    assert!((first.keypoints[5] - a[5]).norm() < 1e-12);
    let second = Selection {
        actor: Some("Second"),
        hand: Hand::Left,
        ..selection(layout)
    };
    let left = parse_packet(&bytes, &second).unwrap();
    assert!((left.keypoints[5] - b[5]).norm() < 1e-12);
    let missing = Selection {
        actor: Some("Third"),
        ..selection(layout)
    };
    let e = parse_packet(&bytes, &missing).unwrap_err();
    assert_eq!(e.kind(), "no_actor");
    assert!(e.to_string().contains("First, Second"), "{e}");
}

#[test]
fn centimetre_streams_are_scaled() {
    let layout = KeypointLayout::Lab21;
    let points = hand_points(layout);
    let pose = HandPose {
        layout,
        keypoints: &points,
        wrist_rotation: UnitQuaternion::identity(),
    };
    let bytes = packet(0.0, vec![actor("A", Hand::Right, &pose, 0.01)]);
    let sel = Selection {
        position_scale_to_m: 0.01,
        ..selection(layout)
    };
    let frame = parse_packet(&bytes, &sel).unwrap();
    assert!((frame.keypoints[3] - points[3]).norm() < 1e-12);
}

#[test]
fn each_kind_of_bad_packet_is_named() {
    let layout = KeypointLayout::Lab22;
    let points = hand_points(layout);
    let good = right_hand_packet(1.0, layout, &points, &Isometry3::identity());
    let sel = selection(layout);
    let kind = |bytes: &[u8], sel: &Selection<'_>| parse_packet(bytes, sel).unwrap_err().kind();
    assert_eq!(kind(&good[..good.len() / 2], &sel), "truncated");
    assert_eq!(kind(b"hello", &sel), "malformed");
    assert_eq!(kind(b"{\"scene\": 3}", &sel), "malformed");
    let small = Selection {
        max_packet_bytes: 1000,
        ..sel
    };
    assert_eq!(kind(&good, &small), "oversized");
    let mut value: Value = serde_json::from_slice(&good).unwrap();
    value["version"] = json!("2,1");
    assert_eq!(kind(value.to_string().as_bytes(), &sel), "version");
    let mut value: Value = serde_json::from_slice(&good).unwrap();
    value["scene"]["actors"] = json!([]);
    assert_eq!(kind(value.to_string().as_bytes(), &sel), "no_actor");
    // No timestamp, or one that is not a finite number: refused, never ordered by arrival.
    for stamp in [None, Some(json!(null)), Some(json!("soon"))] {
        let mut value: Value = serde_json::from_slice(&good).unwrap();
        match stamp {
            None => {
                value["scene"].as_object_mut().unwrap().remove("timestamp");
            }
            Some(v) => value["scene"]["timestamp"] = v,
        }
        let k = kind(value.to_string().as_bytes(), &sel);
        assert!(k == "no_timestamp" || k == "malformed", "{k}");
    }
    let mut value: Value = serde_json::from_slice(&good).unwrap();
    value["scene"].as_object_mut().unwrap().remove("timestamp");
    assert_eq!(kind(value.to_string().as_bytes(), &sel), "no_timestamp");
    let mut value: Value = serde_json::from_slice(&good).unwrap();
    value["scene"]["actors"][0]["body"]
        .as_object_mut()
        .unwrap()
        .remove("rightRingDistal");
    let e = parse_packet(value.to_string().as_bytes(), &sel).unwrap_err();
    assert_eq!(e.kind(), "missing_bone");
    assert!(e.to_string().contains("rightRingDistal"), "{e}");
    let mut value: Value = serde_json::from_slice(&good).unwrap();
    value["scene"]["actors"][0]["body"]["rightHand"]["rotation"] =
        json!({"x": 0.0, "y": 0.0, "z": 0.0, "w": 0.0});
    assert_eq!(kind(value.to_string().as_bytes(), &sel), "missing_bone");
    let mut value: Value = serde_json::from_slice(&good).unwrap();
    value["scene"]["actors"][0]["body"]["rightIndexTip"]["position"]["x"] = json!(1e308);
    let huge = Selection {
        position_scale_to_m: 10.0,
        ..sel
    };
    let e = parse_packet(value.to_string().as_bytes(), &huge).unwrap_err();
    assert!(e.to_string().contains("non-finite"), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Arbitrary bytes never panic the parser.
    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..2048)) {
        let _ = parse_packet(&bytes, &selection(KeypointLayout::Lab22));
    }

    /// Mutated real packets either parse to finite values or are refused; never a panic.
    #[test]
    fn mutated_packets_give_finite_frames_or_errors(
        cut in 0usize..20_000,
        flips in proptest::collection::vec((0usize..20_000, any::<u8>()), 0..8),
        scale in -1e6f64..1e6,
    ) {
        let layout = KeypointLayout::Lab22;
        let points: Vec<Point3<f64>> = hand_points(layout).iter().map(|p| p * scale).collect();
        let mut bytes = right_hand_packet(1.0, layout, &points, &Isometry3::identity());
        for (at, byte) in flips {
            let n = bytes.len();
            bytes[at % n] = byte;
        }
        bytes.truncate(bytes.len().min(cut.max(1)).max(bytes.len() / 2));
        if let Ok(frame) = parse_packet(&bytes, &selection(layout)) {
            prop_assert!(frame.keypoints.iter().all(|p| p.coords.iter().all(|c| c.is_finite())));
            prop_assert!(frame.wrist.translation.vector.iter().all(|c| c.is_finite()));
            prop_assert!((frame.wrist.rotation.norm() - 1.0).abs() < 1e-9);
        }
    }
}
