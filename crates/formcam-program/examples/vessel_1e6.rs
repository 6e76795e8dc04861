//! The speed case of the `wind` bench, run on its own for profilers
//! (`perf stat`, `perf record`): the 3-layer vessel with 10^6 path points
//! planned and its program written, as many times as the argument says
//! (once by default).

#![allow(clippy::expect_used)]

use std::path::Path;

use formcam_program::{WindJob, plan_program, write_program};

fn main() {
    let times: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1);
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let job = WindJob::from_toml(include_str!("../benches/vessel-1e6.toml"), here).expect("job");
    let mut bytes = 0;
    for _ in 0..times {
        let p = plan_program(&job).expect("plan");
        let mut text = Vec::new();
        write_program(&p, &mut text).expect("post");
        bytes = text.len();
    }
    println!("{bytes} bytes");
}
