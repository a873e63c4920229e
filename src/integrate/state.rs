//! The state every method advances: time, beam displacements and
//! velocities, and the mass dofs of the carriers (MODEL §2, §5:
//! `d = [d_b; q]`). What a method needs beyond this (generalized-α's
//! accelerations, its predictors) it keeps in its own stepper.

use crate::numeric::lanes::AlignedLanes;

/// The state at t_n.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Steps taken, n.
    pub step: usize,
    /// Time t_n = n·Δt, s (from the step count: one rounding, not accumulated).
    pub t: f64,
    /// Beam dofs d_b (m and rad).
    pub d: Dofs,
    /// Beam velocities (m/s and rad/s). Central difference keeps the
    /// half-step velocity v_{n−1/2} here (MODEL §9.1).
    pub v: Dofs,
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
            d: Dofs::zeros(beam_dofs),
            v: Dofs::zeros(beam_dofs),
            q: vec![0.0; contacts],
            q_dot: vec![0.0; contacts],
        }
    }

    /// t_{n+1} = (n + 1)·Δt, s.
    pub fn next_time(&self, dt: f64) -> f64 {
        (self.step + 1) as f64 * dt
    }
}

/// A state vector (the beam's dofs or velocities): its values seen as a
/// slice (`&[f64]`, indexing, iteration), held in whole 64-byte-aligned
/// lines, so that the modal kernels' 512-bit loads of eight modes at a
/// multiple of eight never span two cache lines (a `Vec<f64>` starts
/// wherever the allocator puts it, 16-byte aligned, and then every such
/// load and store of the state is split: the AVX-512 cruise pass at
/// J = 800 measured 2–6 % slower with the state one, two or four values
/// off a line, on an AMD EPYC, Zen 4). The same values as a `Vec<f64>`,
/// which converts into it.
#[derive(Clone, Default, PartialEq)]
pub struct Dofs(AlignedLanes);

impl Dofs {
    /// `len` zeros.
    pub fn zeros(len: usize) -> Self {
        Dofs(AlignedLanes::zeros(len))
    }
}

impl From<Vec<f64>> for Dofs {
    fn from(v: Vec<f64>) -> Self {
        Dofs::from(&v[..])
    }
}

impl From<&[f64]> for Dofs {
    fn from(v: &[f64]) -> Self {
        let mut d = Dofs::zeros(v.len());
        d.copy_from_slice(v);
        d
    }
}

impl FromIterator<f64> for Dofs {
    fn from_iter<I: IntoIterator<Item = f64>>(it: I) -> Self {
        Dofs::from(it.into_iter().collect::<Vec<f64>>())
    }
}

impl<'a> IntoIterator for &'a Dofs {
    type Item = &'a f64;
    type IntoIter = std::slice::Iter<'a, f64>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<'a> IntoIterator for &'a mut Dofs {
    type Item = &'a mut f64;
    type IntoIter = std::slice::IterMut<'a, f64>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter_mut()
    }
}

impl std::fmt::Debug for Dofs {
    /// As the slice (a `Vec<f64>`'s format).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Debug::fmt(&**self, f)
    }
}

impl std::ops::Deref for Dofs {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        &self.0
    }
}

impl std::ops::DerefMut for Dofs {
    fn deref_mut(&mut self) -> &mut [f64] {
        &mut self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A state's vectors start on a cache line, hold zeros, and convert
    /// from a `Vec<f64>` value for value.
    #[test]
    fn dofs_are_aligned_and_convert_from_a_vec() {
        let st = State::at_rest(803, 1);
        for x in [&st.d, &st.v] {
            assert_eq!(x.as_ptr() as usize % 64, 0);
            assert_eq!(x.len(), 803);
            assert!(x.iter().all(|x| *x == 0.0));
        }
        let v: Vec<f64> = (0..13).map(|i| i as f64 * 0.5).collect();
        let d = Dofs::from(v.clone());
        assert_eq!(*d, *v);
        assert_eq!(d.as_ptr() as usize % 64, 0);
        assert_eq!(format!("{d:?}"), format!("{v:?}"));
    }
}
