//! Iso-lines by marching squares.
/// One iso-line level by marching squares over node values `s[i][j]` at
/// plotted coordinates (`px[i]`, `py[j]`): segments in plotted coordinates.
pub(super) fn marching_squares(
    px: &[f64],
    py: &[f64],
    s: &[Vec<f64>],
    level: f64,
) -> Vec<[(f64, f64); 2]> {
    let mut segs = Vec::new();
    if px.len() < 2 || py.len() < 2 {
        return segs;
    }
    let cross = |a: (f64, f64, f64), b: (f64, f64, f64)| {
        let t = (level - a.2) / (b.2 - a.2);
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    };
    for i in 0..px.len() - 1 {
        for j in 0..py.len() - 1 {
            // corners counter-clockwise: (i,j) (i+1,j) (i+1,j+1) (i,j+1)
            let c = [
                (px[i], py[j], s[i][j]),
                (px[i + 1], py[j], s[i + 1][j]),
                (px[i + 1], py[j + 1], s[i + 1][j + 1]),
                (px[i], py[j + 1], s[i][j + 1]),
            ];
            if c.iter().any(|p| !p.2.is_finite()) {
                continue;
            }
            let above: Vec<bool> = c.iter().map(|p| p.2 >= level).collect();
            // crossings on the edges k: corner k → corner k+1
            let mut pts: Vec<(usize, (f64, f64))> = Vec::new();
            for k in 0..4 {
                let (a, b) = (c[k], c[(k + 1) % 4]);
                if above[k] != above[(k + 1) % 4] {
                    pts.push((k, cross(a, b)));
                }
            }
            match pts.len() {
                2 => segs.push([pts[0].1, pts[1].1]),
                4 => {
                    // saddle: decide by the centre value
                    let centre = c.iter().map(|p| p.2).sum::<f64>() / 4.0;
                    let centre_above = centre >= level;
                    if centre_above == above[0] {
                        // corners 0 and 2 join through the centre: cut off
                        // corner 1 (edges 0, 1) and corner 3 (edges 2, 3)
                        segs.push([pts[0].1, pts[1].1]);
                        segs.push([pts[2].1, pts[3].1]);
                    } else {
                        // corners 1 and 3 join: cut off corners 0 and 2
                        segs.push([pts[3].1, pts[0].1]);
                        segs.push([pts[1].1, pts[2].1]);
                    }
                }
                _ => {}
            }
        }
    }
    segs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marching_squares_finds_a_straight_iso_line() {
        // s = x: the level 0.5 is the vertical line x = 0.5
        let px = [0.0, 1.0];
        let py = [0.0, 1.0, 2.0];
        let s = vec![vec![0.0, 0.0, 0.0], vec![1.0, 1.0, 1.0]];
        let segs = marching_squares(&px, &py, &s, 0.5);
        assert_eq!(segs.len(), 2);
        for sg in segs {
            for p in sg {
                assert!((p.0 - 0.5).abs() < 1e-12);
            }
        }
    }
}
