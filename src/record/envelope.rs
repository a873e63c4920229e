//! The uplift envelope (`[output] envelope = true`; docs/output.md#envelope):
//! the largest and smallest beam displacement v(x_i, t) (positive up, m)
//! over every step, row 0 (t = 0) included, at every mesh node x_i. O(n)
//! per step, recorded only when asked; `envelope.csv` and `line.svg` show it.

/// v's range over time at each point.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Envelope {
    /// The points (the mesh nodes), m.
    pub x: Vec<f64>,
    /// Smallest v(x_i, t) over the steps, m.
    pub v_min: Vec<f64>,
    /// Largest v(x_i, t) over the steps, m.
    pub v_max: Vec<f64>,
    /// v(x_i, 0): the contact wire where the run started (0 at rest, the
    /// static sag with `[time] initial = "static"`), m; drawn in
    /// `line.svg`, not written to `envelope.csv`.
    pub start: Vec<f64>,
    /// v_m(x_i, 0) of the messenger wire at the same points, m (empty
    /// without a messenger).
    pub messenger_start: Vec<f64>,
}

impl Envelope {
    /// An envelope on `x` before any step.
    pub fn new(x: Vec<f64>) -> Self {
        Envelope {
            v_min: vec![f64::INFINITY; x.len()],
            v_max: vec![f64::NEG_INFINITY; x.len()],
            x,
            start: Vec::new(),
            messenger_start: Vec::new(),
        }
    }

    /// True when nothing is recorded (no envelope asked for).
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Widen point i's range by v (m).
    pub fn push(&mut self, i: usize, v: f64) {
        self.v_min[i] = self.v_min[i].min(v);
        self.v_max[i] = self.v_max[i].max(v);
    }
}
