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

use scoring::PhysicsMapping;

use super::Scaffold;
use super::mjcf::{num, nums};

/// The post's axis on the table (world x, y), m.
const AXIS_XY: [f64; 2] = [0.5, 0.0];
/// The post's top, where a rotor's hinge sits, m.
const POST_TOP: f64 = 0.06;
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
    /// C1: a bolt, 7 mm shaft, 24 mm head, 15 g; ten turns.
    Bolt,
    /// C2: a T-bar, 8 mm thick, 100 mm long, on a hub, 15 g.
    Stick,
    /// C3: a wheel, 70 mm across, 16 mm thick, 35 g.
    Wheel,
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
    let bodies = format!(
        r#"{base}    <body name="rotor" pos="{xy} {top}">
      <joint name="rotor_hinge" class="pomdar_object" type="hinge" axis="0 0 -1"{range} damping="0.002" frictionloss="0.002"/>
{geoms}    </body>
"#,
        base = base(AXIS_XY, POST_TOP),
        xy = nums(&AXIS_XY),
        top = num(POST_TOP),
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
