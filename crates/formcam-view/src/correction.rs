//! A correction result (`formcam correct JOB -o OUT`): the deviation map of
//! the measurements its `report.json` names — every measured point at its
//! nominal place, with its deviation — and the deviation per section and
//! per run of the report's history (`/api/correction`).

use std::path::{Path, PathBuf};

use formcam_correct::{MeasuredPoint, Measurements};
use serde::Serialize;
use serde_json::{Map, Value};

use crate::ViewError;

/// What `/api/correction` sends.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CorrectionBody {
    /// The measurement file, as the report names it.
    pub measurements: String,
    /// The corrected program's file in the folder, if there.
    pub program: Option<String>,
    /// Every measured point's nominal `x`, mm.
    pub x: Vec<f64>,
    /// Nominal `y`, mm.
    pub y: Vec<f64>,
    /// Nominal `z`, mm.
    pub z: Vec<f64>,
    /// The deviation, mm: along the nominal normal where the report gives
    /// it (positive outward), else actual − nominal in `z`.
    pub deviation: Vec<f64>,
    /// Each point's section (an index into `sections`).
    pub section: Vec<usize>,
    /// Per section in the report's order.
    pub sections: Vec<SectionStats>,
    /// The report's keys (`max_deviation_mm`, `history`, ...), as written.
    pub report: Map<String, Value>,
}

/// One section's deviations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SectionStats {
    /// The section's name.
    pub name: String,
    /// Its points.
    pub points: usize,
    /// The least deviation, mm.
    pub min: f64,
    /// The largest, mm.
    pub max: f64,
    /// The RMS deviation, mm.
    pub rms: f64,
}

/// The signed deviation of a point: along its normal where given, else in `z`.
pub fn signed_deviation(p: &MeasuredPoint) -> f64 {
    let d = [
        p.actual[0] - p.nominal[0],
        p.actual[1] - p.nominal[1],
        p.actual[2] - p.nominal[2],
    ];
    match p.normal {
        Some(n) => d[0] * n[0] + d[1] * n[1] + d[2] * n[2],
        None => d[2],
    }
}

impl CorrectionBody {
    /// Reads the correction result in `root`: `report.json` (already read
    /// as `report`) and the measurements it names (a relative name is
    /// taken from the folder `formcam view` runs in, as it was for
    /// `formcam correct`; CSV, or DMIS by the extension).
    ///
    /// # Errors
    ///
    /// [`ViewError::Read`] or [`ViewError::Measurements`] naming the report
    /// and the file.
    pub fn read(root: &Path, report: Map<String, Value>) -> Result<Self, ViewError> {
        let report_path = root.join("report.json");
        let name = report
            .get("measurements")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string();
        let path = PathBuf::from(&name);
        let text = crate::folder::read_text(&path)?;
        let m = Measurements::from_file_text(&path, &text).map_err(|source| {
            ViewError::Measurements {
                report: report_path,
                measurements: path.clone(),
                source: Box::new(source),
            }
        })?;
        let program = std::fs::read_dir(root).ok().and_then(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.starts_with("corrected.") && !n.ends_with(".svg"))
                .min()
        });
        Ok(Self::of(&m, name, program, report))
    }

    /// The map of `m`.
    pub fn of(
        m: &Measurements,
        measurements: String,
        program: Option<String>,
        report: Map<String, Value>,
    ) -> Self {
        let mut body = Self {
            measurements,
            program,
            x: Vec::new(),
            y: Vec::new(),
            z: Vec::new(),
            deviation: Vec::new(),
            section: Vec::new(),
            sections: Vec::new(),
            report,
        };
        for (k, s) in m.sections.iter().enumerate() {
            let devs: Vec<f64> = s.points.iter().map(signed_deviation).collect();
            for (p, d) in s.points.iter().zip(&devs) {
                body.x.push(p.nominal[0]);
                body.y.push(p.nominal[1]);
                body.z.push(p.nominal[2]);
                body.deviation.push(*d);
                body.section.push(k);
            }
            let n = devs.len().max(1) as f64;
            body.sections.push(SectionStats {
                name: s.name.clone(),
                points: devs.len(),
                min: devs.iter().copied().fold(f64::INFINITY, f64::min),
                max: devs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                rms: (devs.iter().map(|d| d * d).sum::<f64>() / n).sqrt(),
            });
        }
        body
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn deviations_along_the_normal_and_per_section() {
        let csv = "section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act,nx,ny,nz\n\
                   S1,1,0,0,1,0.3,0,1.4,0.6,0,0.8\n\
                   S1,2,10,0,1,10,0,0.9,0,0,1\n\
                   S2,1,0,5,2,0,5,2.2,0,0,1\n";
        let m = Measurements::from_csv(csv).unwrap();
        let b = CorrectionBody::of(&m, "cmm.csv".into(), None, Map::new());
        assert_eq!(b.x, [0.0, 10.0, 0.0]);
        assert_eq!(b.y, [0.0, 0.0, 5.0]);
        assert_eq!(b.section, [0, 0, 1]);
        // 0.3 * 0.6 + 0.4 * 0.8 = 0.5 along the normal.
        let want = [0.5, -0.1, 0.2];
        for (d, w) in b.deviation.iter().zip(want) {
            assert!((d - w).abs() < 1e-12, "{d} {w}");
        }
        assert_eq!(b.sections.len(), 2);
        assert_eq!(b.sections[0].points, 2);
        assert!((b.sections[0].min + 0.1).abs() < 1e-12);
        assert!((b.sections[0].max - 0.5).abs() < 1e-12);
        assert!((b.sections[0].rms - (0.13f64).sqrt()).abs() < 1e-12);
        assert!((b.sections[1].rms - 0.2).abs() < 1e-12);
    }
}
