//! Line geometry for the trial review figure: series split at gaps, long runs thinned to
//! their pixel columns, and dashed or dotted lines as short polylines (the drawing
//! description has solid strokes only).

use super::primitives::Point;

/// The runs of `points` between gaps, mapped to pixels: a non-finite value ends a run;
/// points outside the time range `0..=duration` are left out.
pub(super) fn runs(
    points: &[(f64, f64)],
    duration: f64,
    to_px: impl Fn(f64, f64) -> Point,
) -> Vec<Vec<Point>> {
    let mut runs = Vec::new();
    let mut current = Vec::new();
    for &(t, v) in points {
        if !(0.0..=duration).contains(&t) {
            continue;
        }
        if v.is_finite() {
            current.push(to_px(t, v));
        } else if !current.is_empty() {
            runs.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        runs.push(current);
    }
    runs
}

/// `run` (pixels, left to right) with each pixel column reduced to its first, highest,
/// lowest and last point, in their order: the same envelope at a bounded size.
pub(super) fn thin(run: &[Point]) -> Vec<Point> {
    let mut out = Vec::with_capacity(run.len().min(4096));
    for column in run.chunk_by(|a, b| a.x.floor() == b.x.floor()) {
        let by_y = |pick: fn(f64, f64) -> bool| {
            (0..column.len()).fold(0, |best, k| {
                if pick(column[k].y, column[best].y) {
                    k
                } else {
                    best
                }
            })
        };
        let mut keep = [0, by_y(|a, b| a < b), by_y(|a, b| a > b), column.len() - 1];
        keep.sort_unstable();
        let mut previous = None;
        for k in keep {
            if previous != Some(k) {
                out.push(column[k]);
                previous = Some(k);
            }
        }
    }
    out
}

/// `line` cut into dashes `on` pixels long with `off` pixels between them, measured along
/// x (time), not along the line: a jittery series, whose path runs up and down within each
/// pixel column, still shows its gaps. A vertical piece belongs to the dash or gap it is in.
pub(super) fn dashes(line: &[Point], (on, off): (f64, f64)) -> Vec<Vec<Point>> {
    let mut out = Vec::new();
    let Some(&first) = line.first() else {
        return out;
    };
    let (mut drawing, mut left) = (true, on);
    let mut current = vec![first];
    for pair in line.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.x - a.x).abs();
        if length == 0.0 && drawing {
            current.push(b);
        }
        let mut done = 0.0;
        while done < length {
            let step = left.min(length - done);
            done += step;
            left -= step;
            let f = done / length;
            let p = Point::new(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y));
            if drawing {
                current.push(p);
            }
            if left <= 1e-9 {
                if drawing {
                    out.push(std::mem::take(&mut current));
                } else {
                    current = vec![p];
                }
                drawing = !drawing;
                left = if drawing { on } else { off };
            }
        }
    }
    if drawing && current.len() > 1 {
        out.push(current);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn review_runs_break_at_gaps_and_skip_points_outside_the_time_range() {
        let points = [
            (-1.0, 1.0),
            (0.0, 1.0),
            (1.0, f64::NAN),
            (2.0, 2.0),
            (3.0, 3.0),
            (9.0, 3.0),
        ];
        let runs = runs(&points, 5.0, Point::new);
        let lengths: Vec<usize> = runs.iter().map(Vec::len).collect();
        assert_eq!(lengths, [1, 2]);
    }

    #[test]
    fn review_thinning_keeps_each_columns_envelope() {
        let run: Vec<Point> = (0..1000)
            .map(|k| Point::new(k as f64 / 100.0, (k % 7) as f64))
            .collect();
        let thinned = thin(&run);
        assert!(thinned.len() <= 40, "{}", thinned.len());
        for column in thinned.chunk_by(|a, b| a.x.floor() == b.x.floor()) {
            let ys: Vec<f64> = column.iter().map(|p| p.y).collect();
            assert!(ys.contains(&0.0) && ys.contains(&6.0), "{ys:?}");
        }
    }

    #[test]
    fn review_dashes_follow_the_pattern_along_x() {
        let p = Point::new;
        let line = [p(0.0, 0.0), p(10.0, 0.0), p(10.0, 12.0), p(22.0, 12.0)];
        let cut = dashes(&line, (4.0, 2.0));
        // 22 px along x: dashes at 0–4, 6–10, 12–16, 18–22; the rise at 10 is in a gap.
        assert_eq!(
            cut,
            [
                vec![p(0.0, 0.0), p(4.0, 0.0)],
                vec![p(6.0, 0.0), p(10.0, 0.0)],
                vec![p(12.0, 12.0), p(16.0, 12.0)],
                vec![p(18.0, 12.0), p(22.0, 12.0)],
            ]
        );
        let step = [p(0.0, 0.0), p(2.0, 0.0), p(2.0, 10.0), p(4.0, 10.0)];
        assert_eq!(
            dashes(&step, (4.0, 2.0)),
            [step.to_vec()],
            "a rise inside a dash"
        );
    }
}
