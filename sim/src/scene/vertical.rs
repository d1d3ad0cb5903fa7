//! V1–V3: a handle keyed through six slotted plates on a tower.
//!
//! From the paper: six notches at ±15°, ±30°, ±45°, the arm moving along the vertical axis;
//! the objects are a wheel (V1), a stick (V2) and a sphere (V3). This project's model (sizes,
//! masses, the plate order and the key design are guesses): the handle slides up a vertical
//! axis (`handle_slide`) and turns about it (`handle_twist`); at its foot a flat key bar.
//! Each plate is split by a slot through the axis, turned by its notch angle; the key passes
//! a plate only when turned within about ±8° of the slot, and otherwise rests on it. The
//! operator lifts the handle and twists it to each notch in turn: progress is the number of
//! plates the key has cleared.
//!
//! ## Where the tower stands and why the grip rides on a coupling (measured with MuJoCo)
//!
//! Under `vertical_axis` the end effector only rises and sinks on the vertical through its
//! start (0.45, 0) and, with the `twist_about_axis` preset, turns about that vertical. The
//! project's hand hangs flange down with its palm on that axis: in the open start pose the
//! palm spans 0.17–0.24 m below the flange and the middle finger hangs along the axis down to
//! 6 cm above the table. So nothing can stand on the flange axis under the hand, and the
//! hand's grasp is in front of its palm: a closed fist holds a bar 4 cm in front of the axis,
//! 0.235 m below the flange. A wrist turn therefore carries the grip on a 4 cm circle about the
//! flange axis, which a handle on a fixed axis of its own cannot follow (a rigid grasp would
//! have to be coaxial). In the first draft (the tower at (0.5, 0), the grip 9 mm over the top
//! plate) the open hand even started inside the plates: the ±45° plates' corners reach to
//! 1 mm from the flange axis, and at the start the palm was 19 mm deep in the top plate.
//!
//! Hence, keeping the six notches at ±15°, ±30°, ±45°: (1) the grip sits on the handle through
//! a coupling with two free slides across the handle (an Oldham coupling: it passes the grip's
//! turn to the shaft whatever the offset), resting 7 cm from the shaft towards the arm (the
//! stick; the wheel and the sphere 5.5 cm, clear of the open palm), in front of the palm where
//! the fist closes; a wrist turn then turns the key by the wrist's angle while the grip follows
//! its circle. (2) The tower stands 11 cm in front of the flange axis,
//! so that the plates' corners stay 3 cm clear of the open fingers and the curling fingers
//! sweep above them. (3) The stack is lower and tighter (plates 6 mm thick every 22 mm, a key
//! 6 mm high: 10 mm of free lift between plates), its top 27 mm under the grip, so that the
//! grip sits at the start where the fist closes, under the thumb. (4) The stick is 14 mm thick
//! and lies across the palm (along the handle's y): a thinner bar turned 8–16° in the closed
//! fist and lagged the wrist by that much.
//!
//! With the hand rigidly on the arm, a fist or a cylinder grasp closed round the horizontal
//! wheel or the sphere did not hold them against turning (in lock step they spun in the hand,
//! tens of degrees off the wrist's turn, or were pushed up against the next plate); a wheel
//! standing on edge, its face to the palm, followed the first three notches. On the welded
//! mount (measured in lock step, seeds 1–20, moved starts) the round grips still turn in the
//! fist, the key ending 18° behind to 4° ahead of the wrist at a hold, differently from run to
//! run, so the V1 and V3 scripts press the key lightly under each plate and sweep the wrist
//! from 20° short of its notch to 20° past it: 20 of 20 each with the manufacturer's MJCF
//! hand, 0 of 20 with the project's hand, in whose fist the wheel and the sphere turn further
//! (a 40° sweep turned the key by 4–17°).

use std::fmt::Write as _;

use scoring::PhysicsMapping;

use super::Scaffold;
use super::mjcf::{num, nums, yaw};

/// The tower's axis on the table (world x, y), m.
const AXIS_XY: [f64; 2] = [0.56, 0.0];
/// The plates' centre heights, bottom to top, m.
const PLATE_Z: [f64; 6] = [0.025, 0.047, 0.069, 0.091, 0.113, 0.135];
/// The plates' slot angles about the vertical, bottom to top, degrees (order a guess).
const NOTCH_DEG: [f64; 6] = [15.0, -15.0, 30.0, -30.0, 45.0, -45.0];
/// A plate's half thickness, m.
const PLATE_HALF_THICKNESS: f64 = 0.003;
/// Half the slot's width, m.
const SLOT_HALF_WIDTH: f64 = 0.006;
/// How far a plate reaches from the axis, m.
const PLATE_REACH: f64 = 0.035;
/// The key bar's half extents (along the bar, across it, up), m. Long, so that a key pressed
/// hard against a plate 30° off its slot overlaps the plate by ~9 mm sideways: MuJoCo pushes
/// a deep box–box overlap out along its shallowest axis, and a short key could be squeezed
/// sideways into the slot.
const KEY_HALF: [f64; 3] = [0.025, 0.0025, 0.003];
/// The key's centre height with the handle down (the handle body's origin), m.
const KEY_Z: f64 = 0.016;
/// The shaft's radius, m (inside the slot with 2.5 mm to spare).
const SHAFT_RADIUS: f64 = 0.0035;
/// Where the stick rests in the handle's frame, from the shaft's axis (x towards the arm, y),
/// m, and its centre's height above the key, m: 4 cm in front of the palm of the hand at its
/// start pose, 0.235 m below the flange, where the closing fist holds it (see the module
/// documentation).
const STICK_REST: [f64; 3] = [-0.07, 0.0, 0.149];
/// Where the wheel and the sphere rest: 1.5 cm further from the palm than the stick, so that
/// the open hand at its start does not touch them (their near side 4 mm in front of the palm).
const ROUND_GRIP_REST: [f64; 3] = [-0.055, 0.0, 0.149];
/// The shaft's top above the key, m: at the top plate, below the grip and the curled fingers.
const SHAFT_TOP: f64 = 0.119;
/// How far the grip may slide from its rest along each of the handle's horizontal axes (the
/// coupling), m: a wrist turn of ±52° carries a grip held 4 cm in front of the flange axis
/// up to 8.5 cm from its rest, seen from the turned handle.
const COUPLING_TRAVEL: f64 = 0.1;
/// The slide's travel, m.
const TRAVEL: f64 = 0.15;
/// How far below "cleared" each mark sits, m: a key resting on its plate (sunk by contact
/// softness) still counts, with the 1 mm band.
const MARK_BELOW_CLEAR: f64 = 0.002;

/// The vertical tasks' handles.
#[derive(Debug, Clone, Copy)]
pub(super) enum Handle {
    /// V1: a wheel, 60 mm across, 16 mm thick, 30 g.
    Wheel,
    /// V2: a T-stick, 8 mm thick, 100 mm long, 12 g.
    Stick,
    /// V3: a sphere, 55 mm across, 40 g.
    Sphere,
}

/// The tower, the plates and the handle, with marks at the plates.
pub(super) fn scaffold(handle: Handle) -> Scaffold {
    let mut bodies = format!(
        "    <body name=\"tower\" pos=\"{}\">\n",
        nums(&[AXIS_XY[0], AXIS_XY[1], 0.0])
    );
    bodies.push_str(&tower_geoms());
    bodies.push_str(&handle_body(handle));
    bodies.push_str("    </body>\n");
    Scaffold {
        bodies,
        mapping: PhysicsMapping {
            marks: marks(),
            ..PhysicsMapping::joint("handle_slide")
        },
    }
}

/// The slide position at which the key has cleared each plate, minus [`MARK_BELOW_CLEAR`].
fn marks() -> Vec<f64> {
    let key_bottom = KEY_Z - KEY_HALF[2];
    PLATE_Z
        .iter()
        .map(|z| z + PLATE_HALF_THICKNESS - key_bottom - MARK_BELOW_CLEAR)
        .collect()
}

/// The base, the column and the six split plates.
fn tower_geoms() -> String {
    let top = PLATE_Z[5] + PLATE_HALF_THICKNESS;
    let mut geoms = String::from(
        "      <geom name=\"tower_base\" class=\"pomdar_fixture\" type=\"box\" size=\"0.06 0.06 0.005\" pos=\"0 0 0.005\"/>\n",
    );
    let _ = writeln!(
        geoms,
        "      <geom name=\"tower_column\" class=\"pomdar_fixture\" type=\"box\" size=\"0.008 0.008 {}\" pos=\"0 0.047 {}\"/>",
        num(top / 2.0),
        num(top / 2.0)
    );
    for (k, (z, deg)) in PLATE_Z.iter().zip(NOTCH_DEG).enumerate() {
        let _ = write!(
            geoms,
            "      <body name=\"plate_{k}\" pos=\"0 0 {}\" quat=\"{}\">\n{}      </body>\n",
            num(*z),
            yaw(deg.to_radians()),
            plate_halves(k)
        );
    }
    geoms
}

/// A plate's two halves either side of the slot (along the plate's x axis).
fn plate_halves(k: usize) -> String {
    let half_depth = (PLATE_REACH - SLOT_HALF_WIDTH) / 2.0;
    let offset = SLOT_HALF_WIDTH + half_depth;
    let size = nums(&[PLATE_REACH, half_depth, PLATE_HALF_THICKNESS]);
    [("a", offset), ("b", -offset)]
        .iter()
        .map(|(side, y)| {
            format!(
                "        <geom name=\"plate_{k}_{side}\" class=\"pomdar_fixture\" type=\"box\" size=\"{size}\" pos=\"0 {} 0\"/>\n",
                num(*y)
            )
        })
        .collect()
}

/// The handle: key bar and shaft on a slide and a twist about the vertical, and the grip on
/// the coupling's two free slides across the handle.
fn handle_body(handle: Handle) -> String {
    format!(
        r#"      <body name="handle" pos="0 0 {key_z}">
        <joint name="handle_slide" class="pomdar_object" type="slide" axis="0 0 1" range="0 {travel}" damping="0.5" frictionloss="0.01"/>
        <joint name="handle_twist" class="pomdar_object" type="hinge" axis="0 0 1" damping="0.0005"/>
        <geom name="handle_key" class="pomdar_object" type="box" size="{key}" mass="0.005"/>
        <geom name="handle_shaft" class="pomdar_object" type="cylinder" fromto="0 0 {shaft_from} 0 0 {shaft_to}" size="{shaft}" mass="0.01"/>
        <body name="handle_grip" pos="{grip_pos}">
          <joint name="grip_shift_x" class="pomdar_object" type="slide" axis="1 0 0" range="-{coupling} {coupling}" damping="0.2" frictionloss="0.002"/>
          <joint name="grip_shift_y" class="pomdar_object" type="slide" axis="0 1 0" range="-{coupling} {coupling}" damping="0.2" frictionloss="0.002"/>
          {grip}
        </body>
      </body>
"#,
        key_z = num(KEY_Z),
        travel = num(TRAVEL),
        key = nums(&KEY_HALF),
        shaft_from = num(KEY_HALF[2]),
        shaft_to = num(SHAFT_TOP),
        shaft = num(SHAFT_RADIUS),
        grip_pos = nums(&grip_rest(handle)),
        coupling = num(COUPLING_TRAVEL),
        grip = grip_geom(handle),
    )
}

/// Where the grip rests in the handle's frame.
fn grip_rest(handle: Handle) -> [f64; 3] {
    match handle {
        Handle::Stick => STICK_REST,
        Handle::Wheel | Handle::Sphere => ROUND_GRIP_REST,
    }
}

/// The grip's geom, centred on the grip body.
fn grip_geom(handle: Handle) -> &'static str {
    match handle {
        Handle::Wheel => {
            r#"<geom name="handle_wheel" class="pomdar_object" type="cylinder" size="0.03 0.008" mass="0.03"/>"#
        }
        Handle::Stick => {
            r#"<geom name="handle_stick" class="pomdar_object" type="capsule" fromto="0 -0.05 0 0 0.05 0" size="0.007" mass="0.012"/>"#
        }
        Handle::Sphere => {
            r#"<geom name="handle_sphere" class="pomdar_object" type="sphere" size="0.0275" mass="0.04"/>"#
        }
    }
}
