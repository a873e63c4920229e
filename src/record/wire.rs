//! The wire's displacement along the span as recorded: snapshots v(x) at
//! chosen times and the space–time field v(x, t) (`[output] snapshots`,
//! `field`; docs/output.md#snapshots). v is the beam displacement, positive
//! up, as the probes record it (MODEL §4: v(x) = r_b(x)ᵀ d, the basis's own
//! interpolation: Hermite cubics on a mesh, the modal sum in a modal basis).

/// v(x_i) at a series of times, row by row.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WireSeries {
    /// The times asked for, s (a snapshot's `output.snapshots` entry; the
    /// step's time for the field).
    pub requested: Vec<f64>,
    /// The recorded step's time, s.
    pub t: Vec<f64>,
    /// The points, m.
    pub x: Vec<f64>,
    /// v, m, row-major: `v[k * x.len() + i]` is v(x_i) at `t[k]`.
    pub v: Vec<f64>,
}

impl WireSeries {
    /// An empty series on `x` with room for `rows` rows (no allocation
    /// while recording them).
    pub fn with_capacity(x: Vec<f64>, rows: usize) -> Self {
        WireSeries {
            requested: Vec::with_capacity(rows),
            t: Vec::with_capacity(rows),
            v: Vec::with_capacity(rows.saturating_mul(x.len())),
            x,
        }
    }

    /// Rows recorded.
    pub fn rows(&self) -> usize {
        self.t.len()
    }

    /// True when nothing is recorded (no snapshot or field asked for).
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Row k: v at every point.
    pub fn row(&self, k: usize) -> &[f64] {
        let n = self.x.len();
        &self.v[k * n..(k + 1) * n]
    }
}
