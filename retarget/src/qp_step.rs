//! One Gauss–Newton step as a box-constrained QP. With [`QpMethod::ActiveSet`] (the default)
//! a step is first tried by the exact active-set method of `box_active_set`
//! (certified by the KKT conditions); when that gives no certified answer, or with
//! [`QpMethod::Clarabel`], Clarabel solves it:
//!
//! ```text
//! minimise  ½ Δᵀ P Δ + qᵀ Δ   subject to   l ≤ Δ ≤ u
//! ```
//!
//! posed for Clarabel as `A Δ + s = b`, `s ≥ 0` with `A = [I; −I]`, `b = [u; −l]`. The solver is
//! built once with a dense upper-triangular pattern for `P` and afterwards only its data is
//! updated in place (`update_P`, `update_q`, `update_b`; presolve off so updates are allowed).
//! The problem is scaled on every solve, `Δ = t D y` with `D = diag(1/√H_ii)` and
//! `t = ‖D g‖∞`, so the QP Clarabel sees has a unit diagonal and a linear term of unit size:
//! its minimiser and cost are O(1) and equally conditioned in every direction on every frame,
//! and the solver's absolute tolerances are relative to the step. (Clarabel's own equilibration is computed once at set-up and
//! reused by data updates, so it would go stale; it is turned off.) Weakly constrained
//! directions — an abduction joint of a strongly flexed finger — are then solved as accurately
//! as strong ones.

#![allow(non_snake_case)] // P, q, A, b: the QP's standard names

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::{DMatrix, DVector};

use crate::box_active_set::solve_box_qp;
use crate::retarget_config::QpMethod;

/// Which method solved a QP.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QpSolver {
    /// The exact active-set method, its answer certified by the KKT conditions.
    ActiveSet,
    /// Clarabel's interior-point method.
    Clarabel,
}

/// What one QP solve produced.
#[derive(Debug, Clone, PartialEq)]
pub struct QpOutcome {
    /// The method that produced the answer.
    pub solver: QpSolver,
    /// Clarabel's status (`Solved` for a certified active-set answer).
    pub status: SolverStatus,
    /// Active-set changes, or Clarabel's interior-point iterations.
    pub iterations: u32,
    /// Clarabel's own solve time, seconds.
    pub solve_time_s: f64,
}

impl QpOutcome {
    /// Whether the step in the buffer can be used.
    pub fn usable(&self) -> bool {
        matches!(
            self.status,
            SolverStatus::Solved | SolverStatus::AlmostSolved
        )
    }
}

/// A reusable box QP of fixed size.
pub struct BoxQp {
    n: usize,
    max_iterations: u32,
    method: QpMethod,
    solver: Option<DefaultSolver<f64>>,
    p_values: Vec<f64>,
    q: Vec<f64>,
    b: Vec<f64>,
    d: Vec<f64>,
}

impl std::fmt::Debug for BoxQp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BoxQp")
            .field("n", &self.n)
            .field("built", &self.solver.is_some())
            .finish()
    }
}

impl BoxQp {
    /// A QP over `n` variables, solved by `method`.
    pub fn new(n: usize, max_iterations: u32, method: QpMethod) -> BoxQp {
        BoxQp {
            n,
            max_iterations,
            method,
            solver: None,
            p_values: vec![0.0; n * (n + 1) / 2],
            q: vec![0.0; n],
            b: vec![0.0; 2 * n],
            d: vec![1.0; n],
        }
    }

    fn settings(&self) -> DefaultSettings<f64> {
        #[allow(clippy::expect_used)] // all fields are set to valid constants
        DefaultSettingsBuilder::default()
            .verbose(false)
            .presolve_enable(false)
            .equilibrate_enable(false)
            .max_iter(self.max_iterations)
            .build()
            .expect("valid Clarabel settings")
    }

    /// Solve for `H`, `g` (only the upper triangle of `H` is read) and bounds `lower ≤ Δ ≤
    /// upper`; the minimiser is written to `step`.
    pub fn solve(
        &mut self,
        H: &DMatrix<f64>,
        g: &DVector<f64>,
        lower: &[f64],
        upper: &[f64],
        step: &mut DVector<f64>,
    ) -> QpOutcome {
        if self.method == QpMethod::ActiveSet
            && let Some((x, iterations)) = solve_box_qp(H, g, lower, upper, 4 * self.n + 4)
        {
            step.copy_from(&x);
            return QpOutcome {
                solver: QpSolver::ActiveSet,
                status: SolverStatus::Solved,
                iterations,
                solve_time_s: 0.0,
            };
        }
        let n = self.n;
        let floor = 1e-12 * (0..n).map(|i| H[(i, i)]).fold(f64::MIN_POSITIVE, f64::max);
        for i in 0..n {
            self.d[i] = 1.0 / H[(i, i)].max(floor).sqrt();
        }
        // Dense upper triangle of D H D, column by column (CSC order); the t² of the scaled
        // objective divides out.
        let mut k = 0;
        for col in 0..n {
            for row in 0..=col {
                self.p_values[k] = self.d[row] * H[(row, col)] * self.d[col];
                k += 1;
            }
        }
        let t = (0..n)
            .map(|i| (g[i] * self.d[i]).abs())
            .fold(1e-300, f64::max);
        for i in 0..n {
            self.q[i] = g[i] * self.d[i] / t;
            self.d[i] *= t;
            self.b[i] = upper[i] / self.d[i];
            self.b[n + i] = -lower[i] / self.d[i];
        }

        let solver = match &mut self.solver {
            Some(solver) => {
                let updated = solver
                    .update_P(&self.p_values)
                    .and_then(|_| solver.update_q(&self.q))
                    .and_then(|_| solver.update_b(&self.b));
                if updated.is_err() {
                    self.solver = None;
                    return self.solve(H, g, lower, upper, step);
                }
                solver
            }
            None => {
                let built = DefaultSolver::new(
                    &self.p_matrix(),
                    &self.q,
                    &self.a_matrix(),
                    &self.b,
                    &[SupportedConeT::NonnegativeConeT(2 * n)],
                    self.settings(),
                );
                match built {
                    Ok(solver) => self.solver.insert(solver),
                    Err(_) => {
                        return QpOutcome {
                            solver: QpSolver::Clarabel,
                            status: SolverStatus::NumericalError,
                            iterations: 0,
                            solve_time_s: 0.0,
                        };
                    }
                }
            }
        };
        solver.solve();
        let solution = &solver.solution;
        for (i, y) in solution.x.iter().enumerate() {
            step[i] = y * self.d[i];
        }
        QpOutcome {
            solver: QpSolver::Clarabel,
            status: solution.status,
            iterations: solution.iterations,
            solve_time_s: solution.solve_time,
        }
    }

    fn p_matrix(&self) -> CscMatrix<f64> {
        let n = self.n;
        let mut colptr = Vec::with_capacity(n + 1);
        let mut rowval = Vec::with_capacity(self.p_values.len());
        colptr.push(0);
        for col in 0..n {
            rowval.extend(0..=col);
            colptr.push(rowval.len());
        }
        CscMatrix::new(n, n, colptr, rowval, self.p_values.clone())
    }

    fn a_matrix(&self) -> CscMatrix<f64> {
        // Column j has +1 at row j and −1 at row n + j.
        let n = self.n;
        let colptr = (0..=n).map(|j| 2 * j).collect();
        let rowval = (0..n).flat_map(|j| [j, n + j]).collect();
        let nzval = (0..n).flat_map(|_| [1.0, -1.0]).collect();
        CscMatrix::new(2 * n, n, colptr, rowval, nzval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_box_qp_with_an_active_bound_and_reuses_the_solver() {
        // minimise (x0 − 1)² + (x1 + 2)² + x0·x1 with x1 ≥ −1: golden answer by hand,
        // stationarity in x0 with x1 = −1: 2(x0 − 1) + x1 = 0 ⇒ x0 = 1.5.
        let H = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
        let g = DVector::from_vec(vec![-2.0, 4.0]);
        let mut qp = BoxQp::new(2, 50, QpMethod::Clarabel);
        let mut x = DVector::zeros(2);
        let out = qp.solve(&H, &g, &[-10.0, -1.0], &[10.0, 10.0], &mut x);
        assert!(out.usable(), "{out:?}");
        assert!(
            (x[0] - 1.5).abs() < 1e-6 && (x[1] + 1.0).abs() < 1e-6,
            "{x}"
        );

        // Second solve on the same solver with new data: unconstrained optimum of
        // 2x0² + 2x1² + 2x0x1 − 2x0 − 2x1 ⇒ [[2,1],[1,2]] x = [1,1] ⇒ x = (1/3, 1/3).
        let g2 = DVector::from_vec(vec![-1.0, -1.0]);
        let out = qp.solve(&H, &g2, &[-10.0, -10.0], &[10.0, 10.0], &mut x);
        assert!(out.usable());
        assert!(
            (x[0] - 1.0 / 3.0).abs() < 1e-6 && (x[1] - 1.0 / 3.0).abs() < 1e-6,
            "{x}"
        );
    }

    #[test]
    fn scaling_does_not_move_the_minimiser() {
        let H = DMatrix::from_row_slice(2, 2, &[4e-6, 0.0, 0.0, 1e-6]);
        let g = DVector::from_vec(vec![-4e-6, 2e-6]);
        let mut qp = BoxQp::new(2, 50, QpMethod::Clarabel);
        let mut x = DVector::zeros(2);
        assert!(
            qp.solve(&H, &g, &[-5.0, -5.0], &[5.0, 5.0], &mut x)
                .usable()
        );
        assert!(
            (x[0] - 1.0).abs() < 1e-6 && (x[1] + 2.0).abs() < 1e-6,
            "{x}"
        );
    }
}
