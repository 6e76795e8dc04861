//! The per-point work of a 1e5-point circuit: the targets, the inverse
//! kinematics on the 4-axis winder (closed form) and the 6-axis winder
//! (Levenberg–Marquardt), the band past the band path's key points.

#![allow(clippy::expect_used, missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_geom::{DomeShape, Vessel};
use formcam_machine::{IkMethod, solve};
use formcam_machine::{Machine, band_passed};
use formcam_program::winder_targets;
use formcam_winding::eye::{EyeMode, EyeSpec, eye_trajectory};
use formcam_winding::{Ends, LayerSpec, Slippage, plan_layer};

fn machine(name: &str) -> Machine {
    Machine::from_toml(&formcam_testkit::machine_text(name)).expect("machine")
}

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
    let eye = EyeSpec {
        mode: EyeMode::AxisParallel,
        radius: Some(160.0),
        l_max: 600.0,
        samples: 100_001,
        ..EyeSpec::default()
    };
    let t = eye_trajectory(&v, &layer, &eye).expect("eye");
    let targets = winder_targets(&v, &t);
    c.bench_function("targets, 1e5-point circuit", |b| {
        b.iter(|| black_box(winder_targets(&v, black_box(&t))))
    });
    for (name, method) in [
        ("winder-4axis.toml", IkMethod::Auto),
        ("winder-4axis.toml", IkMethod::Solver),
        ("winder-6axis.toml", IkMethod::Auto),
    ] {
        let m = machine(name);
        c.bench_function(&format!("IK {name} {method:?}, 1e5-point circuit"), |b| {
            b.iter(|| black_box(solve(&m, &targets, method).expect("ik")))
        });
    }
    let m = machine("winder-4axis.toml");
    let track = solve(&m, &targets, IkMethod::Auto).expect("ik");
    c.bench_function("band passed winder-4axis.toml, 1e5-point circuit", |b| {
        b.iter(|| black_box(band_passed(&m, &targets, &track)))
    });
}

criterion_group!(name = g; config = Criterion::default().sample_size(10); targets = benches);
criterion_main!(g);
