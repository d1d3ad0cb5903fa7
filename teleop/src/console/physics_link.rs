//! The trial console's link to the simulated robot (`pomdar trial --simulate --physics`): the
//! robot in the task's MuJoCo scene instead of the mock robot. Its physics marks the trial's progress: each event it measures reaches
//! the console as the operator's own mark would (`p VALUE`, `d`), so the log, the summary and
//! `pomdar score` are unchanged and the operator can still correct a mark. Every trial starts
//! from the scene's initial state, and a glove task script plays from the trial's start.

use tokio::sync::{mpsc, watch};

use super::keys::Action;
use crate::stand_ins::progress_message::ProgressMessage;

/// What starting the simulated robot gives the console: its task, the link, and the glove's
/// time origin to play a script from.
pub(crate) type PhysicsParts = (
    tokio::task::JoinHandle<Result<(), crate::stand_ins::SimError>>,
    PhysicsLink,
    watch::Receiver<Option<i64>>,
);

/// The console's side of the simulated robot.
#[cfg_attr(not(feature = "physics"), allow(dead_code))] // only built with the simulator
pub(crate) struct PhysicsLink {
    /// Resets of the scene.
    #[cfg(feature = "physics")]
    control: mpsc::Sender<crate::physics::robot_node::SimControl>,
    /// The progress events the physics measures.
    events: mpsc::UnboundedReceiver<ProgressMessage>,
    /// When the glove's task script starts (station clock, ns).
    glove_origin: watch::Sender<Option<i64>>,
}

#[cfg_attr(not(feature = "physics"), allow(dead_code))]
impl PhysicsLink {
    /// A trial starts at `now_ns`: the scene back to its initial state, the glove's script from
    /// its beginning.
    pub(crate) fn trial_started(&self, now_ns: i64) {
        #[cfg(feature = "physics")]
        {
            use crate::physics::robot_node::SimControl;
            self.control.try_send(SimControl::Reset).ok();
        }
        self.glove_origin.send(Some(now_ns)).ok();
    }
}

/// The next progress event of `link` (never, without one).
pub(crate) async fn next_progress(link: &mut Option<PhysicsLink>) -> Option<ProgressMessage> {
    match link {
        Some(link) => link.events.recv().await,
        None => std::future::pending().await,
    }
}

/// The operator's action a progress event stands for: a mark of its value, or a drop.
pub(crate) fn progress_action(message: &ProgressMessage) -> Action {
    match message.value {
        Some(value) if message.event == "progress" => Action::Progress(Some(value)),
        _ => Action::Drop,
    }
}

/// The simulated robot of `task` on `config`'s network and topics, until `shutdown`; its task
/// and the console's link to it, and the glove's time origin to play a script from.
#[cfg(feature = "physics")]
pub(crate) fn spawn_physics_robot(
    config: &station::StationConfig,
    model: &retarget::HandModel,
    task: &scoring::TaskSpec,
    scene: Option<&std::path::Path>,
    clock: crate::clock::StationClock,
    shutdown: &watch::Receiver<bool>,
) -> Result<PhysicsParts, super::session_error::SessionError> {
    use crate::physics::robot_node::{PhysicsRobotOptions, spawn_physics_robot as spawn};
    use crate::physics::setup::{ProjectScene, SceneSource, load_task};
    let source = match scene {
        Some(path) => SceneSource::LabFile(path),
        None => SceneSource::Project(ProjectScene::for_station(config)),
    };
    let arm_start = config.arm.start_pose_isometry()?;
    let loaded = load_task(task, model, source, arm_start)?;
    let (events_tx, events) = mpsc::unbounded_channel();
    let robot = spawn(
        config,
        model,
        loaded,
        clock,
        shutdown,
        PhysicsRobotOptions::default(),
        Some(events_tx),
    )?;
    let handle = tokio::spawn(async move {
        match robot.task.await {
            Ok(Ok(())) => Ok(()),
            Ok(Err(e)) => Err(crate::stand_ins::SimError::Physics {
                message: e.to_string(),
            }),
            Err(e) => Err(crate::stand_ins::SimError::Physics {
                message: format!("the simulated robot's task ended: {e}"),
            }),
        }
    });
    let (glove_origin, origin_rx) = watch::channel(None);
    let link = PhysicsLink {
        control: robot.control,
        events,
        glove_origin,
    };
    Ok((handle, link, origin_rx))
}
