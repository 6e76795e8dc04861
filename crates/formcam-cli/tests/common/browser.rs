//! What the browser tests share: whether the browser test can run here,
//! and the browser driver (`viewer/tests/SCRIPT` under node) run with a
//! time limit.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use super::repo;

/// Whether the browser test can run here; fails when it must.
pub fn browser_present() -> bool {
    let missing: Vec<&str> = [
        (!Path::new("/usr/bin/chromium").is_file())
            .then_some("/usr/bin/chromium (apt-get install chromium)"),
        (!repo().join("viewer/node_modules/playwright-core").is_dir())
            .then_some("viewer/node_modules (npm ci in viewer/)"),
        (!formcam_view::Page::is_embedded())
            .then_some("the built page (npm run build in viewer/, then cargo build)"),
    ]
    .into_iter()
    .flatten()
    .collect();
    if !missing.is_empty() {
        assert!(
            std::env::var("FORMCAM_REQUIRE_BROWSER").as_deref() != Ok("1"),
            "FORMCAM_REQUIRE_BROWSER=1 but missing: {}",
            missing.join(", ")
        );
        eprintln!("skipped: the browser test needs {}", missing.join(", "));
    }
    missing.is_empty()
}

/// The most a browser driver may take; each bounds itself (a page not
/// ready within 45 s, the whole run within 150 to 280 s), this is the last
/// resort.
pub const DRIVER_LIMIT: Duration = Duration::from_secs(330);

/// Runs `viewer/tests/SCRIPT` with `args`, killed past [`DRIVER_LIMIT`]
/// (`report`: the file it writes, quoted when it is killed).
pub fn driver(script: &str, args: &[&str], report: &Path) -> Output {
    let mut child = Command::new("node")
        .arg(repo().join("viewer/tests").join(script))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > DRIVER_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "the browser driver did not end within {} s; its report so far: {}",
                DRIVER_LIMIT.as_secs(),
                std::fs::read_to_string(report).unwrap_or_default()
            );
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    child.wait_with_output().unwrap()
}
