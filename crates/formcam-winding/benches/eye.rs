//! Speed of the payout-eye trajectory: geometric modes on a 1e5-point circuit and
//! the pull-speed optimisation with 2000 unknowns.

#![allow(clippy::expect_used, missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_geom::{DomeShape, Vessel};
use formcam_winding::eye::{EyeMode, EyeSpec, eye_trajectory};
use formcam_winding::{Ends, LayerSpec, Slippage, plan_layer};

fn benches(c: &mut Criterion) {
    let v = Vessel::new(
        100.0,
        300.0,
        (DomeShape::Hemisphere, 30.0),
        (DomeShape::Hemisphere, 30.0),
    )
    .expect("vessel");
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Poles {
            start: 30.0,
            end: 30.0,
        },
        ..LayerSpec::default()
    };
    let layer = plan_layer(&v, &spec).expect("layer");
    for mode in [EyeMode::AxisParallel, EyeMode::Equidistant] {
        let eye = EyeSpec {
            mode,
            radius: Some(160.0),
            l_max: 400.0,
            samples: 100_001,
            ..EyeSpec::default()
        };
        c.bench_function(&format!("eye {mode:?}, 1e5-point circuit"), |b| {
            b.iter(|| black_box(eye_trajectory(&v, &layer, &eye).expect("eye")))
        });
    }
    for fixed in [false, true] {
        let eye = EyeSpec {
            mode: EyeMode::PullSpeed,
            radius: Some(160.0),
            l_max: 400.0,
            nodes: 2000,
            bath_moves_with_eye: !fixed,
            ..EyeSpec::default()
        };
        let name = if fixed {
            "fixed bath (SLP)"
        } else {
            "bath with the eye"
        };
        c.bench_function(&format!("pull-speed optimum, 2000 unknowns, {name}"), |b| {
            b.iter(|| black_box(eye_trajectory(&v, &layer, &eye).expect("eye")))
        });
    }
}

criterion_group!(name = g; config = Criterion::default().sample_size(10); targets = benches);
criterion_main!(g);
