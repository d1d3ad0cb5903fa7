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

use std::fmt::Write as _;

use scoring::PhysicsMapping;

use super::Scaffold;
use super::mjcf::{num, nums, yaw};

/// The tower's axis on the table (world x, y), m.
const AXIS_XY: [f64; 2] = [0.5, 0.0];
/// The plates' centre heights, bottom to top, m.
const PLATE_Z: [f64; 6] = [0.04, 0.07, 0.10, 0.13, 0.16, 0.19];
/// The plates' slot angles about the vertical, bottom to top, degrees (order a guess).
const NOTCH_DEG: [f64; 6] = [15.0, -15.0, 30.0, -30.0, 45.0, -45.0];
/// A plate's half thickness, m.
const PLATE_HALF_THICKNESS: f64 = 0.004;
/// Half the slot's width, m.
const SLOT_HALF_WIDTH: f64 = 0.006;
/// How far a plate reaches from the axis, m.
const PLATE_REACH: f64 = 0.035;
/// The key bar's half extents (along the bar, across it, up), m. Long, so that a key pressed
/// hard against a plate 30° off its slot overlaps the plate by ~9 mm sideways: MuJoCo pushes
/// a deep box–box overlap out along its shallowest axis, and a short key could be squeezed
/// sideways into the slot.
const KEY_HALF: [f64; 3] = [0.025, 0.0025, 0.004];
/// The key's centre height with the handle down (the handle body's origin), m.
const KEY_Z: f64 = 0.022;
/// The shaft's radius, m (inside the slot with 2.5 mm to spare).
const SHAFT_RADIUS: f64 = 0.0035;
/// The grip's lowest point above the key with the handle down, m: 9 mm over the top plate.
const GRIP_BASE: f64 = 0.181;
/// The slide's travel, m.
const TRAVEL: f64 = 0.185;
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

/// The handle: key bar, shaft and grip, on a slide and a twist about the vertical.
fn handle_body(handle: Handle) -> String {
    let (grip, grip_centre) = grip_geom(handle);
    format!(
        r#"      <body name="handle" pos="0 0 {key_z}">
        <joint name="handle_slide" class="pomdar_object" type="slide" axis="0 0 1" range="0 {travel}" damping="0.5" frictionloss="0.01"/>
        <joint name="handle_twist" class="pomdar_object" type="hinge" axis="0 0 1" damping="0.0005"/>
        <geom name="handle_key" class="pomdar_object" type="box" size="{key}" mass="0.005"/>
        <geom name="handle_shaft" class="pomdar_object" type="cylinder" fromto="0 0 {shaft_from} 0 0 {shaft_to}" size="{shaft}" mass="0.01"/>
{grip}      </body>
"#,
        key_z = num(KEY_Z),
        travel = num(TRAVEL),
        key = nums(&KEY_HALF),
        shaft_from = num(KEY_HALF[2]),
        shaft_to = num(grip_centre),
        shaft = num(SHAFT_RADIUS),
    )
}

/// The grip's geom and its centre height above the key.
fn grip_geom(handle: Handle) -> (String, f64) {
    match handle {
        Handle::Wheel => {
            let z = GRIP_BASE + 0.008;
            let geom = format!(
                "        <geom name=\"handle_wheel\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.03 0.008\" pos=\"0 0 {}\" mass=\"0.03\"/>\n",
                num(z)
            );
            (geom, z)
        }
        Handle::Stick => {
            let z = GRIP_BASE + 0.004;
            let geom = format!(
                "        <geom name=\"handle_stick\" class=\"pomdar_object\" type=\"capsule\" fromto=\"-0.05 0 {z} 0.05 0 {z}\" size=\"0.004\" mass=\"0.012\"/>\n",
                z = num(z)
            );
            (geom, z)
        }
        Handle::Sphere => {
            let z = GRIP_BASE + 0.0275;
            let geom = format!(
                "        <geom name=\"handle_sphere\" class=\"pomdar_object\" type=\"sphere\" size=\"0.0275\" pos=\"0 0 {}\" mass=\"0.04\"/>\n",
                num(z)
            );
            (geom, z)
        }
    }
}
