//! Series colours: the Okabe–Ito colour-blind-safe set, ordered so the first colours differ
//! most on white (yellow, the weakest on white, comes last).

use super::primitives::Rgba;

/// Series colours in the order series receive them.
pub const SERIES_COLORS: [Rgba; 8] = [
    Rgba::rgb(0x00, 0x72, 0xB2), // blue
    Rgba::rgb(0xD5, 0x5E, 0x00), // vermillion
    Rgba::rgb(0x00, 0x9E, 0x73), // bluish green
    Rgba::rgb(0xCC, 0x79, 0xA7), // reddish purple
    Rgba::rgb(0xE6, 0x9F, 0x00), // orange
    Rgba::rgb(0x56, 0xB4, 0xE9), // sky blue
    Rgba::rgb(0x00, 0x00, 0x00), // black
    Rgba::rgb(0xF0, 0xE4, 0x42), // yellow
];

/// The colour of series number `index` (0-based); colours repeat after the eighth.
pub fn series_color(index: usize) -> Rgba {
    SERIES_COLORS[index % SERIES_COLORS.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_are_distinct_opaque_and_not_white() {
        for (i, a) in SERIES_COLORS.iter().enumerate() {
            assert_eq!(a.a, 255);
            assert_ne!(*a, Rgba::WHITE);
            for b in &SERIES_COLORS[i + 1..] {
                assert_ne!(a, b);
            }
        }
        assert_eq!(series_color(8), series_color(0));
    }
}
