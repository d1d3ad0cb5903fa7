//! C1–C3: a rotor on a post; C4: a fidget spinner.
//!
//! From the paper: rotation out of 360°; C1 thread, C2 stick and C3 wheel with the arm
//! moving along the vertical axis, C4 fidget with the arm fixed. The lab's C1 turns a bolt
//! through ten turns; its C1–C3 sit behind a gravity clutch (only forward turning counts,
//! which the progress tracker's ratchet models) and its C4 spinner drives a gear train
//! (which shaft counts is unverified: here the spinner's own axis). This project's model
//! (sizes, masses, damping and friction are guesses): every rotor turns about the vertical on
//! a hinge whose positive sense is clockwise seen from above (the way a right-hand bolt goes
//! in); the bolt's hinge stops at the start and after ten turns, the others turn freely.
//!
//! Under `vertical_axis` the arm only moves along the vertical through its start position and,
//! with the orientation policy `twist_about_axis`, turns about it; the hand hangs on that axis
//! with its palm toward +x. The C1 and C2 layouts were found with the hand parented rigidly to
//! the arm's mocap body, moved by setting its pose each step: its motion gave the contact
//! solver no velocity, so a finger that the wrist turned slid over a part it pressed on
//! without dragging it (measured: finger tips pressing 48 N on the wheel's top while the wrist
//! turned 150° forward turned it 6.5° backward), and only the push of the fingers' surfaces,
//! the normal force, moved a part. A normal force on a round part passes through its axis, so
//! the wrist could turn a part only by pushing a feature that sticks out from its axis, and
//! only about the axis the wrist turns about. Hence the C1 bolt and the C2 stick stand under
//! the flange (x = 0.45 m, 5 cm nearer the arm than before), lowered so that the open hand
//! hangs clear of them at the start, and the bolt carries a wing (a wing bolt, as bolts turned
//! by hand are made): with the round 24 mm head alone, or a hexagonal one, the curled finger
//! tips (3.6 to 5.2 cm from the axis) never reached it and the scripted strokes turned it 4 to
//! 10°.
//!
//! The hand now hangs on a free body welded to the mocap body (`world.rs`), whose contacts
//! carry the arm's motion, so a pressing finger drags what it presses by friction. The C3
//! wheel, plain and round (70 mm across, as before), stands under the flange too,
//! its top face 5.6 cm above the table, where the open hand's middle finger tip, a few
//! millimetres from the flange axis, comes down on it: pressed there while the wrist turns,
//! the tip drags the wheel round about its own axis. Measured in lock step
//! (`launch_configs/sim/tasks/C3.toml`, seeds 1–20, 1 mm glove noise, moved starts): two
//! strokes of 300° each turned the wheel 502° to 638° in all, correctness 1 in 20 of 20 with
//! both the project's hand and the manufacturer's MJCF. The same script with the wheel where
//! it stood before (5 cm in front of the flange, on a 6 cm post, above the hanging finger
//! tips) turned it 212° to 223° with the project's hand and 150° to 156° with the
//! manufacturer's (seeds 1–5, unmoved starts, 0 of 5 each): there its axis lies 5 cm off the
//! one the wrist turns about, so the fingers sweep past its rim instead of riding on its face.

use scoring::PhysicsMapping;

use super::Scaffold;
use super::mjcf::{num, nums};

/// C1's and C2's axis (world x, y), m: under the flange, where the arm's vertical axis meets the
/// table (the station's start pose, x = 0.45 m). Under `vertical_axis` the arm only moves along
/// that vertical and, with the orientation policy `twist_about_axis`, turns about it; the
/// scripted hand turns the stick by pushing it with its curled finger tips while the wrist
/// turns, which turns the stick about its own axis only when the two axes meet. At the old
/// place, 5 cm in front of the flange, a turned hand sweeps a circle about the flange axis and
/// pushes the stick sideways against its hinge instead.
const UNDER_FLANGE_XY: [f64; 2] = [0.45, 0.0];
/// C2's post top, m: 3.5 cm lower than the wheel's, so that the stick (its top 29 mm above the
/// post) lies 14 mm below the open hand's lowest finger tip at the start pose (0.068 m). At
/// 0.06 m the stick ran through the hanging middle finger at the start and MuJoCo shot it away
/// (a contact of some 2 kN) before the script began.
const STICK_POST_TOP: f64 = 0.025;
/// C1's post top, m: the bolt's wing (its top 45 mm above the post) 11 mm below the open hand's
/// lowest finger tip at the start pose; the post is a 6 mm boss on the base plate.
const BOLT_POST_TOP: f64 = 0.012;
/// C3's post top, m: the wheel's top face (31 mm above the post, 0.056 m) lies 12 mm below the
/// project's open hand's lowest finger tip (the middle one, near the flange axis) at the start
/// pose and 3 mm below the manufacturer's (its fingers hang 8 mm lower), so that both hang clear
/// of it at the start. It stood 6 cm high, 5 cm in front of the flange, before.
const WHEEL_POST_TOP: f64 = 0.025;
/// C4's spinner axis on the table (world x, y), m, and the top of its post, m: 1 cm nearer
/// the arm, 3 cm to the hand's right of the rotors' axis and 1.5 cm higher. C4 keeps the arm
/// fixed at its start pose, where the open fingertips hang 4.5 cm in front of the rotors' axis
/// at the height of a spinner's lobes and curl up and away from it: there closing the hand
/// turned the spinner backward or not at all. Here the ring and little fingers' curl sweeps
/// through the lobes left of the axis and flicks it forward: more than a turn anywhere within
/// ±1 cm of this place (measured with MuJoCo, a fist closed in 0.5 s).
const SPINNER_XY: [f64; 2] = [0.49, -0.03];
const SPINNER_TOP: f64 = 0.075;
/// Ten turns, rad (the lab's C1 bolt).
const TEN_TURNS_RAD: f64 = 20.0 * std::f64::consts::PI;

/// The C1–C3 rotors.
#[derive(Debug, Clone, Copy)]
pub(super) enum Rotor {
    /// C1: a wing bolt, 7 mm shaft, 24 mm head with a wing 60 mm across, 21 g; ten turns.
    Bolt,
    /// C2: a T-bar, 8 mm thick, 100 mm long, on a hub, 15 g.
    Stick,
    /// C3: a wheel, 70 mm across, 16 mm thick, 35 g.
    Wheel,
}

impl Rotor {
    /// The post's axis (world x, y) and top, m.
    fn placement(self) -> ([f64; 2], f64) {
        match self {
            Rotor::Stick => (UNDER_FLANGE_XY, STICK_POST_TOP),
            Rotor::Bolt => (UNDER_FLANGE_XY, BOLT_POST_TOP),
            Rotor::Wheel => (UNDER_FLANGE_XY, WHEEL_POST_TOP),
        }
    }
}

/// The base plate and the post the rotors sit on.
fn base(xy: [f64; 2], top: f64) -> String {
    format!(
        concat!(
            "    <body name=\"rotor_base\" pos=\"{xy} 0\">\n",
            "      <geom name=\"base_plate\" class=\"pomdar_fixture\" type=\"cylinder\" size=\"0.06 0.003\" pos=\"0 0 0.003\"/>\n",
            "      <geom name=\"base_post\" class=\"pomdar_fixture\" type=\"cylinder\" size=\"0.015 {half}\" pos=\"0 0 {mid}\"/>\n",
            "    </body>\n",
        ),
        xy = nums(&xy),
        half = num((top - 0.006) / 2.0),
        mid = num((top + 0.006) / 2.0),
    )
}

/// A rotor on the post, hinged about the vertical (clockwise positive).
pub(super) fn rotor_scaffold(rotor: Rotor) -> Scaffold {
    let range = match rotor {
        Rotor::Bolt => format!(" range=\"0 {}\"", num(TEN_TURNS_RAD)),
        Rotor::Stick | Rotor::Wheel => String::new(),
    };
    let (xy, top) = rotor.placement();
    let bodies = format!(
        r#"{base}    <body name="rotor" pos="{xy} {top}">
      <joint name="rotor_hinge" class="pomdar_object" type="hinge" axis="0 0 -1"{range} damping="0.002" frictionloss="0.002"/>
{geoms}    </body>
"#,
        base = base(xy, top),
        xy = nums(&xy),
        top = num(top),
        geoms = rotor_geoms(rotor),
    );
    Scaffold {
        bodies,
        mapping: PhysicsMapping::joint("rotor_hinge"),
    }
}

/// A rotor's geoms, 1 mm above the post top.
fn rotor_geoms(rotor: Rotor) -> &'static str {
    match rotor {
        Rotor::Bolt => concat!(
            "      <geom name=\"bolt_shaft\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.0035 0.015\" pos=\"0 0 0.016\" mass=\"0.004\"/>\n",
            "      <geom name=\"bolt_head\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.012 0.006\" pos=\"0 0 0.037\" mass=\"0.011\"/>\n",
            "      <geom name=\"bolt_wing\" class=\"pomdar_object\" type=\"box\" size=\"0.03 0.003 0.008\" pos=\"0 0 0.037\" mass=\"0.006\"/>\n",
        ),
        Rotor::Stick => concat!(
            "      <geom name=\"stick_hub\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.01 0.01\" pos=\"0 0 0.011\" mass=\"0.005\"/>\n",
            "      <geom name=\"stick_bar\" class=\"pomdar_object\" type=\"capsule\" fromto=\"-0.05 0 0.025 0.05 0 0.025\" size=\"0.004\" mass=\"0.01\"/>\n",
        ),
        Rotor::Wheel => concat!(
            "      <geom name=\"wheel_hub\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.01 0.007\" pos=\"0 0 0.008\" mass=\"0.005\"/>\n",
            "      <geom name=\"wheel_rim\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.035 0.008\" pos=\"0 0 0.023\" mass=\"0.03\"/>\n",
        ),
    }
}

/// C4: a three-lobed spinner on the post, nearly frictionless.
pub(super) fn spinner_scaffold() -> Scaffold {
    let lobes: String = (0..3)
        .map(|k| {
            let angle = f64::from(k) * 2.0 * std::f64::consts::PI / 3.0;
            let (x, y) = (0.027 * angle.cos(), 0.027 * angle.sin());
            format!(
                "      <geom name=\"spinner_lobe_{k}\" class=\"pomdar_object\" type=\"cylinder\" size=\"0.011 0.004\" pos=\"{}\" mass=\"0.008\"/>\n      <geom name=\"spinner_arm_{k}\" class=\"pomdar_object\" type=\"box\" size=\"0.0135 0.005 0.003\" pos=\"{}\" euler=\"0 0 {}\" mass=\"0.002\"/>\n",
                nums(&[x, y, 0.005]),
                nums(&[x / 2.0, y / 2.0, 0.005]),
                num(angle),
            )
        })
        .collect();
    let bodies = format!(
        r#"{base}    <body name="spinner" pos="{xy} {top}">
      <joint name="spinner_hinge" class="pomdar_object" type="hinge" axis="0 0 -1" damping="0.00002"/>
      <geom name="spinner_hub" class="pomdar_object" type="cylinder" size="0.011 0.004" pos="0 0 0.005" mass="0.006"/>
{lobes}    </body>
"#,
        base = base(SPINNER_XY, SPINNER_TOP),
        xy = nums(&SPINNER_XY),
        top = num(SPINNER_TOP),
    );
    Scaffold {
        bodies,
        mapping: PhysicsMapping::joint("spinner_hinge"),
    }
}
