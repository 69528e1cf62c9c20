//! The obstacle test of docs/spec.md §5, decided exactly in integers, and its `f64` twin for the
//! reference mode (docs/spec.md §7).
//!
//! A move between grid points `P` and `Q` is safe iff for every disc `(C, r)`: neither endpoint
//! is strictly inside (`|P−C|² < r²`), and, when the projection of `C` onto the line falls
//! within the segment (`0 ≤ (C−P)·(Q−P) ≤ |Q−P|²`), the closest point is not strictly inside:
//! `|C−P|²·|Q−P|² − ((C−P)·(Q−P))² < r²·|Q−P|²`. All quantities are scaled by 19 so that the
//! grid points `(800·col/19, 800·row/19)` become integers; `i128` holds every product.

/// A disc obstacle `[cx, cy, r]` in world units (integers in the paper's data).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Disc {
    /// Centre x.
    pub cx: i64,
    /// Centre y.
    pub cy: i64,
    /// Radius.
    pub r: i64,
}

/// A point with integer coordinates in some scaled frame.
pub type IPoint = (i128, i128);

/// Whether `p` lies strictly inside the disc `(c, r)` (all in the same scaled frame).
///
/// ```
/// use truecost::problems::geometry::strictly_inside;
/// assert!(strictly_inside((1, 0), (0, 0), 2));
/// assert!(!strictly_inside((2, 0), (0, 0), 2)); // on the circle: not strictly inside
/// ```
pub fn strictly_inside(p: IPoint, c: IPoint, r: i128) -> bool {
    let (dx, dy) = (p.0 - c.0, p.1 - c.1);
    dx * dx + dy * dy < r * r
}

/// Whether the segment `p–q` is safe with respect to the disc `(c, r)`, exactly.
///
/// ```
/// use truecost::problems::geometry::segment_safe;
/// // A horizontal segment passing 1 unit from a centre: blocked by r = 2, safe for r = 1.
/// assert!(!segment_safe((-5, 1), (5, 1), (0, 0), 2));
/// assert!(segment_safe((-5, 1), (5, 1), (0, 0), 1));
/// // Projection outside the segment: only the endpoints count.
/// assert!(segment_safe((3, 0), (5, 0), (0, 0), 2));
/// ```
pub fn segment_safe(p: IPoint, q: IPoint, c: IPoint, r: i128) -> bool {
    if strictly_inside(p, c, r) || strictly_inside(q, c, r) {
        return false;
    }
    let d = (q.0 - p.0, q.1 - p.1);
    let w = (c.0 - p.0, c.1 - p.1);
    let len2 = d.0 * d.0 + d.1 * d.1;
    let dot = w.0 * d.0 + w.1 * d.1;
    if len2 == 0 || dot < 0 || dot > len2 {
        return true;
    }
    let w2 = w.0 * w.0 + w.1 * w.1;
    // squared distance × len2, compared with r² × len2
    w2 * len2 - dot * dot >= r * r * len2
}

/// The `f64` obstacle test of the reference code (docs/spec.md §7): the same rule evaluated in
/// floating point on the reference coordinates.
pub fn segment_safe_f64(p: (f64, f64), q: (f64, f64), disc: &Disc) -> bool {
    let (cx, cy, r) = (disc.cx as f64, disc.cy as f64, disc.r as f64);
    let inside = |x: f64, y: f64| {
        let (dx, dy) = (x - cx, y - cy);
        (dx * dx + dy * dy).sqrt() < r
    };
    if inside(p.0, p.1) || inside(q.0, q.1) {
        return false;
    }
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let len2 = dx * dx + dy * dy;
    if len2 == 0.0 {
        return true;
    }
    let t = ((cx - p.0) * dx + (cy - p.1) * dy) / len2;
    if !(0.0..=1.0).contains(&t) {
        return true;
    }
    !inside(p.0 + t * dx, p.1 + t * dy)
}
