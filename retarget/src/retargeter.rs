//! [`Retargeter`]: per-frame energy minimisation by Gauss–Newton steps, each a box QP.
//!
//! For free joints `q` (the embodiment's unlocked degrees of freedom; the others stay at
//! their neutral value exactly), previous command `q₋`, the energy is
//!
//! ```text
//! E(q) = Σ_k w_k ρ_δ(‖r_k(q) − t_k‖) + ½ λ ‖q − q₋‖² + ½ μ Σ_{j ∈ abd} (q_j − q_rest,j)²
//! ```
//!
//! (key vectors `r_k`, targets `t_k`: see [`crate::energy`]). A step linearises
//! `r_k(q + Δ) ≈ r_k(q) + J_k Δ`, reweights each residual by `min(1, δ/‖e_k‖)` (IRLS for the
//! Huber function ρ) and solves
//!
//! ```text
//! min_Δ ½ Δᵀ (Σ w̃_k J_kᵀ J_k + (λ + ε) I + μ D) Δ + (Σ w̃_k J_kᵀ e_k + λ (q − q₋) + μ D (q − q_rest))ᵀ Δ
//! s.t.  max(q_min, q₋ − v·τ) − q ≤ Δ ≤ min(q_max, q₋ + v·τ) − q
//! ```
//!
//! with `τ = min(dt, max_rate_dt)`, the joint speed limit `v` and damping `ε`. A step is
//! accepted when it lowers the true energy (halving it up to four times); the frame ends when
//! a step is below tolerance, no step lowers the energy, or the step budget is spent. Every
//! iterate lies in the box, so the returned command is always within limits and rate bounds.

#![allow(non_snake_case)] // H, g: the normal equations

use nalgebra::{DMatrix, DVector, Matrix3xX, Point3, Vector3};

use crate::calibration_transform::CalibrationTransform;
use crate::embodiment::EmbodimentCatalog;
use crate::energy::{
    KEY_VECTORS, KeyVector, POINTS, accumulate_key_vectors, key_vector_energy, key_vector_targets,
    pinch_activation,
};
use crate::error::Error;
use crate::forward_kinematics::FkState;
use crate::hand_model::HandModel;
use crate::hand_model::LinkId;
use crate::human_key_vectors::{HumanKeyVectors, human_key_vectors};
use crate::one_euro::KeyPointFilter;
use crate::pinch_approach::PinchApproach;
use crate::qp_step::{BoxQp, QpSolver};
use crate::retarget_config::RetargetConfig;

/// How a frame's solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolveStatus {
    /// The last step was below tolerance, or no step could lower the energy further.
    Converged,
    /// The step budget ran out first; the command is the best iterate, still feasible.
    StepLimit,
    /// A QP failed (status named); the command is the best iterate before it.
    QpFailed(&'static str),
}

/// The result of one frame: the command and how it was obtained.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// How the solve ended.
    pub status: SolveStatus,
    /// The joint command, radians, one value per degree of freedom of the model.
    pub q: Vec<f64>,
    /// Gauss–Newton steps taken (QPs solved).
    pub steps: u32,
    /// QPs the exact active-set method solved.
    pub qp_active_set: u32,
    /// QPs Clarabel solved (all of them with `solver.qp_method = "clarabel"`; otherwise the
    /// active set's fallbacks).
    pub qp_clarabel: u32,
    /// Iterations over all QPs: active-set changes plus Clarabel's interior-point iterations.
    pub qp_iterations: u32,
    /// Energy at the previous command, for this frame's targets.
    pub cost_before: f64,
    /// Energy at the returned command.
    pub cost_after: f64,
    /// Clarabel's solve time summed over the frame's QPs, seconds.
    pub qp_time_s: f64,
    /// Mean over the 5 palm → fingertip key vectors of ‖robot − target‖, metres.
    pub tip_error_m: f64,
    /// Weight of the pull toward the previous command in the returned solve (per rad²):
    /// `regularisation.previous_command` plus the residual-adaptive smoothing.
    pub prior_weight: f64,
}

/// The retargeter for one hand model, configuration and calibration.
///
/// ```
/// use retarget::{EmbodimentCatalog, HandModel, KeypointLayout, RetargetConfig, Retargeter};
///
/// let model = HandModel::orca_v1_right();
/// let mut retargeter =
///     Retargeter::new(model.clone(), RetargetConfig::default(), &EmbodimentCatalog::builtin())?;
/// // Keypoints of the robot itself at a pose, in the lab's 22-point layout.
/// let mut q = model.zero_pose();
/// q[model.dof_index("index_mcp").unwrap()] = 0.9;
/// let keypoints = model.synthetic_keypoints(&model.forward_new(&q)?, KeypointLayout::Lab22);
/// for _ in 0..25 {
///     let solution = retargeter.retarget(&keypoints, 0.04)?; // 25 Hz
///     assert!(model.within_limits(&solution.q));
/// }
/// let index_mcp = retargeter.command()[model.dof_index("index_mcp").unwrap()];
/// assert!((index_mcp - 0.9).abs() < 0.05);
/// # Ok::<(), retarget::Error>(())
/// ```
#[derive(Debug)]
pub struct Retargeter {
    model: HandModel,
    config: RetargetConfig,
    transform: CalibrationTransform,
    /// Degrees of freedom solved for.
    free: Vec<usize>,
    /// Rest targets, as (position in `free`, radians).
    rest: Vec<(usize, f64)>,
    neutral: Vec<f64>,
    command: Vec<f64>,
    fk: FkState,
    /// The links behind the energy's points: 5 fingertips, then 5 mid frames (the tips again
    /// for a model without mid frames; their key vectors then weigh 0).
    point_links: [LinkId; POINTS],
    full_jacobian: Matrix3xX<f64>,
    point_jacobians: [Matrix3xX<f64>; POINTS],
    scratch: Matrix3xX<f64>,
    H: DMatrix<f64>,
    g: DVector<f64>,
    step: DVector<f64>,
    limits: Vec<crate::hand_model::Limits>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    lower_step: Vec<f64>,
    upper_step: Vec<f64>,
    trial: Vec<f64>,
    qp: BoxQp,
    /// The pull toward the previous command in this frame's energy, per degree of freedom
    /// (per rad²).
    pull: Vec<f64>,
    /// Per degree of freedom, the digit it moves alone (`None`: shared or none).
    dof_digits: Vec<Option<crate::finger::Finger>>,
    /// How fast the human's thumb closes on each finger.
    approach: PinchApproach,
    /// The previous command, kept for the smoothing's second solve (no allocation per frame).
    previous: Vec<f64>,
    /// The speed-adaptive filter of the human key points.
    filter: KeyPointFilter,
}

impl Retargeter {
    /// Build a retargeter; the embodiment named in `config` comes from `catalog`.
    pub fn new(
        model: HandModel,
        config: RetargetConfig,
        catalog: &EmbodimentCatalog,
    ) -> Result<Retargeter, Error> {
        config.validate()?;
        let embodiment = catalog
            .get(&config.embodiment)
            .ok_or_else(|| Error::BadEmbodiment {
                embodiment: config.embodiment.clone(),
                problem: format!(
                    "not in the catalog (known: {})",
                    catalog.names().collect::<Vec<_>>().join(", ")
                ),
            })?;
        let mask = embodiment.unlocked_mask(&model)?;
        let free: Vec<usize> = (0..model.dof()).filter(|&i| mask[i]).collect();
        let mut neutral = model.zero_pose();
        let mut rest = Vec::new();
        for (joint, &value) in &config.rest_posture_rad {
            let dof = model.dof_index(joint).ok_or_else(|| Error::ConfigRange {
                key: format!("rest_posture_rad.{joint}"),
                value: value.to_string(),
                allowed: format!("'{joint}' is not a joint of model '{}'", model.name()),
            })?;
            let limits = model.dofs()[dof].limits;
            if !limits.contains(value) {
                return Err(Error::ConfigRange {
                    key: format!("rest_posture_rad.{joint}"),
                    value: value.to_string(),
                    allowed: format!(
                        "must be within the joint limits [{}, {}]",
                        limits.lower_rad, limits.upper_rad
                    ),
                });
            }
            if let Some(position) = free.iter().position(|&f| f == dof) {
                rest.push((position, value));
                neutral[dof] = value;
            }
        }
        let n = free.len();
        let dof = model.dof();
        let frames = model.frames();
        let mids = frames.mids.unwrap_or(frames.tips);
        let point_links = std::array::from_fn(|i| if i < 5 { frames.tips[i] } else { mids[i - 5] });
        let mut config = config;
        if frames.mids.is_none() {
            config.weights.palm_to_mid = 0.0;
        }
        Ok(Retargeter {
            point_links,
            fk: model.fk_state(),
            full_jacobian: Matrix3xX::zeros(dof),
            point_jacobians: std::array::from_fn(|_| Matrix3xX::zeros(n)),
            scratch: Matrix3xX::zeros(n),
            H: DMatrix::zeros(n, n),
            g: DVector::zeros(n),
            step: DVector::zeros(n),
            limits: model.limits().collect(),
            lower: vec![0.0; n],
            upper: vec![0.0; n],
            lower_step: vec![0.0; n],
            upper_step: vec![0.0; n],
            trial: neutral.clone(),
            qp: BoxQp::new(n, config.solver.qp_max_iterations, config.solver.qp_method),
            command: neutral.clone(),
            previous: neutral.clone(),
            pull: vec![config.regularisation.previous_command; dof],
            dof_digits: model.dof_digits(),
            approach: PinchApproach::default(),
            filter: KeyPointFilter::new(config.input_filter.clone()),
            neutral,
            free,
            rest,
            model,
            config,
            transform: CalibrationTransform::IDENTITY,
        })
    }

    /// Use a calibration transform from now on.
    pub fn set_calibration(&mut self, transform: CalibrationTransform) -> Result<(), Error> {
        transform.validate()?;
        self.transform = transform;
        self.filter.reset(); // its history was in the old transform's frame
        self.approach.reset();
        Ok(())
    }

    /// The calibration transform in use.
    pub fn calibration(&self) -> &CalibrationTransform {
        &self.transform
    }

    /// The hand model.
    pub fn model(&self) -> &HandModel {
        &self.model
    }

    /// The configuration.
    pub fn config(&self) -> &RetargetConfig {
        &self.config
    }

    /// Degrees of freedom the solver moves (indices into the joint vector).
    pub fn free_dofs(&self) -> &[usize] {
        &self.free
    }

    /// The last command (the neutral pose before the first frame).
    pub fn command(&self) -> &[f64] {
        &self.command
    }

    /// The neutral pose: zero, abduction joints at their rest posture.
    pub fn neutral(&self) -> &[f64] {
        &self.neutral
    }

    /// Start the next frame from `q` (e.g. the hand's measured state). Values are clamped into
    /// the joint limits; locked joints keep their neutral value.
    pub fn set_command(&mut self, q: &[f64]) -> Result<(), Error> {
        if q.len() != self.model.dof() {
            return Err(Error::DofMismatch {
                expected: self.model.dof(),
                got: q.len(),
            });
        }
        for &dof in &self.free {
            let value = if q[dof].is_finite() {
                q[dof]
            } else {
                self.neutral[dof]
            };
            self.command[dof] = self.limits[dof].clamp(value);
        }
        Ok(())
    }

    /// Forget the last command and the input filter's history: the next frame starts from
    /// the neutral pose.
    pub fn reset(&mut self) {
        self.command.copy_from_slice(&self.neutral);
        self.filter.reset();
        self.approach.reset();
    }

    /// Retarget one frame of keypoints (layout from the configuration, metres), `dt_s`
    /// seconds after the previous frame. On `Err` (malformed input) the command is unchanged:
    /// the caller holds it.
    pub fn retarget(&mut self, keypoints: &[Point3<f64>], dt_s: f64) -> Result<Solution, Error> {
        if !(dt_s.is_finite() && dt_s > 0.0) {
            return Err(Error::InvalidTimeStep { dt_s });
        }
        let raw = human_key_vectors(self.config.layout, keypoints, &self.transform)?;
        let filtered = self.filter.apply(&raw, dt_s);
        let base = self.config.regularisation.previous_command;
        let smoothing = &self.config.smoothing;
        let (extra, residual_m) = (smoothing.previous_command, smoothing.residual_m);
        let release_speed = smoothing.release_speed_m_s;
        let filter_on = self.config.input_filter.enabled();
        let targets = key_vector_targets(&raw, &self.config);
        let shares = self.approach.pull_shares(
            raw.pinch_distances_m,
            dt_s,
            smoothing.approach_range_m,
            smoothing.approach_speed_m_s,
        );
        if extra <= 0.0 && !filter_on {
            return Ok(self.solve(&targets, dt_s, base, [1.0; 5]));
        }
        self.previous.copy_from_slice(&self.command);
        let first = self.solve(&targets, dt_s, base, [1.0; 5]);
        // How far the robot is from reproducing the frame: 0 for a reachable one (tracked
        // as it is), toward 1 for one it cannot reproduce (smoothed).
        let x = (first.tip_error_m / residual_m).powi(2);
        let unreproduced = x / (1.0 + x);
        let release = match release_speed {
            0.0 => 1.0,
            v_s => 1.0 / (1.0 + (self.filter.fastest_speed_m_s() / v_s).powi(2)),
        };
        let prior = base + extra * unreproduced * release;
        let blend = if filter_on { unreproduced } else { 0.0 };
        if prior <= base && blend <= 0.0 {
            return Ok(first);
        }
        let smoothed = raw.toward(&filtered, self.filter_shares(&raw, blend));
        let targets = key_vector_targets(&smoothed, &self.config);
        self.command.copy_from_slice(&self.previous);
        let mut second = self.solve(&targets, dt_s, prior, shares);
        second.steps += first.steps;
        second.qp_iterations += first.qp_iterations;
        second.qp_active_set += first.qp_active_set;
        second.qp_clarabel += first.qp_clarabel;
        second.qp_time_s += first.qp_time_s;
        Ok(second)
    }

    /// How much of the filtered key points each digit takes: `blend`, less on a pinching pair
    /// (the thumb and the finger it closes on follow the glove as it is, so a pinch is aimed
    /// where the fingers are now).
    fn filter_shares(&self, raw: &HumanKeyVectors, blend: f64) -> [f64; 5] {
        let p = &self.config.pinch;
        let beta = raw
            .pinch_distances_m
            .map(|d| pinch_activation(d, p.engage_m, p.release_m));
        let thumb = beta.iter().copied().fold(0.0, f64::max);
        std::array::from_fn(|i| blend * (1.0 - if i == 0 { thumb } else { beta[i - 1] }))
    }

    /// Fingertips of the robot at `q`, in the robot palm frame, metres.
    pub fn robot_tips(&mut self, q: &[f64]) -> Result<[Vector3<f64>; 5], Error> {
        let points = self.robot_points(q)?;
        Ok(std::array::from_fn(|i| points[i]))
    }

    /// The energy's robot points at `q` (fingertips, then mid points), robot palm frame.
    fn robot_points(&mut self, q: &[f64]) -> Result<[Vector3<f64>; POINTS], Error> {
        self.model.forward(q, &mut self.fk)?;
        let palm = self.model.palm_frame(&self.fk)?;
        Ok(self
            .point_links
            .map(|l| palm.point_to_palm(&self.fk.position(l))))
    }

    /// Minimise the energy with pull `prior` toward the previous command, from it; digit `d`
    /// keeps `shares[d]` of the pull beyond the configured base (see [`PinchApproach`]).
    fn solve(
        &mut self,
        targets: &[KeyVector; KEY_VECTORS],
        dt_s: f64,
        prior: f64,
        shares: [f64; 5],
    ) -> Solution {
        let base = self.config.regularisation.previous_command.min(prior);
        for (pull, digit) in self.pull.iter_mut().zip(&self.dof_digits) {
            let share = digit.map_or(1.0, |d| shares[d.index()]);
            *pull = base + (prior - base) * share;
        }
        let reach =
            self.config.solver.max_joint_speed_rad_s * dt_s.min(self.config.solver.max_rate_dt_s);
        for (k, &dof) in self.free.iter().enumerate() {
            let previous = self.command[dof];
            self.lower[k] = self.limits[dof].lower_rad.max(previous - reach);
            self.upper[k] = self.limits[dof].upper_rad.min(previous + reach);
        }
        let mut q = self.command.clone();
        let cost_before = self.energy(targets, &q);
        let mut cost = cost_before;
        let mut status = SolveStatus::StepLimit;
        let mut steps = 0;
        let mut qp_iterations = 0;
        let mut qp_active_set = 0;
        let mut qp_clarabel = 0;
        let mut qp_time_s = 0.0;
        for _ in 0..self.config.solver.steps_per_frame {
            self.normal_equations(targets, &q);
            for (k, &dof) in self.free.iter().enumerate() {
                self.lower_step[k] = (self.lower[k] - q[dof]).min(0.0);
                self.upper_step[k] = (self.upper[k] - q[dof]).max(0.0);
            }
            let outcome = self.qp.solve(
                &self.H,
                &self.g,
                &self.lower_step,
                &self.upper_step,
                &mut self.step,
            );
            steps += 1;
            qp_iterations += outcome.iterations;
            match outcome.solver {
                QpSolver::ActiveSet => qp_active_set += 1,
                QpSolver::Clarabel => qp_clarabel += 1,
            }
            qp_time_s += outcome.solve_time_s;
            if !outcome.usable() || !self.step.iter().all(|s| s.is_finite()) {
                status = SolveStatus::QpFailed(status_name(outcome.status));
                break;
            }
            match self.line_search(targets, &q, cost) {
                Some((next_cost, step_size)) => {
                    q.copy_from_slice(&self.trial);
                    cost = next_cost;
                    if step_size < self.config.solver.step_tolerance_rad {
                        status = SolveStatus::Converged;
                        break;
                    }
                }
                None => {
                    status = SolveStatus::Converged;
                    break;
                }
            }
        }
        self.command.copy_from_slice(&q);
        let points = self.robot_points(&q).unwrap_or([Vector3::zeros(); POINTS]);
        let tip_error_m = targets[..5]
            .iter()
            .map(|v| (v.robot(&points) - v.target).norm())
            .sum::<f64>()
            / 5.0;
        Solution {
            status,
            q,
            steps,
            qp_iterations,
            qp_active_set,
            qp_clarabel,
            cost_before,
            cost_after: cost,
            qp_time_s,
            tip_error_m,
            prior_weight: prior,
        }
    }

    /// Try `q + α Δ` for α = 1, ½, ¼, ⅛ (clamped into the box); on the first that lowers the
    /// energy, leave it in `self.trial` and return its energy and max-norm step size.
    fn line_search(
        &mut self,
        targets: &[KeyVector; KEY_VECTORS],
        q: &[f64],
        cost: f64,
    ) -> Option<(f64, f64)> {
        let mut alpha = 1.0;
        for _ in 0..4 {
            self.trial.copy_from_slice(q);
            let mut size: f64 = 0.0;
            for (k, &dof) in self.free.iter().enumerate() {
                let value = (q[dof] + alpha * self.step[k]).clamp(self.lower[k], self.upper[k]);
                size = size.max((value - q[dof]).abs());
                self.trial[dof] = value;
            }
            let trial = std::mem::take(&mut self.trial);
            let trial_cost = self.energy(targets, &trial);
            self.trial = trial;
            if trial_cost < cost {
                return Some((trial_cost, size));
            }
            alpha *= 0.5;
        }
        None
    }

    /// The energy at `q` (key vectors + regularisers).
    fn energy(&mut self, targets: &[KeyVector; KEY_VECTORS], q: &[f64]) -> f64 {
        let Ok(points) = self.robot_points(q) else {
            return f64::INFINITY;
        };
        let reg = &self.config.regularisation;
        let mut energy = key_vector_energy(targets, &points, self.config.huber_delta_m);
        for &dof in &self.free {
            energy += 0.5 * self.pull[dof] * (q[dof] - self.command[dof]).powi(2);
        }
        for &(k, rest) in &self.rest {
            energy += 0.5 * reg.rest_posture * (q[self.free[k]] - rest).powi(2);
        }
        energy
    }

    /// Assemble `H` and `g` at `q`.
    fn normal_equations(&mut self, targets: &[KeyVector; KEY_VECTORS], q: &[f64]) {
        let (rest_posture, damping) = {
            let r = &self.config.regularisation;
            (r.rest_posture, r.damping)
        };
        self.H.fill(0.0);
        self.g.fill(0.0);
        for (k, &dof) in self.free.iter().enumerate() {
            self.H[(k, k)] = self.pull[dof] + damping;
            self.g[k] = self.pull[dof] * (q[dof] - self.command[dof]);
        }
        for &(k, rest) in &self.rest {
            self.H[(k, k)] += rest_posture;
            self.g[k] += rest_posture * (q[self.free[k]] - rest);
        }
        if self.model.forward(q, &mut self.fk).is_err() {
            return;
        }
        let Ok(palm) = self.model.palm_frame(&self.fk) else {
            return;
        };
        let positions = self
            .point_links
            .map(|l| palm.point_to_palm(&self.fk.position(l)));
        let to_palm = palm.rotation.inverse();
        for (i, &link) in self.point_links.iter().enumerate() {
            if self
                .model
                .position_jacobian(&self.fk, link, &mut self.full_jacobian)
                .is_err()
            {
                return;
            }
            for (k, &dof) in self.free.iter().enumerate() {
                let column = to_palm * self.full_jacobian.column(dof).into_owned();
                self.point_jacobians[i].set_column(k, &column);
            }
        }
        accumulate_key_vectors(
            targets,
            &positions,
            &self.point_jacobians,
            self.config.huber_delta_m,
            &mut self.H,
            &mut self.g,
            &mut self.scratch,
        );
    }
}

fn status_name(status: clarabel::solver::SolverStatus) -> &'static str {
    use clarabel::solver::SolverStatus as S;
    match status {
        S::Unsolved => "unsolved",
        S::Solved => "solved",
        S::AlmostSolved => "almost solved",
        S::PrimalInfeasible | S::AlmostPrimalInfeasible => "primal infeasible",
        S::DualInfeasible | S::AlmostDualInfeasible => "dual infeasible",
        S::MaxIterations => "iteration limit",
        S::MaxTime => "time limit",
        S::NumericalError => "numerical error",
        S::InsufficientProgress => "insufficient progress",
        S::CallbackTerminated => "callback terminated",
    }
}
