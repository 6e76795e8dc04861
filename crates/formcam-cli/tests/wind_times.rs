//! A `.wind` job the format's rules refuse, through the built binary: exit
//! status, one line naming the layer and the rule, nothing written. (The
//! programs' block times are tested in formcam-program.)

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{formcam, scratch};

/// The issue's job (`pairwise 6334.65 s, global 25616.37 s` before the
/// global times were fixed), its patterns made to divide the layers' circuits
/// (55 and 75) as `.wind` readers now require. Its joins between layers broke
/// the jump limits up to 18.6x before they were timed with the layers.
const ISSUE_JOB: &str = r#"{"schemaVersion": "1.0", "mandrelParameters": {"diameter": 160, "windLength": 1200}, "towParameters": {"width": 5, "thickness": 0.3}, "defaultFeedRate": 2000, "layers": [{"windType": "hoop", "terminal": false}, {"windType": "helical", "windAngle": 57, "patternNumber": 5, "skipIndex": 1, "lockDegrees": 720, "leadInMM": 25, "leadOutDegrees": 60}, {"windType": "hoop", "terminal": false}, {"windType": "helical", "windAngle": 26, "patternNumber": 1, "skipIndex": 1, "lockDegrees": 540, "leadInMM": 25, "leadOutDegrees": 60}, {"windType": "hoop", "terminal": false}, {"windType": "helical", "windAngle": 45, "patternNumber": 2, "skipIndex": 1, "lockDegrees": 720, "leadInMM": 25, "leadOutDegrees": 60}, {"windType": "hoop", "terminal": false}, {"windType": "helical", "windAngle": 42, "patternNumber": 5, "skipIndex": 1, "lockDegrees": 720, "leadInMM": 25, "leadOutDegrees": 60}]}"#;

/// The issue's job exactly as it was filed: the format's specification asks a
/// reader to refuse it (4 divides neither layer's circuit count, 55 and 75),
/// and the message names the layer and the rule.
#[test]
fn the_issue_job_as_filed_is_refused_for_its_patterns() {
    let dir = scratch("issue-as-filed");
    let path = dir.join("job.wind");
    let filed = ISSUE_JOB.replace(
        r#""windAngle": 57, "patternNumber": 5"#,
        r#""windAngle": 57, "patternNumber": 4"#,
    );
    assert_ne!(filed, ISSUE_JOB);
    std::fs::write(&path, &filed).unwrap();
    let st = formcam()
        .arg("wind")
        .arg(&path)
        .arg("-o")
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&st.stderr);
    assert!(!st.status.success(), "{stderr}");
    assert!(
        stderr.contains("layers[1].patternNumber") && stderr.contains("does not divide"),
        "{stderr}"
    );
    assert!(!dir.join("out").join("program.gcode").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
