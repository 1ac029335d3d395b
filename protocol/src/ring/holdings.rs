//! What the reading end holds for its peer, charged before it is allocated.

/// Charges the memory a reader holds for its peer (a chunked message being assembled)
/// before the reader allocates it.
pub trait Holdings: Send {
    /// The reader is about to hold `bytes` in all (less than before: it gives some back). An
    /// error, with the reason, refuses the growth: the message is skipped and reported as
    /// [`super::Message::Oversized`].
    fn hold(&mut self, bytes: usize) -> Result<(), String>;
}
