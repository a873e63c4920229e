//! The state every method advances: time, beam displacements and
//! velocities, and the mass dofs of the carriers (MODEL §2, §5:
//! `d = [d_b; q]`). What a method needs beyond this (generalized-α's
//! accelerations, its predictors) it keeps in its own stepper.

/// The state at t_n.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Steps taken, n.
    pub step: usize,
    /// Time t_n = n·Δt, s (from the step count: one rounding, not accumulated).
    pub t: f64,
    /// Beam dofs d_b (m and rad).
    pub d: Vec<f64>,
    /// Beam velocities (m/s and rad/s). Central difference keeps the
    /// half-step velocity v_{n−1/2} here (MODEL §9.1).
    pub v: Vec<f64>,
    /// Mass displacement q = s·ξ of each contact, m (positive into the beam).
    pub q: Vec<f64>,
    /// Mass velocity q̇ of each contact, m/s.
    pub q_dot: Vec<f64>,
}

impl State {
    /// At rest at t = 0: beam straight, masses touching it (MODEL §5).
    pub fn at_rest(beam_dofs: usize, contacts: usize) -> Self {
        State {
            step: 0,
            t: 0.0,
            d: vec![0.0; beam_dofs],
            v: vec![0.0; beam_dofs],
            q: vec![0.0; contacts],
            q_dot: vec![0.0; contacts],
        }
    }

    /// t_{n+1} = (n + 1)·Δt, s.
    pub fn next_time(&self, dt: f64) -> f64 {
        (self.step + 1) as f64 * dt
    }
}
