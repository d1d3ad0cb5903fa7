//! The hand check over ROS 2: the check's command sent through the table at a fixed rate on the
//! consumer's topic, the operator's answers from a `--script` or typed on stdin, the check's
//! lines printed on stdout.

use std::time::{Duration, Instant};

use msgs::Float32MultiArray;
use station::policy_array;
use tokio::sync::{mpsc, watch};

use crate::hand_check::HandCheckError;
use crate::hand_check::hand_check_script::{CheckScriptPlayer, parse_answer};
use crate::hand_check::session::{Answer, HandCheck};
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use crate::tui::terminal::Input;

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

/// Run `check` until it is complete or quit (or the script or stdin ends, or `shutdown`).
pub async fn run_check(
    check: &mut HandCheck,
    output: &CheckOutput,
    mut answers: Answers,
    mut shutdown: watch::Receiver<bool>,
) -> Result<(), HandCheckError> {
    let mut node = RosNode::join(&output.network, "/", "pomdar_hand_check")?;
    let publisher = node.publisher::<Float32MultiArray>(&output.topic, output.qos)?;
    let start = Instant::now();
    let mut interval = tokio::time::interval(Duration::from_secs_f64(1.0 / output.rate_hz));
    let mut publish_failed = 0u64;
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() {
                check.answer(Answer::Quit, start.elapsed().as_secs_f64());
            },
            _ = interval.tick() => {
                let now_s = start.elapsed().as_secs_f64();
                check.tick(now_s);
                next_answers(check, &mut answers, now_s)?;
                let message = policy_array(check.command(now_s));
                if publisher.async_publish(message).await.is_err() {
                    publish_failed += 1;
                }
            }
        }
        for line in check.take_lines() {
            println!("{line}");
        }
        if check.phase().is_over() {
            break;
        }
    }
    if publish_failed > 0 {
        println!("note: {publish_failed} commands could not be published");
    }
    Ok(())
}

/// Give `check` the answers due at `now_s`.
fn next_answers(
    check: &mut HandCheck,
    answers: &mut Answers,
    now_s: f64,
) -> Result<(), HandCheckError> {
    match answers {
        Answers::Script(player) => {
            while let Some(answer) = player.next(check.phase(), Instant::now())? {
                check.answer(answer, now_s);
            }
            if player.finished() && !check.phase().is_over() {
                println!("the script has ended");
                check.answer(Answer::Quit, now_s);
            }
        }
        Answers::Stdin(lines) => {
            while let Ok(input) = lines.try_recv() {
                match input {
                    Input::Line(line) if line.trim().is_empty() => {}
                    Input::Line(line) => match parse_answer(&line) {
                        Ok(answer) => check.answer(answer, now_s),
                        Err(e) => println!("{e}"),
                    },
                    Input::Closed | Input::CtrlC => check.answer(Answer::Quit, now_s),
                    _ => {}
                }
            }
        }
    }
    Ok(())
}
