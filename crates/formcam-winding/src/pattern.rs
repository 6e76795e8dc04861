//! Circuits and patterns: how many circuits cover the mandrel and by how much
//! the mandrel must advance per circuit so that the bands lie side by side.
//!
//! With `n` circuits in a layer, the band positions at the equator are the
//! multiples of `2 pi / n`. A circuit advances the mandrel by
//! `natural + dwell ≡ 2 pi q / n (mod 2 pi)`; when `q` is coprime with `n` the
//! layer visits every position once. The **pattern number** `p` is the number of
//! circuits after which a band lies next to the first one (`p q ≡ ±1 mod n`),
//! and the **skip index** `k = round(p q / n)` is how many times the pattern goes
//! round the mandrel in those `p` circuits. The dwell closes the pattern: the
//! extra mandrel rotation at the turn-arounds, `0 <= dwell - dwell_min < 2 pi`.

use std::f64::consts::TAU;

use serde::Serialize;

use crate::WindingError;

/// What a pattern must achieve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatternRequest {
    /// Band width, mm.
    pub band_width: f64,
    /// Overlap of neighbouring bands as a fraction of the band width, `0 <= overlap < 1`.
    pub overlap: f64,
    /// Radius of the reference parallel (the equator), mm.
    pub radius: f64,
    /// Winding angle there, rad.
    pub alpha: f64,
    /// Turn angle of one circuit without dwell, rad.
    pub natural_turn: f64,
    /// Least dwell per circuit (both turn-arounds together), rad.
    pub dwell_min: f64,
    /// Required pattern number, if any.
    pub pattern_number: Option<u32>,
    /// Required skip index, if any.
    pub skip_index: Option<u32>,
}

/// The chosen pattern.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Pattern {
    /// Circuits in the layer.
    pub circuits: u32,
    /// Least circuits for full coverage with the requested overlap.
    pub circuits_min: u32,
    /// Pattern number `p`.
    pub pattern_number: u32,
    /// Skip index `k`.
    pub skip_index: u32,
    /// Position step `q`: each circuit advances `2 pi q / n`.
    pub step: u32,
    /// Mandrel advance per circuit, modulo one turn, rad.
    pub advance_rad: f64,
    /// Dwell per circuit (both turn-arounds), rad.
    pub dwell_rad: f64,
    /// Overlap actually obtained at the equator, fraction of the band width.
    pub overlap: f64,
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// Inverse of `q` modulo `n` (extended Euclid), if `gcd(q, n) = 1`.
fn inverse(q: u32, n: u32) -> Option<u32> {
    let (mut a, mut b) = (i64::from(q), i64::from(n));
    let (mut x0, mut x1) = (1i64, 0i64);
    while b != 0 {
        let t = a / b;
        (a, b) = (b, a - t * b);
        (x0, x1) = (x1, x0 - t * x1);
    }
    (a == 1).then(|| x0.rem_euclid(i64::from(n)) as u32)
}

/// `(p, k)` of step `q` (coprime with `n`) in a layer of `n` circuits: the
/// fewest circuits `p` with `p q ≡ ±1 (mod n)`, and the turns `k` they make.
fn pattern_of(q: u32, n: u32) -> (u32, u32) {
    if n <= 2 {
        return (1, q);
    }
    let inv = inverse(q, n).unwrap_or(1);
    let p = inv.min(n - inv);
    let k = ((f64::from(p) * f64::from(q)) / f64::from(n)).round() as u32;
    (p, k)
}

/// Chooses the number of circuits and the pattern with the least dwell.
pub fn choose_pattern(req: &PatternRequest) -> Result<Pattern, WindingError> {
    if !(req.band_width > 0.0 && req.band_width.is_finite()) {
        return Err(WindingError::field("winding.band_width", "must be > 0 mm"));
    }
    if !(0.0..1.0).contains(&req.overlap) {
        return Err(WindingError::field(
            "winding.overlap",
            "must be in [0, 1) (a fraction of the band width)",
        ));
    }
    let cover = TAU * req.radius * req.alpha.cos();
    let width = req.band_width * (1.0 - req.overlap);
    let n0f = (cover / width - 1e-9).ceil().max(1.0);
    if n0f > 1e6 {
        return Err(WindingError::field(
            "winding.band_width",
            format!(
                "with overlap {} gives {n0f:.0} circuits per layer; at most 1e6 are supported",
                req.overlap
            ),
        ));
    }
    let n0 = n0f as u32;
    let natural = req.natural_turn.rem_euclid(TAU);
    if req.pattern_number == Some(0) {
        return Err(WindingError::field(
            "winding.pattern_number",
            "must be >= 1",
        ));
    }
    let mut best: Option<Pattern> = None;
    'layer: for n in n0..=n0.saturating_add(200) {
        // Positions in order of increasing dwell: the first acceptable one is the best.
        let first = ((natural + req.dwell_min) / TAU * f64::from(n) - 1e-9).ceil() as i64;
        // A requested pattern number p allows only q = ±p^-1 (mod n).
        let allowed: Option<Vec<u32>> =
            req.pattern_number.map(|p| match inverse(p % n.max(1), n) {
                Some(i) if n > 2 => vec![i, n - i],
                _ => Vec::new(),
            });
        for t in 0..i64::from(n) {
            let q = (first + t).rem_euclid(i64::from(n)) as u32;
            if allowed.as_ref().is_some_and(|a| !a.contains(&q)) {
                continue;
            }
            if n > 1 && gcd(q, n) != 1 {
                continue;
            }
            let (p, k) = pattern_of(q, n);
            if req.pattern_number.is_some_and(|want| want != p)
                || req.skip_index.is_some_and(|want| want != k)
            {
                continue;
            }
            let target = TAU * f64::from(q) / f64::from(n);
            let mut extra = (target - natural - req.dwell_min).rem_euclid(TAU);
            if extra > TAU - 1e-9 {
                extra = 0.0;
            }
            let dwell = extra + req.dwell_min;
            best = Some(Pattern {
                circuits: n,
                circuits_min: n0,
                pattern_number: p,
                skip_index: k,
                step: q,
                advance_rad: target,
                dwell_rad: dwell,
                overlap: 1.0 - cover / (f64::from(n) * req.band_width),
            });
            break 'layer;
        }
    }
    best.ok_or_else(|| {
        WindingError::field(
            "winding.pattern_number",
            "no layer of up to 200 circuits above the minimum has this pattern number and skip index",
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(natural: f64) -> PatternRequest {
        PatternRequest {
            band_width: 10.0,
            overlap: 0.0,
            radius: 100.0,
            alpha: 0.5,
            natural_turn: natural,
            dwell_min: 0.0,
            pattern_number: None,
            skip_index: None,
        }
    }

    #[test]
    fn covers_the_equator_and_closes_the_pattern() {
        let r = req(7.3);
        let p = choose_pattern(&r).unwrap();
        let n0 = (TAU * 100.0 * 0.5f64.cos() / 10.0).ceil() as u32;
        assert_eq!(p.circuits, n0);
        assert!(p.overlap >= 0.0);
        // Natural turn + dwell lands on a band position.
        let total = (7.3 + p.dwell_rad).rem_euclid(TAU);
        assert!((total - p.advance_rad).abs() < 1e-9 || (total - p.advance_rad).abs() > TAU - 1e-9);
        assert!(p.dwell_rad >= 0.0 && p.dwell_rad < TAU);
        // Every position is visited exactly once.
        let mut seen = vec![false; p.circuits as usize];
        for j in 0..p.circuits {
            let pos = (j as u64 * p.step as u64 % p.circuits as u64) as usize;
            assert!(!seen[pos]);
            seen[pos] = true;
        }
        // After p circuits the band lies next to the first.
        let after = (u64::from(p.pattern_number) * u64::from(p.step)) % u64::from(p.circuits);
        assert!(after == 1 || after == u64::from(p.circuits - 1));
    }

    #[test]
    fn least_dwell_is_at_most_one_band_step_when_unconstrained() {
        for natural in [0.1, 1.0, 3.0, 5.5] {
            let p = choose_pattern(&req(natural)).unwrap();
            // Positions coprime with n are at most a few steps apart.
            assert!(p.dwell_rad < 4.0 * TAU / f64::from(p.circuits), "{p:?}");
        }
    }

    #[test]
    fn honours_a_requested_pattern_number() {
        let mut r = req(2.0);
        r.pattern_number = Some(3);
        let p = choose_pattern(&r).unwrap();
        assert_eq!(p.pattern_number, 3);
        assert!(p.circuits >= p.circuits_min);
    }

    #[test]
    fn pattern_number_from_the_modular_inverse_matches_a_scan() {
        for n in 3..80u32 {
            for q in 1..n {
                if gcd(q, n) != 1 {
                    continue;
                }
                let scan = (1..=n)
                    .find(|j| {
                        let rem = (j * q) % n;
                        rem == 1 || rem == n - 1
                    })
                    .unwrap();
                assert_eq!(pattern_of(q, n).0, scan, "n {n} q {q}");
            }
        }
    }

    #[test]
    fn a_requested_pattern_on_a_large_layer_is_found_directly() {
        let mut r = req(2.0);
        r.band_width = 0.02; // about 27 000 circuits
        r.pattern_number = Some(7);
        let p = choose_pattern(&r).unwrap();
        assert_eq!(p.pattern_number, 7);
        r.pattern_number = Some(0);
        assert!(choose_pattern(&r).is_err());
    }

    #[test]
    fn rejects_bad_overlap() {
        let mut r = req(2.0);
        r.overlap = 1.0;
        assert!(choose_pattern(&r).is_err());
    }
}
