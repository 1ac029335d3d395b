//! How `stratad ctl` prints its answers for people (`--json` prints them as they are).

use strata_protocol::control::{OutputRow, SurfaceRow};
use strata_protocol::events::Event;
use strata_protocol::properties::LayerRow;

/// A surface's regions where set, and its own visibility and opacity where its layers change
/// them, as a suffix of its row.
fn regions(r: &SurfaceRow) -> String {
    let mut s = String::new();
    if let Some(v) = r.props.source {
        s += &format!("  source {}x{}+{}+{} of {}x{}", v[2], v[3], v[0], v[1], r.image[0], r.image[1]);
    }
    if r.props.destination.is_some() {
        s += "  scaled";
    }
    if (r.props.visible, r.props.opacity) != (r.shown_visible, r.shown_opacity) {
        s += &format!("  own: {} {:.3}", if r.props.visible { "on" } else { "off" }, r.props.opacity);
    }
    s
}

/// A client's credentials: uid and pid, and whether it claims a name it may not use.
fn credentials(p: &strata_protocol::control::Peer) -> String {
    format!("uid {} pid {}{}", p.uid, p.pid, if p.unverified { " unverified" } else { "" })
}

/// Every output, surface and layer, as tables.
pub fn list(outputs: &[OutputRow], surfaces: &[SurfaceRow], layers: &[LayerRow]) {
    println!(
        "{:<16} {:<9} {:>6} {:>6} {:>6} {:>6} {:>10} {:>6} {:>6} {:>9} {:>8} {:>9} {:>6}  last redrawn",
        "output",
        "kind",
        "x",
        "y",
        "w",
        "h",
        "composites",
        "banded",
        "passes",
        "device ms",
        "queue ms",
        "encode ms",
        "focus"
    );
    for o in outputs {
        let r = o.region;
        let each = |us: u64| us as f64 / 1000.0 / o.composites.max(1) as f64;
        let (ms, queue, encode) = (each(o.composite_us), each(o.queue_us), each(o.encode_us));
        println!(
            "{:<16} {:<9} {:>6} {:>6} {:>6} {:>6} {:>10} {:>6} {:>6} {ms:>9.2} {queue:>8.2} {encode:>9.2} {:>6}  {}x{}+{}+{}",
            o.name,
            o.kind,
            o.rect[0],
            o.rect[1],
            o.rect[2],
            o.rect[3],
            o.composites,
            o.banded,
            o.passes,
            o.focus.map_or_else(|| "-".to_string(), |s| s.to_string()),
            r[2],
            r[3],
            r[0],
            r[1]
        );
    }
    println!();
    println!(
        "{:>4} {:<20} {:<24} {:>6} {:>6} {:>6} {:>6} {:>8} {:>8} {:>8} {:>8} {:>12} {:>8} {:>8} {:>16} {:>4} {:>7} {:>5}  projection",
        "id",
        "client",
        "credentials",
        "x",
        "y",
        "w",
        "h",
        "z",
        "frames",
        "shown",
        "interval",
        "stream bytes",
        "priority",
        "missed",
        "shown in (p99)",
        "vis",
        "opacity",
        "input"
    );
    for r in surfaces {
        println!(
            "{:>4} {:<20} {:<24} {:>6} {:>6} {:>6} {:>6} {:>8.3} {:>8} {:>8} {:>8} {:>12} {:>8} {:>8} {:>16} {:>4} {:>7.3} {:>5}  {}{}",
            r.id,
            format!("{} ({})", r.client, r.client_id),
            credentials(&r.peer),
            r.rect[0],
            r.rect[1],
            r.rect[2],
            r.rect[3],
            r.z,
            r.frames,
            r.shown,
            r.interval,
            r.stream_bytes,
            r.priority.name(),
            if r.deadline { r.deadline_misses.to_string() } else { "-".into() },
            format!("{:.1} ms", r.shown_latency_us[1] as f64 / 1000.0),
            if r.shown_visible { "on" } else { "off" },
            r.shown_opacity,
            if r.props.input { "on" } else { "off" },
            r.projection.map_or_else(|| "-".to_string(), |p| p.to_string()),
            regions(r)
        );
    }
    if !layers.is_empty() {
        println!();
        println!("{:<20} {:>4} {:>7}  surfaces", "layer", "vis", "opacity");
        for l in layers {
            let ids: Vec<String> = l.surfaces.iter().map(u64::to_string).collect();
            println!(
                "{:<20} {:>4} {:>7.3}  {}",
                l.name,
                if l.visible { "on" } else { "off" },
                l.opacity,
                ids.join(" ")
            );
        }
    }
}

fn mib(bytes: u64) -> String {
    format!("{:.1} MiB", bytes as f64 / (1 << 20) as f64)
}

/// One device as `ctl stats` prints it: busy time, its driver threads' nice values, the global
/// priority granted, whether it is the client's own and whether it was lost.
fn device_line(d: &strata_protocol::control::DeviceStats) -> String {
    let mut nice: Vec<i32> = d.threads.iter().map(|t| t.nice).collect();
    nice.sort_unstable();
    nice.dedup();
    format!(
        "busy {:.1} ms, {} threads at nice {:?}, global priority {}{}{}",
        d.busy_us as f64 / 1000.0,
        d.threads.len(),
        nice,
        d.global_priority.as_deref().unwrap_or("not offered"),
        if d.own { "" } else { ", shared" },
        if d.lost { ", LOST" } else { "" }
    )
}

pub fn stats(s: &strata_protocol::control::DaemonStats) {
    println!(
        "daemon: rss {} (peak {}), {} sessions started, {} input actions dropped",
        mib(s.rss_bytes),
        mib(s.peak_rss_bytes),
        s.sessions,
        s.input_dropped
    );
    println!(
        "input picks: {} texels read on input routing's device, {} on the compositor's",
        s.pick_reads[0], s.pick_reads[1]
    );
    println!(
        "gpu memory: {} of {} for all clients ({} of it reserved for the reserved class); daemon's memory: {} of {}",
        mib(s.gpu_bytes),
        mib(s.gpu_bytes_limit),
        mib(s.reserve_bytes),
        mib(s.daemon_bytes),
        mib(s.daemon_bytes_limit)
    );
    if !s.refused.is_empty() {
        let by: Vec<String> = s.refused.iter().map(|(cap, n)| format!("{cap} {n}")).collect();
        println!("connections refused: {}", by.join(", "));
    }
    let kinds: Vec<&String> = s.objects.keys().collect();
    print!(
        "{:>4} {:<20} {:>8} {:>8} {:>12} {:>12} {:>12} {:>8}",
        "id", "client", "priority", "missed", "gpu memory", "daemon-side", "limit", "refused"
    );
    for k in &kinds {
        print!(" {:>13}", k);
    }
    println!();
    for c in &s.clients {
        print!(
            "{:>4} {:<20} {:>8} {:>8} {:>12} {:>12} {:>12} {:>8}",
            c.id,
            c.name,
            c.priority.name(),
            c.deadline_misses,
            mib(c.gpu_bytes),
            mib(c.daemon_bytes),
            mib(c.gpu_bytes_limit),
            c.refusals
        );
        for k in &kinds {
            print!(" {:>13}", c.objects.get(*k).copied().unwrap_or(0));
        }
        println!();
    }
    print!(
        "{:>4} {:<20} {:>8} {:>8} {:>12} {:>12} {:>12} {:>8}",
        "",
        "total",
        "",
        "",
        mib(s.gpu_bytes),
        mib(s.daemon_bytes),
        mib(s.gpu_bytes_limit),
        ""
    );
    for k in &kinds {
        print!(" {:>13}", s.objects[*k]);
    }
    println!();
    println!("where frames waited (ms): swap, device; each device: busy ms, threads at nice, global priority");
    for c in &s.clients {
        let w = &c.waits;
        let ms = |us: u64| us as f64 / 1000.0;
        print!("{:>4} {:<20} {:>10.1} {:>10.1}", c.id, c.name, ms(w.swap_us), ms(w.gpu_us));
        match &c.device {
            Some(d) => println!("  {}", device_line(d)),
            None => println!(),
        }
    }
    if let Some(d) = &s.compositor_device {
        println!("{:>4} {:<20} {:>10} {:>10}  {}", "", "(compositor)", "", "", device_line(d));
    }
    if !s.device_objects.is_empty() {
        let live: Vec<String> = s.device_objects.iter().map(|(k, v)| format!("{k} {v}")).collect();
        println!("device objects: {}", live.join(", "));
    }
}

/// One event as a line for people.
pub fn event(e: &Event) -> String {
    match e {
        Event::ClientConnected { client, name, pid } => format!("client {client} {name:?} (pid {pid}) connected"),
        Event::ClientGone { client, name, pid, reason } => {
            format!("client {client} {name:?} (pid {pid}) gone: {reason}")
        }
        Event::SurfaceCreated { surface, client, name, pid } => {
            format!("surface {surface} created by client {client} {name:?} (pid {pid})")
        }
        Event::SurfaceDestroyed { surface, client, name, pid } => {
            format!("surface {surface} of client {client} {name:?} (pid {pid}) destroyed")
        }
        Event::Changed(c) => format!("changed: {}", serde_json::json!(c)),
        Event::Frames { surface, frames, shown, deadline_misses, fps } => {
            format!("surface {surface}: {frames} frames, {shown} shown, {deadline_misses} missed, {fps:.1} fps")
        }
        Event::Focus { output, surface: Some(s) } => format!("output {output:?}: keyboard focus on surface {s}"),
        Event::Focus { output, surface: None } => format!("output {output:?}: no keyboard focus"),
        Event::Dropped { missed } => format!("dropped by the daemon: {missed} events behind"),
    }
}
