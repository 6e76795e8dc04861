//! The collision check's bounds change nothing: on random programs for the
//! shipped 4-axis winder, with its chuck widened, a block on the bed in the
//! eye's way and a vessel mandrel of two layers, [`Collisions::check`]
//! finds what measuring every pair exactly at every sample finds
//! ([`Collisions::check_exhaustive`]): the same pairs, blocks, lines and
//! times, and the same distances.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::sync::OnceLock;

use formcam_geom::{DomeShape, Vessel};
use formcam_machine::Machine;
use formcam_machine::shipped::shipped;
use formcam_nc::{Block, Feed, Program};
use formcam_sim::{
    Collisions, FeedRule, Laminate, Timeline, Violation, program_axes, revolution_solid,
};
use proptest::prelude::*;

/// The winder with its chuck widened to radius 200 and a 120 mm block on
/// the bed where the eye and the cross feed pass (x = 800, 300 mm from the
/// spindle axis towards the carriage, at its height).
fn machine() -> &'static Machine {
    static M: OnceLock<Machine> = OnceLock::new();
    M.get_or_init(|| {
        let text = shipped("winder-4axis").unwrap().text.to_string();
        let text = text.replacen("radius = 120.0", "radius = 200.0", 1);
        let bed = "color = \"#5b6470\"\n";
        assert!(text.contains(bed));
        let text = text.replacen(
            bed,
            "color = \"#5b6470\"\n[[link.visual]]\nshape = \"box\"\n\
             size = [120.0, 120.0, 120.0]\norigin = { xyz = [800.0, 300.0, 1000.0] }\n",
            1,
        );
        Machine::from_toml(&text).unwrap()
    })
}

/// A vessel mandrel (radius 100, 300 mm of cylinder, hemispheres), bare
/// and grown by 8 mm.
fn laminate() -> &'static Laminate {
    static L: OnceLock<Laminate> = OnceLock::new();
    L.get_or_init(|| {
        let solid = |r: f64| {
            let v = Vessel::new(
                r,
                300.0,
                (DomeShape::Hemisphere, 30.0),
                (DomeShape::Hemisphere, 30.0),
            )
            .unwrap();
            revolution_solid(&v).unwrap()
        };
        Laminate {
            labels: vec!["layer 1".into(), "layer 2".into()],
            solids: vec![solid(100.0), solid(108.0)],
            thickness: vec![0.0, 8.0],
        }
    })
}

/// One block: rapid or not, its time (inverse-time feed), and the axes
/// X, Y, B and the spindle's turn.
type Move = (bool, f64, f64, f64, f64, f64);

fn program(m: &Machine, moves: &[Move]) -> Program {
    let mut p = Program::new("PROP", program_axes(m));
    let (x, y, a, b) = (
        m.axis("X").unwrap(),
        m.axis("Y").unwrap(),
        m.axis("A").unwrap(),
        m.axis("B").unwrap(),
    );
    let mut spindle = 0.0;
    for &(rapid, seconds, xv, yv, bv, turn) in moves {
        spindle += turn;
        let mut target = vec![0.0; p.axes.len()];
        target[x] = xv;
        target[y] = yv;
        target[a] = spindle;
        target[b] = bv;
        p.blocks.push(if rapid {
            Block::rapid(target)
        } else {
            Block::linear(target, Feed::InverseTime(seconds))
        });
    }
    p
}

/// A finding compared exactly: kind, links, block, line, time (bits),
/// blocks, worst block.
type Key = (String, Vec<String>, usize, usize, u64, usize, usize);

/// The findings in a form compared exactly (the distances apart).
fn key(v: &[Violation]) -> Vec<Key> {
    v.iter()
        .map(|v| {
            (
                v.kind.name().to_string(),
                v.links.clone(),
                v.block,
                v.line,
                v.time_s.to_bits(),
                v.count,
                v.worst_block,
            )
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn the_bounds_find_what_every_exact_distance_finds(
        moves in proptest::collection::vec(
            (
                proptest::bool::weighted(0.15),
                0.05f64..1.5,
                -420.0f64..900.0,
                40.0f64..420.0,
                -120.0f64..120.0,
                -200.0f64..200.0,
            ),
            2..14,
        ),
        stages in proptest::collection::vec(0usize..2, 14),
    ) {
        let m = machine();
        let p = program(m, &moves);
        let lines: Vec<usize> = (1..=p.blocks.len()).collect();
        let tl = Timeline::new(&p, &lines, FeedRule::Iso, m).unwrap();
        let stages = stages[..p.blocks.len()].to_vec();
        let c = Collisions::with_mandrel(m, None, laminate(), stages).unwrap();
        let fast = c.check(&tl, m);
        let every = c.check_exhaustive(&tl, m);
        prop_assert_eq!(key(&fast), key(&every));
        for (f, e) in fast.iter().zip(&every) {
            prop_assert!((f.value - e.value).abs() <= 1e-9, "{} vs {}", f.value, e.value);
            prop_assert!(
                (f.worst_value - e.worst_value).abs() <= 1e-9,
                "{} vs {}",
                f.worst_value,
                e.worst_value
            );
        }
    }
}
