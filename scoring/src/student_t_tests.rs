//! `student_t`'s tests: against closed forms (ν = 1: Cauchy, ν = 2), the classic table values
//! and figures from SciPy 1.17.1 (`scipy.stats.t.ppf`, `scipy.special.betainc`), each quoted
//! where it is used.

use super::*;

fn close(actual: Option<f64>, expected: f64, relative: f64, what: &str) {
    let actual = actual.unwrap_or(f64::NAN);
    assert!(
        (actual - expected).abs() <= relative * expected.abs().max(1e-300),
        "{what}: {actual} != {expected}"
    );
}

#[test]
fn ln_gamma_matches_factorials_and_the_half() {
    // Γ(n) = (n − 1)!, Γ(½) = √π, Γ(3/2) = √π / 2.
    let mut factorial = 1.0_f64;
    for n in 1..30 {
        let got = ln_gamma(f64::from(n));
        assert!(
            (got - factorial.ln()).abs() < 1e-13 * factorial.ln().max(1.0),
            "ln Γ({n}) = {got}"
        );
        factorial *= f64::from(n);
    }
    let ln_sqrt_pi = 0.5 * std::f64::consts::PI.ln();
    assert!((ln_gamma(0.5) - ln_sqrt_pi).abs() < 1e-14);
    assert!((ln_gamma(1.5) - (ln_sqrt_pi - 2.0_f64.ln())).abs() < 1e-14);
    // Reflection: Γ(0.25) = 3.625609908221908...
    assert!((ln_gamma(0.25) - 3.625_609_908_221_908_f64.ln()).abs() < 1e-13);
}

#[test]
fn incomplete_beta_matches_closed_forms() {
    for x in [0.0, 1e-6, 0.1, 0.37, 0.5, 0.81, 0.999, 1.0] {
        // I_x(1, 1) = x; I_x(a, 1) = x^a; I_x(1, b) = 1 − (1 − x)^b.
        close(regularized_incomplete_beta(x, 1.0, 1.0), x, 1e-13, "I(1,1)");
        close(
            regularized_incomplete_beta(x, 3.5, 1.0),
            x.powf(3.5),
            1e-12,
            "I(a,1)",
        );
        let expected = 1.0 - (1.0 - x).powf(2.25);
        let got = regularized_incomplete_beta(x, 1.0, 2.25).unwrap();
        assert!((got - expected).abs() < 1e-14, "I(1,b) at {x}: {got}");
    }
    // SciPy: betainc(2.5, 0.5, 0.3) = 0.018927124071945658, betainc(10, 0.5, 0.9) =
    // 0.15164090963470994, betainc(0.5, 0.5, 0.5) = 0.5, betainc(3, 4, 0.2) = 0.09888.
    close(
        regularized_incomplete_beta(0.3, 2.5, 0.5),
        0.018_927_124_071_945_658,
        1e-12,
        "I_0.3(2.5, .5)",
    );
    close(
        regularized_incomplete_beta(0.9, 10.0, 0.5),
        0.151_640_909_634_709_94,
        1e-12,
        "I_0.9(10, .5)",
    );
    close(
        regularized_incomplete_beta(0.5, 0.5, 0.5),
        0.5,
        1e-13,
        "I_.5",
    );
    close(
        regularized_incomplete_beta(0.2, 3.0, 4.0),
        0.098_88,
        1e-12,
        "I_0.2(3,4)",
    );
    assert_eq!(regularized_incomplete_beta(1.2, 1.0, 1.0), None);
    assert_eq!(regularized_incomplete_beta(0.5, 0.0, 1.0), None);
    assert_eq!(regularized_incomplete_beta(f64::NAN, 1.0, 1.0), None);
}

#[test]
fn the_cdf_matches_cauchy_and_two_degrees_of_freedom() {
    for t in [-30.0, -2.0, -0.3, 0.0, 0.7, 1.0, 4.2, 250.0] {
        // ν = 1 (Cauchy): F(t) = ½ + atan(t)/π.  ν = 2: F(t) = ½ + t / (2 √(2 + t²)).
        let cauchy = 0.5 + f64::atan(t) / std::f64::consts::PI;
        let two = 0.5 + t / (2.0 * (2.0 + t * t).sqrt());
        assert!(
            (student_t_cdf(t, 1.0).unwrap() - cauchy).abs() < 1e-14,
            "ν=1, t={t}"
        );
        assert!(
            (student_t_cdf(t, 2.0).unwrap() - two).abs() < 1e-14,
            "ν=2, t={t}"
        );
    }
    assert_eq!(student_t_cdf(f64::INFINITY, 3.0), Some(1.0));
    assert_eq!(student_t_cdf(1.0, 0.0), None);
    assert_eq!(student_t_cdf(f64::NAN, 3.0), None);
}

#[test]
fn quantiles_match_the_table() {
    // Two-sided 95 % table values (and SciPy's t.ppf to 16 digits).
    for (p, df, expected) in [
        (0.975, 1.0, 12.706_204_736_174_694),
        (0.975, 2.0, 4.302_652_729_749_462),
        (0.975, 5.0, 2.570_581_835_636_314_6),
        (0.975, 30.0, 2.042_272_456_301_237_8),
        (0.95, 10.0, 1.812_461_122_811_675_6),
        (0.995, 3.0, 5.840_909_309_733_355),
        (0.6, 4.0, 0.270_722_294_707_597_6),
        (0.025, 7.0, -2.364_624_251_592_784_4),
        // Non-integer degrees of freedom, as Welch's interval has them.
        (0.975, 2.5, 3.574_654_842_003_681_7),
        (0.975, 5.882_352_941_176_471, 2.458_823_709_699_146),
        (0.999, 1.3, 89.922_428_981_88),
        // Near the normal: z(0.975) = 1.959964; SciPy at ν = 1e6: 1.959966356814107.
        (0.975, 1e6, 1.959_966_356_814_107),
    ] {
        close(
            student_t_quantile(p, df),
            expected,
            1e-9,
            &format!("t({p}, {df})"),
        );
    }
    // The printed table, to half a unit of its last digit.
    for (df, printed, half_unit) in [
        (1.0, 12.706, 5e-4),
        (5.0, 2.5706, 5e-5),
        (30.0, 2.0423, 5e-5),
    ] {
        let t = student_t_quantile(0.975, df).unwrap();
        assert!((t - printed).abs() <= half_unit, "t(0.975, {df}) = {t}");
    }
}

#[test]
fn quantiles_invert_the_cdf_and_match_the_closed_forms() {
    for df in [1.0, 1.7, 2.0, 3.0, 8.5, 40.0, 1_000.0] {
        for p in [1e-6, 0.001, 0.025, 0.2, 0.5, 0.77, 0.975, 0.9999] {
            let t = student_t_quantile(p, df).unwrap();
            let back = student_t_cdf(t, df).unwrap();
            assert!(
                (back - p).abs() < 1e-12 * p.max(1e-3),
                "ν={df} p={p}: {back}"
            );
        }
    }
    for p in [0.6, 0.9, 0.975, 0.9995] {
        // ν = 1: t = tan(π (p − ½)).  ν = 2: t = (2p − 1) / √(2 p (1 − p)).
        let cauchy = (std::f64::consts::PI * (p - 0.5)).tan();
        close(student_t_quantile(p, 1.0), cauchy, 1e-11, "Cauchy quantile");
        let two = (2.0 * p - 1.0) / (2.0 * p * (1.0 - p)).sqrt();
        close(student_t_quantile(p, 2.0), two, 1e-11, "ν=2 quantile");
    }
    assert_eq!(student_t_quantile(0.5, 3.0), Some(0.0));
    for (p, df) in [
        (0.0, 3.0),
        (1.0, 3.0),
        (0.9, 0.0),
        (0.9, f64::INFINITY),
        (f64::NAN, 2.0),
    ] {
        assert_eq!(student_t_quantile(p, df), None, "p={p} ν={df}");
    }
}
