//! Measured sections harmonised into a grid of quadrilateral facets.

use crate::vec3::{V3, add, dot, norm, scale, sub, unit};
use crate::{CorrectError, JobField, Measurements, Rule, SectionsError};

/// The measured points as a regular grid: `sections` rows of
/// `points_per_section` corresponding points. Facet `(i, j)` is spanned by
/// points `i, i+1` of sections `j, j+1`.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Points per section (`s` runs along them).
    pub nu: usize,
    /// Sections (`t` runs across them).
    pub nv: usize,
    /// Nominal points, section by section (`j * nu + i`).
    pub nominal: Vec<V3>,
    /// Deviations (actual − nominal, or its normal component), same order.
    pub deviation: Vec<V3>,
    /// Nominal normals where the report gives them.
    pub normal: Option<Vec<V3>>,
    /// Whether the sections were resampled to corresponding points.
    pub resampled: bool,
    /// Whether the sections were put in spatial order (the report listed
    /// them otherwise).
    pub reordered: bool,
}

/// The sections in the order they lie across their direction: by their
/// centroids projected on the direction in which the centroids spread
/// (after removing the component along the sections). Sections that lie at
/// the same place are an error.
fn spatial_order(m: &Measurements) -> Result<Vec<usize>, CorrectError> {
    let n = m.sections.len();
    let centroid = |s: &crate::Section| {
        let k = 1.0 / s.points.len() as f64;
        s.points
            .iter()
            .fold([0.0; 3], |a, p| add(a, scale(p.nominal, k)))
    };
    let first = &m.sections[0].points;
    let along = unit(sub(first[first.len() - 1].nominal, first[0].nominal));
    let across: Vec<V3> = m
        .sections
        .iter()
        .map(|s| {
            let c = centroid(s);
            sub(c, scale(along, dot(c, along)))
        })
        .collect();
    let (far, spread) = across
        .iter()
        .enumerate()
        .map(|(j, c)| (j, norm(sub(*c, across[0]))))
        .fold((0, 0.0), |best, x| if x.1 > best.1 { x } else { best });
    let size = m
        .points()
        .map(|p| norm(sub(p.nominal, m.sections[0].points[0].nominal)))
        .fold(0.0, f64::max);
    if spread <= 1e-9 * (1.0 + size) {
        return Err(SectionsError::SamePlace {
            first: m.sections[0].name.clone(),
            second: m.sections[n - 1].name.clone(),
        }
        .into());
    }
    let e = unit(sub(across[far], across[0]));
    let key: Vec<f64> = across.iter().map(|c| dot(*c, e)).collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| key[a].total_cmp(&key[b]));
    for w in order.windows(2) {
        if key[w[1]] - key[w[0]] <= 1e-6 * spread {
            return Err(SectionsError::SamePlace {
                first: m.sections[w[0]].name.clone(),
                second: m.sections[w[1]].name.clone(),
            }
            .into());
        }
    }
    Ok(order)
}

/// The slope of a sequence of `n` points at `k`: central differences,
/// second-order one-sided ones at the ends (first-order for two points).
fn slope(at: impl Fn(usize) -> V3, k: usize, n: usize) -> V3 {
    if n < 3 {
        return sub(at(1), at(0));
    }
    let comb = |a: V3, b: V3, c: V3, s: f64| {
        [0, 1, 2].map(|x| s * (-3.0 * a[x] + 4.0 * b[x] - c[x]) / 2.0)
    };
    if k == 0 {
        comb(at(0), at(1), at(2), 1.0)
    } else if k == n - 1 {
        comb(at(n - 1), at(n - 2), at(n - 3), -1.0)
    } else {
        scale(sub(at(k + 1), at(k - 1)), 0.5)
    }
}

impl Grid {
    /// Harmonises the sections: each one resampled by arc length to
    /// `points_per_section` points (`None`: as measured when every section
    /// has the same count, else to the largest count), nominal points,
    /// deviations and normals interpolated linearly along the section.
    ///
    /// Errors: fewer than two sections, a section with fewer than two
    /// points, two consecutive points at the same place, a section running
    /// the other way than its neighbour, normals on some points only.
    pub fn from_measurements(
        m: &Measurements,
        points_per_section: Option<usize>,
    ) -> Result<Self, CorrectError> {
        let err = |e: SectionsError| Err(CorrectError::Sections(e));
        if m.sections.len() < 2 {
            return err(SectionsError::TooFew {
                count: m.sections.len(),
            });
        }
        if let Some(count) = points_per_section
            && let Some(Err(rule)) = JobField::PointsPerSection
                .described()
                .map(|f| Rule::check(f, count as f64))
        {
            return err(SectionsError::PointsPerSection { count, rule });
        }
        let with_normals = m.points().filter(|p| p.normal.is_some()).count();
        if with_normals != 0 && with_normals != m.len() {
            return err(SectionsError::SomeNormals {
                with_normals,
                points: m.len(),
            });
        }
        for s in &m.sections {
            if s.points.len() < 2 {
                return err(SectionsError::ShortSection {
                    section: s.name.clone(),
                    points: s.points.len(),
                });
            }
        }
        let order = spatial_order(m)?;
        let reordered = order.iter().enumerate().any(|(k, &j)| k != j);
        let sections: Vec<&crate::Section> = order.iter().map(|&j| &m.sections[j]).collect();
        let mut prev_dir: Option<V3> = None;
        for (j, s) in sections.iter().enumerate() {
            let len: f64 = s
                .points
                .windows(2)
                .map(|w| norm(sub(w[1].nominal, w[0].nominal)))
                .sum();
            for w in s.points.windows(2) {
                if norm(sub(w[1].nominal, w[0].nominal)) <= 1e-9 * (1.0 + len) {
                    return err(SectionsError::DuplicatePoint {
                        section: s.name.clone(),
                        first: w[0].point.clone(),
                        second: w[1].point.clone(),
                    });
                }
            }
            let dir = sub(s.points[s.points.len() - 1].nominal, s.points[0].nominal);
            if let Some(p) = prev_dir
                && dot(p, dir) < 0.0
            {
                return err(SectionsError::Reversed {
                    section: s.name.clone(),
                    previous: sections[j - 1].name.clone(),
                });
            }
            prev_dir = Some(dir);
        }
        let counts: Vec<usize> = sections.iter().map(|s| s.points.len()).collect();
        let same = counts.iter().all(|&c| c == counts[0]);
        let nu = points_per_section.unwrap_or_else(|| counts.iter().copied().max().unwrap_or(2));
        let resample = !(same && nu == counts[0]);
        let nv = m.sections.len();
        let mut nominal = Vec::with_capacity(nu * nv);
        let mut deviation = Vec::with_capacity(nu * nv);
        let mut normal = (with_normals > 0).then(|| Vec::with_capacity(nu * nv));
        for s in &sections {
            if !resample {
                for p in &s.points {
                    nominal.push(p.nominal);
                    deviation.push(p.deviation());
                    if let (Some(v), Some(n)) = (&mut normal, p.normal) {
                        v.push(n);
                    }
                }
                continue;
            }
            // Cumulative arc length of the nominal polyline.
            let mut acc = vec![0.0];
            for w in s.points.windows(2) {
                let l = acc[acc.len() - 1] + norm(sub(w[1].nominal, w[0].nominal));
                acc.push(l);
            }
            let total = acc[acc.len() - 1];
            let mut seg = 0;
            for k in 0..nu {
                let at = total * k as f64 / (nu - 1) as f64;
                while seg + 2 < acc.len() && acc[seg + 1] < at {
                    seg += 1;
                }
                let f = ((at - acc[seg]) / (acc[seg + 1] - acc[seg])).clamp(0.0, 1.0);
                let (a, b) = (&s.points[seg], &s.points[seg + 1]);
                let lerp = |x: V3, y: V3| add(scale(x, 1.0 - f), scale(y, f));
                nominal.push(lerp(a.nominal, b.nominal));
                deviation.push(lerp(a.deviation(), b.deviation()));
                if let (Some(v), Some(na), Some(nb)) = (&mut normal, a.normal, b.normal) {
                    v.push(unit(lerp(na, nb)));
                }
            }
        }
        Ok(Self {
            nu,
            nv,
            nominal,
            deviation,
            normal,
            resampled: resample,
            reordered,
        })
    }

    /// Nominal point `i` of section `j`.
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> V3 {
        self.nominal[j * self.nu + i]
    }

    /// The deviation at point `i` of section `j`.
    #[inline]
    pub fn deviation_at(&self, i: usize, j: usize) -> V3 {
        self.deviation[j * self.nu + i]
    }

    /// The unit surface normal at point `i` of section `j`: the report's
    /// normal where it gives one, else the cross product of the grid's
    /// slopes (`along section x across sections`, by central differences,
    /// second-order one-sided ones on the edges).
    pub fn normal_at(&self, i: usize, j: usize) -> V3 {
        if let Some(n) = &self.normal {
            return n[j * self.nu + i];
        }
        let du = slope(|k| self.at(k, j), i, self.nu);
        let dv = slope(|k| self.at(i, k), j, self.nv);
        unit(crate::vec3::cross(du, dv))
    }

    /// The number of facets.
    pub fn facets(&self) -> usize {
        (self.nu - 1) * (self.nv - 1)
    }

    /// The largest deviation on the grid, mm.
    pub fn max_deviation(&self) -> f64 {
        self.deviation.iter().map(|d| norm(*d)).fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::{MeasuredPoint, Section};

    fn section(name: &str, y: f64, xs: &[f64]) -> Section {
        Section {
            name: name.into(),
            points: xs
                .iter()
                .enumerate()
                .map(|(k, &x)| MeasuredPoint {
                    point: k.to_string(),
                    nominal: [x, y, 0.0],
                    actual: [x, y, 0.1 * x],
                    normal: None,
                })
                .collect(),
        }
    }

    #[test]
    fn sections_of_different_counts_are_resampled_by_arc_length() {
        let m = Measurements {
            sections: vec![
                section("a", 0.0, &[0.0, 10.0]),
                section("b", 5.0, &[0.0, 2.0, 10.0]),
            ],
        };
        let g = Grid::from_measurements(&m, None).unwrap();
        assert!(g.resampled);
        assert_eq!((g.nu, g.nv), (3, 2));
        assert_eq!(g.at(1, 0), [5.0, 0.0, 0.0]);
        assert!((g.deviation_at(1, 0)[2] - 0.5).abs() < 1e-15);
        assert_eq!(g.at(1, 1), [5.0, 5.0, 0.0]);
    }

    #[test]
    fn sections_are_put_in_spatial_order_and_must_be_apart() {
        // Listed as exports sort names: S1, S10, S2, ...
        let mut sections: Vec<Section> = (1..=10)
            .map(|k| section(&format!("S{k}"), 10.0 * k as f64, &[0.0, 5.0, 10.0]))
            .collect();
        sections.sort_by(|a, b| a.name.cmp(&b.name));
        let m = Measurements { sections };
        let g = Grid::from_measurements(&m, None).unwrap();
        assert!(g.reordered);
        for j in 0..g.nv {
            assert_eq!(g.at(0, j)[1], 10.0 * (j + 1) as f64);
        }
        let same = Measurements {
            sections: vec![
                section("a", 0.0, &[0.0, 1.0]),
                section("b", 5.0, &[0.0, 1.0]),
                section("c", 5.0, &[0.0, 1.0]),
            ],
        };
        let e = Grid::from_measurements(&same, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("sections `b` and `c` lie at the same place"),
            "{e}"
        );
    }

    #[test]
    fn bad_sections_are_named() {
        let one = Measurements {
            sections: vec![section("a", 0.0, &[0.0, 1.0]), section("b", 1.0, &[0.0])],
        };
        let e = Grid::from_measurements(&one, None).unwrap_err().to_string();
        assert!(e.contains("section `b` has 1 point"), "{e}");
        let rev = Measurements {
            sections: vec![
                section("a", 0.0, &[0.0, 1.0]),
                section("b", 1.0, &[1.0, 0.0]),
            ],
        };
        let e = Grid::from_measurements(&rev, None).unwrap_err().to_string();
        assert!(e.contains("runs the other way"), "{e}");
        let dup = Measurements {
            sections: vec![
                section("a", 0.0, &[0.0, 1.0, 1.0]),
                section("b", 1.0, &[0.0, 1.0, 2.0]),
            ],
        };
        let e = Grid::from_measurements(&dup, None).unwrap_err().to_string();
        assert!(e.contains("duplicate"), "{e}");
    }
}
