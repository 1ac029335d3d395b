//! The control protocol's wire form: JSON lines on the daemon's socket (docs/control.md). A
//! control client's first byte is `{`, which no command-stream client's preamble (`STRT`)
//! starts with, so both share the socket.
//!
//! The client opens with `{"hello":{"version":V,"name":"…"}}`; the daemon answers
//! `{"ready":{"version":V}}`, or `{"refused":{"reason":"…"}}` and closes when the versions
//! differ. Then each line the client sends is one [`ControlRequest`] and each line the daemon
//! sends back is one [`ControlReply`]; after `"watch"`, the daemon sends
//! [`ControlReply::Event`] lines until either side closes.

use serde::{de::DeserializeOwned, Deserialize, Serialize};

pub use crate::control::{ControlReply, ControlRequest};

/// The control protocol's version: it changes whenever a control message changes shape.
pub const CONTROL_VERSION: u32 = 1;

/// Longest line either side accepts from the other, bytes (a screenshot reply is one line).
pub const MAX_LINE: usize = 512 << 20;

/// Longest request line the daemon accepts, bytes.
pub const MAX_REQUEST_LINE: usize = 1 << 20;

/// The client's first line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Opening {
    /// Who it is and which version it speaks.
    Hello {
        /// [`CONTROL_VERSION`] of its build.
        version: u32,
        /// Its name, for the daemon's log.
        name: String,
    },
}

/// The daemon's answer to the opening.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Greeting {
    /// Requests may follow.
    Ready {
        /// The daemon's [`CONTROL_VERSION`].
        version: u32,
    },
    /// The daemon will not serve this client.
    Refused {
        /// Why.
        reason: String,
    },
}

/// A control line that cannot be read or written.
#[derive(Debug, thiserror::Error)]
pub enum LineError {
    /// Not JSON of the expected shape.
    #[error("malformed {what}: {source}")]
    Json {
        /// What was being read.
        what: &'static str,
        /// serde_json's report.
        source: serde_json::Error,
    },
    /// Longer than the limit.
    #[error("{what} longer than {limit} bytes")]
    TooLong {
        /// What was being read.
        what: &'static str,
        /// The limit.
        limit: usize,
    },
}

/// `v` as one line of JSON, newline included.
pub fn line<T: Serialize>(v: &T) -> Result<Vec<u8>, LineError> {
    let mut out = serde_json::to_vec(v).map_err(|source| LineError::Json { what: "message", source })?;
    out.push(b'\n');
    Ok(out)
}

/// One line (its newline included or not) read as `T`.
pub fn parse<T: DeserializeOwned>(bytes: &[u8], what: &'static str) -> Result<T, LineError> {
    serde_json::from_slice(bytes).map_err(|source| LineError::Json { what, source })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::properties::Change;

    #[test]
    fn messages_read_as_docs_control_md_writes_them() {
        let o: Opening = parse(br#"{"hello":{"version":1,"name":"hmi"}}"#, "opening").expect("hello");
        assert_eq!(o, Opening::Hello { version: 1, name: "hmi".into() });
        let r: ControlRequest = parse(br#""list""#, "request").expect("list");
        assert_eq!(r, ControlRequest::List);
        let r: ControlRequest =
            parse(br#"{"apply":{"changes":[{"visibility":{"surface":7,"visible":false}}]}}"#, "request")
                .expect("apply");
        assert_eq!(r, ControlRequest::Apply { changes: vec![Change::Visibility { surface: 7, visible: false }] });
        let r: ControlRequest = parse(br#"{"move":{"surface":7,"x":1,"y":2,"z":0.5}}"#, "request").expect("move");
        assert_eq!(r, ControlRequest::Move { surface: 7, x: 1, y: 2, z: 0.5 });
        assert!(parse::<ControlRequest>(br#"{"mvoe":{}}"#, "request").is_err());
        let image = ControlReply::Image { width: 1, height: 1, rgba: crate::Bytes(vec![1, 2, 3, 255]) };
        let text = String::from_utf8(line(&image).expect("line")).expect("utf-8");
        assert_eq!(text, "{\"image\":{\"width\":1,\"height\":1,\"rgba\":\"AQID/w==\"}}\n");
        assert_eq!(parse::<ControlReply>(text.as_bytes(), "reply").expect("image"), image);
    }
}
