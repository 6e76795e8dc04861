//! The CMM's measurements: nominal and actual points per control section.

use crate::vec3::{V3, dot, norm, scale, sub, unit};
use crate::{CorrectError, MeasureError, MeasureProblem};

mod dmis;

/// One measured point.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredPoint {
    /// The point's name in its section.
    pub point: String,
    /// The nominal (model) point, mm.
    pub nominal: V3,
    /// The measured point, mm.
    pub actual: V3,
    /// The nominal surface normal (unit), if the report gives it.
    pub normal: Option<V3>,
}

impl MeasuredPoint {
    /// Actual − nominal; its normal component (a vector along the normal)
    /// where the normal is given.
    pub fn deviation(&self) -> V3 {
        let d = sub(self.actual, self.nominal);
        match self.normal {
            Some(n) => scale(n, dot(d, n)),
            None => d,
        }
    }
}

/// The points of one control section, in measuring order.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// The section's name.
    pub name: String,
    /// Its points.
    pub points: Vec<MeasuredPoint>,
}

/// A CMM report: sections in order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Measurements {
    /// The sections in the order they first appear.
    pub sections: Vec<Section>,
}

fn bad(line: usize, problem: MeasureProblem) -> CorrectError {
    CorrectError::Measurements(MeasureError::At { line, problem })
}

impl Measurements {
    /// Every point.
    pub fn points(&self) -> impl Iterator<Item = &MeasuredPoint> {
        self.sections.iter().flat_map(|s| s.points.iter())
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.sections.iter().map(|s| s.points.len()).sum()
    }

    /// No points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The largest deviation (length of the deviation vector), mm.
    pub fn max_deviation(&self) -> f64 {
        self.points()
            .map(|p| norm(p.deviation()))
            .fold(0.0, f64::max)
    }

    /// Checks every point's deviation against `limit_mm`: the first point
    /// beyond it (in the report's order) is the error, naming its section
    /// and point.
    pub fn check_deviation(&self, limit_mm: f64) -> Result<(), CorrectError> {
        for s in &self.sections {
            for p in &s.points {
                let d = norm(p.deviation());
                // A NaN deviation is beyond every limit.
                if d.is_nan() || d > limit_mm {
                    return Err(CorrectError::Deviation {
                        section: s.name.clone(),
                        point: p.point.clone(),
                        deviation_mm: d,
                        limit_mm,
                    });
                }
            }
        }
        Ok(())
    }

    /// The root mean square deviation, mm.
    pub fn rms_deviation(&self) -> f64 {
        let n = self.len();
        if n == 0 {
            return 0.0;
        }
        let s: f64 = self
            .points()
            .map(|p| dot(p.deviation(), p.deviation()))
            .sum();
        (s / n as f64).sqrt()
    }

    /// The report as the CSV [`Self::from_csv`] reads: `section, point`,
    /// the nominal and actual points and, when every point has one, the
    /// normal `nx, ny, nz`; every number as written by Rust's shortest
    /// round trip, so the file reads back to the same nominal and actual
    /// points.
    pub fn to_csv(&self) -> String {
        let normals = !self.is_empty() && self.points().all(|p| p.normal.is_some());
        let mut out = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act");
        out.push_str(if normals { ",nx,ny,nz\n" } else { "\n" });
        for s in &self.sections {
            for p in &s.points {
                let [a, b, c] = p.nominal;
                let [d, e, f] = p.actual;
                out.push_str(&format!("{},{},{a},{b},{c},{d},{e},{f}", s.name, p.point));
                match p.normal {
                    Some([x, y, z]) if normals => out.push_str(&format!(",{x},{y},{z}\n")),
                    _ => out.push('\n'),
                }
            }
        }
        out
    }

    /// Reads the CSV report: a header with the columns `section, point,
    /// x_nom, y_nom, z_nom, x_act, y_act, z_act` (any order), optionally
    /// `nx, ny, nz` (the nominal normal); instead of the actual point, a
    /// `dev` column (the normal deviation, mm) with the normal. Points of a
    /// section are ordered by `point` (numerically when every name is a
    /// number, else as listed); sections by their first row.
    pub fn from_csv(text: &str) -> Result<Self, CorrectError> {
        let mut rows = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let Some((header_line, header)) = rows.next() else {
            return Err(MeasureError::Empty.into());
        };
        let names: Vec<String> = header
            .split([',', ';'])
            .map(|s| s.trim().to_ascii_lowercase())
            .collect();
        let col = |n: &str| names.iter().position(|c| c == n);
        let need = |n: &'static str| {
            col(n).ok_or_else(|| bad(header_line, MeasureProblem::NoColumn { column: n }))
        };
        let sec = need("section")?;
        let pt = need("point")?;
        let nom = [need("x_nom")?, need("y_nom")?, need("z_nom")?];
        let normal_cols = match (col("nx"), col("ny"), col("nz")) {
            (Some(a), Some(b), Some(c)) => Some([a, b, c]),
            (None, None, None) => None,
            _ => {
                return Err(bad(header_line, MeasureProblem::SomeNormals));
            }
        };
        let act_cols = match (col("x_act"), col("y_act"), col("z_act")) {
            (Some(a), Some(b), Some(c)) => Some([a, b, c]),
            _ => None,
        };
        let dev_col = col("dev");
        if act_cols.is_none() && (dev_col.is_none() || normal_cols.is_none()) {
            return Err(bad(header_line, MeasureProblem::NoActualColumns));
        }
        let mut m = Measurements::default();
        for (line, row) in rows {
            let f: Vec<&str> = row.split([',', ';']).map(str::trim).collect();
            let field = |c: usize| -> Result<f64, CorrectError> {
                let s = f.get(c).ok_or_else(|| {
                    bad(
                        line,
                        MeasureProblem::NoValue {
                            column: names[c].clone(),
                        },
                    )
                })?;
                let v: f64 = s.parse().map_err(|_| {
                    bad(
                        line,
                        MeasureProblem::NotANumber {
                            column: names[c].clone(),
                            text: (*s).into(),
                        },
                    )
                })?;
                if !v.is_finite() {
                    return Err(bad(
                        line,
                        MeasureProblem::NotFinite {
                            column: names[c].clone(),
                            text: (*s).into(),
                        },
                    ));
                }
                Ok(v)
            };
            let section = f.get(sec).copied().unwrap_or_default().to_string();
            let point = f.get(pt).copied().unwrap_or_default().to_string();
            if section.is_empty() || point.is_empty() {
                return Err(bad(line, MeasureProblem::NoName));
            }
            let nominal = [field(nom[0])?, field(nom[1])?, field(nom[2])?];
            let normal = match normal_cols {
                Some(c) => {
                    let n = [field(c[0])?, field(c[1])?, field(c[2])?];
                    if norm(n) < 1e-9 {
                        return Err(bad(line, MeasureProblem::ZeroNormal));
                    }
                    Some(unit(n))
                }
                None => None,
            };
            let actual = match (act_cols, dev_col, normal) {
                (Some(c), _, _) => [field(c[0])?, field(c[1])?, field(c[2])?],
                (None, Some(d), Some(n)) => {
                    let d = field(d)?;
                    [
                        nominal[0] + d * n[0],
                        nominal[1] + d * n[1],
                        nominal[2] + d * n[2],
                    ]
                }
                _ => return Err(bad(line, MeasureProblem::NoActualPoint)),
            };
            m.push(
                section,
                MeasuredPoint {
                    point,
                    nominal,
                    actual,
                    normal,
                },
                line,
            )?;
        }
        m.finish()
    }

    /// Reads the text of the CMM report file `path` by its extension: DMIS
    /// for `.dmi`, `.dmis`, `.dms`, `.dmo` (any case), else CSV.
    pub fn from_file_text(path: &std::path::Path, text: &str) -> Result<Self, CorrectError> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        match ext.as_str() {
            "dmi" | "dmis" | "dms" | "dmo" => Self::from_dmis(text),
            _ => Self::from_csv(text),
        }
    }

    /// Reads the point features of a DMIS output file: nominals
    /// `F(label)=FEAT/POINT,CART,x,y,z[,i,j,k]` and actuals
    /// `FA(label)=FEAT/POINT,CART,x,y,z[,i,j,k]`. A label names its section
    /// and point as `<section>_<point>` (also `.` or `-`), e.g. `S1_P3`.
    /// `UNITS/INCH` scales to mm; `$$` comments and `$` continuations are
    /// understood; other statements are passed over.
    pub fn from_dmis(text: &str) -> Result<Self, CorrectError> {
        let mut features = dmis::DmisFeatures::new();
        for (line, statement) in dmis::dmis_statements(text) {
            features.read(line, &statement)?;
        }
        features.measurements()
    }

    fn push(&mut self, section: String, p: MeasuredPoint, line: usize) -> Result<(), CorrectError> {
        let s = match self.sections.iter().position(|s| s.name == section) {
            Some(k) => &mut self.sections[k],
            None => {
                self.sections.push(Section {
                    name: section,
                    points: Vec::new(),
                });
                let last = self.sections.len() - 1;
                &mut self.sections[last]
            }
        };
        if s.points.iter().any(|q| q.point == p.point) {
            return Err(bad(
                line,
                MeasureProblem::PointTwice {
                    section: s.name.clone(),
                    point: p.point,
                },
            ));
        }
        s.points.push(p);
        Ok(())
    }

    /// Orders the points of every section by name (numerically where all are numbers).
    fn finish(mut self) -> Result<Self, CorrectError> {
        if self.is_empty() {
            return Err(MeasureError::NoPoints.into());
        }
        for s in &mut self.sections {
            if s.points.iter().all(|p| p.point.parse::<f64>().is_ok()) {
                s.points.sort_by(|a, b| {
                    let (x, y) = (
                        a.point.parse::<f64>().unwrap_or(0.0),
                        b.point.parse::<f64>().unwrap_or(0.0),
                    );
                    x.total_cmp(&y)
                });
            }
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_with_normals_takes_the_normal_component() {
        let text = "section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act,nx,ny,nz\n\
                    A,2,0,1,0,0.3,1,0.2,0,0,2\nA,1,0,0,0,0,0,0.1,0,0,1\nB,1,1,0,0,1,0,0,0,0,1\n";
        let m = Measurements::from_csv(text).unwrap();
        assert_eq!(m.sections.len(), 2);
        assert_eq!(m.sections[0].points[0].point, "1");
        assert_eq!(m.sections[0].points[1].deviation(), [0.0, 0.0, 0.2]);
        assert!((m.max_deviation() - 0.2).abs() < 1e-15);
    }

    #[test]
    fn csv_written_reads_back_to_the_same_points() {
        let text = "section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act,nx,ny,nz\n\
                    A,1,0,0,0.1,0,0,0.30000000000000004,0,0.6,0.8\nA,2,1.5,0,0,1.5,0,-0.1,0,0,1\n\
                    B,1,0,2,0,1e-7,2,0.2,0,0,1\nB,2,1.5,2,0,1.5,2,0.2,0,0,1\n";
        let m = Measurements::from_csv(text).unwrap();
        let again = Measurements::from_csv(&m.to_csv()).unwrap();
        assert_eq!(again.len(), m.len());
        for (a, b) in again.points().zip(m.points()) {
            assert_eq!(
                (&a.point, a.nominal, a.actual),
                (&b.point, b.nominal, b.actual)
            );
            let n = (a.normal.unwrap(), b.normal.unwrap());
            assert!((0..3).all(|k| (n.0[k] - n.1[k]).abs() < 1e-15), "{n:?}");
        }
        let plain = Measurements {
            sections: vec![Section {
                name: "S".into(),
                points: vec![MeasuredPoint {
                    point: "1".into(),
                    nominal: [0.0; 3],
                    actual: [0.0, 0.0, 0.25],
                    normal: None,
                }],
            }],
        };
        assert_eq!(
            plain.to_csv(),
            "section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\nS,1,0,0,0,0,0,0.25\n"
        );
    }

    #[test]
    fn dmis_points_pair_nominal_and_actual() {
        let text = "DMISMN/'mould',05.0\nUNITS/MM,ANGDEG\n\
                    F(S1_P1)=FEAT/POINT,CART,0,0,0,0,0,1\n\
                    F(S1_P2)=FEAT/POINT,CART,$\n 10,0,0,0,0,1\n\
                    $$ measured\nFA(S1_P2)=FEAT/POINT,CART,10,0,0.05,0,0,1\n\
                    FA(S1_P1)=FEAT/POINT,CART,0,0,-0.02,0,0,1\nENDFIL\n";
        let m = Measurements::from_dmis(text).unwrap();
        assert_eq!(m.sections.len(), 1);
        let s = &m.sections[0];
        assert_eq!(s.name, "S1");
        assert_eq!(s.points[1].point, "P2");
        assert!((s.points[1].deviation()[2] - 0.05).abs() < 1e-15);
        assert!((s.points[0].deviation()[2] + 0.02).abs() < 1e-15);
    }

    #[test]
    fn bad_reports_name_the_line_and_field() {
        let head = "section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n";
        let cases = [
            (
                format!("{head}A,1,0,0,NaN,0,0,0\n"),
                "line 2: `z_nom` = `NaN` is not finite",
            ),
            (
                format!("{head}A,1,0,0,0,0,0,0\nA,1,1,0,0,1,0,0\n"),
                "line 3: point `1` of section `A` is given twice",
            ),
            (
                format!("{head}A,1,0,0,x,0,0,0\n"),
                "`z_nom` = `x` is not a number",
            ),
            ("section,point,x_nom\n".to_string(), "no column `y_nom`"),
            (String::new(), "empty"),
        ];
        for (text, want) in cases {
            let e = Measurements::from_csv(&text).unwrap_err().to_string();
            assert!(e.contains(want), "{e}");
        }
        let e =
            Measurements::from_dmis("F(P1)=FEAT/POINT,CART,0,0,0\nFA(P1)=FEAT/POINT,CART,0,0,0\n")
                .unwrap_err()
                .to_string();
        assert!(e.contains("<section>_<point>"), "{e}");
    }
}
