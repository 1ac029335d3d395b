//! The proof that pending draws were submitted before a write they may read.

/// Proof that the pending pass was submitted before the command that holds it: whatever writes
/// a buffer or texture that a recorded draw may read takes one, so that the write cannot land
/// before that draw. Only the dispatch of a command the table marks `[Flush]` makes one.
pub struct Flushed(());

impl Flushed {
    /// Made by the dispatch alone, for a command the table marks `[Flush]`, right after it
    /// submits the pending pass.
    pub(crate) fn after_flush() -> Flushed {
        Flushed(())
    }
}
