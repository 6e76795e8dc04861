//! The free fibre along written winding programs: the contact point
//! recovered from the job planned again gives the planner's own free-fibre
//! direction at every block end; a solid put in the fibre's way on a shipped
//! machine is found where the fibre meets it; the demo programs are clean.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_machine::{Shape, Visual};
use formcam_nc::Dialect;
use formcam_program::{Stage, WindJob, WoundProgram, plan_until, write_program};
use formcam_sim::{FeedRule, SnagOptions, Timeline, ViolationKind, check_snag, read_program};
use nalgebra::{Isometry3, Point3};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// The example job `name`, planned to its program.
fn planned(name: &str) -> WoundProgram {
    let path = examples().join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let job = WindJob::from_toml(&text, &examples()).unwrap().named(&path);
    plan_until(&job, Stage::Program).unwrap()
}

/// The program of `wound` as written, read back: its timeline on the job's
/// machine.
fn timeline(wound: &WoundProgram) -> (Timeline, Dialect) {
    let mut bytes = Vec::new();
    write_program(wound, &mut bytes).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    let m = wound.machine.as_ref().unwrap();
    let ext = wound.post.extension().to_string();
    let (p, lines, d) = read_program(Path::new(&format!("program.{ext}")), &text, m).unwrap();
    (Timeline::new(&p, &lines, FeedRule::of(d), m).unwrap(), d)
}

/// At every block end that winds a layer: the angle between the fibre
/// (program payout point to recovered contact) and the planner's free band
/// (its eye and path rows, the numbers of `eye.csv`, at the same place), and
/// how far the payout point is from the planned eye; the largest of each.
fn direction_errors(wound: &WoundProgram) -> (f64, f64, usize) {
    let (tl, _) = timeline(wound);
    let fibre = formcam_program::free_fibre(wound).unwrap();
    let track = fibre.follow(&tl).unwrap();
    let mut s = fibre.sampler(&tl, &track);
    let (mut angle, mut eye, mut n) = (0.0f64, 0.0f64, 0);
    for b in tl.blocks() {
        let Some(st) = s.at(b.index, b.start_s + b.duration_s) else {
            continue;
        };
        let layer = &fibre.layers()[st.layer];
        let k = (st.row + 1).min(layer.rows() - 1);
        let lerp = |p: Point3<f64>, q: Point3<f64>| p + (q - p) * st.fraction;
        let planned_eye = lerp(layer.eye(st.row).unwrap(), layer.eye(k).unwrap());
        let planned_path = lerp(layer.contact(st.row).unwrap(), layer.contact(k).unwrap());
        let planned = (planned_eye - planned_path).normalize();
        let got = (st.payout_mandrel - st.contact_mandrel).normalize();
        angle = angle.max(got.dot(&planned).clamp(-1.0, 1.0).acos());
        eye = eye.max((st.payout_mandrel - planned_eye).norm());
        n += 1;
    }
    (angle.to_degrees(), eye, n)
}

#[test]
fn the_recovered_fibre_is_the_planners_free_band_at_every_block_end() {
    // A 4-axis winder (pull-speed eye) and the 6-axis one.
    for name in ["vessel-axes-4axis.toml", "vessel-axes-6axis.toml"] {
        let wound = planned(name);
        let (angle_deg, eye_mm, n) = direction_errors(&wound);
        assert!(n > 100, "{name}: {n} block ends");
        assert!(
            angle_deg < 0.05,
            "{name}: {angle_deg}° between the directions"
        );
        assert!(
            eye_mm < 0.05,
            "{name}: payout point {eye_mm} mm from the planned eye"
        );
    }
}

#[test]
fn a_solid_in_the_fibres_way_is_found_where_the_fibre_meets_it() {
    let wound = planned("vessel-axes-4axis.toml");
    let (tl, _) = timeline(&wound);
    let fibre = formcam_program::free_fibre(&wound).unwrap();
    let opts = SnagOptions::default();
    assert_eq!(check_snag(&tl, &fibre, &opts).unwrap(), []);
    // The fibre's middle at the end of a block a third into the first
    // circuit (every circuit puts the fibre at the same places in the world,
    // so the first is where it is met first), in the world.
    let track = fibre.follow(&tl).unwrap();
    let mut sampler = fibre.sampler(&tl, &track);
    let first_circuit: Vec<usize> = tl
        .blocks()
        .filter(|b| {
            sampler
                .at(b.index, b.start_s + b.duration_s)
                .is_some_and(|st| st.circuit == 0)
        })
        .map(|b| b.index)
        .collect();
    let k = first_circuit[first_circuit.len() / 3];
    let end = tl.block(k).unwrap();
    let t = end.start_s + end.duration_s;
    let st = sampler.at(k, t).unwrap();
    let middle = st.payout + (st.contact - st.payout) * 0.5;
    // A 3 mm ball there, on the bed (the world frame).
    let mut m = fibre.machine().clone();
    m.links[0].visuals.push(Visual {
        shape: Shape::Sphere(3.0),
        origin: Isometry3::translation(middle.x, middle.y, middle.z),
        color: "#ff0000".into(),
        scale: [1.0; 3],
    });
    let blocked = fibre.clone().with_machine(m).unwrap();
    let found = check_snag(&tl, &blocked, &opts).unwrap();
    assert_eq!(found.len(), 1, "{found:?}");
    let v = &found[0];
    assert_eq!(
        (v.kind, v.axis.as_str()),
        (ViolationKind::Snag, "bed solid 2")
    );
    // The fibre passes through the ball's centre at t: it is found there or
    // before, where it comes within the margin; the worst clearance is the
    // ball's radius inside it.
    assert!(v.time_s <= t + 1e-9, "{} > {t}", v.time_s);
    assert!(v.block <= k + 1, "block {} (k = {k})", v.block);
    // The clearance of the fibre from the ball at a time, by hand.
    let mut clearance = |block: usize, time: f64| {
        let at = sampler.at(block, time).unwrap();
        let d = at.contact - at.payout;
        let u = ((middle - at.payout).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
        (at.payout + d * u - middle).norm() - 3.0
    };
    // Where it is first found, the fibre is that near; at the start of the
    // block before, it is clear of the margin: it comes within it in the
    // block found or the one before (the samples are 1 mm apart).
    let near = clearance(v.block - 1, v.time_s);
    assert!((near - v.value).abs() < 1e-6, "{near} vs {}", v.value);
    assert!(near < opts.solid_margin_mm);
    let before = tl.block(v.block - 2).unwrap();
    let clear = clearance(before.index, before.start_s);
    assert!(
        clear > opts.solid_margin_mm,
        "{clear} mm at block {}",
        before.index + 1
    );
    assert_eq!(v.line, tl.block(v.block - 1).unwrap().line);
    assert!(v.worst_value <= -3.0 + opts.sample_mm, "{}", v.worst_value);
    assert!(v.worst_value >= -3.0 - 1e-6, "{}", v.worst_value);
    assert_eq!(v.limit, opts.solid_margin_mm);
}

#[test]
fn every_demo_winding_program_is_clean_of_snags() {
    let mut jobs: Vec<(String, WoundProgram)> = [
        "tube-axes-2axis.toml",
        "tube-layers-4axis.toml",
        "vessel-axes-6axis.toml",
        "vessel-layers-840d.toml",
        "vessel-program-840d.toml",
    ]
    .iter()
    .map(|n| (n.to_string(), planned(n)))
    .collect();
    let wind = std::fs::read_to_string(examples().join("tube-fiberpath.wind")).unwrap();
    let job = WindJob::from_wind(&wind, formcam_program::EYE_CLEARANCE_MM, &[]).unwrap();
    jobs.push((
        "tube-fiberpath.wind".into(),
        plan_until(&job, Stage::Program).unwrap(),
    ));
    for (name, wound) in &jobs {
        let (tl, _) = timeline(wound);
        let fibre = formcam_program::free_fibre(wound).unwrap();
        let track = fibre.follow(&tl).unwrap();
        // Every wound layer is found in the program.
        let found: std::collections::BTreeSet<usize> =
            track.blocks.iter().flatten().map(|(l, _)| *l).collect();
        assert_eq!(found.len(), fibre.layers().len(), "{name}");
        let snags = check_snag(&tl, &fibre, &SnagOptions::default()).unwrap();
        assert_eq!(snags, [], "{name}");
    }
}

#[test]
fn a_laminate_thicker_than_the_eyes_clearance_snags_where_the_eye_dips_into_it() {
    // The 4-axis vessel's layer checked on its mandrel grown by 30 mm: the
    // eye, kept 20 mm out of the clearance zone, runs inside the laminate
    // where it comes nearest, so the fibre cuts the surface there.
    let path = examples().join("vessel-axes-4axis.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let job = WindJob::from_toml(&text, &examples()).unwrap();
    let mut wound = plan_until(&job, Stage::Program).unwrap();
    let (tl, _) = timeline(&wound);
    let grown = job
        .mandrel
        .grown(30.0)
        .unwrap()
        .build(|f| Err(f.to_string()))
        .unwrap();
    if let formcam_program::LayerBody::Wind(w) = &mut wound.layers[0].body {
        w.mandrel = grown;
    }
    let fibre = formcam_program::free_fibre(&wound).unwrap();
    let track = fibre.follow(&tl).unwrap();
    // The first block at whose end the program's payout point is inside
    // the grown surface, by the surface's own clearance of that point.
    let mut sampler = fibre.sampler(&tl, &track);
    let layer = &fibre.layers()[0];
    let inside = tl
        .blocks()
        .find(|b| {
            sampler
                .at(b.index, b.start_s + b.duration_s)
                .and_then(|st| layer.gap(&st.payout_mandrel))
                .is_some_and(|g| g < 0.0)
        })
        .unwrap();
    let found = check_snag(&tl, &fibre, &SnagOptions::default()).unwrap();
    assert_eq!(found.len(), 1, "{found:?}");
    let v = &found[0];
    assert_eq!((v.kind, v.axis.as_str()), (ViolationKind::Snag, "mandrel"));
    // Found no later than there (the fibre's middle may dip in first).
    assert!(
        v.block <= inside.index + 1,
        "{} > {}",
        v.block,
        inside.index + 1
    );
    assert_eq!(v.line, tl.block(v.block - 1).unwrap().line);
    // Inside the surface, and as deep as the eye is under it at worst.
    assert!(v.value < 0.0 && v.limit < 0.0, "{v:?}");
    assert!(v.worst_value < -5.0 && v.worst_value > -30.0, "{v:?}");
}
