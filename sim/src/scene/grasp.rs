//! G1–G6: a free object to lift and set down in a target region.
//!
//! From the paper: levels 0 not lifted, 0.5 lifted then dropped, 1 relocated; the objects
//! wheel, sphere, disk and three cylinders; the arm free. The lab's README says the objects
//! are the V handles, the C base plate and clutch rotor and the V tower reused. This
//! project's model (sizes, masses, supports and the target's place are guesses): the object
//! starts at (0.5, −0.2) on the table (clear of the hand at the arm's start pose) or on a small support that leaves room for the fingers
//! under it (wheel and disk on a 60 mm pedestal: see [`PEDESTAL`]; the small and the medium
//! cylinder lying across two 10 cm posts, each set down in a low bin around the target; the
//! sphere and the large cylinder on a tee, set down in the same bin); the target is a 16 × 18
//! cm region
//! at (0.7, −0.2), 0.2 m along +x, drawn on the table (a non-colliding marker).
//!
//! The medium cylinder (G5) lies across posts rather than standing on the table because the
//! ORCA hand as built did not lift it standing in a search in lock step (2026-11), flange down
//! or with the wrist turned: the thumb is a nearly fixed post some 6.5 cm in front of the palm
//! and the fingers close onto it. Hanging flange down, the fingers curl in the plane of the
//! cylinder's axis and only poke it. Turned 90° about +x (palm facing the cylinder, fingers
//! level, thumb up) so that they would wrap around it, the open little finger reaches 8 cm
//! below the palm, so the hand must stay high and the thumb meets the cylinder only at its top;
//! the curling fingers then tip it over or push it past the thumb toward the wrist. Lying across
//! posts like G4's cylinder, it is wrapped against the palm by the curling fingers.
//!
//! The sphere (G2) rests on a tee for the same reason (searched in lock step, 2026-11, the hand
//! on its welded mount). Hanging flange down, the thumb is some 22 cm below the flange and the
//! open fingers reach 33 cm, so with the thumb at a sphere's height on the table the hanging
//! fingers are in the table; the wrap that lifts it off the tee (G2's script), lowered by the
//! 86 mm the tee raises it (or by 6 cm only), lifted the sphere on the table in none of 5 runs
//! with either hand. Raised on the tee's thin stem, the sphere sits between the hanging fingers
//! and the thumb, and the fingers close under it beside the stem.
//!
//! The large cylinder (G6) stands on the same tee for the same reason: G6's wrap lowered by the
//! 89.5 mm the tee raises it lifted the cylinder standing on the table in 2 of 5 runs with the
//! project's hand and 1 of 5 with the manufacturer's and set it down in the target in none (6 cm
//! lower only: 0 of 5 and 1 of 5).
//!
//! An object counts as relocated when the object's origin rests inside the region no more than 1 cm
//! above the highest it rests stably on the table (a cylinder standing or lying, the wheel
//! on its face or edge, the disk and the thin cylinder flat), so that it must be set down
//! rather than held over the region.

use scoring::{GraspMapping, PhysicsMapping};

use super::mjcf::nums;
use super::{Scaffold, StartPerturbation};

/// Where the object starts (world x, y), m.
const START_XY: [f64; 2] = [0.5, -0.2];
/// The target region's centre (world x, y), m.
const TARGET_XY: [f64; 2] = [0.7, -0.2];
/// The target region's half extents along x and y, m.
const TARGET_HALF: [f64; 2] = [0.08, 0.09];
/// How far above its highest stable rest on the table the origin may rest and count, m.
const TARGET_SLACK_Z: f64 = 0.01;

/// The grasp tasks' objects.
#[derive(Debug, Clone, Copy)]
pub(super) enum Object {
    /// G1: a wheel, 60 mm across, 16 mm thick, 30 g, flat on a 60 mm pedestal.
    Wheel,
    /// G2: a sphere, 55 mm across, 40 g, on a tee (on the table the hand as built cannot lift
    /// it: see the module documentation), to be set down in the low bin around the target
    /// region.
    Sphere,
    /// G3: a disk, 120 mm across, 4 mm thick, 40 g, flat on a 60 mm pedestal.
    Disk,
    /// G4: a cylinder, 30 mm across, 140 mm long, 40 g, lying along y across two 10 cm posts
    /// (the fingers of a hand coming down from above pass behind it and close around it), to be
    /// set down in a low bin around the target region.
    CylinderSmall,
    /// G5: a cylinder, 28 mm across, 120 mm long, 30 g, lying along y across two posts 96 mm
    /// apart (standing, the hand as built cannot lift it: see the module documentation), to be
    /// set down in the low bin around the target region.
    CylinderMedium,
    /// G6: a cylinder, 60 mm across, 60 mm tall, 50 g, standing on a tee like the sphere's (on
    /// the table the hand as built cannot lift it: see the module documentation), to be set
    /// down in the low bin around the target region.
    CylinderLarge,
}

/// An object's place at the start.
struct Layout {
    /// The geom's shape and mass attributes.
    geom: &'static str,
    /// The geoms it starts on (maybe none: the table).
    support: &'static str,
    /// Its origin's height at the start, m.
    start_z: f64,
    /// The highest its origin rests stably on the table (or on the target's support), m.
    max_rest_z: f64,
    /// The geoms the target region holds (maybe none: the object is set down on the table).
    target_support: &'static str,
    /// The highest the origin may rest in the target and count (default: `max_rest_z` plus
    /// [`TARGET_SLACK_Z`]); a bin's walls hold an object leaning on them higher.
    target_max_z: Option<f64>,
}

/// Two posts 10 cm high, 124 mm apart along y: the thin cylinder lies across them, and a
/// thumb–index pinch from above reaches under it between them, the other fingers hanging below
/// the pinch beside the posts. Each post's top is rounded (a capsule across it along x): a
/// cylinder lying on a flat box top turned a few degrees got a spurious deep contact from
/// MuJoCo's convex collision and was shot off the posts (6 of 60 starts moved by up to 5 mm
/// and 3°); on the rounded tops none moved.
const POSTS: &str = concat!(
    "      <geom name=\"post_a\" class=\"pomdar_fixture\" type=\"box\" size=\"0.012 0.006 0.047\" pos=\"0 0.062 0.047\"/>\n",
    "      <geom name=\"post_a_top\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.006 0.012\" pos=\"0 0.062 0.094\" quat=\"0.707107 0 0.707107 0\"/>\n",
    "      <geom name=\"post_b\" class=\"pomdar_fixture\" type=\"box\" size=\"0.012 0.006 0.047\" pos=\"0 -0.062 0.047\"/>\n",
    "      <geom name=\"post_b_top\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.006 0.012\" pos=\"0 -0.062 0.094\" quat=\"0.707107 0 0.707107 0\"/>\n",
);
/// A bin around the target region, walls 60 mm high (relative to the start's support body:
/// the target is 0.2 m along +x): a rolling cylinder set down in it stays in it.
const TARGET_BIN: &str = concat!(
    "      <geom name=\"bin_near\" class=\"pomdar_fixture\" type=\"box\" size=\"0.0025 0.0925 0.03\" pos=\"0.1175 0 0.03\"/>\n",
    "      <geom name=\"bin_far\" class=\"pomdar_fixture\" type=\"box\" size=\"0.0025 0.0925 0.03\" pos=\"0.2825 0 0.03\"/>\n",
    "      <geom name=\"bin_right\" class=\"pomdar_fixture\" type=\"box\" size=\"0.08 0.0025 0.03\" pos=\"0.2 -0.0925 0.03\"/>\n",
    "      <geom name=\"bin_left\" class=\"pomdar_fixture\" type=\"box\" size=\"0.08 0.0025 0.03\" pos=\"0.2 0.0925 0.03\"/>\n",
);
/// Two posts like [`POSTS`], 96 mm apart along y, for the 120 mm cylinder of G5 lying across
/// them.
const POSTS_NARROW: &str = concat!(
    "      <geom name=\"post_a\" class=\"pomdar_fixture\" type=\"box\" size=\"0.012 0.006 0.047\" pos=\"0 0.048 0.047\"/>\n",
    "      <geom name=\"post_a_top\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.006 0.012\" pos=\"0 0.048 0.094\" quat=\"0.707107 0 0.707107 0\"/>\n",
    "      <geom name=\"post_b\" class=\"pomdar_fixture\" type=\"box\" size=\"0.012 0.006 0.047\" pos=\"0 -0.048 0.047\"/>\n",
    "      <geom name=\"post_b_top\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.006 0.012\" pos=\"0 -0.048 0.094\" quat=\"0.707107 0 0.707107 0\"/>\n",
);
/// The pedestal of the wheel and the disk: 30 mm across and 60 mm high (this project's guess, as
/// the other supports), so that the finger tips of a hand curled to 30 % of a fist pass under
/// the object's overhang without touching the table. It was 30 mm high; with the hand on its
/// welded (compliant) mount neither was lifted there by the manufacturer's MJCF hand (2026-11,
/// lock step; the disk: seeds 1–2 at approach heights 0.095–0.125 m below the start and approach
/// closures 20–50 % of a fist): curled to 30 % of a fist its finger tips span 44 mm in height
/// (the middle tip 19 mm below the index tip, each tip 25–29 mm tall), more than the 30 mm
/// gap, so they pressed into the table (20–40 N), stuck there by friction while the arm slid in
/// (the wrist joint yielded from −0.15 to +0.4…+0.6 rad) and never got under the rim. At 50 mm
/// the middle tip still touched the table (the disk: 0 of 5 starts with either hand); at 60 mm
/// the G1 and G3 scripts' pinches hold with that hand.
const PEDESTAL: &str = "      <geom name=\"pedestal\" class=\"pomdar_fixture\" type=\"cylinder\" size=\"0.015 0.03\" pos=\"0 0 0.03\"/>\n";

/// A tee for the sphere of G2 and the large cylinder of G6: a stem 8 mm across and 87 mm high
/// at the object's start, and six spokes from just below its top out to six rests (balls 5 mm
/// across on a ring 28 mm across, 87 mm up). The sphere rests on the stem's top (its centre
/// 114.5 mm up, at the height of G4's cylinder), and on the rests when pushed off it; the
/// cylinder stands on the rests (its centre 119.5 mm up). On the table the hand as built did not
/// lift either (the module documentation says why); on the tee the fingers hang beside the
/// object and close under it. With a ring of three rests 18 mm across the sphere started 5 mm
/// off centre rolled off before the hand came (2 of 10 starts); with the wider ring of six none
/// did.
const TEE: &str = concat!(
    "      <geom name=\"tee_stem\" class=\"pomdar_fixture\" type=\"cylinder\" size=\"0.004 0.0435\" pos=\"0 0 0.0435\"/>\n",
    "      <geom name=\"tee_spoke_a\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.0015\" fromto=\"0 0 0.083 0.014 0 0.087\"/>\n",
    "      <geom name=\"tee_spoke_b\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.0015\" fromto=\"0 0 0.083 0.007 0.012124 0.087\"/>\n",
    "      <geom name=\"tee_spoke_c\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.0015\" fromto=\"0 0 0.083 -0.007 0.012124 0.087\"/>\n",
    "      <geom name=\"tee_spoke_d\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.0015\" fromto=\"0 0 0.083 -0.014 0 0.087\"/>\n",
    "      <geom name=\"tee_spoke_e\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.0015\" fromto=\"0 0 0.083 -0.007 -0.012124 0.087\"/>\n",
    "      <geom name=\"tee_spoke_f\" class=\"pomdar_fixture\" type=\"capsule\" size=\"0.0015\" fromto=\"0 0 0.083 0.007 -0.012124 0.087\"/>\n",
    "      <geom name=\"tee_rest_a\" class=\"pomdar_fixture\" type=\"sphere\" size=\"0.0025\" pos=\"0.014 0 0.087\"/>\n",
    "      <geom name=\"tee_rest_b\" class=\"pomdar_fixture\" type=\"sphere\" size=\"0.0025\" pos=\"0.007 0.012124 0.087\"/>\n",
    "      <geom name=\"tee_rest_c\" class=\"pomdar_fixture\" type=\"sphere\" size=\"0.0025\" pos=\"-0.007 0.012124 0.087\"/>\n",
    "      <geom name=\"tee_rest_d\" class=\"pomdar_fixture\" type=\"sphere\" size=\"0.0025\" pos=\"-0.014 0 0.087\"/>\n",
    "      <geom name=\"tee_rest_e\" class=\"pomdar_fixture\" type=\"sphere\" size=\"0.0025\" pos=\"-0.007 -0.012124 0.087\"/>\n",
    "      <geom name=\"tee_rest_f\" class=\"pomdar_fixture\" type=\"sphere\" size=\"0.0025\" pos=\"0.007 -0.012124 0.087\"/>\n",
);

fn layout(object: Object) -> Layout {
    match object {
        Object::Wheel => Layout {
            geom: r#"type="cylinder" size="0.03 0.008" mass="0.03""#,
            support: PEDESTAL,
            start_z: 0.068,
            max_rest_z: 0.03,
            target_support: "",
            target_max_z: None,
        },
        Object::Sphere => Layout {
            geom: r#"type="sphere" size="0.0275" mass="0.04""#,
            support: TEE,
            start_z: 0.1145,
            max_rest_z: 0.0275,
            target_support: TARGET_BIN,
            target_max_z: Some(0.075),
        },
        Object::Disk => Layout {
            geom: r#"type="cylinder" size="0.06 0.002" mass="0.04""#,
            support: PEDESTAL,
            start_z: 0.062,
            max_rest_z: 0.002,
            target_support: "",
            target_max_z: None,
        },
        Object::CylinderSmall => Layout {
            geom: r#"type="cylinder" size="0.015 0.07" quat="0.707107 0.707107 0 0" mass="0.04""#,
            support: POSTS,
            start_z: 0.115,
            max_rest_z: 0.015,
            target_support: TARGET_BIN,
            target_max_z: Some(0.075),
        },
        Object::CylinderMedium => Layout {
            geom: r#"type="cylinder" size="0.014 0.06" quat="0.707107 0.707107 0 0" mass="0.03""#,
            support: POSTS_NARROW,
            start_z: 0.114,
            max_rest_z: 0.06,
            target_support: TARGET_BIN,
            target_max_z: Some(0.075),
        },
        Object::CylinderLarge => Layout {
            geom: r#"type="cylinder" size="0.03 0.03" mass="0.05""#,
            support: TEE,
            start_z: 0.1195,
            max_rest_z: 0.03,
            target_support: TARGET_BIN,
            target_max_z: Some(0.075),
        },
    }
}

/// The support, the free object and the target marker, with the grasp mapping.
pub(super) fn scaffold(object: Object, start: &StartPerturbation) -> Scaffold {
    let layout = layout(object);
    let mut bodies = format!(
        "    <body name=\"object_support\" pos=\"{} 0\">\n{}",
        nums(&START_XY),
        layout.support
    );
    bodies.push_str(layout.target_support);
    bodies.push_str(&format!(
        "      <geom name=\"target_region\" class=\"pomdar_marker\" type=\"box\" size=\"{}\" pos=\"{}\"/>\n    </body>\n",
        nums(&[TARGET_HALF[0], TARGET_HALF[1], 0.0005]),
        nums(&[TARGET_XY[0] - START_XY[0], TARGET_XY[1] - START_XY[1], 0.0005]),
    ));
    bodies.push_str(&format!(
        "    <body name=\"object\" {}>\n      <freejoint name=\"object_free\"/>\n      <geom name=\"object\" class=\"pomdar_free_object\" {}/>\n    </body>\n",
        start.free_body_attributes([START_XY[0], START_XY[1], layout.start_z]),
        layout.geom
    ));
    let grasp = GraspMapping::with_target(
        [
            TARGET_XY[0] - TARGET_HALF[0],
            TARGET_XY[1] - TARGET_HALF[1],
            0.0,
        ],
        [
            TARGET_XY[0] + TARGET_HALF[0],
            TARGET_XY[1] + TARGET_HALF[1],
            layout
                .target_max_z
                .unwrap_or(layout.max_rest_z + TARGET_SLACK_Z),
        ],
    );
    Scaffold {
        bodies,
        mapping: PhysicsMapping {
            grasp: Some(grasp),
            ..PhysicsMapping::joint("object_free")
        },
    }
}
