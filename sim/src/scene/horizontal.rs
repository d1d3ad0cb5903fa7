//! H1–H3: a carriage on a rail, lifted over bumps; H4/H5: a rod slid along its axis by finger
//! strokes.
//!
//! From the paper: H1 scissors (6 curves), H2 chopsticks (3), H3 squeeze (4), the arm moving
//! along a horizontal axis; H4 palmar and H5 pinch slide a rod 0–200 mm with the arm fixed
//! (the lab's README: both use the same objects). This project's model (sizes, masses, the
//! shapes standing in for scissors, chopsticks and the syringe are guesses): each "curve" is
//! a bump across the rail that the carriage's shoe must be lifted over (`carriage_lift`)
//! while it travels along world y (`carriage_slide`, the progress).
//!
//! H4/H5, changed from the first model (a plain rod along world y on two U-supports, 8 cm up,
//! in front of the hand): with the arm fixed at its start pose nothing of the hand reaches
//! along world y (the fingers curl in the x–z plane, the palm facing +x), and a finger stroke
//! moves a tip at most some 7 cm, so no grasp can slide a rod 200 mm. The paper's real
//! mechanism is unverified; this model turns finger strokes into slide with a feed of sprung
//! flaps (as a ratchet's pawl feeds its wheel): the rod lies along world x, the way the curling
//! fingers sweep, 4 cm up under the hanging middle finger, and carries a row of flaps 3 cm
//! apart (the first two 4.5 cm), 18 mm wide and 12 cm high, each hinged on the rod's top about
//! world y. A flap stands against its stop when the finger's pad pushes it forward, so closing
//! the hand (a palmar grasp, H4, or the middle finger's pinch, H5) carries the rod some 5 cm
//! along +x; a flap the returning finger meets from the front folds back under it (a weak
//! spring stands it up again), so opening the hand leaves the rod where it is, held by its
//! friction. Each stroke thus advances the rod by about one pitch or more (the rod, 60 g held
//! by 0.2 N of friction, also coasts a few centimetres when a pad slips off a flap's top); two
//! to ten strokes make 200 mm. Progress is `rod_slide` (0–210 mm) as before.
//!
//! Measured with MuJoCo 3.17 (strokes replayed in this scene, both hand models): the full
//! 200 mm with the rod's line anywhere from 12 mm to the index side of the middle finger's tip
//! to straight under it (the scene takes the middle of that band), the first flap ±5 mm along
//! the rod, pitches 25–35 mm; fixed pegs instead of flaps never gained, since the returning
//! finger pushed the next peg back as far as the closing one had pushed its own. In the lock
//! step (`launch_configs/sim/tasks/H4.toml`, `H5.toml`; 1 mm of glove noise, moved starts) both
//! scripts did it for seeds 1–20 and held-out seeds 501–600 with both hand models.
//!
//! H1–H3 are unchanged and not yet done by the hand: the rail runs along world y, across the
//! arm's horizontal axis (world x), and with the flange held at its height only the fingers
//! can lift the carriage.

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

/// The rod's axis: its line across the table (world y) and its height, m. The rod lies along
/// world x, under the middle finger of the hand hanging at the arm's start pose (its tip at
/// about y = −3 mm), with its flaps' centre 3 mm to the index side of it: the band in which
/// the strokes carried the rod the full 200 mm (replayed with MuJoCo, both hand models) was
/// y = −12 … 0 mm; 4 mm further to either side the flap met the middle finger's rounded
/// edge or the ring finger, and the strokes stalled.
const ROD_Y: f64 = -0.006;
const ROD_Z: f64 = 0.04;
/// The rod's radius, m.
const ROD_RADIUS: f64 = 0.006;
/// The rod's travel, m: 200 mm (the paper) plus 10 mm so that the end stop is not needed.
const ROD_TRAVEL: f64 = 0.21;
/// The first flap's place at the start (world x), m: 1 cm in front of the hanging middle
/// finger's pad (x = 0.462 at 4–9 cm up).
const FLAP_FIRST_X: f64 = 0.472;
/// The distance between flaps along the rod, m (pitches of 25 to 35 mm all did).
const FLAP_PITCH: f64 = 0.03;
/// The extra distance between the first flap and the second, m, so that at the start the
/// second stands 5 mm or more behind the hanging middle finger (whose back is at x ≈ 0.437)
/// wherever the start is moved. One pitch behind the first, it stood under the finger and,
/// pressed up into it by its spring, was squeezed: the rod was pushed back, or flung 130 mm
/// in 0.2 s when the flap came free.
const FLAP_FIRST_GAP: f64 = 0.015;
/// The flaps' top above the table, m: 12 cm, up where the curling middle finger's tip leaves
/// a flap only some 5 cm further on (flaps 10 cm high were left after 2–4 cm).
const FLAP_TOP: f64 = 0.12;
/// A flap's half thickness along the rod and half width across it, m.
const FLAP_HALF: [f64; 2] = [0.002, 0.009];
/// A flap's spring (N·m/rad): enough to stand it up against its own weight (0.5 mN·m), far
/// too little to push the rod back against the rod's friction.
const FLAP_SPRING: f64 = 0.002;
/// How far a flap folds back, rad (80°).
const FLAP_FOLD: f64 = 1.4;
/// The channels holding the rod (world x), m: under the rod over its whole travel.
const ROD_SUPPORT_X: [f64; 2] = [0.40, 0.58];
/// The rod's front end ahead of the rail line (world x 0.5 at the start), m.
const ROD_FRONT: f64 = 0.12;

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

/// The rod in two channels, sliding along world x, with its row of sprung flaps.
pub(super) fn rod_scaffold() -> Scaffold {
    let mut bodies = String::from("    <body name=\"rod_supports\" pos=\"0 0 0\">\n");
    for (k, x) in ROD_SUPPORT_X.iter().enumerate() {
        bodies.push_str(&channel(k, *x));
    }
    bodies.push_str("    </body>\n");
    let flaps = flap_count();
    let back = flap_x(flaps - 1) - 0.01;
    bodies.push_str(&format!(
        r#"    <body name="rod" pos="{pos}">
      <joint name="rod_slide" class="pomdar_object" type="slide" axis="1 0 0" range="0 {travel}" damping="0.5" frictionloss="0.2"/>
      <geom name="rod" class="pomdar_object" type="capsule" fromto="{back} 0 0 {front} 0 0" size="{r}" mass="0.06"/>
{flaps}    </body>
"#,
        pos = nums(&[RAIL_X, ROD_Y, ROD_Z]),
        travel = num(ROD_TRAVEL),
        back = num(back),
        front = num(ROD_FRONT),
        r = num(ROD_RADIUS),
        flaps = (0..flaps).map(flap).collect::<String>(),
    ));
    Scaffold {
        bodies,
        mapping: PhysicsMapping::joint("rod_slide"),
    }
}

/// Enough flaps that one stands in front of the hanging finger over the whole travel.
fn flap_count() -> usize {
    ((ROD_TRAVEL + FLAP_PITCH) / FLAP_PITCH).round() as usize + 1
}

/// Flap `k`'s place along the rod, from the rod body's origin, m.
fn flap_x(k: usize) -> f64 {
    let gap = if k == 0 { 0.0 } else { FLAP_FIRST_GAP };
    FLAP_FIRST_X - RAIL_X - gap - k as f64 * FLAP_PITCH
}

/// Flap `k` (the first in front of the finger, the others behind it), hinged on the rod's
/// top about world y: upright against its stop when pushed forward, folding back when pushed
/// from the front. Flaps touch the hand and the fixtures but not one another (contype 5 shares
/// a bit with both hand models' and the fixtures' conaffinity; conaffinity 0): a folded flap
/// lies in a slot in the rod.
fn flap(k: usize) -> String {
    let x = flap_x(k);
    let hinge_z = ROD_RADIUS / 2.0;
    let half_height = (FLAP_TOP - ROD_Z - hinge_z) / 2.0;
    format!(
        r#"      <body name="flap_{k}" pos="{pos}">
        <joint name="flap_{k}_hinge" class="pomdar_object" type="hinge" axis="0 1 0" range="{fold} 0" stiffness="{spring}" springref="0" damping="0.0005"/>
        <geom name="flap_{k}" class="pomdar_object" contype="5" conaffinity="0" type="box" size="{size}" pos="0 0 {half}" mass="0.002"/>
      </body>
"#,
        pos = nums(&[x, 0.0, hinge_z]),
        fold = num(-FLAP_FOLD),
        spring = num(FLAP_SPRING),
        size = nums(&[FLAP_HALF[0], FLAP_HALF[1], half_height]),
        half = num(half_height),
    )
}

/// A post with a channel under the rod (1 mm clear of it), at world `x`; its walls end below
/// the rod's top so that the flaps pass over them.
fn channel(k: usize, x: f64) -> String {
    let floor = ROD_Z - ROD_RADIUS - 0.001;
    let wall_y = ROD_RADIUS + 0.001 + 0.003;
    let wall_half = ROD_RADIUS / 2.0;
    format!(
        concat!(
            "      <geom name=\"support_{k}_post\" class=\"pomdar_fixture\" type=\"box\" size=\"{post}\" pos=\"{post_pos}\"/>\n",
            "      <geom name=\"support_{k}_wall_a\" class=\"pomdar_fixture\" type=\"box\" size=\"{wall}\" pos=\"{wall_a}\"/>\n",
            "      <geom name=\"support_{k}_wall_b\" class=\"pomdar_fixture\" type=\"box\" size=\"{wall}\" pos=\"{wall_b}\"/>\n",
        ),
        k = k,
        post = nums(&[0.008, 0.012, floor / 2.0]),
        post_pos = nums(&[x, ROD_Y, floor / 2.0]),
        wall = nums(&[0.008, 0.003, wall_half]),
        wall_a = nums(&[x, ROD_Y + wall_y, floor + wall_half]),
        wall_b = nums(&[x, ROD_Y - wall_y, floor + wall_half]),
    )
}

#[cfg(test)]
mod tests {
    use super::super::START_OFFSET_MAX_M;
    use super::*;

    fn floats(text: &str) -> Vec<f64> {
        text.split(' ').map(|v| v.parse().unwrap()).collect()
    }

    #[test]
    fn the_rod_slides_along_x_with_a_flap_in_front_of_the_finger_and_the_next_behind_it() {
        let xml = format!("<w>{}</w>", rod_scaffold().bodies);
        let doc = roxmltree::Document::parse(&xml).unwrap();
        let slide = doc
            .descendants()
            .find(|n| n.attribute("name") == Some("rod_slide"))
            .unwrap();
        assert_eq!(slide.attribute("axis"), Some("1 0 0"));
        assert!(floats(slide.attribute("range").unwrap())[1] > 0.2);
        let flaps: Vec<_> = doc
            .descendants()
            .filter(|n| n.tag_name().name() == "geom")
            .filter(|n| n.attribute("name").is_some_and(|v| v.starts_with("flap_")))
            .collect();
        assert_eq!(flaps.len(), flap_count());
        for geom in &flaps {
            // Flaps touch the hand and the fixtures, not one another.
            assert_eq!(geom.attribute("contype"), Some("5"));
            assert_eq!(geom.attribute("conaffinity"), Some("0"));
        }
        // World x at the start: the first flap in front of the hanging middle finger's pad
        // (x ≈ 0.462), the second 5 mm or more behind its back (x ≈ 0.437) after a 5 mm move.
        let first = RAIL_X + flap_x(0);
        let second = RAIL_X + flap_x(1);
        assert!(first - START_OFFSET_MAX_M > 0.462, "{first}");
        assert!(
            second + START_OFFSET_MAX_M <= 0.437 - 0.005 + 1e-9,
            "{second}"
        );
        // Enough flaps that the last is still behind the finger at the end of the travel.
        let last = RAIL_X + flap_x(flap_count() - 1);
        assert!(last + ROD_TRAVEL < 0.437, "{last}");
    }
}
