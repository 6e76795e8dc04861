//! Collisions on shipped machines: a solid enlarged so that a known block
//! collides, found at that block and line in two dialects with the depth of
//! the overlap; the exemptions; the mandrel against the payout eye with too
//! small a clearance; every bundled winding program clean.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_machine::Machine;
use formcam_machine::shipped::shipped;
use formcam_nc::{Block, Dialect, Feed, Program, write};
use formcam_program::{Stage, WindJob, plan_until, write_program};
use formcam_sim::{
    Collisions, FeedRule, Laminate, Timeline, Violation, ViolationKind, check_text_in,
    program_axes, read_program,
};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The shipped chuck (its face 300 mm from the mandrel's origin) moved
/// to x from -400 to -200, where these tests' programs reach it.
const TEST_CHUCK: (&str, &str) = (
    "origin = { xyz = [0.0, 0.0, -400.0] }",
    "origin = { xyz = [0.0, 0.0, -300.0] }",
);

/// The 4-axis winder's text with its chuck at [`TEST_CHUCK`] and `edit`
/// applied (`from` must be in it).
fn winder(edits: &[(&str, &str)]) -> Machine {
    let mut text = shipped("winder-4axis").unwrap().text.to_string();
    text = text.replacen(TEST_CHUCK.0, TEST_CHUCK.1, 1);
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    Machine::from_toml(&text).unwrap()
}

/// The spindle's chuck (a cylinder of radius 120 about the spindle axis,
/// x from -400 to -200) widened to radius 200.
const WIDE_CHUCK: (&str, &str) = ("radius = 120.0", "radius = 200.0");

/// X from 0 down to -200 mm in 10 blocks of 20 mm, 0.5 s each, the cross
/// feed at Y = 140: the eye's roller (radius 12, x within X ± 40) from
/// y = 128 and the cross's box (x within X ± 60) from y = 170, both above
/// the shipped chuck (radius 120) by more than the margin, both inside the
/// wide one (radius 200).
fn towards_the_chuck(m: &Machine) -> Program {
    let mut p = Program::new("CHUCK", program_axes(m));
    p.blocks.push(Block::rapid(vec![0.0, 0.0, 140.0, 0.0]));
    for k in 1..=10 {
        let x = -20.0 * k as f64;
        p.blocks.push(Block::linear(
            vec![0.0, x, 140.0, 0.0],
            Feed::InverseTime(0.5),
        ));
    }
    p
}

/// The first block (1-based) of `towards_the_chuck` that brings a solid
/// reaching `reach` mm past X towards the chuck's end face (x = -200)
/// within the margin: the block that moves X past `-200 + reach + margin`.
fn first_block(reach: f64, margin: f64) -> usize {
    1 + ((200.0 - reach - margin) / 20.0).ceil() as usize
}

fn collisions(v: &[Violation]) -> Vec<&Violation> {
    v.iter()
        .filter(|v| v.kind == ViolationKind::Collision)
        .collect()
}

/// The program written in `dialect` and checked on `m`, and its timeline.
fn check(p: &Program, dialect: Dialect, m: &Machine) -> (Vec<Violation>, Timeline) {
    let mut text = String::new();
    write(p, dialect, &mut text).unwrap();
    let path = PathBuf::from(format!("program.{}", dialect.extension()));
    let (read, lines, _) = read_program(&path, &text, m).unwrap();
    let tl = Timeline::new(&read, &lines, FeedRule::of(dialect), m).unwrap();
    let r = check_text_in(&path, &text, m, "test", None, None).unwrap();
    (r.violations, tl)
}

#[test]
fn an_enlarged_chuck_is_hit_at_the_right_block_in_two_dialects() {
    let shipped = winder(&[]);
    let wide = winder(&[WIDE_CHUCK]);
    let p = towards_the_chuck(&wide);
    let margin = wide.collision.margin;
    for dialect in [Dialect::Iso, Dialect::Sinumerik840d] {
        let (v, _) = check(&p, dialect, &shipped);
        assert_eq!(collisions(&v), Vec::<&Violation>::new(), "{dialect:?}");
        let (v, tl) = check(&p, dialect, &wide);
        let c = collisions(&v);
        assert_eq!(c.len(), 2, "{dialect:?}: {c:?}");
        // The cross's box first (60 mm past X), then the eye (40 mm): each
        // in the block that moves X past -200 + reach + margin (the 8th:
        // X from -120 to -140; the 9th: -140 to -160).
        for (c, links, reach, worst, deepest_from) in [
            // The box 30 mm into the chuck along y (from 170 to 200) and
            // along x from X = -170 on (blocks 10 and 11).
            (c[0], ["spindle", "cross"], 60.0, -30.0, 10),
            // The roller 40 mm into it along x at X = -200, 72 radially.
            (c[1], ["spindle", "eye"], 40.0, -40.0, 11),
        ] {
            assert_eq!(c.links, links, "{dialect:?}");
            let block = first_block(reach, margin);
            assert_eq!(c.block, block, "{dialect:?} {links:?}");
            let span = tl.block(block - 1).unwrap();
            assert_eq!(c.line, span.line, "{dialect:?}");
            assert!(
                c.time_s > span.start_s && c.time_s <= span.start_s + span.duration_s,
                "{c:?}"
            );
            // Sampled every half margin at most: the first sample past the
            // margin lies within 2.5 mm of it.
            assert!(c.value < margin && c.value >= margin - 2.5 - 1e-9, "{c:?}");
            assert!(c.worst_block >= deepest_from, "{c:?}");
            assert!((c.worst_value - worst).abs() < 1e-6, "{c:?}");
            assert_eq!(c.count, 11 - block + 1);
        }
        // The verdict leads with the deepest overlap, then how often and
        // from where.
        assert_eq!(
            c[0].to_string(),
            format!(
                "collision at block {} (line {}, {:.3} s): spindle and cross overlap by 30 mm \
                 (margin 5 mm); broken 4 times from block 8 (line {})",
                c[0].worst_block, c[0].worst_line, c[0].worst_time_s, c[0].line
            )
        );
    }
}

/// A block as an OBJ mesh: 8 vertices, 6 quads.
fn box_obj(min: [f64; 3], max: [f64; 3]) -> String {
    let mut s = String::from("# a box\n");
    for k in 0..8 {
        let c = |i: usize| if k >> i & 1 == 1 { max[i] } else { min[i] };
        s += &format!("v {} {} {}\n", c(0), c(1), c(2));
    }
    for f in [
        "1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6",
    ] {
        s += &format!("f {f}\n");
    }
    s
}

#[test]
fn a_mesh_chuck_is_hit_like_the_solid_one() {
    let dir = std::env::temp_dir().join(format!("formcam-sim-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // In the spindle's frame (z along world x, x along world -z): the chuck
    // as a block from z = -400 to -200, 200 mm each side of the axis.
    std::fs::write(
        dir.join("chuck.obj"),
        box_obj([-200.0, -200.0, -400.0], [200.0, 200.0, -200.0]),
    )
    .unwrap();
    let m = winder(&[(
        "shape = \"cylinder\"\nradius = 120.0\nlength = 200.0\norigin = { xyz = [0.0, 0.0, -300.0] }",
        "shape = \"mesh\"\nfile = \"chuck.obj\"",
    )]);
    let p = towards_the_chuck(&m);
    let mut text = String::new();
    write(&p, Dialect::LinuxCnc, &mut text).unwrap();
    let path = Path::new("program.ngc");
    let r = check_text_in(path, &text, &m, "test", Some(&dir), None).unwrap();
    let c = collisions(&r.violations);
    // As the wide cylinder's: the same faces meet.
    let found: Vec<_> = c.iter().map(|c| (c.block, c.worst_value.round())).collect();
    assert_eq!(found, [(8, -30.0), (9, -40.0)], "{c:?}");
    // A mesh that is not there names its file.
    let e = check_text_in(path, &text, &m, "test", Some(&dir.join("none")), None).unwrap_err();
    assert!(e.to_string().contains("chuck.obj"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn adjacent_links_and_ignored_pairs_are_exempt() {
    let shipped = winder(&[]);
    let c = Collisions::new(&shipped, None).unwrap();
    let names = |i: usize| c.bodies()[i].name.as_str();
    let pairs: Vec<(&str, &str)> = c.pairs().iter().map(|p| (names(p.a), names(p.b))).collect();
    // Joined directly: bed-spindle, bed-carriage, carriage-cross, cross-eye.
    for (a, b) in [
        ("bed", "spindle"),
        ("bed", "carriage"),
        ("carriage", "cross"),
        ("cross", "eye"),
    ] {
        assert!(
            !pairs.contains(&(a, b)) && !pairs.contains(&(b, a)),
            "{a}-{b}: {pairs:?}"
        );
    }
    assert!(pairs.contains(&("spindle", "cross")), "{pairs:?}");
    assert!(pairs.contains(&("bed", "eye")), "{pairs:?}");
    // The cross's box grown into the carriage's: its parent, no collision.
    let deep = winder(&[(
        "size = [120.0, 700.0, 80.0]",
        "size = [120.0, 700.0, 900.0]",
    )]);
    let p = towards_the_chuck(&deep);
    let (v, _) = check(&p, Dialect::Iso, &deep);
    assert_eq!(collisions(&v), Vec::<&Violation>::new());
    // The wide chuck with the cross's pair ignored: the eye's stays.
    let ignored = winder(&[
        WIDE_CHUCK,
        (
            "[[point]]\nname = \"payout\"",
            "[collision]\nignore = [[\"cross\", \"spindle\"]]\n\n[[point]]\nname = \"payout\"",
        ),
    ]);
    let (v, _) = check(&p, Dialect::Iso, &ignored);
    let links: Vec<_> = collisions(&v).iter().map(|c| c.links.clone()).collect();
    assert_eq!(links, [["spindle", "eye"]]);
}

/// A winding job's program and its laminate.
fn wound(job_text: &str, base: &Path) -> (String, Laminate, WindJob) {
    let job = WindJob::from_toml(job_text, base).unwrap();
    let planned = plan_until(&job, Stage::Program).unwrap();
    let mut out = Vec::new();
    write_program(&planned, &mut out).unwrap();
    let laminate = formcam_program::laminate(&job, &planned.layers).unwrap();
    (String::from_utf8(out).unwrap(), laminate, job)
}

#[test]
fn the_eye_too_close_to_the_mandrel_is_found() {
    let m = winder(&[]);
    let base = repo().join("examples");
    let text = std::fs::read_to_string(base.join("tube-layers-4axis.toml")).unwrap();
    // The first (hoop) layer alone.
    let one = text
        .split("\n[[layer]]\nkind = \"helical\"")
        .next()
        .unwrap()
        .to_string()
        + &text[text.find("\n[eye]").unwrap()..];
    for (clearance, clean) in [("20.0", true), ("6.0", false)] {
        let job = one.replace("clearance = 20.0", &format!("clearance = {clearance}"));
        let (program, laminate, _) = wound(&job, &base);
        let path = Path::new("program.ngc");
        let r = check_text_in(path, &program, &m, "test", None, Some(&laminate)).unwrap();
        let c = collisions(&r.violations);
        if clean {
            assert_eq!(c, Vec::<&Violation>::new());
            continue;
        }
        assert_eq!(c.len(), 1, "{c:?}");
        let c = c[0];
        assert_eq!(c.links, ["eye", "mandrel"]);
        // The eye (a roller of radius 12 about the payout point, its axis
        // square to the cross feed) stands Y - 12 from the spindle axis; the
        // mandrel's solid reaches 75 mm plus the hoop layer.
        let t = laminate.thickness[0];
        let reach = 75.0 + t;
        let (p, lines, _) = read_program(path, &program, &m).unwrap();
        let tl = Timeline::new(&p, &lines, FeedRule::LinuxCnc, &m).unwrap();
        let y = m.axis("Y").unwrap();
        let first = tl
            .blocks()
            .find(|b| b.to[y] - 12.0 - reach < m.collision.margin)
            .unwrap();
        assert_eq!(c.block, first.index + 1);
        assert_eq!(c.line, first.line);
        // The deepest overlap: 6 - 12 - t, the solid's polygon a little
        // wider than the circle.
        let want = 6.0 - 12.0 - t;
        assert!(
            c.worst_value <= want && c.worst_value > want - 0.2,
            "{c:?} vs {want}"
        );
    }
}

#[test]
fn every_bundled_winding_program_is_clean_of_collisions() {
    let base = repo().join("examples");
    let mut checked = Vec::new();
    let mut names: Vec<PathBuf> = std::fs::read_dir(&base)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    for path in names {
        let text = std::fs::read_to_string(&path).unwrap();
        let Ok(job) = WindJob::from_toml(&text, &base) else {
            continue;
        };
        if job.furthest_stage() != Stage::Program {
            continue;
        }
        let (program, laminate, job) = wound(&text, &base);
        let m = job.machine.as_ref().unwrap().machine.clone();
        let file = PathBuf::from(format!("program.{}", job.post().extension()));
        let r = check_text_in(&file, &program, &m, "demo", None, Some(&laminate)).unwrap();
        let c = collisions(&r.violations);
        // The 840D vessels' pull-speed eye turns round past the poles, to
        // X = -144.6: the chuck of the shipped machine (its face at x =
        // -300) leaves the cross's bar (X - 60) room.
        assert_eq!(c, Vec::<&Violation>::new(), "{}", path.display());
        checked.push(path);
    }
    assert!(checked.len() >= 4, "{checked:?}");
}

/// Every layer's label is found again in the program as each dialect
/// writes it (LinuxCNC and ISO write `layer 2 [hoop]`, their comments being
/// in parentheses), so each block is checked against the laminate of its
/// own layer, in every dialect.
#[test]
fn each_layer_is_found_in_every_dialect() {
    let base = repo().join("examples");
    let text = std::fs::read_to_string(base.join("tube-layers-4axis.toml")).unwrap();
    for dialect in Dialect::ALL {
        let job = text.replace(
            "dialect = \"linuxcnc\"",
            &format!("dialect = \"{}\"", dialect.name()),
        );
        let (program, laminate, job) = wound(&job, &base);
        let m = job.machine.as_ref().unwrap().machine.clone();
        let path = PathBuf::from(format!("program.{}", dialect.extension()));
        let (p, _, read_as) = read_program(&path, &program, &m).unwrap();
        assert_eq!(read_as, dialect);
        let mut stages =
            laminate.stage_of_blocks(dialect, p.blocks.iter().map(|b| b.comment.as_deref()));
        // The stages rise through every layer in order, each starting once.
        stages.dedup();
        let every: Vec<usize> = (0..laminate.labels.len()).collect();
        assert_eq!(stages, every, "{dialect}: {:?}", laminate.labels);
    }
}

/// A solid exactly at the margin passes, whatever the rounding of the
/// distance query; a hundredth of a millimetre closer is a collision, told
/// by its worst value.
#[test]
fn a_solid_at_the_margin_passes_and_one_closer_is_told_by_its_worst() {
    let m = winder(&[]);
    let margin = m.collision.margin;
    // The eye's roller (radius 12) over the chuck (radius 120) at Y: Y - 132
    // mm apart.
    let at = |y: f64| {
        let mut p = towards_the_chuck(&m);
        for b in &mut p.blocks {
            b.target[2] = y;
        }
        check(&p, Dialect::Iso, &m).0
    };
    assert_eq!(collisions(&at(132.0 + margin)), Vec::<&Violation>::new());
    let v = at(132.0 + margin - 0.01);
    let c = collisions(&v);
    assert_eq!(c.len(), 1, "{c:?}");
    assert!(
        (c[0].worst_value - (margin - 0.01)).abs() < 1e-6,
        "{:?}",
        c[0]
    );
    let text = c[0].to_string();
    assert!(
        text.starts_with(&format!(
            "collision at block {} (line {}",
            c[0].worst_block, c[0].worst_line
        )),
        "{text}"
    );
}
