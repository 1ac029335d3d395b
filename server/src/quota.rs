//! The quota options and configuration entries (`--quota-*`, `[[quota]]`): they set each
//! client's `strata_device::account::Limits`, which its account holds it to.

use serde::Deserialize;

use strata_device::account::{default_total, Kind, Limits};

/// A byte count given as a number or with a binary suffix: `1048576`, `512K`, `256M`, `2G`
/// (also `KiB`, `MiB`, `GiB`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ByteSize(pub u64);

impl std::str::FromStr for ByteSize {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s.trim();
        let split = t.find(|c: char| !c.is_ascii_digit()).unwrap_or(t.len());
        let (digits, unit) = t.split_at(split);
        let shift = match unit.trim().to_ascii_lowercase().as_str() {
            "" | "b" => 0,
            "k" | "kib" => 10,
            "m" | "mib" => 20,
            "g" | "gib" => 30,
            "t" | "tib" => 40,
            _ => return Err(format!("{s:?} is not a size: give bytes, or a number with K, M, G or T")),
        };
        let n: u64 = digits.parse().map_err(|_| format!("{s:?} is not a size: it must start with a whole number"))?;
        n.checked_mul(1 << shift).map(ByteSize).ok_or_else(|| format!("{s:?} is too large"))
    }
}

/// Written as a plain number of bytes, which reads back as the same size.
impl serde::Serialize for ByteSize {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_u64(self.0)
    }
}

impl<'de> Deserialize<'de> for ByteSize {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Int(u64),
            Text(String),
        }
        match Raw::deserialize(d)? {
            Raw::Int(n) => Ok(ByteSize(n)),
            Raw::Text(t) => t.parse().map_err(serde::de::Error::custom),
        }
    }
}

/// A client's quota in the configuration file (`[[quota]]`): every field given replaces the
/// daemon's `--quota-*` value for that client.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct QuotaEntry {
    /// The client name it applies to; empty or absent: every client whose credentials the
    /// entry's `uid`/`user`/`gid`/`group` admit, whatever it calls itself.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub client: String,
    /// GPU memory.
    #[serde(alias = "gpu-bytes")]
    pub gpu_bytes: Option<ByteSize>,
    /// Buffer objects.
    pub buffers: Option<u64>,
    /// Texture objects.
    pub textures: Option<u64>,
    /// Renderbuffer objects.
    pub renderbuffers: Option<u64>,
    /// Framebuffer objects.
    pub framebuffers: Option<u64>,
    /// Shader objects.
    pub shaders: Option<u64>,
    /// Program objects.
    pub programs: Option<u64>,
    /// Vertex array objects.
    #[serde(alias = "vertex-arrays")]
    pub vertex_arrays: Option<u64>,
    /// EGL contexts.
    pub contexts: Option<u64>,
    /// EGL surfaces.
    pub surfaces: Option<u64>,
    /// The largest single command.
    #[serde(alias = "command-bytes")]
    pub command_bytes: Option<ByteSize>,
    /// The daemon's own memory held for it.
    #[serde(default, alias = "daemon-bytes", skip_serializing_if = "Option::is_none")]
    pub daemon_bytes: Option<ByteSize>,
    /// Most sessions the clients this entry matches hold together (see [`crate::caps`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sessions: Option<u64>,
    /// Whether its clients draw on the reserves (`--reserve-devices`, `--reserve-gpu-bytes`)
    /// whatever their class.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reserve: Option<bool>,
    // The same four fields stand on [[layout]] entries: serde cannot flatten a shared struct into
    // one that denies unknown fields.
    /// The user ID a client must connect as to get this entry (see [`crate::identity`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uid: Option<u32>,
    /// The user a client must connect as (resolved into `uid` when the configuration is read).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub user: Option<String>,
    /// The primary group ID a client must connect with.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gid: Option<u32>,
    /// The primary group a client must connect with (resolved into `gid`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
}

impl QuotaEntry {
    /// The credentials a client needs to get this entry.
    pub fn requirement(&self) -> crate::credentials::Requirement {
        crate::credentials::Requirement { uid: self.uid, gid: self.gid }
    }

    /// `base` with this entry's values in place.
    pub fn apply(&self, mut base: Limits) -> Limits {
        if let Some(b) = self.gpu_bytes {
            base.gpu_bytes = b.0;
        }
        if let Some(b) = self.command_bytes {
            base.command_bytes = b.0;
        }
        if let Some(b) = self.daemon_bytes {
            base.daemon_bytes = b.0;
        }
        let counts = [
            self.buffers,
            self.textures,
            self.renderbuffers,
            self.framebuffers,
            self.shaders,
            self.programs,
            self.vertex_arrays,
            self.contexts,
            self.surfaces,
        ];
        for (kind, v) in Kind::ALL.into_iter().zip(counts) {
            if let Some(v) = v {
                base.set_count(kind, v);
            }
        }
        base
    }
}

/// The `--quota-*` options of `stratad serve`: each client's limits, and the total.
#[derive(Debug, Clone, clap::Args)]
pub struct QuotaArgs {
    /// GPU memory one client may hold (buffers, textures, renderbuffers, surfaces).
    #[arg(long, default_value = "2G", value_parser = parse_size)]
    pub quota_gpu_bytes: ByteSize,
    /// GPU memory all clients together may hold [default: half the machine's memory].
    #[arg(long, value_parser = parse_size)]
    pub quota_total_gpu_bytes: Option<ByteSize>,
    /// Buffer objects per client.
    #[arg(long, default_value_t = 65_536)]
    pub quota_buffers: u64,
    /// Texture objects per client.
    #[arg(long, default_value_t = 65_536)]
    pub quota_textures: u64,
    /// Renderbuffer objects per client.
    #[arg(long, default_value_t = 65_536)]
    pub quota_renderbuffers: u64,
    /// Framebuffer objects per client.
    #[arg(long, default_value_t = 65_536)]
    pub quota_framebuffers: u64,
    /// Shader objects per client.
    #[arg(long, default_value_t = 65_536)]
    pub quota_shaders: u64,
    /// Program objects per client.
    #[arg(long, default_value_t = 65_536)]
    pub quota_programs: u64,
    /// Vertex array objects per client.
    #[arg(long, default_value_t = 65_536)]
    pub quota_vertex_arrays: u64,
    /// EGL contexts per client.
    #[arg(long, default_value_t = 64)]
    pub quota_contexts: u64,
    /// EGL surfaces (window and pbuffer) per client.
    #[arg(long, default_value_t = 64)]
    pub quota_surfaces: u64,
    /// The largest single command or upload a client may send.
    #[arg(long, default_value = "256M", value_parser = parse_size)]
    pub quota_command_bytes: ByteSize,
    /// The daemon's own memory one client's session may hold: its segment (twice the command
    /// ring and the reply ring) and a command being assembled from chunks.
    #[arg(long, default_value = "512M", value_parser = parse_size)]
    pub quota_daemon_bytes: ByteSize,
    /// The daemon's own memory all clients' sessions together may hold [default: a quarter of
    /// the machine's memory].
    #[arg(long, value_parser = parse_size)]
    pub quota_total_daemon_bytes: Option<ByteSize>,
    /// Longest a command sent in chunks may take, from its first chunk to its last, in
    /// seconds; a client that leaves one unfinished longer is disconnected, and its memory
    /// freed.
    #[arg(long, default_value_t = 30.0)]
    pub quota_command_seconds: f64,
}

fn parse_size(s: &str) -> Result<ByteSize, String> {
    s.parse()
}

impl QuotaArgs {
    /// The per-client limits the options give.
    pub fn limits(&self) -> Limits {
        let counts = [
            self.quota_buffers,
            self.quota_textures,
            self.quota_renderbuffers,
            self.quota_framebuffers,
            self.quota_shaders,
            self.quota_programs,
            self.quota_vertex_arrays,
            self.quota_contexts,
            self.quota_surfaces,
        ];
        Limits {
            gpu_bytes: self.quota_gpu_bytes.0,
            counts,
            command_bytes: self.quota_command_bytes.0,
            daemon_bytes: self.quota_daemon_bytes.0,
        }
    }

    /// The time a chunked command may take (`--quota-command-seconds`).
    pub fn command_time(&self) -> Result<std::time::Duration, String> {
        std::time::Duration::try_from_secs_f64(self.quota_command_seconds).ok().filter(|d| !d.is_zero()).ok_or_else(
            || format!("--quota-command-seconds {} must be a number of seconds above 0", self.quota_command_seconds),
        )
    }

    /// The total of the daemon's own memory for all clients.
    pub fn total_daemon(&self) -> u64 {
        self.quota_total_daemon_bytes.map_or_else(|| default_total() / 2, |b| b.0)
    }

    /// The total for all clients.
    pub fn total(&self) -> u64 {
        self.quota_total_gpu_bytes.map_or_else(default_total, |b| b.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_suffixes_and_bad_ones_say_why() {
        assert_eq!("1048576".parse(), Ok(ByteSize(1 << 20)));
        assert_eq!("512K".parse(), Ok(ByteSize(512 << 10)));
        assert_eq!("256 MiB".parse(), Ok(ByteSize(256 << 20)));
        assert_eq!("2g".parse(), Ok(ByteSize(2 << 30)));
        for bad in ["", "M", "1.5G", "12X", "-1", "99999999999T"] {
            assert!(bad.parse::<ByteSize>().is_err(), "{bad} parsed");
        }
    }

    #[test]
    fn a_clients_entry_overrides_the_daemons_limits_field_by_field() {
        let entries: Vec<QuotaEntry> = vec![
            QuotaEntry { client: "ic".into(), gpu_bytes: Some(ByteSize(4 << 30)), ..Default::default() },
            QuotaEntry { client: "hu".into(), textures: Some(10), ..Default::default() },
        ];
        let base = Limits::default();
        let peer = strata_protocol::control::Peer::default();
        let limits_for =
            |base, entries: &[QuotaEntry], name| crate::identity::identify(&[], entries, name, &peer).limits(base);
        let ic = limits_for(base, &entries, "ic");
        assert_eq!((ic.gpu_bytes, ic.count(Kind::Texture)), (4 << 30, base.count(Kind::Texture)));
        let hu = limits_for(base, &entries, "hu");
        assert_eq!((hu.gpu_bytes, hu.count(Kind::Texture)), (base.gpu_bytes, 10));
        assert_eq!(limits_for(base, &entries, "other"), base);
    }
}
