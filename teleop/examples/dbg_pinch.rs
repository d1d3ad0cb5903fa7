use retarget::{Finger, HandModel};
use station::StationConfig;
use teleop::eval::{build_retargeter, distinct_frames};
use teleop::mcap_log::TrialReader;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = std::path::PathBuf::from(&args[1]);
    let finger = match args[2].as_str() {
        "index" => Finger::Index,
        "middle" => Finger::Middle,
        "ring" => Finger::Ring,
        _ => Finger::Little,
    };
    let mut config = match args.get(3) {
        Some(p) => {
            teleop::station_setup::load_station_config(Some(std::path::Path::new(p)), None).unwrap()
        }
        None => StationConfig::default(),
    };
    let _ = &mut config;
    let reader = TrialReader::open(&path).unwrap();
    let (frames, _) = distinct_frames(&reader, &config).unwrap();
    let mut rc = config.retarget.clone();
    if frames[0].points.len() == 21 {
        rc.layout = retarget::KeypointLayout::Lab21;
    }
    let layout = rc.layout;
    let model = HandModel::orca_v1_right();
    let mut r = build_retargeter(&model, rc, None).unwrap();
    let mut prev: Option<(i64, Vec<f64>)> = None;
    let mut hist: Vec<String> = Vec::new();
    let mut qs: Vec<Vec<f64>> = Vec::new();
    for f in &frames {
        let dt = prev
            .as_ref()
            .map_or(1.0 / 30.0, |p| (f.t_ns - p.0) as f64 * 1e-9);
        let s = r.retarget(&f.points, dt).unwrap();
        let fk = model.forward_new(&s.q).unwrap();
        let tip = |g: Finger| fk.position(model.frames().tip(g));
        let rob = (tip(finger) - tip(Finger::Thumb)).norm();
        let hum = (f.points[layout.tip(finger)] - f.points[layout.tip(Finger::Thumb)]).norm();
        let step = prev.as_ref().map_or(0.0, |p| {
            p.1.iter()
                .zip(&s.q)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
        });
        let line = format!(
            "{:4} t={:.3} human {:5.1} robot {:5.1} step {:.3} prior {:.2} {}",
            hist.len(),
            (f.t_ns - frames[0].t_ns) as f64 * 1e-9,
            hum * 1e3,
            rob * 1e3,
            step,
            s.prior_weight,
            if hum < 0.02 {
                if rob < 0.015 {
                    "PINCH ok"
                } else {
                    "PINCH MISS"
                }
            } else {
                ""
            }
        );
        hist.push(line);
        qs.push(s.q.clone());
        prev = Some((f.t_ns, s.q.clone()));
    }
    if std::env::var("JERK").is_ok() {
        for k in 3..qs.len() {
            let j: f64 = (0..qs[k].len())
                .map(|d| (qs[k][d] - 3.0 * qs[k - 1][d] + 3.0 * qs[k - 2][d] - qs[k - 3][d]).abs())
                .sum();
            let f = &frames[k];
            let dd: Vec<String> = Finger::OPPOSING
                .iter()
                .map(|g| {
                    format!(
                        "{:.0}",
                        (f.points[layout.tip(*g)] - f.points[layout.tip(Finger::Thumb)]).norm()
                            * 1e3
                    )
                })
                .collect();
            println!("{k} {j:.5} {}", dd.join(","));
        }
        return;
    }
    if std::env::var("SPEEDS").is_ok() {
        let mut prevd: Option<[f64; 4]> = None;
        let mut counts = [0usize; 6];
        for f in &frames {
            let d: [f64; 4] = std::array::from_fn(|i| {
                (f.points[layout.tip(Finger::OPPOSING[i])] - f.points[layout.tip(Finger::Thumb)])
                    .norm()
            });
            if let Some(p) = prevd {
                for i in 0..4 {
                    if d[i] < 0.06 {
                        let v = (p[i] - d[i]) * 30.0;
                        let a = 1.0 - 1.0 / (1.0 + (v.max(0.0) / 0.5).powi(2));
                        if a > 0.05 {
                            counts[i] += 1;
                        }
                        if a > 0.3 {
                            counts[4] += 1;
                        }
                    }
                }
            }
            prevd = Some(d);
        }
        println!(
            "frames {} alpha>0.05 per finger {:?} >0.3 {}",
            frames.len(),
            &counts[..4],
            counts[4]
        );
        return;
    }
    for (i, l) in hist.iter().enumerate() {
        if l.contains("PINCH") {
            for j in i.saturating_sub(4)..=(i + 1).min(hist.len() - 1) {
                println!("{}", hist[j]);
            }
            println!("--");
        }
    }
}
#[allow(dead_code)]
fn unused() {}
