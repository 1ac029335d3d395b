//! `stratad ctl stats`: the daemon's resident memory, each client's resources against its
//! quota, the totals, and the objects alive on the device. It is how an operator sees a leak
//! or a greedy client, and how tests check for both.

use std::collections::{BTreeMap, HashMap};

use strata_protocol::control::{ClientStats, DaemonStats, DeviceStats, DeviceThread};

use crate::listener::ClientInfo;
use strata_device::account::{Kind, Pool};
use strata_device::Gpu;
use strata_scene::Scene;

/// The process's resident, peak resident and anonymous resident memory, bytes (from
/// `/proc/self/status`).
pub fn rss() -> (u64, u64, u64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find_map(|l| l.strip_prefix(name))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map_or(0, |kib| kib * 1024)
    };
    (field("VmRSS:"), field("VmHWM:"), field("RssAnon:"))
}

/// Live objects on the device by type, as wgpu's registries count them (empty when the
/// backend keeps no registry).
fn device_objects(gpu: &Gpu) -> BTreeMap<String, u64> {
    let Some(report) = gpu.instance.generate_report() else { return BTreeMap::new() };
    let h = report.hub_report();
    [
        ("buffers", &h.buffers),
        ("textures", &h.textures),
        ("texture_views", &h.texture_views),
        ("samplers", &h.samplers),
        ("bind_groups", &h.bind_groups),
        ("bind_group_layouts", &h.bind_group_layouts),
        ("pipeline_layouts", &h.pipeline_layouts),
        ("render_pipelines", &h.render_pipelines),
        ("shader_modules", &h.shader_modules),
        ("command_encoders", &h.command_encoders),
        ("command_buffers", &h.command_buffers),
        ("query_sets", &h.query_sets),
    ]
    .into_iter()
    .map(|(name, r)| (name.to_string(), r.num_kept_from_user as u64))
    .collect()
}

/// Thread `tid` of this process, if it still runs.
fn thread(tid: i32) -> Option<DeviceThread> {
    let stat = std::fs::read_to_string(format!("/proc/self/task/{tid}/stat")).ok()?;
    let name = std::fs::read_to_string(format!("/proc/self/task/{tid}/comm")).ok()?.trim_end().to_string();
    // Fields after the command name (which may hold spaces): nice is field 19, the 17th after it.
    let nice = stat.rsplit_once(')').and_then(|(_, rest)| rest.split_whitespace().nth(16)?.parse().ok())?;
    Some(DeviceThread { tid, name, nice })
}

/// What `ctl stats` shows of a device; `own`: not the compositor's.
pub fn device_stats(gpu: &Gpu, own: bool) -> DeviceStats {
    DeviceStats {
        own,
        threads: gpu.threads.iter().filter_map(|&t| thread(t)).collect(),
        global_priority: gpu.global_priority.map(str::to_string),
        busy_us: gpu.busy().as_micros().min(u128::from(u64::MAX)) as u64,
        lost: gpu.is_lost(),
    }
}

/// Gathers the daemon's statistics.
pub fn collect(
    gpu: Option<&Gpu>,
    pools: (&Pool, &Pool),
    sessions: u64,
    clients: &HashMap<u64, ClientInfo>,
    scene: &Scene,
) -> DaemonStats {
    let (rss_bytes, peak_rss_bytes, rss_anon_bytes) = rss();
    let mut ids: Vec<&u64> = clients.keys().collect();
    ids.sort();
    let surfaces = scene.rows();
    let mut objects: BTreeMap<String, u64> = Kind::ALL.iter().map(|k| (k.name().to_string(), 0)).collect();
    let rows = ids
        .into_iter()
        .filter_map(|id| clients.get(id).map(|c| (*id, c)))
        .map(|(id, c)| {
            let usage = c.account.usage();
            let mine: BTreeMap<String, u64> =
                Kind::ALL.iter().zip(usage.counts).map(|(k, n)| (k.name().to_string(), n)).collect();
            for (k, n) in &mine {
                *objects.entry(k.clone()).or_default() += n;
            }
            ClientStats {
                id,
                name: c.name.clone(),
                role: c.role.clone(),
                gpu_bytes: usage.gpu_bytes,
                gpu_bytes_limit: c.account.limits().gpu_bytes,
                daemon_bytes: usage.daemon_bytes,
                daemon_bytes_limit: c.account.limits().daemon_bytes,
                objects: mine,
                refusals: usage.refusals,
                stream_bytes: scene.stream_bytes(id),
                priority: c.lane.as_ref().map(|l| l.class()).unwrap_or_default(),
                waits: c.lane.as_ref().map(|l| l.waits()).unwrap_or_default(),
                deadline_misses: surfaces.iter().filter(|r| r.client_id == id).map(|r| r.deadline_misses).sum(),
                peer: scene.peer(id),
                device: c.device.get().map(|d| device_stats(d, gpu.is_none_or(|g| !std::ptr::eq(g, &**d)))),
            }
        })
        .collect();
    DaemonStats {
        rss_bytes,
        peak_rss_bytes,
        rss_anon_bytes,
        sessions,
        clients: rows,
        gpu_bytes: pools.0.used(),
        gpu_bytes_limit: pools.0.limit(),
        reserve_bytes: pools.0.reserve(),
        daemon_bytes: pools.1.used(),
        daemon_bytes_limit: pools.1.limit(),
        // Filled in by the listener, which counts them.
        refused: BTreeMap::new(),
        objects,
        device_objects: gpu.map(device_objects).unwrap_or_default(),
        compositor_device: gpu.map(|g| device_stats(g, false)),
        // Filled in by the listener, which routes input.
        input_dropped: 0,
        pick_reads: [0; 2],
    }
}
