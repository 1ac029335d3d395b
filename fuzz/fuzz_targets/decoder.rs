//! Every decoder that reads bytes a client sent: the command decoder (ring messages), the
//! socket's preamble, frame length, hello and `Mapped`, the control protocol's JSON lines (the
//! opening and requests, with the checks every request's values get), and (for the client side)
//! the reply decoder. A command that decodes must encode back to bytes that decode to the same
//! command.
#![no_main]

use libfuzzer_sys::fuzz_target;
use strata_protocol::codec::{decode_command, decode_owned, decode_reply, encode_to_vec, encoded_len};
use strata_protocol::control::ControlRequest;
use strata_protocol::handshake::{check_preamble, frame_len, ClientMessage, Hello};
use strata_protocol::json_control::{parse, Opening};

fuzz_target!(|data: &[u8]| {
    if let Ok(cmd) = decode_command(data) {
        let bytes = encode_to_vec(&cmd).expect("a decoded command encodes");
        assert_eq!(encoded_len(&cmd).expect("length"), bytes.len());
        let back = decode_command(&bytes).expect("a re-encoded command decodes");
        // Bytes, not values: NaN fields compare unequal to themselves.
        assert_eq!(encode_to_vec(&back).expect("encodes again"), bytes, "{cmd:?} did not round-trip");
        assert_eq!(back.opcode(), cmd.opcode());
    }
    if let Some(p) = data.first_chunk::<8>() {
        let _ = check_preamble(*p);
    }
    if let Some(p) = data.first_chunk::<4>() {
        let _ = frame_len(*p);
    }
    let _ = decode_owned::<Hello>(data, "hello");
    let _ = decode_owned::<ClientMessage>(data, "mapped");
    let _ = parse::<Opening>(data, "opening");
    match parse::<ControlRequest>(data, "control request") {
        Ok(ControlRequest::Apply { changes }) => {
            for c in &changes {
                let _ = c.validate();
            }
        }
        Ok(ControlRequest::Light(change)) => {
            let _ = change.validate();
        }
        _ => {}
    }
    let _ = decode_reply(data);
});
