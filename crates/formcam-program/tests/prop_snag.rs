//! The snag check's bounds and its parallel runs change nothing: a helical
//! vessel program on the shipped 4-axis winder, with a ball or a block put
//! on the bed at random where the free fibre sweeps and random margins,
//! [`check_snag`] finds what measuring every solid exactly at every sample
//! in one pass finds ([`check_snag_exhaustive`]): the same obstacles,
//! blocks, lines and times, the same clearances.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use std::sync::OnceLock;

use formcam_machine::Machine;
use formcam_machine::shipped::shipped;
use formcam_program::{Stage, WindJob, plan_until, write_program};
use formcam_sim::{
    FeedRule, FreeFibre, SnagOptions, Timeline, Violation, check_snag, check_snag_exhaustive,
    read_program,
};
use proptest::prelude::*;

/// One geodesic helical layer on a vessel, its program read back and its
/// fibre.
fn wound() -> &'static (Timeline, FreeFibre) {
    static W: OnceLock<(Timeline, FreeFibre)> = OnceLock::new();
    W.get_or_init(|| {
        let text = "[mandrel]\nkind = \"vessel\"\nradius = 100.0\ncylinder_length = 150.0\n\
             dome = \"hemisphere\"\npolar_opening = 30.0\n\n\
             [[layer]]\nband_width = 10.0\nband_thickness = 0.5\n\n\
             [eye]\nmode = \"axis-parallel\"\nradius = 160.0\nclearance = 20.0\nl_max = 600.0\n\n\
             [machine]\nname = \"winder-4axis\"\n\n\
             [motion]\ntolerance_mm = 0.2\ntolerance_deg = 0.2\n\n\
             [checks]\nallow = [\"slack\", \"clearance\", \"l_max\", \"reverse-rotation\"]\n\n\
             [post]\ndialect = \"sinumerik-840d\"\n";
        let job = WindJob::from_toml(text, Path::new(".")).unwrap();
        let wound = plan_until(&job, Stage::Program).unwrap();
        let mut bytes = Vec::new();
        write_program(&wound, &mut bytes).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let m = wound.machine.clone().unwrap();
        let (p, lines, d) = read_program(Path::new("program.mpf"), &text, &m).unwrap();
        let tl = Timeline::new(&p, &lines, FeedRule::of(d), &m).unwrap();
        (tl, formcam_program::free_fibre(&wound).unwrap())
    })
}

/// The shipped winder with `solid` (a `[[link.visual]]` body) on its bed.
fn with_solid(solid: &str) -> Machine {
    let text = shipped("winder-4axis").unwrap().text.to_string();
    let bed = "color = \"#5b6470\"\n";
    assert!(text.contains(bed));
    let text = text.replacen(bed, &format!("{bed}[[link.visual]]\n{solid}\n"), 1);
    Machine::from_toml(&text).unwrap()
}

/// A finding compared exactly: obstacle, block, line, time (bits), blocks,
/// worst block, limit (bits).
type Key = (String, usize, usize, u64, usize, usize, u64);

/// The findings in a form compared exactly (the clearances apart).
fn key(v: &[Violation]) -> Vec<Key> {
    v.iter()
        .map(|v| {
            (
                v.axis.clone(),
                v.block,
                v.line,
                v.time_s.to_bits(),
                v.count,
                v.worst_block,
                v.limit.to_bits(),
            )
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn the_bounds_find_what_every_exact_distance_finds(
        ball in proptest::bool::ANY,
        size in 5.0f64..60.0,
        x in -350.0f64..700.0,
        y in 40.0f64..260.0,
        z in 880.0f64..1120.0,
        solid_margin in 1.0f64..30.0,
        mandrel_margin in 0.2f64..3.0,
        sample_mm in 0.5f64..4.0,
        points in 8usize..64,
    ) {
        let (tl, fibre) = wound();
        // Several of the check's runs of blocks, merged.
        prop_assert!(tl.len() > 1500, "{} blocks", tl.len());
        let shape = if ball {
            format!("shape = \"sphere\"\nradius = {size}")
        } else {
            format!("shape = \"box\"\nsize = [{size}, {}, {}]", 0.5 * size, 2.0 * size)
        };
        let m = with_solid(&format!("{shape}\norigin = {{ xyz = [{x}, {y}, {z}] }}"));
        let fibre = fibre.clone().with_machine(m).unwrap();
        let opts = SnagOptions {
            solid_margin_mm: solid_margin,
            mandrel_margin_mm: mandrel_margin,
            sample_mm,
            points_per_fibre: points,
            ..SnagOptions::default()
        };
        let fast = check_snag(tl, &fibre, &opts).unwrap();
        let every = check_snag_exhaustive(tl, &fibre, &opts).unwrap();
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
