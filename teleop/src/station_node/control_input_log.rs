//! What a station log holds besides the ROS messages it received and sent: the control inputs
//! (timer ticks, the operator's engage and disengage, the arm topic's second publisher), one
//! JSON document per input on [`STATION_CONTROL_TOPIC`], so that every input the station was
//! stepped with is in the log with its receive time and the run re-simulates to itself.

use msgs::StringMsg;
use station::ControlInput;

/// The channel of the station's control inputs (`std_msgs/String`, JSON such as
/// `{"input":"tick"}`).
pub const STATION_CONTROL_TOPIC: &str = "/pomdar/station_control";

/// The message recording `input`.
pub fn control_message(input: ControlInput) -> StringMsg {
    StringMsg {
        data: serde_json::to_string(&input).unwrap_or_default(),
    }
}

/// The control input a recorded message holds; the error quotes it.
pub fn control_input(message: &StringMsg) -> Result<ControlInput, serde_json::Error> {
    serde_json::from_str(&message.data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_inputs_round_trip_through_their_messages() {
        for input in [
            ControlInput::Tick,
            ControlInput::Engage,
            ControlInput::Disengage,
            ControlInput::ArmBlocked { blocked: true },
        ] {
            assert_eq!(control_input(&control_message(input)).unwrap(), input);
        }
        assert_eq!(
            control_message(ControlInput::Tick).data,
            r#"{"input":"tick"}"#
        );
        assert!(control_input(&StringMsg { data: "{}".into() }).is_err());
    }
}
