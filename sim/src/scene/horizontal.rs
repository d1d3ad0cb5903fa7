//! H1–H3: a carriage on a rail, lifted over bumps; H4/H5: a rod slid through its supports.
//!
//! From the paper: H1 scissors (6 curves), H2 chopsticks (3), H3 squeeze (4), the arm moving
//! along a horizontal axis; H4 palmar and H5 pinch slide a rod 0–200 mm with the arm fixed
//! (the lab's README: both use the same objects). This project's model (sizes, masses, the
//! shapes standing in for scissors, chopsticks and the syringe are guesses): each "curve" is
//! a bump across the rail that the carriage's shoe must be lifted over (`carriage_lift`)
//! while it travels along world y (`carriage_slide`, the progress). The rod lies along world
//! y on two U-supports and slides along its axis (`rod_slide`), held back by joint friction
//! so that it moves only when pushed.

use scoring::PhysicsMapping;

use super::Scaffold;
use super::mjcf::{num, nums};

/// The rail's line on the table (world x), m.
const RAIL_X: f64 = 0.5;
/// The carriage's start (world y), m.
const START_Y: f64 = -0.15;
/// The rail floor's top, m.
const FLOOR_TOP: f64 = 0.01;
/// The first bump's centre ahead of the carriage's start, m.
const FIRST_BUMP: f64 = 0.04;
/// The distance between bumps, m.
const BUMP_PITCH: f64 = 0.05;
/// A bump's half extents (across the rail, along it, up), m: 15 mm high.
const BUMP_HALF: [f64; 3] = [0.02, 0.006, 0.0075];
/// The shoe's half extents, m.
const SHOE_HALF: [f64; 3] = [0.012, 0.008, 0.006];
/// How far past "cleared" each mark sits, m (2 mm, then the 1 mm band).
const MARK_PAST_CLEAR: f64 = 0.002;
/// The travel left after the last bump, m.
const RUN_OUT: f64 = 0.04;

/// The rod's height above the table, m.
const ROD_Z: f64 = 0.08;
/// The rod's radius, m (12 mm across, a guess between a palmar and a pinch grasp).
const ROD_RADIUS: f64 = 0.006;
/// The rod's half length, m.
const ROD_HALF_LENGTH: f64 = 0.17;
/// The rod centre's start (world y), m.
const ROD_START_Y: f64 = -0.10;
/// The rod's travel, m: 200 mm (the paper) plus 10 mm so that the end stop is not needed.
const ROD_TRAVEL: f64 = 0.21;

/// What the rail carriage carries for the operator to hold.
#[derive(Debug, Clone, Copy)]
pub(super) enum RailGrip {
    /// H1: two crossed blades, 120 mm, 40 g (6 bumps).
    Scissors,
    /// H2: two parallel sticks, 180 mm, 20 g (3 bumps).
    Chopsticks,
    /// H3: a syringe barrel with a flange, 24 mm across, 30 g (4 bumps).
    Syringe,
}

impl RailGrip {
    fn bumps(self) -> usize {
        match self {
            RailGrip::Scissors => 6,
            RailGrip::Chopsticks => 3,
            RailGrip::Syringe => 4,
        }
    }
}

/// The rail with its bumps and the carriage, with a mark past each bump.
pub(super) fn rail_scaffold(grip: RailGrip) -> Scaffold {
    let n = grip.bumps();
    let bump_y: Vec<f64> = (0..n).map(|k| FIRST_BUMP + k as f64 * BUMP_PITCH).collect();
    let travel = bump_y[n - 1] + RUN_OUT;
    let mut bodies = format!(
        "    <body name=\"rail\" pos=\"{}\">\n",
        nums(&[RAIL_X, START_Y, 0.0])
    );
    bodies.push_str(&format!(
        "      <geom name=\"rail_floor\" class=\"pomdar_fixture\" type=\"box\" size=\"{}\" pos=\"{}\"/>\n",
        nums(&[0.03, travel / 2.0 + 0.03, FLOOR_TOP / 2.0]),
        nums(&[0.0, travel / 2.0, FLOOR_TOP / 2.0])
    ));
    for (k, y) in bump_y.iter().enumerate() {
        bodies.push_str(&format!(
            "      <geom name=\"bump_{k}\" class=\"pomdar_fixture\" type=\"box\" size=\"{}\" pos=\"{}\"/>\n",
            nums(&BUMP_HALF),
            nums(&[0.0, *y, FLOOR_TOP + BUMP_HALF[2]])
        ));
    }
    bodies.push_str(&carriage_body(grip, travel));
    bodies.push_str("    </body>\n");
    let marks = bump_y
        .iter()
        .map(|y| y + BUMP_HALF[1] + SHOE_HALF[1] + MARK_PAST_CLEAR)
        .collect();
    Scaffold {
        bodies,
        mapping: PhysicsMapping {
            marks,
            ..PhysicsMapping::joint("carriage_slide")
        },
    }
}

/// The carriage: shoe, post and grip, sliding along the rail and lifting off it.
fn carriage_body(grip: RailGrip, travel: f64) -> String {
    format!(
        r#"      <body name="carriage" pos="0 0 {z}">
        <joint name="carriage_slide" class="pomdar_object" type="slide" axis="0 1 0" range="0 {travel}" damping="0.3" frictionloss="0.05"/>
        <joint name="carriage_lift" class="pomdar_object" type="slide" axis="0 0 1" range="0 0.03" damping="0.3"/>
        <geom name="carriage_shoe" class="pomdar_object" type="box" size="{shoe}" mass="0.01"/>
        <geom name="carriage_post" class="pomdar_object" type="capsule" fromto="0 0 0.01 0 0 0.05" size="0.004" mass="0.005"/>
{grip}      </body>
"#,
        z = num(FLOOR_TOP + SHOE_HALF[2]),
        travel = num(travel),
        shoe = nums(&SHOE_HALF),
        grip = grip_geoms(grip),
    )
}

fn grip_geoms(grip: RailGrip) -> String {
    match grip {
        RailGrip::Scissors => concat!(
            "        <geom name=\"scissors_blade_a\" class=\"pomdar_object\" type=\"capsule\" fromto=\"-0.058 -0.015 0.055 0.058 0.015 0.055\" size=\"0.004\" mass=\"0.02\"/>\n",
            "        <geom name=\"scissors_blade_b\" class=\"pomdar_object\" type=\"capsule\" fromto=\"-0.058 0.015 0.055 0.058 -0.015 0.055\" size=\"0.004\" mass=\"0.02\"/>\n",
        ),
        RailGrip::Chopsticks => concat!(
            "        <geom name=\"chopstick_a\" class=\"pomdar_object\" type=\"capsule\" fromto=\"-0.09 0.006 0.055 0.09 0.006 0.055\" size=\"0.0035\" mass=\"0.01\"/>\n",
            "        <geom name=\"chopstick_b\" class=\"pomdar_object\" type=\"capsule\" fromto=\"-0.09 -0.006 0.055 0.09 -0.006 0.055\" size=\"0.0035\" mass=\"0.01\"/>\n",
        ),
        RailGrip::Syringe => concat!(
            "        <geom name=\"syringe_barrel\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.012 0.03\" pos=\"0 0 0.08\" mass=\"0.025\"/>\n",
            "        <geom name=\"syringe_flange\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.02 0.002\" pos=\"0 0 0.112\" mass=\"0.005\"/>\n",
        ),
    }
    .to_string()
}

/// The rod on two U-supports, sliding along world y.
pub(super) fn rod_scaffold() -> Scaffold {
    let mut bodies = format!(
        "    <body name=\"rod_supports\" pos=\"{}\">\n",
        nums(&[RAIL_X, 0.0, 0.0])
    );
    for (k, y) in [-0.05, 0.05].iter().enumerate() {
        bodies.push_str(&u_support(k, *y));
    }
    bodies.push_str("    </body>\n");
    bodies.push_str(&format!(
        r#"    <body name="rod" pos="{pos}">
      <joint name="rod_slide" class="pomdar_object" type="slide" axis="0 1 0" range="0 {travel}" damping="0.5" frictionloss="0.2"/>
      <geom name="rod" class="pomdar_object" type="capsule" fromto="0 {a} 0 0 {b} 0" size="{r}" mass="0.06"/>
    </body>
"#,
        pos = nums(&[RAIL_X, ROD_START_Y, ROD_Z]),
        travel = num(ROD_TRAVEL),
        a = num(-ROD_HALF_LENGTH),
        b = num(ROD_HALF_LENGTH),
        r = num(ROD_RADIUS),
    ));
    Scaffold {
        bodies,
        mapping: PhysicsMapping::joint("rod_slide"),
    }
}

/// A post with a U-channel under the rod (1 mm clear of it), at world `y`.
fn u_support(k: usize, y: f64) -> String {
    let channel_floor = ROD_Z - ROD_RADIUS - 0.001;
    let wall_x = ROD_RADIUS + 0.001 + 0.003;
    format!(
        concat!(
            "      <geom name=\"support_{k}_post\" class=\"pomdar_fixture\" type=\"box\" size=\"{post}\" pos=\"{post_pos}\"/>\n",
            "      <geom name=\"support_{k}_wall_a\" class=\"pomdar_fixture\" type=\"box\" size=\"0.003 0.008 0.006\" pos=\"{wall_a}\"/>\n",
            "      <geom name=\"support_{k}_wall_b\" class=\"pomdar_fixture\" type=\"box\" size=\"0.003 0.008 0.006\" pos=\"{wall_b}\"/>\n",
        ),
        k = k,
        post = nums(&[0.01, 0.008, channel_floor / 2.0]),
        post_pos = nums(&[0.0, y, channel_floor / 2.0]),
        wall_a = nums(&[wall_x, y, channel_floor + 0.006]),
        wall_b = nums(&[-wall_x, y, channel_floor + 0.006]),
    )
}
