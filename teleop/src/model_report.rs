//! `pomdar model`: a hand model's joints, limits, named frames and embodiments.

use anyhow::{Context, bail};
use retarget::{EmbodimentCatalog, Finger, HandModel};
use serde_json::json;

use crate::hand_source::HandSource;

/// Load the model, pose it and print the report.
pub fn run(source: &HandSource, pose: &[String], json: bool) -> anyhow::Result<()> {
    let model = source.load()?;
    let q = parse_pose(&model, pose)?;
    let state = model.forward_new(&q)?;
    let palm = model
        .palm_frame(&state)
        .context("palm frame at the requested pose")?;
    let frames = model.frames();
    let named: Vec<(String, [f64; 3])> = Finger::ALL
        .iter()
        .flat_map(|&f| {
            [
                (format!("{f}_base"), frames.base(f)),
                (format!("{f}_tip"), frames.tip(f)),
            ]
        })
        .chain([("wrist".to_string(), frames.wrist)])
        .map(|(name, link)| {
            let p = palm.point_to_palm(&state.position(link)) * 1e3;
            (name, [p.x, p.y, p.z])
        })
        .collect();
    let catalog = EmbodimentCatalog::builtin();
    let embodiments: Vec<_> = catalog
        .embodiments
        .iter()
        .map(|e| (e.name.as_str(), e.dof, e.unlocked_mask(&model).is_ok()))
        .collect();

    if json {
        let doc = json!({
            "model": model.name(),
            "source": source.describe(),
            "dof": model.dof(),
            "links": model.link_count(),
            "joints": model.dofs().iter().zip(&q).map(|(d, v)| json!({
                "name": d.name, "lower_rad": d.limits.lower_rad,
                "upper_rad": d.limits.upper_rad, "q_rad": v,
            })).collect::<Vec<_>>(),
            "frames_in_palm_mm": named.iter().map(|(n, p)| (n.clone(), json!(p)))
                .collect::<serde_json::Map<_, _>>(),
            "embodiments": embodiments.iter().map(|(n, dof, ok)| json!({
                "name": n, "dof": dof, "applies": ok,
            })).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&doc)?);
        return Ok(());
    }

    println!(
        "{} — {} ({} degrees of freedom, {} links)",
        model.name(),
        source.describe(),
        model.dof(),
        model.link_count()
    );
    println!(
        "\n{:<12} {:>10} {:>10} {:>10}   {:>8} {:>8}",
        "joint", "lower rad", "upper rad", "q rad", "lower °", "upper °"
    );
    for (dof, v) in model.dofs().iter().zip(&q) {
        println!(
            "{:<12} {:>10.4} {:>10.4} {:>10.4}   {:>8.1} {:>8.1}",
            dof.name,
            dof.limits.lower_rad,
            dof.limits.upper_rad,
            v,
            dof.limits.lower_rad.to_degrees(),
            dof.limits.upper_rad.to_degrees()
        );
    }
    println!("\nnamed frames in the palm frame (mm; x across the knuckles, y to the fingers):");
    for (name, p) in &named {
        println!("  {name:<13} {:>8.1} {:>8.1} {:>8.1}", p[0], p[1], p[2]);
    }
    println!("\nembodiments (built-in catalog):");
    for (name, dof, ok) in &embodiments {
        let status = if *ok {
            ""
        } else {
            "  (not applicable: joints missing in this model)"
        };
        println!("  {name:<10} {dof:>2} DoF{status}");
    }
    Ok(())
}

fn parse_pose(model: &HandModel, pose: &[String]) -> anyhow::Result<Vec<f64>> {
    let mut q = model.zero_pose();
    for item in pose {
        let Some((name, value)) = item.split_once('=') else {
            bail!("--pose: expected NAME=RADIANS, got '{item}'");
        };
        let index = model.dof_index(name.trim()).with_context(|| {
            format!(
                "--pose: '{}' is not a joint of {}; joints: {}",
                name.trim(),
                model.name(),
                model.dof_names().collect::<Vec<_>>().join(", ")
            )
        })?;
        let value: f64 = value
            .trim()
            .parse()
            .with_context(|| format!("--pose: '{value}' is not a number (radians) for {name}"))?;
        let limits = model.dofs()[index].limits;
        if !limits.contains(value) {
            bail!(
                "--pose: {name} = {value} rad is outside its limits [{}, {}] rad",
                limits.lower_rad,
                limits.upper_rad
            );
        }
        q[index] = value;
    }
    Ok(q)
}
