//! Natural frequencies and mode shapes of a scene's beam (`taut modes`,
//! Python's `taut.modes`): the generalized eigenproblem `K φ = ω² M φ` of
//! MODEL §4 with the point attachments of MODEL §10 in K and M, solved by
//! the discretization the scene names:
//!
//! * `hermite` (uniform or graded) and `modal`: the finite-element
//!   eigenpairs of the scene's mesh ([`crate::model::eigen`], the solve the
//!   `modal` basis is built from; for `modal` the J lowest of them *are* its
//!   basis). Source `fe_eigen`.
//! * `galerkin`: the exact modes of the continuous beam
//!   ([`crate::analytic::ModeShapes`], the basis a galerkin run steps in).
//!   Source `exact`.
//!
//! Beside each frequency stands the taut string's `f_j = j c / (2L)`,
//! c = sqrt(T/ρA) (MODEL §1 with EI = 0), where it applies: T > 0, both
//! ends held (not free) and no attachments; it is the limit the bending
//! stiffness raises the frequencies from.
//!
//! Shapes are sampled at the nodes of the scene's FE mesh (for `galerkin`,
//! which has no mesh, at the nodes of the uniform mesh of `mesh.elements`
//! elements): `φ_j(x_i) = r_b(x_i)ᵀ Φ_j`, the discretization's own
//! interpolation (MODEL §4). They are mass-normalized, `Φ_jᵀ M Φ_j = 1`
//! (`∫ρA φ_j² dx + Σ_a m_a φ_j(x_a)² = 1`, units kg^−1/2), and signed so
//! that the sample of largest magnitude is positive (the first such sample
//! on a tie): a solver's arbitrary sign does not reach the output.

use crate::analytic::{MAX_MODES, ModeShapes};
use crate::error::{Error, Result};
use crate::model::beam::BeamModel;
use crate::model::eigen::{MAX_MODAL_DOFS, lowest_eigenpairs};
use crate::model::mesh::Mesh;
use crate::resolve::Resolved;
use crate::scene::{Discretization, Support};

/// Modes computed when no count is asked for.
pub(crate) const DEFAULT_COUNT: usize = 10;

/// Where a scene's frequencies come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeSource {
    /// The finite-element eigenproblem of the scene's mesh.
    FeEigen,
    /// The exact modes of the continuous beam (a `galerkin` scene).
    Exact,
}

impl ModeSource {
    /// The name written in `modes.csv`'s `source` column.
    pub fn name(self) -> &'static str {
        match self {
            ModeSource::FeEigen => "fe_eigen",
            ModeSource::Exact => "exact",
        }
    }
}

/// A scene's lowest modes.
#[derive(Debug, Clone)]
pub struct Modes {
    /// What the frequencies are.
    pub source: ModeSource,
    /// f_j = ω_j / (2π), Hz, ascending.
    pub frequencies_hz: Vec<f64>,
    /// The taut string's j c / (2L), Hz, where it applies (module doc).
    pub string_hz: Option<Vec<f64>>,
    /// Sample points, m (the mesh nodes).
    pub x: Vec<f64>,
    /// `shapes[j][i]` = φ_j(x_i), kg^−1/2 (mass-normalized, signed as the
    /// module doc says).
    pub shapes: Vec<Vec<f64>>,
}

/// The allowed counts for a scene with `most` modes available.
fn check_count(count: usize, most: usize, why: &str) -> Result<usize> {
    if (1..=most).contains(&count) {
        Ok(count)
    } else {
        Err(Error::invalid(
            "--count",
            count,
            format!("must be in 1 ..= {most} ({why})"),
        ))
    }
}

/// The `count` lowest modes of the scene's beam (default
/// `DEFAULT_COUNT`, or fewer when the discretization has fewer).
pub fn modes(sc: &Resolved, count: Option<usize>) -> Result<Modes> {
    let props = &sc.beam;
    let l = props.length;
    let mesh = match sc.discretization {
        Discretization::Galerkin { .. } => Mesh::uniform(l, sc.elements),
        _ => Mesh::new(l, sc.elements, sc.grading)?,
    };
    let x: Vec<f64> = (0..=mesh.elements()).map(|i| mesh.node(i)).collect();
    let (source, omega, mut shapes) = match sc.discretization {
        Discretization::Galerkin { .. } => {
            let count = match count {
                Some(c) => check_count(c, MAX_MODES, "the exact modes computed")?,
                None => DEFAULT_COUNT,
            };
            let m = ModeShapes::new(props, count)?;
            let mut shapes = vec![vec![0.0; x.len()]; count];
            let mut at = vec![0.0; count];
            for (i, &xi) in x.iter().enumerate() {
                m.values_into(xi, &mut at);
                for (s, a) in shapes.iter_mut().zip(&at) {
                    s[i] = *a;
                }
            }
            (ModeSource::Exact, m.omega().to_vec(), shapes)
        }
        Discretization::Hermite | Discretization::Modal { .. } => {
            let beam = BeamModel::on_mesh(props, mesh);
            let n = beam.n;
            if n > MAX_MODAL_DOFS {
                return Err(Error::invalid(
                    "mesh.elements",
                    sc.elements,
                    format!(
                        "gives {n} FE unknowns; the modes are a dense eigenproblem of at most {MAX_MODAL_DOFS} (n² memory, n³ time: model::eigen)"
                    ),
                ));
            }
            let count = match count {
                Some(c) => check_count(c, n, "the mesh's unknowns")?,
                None => DEFAULT_COUNT.min(n),
            };
            let pairs = lowest_eigenpairs(&beam.mass, &beam.stiffness, count)?;
            let pvs: Vec<_> = x.iter().map(|&xi| beam.point_vector(xi)).collect();
            let shapes = (0..count)
                .map(|j| pvs.iter().map(|pv| pv.dot(pairs.shape(j))).collect())
                .collect();
            // a free end's rigid modes have ω² = ±round-off (model::modal)
            let omega = pairs.omega_sq.iter().map(|w| w.max(0.0).sqrt()).collect();
            (ModeSource::FeEigen, omega, shapes)
        }
    };
    for s in &mut shapes {
        sign_largest_positive(s);
    }
    let held = |s: Support| s != Support::Free;
    let string_hz = (props.tension > 0.0
        && held(props.left)
        && held(props.right)
        && props.attachments.is_empty()
        && props.messenger.is_none())
    .then(|| {
        let c = props.wave_speed();
        (1..=omega.len())
            .map(|j| j as f64 * c / (2.0 * l))
            .collect()
    });
    Ok(Modes {
        source,
        frequencies_hz: omega
            .iter()
            .map(|w| w / (2.0 * std::f64::consts::PI))
            .collect(),
        string_hz,
        x,
        shapes,
    })
}

/// Flip `s` so that its entry of largest magnitude (the first on a tie) is
/// positive.
fn sign_largest_positive(s: &mut [f64]) {
    let mut big = 0.0f64;
    for &v in s.iter() {
        if v.abs() > big.abs() {
            big = v;
        }
    }
    if big < 0.0 {
        for v in s.iter_mut() {
            *v = -*v;
        }
    }
}
