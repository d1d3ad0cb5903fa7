//! The hand check over ROS 2, on the consoles' terminal shell ([`run_turns`]): the check's
//! command sent through the table at a fixed rate on the consumer's topic, the operator's
//! answers from a `--script` or typed on stdin, the check's lines printed on stdout.

use std::convert::Infallible;
use std::time::Duration;

use msgs::Float32MultiArray;
use ros2_client::Publisher;
use station::policy_array;
use tokio::sync::mpsc;
use tokio::time::Instant;

use crate::hand_check::HandCheckError;
use crate::hand_check::hand_check_script::{CheckScriptPlayer, parse_answer};
use crate::hand_check::session::{Answer, HandCheck};
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use crate::tui::terminal::Input;
use crate::tui::terminal_shell::{Next, Turn, TurnLoop, Wakeups, run_turns};

/// Where the answers come from.
#[derive(Debug)]
pub enum Answers {
    /// A script, played against the check's phase; when it ends before the check, the check
    /// stops.
    Script(CheckScriptPlayer),
    /// Lines typed on stdin; its end stops the check.
    Stdin(mpsc::UnboundedReceiver<Input>),
}

/// Where the commands go.
#[derive(Debug, Clone)]
pub struct CheckOutput {
    /// The consumer's topic.
    pub topic: String,
    /// Its QoS (the station's output QoS).
    pub qos: QosConfig,
    /// DDS settings.
    pub network: NetworkConfig,
    /// Commands a second.
    pub rate_hz: f64,
}

/// Run `check` until it is complete or quit (or the script or stdin ends, or a SIGINT or
/// SIGTERM among `wakeups`), on the consoles' turn loop: each tick of `wakeups` (set to the
/// command rate) publishes the check's command; the answers due then are acted on in the turn.
pub async fn run_check(
    check: &mut HandCheck,
    output: &CheckOutput,
    answers: Answers,
    wakeups: Wakeups,
) -> Result<(), HandCheckError> {
    let mut node = RosNode::join(&output.network, "/", "pomdar_hand_check")?;
    let publisher = node.publisher::<Float32MultiArray>(&output.topic, output.qos)?;
    let period = Duration::from_secs_f64(1.0 / output.rate_hz);
    let mut console = CheckLoop {
        check,
        publisher,
        answers,
        wakeups: wakeups.ticking_every(period),
        start: Instant::now(),
        publish_failed: 0,
    };
    run_turns(&mut console).await?;
    if console.publish_failed > 0 {
        println!(
            "note: {} commands could not be published",
            console.publish_failed
        );
    }
    Ok(())
}

/// The check's console for [`run_turns`]: its command sent each tick, the operator's answers
/// (a script's or typed ones) and the signals as its actions, its lines printed each turn.
struct CheckLoop<'a> {
    check: &'a mut HandCheck,
    publisher: Publisher<Float32MultiArray>,
    answers: Answers,
    wakeups: Wakeups,
    /// When the check started: its clock's zero.
    start: Instant,
    publish_failed: u64,
}

impl TurnLoop for CheckLoop<'_> {
    type Action = Answer;
    type Effect = Infallible;
    type Error = HandCheckError;

    async fn wait(&mut self, turn: &mut Turn<Answer, Infallible>) -> Result<(), HandCheckError> {
        tokio::select! {
            () = self.wakeups.signals.interrupted() => turn.actions.push(Answer::Quit),
            _ = self.wakeups.tick.tick() => {
                let now_s = self.now_s();
                self.check.tick(now_s);
                let message = policy_array(self.check.command(now_s));
                if self.publisher.async_publish(message).await.is_err() {
                    self.publish_failed += 1;
                }
                if let Answers::Stdin(lines) = &mut self.answers {
                    typed_answers(lines, &mut turn.actions);
                }
            }
        }
        Ok(())
    }

    fn finish_turn(&mut self, turn: Turn<Answer, Infallible>) -> Result<Next, HandCheckError> {
        let now_s = self.now_s();
        for answer in turn.actions {
            self.check.answer(answer, now_s);
        }
        if let Answers::Script(player) = &mut self.answers {
            play_script(self.check, player, now_s)?;
        }
        for line in self.check.take_lines() {
            println!("{line}");
        }
        Ok(match self.check.phase().is_over() {
            true => Next::Quit,
            false => Next::Continue,
        })
    }
}

impl CheckLoop<'_> {
    /// Seconds since the check started.
    fn now_s(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }
}

/// Give `check` the script's answers due now, each against the phase the one before left;
/// when the script ends before the check, the check quits.
fn play_script(
    check: &mut HandCheck,
    player: &mut CheckScriptPlayer,
    now_s: f64,
) -> Result<(), HandCheckError> {
    while let Some(answer) = player.next(check.phase(), std::time::Instant::now())? {
        check.answer(answer, now_s);
    }
    if player.finished() && !check.phase().is_over() {
        println!("the script has ended");
        check.answer(Answer::Quit, now_s);
    }
    Ok(())
}

/// The lines typed since the last turn, as answers (a closed stdin or Ctrl-C typed quits; a
/// line that is no answer is said and skipped).
fn typed_answers(lines: &mut mpsc::UnboundedReceiver<Input>, due: &mut Vec<Answer>) {
    while let Ok(input) = lines.try_recv() {
        match input {
            Input::Line(line) if line.trim().is_empty() => {}
            Input::Line(line) => match parse_answer(&line) {
                Ok(answer) => due.push(answer),
                Err(e) => println!("{e}"),
            },
            Input::Closed | Input::CtrlC => due.push(Answer::Quit),
            _ => {}
        }
    }
}
