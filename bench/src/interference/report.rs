//! The interference benchmark's report: ratios to the IC alone, the per-load verdicts, the
//! table, `interference.json` and the frame-time CDFs in `interference.png`.

use std::path::Path;

use anyhow::{Context, Result};

use super::measures::{Args, Phase, Report, Verdict, DEADLINE_MS, OUTPUT};
use crate::interference_client::plot_cdf;

/// Ratios to the IC alone, the per-load verdicts, the table, the JSON and the plot.
pub(super) fn report(
    args: &Args,
    mut phases: Vec<Phase>,
    skipped: Vec<String>,
    failures: Vec<String>,
    config: &Path,
    daemon_log: String,
) -> Result<()> {
    let alone = phases[0].clone();
    let ratio = |v: f64, a: f64| (a > 0.0 && v.is_finite()).then(|| v / a);
    for p in phases.iter_mut().skip(1) {
        p.p50_ratio = ratio(p.ic.p50_ms, alone.ic.p50_ms);
        p.p99_ratio = ratio(p.ic.p99_ms, alone.ic.p99_ms);
        p.max_ratio = ratio(p.ic.max_ms, alone.ic.max_ms);
    }
    let verdicts: Vec<Verdict> = phases
        .iter()
        .skip(1)
        .map(|p| {
            let p99_ratio = p.p99_ratio.unwrap_or(f64::INFINITY);
            let (client_misses, alone_client_misses) = (p.ic.client_misses, alone.ic.client_misses);
            let (p99_ok, misses_ok) = (p99_ratio <= 1.25, client_misses <= alone_client_misses);
            // A load without a HU (the CPU hog) has nothing to keep.
            let hu_ok = p.hu_alone_fps.is_none() || p.hu_vs_alone.is_some_and(|r| r >= 0.7);
            let load = p.phase.clone();
            Verdict {
                load,
                p99_ratio,
                p99_ok,
                client_misses,
                alone_client_misses,
                misses_ok,
                hu_vs_alone: p.hu_vs_alone,
                hu_ok,
                pass: p99_ok && misses_ok && hu_ok,
            }
        })
        .collect();
    let plot = args.out.join("interference.png");
    let curves: Vec<(&str, &[f64])> = phases.iter().map(|p| (p.phase.as_str(), p.frame_times_ms.as_slice())).collect();
    let plot_result = plot_cdf(&plot, &curves, args.seconds, DEADLINE_MS);
    let r = Report {
        benchmark: "interference",
        seconds: args.seconds,
        priorities: !args.no_priorities,
        config: config.display().to_string(),
        output: OUTPUT,
        deadline_ms: DEADLINE_MS,
        phases,
        skipped,
        failures,
        verdicts,
        plot: plot.display().to_string(),
        daemon_log,
    };
    let json = serde_json::to_string_pretty(&r)?;
    let json_path = args.out.join("interference.json");
    std::fs::write(&json_path, &json).with_context(|| format!("writing {}", json_path.display()))?;
    if args.json {
        println!("{json}");
        return plot_result;
    }
    print_table(&r);
    match plot_result {
        Ok(()) => println!("{} and {}", json_path.display(), r.plot),
        Err(e) => println!("{} (plot not written: {e:#})", json_path.display()),
    }
    Ok(())
}

/// Prints the phases as a table, with the verdicts.
fn print_table(r: &Report) {
    let opt = |v: Option<f64>, d: usize| v.map_or_else(|| "-".into(), |v| format!("{v:.d$}"));
    println!(
        "IC (320x320, swap interval 1) beside each HU load, {} s each; priorities {}; deadline {:.1} ms",
        r.seconds,
        if r.priorities { "on" } else { "off" },
        r.deadline_ms
    );
    println!(
        "phase      frames  p50 ms  p99 ms   max ms misses daemon  p50 x  p99 x  max x  HU fps  HU own HU alone HU/alone  load"
    );
    for p in &r.phases {
        println!(
            "{:<10} {:>6} {:>7.2} {:>7.2} {:>8.2} {:>6} {:>6} {:>6} {:>6} {:>6} {:>7} {:>7} {:>8} {:>8} {:>5}",
            p.phase,
            p.ic.frames,
            p.ic.p50_ms,
            p.ic.p99_ms,
            p.ic.max_ms,
            p.ic.client_misses,
            p.daemon_deadline_misses.map_or_else(|| "null".into(), |m| m.to_string()),
            opt(p.p50_ratio, 2),
            opt(p.p99_ratio, 2),
            opt(p.max_ratio, 2),
            opt(p.hu_fps, 2),
            opt(p.hu_reported_fps, 2),
            opt(p.hu_alone_fps, 2),
            opt(p.hu_vs_alone, 2),
            opt(p.load_average_1m, 2),
        );
    }
    for p in &r.phases {
        if let Some(e) = &p.hu_error {
            println!("  {}: {e}", p.phase);
        }
    }
    for v in &r.verdicts {
        let hu = v.hu_vs_alone.map_or_else(|| "no HU".to_string(), |r| format!("{r:.2}x"));
        println!(
            "target {:<10} p99 {:.2}x alone ({}), misses {} vs {} alone ({}), HU {hu} of alone ({}): {}",
            v.load,
            v.p99_ratio,
            if v.p99_ok { "<= 1.25 ok" } else { "> 1.25" },
            v.client_misses,
            v.alone_client_misses,
            if v.misses_ok { "ok" } else { "more" },
            if v.hu_ok { ">= 0.7 ok" } else { "< 0.7" },
            if v.pass { "MET" } else { "NOT MET" }
        );
    }
    for s in r.skipped.iter().chain(&r.failures) {
        println!("  {s}");
    }
}
