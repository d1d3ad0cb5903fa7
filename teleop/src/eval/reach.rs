//! `pomdar eval --reach`: the reachability bound and the per-digit scales as table lines
//! (computed by [`retarget::quality::Reachability`]).

use retarget::quality::Reachability;

/// The reachability report as table lines.
pub fn reach_lines(reach: &Reachability) -> String {
    let mut out = format!(
        "\n  reachability (targets s*·human, s* = {:.3}; nearest fingertip on a grid of at most \
         {} configurations per digit within the limits):\n  {:<8} {:>10} {:>7} {:>6} {:>18}\n",
        reach.tip_scale,
        reach.grid_max_configurations,
        "",
        "own scale",
        "joints",
        "steps",
        "nearest reach mm"
    );
    let opt = |v: Option<f64>, p: usize| v.map_or("-".into(), |v| format!("{v:.p$}"));
    for d in &reach.per_digit {
        out += &format!(
            "  {:<8} {:>10} {:>7} {:>6} {:>18}\n",
            d.digit,
            opt(d.own_scale, 3),
            d.joints,
            d.grid_steps_per_joint,
            opt(d.nearest_reachable_mean_mm, 1)
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use retarget::quality::DigitReach;

    #[test]
    fn every_digit_has_a_row_with_its_figures() {
        let reach = Reachability {
            tip_scale: 0.861,
            grid_max_configurations: 200_000,
            per_digit: vec![DigitReach {
                digit: "thumb".into(),
                own_scale: Some(0.58),
                joints: 4,
                grid_steps_per_joint: 21,
                nearest_reachable_mean_mm: Some(45.43),
            }],
        };
        let text = reach_lines(&reach);
        assert!(text.contains("s* = 0.861"), "{text}");
        let row = text
            .lines()
            .find(|l| l.trim_start().starts_with("thumb"))
            .unwrap();
        for figure in ["0.580", "4", "21", "45.4"] {
            assert!(row.contains(figure), "{row}");
        }
    }
}
