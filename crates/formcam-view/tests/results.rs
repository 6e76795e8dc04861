//! The plots of a winding result and the dressing and correction results,
//! as the server answers them for the bundled examples: every series as
//! long as the table it comes from, velocities that are the blocks' axis
//! changes over their times, the dresser at each block's end where the
//! program's words put it, and the correction's map with every point of
//! the CMM file.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_view::{Page, ResultKind, View};
use serde_json::Value;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The result of the example job `name`, written into a fresh folder.
fn result(name: &str) -> PathBuf {
    result_as(name, name)
}

/// [`result`] into the folder `folder` (tests running at once of the same
/// job each write their own).
fn result_as(name: &str, folder: &str) -> PathBuf {
    let job = repo().join("examples").join(name);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("view-results")
        .join(folder);
    let _ = std::fs::remove_dir_all(&dir);
    let run = formcam_run::run_job_file(&job, &dir).unwrap();
    for f in &run.files {
        let path = dir.join(&f.name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, &f.bytes).unwrap();
    }
    dir
}

fn get(view: &View, url: &str) -> Value {
    let (status, _, body) = view.answer(url);
    assert_eq!(status, 200, "{url}: {}", String::from_utf8_lossy(&body));
    serde_json::from_slice(&body).unwrap()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Data rows of a CSV file.
fn rows(path: &Path) -> usize {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .count()
}

#[test]
fn winding_plots_hold_every_layer_and_the_blocks_velocities() {
    let dir = result("vessel-layers-840d.toml");
    let view = View::open(&dir, None, Page::default()).unwrap();
    assert_eq!(view.kind(), ResultKind::Winding);
    assert_eq!(get(&view, "/api/kind")["kind"], "winding");
    let p = get(&view, "/api/plots");
    let meridian = p["meridian"].as_array().unwrap();
    assert_eq!(meridian.len(), 3, "three winding layers");
    for m in meridian {
        let layer = m["layer"].as_u64().unwrap();
        let table = dir.join(format!("layer-{layer:02}/path.csv"));
        let z = numbers(&m["z"]);
        assert_eq!(z.len(), rows(&table));
        assert_eq!(numbers(&m["alpha_deg"]).len(), z.len());
        assert_eq!(numbers(&m["thickness"]).len(), z.len());
        assert!(z.windows(2).all(|w| w[0] <= w[1]));
    }
    let pull = p["pull"].as_array().unwrap();
    assert!(!pull.is_empty());
    for u in pull {
        let layer = u["layer"].as_u64().unwrap();
        let table = dir.join(format!("layer-{layer:02}/eye.csv"));
        assert_eq!(numbers(&u["u"]).len(), rows(&table));
    }
    let a = &p["axes"];
    let t = numbers(&a["t"]);
    let blocks = numbers(&a["block_s"]);
    assert_eq!(t.len(), blocks.len() + 1);
    for (k, name) in a["names"].as_array().unwrap().iter().enumerate() {
        let pos = numbers(&a["position"][k]);
        let vel = a["velocity"][k].as_array().unwrap();
        assert_eq!(pos.len(), t.len(), "{name}");
        assert_eq!(vel.len(), t.len(), "{name}");
        for b in 0..blocks.len() {
            assert!((t[b + 1] - t[b] - blocks[b]).abs() < 1e-9);
            match vel[b].as_f64() {
                // Per minute: the change over the block's time.
                Some(v) => {
                    let change = pos[b + 1] - pos[b];
                    let want = change / blocks[b] * 60.0;
                    assert!(
                        (v - want).abs() <= 1e-9 * want.abs().max(1.0),
                        "{name} block {b}: {v} vs {want}"
                    );
                }
                None => assert_eq!(blocks[b], 0.0),
            }
        }
    }
    // The dressing and correction routes are not this result's.
    assert_eq!(view.answer("/api/dressing").0, 404);
    assert_eq!(view.answer("/api/correction").0, 404);
}

/// The `Z`, `X` words of the program line `line` (1-based), modal.
fn program_points(text: &str) -> Vec<(f64, f64)> {
    let mut at = (f64::NAN, f64::NAN);
    let mut out = Vec::new();
    for line in text.lines() {
        let code = line.split(';').next().unwrap_or("");
        for w in code.split_whitespace() {
            if let Some(v) = w.strip_prefix('Z').and_then(|v| v.parse().ok()) {
                at.0 = v;
            } else if let Some(v) = w.strip_prefix('X').and_then(|v| v.parse().ok()) {
                at.1 = v;
            }
        }
        out.push(at);
    }
    out
}

#[test]
fn the_dresser_moves_along_the_programs_points_in_its_own_time() {
    let dir = result("dress-ballscrew-nut.toml");
    let view = View::open(&dir, None, Page::default()).unwrap();
    assert_eq!(view.kind(), ResultKind::Dressing);
    assert_eq!(get(&view, "/api/kind")["kind"], "dressing");
    assert_eq!(view.answer("/api/machine").0, 404);
    assert_eq!(view.answer("/api/plots").0, 404);
    let d = get(&view, "/api/dressing");
    assert_eq!(
        d["profile"].as_array().unwrap().len(),
        rows(&dir.join("profile.csv"))
    );
    let path_points: usize = d["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["path"].as_array().unwrap().len())
        .sum();
    assert_eq!(path_points, rows(&dir.join("dresser.csv")));
    assert_eq!(
        d["mrr"]["z"].as_array().unwrap().len(),
        rows(&dir.join("mrr.csv"))
    );
    // The program's own time against the dressing's: within the rounding
    // of the written program (0.001 mm on steps of 0.01 mm, the feeds'
    // decimals), about 0.2 % here.
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let want = summary["dressing_time_s"].as_f64().unwrap();
    let duration = d["duration_s"].as_f64().unwrap();
    assert!(
        (duration - want).abs() < 1e-2 * want,
        "{duration} s vs {want} s"
    );
    // At each block's end point A stands where the program's words put it,
    // half way between the block's ends at half its time.
    let text = std::fs::read_to_string(dir.join("program.mpf")).unwrap();
    let words = program_points(&text);
    let t = numbers(&d["t"]);
    let lines = d["lines"].as_array().unwrap();
    let mut checked = 0;
    for b in (0..lines.len()).step_by(29).chain([lines.len() - 1]) {
        let line = lines[b].as_u64().unwrap() as usize;
        let (z, x) = words[line - 1];
        let s = get(&view, &format!("/api/dressing/sample?t={}", t[b + 1]));
        let [sx, sz] = [
            s["dresser"][0].as_f64().unwrap(),
            s["dresser"][1].as_f64().unwrap(),
        ];
        if t[b + 1] > t[b] {
            assert!(
                (sz - z).abs() < 1e-6 && (sx - x).abs() < 1e-6,
                "block {b}: {s}"
            );
            checked += 1;
            if b > 0 {
                let (z0, x0) = words[lines[b - 1].as_u64().unwrap() as usize - 1];
                let m = get(
                    &view,
                    &format!("/api/dressing/sample?t={}", 0.5 * (t[b] + t[b + 1])),
                );
                let mz = m["dresser"][1].as_f64().unwrap();
                let mx = m["dresser"][0].as_f64().unwrap();
                assert!((mz - 0.5 * (z0 + z)).abs() < 1e-6, "block {b}: {m}");
                assert!((mx - 0.5 * (x0 + x)).abs() < 1e-6, "block {b}: {m}");
                assert_eq!(m["line"].as_u64().unwrap() as usize, line, "block {b}");
            }
        }
    }
    assert!(checked > 10, "{checked}");
    assert_eq!(view.answer("/api/dressing/sample?t=x").0, 400);
}

/// The area under the polyline `c` (`[z, x]`, `z` non-decreasing) above `x = base`.
fn area_under(c: &Value, base: f64) -> f64 {
    let p: Vec<(f64, f64)> = c
        .as_array()
        .unwrap()
        .iter()
        .map(|q| (q[0].as_f64().unwrap(), q[1].as_f64().unwrap()))
        .collect();
    p.windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1 - 2.0 * base))
        .sum()
}

#[test]
fn the_dressing_sends_each_pass_contour_each_blocks_pass_and_both_feeds() {
    let dir = result_as("dress-ballscrew-nut.toml", "dress-contours");
    let view = View::open(&dir, None, Page::default()).unwrap();
    let d = get(&view, "/api/dressing");
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let passes = summary["passes"].as_array().unwrap().len();
    assert_eq!(passes, 2);

    // The contour after each pass, the last one the final contour; each
    // pass removes material, and between the first and the last lies the
    // area the simulation gives.
    let contours = d["contours"].as_array().unwrap();
    assert_eq!(contours.len(), passes);
    assert_eq!(contours[passes - 1], d["final_contour"]);
    let sent: usize = contours.iter().map(|c| c.as_array().unwrap().len()).sum();
    assert_eq!(sent, rows(&dir.join("contour_passes.csv")));
    let base = -10.0;
    let mut areas = vec![area_under(&d["initial"], base)];
    areas.extend(contours.iter().map(|c| area_under(c, base)));
    assert!(areas.windows(2).all(|w| w[1] < w[0]), "{areas:?}");
    let between = summary["area_between_contours_mm2"].as_f64().unwrap();
    let got = areas[0] - areas[passes];
    assert!((got - between).abs() < 1e-6 * between, "{got} vs {between}");

    // Each block's pass: the runs of feed moves, counted from 1, rapid
    // moves with the pass before; each pass's first feed move starts at
    // the pass's first point of `dresser.csv` (to the program's 0.001 mm).
    let block_pass: Vec<u64> = d["block_pass"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_u64().unwrap())
        .collect();
    let t = numbers(&d["t"]);
    assert_eq!(block_pass.len(), t.len() - 1);
    assert!(
        block_pass
            .windows(2)
            .all(|w| w[1] == w[0] || w[1] == w[0] + 1)
    );
    assert_eq!(block_pass[0], 0, "the program starts with a rapid move");
    assert_eq!(*block_pass.last().unwrap() as usize, passes);
    for (p, pass) in d["passes"].as_array().unwrap().iter().enumerate() {
        let first = (0..block_pass.len())
            .find(|&b| block_pass[b] == p as u64 + 1)
            .unwrap();
        assert!(t[first + 1] > t[first], "pass {}: block {first}", p + 1);
        let start = &pass["path"][0];
        let at = &d["points"][first];
        for c in 0..2 {
            let (a, b) = (at[c].as_f64().unwrap(), start[c].as_f64().unwrap());
            assert!((a - b).abs() <= 5e-4, "pass {}: {at} vs {start}", p + 1);
        }
    }

    // With feed control and without: the rate at the constant feed of the
    // same time is each step's area per mm times that feed.
    let m = &d["mrr"];
    let f0 = summary["feed_uncontrolled_mm_min"].as_f64().unwrap();
    assert_eq!(m["feed_uncontrolled"].as_f64(), Some(f0));
    assert_eq!(m["target"].as_f64(), summary["target_mrr_mm2_min"].as_f64());
    let table = formcam_view::Table::read(&dir.join("mrr.csv")).unwrap();
    let per_mm = table.numbers("area_per_mm").unwrap();
    let free = numbers(&m["mrr_uncontrolled"]);
    assert_eq!(free.len(), per_mm.len());
    assert_eq!(numbers(&m["x"]), table.numbers("x").unwrap());
    for (k, (r, a)) in free.iter().zip(&per_mm).enumerate() {
        assert!(
            (r - a * f0).abs() <= 1e-5 + 1e-6 * r.abs(),
            "step {k}: {r} vs {a} * {f0}"
        );
    }
    // Feed control evens the rate out over the steady steps.
    let steady = table.numbers("steady").unwrap();
    let spread = |v: &[f64]| {
        let s: Vec<f64> = v
            .iter()
            .zip(&steady)
            .filter(|(_, s)| **s > 0.5)
            .map(|(r, _)| *r)
            .collect();
        s.iter().copied().fold(0.0, f64::max) / s.iter().copied().fold(f64::INFINITY, f64::min)
    };
    let (with, without) = (spread(&numbers(&m["mrr"])), spread(&free));
    assert!(with < without, "{with} vs {without}");
}

#[test]
fn a_dressing_result_without_the_passes_contours_opens_without_them() {
    let dir = result_as("dress-ballscrew-nut.toml", "dress-with-passes");
    let old = dir.with_file_name("dress-without-passes");
    let _ = std::fs::remove_dir_all(&old);
    std::fs::create_dir_all(&old).unwrap();
    for e in std::fs::read_dir(&dir).unwrap() {
        let e = e.unwrap();
        if e.file_name() != "contour_passes.csv" {
            std::fs::copy(e.path(), old.join(e.file_name())).unwrap();
        }
    }
    let with = get(
        &View::open(&dir, None, Page::default()).unwrap(),
        "/api/dressing",
    );
    let without = get(
        &View::open(&old, None, Page::default()).unwrap(),
        "/api/dressing",
    );
    assert_eq!(without["contours"], serde_json::json!([]));
    for k in [
        "initial",
        "final_contour",
        "block_pass",
        "mrr",
        "t",
        "points",
    ] {
        assert_eq!(with[k], without[k], "{k}");
    }
}

#[test]
fn the_correction_map_holds_every_measured_point() {
    let dir = result("correct-mould.toml");
    let view = View::open(&dir, None, Page::default()).unwrap();
    assert_eq!(view.kind(), ResultKind::Correction);
    let c = get(&view, "/api/correction");
    let cmm = repo().join("examples/correct/cmm.csv");
    let n = rows(&cmm);
    for k in ["x", "y", "z", "deviation", "section"] {
        assert_eq!(c[k].as_array().unwrap().len(), n, "{k}");
    }
    let sections = c["sections"].as_array().unwrap();
    assert_eq!(sections.len(), 9);
    let counted: u64 = sections.iter().map(|s| s["points"].as_u64().unwrap()).sum();
    assert_eq!(counted as usize, n);
    // The largest |deviation| is the report's.
    let worst = numbers(&c["deviation"])
        .iter()
        .fold(0.0f64, |m, d| m.max(d.abs()));
    let reported = c["report"]["max_deviation_mm"].as_f64().unwrap();
    assert!((worst - reported).abs() < 1e-9, "{worst} vs {reported}");
    // The job joined the file to its folder (through
    // `crates/formcam-view/../..` here); the report names it by its
    // absolute path, `..` resolved, found from any folder; the title shows
    // it plain.
    let named = c["report"]["measurements"].as_str().unwrap();
    assert!(Path::new(named).is_absolute(), "{named}");
    assert!(!named.contains("/../"), "{named}");
    assert_eq!(Path::new(named), cmm.canonicalize().unwrap());
    let shown = c["measurements"].as_str().unwrap();
    assert!(
        Path::new(shown).components().all(|p| matches!(
            p,
            std::path::Component::Normal(_) | std::path::Component::RootDir
        )),
        "{shown}"
    );
    assert_eq!(
        Path::new(shown).canonicalize().unwrap(),
        cmm.canonicalize().unwrap()
    );
    assert_eq!(c["rounds"], serde_json::json!([]));
}

/// The least and largest of `v`.
fn range(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        })
}

#[test]
fn the_correction_sends_its_surface_the_part_after_and_every_node() {
    let dir = result("correct-mould.toml");
    let view = View::open(&dir, None, Page::default()).unwrap();
    let c = get(&view, "/api/correction");
    let r = &c["report"];
    // The surface: the grid of the report's sections and points, two
    // triangles per facet, every index a vertex.
    let s = &c["surface"];
    let (nu, nv) = (s["nu"].as_u64().unwrap(), s["nv"].as_u64().unwrap());
    assert_eq!(nv, r["sections"].as_u64().unwrap());
    assert_eq!(nu, r["points_per_section"].as_u64().unwrap());
    let vertices = s["vertices"].as_array().unwrap();
    assert_eq!(vertices.len() as u64, nu * nv);
    let triangles = s["triangles"].as_array().unwrap();
    assert_eq!(triangles.len() as u64, 2 * (nu - 1) * (nv - 1));
    assert!(
        triangles
            .iter()
            .flat_map(numbers)
            .all(|k| k < (nu * nv) as f64)
    );
    // Every vertex a measured point's nominal place, its deviation the
    // measured one: the same range.
    let measured = numbers(&c["deviation"]);
    let at_vertices = numbers(&c["vertex_deviation"]);
    assert_eq!(at_vertices.len(), vertices.len());
    let (lo, hi) = (range(&measured), range(&at_vertices));
    assert!(
        (lo.0 - hi.0).abs() < 1e-9 && (lo.1 - hi.1).abs() < 1e-9,
        "{lo:?} {hi:?}"
    );
    let (x, y) = (numbers(&c["x"]), numbers(&c["y"]));
    for v in vertices {
        let v = numbers(v);
        assert!(
            x.iter()
                .zip(&y)
                .any(|(a, b)| (a - v[0]).abs() < 1e-9 && (b - v[1]).abs() < 1e-9)
        );
    }
    // After: the next part predicted from the corrected program, at the
    // same points, its worst deviation the report's and far below before.
    let after = &c["after"];
    let worst = |v: &Value| numbers(v).iter().fold(0.0f64, |m, d| m.max(d.abs()));
    assert_eq!(numbers(&after["deviation"]).len(), measured.len());
    assert_eq!(after["x"], c["x"]);
    let predicted = r["predicted_max_deviation_mm"].as_f64().unwrap();
    assert!((worst(&after["deviation"]) - predicted).abs() < 1e-9);
    assert!(worst(&after["deviation"]) < 0.25 * worst(&c["deviation"]));
    assert_eq!(numbers(&after["vertex_deviation"]).len(), vertices.len());
    // The nodes: each counted as the report counts them, every one sent.
    let n = &c["nodes"];
    let counts = &n["counts"];
    for (count, key) in [
        ("nodes", "nodes_feed"),
        ("moved", "nodes_corrected"),
        ("extrapolated", "nodes_extrapolated"),
        ("outside", "nodes_outside"),
        ("unknown", "nodes_unknown"),
    ] {
        assert_eq!(counts[count], r[key], "{count}");
    }
    let nodes = counts["nodes"].as_u64().unwrap();
    assert_eq!(n["every"], 1);
    for k in ["x", "y", "z", "placement", "moved"] {
        assert_eq!(n[k].as_array().unwrap().len() as u64, nodes, "{k}");
    }
    let placed = |w: &str| {
        n["placement"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| *p == w)
            .count() as u64
    };
    assert_eq!(
        placed("extrapolated"),
        counts["extrapolated"].as_u64().unwrap()
    );
    assert_eq!(placed("inside"), counts["inside"].as_u64().unwrap());
    assert_eq!(
        counts["inside"].as_u64().unwrap()
            + counts["extrapolated"].as_u64().unwrap()
            + counts["outside"].as_u64().unwrap()
            + counts["unknown"].as_u64().unwrap(),
        nodes
    );
}

#[test]
fn a_closed_loop_opens_as_a_correction_with_the_map_of_every_round() {
    let dir = result("correct-panel-loop.toml");
    let view = View::open(&dir, None, Page::default()).unwrap();
    assert_eq!(view.kind(), ResultKind::Correction);
    assert_eq!(get(&view, "/api/kind")["kind"], "correction");
    let report = get(&view, "/api/result");
    let c = get(&view, "/api/correction");
    assert_eq!(c["report"], report);
    let listed = report["rounds"].as_array().unwrap();
    let rounds = c["rounds"].as_array().unwrap();
    assert_eq!(
        rounds.len() as u64,
        report["iterations"].as_u64().unwrap() + 1
    );
    assert_eq!(rounds.len(), listed.len());
    for (k, (r, l)) in rounds.iter().zip(listed).enumerate() {
        assert_eq!(r["iteration"].as_u64().unwrap() as usize, k);
        assert_eq!(r["measurements"], format!("cmm-{k}.csv"));
        assert_eq!(r["program"], format!("program-{k}.nc"));
        let n = rows(&dir.join(format!("cmm-{k}.csv")));
        for key in ["x", "y", "z", "deviation", "section"] {
            assert_eq!(r[key].as_array().unwrap().len(), n, "round {k}: {key}");
        }
        let sections = r["sections"].as_array().unwrap();
        assert_eq!(sections.len() as u64, report["sections"].as_u64().unwrap());
        // What the CMM saw: the largest |deviation| along the normal, as the
        // report gives it (the CSV's 4 decimals apart).
        let worst = numbers(&r["deviation"])
            .iter()
            .fold(0.0f64, |m, d| m.max(d.abs()));
        let measured = l["measured_max_mm"].as_f64().unwrap();
        assert!(
            (worst - measured).abs() < 2e-4,
            "round {k}: {worst} vs {measured}"
        );
    }
    // The last round is shown first.
    let last = rounds.last().unwrap();
    for key in ["x", "y", "deviation", "sections", "measurements", "program"] {
        assert_eq!(c[key], last[key], "{key}");
    }
    // Correcting shrinks what the CMM sees.
    let worst = |r: &Value| {
        numbers(&r["deviation"])
            .iter()
            .fold(0.0f64, |m, d| m.max(d.abs()))
    };
    assert!(worst(last) < 0.5 * worst(&rounds[0]));
    let scenario = c["scenario"].as_str().unwrap();
    assert!(!scenario.contains("/../"), "{scenario}");
    assert_eq!(
        Path::new(scenario).canonicalize().unwrap(),
        repo()
            .join("examples/correct-panel-loop.toml")
            .canonicalize()
            .unwrap()
    );
    // One nominal surface for every round, each round's deviation on it;
    // no prediction or nodes: the next round is the after.
    let vertices = c["surface"]["vertices"].as_array().unwrap().len();
    assert_eq!(
        vertices as u64,
        report["sections"].as_u64().unwrap() * report["points_per_section"].as_u64().unwrap()
    );
    for r in rounds {
        assert_eq!(numbers(&r["vertex_deviation"]).len(), vertices);
    }
    assert!(
        c["after"].is_null() && c["nodes"].is_null(),
        "{}",
        c["after"]
    );
    assert_eq!(view.answer("/api/dressing").0, 404);
    assert_eq!(view.answer("/api/plots").0, 404);
}

#[test]
fn a_folder_of_results_names_the_ones_to_view() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("view-results/demo");
    let _ = std::fs::remove_dir_all(&dir);
    for (sub, file) in [("wound", "summary.json"), ("corrected", "report.json")] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
        std::fs::write(dir.join(sub).join(file), "{}").unwrap();
    }
    std::fs::create_dir_all(dir.join("inputs")).unwrap();
    let e = View::open(&dir, None, Page::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a result folder"), "{e}");
    assert!(e.contains("corrected, wound"), "{e}");
    assert!(!e.contains("inputs"), "{e}");
}

#[test]
fn a_folder_without_summary_or_correction_report_is_no_result() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("view-results/empty");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let e = View::open(&dir, None, Page::default()).unwrap_err();
    assert!(e.to_string().contains("not a result folder"), "{e}");
}

#[test]
fn a_winding_result_without_a_program_opens_as_its_path() {
    let dir = result("tube-helical.toml");
    assert!(!dir.join("program.gcode").exists());
    let view = View::open(&dir, None, Page::default()).unwrap();
    assert_eq!(view.kind(), ResultKind::Path);
    assert_eq!(get(&view, "/api/kind")["kind"], "path");
    let summary = get(&view, "/api/result");
    let circuits = summary["circuits"].as_u64().unwrap() as usize;
    let rows = rows(&dir.join("path.csv"));
    // No machine: one bare link carries the mandrel.
    let machine = get(&view, "/api/machine");
    assert_eq!(machine["links"].as_array().unwrap().len(), 1);
    assert_eq!(machine["mandrel"], 0);
    let mandrel = get(&view, "/api/mandrel");
    assert_eq!(mandrel["path_points"], rows);
    let body = get(&view, "/api/path");
    assert_eq!(body["pose"], "none");
    assert!(body["eye"].is_null());
    let band = &body["band"];
    assert_eq!(band["circuits"], circuits);
    assert_eq!(band["table_points"], rows);
    let layers = numbers(&band["layers"]);
    let points = band["points"].as_array().unwrap();
    assert_eq!(layers.len(), circuits);
    assert!(points.len() <= formcam_view::BAND_POINTS);
    // Each circuit is the first turned by its share of a turn, on the
    // radius of the path.
    let per = points.len() / circuits;
    assert_eq!(per * circuits, points.len());
    let (p0, pk) = (numbers(&points[1]), numbers(&points[per + 1]));
    let turn = std::f64::consts::TAU / circuits as f64;
    let (r0, rk) = (p0[0].hypot(p0[1]), pk[0].hypot(pk[1]));
    assert!((r0 - rk).abs() < 1e-9 && (p0[2] - pk[2]).abs() < 1e-9);
    let d = (pk[1].atan2(pk[0]) - p0[1].atan2(p0[0]) - turn).rem_euclid(std::f64::consts::TAU);
    assert!(d.min(std::f64::consts::TAU - d) < 1e-9, "{d}");
    let plots = get(&view, "/api/plots");
    assert_eq!(plots["meridian"][0]["z"].as_array().unwrap().len(), rows);
    assert!(plots["axes"].is_null());
    let none = get(&view, "/api/overlays");
    assert_eq!(
        (none["violations"].as_bool(), none["band"].as_bool()),
        (Some(false), Some(false))
    );
    for url in [
        "/api/program",
        "/api/timeline",
        "/api/sample?t=0",
        "/api/blocks",
        "/api/band",
        "/api/eye",
    ] {
        assert_eq!(view.answer(url).0, 404, "{url}");
    }
}

#[test]
fn a_path_with_an_eye_and_a_machine_shows_both() {
    let dir = result("vessel-axes-4axis.toml");
    let view = View::open(&dir, None, Page::default()).unwrap();
    assert_eq!(view.kind(), ResultKind::Path);
    let machine = get(&view, "/api/machine");
    let links = machine["links"].as_array().unwrap().len();
    assert!(links > 1, "{machine}");
    let body = get(&view, "/api/path");
    assert_eq!(body["pose"], "axes.csv row 1");
    assert_eq!(body["poses"].as_array().unwrap().len(), links);
    assert_eq!(body["band"]["link"], machine["mandrel"]);
    assert_eq!(
        body["eye"].as_array().unwrap().len(),
        rows(&dir.join("eye.csv"))
    );
    let plots = get(&view, "/api/plots");
    assert_eq!(
        plots["pull"][0]["u"].as_array().unwrap().len(),
        rows(&dir.join("eye.csv"))
    );
}
