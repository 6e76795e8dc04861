#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::needless_range_loop,
    missing_docs
)]
//! The correction against analytic cases.

use formcam_correct::{Corrector, Grid, Interpolation, Options, Placement, Tool, Totals};

const KINDS: [Interpolation; 2] = [Interpolation::Bilinear, Interpolation::Bicubic];

/// A grid over `z = f(x, y)`: `nv` sections at `y = j * dy`, `nu` points at
/// `x = i * dx`, with deviation `dev(x, y)`.
fn grid(
    nu: usize,
    nv: usize,
    (dx, dy): (f64, f64),
    f: impl Fn(f64, f64) -> f64,
    dev: impl Fn(f64, f64) -> [f64; 3],
) -> Grid {
    let mut nominal = Vec::new();
    let mut deviation = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (x, y) = (i as f64 * dx, j as f64 * dy);
            nominal.push([x, y, f(x, y)]);
            deviation.push(dev(x, y));
        }
    }
    Grid {
        nu,
        nv,
        nominal,
        deviation,
        normal: None,
        resampled: false,
        reordered: false,
    }
}

fn nodes(f: &dyn Fn(f64, f64) -> f64, x_max: f64, y_max: f64, n: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for a in 0..n {
        for b in 0..n {
            // Irrational-ish fractions so nodes fall inside facets and on edges.
            let x = x_max * (a as f64 + 0.37) / n as f64;
            let y = y_max * (b as f64 + 0.61) / n as f64;
            out.push([x, y, f(x, y)]);
        }
    }
    out
}

#[test]
fn a_constant_offset_is_removed_exactly() {
    let f = |x: f64, y: f64| 20.0 * (x / 80.0).sin() + 0.002 * y * y;
    let c = [0.05, -0.1, 0.4];
    let g = grid(9, 7, (10.0, 12.0), f, |_, _| c);
    for kind in KINDS {
        let corr = Corrector::new(
            &g,
            Options {
                interpolation: kind,
                ..Options::default()
            },
        )
        .unwrap();
        for p in nodes(&f, 80.0, 72.0, 23) {
            let n = corr.correct_node(p);
            assert_eq!(n.placement, Placement::Inside);
            for k in 0..3 {
                assert!(
                    (n.displacement[k] + c[k]).abs() < 1e-12,
                    "{kind:?} {p:?}: {n:?}"
                );
            }
        }
    }
}

#[test]
fn a_bilinear_warp_is_removed_exactly() {
    // A plane grid: (s, t) maps linearly to (x, y), so a warp bilinear in x
    // and y is bilinear in (s, t) on every facet.
    let f = |x: f64, y: f64| 0.3 * x - 0.2 * y + 5.0;
    let warp = |x: f64, y: f64| {
        [
            0.01 + 0.001 * x,
            -0.02 + 0.0005 * y,
            0.4 - 0.003 * x + 0.002 * y + 0.00004 * x * y,
        ]
    };
    let g = grid(6, 5, (16.0, 18.0), f, warp);
    for kind in KINDS {
        let corr = Corrector::new(
            &g,
            Options {
                interpolation: kind,
                gain: 1.0,
                ..Options::default()
            },
        )
        .unwrap();
        for p in nodes(&f, 80.0, 72.0, 17) {
            let n = corr.correct_node(p);
            let w = warp(p[0], p[1]);
            for k in 0..3 {
                assert!(
                    (n.displacement[k] + w[k]).abs() < 1e-12,
                    "{kind:?} {p:?}: {:?} vs {w:?}",
                    n.displacement
                );
            }
        }
    }
}

#[test]
fn the_foot_is_the_nearest_point_of_the_whole_surface() {
    // A doubly curved grid with nodes off the surface on both sides: the
    // foot found by the k-d tree and the walk against a search over every
    // facet.
    let f = |x: f64, y: f64| 30.0 * (x / 50.0).sin() * (y / 70.0).cos();
    let g = grid(12, 10, (8.0, 9.0), f, |_, _| [0.0; 3]);
    for kind in KINDS {
        let corr = Corrector::new(
            &g,
            Options {
                interpolation: kind,
                ..Options::default()
            },
        )
        .unwrap();
        let surf = corr.surface();
        let mut k = 0;
        for p in nodes(&f, 88.0, 81.0, 13) {
            k += 1;
            let lift = if k % 2 == 0 { 3.0 } else { -2.0 };
            let q = [p[0] + 0.3, p[1] - 0.2, p[2] + lift];
            let (_, _, _, _, d) = corr.locate(q);
            let mut best = f64::INFINITY;
            for j in 0..g.nv - 1 {
                for i in 0..g.nu - 1 {
                    best = best.min(surf_distance(surf, i, j, q));
                }
            }
            assert!(
                d <= best + 1e-9,
                "{kind:?} {q:?}: walk {d} vs all facets {best}"
            );
        }
    }
}

/// The least distance from `q` to facet `(i, j)` by a dense search.
fn surf_distance(surf: &formcam_correct::Surface<'_>, i: usize, j: usize, q: [f64; 3]) -> f64 {
    let n = 60;
    let mut best = f64::INFINITY;
    for a in 0..=n {
        for b in 0..=n {
            let p = surf.point(i, j, a as f64 / n as f64, b as f64 / n as f64);
            let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
            best = best.min(d);
        }
    }
    best
}

#[test]
fn a_ball_centre_moves_along_the_normal_by_the_normal_deviation() {
    // A tilted plane; the part is 0.3 mm proud along the normal; ball centres
    // 6 mm above the surface move back by 0.3 mm along the normal, and a
    // tangential part of the deviation does not move them.
    let (a, b) = (0.3, 0.1);
    let f = move |x: f64, y: f64| a * x + b * y;
    let len = (1.0f64 + a * a + b * b).sqrt();
    let n = [-a / len, -b / len, 1.0 / len];
    let tangent = [1.0 / (1.0 + a * a).sqrt(), 0.0, a / (1.0 + a * a).sqrt()];
    let dev = [
        0.3 * n[0] + 0.2 * tangent[0],
        0.3 * n[1],
        0.3 * n[2] + 0.2 * tangent[2],
    ];
    let g = grid(5, 5, (20.0, 20.0), f, |_, _| dev);
    let corr = Corrector::new(
        &g,
        Options {
            tool: Tool::Ball { radius: 6.0 },
            ..Options::default()
        },
    )
    .unwrap();
    for p in nodes(&f, 80.0, 80.0, 7) {
        let centre = [p[0] + 6.0 * n[0], p[1] + 6.0 * n[1], p[2] + 6.0 * n[2]];
        let c = corr.correct_node(centre);
        assert!((c.distance_mm - 6.0).abs() < 1e-9);
        for k in 0..3 {
            assert!((c.displacement[k] + 0.3 * n[k]).abs() < 1e-12, "{c:?}");
        }
    }
}

#[test]
fn nodes_outside_are_left_or_extrapolated_within_the_margin() {
    let f = |_: f64, _: f64| 0.0;
    let warp = |x: f64, y: f64| [0.0, 0.0, 0.1 + 0.001 * x + 0.002 * y];
    let g = grid(5, 4, (10.0, 10.0), f, warp);
    let inside = [20.0, 15.0, 0.0];
    let near = [43.0, 15.0, 0.0]; // 3 mm beyond x = 40
    let far = [55.0, 35.0, 0.0];
    let left = Corrector::new(&g, Options::default()).unwrap();
    let r = left.correct(&[inside, near, far]);
    assert_eq!(r[0].placement, Placement::Inside);
    assert_eq!(r[1].placement, Placement::Outside);
    assert!((r[1].outside_mm - 3.0).abs() < 1e-9);
    assert_eq!(r[1].displacement, [0.0; 3]);
    let t = Totals::of(&r);
    assert_eq!((t.nodes, t.corrected, t.outside), (3, 1, 2));
    let ext = Corrector::new(
        &g,
        Options {
            margin_mm: 5.0,
            ..Options::default()
        },
    )
    .unwrap();
    let r = ext.correct(&[near, far]);
    assert_eq!(r[0].placement, Placement::Extrapolated);
    assert!(
        (r[0].displacement[2] + warp(43.0, 15.0)[2]).abs() < 1e-12,
        "{:?}",
        r[0]
    );
    assert_eq!(r[1].placement, Placement::Outside);
}

#[test]
fn options_out_of_range_are_named() {
    let g = grid(2, 2, (1.0, 1.0), |_, _| 0.0, |_, _| [0.0; 3]);
    for (o, want) in [
        (
            Options {
                gain: 0.0,
                ..Options::default()
            },
            "gain = 0",
        ),
        (
            Options {
                tool: Tool::Ball { radius: -1.0 },
                ..Options::default()
            },
            "ball radius",
        ),
        (
            Options {
                margin_mm: f64::NAN,
                ..Options::default()
            },
            "margin",
        ),
    ] {
        let e = Corrector::new(&g, o).err().unwrap().to_string();
        assert!(e.contains(want), "{e}");
    }
}

#[test]
fn bicubic_halves_the_residual_of_a_smooth_warp() {
    // A doubly curved surface with a smooth warp, 9 x 7 measured points:
    // the error of the interpolated correction at dense nodes.
    let f = |x: f64, y: f64| (x - 80.0).powi(2) / 1600.0 + (y - 60.0).powi(2) / 1200.0;
    let w = |x: f64, y: f64| {
        0.4 * (std::f64::consts::PI * x / 160.0).sin() * (std::f64::consts::PI * y / 120.0).sin()
            + 0.1 * (3.0 * x / 160.0).cos()
    };
    let g = grid(9, 7, (20.0, 20.0), f, |x, y| [0.0, 0.0, w(x, y)]);
    let mut worst = Vec::new();
    for kind in KINDS {
        let corr = Corrector::new(
            &g,
            Options {
                interpolation: kind,
                ..Options::default()
            },
        )
        .unwrap();
        let mut e = 0.0f64;
        for p in nodes(&f, 160.0, 120.0, 41) {
            let c = corr.correct_node(p);
            e = e.max((c.displacement[2] + w(p[0], p[1])).abs());
        }
        worst.push(e);
    }
    eprintln!(
        "largest error: bilinear {:.5} mm, bicubic {:.5} mm",
        worst[0], worst[1]
    );
    assert!(
        worst[1] < 0.5 * worst[0],
        "bilinear {} vs bicubic {}",
        worst[0],
        worst[1]
    );
}

#[test]
fn nodes_over_the_edge_of_a_curved_panel_are_corrected_like_the_rest() {
    // A panel measured edge to edge: 11 sections x 9 points over 200 x 150
    // mm, strongly curved (a bowl, a dome and two saddles, R 300 mm along x,
    // 250 mm along y), warped by up to 0.3 mm. The facets' edges are chords of the curved
    // edges: a node on the surface over the edge has its foot on the chord
    // patch a few hundredths of a millimetre beyond it. Nodes on a raster
    // that includes the four edges, on the surface (point tool) and at a
    // ball's centre (R 6).
    let (l, w) = (200.0, 150.0);
    let warp = |x: f64, y: f64| {
        0.3 * (0.5
            + 0.3 * (std::f64::consts::PI * x / l).sin()
            + 0.2 * (x / l - 0.5) * (y / w - 0.5)
            - 0.1 * (std::f64::consts::PI * y / w).cos())
    };
    let mut failed = Vec::new();
    for sign in [(1.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0)] {
        let f = move |x: f64, y: f64| {
            sign.0 * (x - l / 2.0).powi(2) / 600.0 + sign.1 * (y - w / 2.0).powi(2) / 500.0
        };
        let up = move |x: f64, y: f64| {
            let n = [
                -sign.0 * (x - l / 2.0) / 300.0,
                -sign.1 * (y - w / 2.0) / 250.0,
                1.0,
            ];
            let k = 1.0 / (n[0] * n[0] + n[1] * n[1] + 1.0).sqrt();
            [n[0] * k, n[1] * k, k]
        };
        let g = grid(11, 9, (20.0, 150.0 / 8.0), f, |x, y| [0.0, 0.0, warp(x, y)]);
        for tool in [Tool::Point, Tool::Ball { radius: 6.0 }] {
            let r = match tool {
                Tool::Ball { radius } => radius,
                Tool::Point => 0.0,
            };
            let corr = Corrector::new(
                &g,
                Options {
                    tool,
                    ..Options::default()
                },
            )
            .unwrap();
            let (mut worst_edge, mut worst_inner, mut edge_nodes) = (0.0f64, 0.0f64, 0);
            let mut outside = 0;
            for a in 0..=40 {
                for b in 0..=30 {
                    let (x, y) = (l * a as f64 / 40.0, w * b as f64 / 30.0);
                    let n = up(x, y);
                    let p = [x + r * n[0], y + r * n[1], f(x, y) + r * n[2]];
                    let c = corr.correct_node(p);
                    if c.placement != Placement::Inside {
                        outside += 1;
                    }
                    // The wanted displacement: against the warp (point), its
                    // normal component along the normal (ball).
                    let d = [0.0, 0.0, -warp(x, y)];
                    let want = match tool {
                        Tool::Point => d,
                        Tool::Ball { .. } => {
                            let k = n[2] * d[2];
                            [k * n[0], k * n[1], k * n[2]]
                        }
                    };
                    let e = (0..3)
                        .map(|k| (c.displacement[k] - want[k]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    if a == 0 || a == 40 || b == 0 || b == 30 {
                        worst_edge = worst_edge.max(e);
                        edge_nodes += 1;
                    } else {
                        worst_inner = worst_inner.max(e);
                    }
                }
            }
            assert_eq!(edge_nodes, 140);
            // What is left is the patches' own error (chords for arcs, the
            // facet's normal for the surface's), the same along the edges as
            // inside.
            if outside > 0 || worst_inner >= 0.02 || worst_edge >= 1.5 * worst_inner.max(0.005) {
                failed.push(format!(
                    "{sign:?}, {tool:?}: {outside} nodes outside, error edge {worst_edge} mm, \
                     inner {worst_inner} mm"
                ));
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

#[test]
fn nodes_beyond_the_edge_in_plan_stay_outside() {
    // The same bowl: nodes 0.5 mm and 3 mm beyond the edge in plan, on the
    // surface continued, are outside (corrected only within a margin).
    let f = |x: f64, y: f64| (x - 100.0).powi(2) / 600.0 + (y - 75.0).powi(2) / 500.0;
    let g = grid(11, 9, (20.0, 150.0 / 8.0), f, |_, _| [0.0, 0.0, 0.2]);
    let corr = Corrector::new(&g, Options::default()).unwrap();
    for (x, y) in [(200.5, 40.0), (203.0, 71.0), (-0.5, 20.0), (120.0, 153.0)] {
        let c = corr.correct_node([x, y, f(x, y)]);
        assert_eq!(c.placement, Placement::Outside, "({x}, {y}): {c:?}");
        assert_eq!(c.displacement, [0.0; 3]);
    }
}

#[test]
fn the_corrections_are_the_same_bits_whatever_the_number_of_threads() {
    // A curved, twisted panel with a smooth warp and a zig-zag raster of
    // 17 000 nodes (four whole runs of the walk and a part one) that
    // reaches a little beyond its edges, corrected on pools of one, two and
    // three threads: every displacement, foot and placement alike, bit for bit.
    let f = |x: f64, y: f64| (x - 60.0).powi(2) / 300.0 + x * y / 2000.0 - (y / 40.0).sin();
    let g = grid(31, 25, (4.0, 3.0), f, |x, y| {
        [0.01 * (x / 30.0).sin(), 0.0, 0.2 * (y / 25.0).cos()]
    });
    let (rows, per_row) = (100, 170);
    let mut raster = Vec::with_capacity(rows * per_row);
    for k in 0..rows {
        let y = -1.0 + 74.0 * k as f64 / (rows - 1) as f64;
        for i in 0..per_row {
            let i = if k % 2 == 0 { i } else { per_row - 1 - i };
            let x = -2.0 + 124.0 * i as f64 / (per_row - 1) as f64;
            raster.push([x, y, f(x, y) + 0.1]);
        }
    }
    for kind in KINDS {
        let corr = Corrector::new(
            &g,
            Options {
                interpolation: kind,
                margin_mm: 1.0,
                ..Options::default()
            },
        )
        .unwrap();
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| corr.correct(&raster))
        };
        let one = on(1);
        let bits = |c: &[formcam_correct::NodeCorrection]| -> Vec<[u64; 6]> {
            c.iter()
                .map(|c| {
                    let d = c.displacement.map(f64::to_bits);
                    [
                        d[0],
                        d[1],
                        d[2],
                        c.s.to_bits(),
                        c.t.to_bits(),
                        c.distance_mm.to_bits(),
                    ]
                })
                .collect()
        };
        let totals = Totals::of(&one);
        assert!(
            totals.corrected > raster.len() * 4 / 5,
            "{kind:?}: {totals:?}"
        );
        assert!(
            totals.outside > 0 && totals.extrapolated > 0,
            "{kind:?}: {totals:?}"
        );
        for threads in [2, 3] {
            let many = on(threads);
            assert_eq!(one, many, "{kind:?} on {threads} threads");
            assert_eq!(bits(&one), bits(&many), "{kind:?} on {threads} threads");
        }
    }
}
