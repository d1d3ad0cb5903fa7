//! [`LoggedMessage`]: one message read from a log, and its typed decoding.

use msgs::RosMessage;

use super::LogError;
use super::ros_names::names_definition;

/// One message of a log, with what its channel says about it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoggedMessage {
    /// Topic (`/ingress/mano`).
    pub topic: String,
    /// The channel's schema name (`std_msgs/msg/Float32MultiArray`); empty without a schema.
    pub type_name: String,
    /// The channel's message encoding (`cdr` for ROS 2).
    pub message_encoding: String,
    /// The message's sequence number as recorded (0 when the writer did not number them).
    pub sequence: u32,
    /// Receive time, ns since the epoch.
    pub log_time_ns: i64,
    /// Send (source) time, ns since the epoch.
    pub publish_time_ns: i64,
    /// The payload: for `cdr`, the 4-byte encapsulation header and the CDR body.
    pub data: Vec<u8>,
}

impl LoggedMessage {
    /// Whether this message's channel has type `M` (`pkg/msg/Type`, or the older `pkg/Type`).
    pub fn is<M: RosMessage>(&self) -> bool {
        names_definition(&self.type_name, &M::DEFINITION)
    }

    /// The glove keypoints of a message on a channel of either keypoint type
    /// (`Float32MultiArray`, `PoseArray`); None for another type or a payload that does not
    /// decode.
    pub fn keypoints(&self) -> Option<station::convert::KeypointMessage> {
        use station::convert::KeypointMessage;
        if self.is::<msgs::Float32MultiArray>() {
            self.decode().ok().map(KeypointMessage::Array)
        } else if self.is::<msgs::PoseArray>() {
            self.decode().ok().map(KeypointMessage::Poses)
        } else {
            None
        }
    }

    /// Decodes the payload as `M`, after checking that the channel's type is `M` and its
    /// encoding `cdr`.
    pub fn decode<M: RosMessage>(&self) -> Result<M, LogError> {
        if !self.is::<M>() {
            return Err(LogError::TypeMismatch {
                topic: self.topic.clone(),
                log_time_ns: self.log_time_ns,
                recorded: self.type_name.clone(),
                requested: M::ros_type_name(),
            });
        }
        if self.message_encoding != "cdr" {
            return Err(LogError::NotCdr {
                topic: self.topic.clone(),
                log_time_ns: self.log_time_ns,
                encoding: self.message_encoding.clone(),
            });
        }
        msgs::from_cdr(&self.data).map_err(|source| LogError::Decode {
            topic: self.topic.clone(),
            log_time_ns: self.log_time_ns,
            source,
        })
    }
}

/// [`LoggedMessage::decode`] as a function.
pub fn decode<M: RosMessage>(message: &LoggedMessage) -> Result<M, LogError> {
    message.decode()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use msgs::{JointState, PoseStamped, StringMsg};

    use super::*;

    fn logged(type_name: &str, encoding: &str, data: Vec<u8>) -> LoggedMessage {
        LoggedMessage {
            topic: "/t".to_string(),
            type_name: type_name.to_string(),
            message_encoding: encoding.to_string(),
            sequence: 1,
            log_time_ns: 5,
            publish_time_ns: 4,
            data,
        }
    }

    #[test]
    fn decodes_its_own_type_only() {
        let msg = StringMsg {
            data: "hello".into(),
        };
        let bytes = msgs::to_cdr(&msg).unwrap();
        let m = logged("std_msgs/msg/String", "cdr", bytes.clone());
        assert_eq!(m.decode::<StringMsg>().unwrap(), msg);
        assert_eq!(decode::<StringMsg>(&m).unwrap(), msg);
        // The older spelling without `msg/` is the same type.
        assert!(logged("std_msgs/String", "cdr", bytes.clone()).is::<StringMsg>());
        let err = m.decode::<JointState>().unwrap_err();
        assert!(matches!(err, LogError::TypeMismatch { .. }), "{err}");
        let err = logged("std_msgs/msg/String", "json", bytes)
            .decode::<StringMsg>()
            .unwrap_err();
        assert!(matches!(err, LogError::NotCdr { .. }), "{err}");
    }

    #[test]
    fn bad_payload_is_an_error_naming_the_topic() {
        let m = logged("geometry_msgs/msg/PoseStamped", "cdr", vec![0, 1, 0, 0, 1]);
        let err = m.decode::<PoseStamped>().unwrap_err();
        assert!(matches!(err, LogError::Decode { .. }), "{err}");
        assert!(err.to_string().contains("/t"), "{err}");
    }
}
