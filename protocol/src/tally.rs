//! The running count and CRC-32 of a message stream, kept identically by both ends so that
//! `strataVerify` can prove nothing was lost, duplicated, reordered or altered.

/// Count and CRC-32 of the messages seen so far.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    commands: u64,
    crc: crc32fast::Hasher,
}

impl Tally {
    /// Adds one encoded message.
    pub fn add(&mut self, encoded: &[u8]) {
        self.commands += 1;
        self.crc.update(encoded);
    }

    /// Messages counted.
    pub fn commands(&self) -> u64 {
        self.commands
    }

    /// CRC-32 over every counted message, in order.
    pub fn crc32(&self) -> u32 {
        self.crc.clone().finalize()
    }
}
