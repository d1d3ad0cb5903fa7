//! Where a step's [`StationOutputs`] go, in one order for every loop: the notices, the hand's
//! messages (joint targets, then the policy output), then the arm target. [`deliveries`] lists
//! a step's outputs in that order; a synchronous loop names its sink ([`OutputSink`]: a
//! re-simulation's MCAP log, [`McapSink`]; the lock step's simulated robot, in
//! `physics::lockstep`; a sim-bench run's trial log, in `sim_bench::trial_log`) and [`route`]
//! hands it each one; the live node's asynchronous DDS
//! publishers take the same [`deliveries`] one by one (`station_node::ros_node`).

use msgs::PoseStamped;
use station::HandMessages;
use station::{Notice, StationConfig, StationOutputs};

use crate::mcap_log::{LogError, TrialWriter};

/// One output of a step, as every loop delivers it.
#[derive(Debug, Clone, Copy)]
pub enum Delivery<'a> {
    /// A notice for the operator.
    Notice(&'a Notice),
    /// The hand's messages; `fresh` when they were computed from a new frame.
    Hand {
        /// Joint targets and the policy output.
        hand: &'a HandMessages,
        /// Whether a new frame produced them.
        fresh: bool,
    },
    /// The arm's target.
    Arm(&'a PoseStamped),
}

/// A step's outputs in the order every loop sends them: notices, the hand, the arm.
pub fn deliveries(outputs: &StationOutputs) -> impl Iterator<Item = Delivery<'_>> {
    let fresh = outputs.fresh_frame_received_ns.is_some();
    let notices = outputs.notices.iter().map(Delivery::Notice);
    let hand = outputs
        .hand
        .iter()
        .map(move |hand| Delivery::Hand { hand, fresh });
    let arm = outputs.arm.iter().map(Delivery::Arm);
    notices.chain(hand).chain(arm)
}

/// What takes a station's outputs.
pub trait OutputSink {
    /// What can go wrong in the sink.
    type Error;

    /// A notice for the operator.
    fn notice(&mut self, notice: &Notice) -> Result<(), Self::Error>;

    /// The hand's messages at `now_ns`; `fresh` when they were computed from a new frame.
    fn hand(&mut self, now_ns: i64, hand: &HandMessages, fresh: bool) -> Result<(), Self::Error>;

    /// The arm's target at `now_ns`.
    fn arm(&mut self, now_ns: i64, arm: &PoseStamped) -> Result<(), Self::Error>;
}

/// Hand `outputs` of a step at `now_ns` to `sink`, in the order of [`deliveries`].
pub fn route<S: OutputSink>(
    outputs: &StationOutputs,
    now_ns: i64,
    sink: &mut S,
) -> Result<(), S::Error> {
    for delivery in deliveries(outputs) {
        match delivery {
            Delivery::Notice(notice) => sink.notice(notice)?,
            Delivery::Hand { hand, fresh } => sink.hand(now_ns, hand, fresh)?,
            Delivery::Arm(arm) => sink.arm(now_ns, arm)?,
        }
    }
    Ok(())
}

/// A log of the outputs, each stamped with the step's time only (log and publish time), on the
/// configuration's topics; notices go to stderr.
pub struct McapSink<'a> {
    /// The log written to (the caller finishes it).
    pub writer: &'a mut TrialWriter,
    /// The topics.
    pub config: &'a StationConfig,
    /// Hand commands written.
    pub hand_commands: u64,
    /// Arm targets written.
    pub arm_targets: u64,
}

impl<'a> McapSink<'a> {
    /// A sink writing to `writer` on `config`'s topics.
    pub fn new(writer: &'a mut TrialWriter, config: &'a StationConfig) -> Self {
        Self {
            writer,
            config,
            hand_commands: 0,
            arm_targets: 0,
        }
    }
}

impl OutputSink for McapSink<'_> {
    type Error = LogError;

    fn notice(&mut self, notice: &Notice) -> Result<(), LogError> {
        eprintln!("{notice}");
        Ok(())
    }

    fn hand(&mut self, now_ns: i64, hand: &HandMessages, _fresh: bool) -> Result<(), LogError> {
        let topic = &self.config.output.joint_targets_topic;
        self.writer
            .write(topic, now_ns, now_ns, &hand.joint_state)?;
        self.hand_commands += 1;
        if let Some(policy) = &hand.policy {
            let topic = &self.config.policy_output.topic;
            self.writer.write(topic, now_ns, now_ns, policy)?;
        }
        Ok(())
    }

    fn arm(&mut self, now_ns: i64, arm: &PoseStamped) -> Result<(), LogError> {
        let topic = &self.config.output.arm_target_topic;
        self.writer.write(topic, now_ns, now_ns, arm)?;
        self.arm_targets += 1;
        Ok(())
    }
}
