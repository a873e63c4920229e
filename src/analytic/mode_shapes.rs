//! STUB (replaced by the helper's version at merge): pinned–pinned only.
use crate::error::Result;
use crate::scene::BeamProps;

/// Exact modes, mass-normalized.
#[derive(Debug, Clone)]
pub struct ModeShapes {
    omega: Vec<f64>,
    length: f64,
    norm: f64,
}

impl ModeShapes {
    /// J modes.
    pub fn new(props: &BeamProps, count: usize) -> Result<Self> {
        let l = props.length;
        let omega = (1..=count)
            .map(|j| {
                let k = j as f64 * std::f64::consts::PI / l;
                k * ((props.ei * k * k + props.tension) / props.rho_a).sqrt()
            })
            .collect();
        Ok(ModeShapes {
            omega,
            length: l,
            norm: (2.0 / (props.rho_a * l)).sqrt(),
        })
    }
    /// J.
    pub fn count(&self) -> usize {
        self.omega.len()
    }
    /// ω_j.
    pub fn omega(&self) -> &[f64] {
        &self.omega
    }
    /// φ_j(x).
    pub fn values_into(&self, x: f64, out: &mut [f64]) {
        for (j, o) in out.iter_mut().enumerate() {
            *o = self.norm * ((j + 1) as f64 * std::f64::consts::PI * x / self.length).sin();
        }
    }
    /// φ_j'(x).
    pub fn slopes_into(&self, x: f64, out: &mut [f64]) {
        for (j, o) in out.iter_mut().enumerate() {
            let k = (j + 1) as f64 * std::f64::consts::PI / self.length;
            *o = self.norm * k * (k * x).cos();
        }
    }
    /// ∫pφ_j.
    pub fn uniform_load(&self, p: f64) -> Vec<f64> {
        (0..self.count())
            .map(|j| {
                let k = (j + 1) as f64 * std::f64::consts::PI / self.length;
                p * self.norm * (1.0 - (k * self.length).cos()) / k
            })
            .collect()
    }
}
