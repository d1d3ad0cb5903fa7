//! What must hold for any datagram handed to the Rokoko parser: `Ok` or `Err`, never a
//! panic; a frame that parses has the layout's number of finite keypoints, a finite wrist at
//! the layout's wrist point with a unit rotation, and a finite timestamp (a packet without one
//! is refused as `no_timestamp`); a refusal says why, under one of the status counters' names.
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_rokoko_packet.rs`) and the cargo-fuzz
//! target (`fuzz/fuzz_targets/rokoko_packet.rs`).

use retarget::KeypointLayout;
use teleop::ingress::ingress_config::Hand;
use teleop::ingress::rokoko_packet::{Selection, parse_packet};

/// The selections a packet is parsed with: both layouts and hands, the first or a named
/// actor, metres and centimetres, and a tight size limit.
pub fn selections() -> Vec<Selection<'static>> {
    let mut out = Vec::new();
    for layout in [KeypointLayout::Lab22, KeypointLayout::Lab21] {
        for hand in [Hand::Right, Hand::Left] {
            out.push(Selection {
                actor: None,
                hand,
                layout,
                max_packet_bytes: 65_507,
                position_scale_to_m: 1.0,
            });
        }
    }
    out.push(Selection {
        actor: Some("Actor1"),
        hand: Hand::Right,
        layout: KeypointLayout::Lab22,
        max_packet_bytes: 65_507,
        position_scale_to_m: 0.01,
    });
    out.push(Selection {
        actor: Some("Actor2"),
        hand: Hand::Right,
        layout: KeypointLayout::Lab22,
        max_packet_bytes: 4096,
        position_scale_to_m: 1e300,
    });
    out
}

/// Parse `bytes` with every selection and check each outcome.
pub fn check_packet(bytes: &[u8]) {
    for selection in selections() {
        match parse_packet(bytes, &selection) {
            Ok(frame) => {
                let layout = selection.layout;
                assert_eq!(frame.keypoints.len(), layout.len());
                assert!(
                    frame
                        .keypoints
                        .iter()
                        .all(|p| p.coords.iter().all(|c| c.is_finite())),
                    "non-finite keypoint"
                );
                assert_eq!(
                    frame.wrist.translation.vector,
                    frame.keypoints[layout.wrist()].coords
                );
                let q = frame.wrist.rotation.quaternion();
                assert!(q.coords.iter().all(|c| c.is_finite()));
                assert!((q.norm() - 1.0).abs() < 1e-9, "rotation norm {}", q.norm());
                assert!(frame.timestamp_s.is_finite());
            }
            Err(error) => {
                assert!(!error.kind().is_empty() && !error.to_string().is_empty());
            }
        }
    }
}
