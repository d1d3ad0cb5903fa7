//! What the station offers the lab's ROS tools, as the node publishes it: `/tf` with every
//! hand command, `/tf_static`, the hand's drawing and `/robot_description` once (latched),
//! keypoint markers with every fresh frame, `/diagnostics` at the status rate, the hand's
//! measured state (read, recorded, compared with the command in force), and the
//! `std_srvs/Trigger` services. The messages themselves come from `station::ros_tools` (pure).

use futures::StreamExt;
use futures::stream::BoxStream;
use msgs::{DiagnosticArray, JointState, MarkerArray, StringMsg, TFMessage};
use nalgebra::Point3;
use retarget::{CalibrationTransform, FkState, HandModel, KeypointLayout};
use ros2_client::request_id::RmwRequestId;
use ros2_client::{Publisher, Server, ServiceMapping as RosServiceMapping, Subscription};
use serde::Serialize;
use station::StationConfig;
use station::ros_tools::markers::{glove_points_on_robot, hand_model_markers, keypoint_markers};
use station::ros_tools::{HandTf, ServiceAction, ServiceMapping, dof_of_published_name};

use crate::ros::{QosConfig, RosError, RosNode, TriggerRequest, TriggerResponse};

/// A service request: which service (index into the offered ones) and the request.
pub(crate) type ServiceRequest = (
    usize,
    ros2_client::ReadResult<(RmwRequestId, TriggerRequest)>,
);

/// The tools' publishers, the hand-state subscription and the service servers.
pub(crate) struct ToolEndpoints {
    pub tf: Option<Publisher<TFMessage>>,
    pub tf_static: Option<Publisher<TFMessage>>,
    pub keypoint_markers: Option<Publisher<MarkerArray>>,
    pub hand_model_markers: Option<Publisher<MarkerArray>>,
    pub diagnostics: Option<Publisher<DiagnosticArray>>,
    pub description: Option<Publisher<StringMsg>>,
    pub hand_state: Option<Subscription<JointState>>,
    servers: Vec<(
        ServiceAction,
        String,
        Server<TriggerRequest, TriggerResponse>,
    )>,
}

impl ToolEndpoints {
    /// Open what the configuration names (empty names and `tf = false` open nothing); a robot
    /// description publisher only when the station was given a URDF. A human study's station
    /// draws no robot and reads no hand.
    pub fn open(
        node: &mut RosNode,
        config: &StationConfig,
        has_description: bool,
    ) -> Result<ToolEndpoints, RosError> {
        let tools = &config.ros_tools;
        let robot = config.drives_robot();
        let on = |topic: &str| robot && !topic.is_empty();
        let markers = QosConfig::reliable(10);
        let mapping = match tools.services.mapping {
            ServiceMapping::Enhanced => RosServiceMapping::Enhanced,
            ServiceMapping::Cyclone => RosServiceMapping::Cyclone,
        };
        let mut servers = Vec::new();
        for (action, name) in tools.services.offered() {
            servers.push((
                action,
                name.to_string(),
                node.trigger_server(name, mapping)?,
            ));
        }
        Ok(ToolEndpoints {
            tf: (robot && tools.tf)
                .then(|| node.publisher("/tf", QosConfig::reliable(100)))
                .transpose()?,
            tf_static: (robot && tools.tf)
                .then(|| node.latched_publisher("/tf_static", 1))
                .transpose()?,
            keypoint_markers: on(&tools.keypoint_markers_topic)
                .then(|| node.publisher(&tools.keypoint_markers_topic, markers))
                .transpose()?,
            hand_model_markers: on(&tools.hand_model_markers_topic)
                .then(|| node.latched_publisher(&tools.hand_model_markers_topic, 1))
                .transpose()?,
            diagnostics: (!tools.diagnostics_topic.is_empty())
                .then(|| node.publisher(&tools.diagnostics_topic, QosConfig::reliable(10)))
                .transpose()?,
            description: (has_description && on(&tools.robot_description_topic))
                .then(|| node.latched_publisher(&tools.robot_description_topic, 1))
                .transpose()?,
            hand_state: on(&config.input.hand_state_topic)
                .then(|| {
                    node.subscription(&config.input.hand_state_topic, QosConfig::best_effort(10))
                })
                .transpose()?,
            servers,
        })
    }

    /// Every service's requests, tagged with the service's index.
    pub fn service_requests(&self) -> BoxStream<'_, ServiceRequest> {
        let streams = self
            .servers
            .iter()
            .enumerate()
            .map(|(index, (_, _, server))| {
                server
                    .receive_request_stream()
                    .map(move |request| (index, request))
                    .boxed()
            });
        futures::stream::select_all(streams).boxed()
    }

    /// The action and name of service `index`.
    pub fn service(&self, index: usize) -> Option<(ServiceAction, &str)> {
        self.servers
            .get(index)
            .map(|(action, name, _)| (*action, name.as_str()))
    }

    /// Answer request `id` of service `index`; whether the answer went out.
    pub async fn reply(
        &self,
        index: usize,
        id: RmwRequestId,
        response: msgs::TriggerResponse,
    ) -> bool {
        match self.servers.get(index) {
            Some((_, _, server)) => server
                .async_send_response(id, TriggerResponse(response))
                .await
                .is_ok(),
            None => false,
        }
    }
}

/// What the tools' messages are computed from: the model and its `/tf` tree.
#[derive(Debug, Clone)]
pub(crate) struct ToolScene {
    model: HandModel,
    tree: HandTf,
    layout: KeypointLayout,
    fk: FkState,
    joint_name_prefix: Option<String>,
    tracking: HandTracking,
}

/// The hand's measured state against the command in force.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct HandTracking {
    /// Measured states received.
    pub states: u64,
    /// Measured states that named no joint of the model or carried non-finite values.
    pub states_rejected: u64,
    /// When the last measured state was received, nanoseconds on the station's clock.
    #[serde(skip)]
    pub last_received_ns: Option<i64>,
    /// Largest |command − measured| over the joints in the last state, degrees.
    pub max_error_deg: Option<f64>,
    /// The joint with that error (its published name).
    pub worst_joint: Option<String>,
}

impl ToolScene {
    pub fn new(model: &HandModel, config: &StationConfig) -> ToolScene {
        ToolScene {
            tree: HandTf::new(model, &config.ros_tools),
            fk: model.fk_state(),
            model: model.clone(),
            layout: config.retarget.layout,
            joint_name_prefix: config.output.joint_name_prefix.clone(),
            tracking: HandTracking::default(),
        }
    }

    /// `/tf` of the moving links at joint vector `q`; `None` if `q` does not fit the model.
    pub fn tf(&mut self, q: &[f64], stamp_ns: i64) -> Option<TFMessage> {
        self.model.forward(q, &mut self.fk).ok()?;
        Some(self.tree.moving(&self.fk, stamp_ns))
    }

    /// The arm target as a `/tf` frame.
    pub fn arm_target_tf(&self, target: &msgs::PoseStamped) -> Option<TFMessage> {
        self.tree.arm_target(target)
    }

    /// `/tf_static` and the hand's drawing.
    pub fn latched(&mut self, stamp_ns: i64) -> (TFMessage, MarkerArray) {
        let zero = self.model.zero_pose();
        let fixed = match self.model.forward(&zero, &mut self.fk) {
            Ok(()) => self.tree.fixed(&self.fk, stamp_ns),
            Err(_) => TFMessage::default(),
        };
        (fixed, hand_model_markers(&self.tree, &self.model, stamp_ns))
    }

    /// The keypoint markers for a frame's `points` under `calibration` at command `q`;
    /// `None` when the frame or the pose cannot be placed.
    pub fn keypoint_markers(
        &mut self,
        points: &[Point3<f64>],
        calibration: &CalibrationTransform,
        q: &[f64],
        stamp_ns: i64,
    ) -> Option<MarkerArray> {
        self.model.forward(q, &mut self.fk).ok()?;
        let glove =
            glove_points_on_robot(&self.model, &self.fk, self.layout, calibration, points).ok()?;
        Some(keypoint_markers(
            &self.tree,
            &self.model,
            &self.fk,
            self.layout,
            &glove,
            stamp_ns,
        ))
    }

    /// Compare a measured state with the command in force `command`.
    pub fn hand_state(&mut self, state: &JointState, command: Option<&[f64]>, now_ns: i64) {
        let t = &mut self.tracking;
        t.states += 1;
        t.last_received_ns = Some(now_ns);
        let prefix = self.joint_name_prefix.as_deref();
        let mut worst: Option<(f64, &str)> = None;
        for (name, measured) in state.name.iter().zip(&state.position) {
            let Some(dof) = dof_of_published_name(&self.model, name, prefix) else {
                t.states_rejected += 1;
                return;
            };
            if !measured.is_finite() {
                t.states_rejected += 1;
                return;
            }
            if let Some(q) = command {
                let error = (q[dof] - measured).abs().to_degrees();
                if worst.is_none_or(|(e, _)| error > e) {
                    worst = Some((error, name));
                }
            }
        }
        t.max_error_deg = worst.map(|(e, _)| e);
        t.worst_joint = worst.map(|(_, n)| n.to_string());
    }

    /// The hand-tracking part of the status, with the age of the last measured state.
    pub fn tracking_status(&self, now_ns: i64) -> serde_json::Value {
        let mut value = serde_json::to_value(&self.tracking).unwrap_or_default();
        if let Some(fields) = value.as_object_mut() {
            let age = self
                .tracking
                .last_received_ns
                .map(|t| (now_ns - t) as f64 * 1e-6);
            fields.insert("age_ms".into(), serde_json::json!(age));
        }
        value
    }
}
