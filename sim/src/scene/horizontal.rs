//! H1–H3: a carriage on a rail, lifted over bumps; H4/H5: a rod slid along its axis by finger
//! strokes.
//!
//! From the paper: H1 scissors (6 curves), H2 chopsticks (3), H3 squeeze (4), the arm moving
//! along a horizontal axis; H4 palmar and H5 pinch slide a rod 0–200 mm with the arm fixed
//! (the lab's README: both use the same objects). This project's model (sizes, masses and the
//! mechanism are guesses): each "curve" is a bump across the rail that the carriage's shoe
//! must be lifted over while the carriage travels along the rail (`carriage_slide`, the
//! progress, a mark 2 mm past each bump).
//!
//! H1–H3, changed from the first model (the rail along world y, 0.33 m of travel for H1, the
//! shoe on a lift slide under a tool-shaped grip): `horizontal_axis` moves the arm along world
//! x only and holds the flange's height, so only the fingers could move the carriage along y
//! (spreading the open hand moves a tip 12 mm across y, a stroke some 7 cm along x; measured on
//! the project's hand) and only they could lift it. Now the rail runs along world x under the
//! hanging hand, so the arm carries the carriage (the hand is on a compliant mount, so fingers
//! carried by the arm pull what they press on), and the fingers lift the shoe with a trigger.
//! The carriage travels back along −x, drawn by a rear bar across the rail 5 mm behind the
//! hanging fingers' backs at their middle joints' height (13 cm up). It carries a lever hinged
//! about world y 3.5 cm up: its paddle stands on the hinge 1.2 cm in front of the hanging
//! fingers' pads (9 cm wide, index to ring, 15 cm high), and its arm holds the shoe 5 cm
//! behind the hinge, on a track of bumps beside the paddle's line. Fingers closing onto the
//! paddle turn the lever (to 0.5 rad: the shoe 24 mm up, over the 15 mm bumps) before they
//! move the carriage (0.3 N of friction on the rail, more than the lever needs); the arm then
//! draws the hand back, the fingers' backs pulling the rear bar while their pads hold the
//! paddle; let go, a weak spring and the shoe's weight drop the shoe again. The open hand drawn
//! back pulls the rear bar and never touches the paddle, so the shoe stops at the first bump:
//! the lift is the grip's. The bumps stand 26 mm apart, the first 12 mm behind the shoe, so
//! that the arm's reach back along x (the workspace ends at x = 0.25 m, the start is 0.45)
//! carries the carriage past the sixth. The three tasks shared the mechanism and differed in
//! the number of bumps (the tools' shapes are not modelled, and the grip was the script's:
//! scissor strokes, a pinch, a squeeze); H1 keeps it, H2 and H3 were changed again (below).
//!
//! Measured with MuJoCo 3.17: in the lock step (`launch_configs/sim/tasks/H1.toml`, `H2.toml`,
//! `H3.toml`; 1 mm of glove noise, moved starts) the three scripts of then cleared every bump
//! for seeds 1–20 and held-out seeds 501–540 with both hand models; the open hand drawn back
//! the same 19.5 cm cleared none (seeds 1–5, both hand models). A fist (50 or 70 %) curls the
//! fingers over the paddle's top: no bump (replayed, one trace each). Designs that did not
//! hold, replayed with MuJoCo's Python bindings: a handle in front of the fingers' middle
//! joints for the arm to push along +x, the paddle 1.2 cm further on — the curling fingers
//! pushed the handle, and with it the paddle, 17 mm ahead of their tips, the lever turned
//! 0.16–0.29 rad, not enough, and the carriage stuck at the first bump (both hand models); the
//! paddle alone pushed along +x, or a post in front of the thumb for the arm to push — both did
//! it, but so did the open hand (5 or 6 of the 6 bumps), since the arm pushing on kept the
//! fingers on the paddle; a plate lifted by the curling tips from below — the open fingers'
//! tips slid under it and lifted it too.
//!
//! H2, changed again (the trigger above is H1's, scissors being done alike by every embodiment
//! in the paper; chopsticks need finger abduction there): the paddle is replaced by a tong that
//! only the fingers' sideways motion squeezes. Measured on both hand models (the station's
//! retargeting of the named poses, then the fingers' collision geometry 6.6–9.4 cm up, where
//! the hanging tips are): ORCA's zero abduction is wider than any spread the retargeter asks
//! for — the open hand (fingers together) puts index_abd at its upper limit (0.246 rad) and
//! ring_abd at −0.24, `open_spread` at 0.11 and −0.02 — so an embodiment with abduction locked
//! holds its fingers spread for good, and a part worked by spreading alone would be worked by
//! it too. What it cannot do is bring them together: the index finger's inner side and the ring
//! finger's, 78–86 mm apart at zero abduction (66–73 spread), come to 40–43 mm in the open
//! hand. The tong slides freely across the rail on the carriage (so the moved start and the
//! turned rail do not matter): a prong beside the index finger's inner side and, 58 mm across
//! the middle finger, a paddle beside the ring finger's, on a lever hinged about world x 5.5 cm
//! up whose arm carries the shoe 8 cm across the rail. The two fingers closing sideways squeeze
//! it: the prong's slide stops against the index finger and the ring finger pushes the paddle's
//! top (some 4 cm above the hinge) toward the middle finger, turning the lever (to its 0.45 rad
//! stop: the shoe 31 mm up, over the 15 mm bumps; at least 0.39 rad while drawn for seeds 1–20
//! with the manufacturer's hand, 0.41 with the project's); one finger alone slides the tong
//! (0.02 N of friction) and turns nothing, since the shoe's weight holds the paddle with some
//! 0.2 N. The joints that make it: index_abd and ring_abd (middle_abd barely moves). Flexing
//! fingers did not (the project's reading: the tips curl forward in their own planes, out of
//! the plates' reach along the rail, and an abduction-locked hand's index and ring fingers
//! never come within the tong's span). In the lock step (`launch_configs/sim/tasks/H2.toml`; 1
//! mm of glove noise, moved starts) the script cleared the three bumps for seeds 1–20 with both
//! hand models and held-out seeds 501–540 with the manufacturer's; with orca_5, orca_3 and
//! orca_2 (abduction locked) it and 87 variants a person might try (fist, cylinder grasp,
//! pinches of the index, middle or ring finger, relaxed, at 50–100 %; the wrist 1 cm off; twice
//! as slow or fast; the old H1–H3 scripts, and H1's six strokes with a fist, a cylinder grasp
//! or a pinch) cleared none (seeds 1–5, both hand models). The carriage, its rear bar and the
//! bumps' places are H1's; the bumps are wider across the rail, for the shoe is carried across
//! with the tong.
//!
//! H3, changed with H2: the same tong with four bumps — the squeeze needs finger abduction too.
//! Thumb abduction (the paper's reading of a syringe squeezed) was tried and not taken. The
//! retargeter moves thumb_abd only in the little-finger pinch (−0.27 rad, thumb_mcp at its
//! 0.873 limit; |thumb_abd| ≤ 0.04 in every other named pose), and thumb_abd's axis lies 20°
//! from thumb_mcp's, so abduction carries the thumb's swing on past the limit: the abducted
//! thumb's tip ends 21 mm beyond anywhere an abduction-locked thumb reaches, its distal segment
//! 1.1 mm from the little finger's (8.6 mm or more over a grid of abduction-locked poses; the
//! project's hand's capsules). But the place lies in front of the palm 18 cm up where an
//! abduction-locked hand's little finger reaches too (within 4 mm) and its ring finger, splayed
//! by zero abduction, sweeps through. A syringe there (a flange and a plunger on a lever, 6 mm
//! across, between the two tips), in the lock step: sliding level across the rail, the squeeze
//! bent the manufacturer's hand's wrist 0.09 rad and slipped off (0 of seeds 1–20); sliding
//! down its line onto a stop (its weight), 20 of 20 with both hand models, but the plunger then
//! gave against the stop alone, and orca_5 worked it with strokes of its ring finger (H1's
//! script with pinch_ring at 70 %: all four bumps for 1 of seeds 1–5, the manufacturer's hand;
//! fist strokes three). In the lock step (`launch_configs/sim/tasks/H3.toml`: H2's, drawn 15
//! cm; 1 mm of glove noise, moved starts) the tong cleared the four bumps for seeds 1–20 with
//! both hand models and held-out seeds 501–540 with the manufacturer's; with orca_5, orca_3 and
//! orca_2 it and 110 variants (H2's, and the little-finger pinch) cleared none (seeds 1–5, both
//! hand models).
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
//! the hand (a palmar grasp, H4) carries the rod some 5 cm
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
//! scripts did it for seeds 1–20 and held-out seeds 501–600 with both hand models — H5 then in
//! this same placement, stroked by the middle finger's pinch.
//!
//! H5, changed again (`RodStroke::Pinch`): the paper's pinch is the thumb–index pinch, done
//! alike by every embodiment, and orca_2 (thumb and index only) has no middle finger to stroke
//! with; the index finger hangs 4 cm to the side of H4's rod line, and a flap wide enough to
//! reach it from there was held folded by the resting middle finger. H5's rod now lies under
//! the index finger (`PINCH_ROD_Y`), with flaps 24 mm wide, clear of the middle finger, and
//! 12.5 mm apart (`PINCH_FLAP_PITCH`: at 30 mm the shorter index stroke stalled whenever a
//! stroke left the next flap where the returning tip folds it under the resting finger); the
//! rod, its travel and friction, the flaps' height and spring and the first flap's place are
//! H4's. Where the index hangs depends on the embodiment: the open hand with every joint free
//! holds index_abd at its limit, an abduction-locked hand (orca_5, orca_3, orca_2) at zero, 2 cm
//! further out; the rod's line lies where both overlap (the bands quoted at `PINCH_ROD_Y`,
//! `PINCH_FLAP_HALF_W` and `PINCH_FLAP_PITCH` were measured with one flap fewer at the rod's
//! back end, which only the end of the travel reaches). Measured with MuJoCo 3.17 in the lock
//! step (`launch_configs/sim/tasks/H5.toml`, `pinch_index` strokes; 1 mm of glove noise, moved
//! starts) the one script did the full 200 mm for seeds 1–20 with every embodiment: orca_full,
//! orca_5, orca_3 and orca_2 each 20 of 20 with the manufacturer's hand, and 20, 20, 19 and 20
//! of 20 with the project's (orca_3's one miss stalled at 66 mm); held-out seeds 501–520 with
//! orca_full and orca_2, the manufacturer's hand: 20 of 20 each. H4's scene is unchanged (the
//! same MJCF), and its script still did it for seeds 1–20 with both hand models.

use scoring::PhysicsMapping;

use super::Scaffold;
use super::mjcf::{num, nums};

/// The rod's reference line on the table (world x), m.
const RAIL_X: f64 = 0.5;

/// The trigger's hinge above the table's rail line at the start (world x, y, z), m: the
/// paddle's face 1.2 cm in front of the hanging fingers' pads (x ≈ 0.462, y from −0.05 at the
/// index to 0.03 at the ring finger) and its hinge 2 cm below their tips.
const HINGE: [f64; 3] = [0.47, -0.02, 0.035];
/// The rail floor's top, m.
const FLOOR_TOP: f64 = 0.01;
/// The shoe's place on the lever from the hinge (along the rail, across it), m: behind the
/// hinge, so that the paddle pushed forward lifts it by 5 cm × sin(lever angle), and beside
/// the paddle's line so that its track of bumps runs clear of the lever.
const SHOE_FROM_HINGE: [f64; 2] = [-0.05, 0.04];
/// The shoe's half extents (along the rail, across it, up), m.
const SHOE_HALF: [f64; 3] = [0.006, 0.006, 0.006];
/// The shoe's clearance over the floor at rest, m.
const SHOE_CLEAR: f64 = 0.0005;
/// The first bump's centre behind the shoe's back at the start, m (the carriage travels
/// along −x).
const FIRST_BUMP: f64 = 0.012;
/// The distance between bumps, m (the project's guess, short enough that the arm's reach back
/// along x, to 0.25 m from the start's 0.45, carries the carriage over all six of H1).
const BUMP_PITCH: f64 = 0.026;
/// A bump's half extents (along the rail, across it, up), m: 15 mm high.
const BUMP_HALF: [f64; 3] = [0.005, 0.012, 0.0075];
/// How far past "cleared" each mark sits, m (2 mm, then the 1 mm band).
const MARK_PAST_CLEAR: f64 = 0.002;
/// The carriage's travel past the last mark, m.
const RUN_OUT: f64 = 0.01;
/// The paddle: its face's offset in front of the hinge, its half thickness, its half width
/// across the rail and its top above the table, m.
const PADDLE_X: f64 = 0.006;
const PADDLE_HALF_T: f64 = 0.002;
const PADDLE_HALF_W: f64 = 0.045;
const PADDLE_TOP: f64 = 0.15;
/// The lever's travel, rad: at 0.5 rad the shoe is 24 mm up, 9 mm over a bump's top.
const LEVER_MAX: f64 = 0.5;
/// The lever's return spring, N·m/rad: with the shoe's weight it drops the shoe again when
/// the paddle is let go; a push of some 0.2 N at the fingers' height turns it.
const LEVER_SPRING: f64 = 0.003;
/// The rear bar the backs of the hanging fingers pull (from the hinge along x, above the
/// table), m: 5 mm behind their backs (x ≈ 0.437) wherever the start is moved, at their
/// middle joints' height; and its half width across the rail (index to ring).
const REAR_BAR: [f64; 2] = [-0.043, 0.13];
const REAR_BAR_HALF_W: f64 = 0.055;
/// The carriage's friction on its rail, N: more than the push that turns the lever, so that a
/// push on the paddle lifts the shoe before it moves the carriage.
const CARRIAGE_FRICTION: f64 = 0.3;

/// The rod's axis: its line across the table (world y; H4's, H5's is `PINCH_ROD_Y`) and its
/// height, m. The rod lies along world x, under the middle finger of the hand hanging at the arm's start pose (its tip at
/// about y = −3 mm), with its flaps' centre 3 mm to the index side of it: the band in which
/// the strokes carried the rod the full 200 mm (replayed with MuJoCo, both hand models) was
/// y = −12 … 0 mm; 4 mm further to either side the flap met the middle finger's rounded
/// edge or the ring finger, and the strokes stalled.
const ROD_Y: f64 = -0.006;
const ROD_Z: f64 = 0.04;
/// H5's rod line (world y), m: under the index finger, whose tip hangs 4 cm to the index side
/// of the middle finger's, at y = −52 … −27 mm with all joints free (the open hand holds
/// index_abd at its limit) and −71 … −41 mm with abduction locked at zero (orca_5, orca_3,
/// orca_2; measured on the manufacturer's hand 8–12 cm up; the project's within 3 mm); the rod
/// lies where both overlap. The band (lock step, 10 seeds each of orca_full and orca_2 with
/// both hand models): y = −47 … −35 mm did the full 200 mm for 10 of 10 but one seed (orca_2,
/// the project's hand, at −35); at −49 mm the project's hand fell to 7 of 10 (orca_full), at
/// −33 mm orca_2 to 9 of 10 with both hands. The scene takes the middle.
const PINCH_ROD_Y: f64 = -0.041;
/// H5's flaps' half width across the rod, m: 24 mm wide, the flaps span y = −53 … −29 mm,
/// 16 mm clear of the resting middle finger's side (y ≈ −13 mm), so that it never holds one
/// folded. Flaps 16 mm wide did as well (10 of 10 seeds, orca_full and orca_2, both hand
/// models); 32 mm wide did at a 15 mm pitch.
const PINCH_FLAP_HALF_W: f64 = 0.012;
/// H5's distance between flaps along the rod, m. The index finger's stroke is shorter than the
/// middle finger's (its pad leaves a 12 cm flap some 4–5 cm on), and a flap standing 2–5 cm in
/// front of its resting pad is struck from above by the returning tip, folded back and held
/// down under the resting finger until the next pinch has passed it. At H4's 30 mm that
/// stalled the rod whenever a stroke left the next flap there (orca_full, seeds 1–20, the rod
/// at y = −46 mm: 14 of 20 with the manufacturer's hand, 9 with the project's; a 1 s rest
/// between strokes instead of 0.2 s did not help, 15 and 3 of 20, nor flap springs 2–5 times as
/// stiff; flaps 14 cm high only partly, 10 and 8 of 10 seeds). At 12.5 mm a flap stands within the pad's reach whatever a stroke leaves (15 and
/// 17.5 mm also did, with the project's hand 18–19 of 20 for orca_5). The
/// second flap stands `FLAP_FIRST_GAP` plus this pitch behind the first, so at the start it
/// stands in the resting index finger and is folded there when the scene loads (the rod kicked
/// 1–5 mm forward in the first 0.05 s, seeds 1–3, before the first pinch); with the row set back so that
/// the second flap stood 5 mm behind the finger, as H4's does, orca_5 did it for only 11 of 20
/// seeds and orca_3 for 16 (the manufacturer's hand).
const PINCH_FLAP_PITCH: f64 = 0.0125;
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

/// H2's tong (see the module docs), from the hinge's start (world x, y) and above the table,
/// m: the prong's face against the index finger's inner side and the paddle's face against
/// the ring finger's inner side, their span across the middle finger at rest, and the
/// plates' extent (along the rail, from the hinge; up, over the hanging fingertips).
const TONG_PRONG_FACE_Y: f64 = -0.02;
const TONG_SPAN: f64 = 0.058;
const TONG_PLATE_X: [f64; 2] = [-0.052, 0.006];
const TONG_PLATE_Z: [f64; 2] = [0.066, 0.094];
/// The plates' half thickness, m.
const TONG_PLATE_HALF_T: f64 = 0.001;
/// The lever's hinge (about world x) under the paddle, above the table, m.
const TONG_HINGE_Z: f64 = 0.055;
/// The shoe across the rail from the lever's hinge, m (the lever's arm): a push of the
/// paddle's top by d turns the lever by d / 0.039 rad and lifts the shoe by about
/// 0.08 m × that.
const TONG_SHOE_Y: f64 = 0.08;
/// The lever's travel, rad.
const TONG_LEVER_MAX: f64 = 0.45;
/// The tong's travel across the rail either way, m.
const TONG_SLIDE: f64 = 0.018;
/// The friction of the tong's slide across the rail, N: far less than the shoe's weight holds
/// the paddle with (some 0.2 N at its top), so that one finger alone slides the tong.
const TONG_SLIDE_FRICTION: f64 = 0.02;
/// The bumps' half width across the rail under H2's shoe, m.
const TONG_TRACK_HALF_W: f64 = 0.04;
/// The paddle's hinge across the rail from the rail's origin (world y), m.
const TONG_HINGE_Y: f64 = TONG_PRONG_FACE_Y + TONG_SPAN - TONG_PLATE_HALF_T;

/// Which tool's task the rail stands for: the number of bumps and the trigger (H1's paddle,
/// H2's and H3's tong; the tools' own shapes are not modelled, see the module docs).
#[derive(Debug, Clone, Copy)]
pub(super) enum RailGrip {
    /// H1: scissors (6 bumps).
    Scissors,
    /// H2: chopsticks (3 bumps; the tong, see the module docs).
    Chopsticks,
    /// H3: a syringe squeezed (4 bumps; H2's tong, see the module docs).
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

    /// The bumps' track across the rail: its centre from the hinge (world y) and its half
    /// width, m (wide enough for wherever the shoe is carried across).
    fn track(self) -> (f64, f64) {
        match self {
            RailGrip::Chopsticks | RailGrip::Syringe => {
                (TONG_HINGE_Y + TONG_SHOE_Y, TONG_TRACK_HALF_W)
            }
            RailGrip::Scissors => (SHOE_FROM_HINGE[1], BUMP_HALF[1]),
        }
    }
}

/// Bump `k`'s centre along world x from the hinge's start, m (behind the shoe).
fn bump_x(k: usize) -> f64 {
    SHOE_FROM_HINGE[0] - SHOE_HALF[0] - FIRST_BUMP - k as f64 * BUMP_PITCH
}

/// The carriage's slide (along −x) at which the dropped shoe's front is [`MARK_PAST_CLEAR`]
/// past bump `k`.
fn clear_mark(k: usize) -> f64 {
    SHOE_FROM_HINGE[0] - bump_x(k) + BUMP_HALF[0] + SHOE_HALF[0] + MARK_PAST_CLEAR
}

/// The rail along world x with its bumps and the carriage with its trigger, a mark past each
/// bump.
pub(super) fn rail_scaffold(grip: RailGrip) -> Scaffold {
    let n = grip.bumps();
    let travel = clear_mark(n - 1) + RUN_OUT;
    let (track_y, track_half_w) = grip.track();
    let floor_front = SHOE_FROM_HINGE[0] + SHOE_HALF[0] + 0.02;
    let floor_len = floor_front - bump_x(n - 1) + 0.02;
    let mut bodies = format!(
        "    <body name=\"rail\" pos=\"{}\">\n",
        nums(&[HINGE[0], HINGE[1], 0.0])
    );
    bodies.push_str(&format!(
        "      <geom name=\"rail_floor\" class=\"pomdar_fixture\" type=\"box\" size=\"{}\" pos=\"{}\"/>\n",
        nums(&[floor_len / 2.0, track_half_w + 0.008, FLOOR_TOP / 2.0]),
        nums(&[floor_front - floor_len / 2.0, track_y, FLOOR_TOP / 2.0])
    ));
    for k in 0..n {
        bodies.push_str(&format!(
            "      <geom name=\"bump_{k}\" class=\"pomdar_fixture\" type=\"box\" size=\"{}\" pos=\"{}\"/>\n",
            nums(&[BUMP_HALF[0], track_half_w, BUMP_HALF[2]]),
            nums(&[bump_x(k), track_y, FLOOR_TOP + BUMP_HALF[2]])
        ));
    }
    bodies.push_str(&match grip {
        RailGrip::Chopsticks | RailGrip::Syringe => tong_carriage_body(travel),
        RailGrip::Scissors => carriage_body(travel),
    });
    bodies.push_str("    </body>\n");
    Scaffold {
        bodies,
        mapping: PhysicsMapping {
            marks: (0..n).map(clear_mark).collect(),
            ..PhysicsMapping::joint("carriage_slide")
        },
    }
}

/// The carriage: an axle sliding back along the rail with the rear bar the fingers' backs
/// pull, carrying the lever (the trigger): the paddle standing on the hinge in front of the
/// fingers, and an arm back to the shoe. Only the rear bar, the paddle and the shoe touch
/// anything (the arm, the post and the axle pass through slots).
fn carriage_body(travel: f64) -> String {
    let shoe_z = FLOOR_TOP + SHOE_CLEAR + SHOE_HALF[2] - HINGE[2];
    let [shoe_x, shoe_y] = SHOE_FROM_HINGE;
    let paddle_half_h = (PADDLE_TOP - HINGE[2]) / 2.0;
    let [rear_x, rear_height] = REAR_BAR;
    let rear_z = rear_height - HINGE[2];
    let rear_y0 = -REAR_BAR_HALF_W - 0.005;
    format!(
        r#"      <body name="carriage" pos="0 0 {hinge_z}">
        <joint name="carriage_slide" class="pomdar_object" type="slide" axis="-1 0 0" range="0 {travel}" damping="0.3" frictionloss="{friction}"/>
        <geom name="carriage_axle" class="pomdar_object" contype="0" conaffinity="0" type="capsule" fromto="{axle}" size="0.003" mass="0.005"/>
        <geom name="carriage_rear_bar" class="pomdar_object" type="capsule" fromto="{rear}" size="0.004" mass="0.005"/>
        <geom name="carriage_rear_post" class="pomdar_object" contype="0" conaffinity="0" type="capsule" fromto="{post}" size="0.003" mass="0.002"/>
        <body name="trigger">
          <joint name="trigger_hinge" class="pomdar_object" type="hinge" axis="0 1 0" range="0 {lever_max}" stiffness="{spring}" springref="0" damping="0.002"/>
          <geom name="trigger_paddle" class="pomdar_object" type="box" size="{paddle_size}" pos="{paddle_pos}" mass="0.004"/>
          <geom name="trigger_arm" class="pomdar_object" contype="0" conaffinity="0" type="capsule" fromto="{arm}" size="0.003" mass="0.004"/>
          <geom name="trigger_pin" class="pomdar_object" contype="0" conaffinity="0" type="capsule" fromto="{pin}" size="0.003" mass="0.002"/>
          <geom name="carriage_shoe" class="pomdar_object" type="box" size="{shoe}" pos="{shoe_pos}" mass="0.01"/>
        </body>
      </body>
"#,
        hinge_z = num(HINGE[2]),
        travel = num(travel),
        friction = num(CARRIAGE_FRICTION),
        axle = nums(&[0.0, -PADDLE_HALF_W, 0.0, 0.0, PADDLE_HALF_W, 0.0]),
        rear = nums(&[
            rear_x,
            rear_y0,
            rear_z,
            rear_x,
            rear_y0 + 2.0 * REAR_BAR_HALF_W,
            rear_z
        ]),
        post = nums(&[0.0, -PADDLE_HALF_W, 0.0, rear_x, rear_y0, rear_z]),
        lever_max = num(LEVER_MAX),
        spring = num(LEVER_SPRING),
        paddle_size = nums(&[PADDLE_HALF_T, PADDLE_HALF_W, paddle_half_h]),
        paddle_pos = nums(&[PADDLE_X, 0.0, paddle_half_h]),
        arm = nums(&[0.0, 0.0, 0.0, shoe_x, 0.0, shoe_z]),
        pin = nums(&[shoe_x, 0.0, shoe_z, shoe_x, shoe_y, shoe_z]),
        shoe = nums(&SHOE_HALF),
        shoe_pos = nums(&[shoe_x, shoe_y, shoe_z]),
    )
}

/// H2's carriage: the axle and the rear bar as H1's, and the tong across the middle finger,
/// sliding freely across the rail: its prong stands beside the index finger's inner side, and
/// its lever, hinged about world x under the ring finger, carries the paddle beside the ring
/// finger's inner side and, on its arm across the rail, the shoe. The index and ring fingers
/// closing sideways onto one another squeeze the tong: the prong's slide stops against the
/// index finger, the ring finger turns the lever and lifts the shoe.
fn tong_carriage_body(travel: f64) -> String {
    let [x0, x1] = TONG_PLATE_X;
    let [z0, z1] = TONG_PLATE_Z;
    let plate_half = [(x1 - x0) / 2.0, TONG_PLATE_HALF_T, (z1 - z0) / 2.0];
    let plate_x = (x0 + x1) / 2.0;
    let plate_z = (z0 + z1) / 2.0;
    let [rear_x, rear_z] = REAR_BAR;
    let rear_y0 = -REAR_BAR_HALF_W - 0.005;
    let shoe_x = SHOE_FROM_HINGE[0];
    let shoe_z = FLOOR_TOP + SHOE_CLEAR + SHOE_HALF[2] - TONG_HINGE_Z;
    let prong_y = TONG_PRONG_FACE_Y + TONG_PLATE_HALF_T;
    format!(
        r#"      <body name="carriage" pos="0 0 0">
        <joint name="carriage_slide" class="pomdar_object" type="slide" axis="-1 0 0" range="0 {travel}" damping="0.3" frictionloss="{friction}"/>
        <geom name="carriage_axle" class="pomdar_object" contype="0" conaffinity="0" type="capsule" fromto="{axle}" size="0.003" mass="0.005"/>
        <geom name="carriage_rear_bar" class="pomdar_object" type="capsule" fromto="{rear}" size="0.004" mass="0.005"/>
        <body name="tong">
          <joint name="tong_slide" class="pomdar_object" type="slide" axis="0 1 0" range="{slide_lo} {slide}" damping="0.05" frictionloss="{slide_friction}"/>
          <geom name="tong_prong" class="pomdar_object" type="box" size="{plate}" pos="{prong_pos}" mass="0.003"/>
          <geom name="tong_bridge" class="pomdar_object" contype="0" conaffinity="0" type="capsule" fromto="{bridge}" size="0.002" mass="0.002"/>
          <body name="tong_lever" pos="{hinge}">
            <joint name="tong_hinge" class="pomdar_object" type="hinge" axis="1 0 0" range="0 {lever_max}" stiffness="0.002" springref="0" damping="0.002"/>
            <geom name="tong_paddle" class="pomdar_object" type="box" size="{plate}" pos="{paddle_pos}" mass="0.003"/>
            <geom name="tong_arm" class="pomdar_object" contype="0" conaffinity="0" type="capsule" fromto="{arm}" size="0.003" mass="0.003"/>
            <geom name="carriage_shoe" class="pomdar_object" type="box" size="{shoe}" pos="{shoe_pos}" mass="0.01"/>
          </body>
        </body>
      </body>
"#,
        travel = num(travel),
        friction = num(CARRIAGE_FRICTION),
        axle = nums(&[shoe_x, -0.02, 0.03, rear_x, -0.02, rear_z]),
        rear = nums(&[
            rear_x,
            rear_y0,
            rear_z,
            rear_x,
            rear_y0 + 2.0 * REAR_BAR_HALF_W,
            rear_z
        ]),
        slide_lo = num(-TONG_SLIDE),
        slide = num(TONG_SLIDE),
        slide_friction = num(TONG_SLIDE_FRICTION),
        plate = nums(&plate_half),
        prong_pos = nums(&[plate_x, prong_y, plate_z]),
        bridge = nums(&[plate_x, prong_y, z0, plate_x, TONG_HINGE_Y, TONG_HINGE_Z]),
        hinge = nums(&[0.0, TONG_HINGE_Y, TONG_HINGE_Z]),
        lever_max = num(TONG_LEVER_MAX),
        paddle_pos = nums(&[plate_x, 0.0, plate_z - TONG_HINGE_Z]),
        arm = nums(&[plate_x, 0.0, 0.0, shoe_x, TONG_SHOE_Y, shoe_z]),
        shoe = nums(&SHOE_HALF),
        shoe_pos = nums(&[shoe_x, TONG_SHOE_Y, shoe_z]),
    )
}

/// Which stroke feeds the rod: H4's and H5's scene, placed under the finger that strokes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum RodStroke {
    /// H4: a palmar grasp; the rod under the middle finger.
    Palmar,
    /// H5: the thumb–index pinch; the rod under the index finger, its flaps closer together.
    Pinch,
}

impl RodStroke {
    /// The rod's line across the table (world y) at the start, m.
    fn rod_y(self) -> f64 {
        match self {
            RodStroke::Palmar => ROD_Y,
            RodStroke::Pinch => PINCH_ROD_Y,
        }
    }

    /// A flap's half width across the rod, m.
    fn flap_half_w(self) -> f64 {
        match self {
            RodStroke::Palmar => FLAP_HALF[1],
            RodStroke::Pinch => PINCH_FLAP_HALF_W,
        }
    }

    /// The distance between flaps along the rod, m.
    fn flap_pitch(self) -> f64 {
        match self {
            RodStroke::Palmar => FLAP_PITCH,
            RodStroke::Pinch => PINCH_FLAP_PITCH,
        }
    }
}

/// The rod in two channels, sliding along world x, with its row of sprung flaps, placed for
/// `stroke`.
pub(super) fn rod_scaffold(stroke: RodStroke) -> Scaffold {
    let rod_y = stroke.rod_y();
    let mut bodies = String::from("    <body name=\"rod_supports\" pos=\"0 0 0\">\n");
    for (k, x) in ROD_SUPPORT_X.iter().enumerate() {
        bodies.push_str(&channel(k, *x, rod_y));
    }
    bodies.push_str("    </body>\n");
    let flaps = flap_count(stroke);
    let back = flap_x(stroke, flaps - 1) - 0.01;
    bodies.push_str(&format!(
        r#"    <body name="rod" pos="{pos}">
      <joint name="rod_slide" class="pomdar_object" type="slide" axis="1 0 0" range="0 {travel}" damping="0.5" frictionloss="0.2"/>
      <geom name="rod" class="pomdar_object" type="capsule" fromto="{back} 0 0 {front} 0 0" size="{r}" mass="0.06"/>
{flaps}    </body>
"#,
        pos = nums(&[RAIL_X, rod_y, ROD_Z]),
        travel = num(ROD_TRAVEL),
        back = num(back),
        front = num(ROD_FRONT),
        r = num(ROD_RADIUS),
        flaps = (0..flaps).map(|k| flap(stroke, k)).collect::<String>(),
    ));
    Scaffold {
        bodies,
        mapping: PhysicsMapping::joint("rod_slide"),
    }
}

/// Enough flaps that one stands in front of the hanging finger over the whole travel.
fn flap_count(stroke: RodStroke) -> usize {
    match stroke {
        RodStroke::Palmar => ((ROD_TRAVEL + FLAP_PITCH) / FLAP_PITCH).round() as usize + 1,
        // One more at H5's short pitch, for the first gap.
        RodStroke::Pinch => {
            let pitch = PINCH_FLAP_PITCH;
            ((ROD_TRAVEL + FLAP_FIRST_GAP + pitch) / pitch).ceil() as usize + 1
        }
    }
}

/// Flap `k`'s place along the rod, from the rod body's origin, m: the second one
/// `FLAP_FIRST_GAP` more than the stroke's pitch behind the first, the rest the stroke's pitch
/// apart.
fn flap_x(stroke: RodStroke, k: usize) -> f64 {
    let gap = if k == 0 { 0.0 } else { FLAP_FIRST_GAP };
    FLAP_FIRST_X - RAIL_X - gap - k as f64 * stroke.flap_pitch()
}

/// Flap `k` (the first in front of the finger, the others behind it), hinged on the rod's
/// top about world y: upright against its stop when pushed forward, folding back when pushed
/// from the front. Flaps touch the hand and the fixtures but not one another (contype 5 shares
/// a bit with both hand models' and the fixtures' conaffinity; conaffinity 0): a folded flap
/// lies in a slot in the rod.
fn flap(stroke: RodStroke, k: usize) -> String {
    let x = flap_x(stroke, k);
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
        size = nums(&[FLAP_HALF[0], stroke.flap_half_w(), half_height]),
        half = num(half_height),
    )
}

/// A post with a channel under the rod (1 mm clear of it), at world `x` on the rod's line
/// `rod_y`; its walls end below the rod's top so that the flaps pass over them.
fn channel(k: usize, x: f64, rod_y: f64) -> String {
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
        post_pos = nums(&[x, rod_y, floor / 2.0]),
        wall = nums(&[0.008, 0.003, wall_half]),
        wall_a = nums(&[x, rod_y + wall_y, floor + wall_half]),
        wall_b = nums(&[x, rod_y - wall_y, floor + wall_half]),
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
        for stroke in [RodStroke::Palmar, RodStroke::Pinch] {
            let xml = format!("<w>{}</w>", rod_scaffold(stroke).bodies);
            let doc = roxmltree::Document::parse(&xml).unwrap();
            let named = |name: &str| {
                doc.descendants()
                    .find(|n| n.attribute("name") == Some(name))
                    .unwrap()
            };
            let slide = named("rod_slide");
            assert_eq!(slide.attribute("axis"), Some("1 0 0"));
            assert!(floats(slide.attribute("range").unwrap())[1] > 0.2);
            assert_eq!(
                floats(named("rod").attribute("pos").unwrap())[1],
                stroke.rod_y()
            );
            let flaps: Vec<_> = doc
                .descendants()
                .filter(|n| n.tag_name().name() == "geom")
                .filter(|n| n.attribute("name").is_some_and(|v| v.starts_with("flap_")))
                .collect();
            assert_eq!(flaps.len(), flap_count(stroke));
            for geom in &flaps {
                // Flaps touch the hand and the fixtures, not one another.
                assert_eq!(geom.attribute("contype"), Some("5"));
                assert_eq!(geom.attribute("conaffinity"), Some("0"));
                assert_eq!(
                    floats(geom.attribute("size").unwrap())[1],
                    stroke.flap_half_w()
                );
            }
            // World x at the start: the first flap in front of the hanging finger's pad
            // (x ≈ 0.462), the second 5 mm or more behind its back (x ≈ 0.437) after a 5 mm
            // move (H4; H5's second flap stands in the resting index finger, see
            // `PINCH_FLAP_PITCH`, its third behind it).
            let first = RAIL_X + flap_x(stroke, 0);
            let second = RAIL_X + flap_x(stroke, 1);
            assert!(first - START_OFFSET_MAX_M > 0.462, "{stroke:?} {first}");
            match stroke {
                RodStroke::Palmar => assert!(
                    second + START_OFFSET_MAX_M <= 0.437 - 0.005 + 1e-9,
                    "{second}"
                ),
                RodStroke::Pinch => {
                    assert!(second < 0.462 - START_OFFSET_MAX_M, "{second}");
                    let third = RAIL_X + flap_x(stroke, 2);
                    assert!(third + START_OFFSET_MAX_M <= 0.437 + 1e-9, "{third}");
                }
            }
            // Enough flaps that the last is still behind the finger at the end of the travel.
            let last = RAIL_X + flap_x(stroke, flap_count(stroke) - 1);
            assert!(last + ROD_TRAVEL < 0.437, "{stroke:?} {last}");
        }
        // H5's flaps lie under the index finger wherever the start is moved — 5 mm or more of
        // their width under it with all joints free (y = −52 … −27 mm) and with abduction
        // locked (−71 … −41 mm) — and 10 mm or more clear of the resting middle finger's side
        // (y ≈ −13 mm).
        let inner = PINCH_ROD_Y + PINCH_FLAP_HALF_W;
        let outer = PINCH_ROD_Y - PINCH_FLAP_HALF_W;
        for shift in [-START_OFFSET_MAX_M, START_OFFSET_MAX_M] {
            for finger in [[-0.052, -0.027], [-0.071, -0.041]] {
                let overlap = (inner + shift).min(finger[1]) - (outer + shift).max(finger[0]);
                assert!(overlap >= 0.005, "{shift} {finger:?} {overlap}");
            }
        }
        assert!(
            inner + START_OFFSET_MAX_M <= -0.013 - 0.01 + 1e-9,
            "{inner}"
        );
        const { assert!(PINCH_FLAP_PITCH < FLAP_PITCH) };
    }

    #[test]
    fn the_rail_runs_along_x_and_the_trigger_lifts_the_shoe_over_the_bumps() {
        for (grip, n) in [
            (RailGrip::Scissors, 6),
            (RailGrip::Chopsticks, 3),
            (RailGrip::Syringe, 4),
        ] {
            let scaffold = rail_scaffold(grip);
            let xml = format!("<w>{}</w>", scaffold.bodies);
            let doc = roxmltree::Document::parse(&xml).unwrap();
            let named = |name: &str| {
                doc.descendants()
                    .find(|node| node.attribute("name") == Some(name))
                    .unwrap()
            };
            let slide = named("carriage_slide");
            assert_eq!(slide.attribute("axis"), Some("-1 0 0"));
            let travel = floats(slide.attribute("range").unwrap())[1];
            let marks = &scaffold.mapping.marks;
            assert_eq!(marks.len(), n);
            assert!(marks.windows(2).all(|w| w[1] > w[0]));
            assert!(marks[n - 1] < travel);
            // The lever at its stop holds the shoe's bottom over the bumps' tops.
            let (hinge, axis, lift) = match grip {
                RailGrip::Scissors => (
                    "trigger_hinge",
                    "0 1 0",
                    -SHOE_FROM_HINGE[0] * LEVER_MAX.sin(),
                ),
                RailGrip::Chopsticks | RailGrip::Syringe => {
                    let drop = TONG_HINGE_Z - FLOOR_TOP - SHOE_CLEAR - SHOE_HALF[2];
                    (
                        "tong_hinge",
                        "1 0 0",
                        TONG_SHOE_Y * TONG_LEVER_MAX.sin() - drop * (1.0 - TONG_LEVER_MAX.cos()),
                    )
                }
            };
            assert_eq!(named(hinge).attribute("axis"), Some(axis));
            assert!(
                SHOE_CLEAR + lift > 2.0 * BUMP_HALF[2] + 0.005,
                "{grip:?} {lift}"
            );
            // The dropped shoe meets the first bump behind it (the carriage travels along
            // −x), and each mark puts its front past the bump it counts.
            let shoe_back = SHOE_FROM_HINGE[0] - SHOE_HALF[0];
            assert!(shoe_back > bump_x(0) + BUMP_HALF[0]);
            for (k, mark) in marks.iter().enumerate() {
                let front = SHOE_FROM_HINGE[0] + SHOE_HALF[0] - mark;
                assert!(front < bump_x(k) - BUMP_HALF[0], "{k}");
            }
            // The paddle's face stands in front of the hanging fingers' pads (x ≈ 0.462) and
            // the rear bar behind their backs (x ≈ 0.437) wherever the start is moved, and the
            // arm's reach back (to x = 0.25) carries the carriage past the last mark.
            let face = HINGE[0] + PADDLE_X - PADDLE_HALF_T;
            assert!(face - START_OFFSET_MAX_M > 0.462, "{face}");
            let rear = HINGE[0] + REAR_BAR[0] + 0.004;
            assert!(rear + START_OFFSET_MAX_M < 0.437, "{rear}");
            assert!(0.45 - 0.25 > marks[n - 1] + 0.02, "{}", marks[n - 1]);
        }
    }

    #[test]
    fn the_tong_is_squeezed_only_by_fingers_closing_together_sideways() {
        let xml = format!("<w>{}</w>", rail_scaffold(RailGrip::Chopsticks).bodies);
        let doc = roxmltree::Document::parse(&xml).unwrap();
        let named = |name: &str| {
            doc.descendants()
                .find(|node| node.attribute("name") == Some(name))
                .unwrap()
        };
        assert_eq!(named("tong_slide").attribute("axis"), Some("0 1 0"));
        // Measured on both hand models, 6.6-9.4 cm up: the index and ring fingers' inner sides
        // 40-43 mm apart in the open hand (fingers together), 66-73 mm spread, 78-86 mm at
        // zero abduction. The span lies between, with room to turn the lever, and the tong's
        // slide carries it wherever the start is moved (5 mm, and 6 mm across a turned rail's
        // 12 cm).
        const { assert!(TONG_SPAN > 0.043 + 0.01 && TONG_SPAN < 0.066 - 0.005) };
        const { assert!(TONG_SLIDE > START_OFFSET_MAX_M + 0.007 + 0.005) };
        // The paddle's top lies over the hinge: a push across the rail turns the lever.
        const { assert!(TONG_PLATE_Z[1] - TONG_HINGE_Z > 0.03) };
        // The bumps span the shoe wherever the tong carries it.
        const { assert!(TONG_TRACK_HALF_W > TONG_SLIDE + SHOE_HALF[1] + 0.01) };
    }
}
