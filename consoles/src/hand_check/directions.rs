//! What the operator should see when a joint of the ORCA v1 right hand moves: one sentence for
//! each direction of each joint, in the URDF's sense (the station's). The unit test checks every
//! sentence against the model's forward kinematics (the fingertip's motion in the palm frame:
//! x towards the index side, y towards the fingers, z out of the palm).

/// The sentences for `joint` moving the URDF's positive and negative ways; `None` for a joint
/// that is not an ORCA joint.
pub fn direction_sentences(joint: &str) -> Option<(&'static str, &'static str)> {
    let pair = match joint {
        "thumb_mcp" => (
            "the thumb swings across the palm towards the little finger",
            "the thumb swings away from the palm, towards the index side",
        ),
        "thumb_abd" => (
            "the thumb rises towards the index finger",
            "the thumb drops away from the index finger",
        ),
        "thumb_pip" => (
            "the thumb bends at its middle joint (curls)",
            "the thumb straightens at its middle joint",
        ),
        "thumb_dip" => (
            "the thumb's tip bends (curls)",
            "the thumb's tip straightens",
        ),
        "index_abd" => (
            "the index finger moves towards the middle finger",
            "the index finger spreads away from the middle finger",
        ),
        "middle_abd" => (
            "the middle finger tilts towards the ring finger",
            "the middle finger tilts towards the index finger",
        ),
        "ring_abd" => (
            "the ring finger tilts towards the little finger",
            "the ring finger tilts towards the middle finger",
        ),
        "pinky_abd" => (
            "the little finger spreads away from the ring finger",
            "the little finger moves towards the ring finger",
        ),
        "index_mcp" => (
            "the index finger bends at its knuckle, towards the palm",
            "the index finger bends back at its knuckle",
        ),
        "middle_mcp" => (
            "the middle finger bends at its knuckle, towards the palm",
            "the middle finger bends back at its knuckle",
        ),
        "ring_mcp" => (
            "the ring finger bends at its knuckle, towards the palm",
            "the ring finger bends back at its knuckle",
        ),
        "pinky_mcp" => (
            "the little finger bends at its knuckle, towards the palm",
            "the little finger bends back at its knuckle",
        ),
        "index_pip" => (
            "the index finger curls at its middle joint",
            "the index finger straightens at its middle joint",
        ),
        "middle_pip" => (
            "the middle finger curls at its middle joint",
            "the middle finger straightens at its middle joint",
        ),
        "ring_pip" => (
            "the ring finger curls at its middle joint",
            "the ring finger straightens at its middle joint",
        ),
        "pinky_pip" => (
            "the little finger curls at its middle joint",
            "the little finger straightens at its middle joint",
        ),
        "wrist" => (
            "the hand tilts back at the wrist (fingers towards the back of the hand)",
            "the hand tilts forward at the wrist (fingers towards the palm side)",
        ),
        _ => return None,
    };
    Some(pair)
}

/// The sentence for `joint` moving the URDF's way `direction` (> 0: positive).
pub fn direction_sentence(joint: &str, direction: f64) -> &'static str {
    match direction_sentences(joint) {
        Some((positive, _)) if direction > 0.0 => positive,
        Some((_, negative)) => negative,
        None => "the joint moves",
    }
}

#[cfg(test)]
mod tests {
    use retarget::{Finger, HandModel, ORCA_CORE_JOINTS};

    use super::*;

    /// The fingertip's motion in the palm frame (at the zero pose) for +0.1 rad of `joint`.
    fn tip_motion(model: &HandModel, joint: &str) -> nalgebra::Vector3<f64> {
        let finger = match &joint[..2] {
            "th" => Finger::Thumb,
            "in" => Finger::Index,
            "ri" => Finger::Ring,
            "pi" => Finger::Little,
            _ => Finger::Middle,
        };
        let zero = model.zero_pose();
        let before = model.forward_new(&zero).unwrap();
        let palm = model.palm_frame(&before).unwrap();
        let mut q = zero.clone();
        q[model.dof_index(joint).unwrap()] += 0.1;
        let after = model.forward_new(&q).unwrap();
        let tip = model.frames().tip(finger);
        palm.vector_to_palm(&(after.position(tip) - before.position(tip)))
    }

    #[test]
    fn every_sentence_matches_the_models_motion() {
        let model = HandModel::orca_v1_right();
        for joint in ORCA_CORE_JOINTS {
            let (positive, negative) = direction_sentences(joint).unwrap();
            assert_ne!(positive, negative);
            let d = tip_motion(&model, joint);
            // x: towards the index side; y: towards the fingers; z: out of the palm.
            let holds = if positive.contains("towards the palm") || positive.contains("curls") {
                d.z > 0.0
            } else if positive.contains("back at the wrist") {
                d.z < -0.01
            } else if positive.contains("towards the little finger")
                || positive.contains("towards the middle finger")
                || positive.contains("towards the ring finger")
                || positive.contains("away from the ring finger")
            {
                d.x < -0.005 && d.x.abs() > d.z.abs()
            } else if positive.contains("rises towards the index") {
                d.x > 0.0 && d.y > 0.0
            } else {
                false
            };
            assert!(holds, "{joint}: '{positive}' but the tip moves {d:?}");
        }
        assert_eq!(direction_sentence("nose", 1.0), "the joint moves");
    }
}
