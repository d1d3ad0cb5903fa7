//! Student's t distribution: its CDF and quantile, through the regularized incomplete beta
//! function, for the comparison's confidence intervals.
//!
//! ```text
//! I_x(a, b) = B(x; a, b) / B(a, b)                       regularized incomplete beta
//! F_ν(t)    = 1 − ½ · I_{ν/(ν+t²)}(ν/2, ½)     t ≥ 0      the t CDF, ν > 0 (not only integers)
//! F_ν(−t)   = 1 − F_ν(t)
//! t_ν(p)    = the t with F_ν(t) = p                       the quantile
//! ```
//!
//! `I_x` is the continued fraction
//!
//! ```text
//! I_x(a, b) = x^a (1−x)^b / (a · B(a, b)) · 1 / (1 + d₁ / (1 + d₂ / (1 + …)))
//! d_{2m+1}  = −(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1))
//! d_{2m}    = m (b − m) x / ((a + 2m − 1)(a + 2m))
//! ```
//!
//! evaluated by the modified Lentz method where it converges fast, x < (a + 1)/(a + b + 2),
//! and through `I_x(a, b) = 1 − I_{1−x}(b, a)` elsewhere; `ln B` from `ln Γ` by the Lanczos
//! approximation (g = 7, nine terms; relative error about 1e-15). The quantile is found by
//! bisection on the tail, which is monotone: slow-ish (about a hundred CDF evaluations) but
//! it cannot diverge, and the intervals need a handful of quantiles per report.

/// Relative accuracy the continued fraction stops at.
const EPSILON: f64 = 1e-15;
/// Continued-fraction terms before giving up (convergence takes O(√max(a, b)) terms).
const MAX_TERMS: usize = 10_000;
/// Guard against a zero denominator in Lentz's method.
const TINY: f64 = 1e-300;

/// ln Γ(x) for x > 0 (Lanczos, g = 7, nine coefficients; reflection below ½).
pub fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const COEFFICIENTS: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Γ(x) Γ(1 − x) = π / sin(πx)
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut sum = COEFFICIENTS[0];
    for (k, c) in COEFFICIENTS.iter().enumerate().skip(1) {
        sum += c / (x + k as f64);
    }
    let t = x + G + 0.5;
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// ln B(a, b) = ln Γ(a) + ln Γ(b) − ln Γ(a + b).
fn ln_beta(a: f64, b: f64) -> f64 {
    ln_gamma(a) + ln_gamma(b) - ln_gamma(a + b)
}

/// The regularized incomplete beta function `I_x(a, b)` for `a, b > 0`, `x ∈ [0, 1]`;
/// `None` outside that domain or if the continued fraction does not converge.
pub fn regularized_incomplete_beta(x: f64, a: f64, b: f64) -> Option<f64> {
    if !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite() && (0.0..=1.0).contains(&x)) {
        return None;
    }
    if x == 0.0 || x == 1.0 {
        return Some(x);
    }
    if x < (a + 1.0) / (a + b + 2.0) {
        beta_continued_fraction(x, a, b)
    } else {
        beta_continued_fraction(1.0 - x, b, a).map(|v| 1.0 - v)
    }
}

/// `I_x(a, b)` by its continued fraction (modified Lentz); accurate for
/// x < (a + 1)/(a + b + 2).
fn beta_continued_fraction(x: f64, a: f64, b: f64) -> Option<f64> {
    let front = (a * x.ln() + b * (1.0 - x).ln() - ln_beta(a, b)).exp() / a;
    let guard = |v: f64| if v.abs() < TINY { TINY } else { v };
    // f = 1 + d₁/(1 + d₂/(1 + …)), evaluated from the front: f₀ = 1, C₀ = f₀, D₀ = 0.
    let (mut f, mut c, mut d) = (1.0_f64, 1.0_f64, 0.0_f64);
    for j in 1..=MAX_TERMS {
        let m = (j / 2) as f64;
        let coefficient = if j % 2 == 1 {
            -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0))
        } else {
            m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m))
        };
        d = 1.0 / guard(1.0 + coefficient * d);
        c = guard(1.0 + coefficient / c);
        let delta = c * d;
        f *= delta;
        if (delta - 1.0).abs() < EPSILON {
            return Some(front / f);
        }
    }
    None
}

/// The upper tail `P(T > t) = ½ · I_{ν/(ν+t²)}(ν/2, ½)` for `t ≥ 0`.
fn upper_tail(t: f64, df: f64) -> Option<f64> {
    regularized_incomplete_beta(df / (df + t * t), df / 2.0, 0.5).map(|i| 0.5 * i)
}

/// The CDF of Student's t with `df` degrees of freedom (any real `df > 0`); `None` for a
/// `df` that is not positive and finite or a `t` that is NaN.
pub fn student_t_cdf(t: f64, df: f64) -> Option<f64> {
    if !(df > 0.0 && df.is_finite()) || t.is_nan() {
        return None;
    }
    if t.is_infinite() {
        return Some(if t > 0.0 { 1.0 } else { 0.0 });
    }
    let tail = upper_tail(t.abs(), df)?;
    Some(if t >= 0.0 { 1.0 - tail } else { tail })
}

/// The quantile `t_ν(p)` of Student's t with `df` degrees of freedom: the `t` with
/// `F_ν(t) = p`. `None` for `p` outside (0, 1) or a `df` that is not positive and finite.
pub fn student_t_quantile(p: f64, df: f64) -> Option<f64> {
    if !(p > 0.0 && p < 1.0 && df > 0.0 && df.is_finite()) {
        return None;
    }
    if p == 0.5 {
        return Some(0.0);
    }
    // Solve upper_tail(t) = q for t ≥ 0, q < ½; the tail falls from ½ at t = 0 towards 0.
    let q = p.min(1.0 - p);
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    while upper_tail(hi, df)? > q {
        lo = hi;
        hi *= 2.0;
        if !hi.is_finite() {
            return None;
        }
    }
    for _ in 0..2_000 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi || hi - lo <= 2.0 * f64::EPSILON * hi {
            break;
        }
        if upper_tail(mid, df)? > q {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = 0.5 * (lo + hi);
    Some(if p > 0.5 { t } else { -t })
}

#[cfg(test)]
#[path = "student_t_tests.rs"]
mod tests;
