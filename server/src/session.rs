//! One client's decoder loop, on its own thread: read frames from the command ring, decode and
//! validate them, hand them to the executor, and write replies to the reply ring.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;

use strata_protocol::codec::{self, CodecError};
use strata_protocol::ring::{Message, Reader, RingError, Writer};
use strata_protocol::tally::Tally;
use strata_protocol::{Command, Reply, StreamTally};

use strata_gles::execute::{ExecError, Executor};

/// Why a session's decoder stopped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SessionEnd {
    /// The client disconnected between commands.
    ClientLeft,
    /// The client disconnected in the middle of a command.
    LeftMidCommand,
    /// The client broke the protocol; the text is the logged reason.
    Violation(String),
    /// The daemon could not go on serving the client (its GPU device was lost, or none could
    /// be opened); the text is the logged reason.
    Failed(String),
}

impl std::fmt::Display for SessionEnd {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SessionEnd::ClientLeft => f.write_str("client disconnected"),
            SessionEnd::LeftMidCommand => f.write_str("client disconnected in the middle of a command"),
            SessionEnd::Violation(r) => write!(f, "protocol violation: {r}"),
            SessionEnd::Failed(r) => write!(f, "session ended: {r}"),
        }
    }
}

#[derive(Debug, thiserror::Error)]
enum Stop {
    #[error(transparent)]
    Ring(#[from] RingError),
    #[error(transparent)]
    Codec(#[from] CodecError),
    #[error(transparent)]
    Exec(#[from] ExecError),
}

/// Refuses a command of `op` for `why` without running it: a synchronous one is answered,
/// and the stream goes on.
fn refuse(
    executor: &mut dyn Executor,
    replies: &mut Writer,
    alive: &dyn Fn() -> bool,
    op: strata_protocol::Opcode,
    why: &str,
) -> Result<(), Stop> {
    if let Some(reply) = executor.refuse(op, why) {
        let len = codec::encoded_len(&reply)?;
        replies.write::<Stop>(len, alive, |buf| Ok(codec::encode_into(&reply, buf).map(|_| ())?))?;
        replies.publish();
    }
    Ok(())
}

/// Summary of what a session decoded.
#[derive(Debug, Clone, Copy, Default)]
pub struct SessionStats {
    /// Messages decoded.
    pub commands: u64,
    /// Encoded bytes decoded.
    pub bytes: u64,
}

/// A client's decoder state.
pub struct Session {
    reader: Reader,
    replies: Writer,
    tally: Option<Tally>,
    executor: Box<dyn Executor>,
    closed: Arc<AtomicBool>,
    stats: SessionStats,
    /// Where the bytes decoded are also counted for others to read (`ctl list`).
    counter: Option<Arc<AtomicU64>>,
    /// The client's quota: the largest command it may send.
    account: Option<Arc<strata_device::account::Account>>,
}

impl Session {
    /// Assembles a session from its ring ends; `closed` is raised when the client's socket
    /// closes or the daemon shuts down.
    pub fn new(
        reader: Reader,
        replies: Writer,
        tally: bool,
        executor: Box<dyn Executor>,
        closed: Arc<AtomicBool>,
    ) -> Self {
        Session {
            reader,
            replies,
            tally: tally.then(Tally::default),
            executor,
            closed,
            stats: SessionStats::default(),
            counter: None,
            account: None,
        }
    }

    /// Also counts the bytes decoded into `counter`, readable while the session runs.
    pub fn with_byte_counter(mut self, counter: Arc<AtomicU64>) -> Self {
        self.counter = Some(counter);
        self
    }

    /// Refuses commands larger than `account` allows, as `GL_OUT_OF_MEMORY`.
    pub fn with_account(mut self, account: Arc<strata_device::account::Account>) -> Self {
        self.account = Some(account);
        self
    }

    /// Decodes and executes until the client leaves or misbehaves.
    pub fn run(mut self) -> (SessionEnd, SessionStats) {
        let closed = self.closed.clone();
        let alive = move || !closed.load(Ordering::Acquire);
        let Session { reader, replies, tally, executor, stats, counter, account, .. } = &mut self;
        loop {
            let r = reader.recv_messages::<Stop>(&alive, strata_protocol::ring::Oversized::Skip, |message, bulk| {
                let mut count = |len: u64| {
                    stats.commands += 1;
                    stats.bytes += len;
                    if let Some(c) = counter {
                        c.fetch_add(len, Ordering::Relaxed);
                    }
                };
                let bytes = match message {
                    Message::Whole(bytes) => bytes,
                    // The reader kept only its start: the command is refused.
                    Message::Oversized { len, head, why } => {
                        count(len);
                        let why = match (why, account.as_ref()) {
                            (Some(why), _) => why.to_string(),
                            (None, Some(a)) => a.admit_command(len).err().map_or_else(
                                || {
                                    format!(
                                        "{len} bytes exceed the {}-byte limit on one command",
                                        codec::MAX_MESSAGE_LEN
                                    )
                                },
                                |e| e.to_string(),
                            ),
                            (None, None) => {
                                return Err(RingError::TooLarge { len, limit: codec::MAX_MESSAGE_LEN }.into())
                            }
                        };
                        let op = codec::peek_opcode(head).ok_or(CodecError::UnknownCommand {
                            opcode: u64::MAX,
                            known: strata_protocol::Opcode::COUNT,
                        })?;
                        return refuse(executor.as_mut(), replies, &alive, op, &why);
                    }
                };
                let mut cmd = codec::decode_command(bytes)?;
                let op = cmd.opcode();
                // A streamed blob follows the message: it counts toward its size.
                let mut blob = cmd.bulk_mut();
                let streamed = blob.as_ref().and_then(|b| b.streamed_len()).unwrap_or(0);
                bulk.expect(streamed)?;
                let len = (bytes.len() as u64).saturating_add(streamed);
                count(len);
                let admitted = match account.as_ref() {
                    Some(a) => a.admit_command(len).map_err(|e| e.to_string()),
                    None if len > codec::MAX_MESSAGE_LEN as u64 => {
                        return Err(RingError::TooLarge { len, limit: codec::MAX_MESSAGE_LEN }.into())
                    }
                    None => Ok(()),
                };
                if let Err(why) = admitted {
                    // Too large to run: the client's call fails, and the stream goes on.
                    return refuse(executor.as_mut(), replies, &alive, op, &why);
                }
                if let Some(blob) = blob.as_mut() {
                    blob.attach(bulk);
                    if !executor.streams(op) {
                        // Into the daemon's memory, charged first; refused, the call fails.
                        match blob.materialize() {
                            Err(RingError::NotHeld { why, .. }) => {
                                return refuse(executor.as_mut(), replies, &alive, op, &why)
                            }
                            other => other?,
                        }
                    }
                    if cmd.bulk_mut().is_some() {
                        // One stream follows a message: a second streamed blob has no bytes.
                        return Err(RingError::BadChunk("a second streamed blob in one message").into());
                    }
                }
                let reply = match cmd {
                    Command::Verify { commands, crc32 } => Some(Reply::Verify(match tally {
                        Some(t) => StreamTally {
                            commands: t.commands(),
                            crc32: t.crc32(),
                            matches: t.commands() == commands && t.crc32() == crc32,
                        },
                        None => StreamTally { commands: 0, crc32: 0, matches: false },
                    })),
                    cmd => executor.execute(cmd)?,
                };
                if let Some(t) = tally {
                    t.add(bytes);
                }
                if op.is_sync() {
                    let reply =
                        reply.unwrap_or_else(|| Reply::Unsupported(format!("{} is not implemented", op.name())));
                    let len = codec::encoded_len(&reply)?;
                    replies.write::<Stop>(len, &alive, |buf| Ok(codec::encode_into(&reply, buf).map(|_| ())?))?;
                    replies.publish();
                }
                Ok(())
            });
            match r {
                Ok(_) => {}
                Err(Stop::Ring(RingError::PeerGone)) => {
                    let end = if reader.mid_message() { SessionEnd::LeftMidCommand } else { SessionEnd::ClientLeft };
                    return (end, *stats);
                }
                Err(Stop::Exec(e)) => return (SessionEnd::Failed(e.to_string()), *stats),
                Err(e) => return (SessionEnd::Violation(e.to_string()), *stats),
            }
        }
    }
}
