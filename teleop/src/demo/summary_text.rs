//! `pomdar demo`'s summary for a person on stdout: rates, latency, the control step, rejected
//! frames, the longest glove gap, the recording, the fingertip error and, with `--physics`, the
//! task's progress as the physics measured it.

use std::path::Path;

use super::DemoSummary;

/// The demo's summary for a person.
pub fn print_summary(summary: &DemoSummary, recorded: Option<&Path>, control: &str) {
    let ms = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2} ms"));
    println!("summary over {:.1} s:", summary.duration_s);
    println!(
        "  glove frames       {:.1} /s over {:.1} s of sending",
        summary.input_rate_hz, summary.glove_sending_s
    );
    println!(
        "  joint targets      {:.1} /s ({} received)",
        summary.output_rate_hz, summary.hand_targets
    );
    println!("  arm targets        {}", summary.arm_targets);
    println!(
        "  end-to-end latency p50 {}, p99 {} (glove publish → joint target received, {control})",
        ms(summary.latency_ms_p50),
        ms(summary.latency_ms_p99)
    );
    println!(
        "  control step       p50 {}, p99 {}",
        ms(summary.solver_ms_p50),
        ms(summary.solver_ms_p99)
    );
    println!("  rejected frames    {}", summary.rejected_frames);
    if let Some(gap) = &summary.longest_input_gap {
        println!(
            "  longest glove gap  {:.0} ms as received ({:.0} ms as sent)",
            gap.received_ms, gap.sent_ms
        );
    }
    if let Some(path) = recorded {
        println!("  recorded           {}", path.display());
        if summary.log_dropped > 0 {
            println!(
                "  not logged         {} messages (the disk fell behind)",
                summary.log_dropped
            );
        }
    }
    println!(
        "  fingertip error    {} (palm-to-tip key vectors, uncalibrated)",
        summary
            .fingertip_error_mm
            .map_or("-".into(), |v| format!("{v:.1} mm"))
    );
    if let Some(p) = &summary.physics {
        println!(
            "  task {}           progress {} {}, correctness {} (measured by the physics); physics {:.1}× real time",
            p.task,
            p.progress,
            p.unit,
            p.correctness.map_or("-".into(), |c| format!("{c:.2}")),
            p.realtime_factor
        );
    }
}
