//! The discretized beam (MODEL §4, §6, §9.2): the unknowns, their mass and
//! stiffness matrices M and K (banded), the distributed load, and point
//! vectors r_b(x) with v(x) = r_b(x)ᵀd.
//!
//! Only what the scene requires: Hermite elements (v, θ per node,
//! half-bandwidth 3) when EI > 0, linear string elements (v per node,
//! half-bandwidth 1) when EI = 0, on a uniform or graded [`Mesh`]. Two more
//! bases share the seam (`[mesh] kind`, MODEL §9.2): the J lowest FE modes
//! (`modal`, FE modal truncation) and the J exact modes of the continuous
//! beam (`galerkin`). Both are mass-normalized, so their M is the identity
//! and K = diag(ω_j²), stored as bands of half-bandwidth 0: every time
//! integrator and contact law runs on them unchanged, at O(J) per step,
//! through M, K, the load and the point vectors (which become dense
//! J-vectors, `r_j = φ_j(x)`).

use super::banded::SymBand;
use super::element;
use super::mesh::Mesh;
use crate::analytic::ModeShapes;
use crate::error::Result;
use crate::numeric::lanes::AlignedLanes;
use crate::scene::{Attachment, BeamProps, Discretization, MeshPlan, Support};

/// Which element family the beam uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Hermite cubic beam elements with tension (EI > 0).
    Hermite,
    /// Linear C0 string elements (EI = 0).
    String,
}

/// A point vector r(x) over the unknowns: v(x) = r(x)ᵀd (MODEL §4, r_b(x)).
///
/// On a mesh it is sparse, the shape functions of the element holding the
/// point (at most four dofs; supported dofs carry weight 0). In a modal
/// basis it is dense, `r_j = φ_j(x)`, kept in a buffer that
/// [`BeamModel::point_vector_into`] refills without allocating.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointVector {
    /// Global dof indices (unused slots point at 0 with weight 0).
    pub idx: [usize; 4],
    /// Weights (shape function values).
    pub val: [f64; 4],
    /// The dense weights of a modal basis (empty on a mesh), cache-line
    /// aligned for the modal kernels' 512-bit loads.
    dense: AlignedLanes,
}

impl PointVector {
    /// The dense weights r_j of a modal basis (empty on a mesh).
    pub fn dense(&self) -> &[f64] {
        &self.dense
    }

    /// The dense weights of a modal basis, to be written in place (a
    /// method that evaluates the basis itself, `modal_exact`).
    pub(crate) fn dense_mut(&mut self) -> &mut [f64] {
        &mut self.dense
    }

    /// rᵀx.
    #[inline]
    pub fn dot(&self, x: &[f64]) -> f64 {
        if self.dense.is_empty() {
            self.val[0] * x[self.idx[0]]
                + self.val[1] * x[self.idx[1]]
                + self.val[2] * x[self.idx[2]]
                + self.val[3] * x[self.idx[3]]
        } else {
            crate::numeric::lanes::dot(&self.dense, x)
        }
    }

    /// rᵀx where x holds `lanes` runs interleaved (`x[i·lanes + lane]`,
    /// batched stepping): the same operations in the same order as
    /// [`PointVector::dot`] on that run's own vector, so the bits agree.
    #[inline]
    pub fn dot_lane(&self, x: &[f64], lanes: usize, lane: usize) -> f64 {
        self.dot_by(|i| x[i * lanes + lane])
    }

    /// rᵀx with `x_i = at(i)`: the operations and order of
    /// [`PointVector::dot`] (so the same bits as that dot on a vector
    /// holding those values), for a caller whose x is not stored as one
    /// (a batch's interleaved runs, a state with an update pending).
    #[inline]
    pub fn dot_by(&self, at: impl Fn(usize) -> f64) -> f64 {
        if self.dense.is_empty() {
            self.val[0] * at(self.idx[0])
                + self.val[1] * at(self.idx[1])
                + self.val[2] * at(self.idx[2])
                + self.val[3] * at(self.idx[3])
        } else {
            // crate::numeric::lanes::dot's partial sums, in its order
            let n = self.dense.len();
            let full = n / crate::numeric::lanes::LANES * crate::numeric::lanes::LANES;
            let mut acc = [0.0; crate::numeric::lanes::LANES];
            for (i, r) in self.dense.iter().enumerate() {
                let l = if i < full {
                    i % crate::numeric::lanes::LANES
                } else {
                    i - full
                };
                acc[l] = r.mul_add(at(i), acc[l]);
            }
            crate::numeric::lanes::reduce(&acc)
        }
    }

    /// y += a·r. `y` has `stride` interleaved columns; this writes column `col`.
    #[inline]
    pub fn scatter(&self, a: f64, y: &mut [f64], stride: usize, col: usize) {
        if self.dense.is_empty() {
            for k in 0..4 {
                y[self.idx[k] * stride + col] += a * self.val[k];
            }
        } else {
            for (r, y) in self.dense.iter().zip(y.chunks_exact_mut(stride)) {
                y[col] += a * r;
            }
        }
    }

    /// rᵀx where x has `stride` interleaved columns; reads column `col`.
    #[inline]
    pub fn dot_strided(&self, x: &[f64], stride: usize, col: usize) -> f64 {
        if self.dense.is_empty() {
            (0..4)
                .map(|k| self.val[k] * x[self.idx[k] * stride + col])
                .sum()
        } else {
            self.dense
                .iter()
                .zip(x.chunks_exact(stride))
                .map(|(r, x)| r * x[col])
                .sum()
        }
    }
}

/// What the unknowns are (MODEL §9.2).
#[derive(Debug, Clone)]
pub enum Basis {
    /// Nodal values of the finite elements.
    Elements,
    /// Modal coordinates of the J lowest FE modes: v(x) = Σ_j φ_j(x) η_j,
    /// φ_j(x) = r_b(x)ᵀΦ_j.
    Modal {
        /// Φ row by row: FE dof i's entries of the J modes at i·J .. (i+1)·J.
        shapes: Vec<f64>,
        /// J.
        modes: usize,
    },
    /// Coordinates of the J exact modes of the continuous beam.
    Galerkin(ModeShapes),
}

/// The assembled beam.
#[derive(Debug, Clone)]
pub struct BeamModel {
    /// Element family of the FE mesh (of the mesh a `modal` basis is taken
    /// from; for `galerkin`, the family the section would use).
    pub family: Family,
    /// Number of elements N of the FE mesh (0 for `galerkin`: no mesh).
    pub elements: usize,
    /// Span L, m.
    pub length: f64,
    /// The shortest length the discretization resolves, m: the shortest
    /// element (h = L/N on a uniform mesh), or for a modal basis of J
    /// modes the larger of that and the half-wavelength L/J of its last
    /// mode (what a support-arrival or resolution check compares with).
    pub h: f64,
    /// The FE mesh (a one-element placeholder for `galerkin`).
    pub mesh: Mesh,
    /// For each node-local dof of the contact wire (node·dofs_per_node +
    /// local), its global index or `None` when a support removes it (the FE
    /// dofs).
    pub dof_of: Vec<Option<usize>>,
    /// The same for the messenger wire (`[messenger]`; empty without it).
    /// With a messenger the global unknowns are interleaved node by node:
    /// contact w, θ, messenger w, θ (Hermite), or contact w, messenger w
    /// (string), supported dofs skipped (`docs/lines.md` eq. W1).
    pub messenger_dof_of: Vec<Option<usize>>,
    /// Number of unknowns n (FE dofs, or J modes).
    pub n: usize,
    /// Global mass matrix M, kg (and kg·m² on rotations; the identity in a
    /// mass-normalized modal basis).
    pub mass: SymBand,
    /// Global stiffness K = K_B + K_T, N/m (diag ω_j² in a modal basis).
    pub stiffness: SymBand,
    /// Consistent load vector of the distributed load p, N.
    pub load: Vec<f64>,
    /// What the unknowns are.
    pub basis: Basis,
}

impl BeamModel {
    /// Assemble the beam for `props` on `elements` equal elements.
    pub fn new(props: &BeamProps, elements: usize) -> Self {
        Self::on_mesh(props, Mesh::uniform(props.length, elements))
    }

    /// The beam `props` discretized as `plan` says (`[mesh]`, MODEL §9.2):
    /// Hermite elements on a uniform or graded mesh, or a modal or Galerkin
    /// basis. The modal bases are computed here, once per run.
    pub fn build(props: &BeamProps, plan: &MeshPlan) -> Result<Self> {
        let mesh = || Mesh::new(props.length, plan.elements, plan.grading);
        match plan.discretization {
            Discretization::Hermite => Ok(Self::on_mesh(props, mesh()?)),
            Discretization::Modal { modes } => Self::modal(Self::on_mesh(props, mesh()?), modes),
            Discretization::Galerkin { modes } => Self::galerkin(props, modes),
        }
    }

    /// Assemble the finite elements on a mesh: the contact wire, and with a
    /// `[messenger]` both lines interleaved node by node
    /// ([`BeamModel::on_mesh`]'s layout, `docs/lines.md` eq. W1).
    pub fn on_mesh(props: &BeamProps, mesh: Mesh) -> Self {
        let elements = mesh.elements();
        let family = if props.is_string() {
            Family::String
        } else {
            Family::Hermite
        };
        let per_node = match family {
            Family::Hermite => 2,
            Family::String => 1,
        };
        // lines per node: the contact wire's dofs first, then the messenger's
        let lines = if props.messenger.is_some() { 2 } else { 1 };
        let nodes = elements + 1;
        let stride = lines * per_node;
        let mut removed = vec![false; nodes * stride];
        for (node, support) in [(0, props.left), (elements, props.right)] {
            match support {
                Support::Clamped => {
                    removed[node * stride] = true;
                    // a deliberate defect of the test build (`crate::defects`)
                    let free = crate::defects::on(crate::defects::Defect::ClampedRotationFree);
                    if per_node == 2 && !free {
                        removed[node * stride + 1] = true;
                    }
                }
                Support::Pinned => removed[node * stride] = true,
                Support::Free => {}
            }
        }
        if let Some(m) = &props.messenger {
            // pinned: the messenger's w at each support's node (W3); an
            // elastic support keeps it (a spring there, E1)
            for x in m.pinned() {
                removed[nearest_node(&mesh, x) * stride + per_node] = true;
            }
        }
        let mut n = 0;
        let global: Vec<Option<usize>> = removed
            .iter()
            .map(|&r| {
                if r {
                    None
                } else {
                    n += 1;
                    Some(n - 1)
                }
            })
            .collect();
        // the contact wire's node-local dofs (node·per_node + local), and
        // the messenger's, each to its global index
        let line_of = |line: usize| -> Vec<Option<usize>> {
            (0..nodes * per_node)
                .map(|k| global[(k / per_node) * stride + line * per_node + k % per_node])
                .collect()
        };
        let dof_of = line_of(0);
        let messenger_dof_of = if lines == 2 { line_of(1) } else { Vec::new() };
        // half-bandwidth: an element couples its nodes' dofs (3 Hermite, 1
        // string); with two lines a tie between nodes couples a node's
        // contact w with the next node's last messenger dof (7 Hermite, 3
        // string, eq. W5)
        let p = match (family, lines) {
            (Family::Hermite, 1) => 3,
            (Family::String, 1) => 1,
            (Family::Hermite, _) => 7,
            (Family::String, _) => 3,
        };
        let mut mass = SymBand::zeros(n, p);
        let mut stiffness = SymBand::zeros(n, p);
        let mut load = vec![0.0; n];
        let contact = LineProps {
            rho_a: props.rho_a,
            ei: props.ei,
            tension: props.tension,
            load: props.distributed_load,
        };
        let mut assemble = |line: &LineProps, map: &[Option<usize>]| {
            for e in 0..elements {
                let h = mesh.element_length(e);
                let w = line.load;
                match family {
                    Family::Hermite => {
                        let me = element::hermite_mass(line.rho_a, h);
                        let ke = element::hermite_bending(line.ei, h)
                            + element::hermite_tension(line.tension, h);
                        let fe = element::hermite_uniform_load(w, h);
                        let dofs: [Option<usize>; 4] = std::array::from_fn(|k| map[2 * e + k]);
                        scatter(
                            &mut mass,
                            &mut stiffness,
                            &mut load,
                            &dofs,
                            &me,
                            &ke,
                            fe.as_slice(),
                        );
                    }
                    Family::String => {
                        let me = element::string_mass(line.rho_a, h);
                        let ke = element::string_stiffness(line.tension, h);
                        let fe = element::string_uniform_load(w, h);
                        let dofs: [Option<usize>; 2] = [map[e], map[e + 1]];
                        scatter(
                            &mut mass,
                            &mut stiffness,
                            &mut load,
                            &dofs,
                            &me,
                            &ke,
                            fe.as_slice(),
                        );
                    }
                }
            }
        };
        assemble(&contact, &dof_of);
        if let Some(m) = &props.messenger {
            let line = LineProps {
                rho_a: m.rho_a,
                ei: m.ei,
                tension: m.tension,
                load: m.distributed_load,
            };
            assemble(&line, &messenger_dof_of);
        }
        let mut model = BeamModel {
            family,
            elements,
            length: props.length,
            h: mesh.h_min(),
            mesh,
            dof_of,
            messenger_dof_of,
            n,
            mass,
            stiffness,
            load,
            basis: Basis::Elements,
        };
        model.attach(&props.attachments, Self::element_pairs);
        if let Some(m) = &props.messenger {
            model.tie(&m.ties);
            model.attach(&m.attachments, Self::messenger_pairs);
        }
        model
    }

    /// Add the linear messenger droppers' springs (eq. W4): k_d r_d r_dᵀ to
    /// K with r_d = r_c(x_d) − r_m(x_d), the contact wire's point vector
    /// minus the messenger's. At a node r_d is that node's contact w minus
    /// its messenger w (two entries two apart); between nodes, both
    /// elements' shape functions (eight entries, within the band 7).
    fn tie(&mut self, ties: &[(f64, f64)]) {
        for &(x, k) in ties {
            let r = self.tie_vector(x);
            self.stiffness.add_outer(&r, k);
        }
    }

    /// r_d = r_c(x) − r_m(x) of a link between the two lines at x (eq. W4)
    /// as (index, value) pairs: the contact wire's element vector, then
    /// the messenger's negated.
    pub(super) fn tie_vector(&self, x: f64) -> [(usize, f64); 8] {
        let (ci, cv) = self.element_vector(x, false);
        let (mi, mv) = self.messenger_element_vector(x, false);
        let mut r = [(0usize, 0.0f64); 8];
        for (k, e) in r.iter_mut().enumerate() {
            *e = if k < 4 {
                (ci[k], cv[k])
            } else {
                (mi[k - 4], -mv[k - 4])
            };
        }
        r
    }

    /// The element vector r_b(x) as (index, value) pairs.
    pub(super) fn element_pairs(&self, x: f64) -> [(usize, f64); 4] {
        let (idx, val) = self.element_vector(x, false);
        [0, 1, 2, 3].map(|k| (idx[k], val[k]))
    }

    /// Add the point attachments (MODEL §10): `k_a r_a r_aᵀ` to K and
    /// `m_a r_a r_aᵀ` to M, r_a = r_b(x_a) the interpolation vector at x_a
    /// (MODEL §4). Between nodes r_a is the cubic Hermite shape functions of
    /// the element holding x_a on its four dofs (w, θ at both ends; the
    /// linear ones on its two w dofs for a string), so the attachment
    /// couples only dofs one element already couples and the band is
    /// unchanged; at a node it is that node's w dof alone (the other shape
    /// functions vanish there). Supported dofs carry weight 0. The
    /// messenger's attachments (its elastic supports, eq. E1, and dropper
    /// clamps) are the same with r_m(x), its interpolation vector
    /// ([`BeamModel::messenger_pairs`]), as `vector`.
    fn attach(&mut self, attachments: &[Attachment], vector: fn(&Self, f64) -> [(usize, f64); 4]) {
        for a in attachments {
            let r = vector(self, a.x);
            self.stiffness.add_outer(&r, a.stiffness);
            self.mass.add_outer(&r, a.mass);
        }
    }

    /// The messenger's element vector r_m(x) as (index, value) pairs.
    pub(super) fn messenger_pairs(&self, x: f64) -> [(usize, f64); 4] {
        let (idx, val) = self.messenger_element_vector(x, false);
        [0, 1, 2, 3].map(|k| (idx[k], val[k]))
    }

    /// FE modal truncation (MODEL §9.2): the J lowest eigenpairs of the
    /// assembled (K, M), mass-normalized ([`super::eigen`]), as the basis.
    pub fn modal(fe: BeamModel, modes: usize) -> Result<Self> {
        let pairs = super::eigen::lowest_eigenpairs(&fe.mass, &fe.stiffness, modes)?;
        let (n_fe, j) = (fe.n, modes);
        // Φ row-major: a point vector sums four rows of it
        let mut shapes = vec![0.0; n_fe * j];
        for col in 0..j {
            for i in 0..n_fe {
                shapes[i * j + col] = pairs.shapes[col * n_fe + i];
            }
        }
        let mut load = vec![0.0; j];
        for (i, f) in fe.load.iter().enumerate() {
            for (l, phi) in load.iter_mut().zip(&shapes[i * j..(i + 1) * j]) {
                *l += phi * f;
            }
        }
        let h = fe.h.max(fe.length / j as f64);
        Ok(BeamModel {
            n: j,
            h,
            mass: diagonal(&vec![1.0; j]),
            // a free end's rigid modes have ω² = 0; the solve returns them
            // as ±round-off (≈ n·ε·ω_max²): a negative one is that round-off
            stiffness: diagonal(
                &pairs
                    .omega_sq
                    .iter()
                    .map(|w| w.max(0.0))
                    .collect::<Vec<_>>(),
            ),
            load,
            basis: Basis::Modal { shapes, modes: j },
            ..fe
        })
    }

    /// The analytic-mode Galerkin basis (MODEL §9.2): the J exact modes of
    /// the continuous beam, mass-normalized; no finite element on its path.
    pub fn galerkin(props: &BeamProps, modes: usize) -> Result<Self> {
        let shapes = ModeShapes::new(props, modes)?;
        let omega_sq: Vec<f64> = shapes.omega().iter().map(|w| w * w).collect();
        let load = shapes.uniform_load(props.distributed_load);
        Ok(BeamModel {
            family: if props.is_string() {
                Family::String
            } else {
                Family::Hermite
            },
            elements: 0,
            length: props.length,
            h: props.length / modes as f64,
            mesh: Mesh::uniform(props.length, 1),
            dof_of: Vec::new(),
            messenger_dof_of: Vec::new(),
            n: modes,
            mass: diagonal(&vec![1.0; modes]),
            stiffness: diagonal(&omega_sq),
            load,
            basis: Basis::Galerkin(shapes),
        })
    }

    /// Half-bandwidth of M and K (0 in a modal basis).
    pub fn bandwidth(&self) -> usize {
        self.mass.bandwidth()
    }

    /// The element holding x and the local coordinate s ∈ [0, 1].
    pub fn locate(&self, x: f64) -> (usize, f64) {
        self.mesh.locate(x)
    }

    /// r_b(x): beam displacement v(x) = r_b(x)ᵀ d (MODEL §4).
    pub fn point_vector(&self, x: f64) -> PointVector {
        let mut pv = PointVector::default();
        self.point_vector_into(x, false, &mut pv);
        pv
    }

    /// r_b'(x): beam slope v'(x) = r_b'(x)ᵀ d (for the convective part of a
    /// moving contact's gap rate, V·v'(x_m)).
    pub fn slope_vector(&self, x: f64) -> PointVector {
        let mut pv = PointVector::default();
        self.point_vector_into(x, true, &mut pv);
        pv
    }

    /// r_b(x), or r_b'(x) when `slope`, into `pv`, reusing its buffer: no
    /// allocation once `pv` has held a vector of this basis.
    pub fn point_vector_into(&self, x: f64, slope: bool, pv: &mut PointVector) {
        match &self.basis {
            Basis::Elements => {
                pv.dense.clear();
                let (idx, val) = self.element_vector(x, slope);
                pv.idx = idx;
                pv.val = val;
            }
            Basis::Modal { shapes, modes } => {
                let (idx, val) = self.element_vector(x, slope);
                modal_rows(shapes, *modes, idx, val, pv);
            }
            Basis::Galerkin(modes) => {
                pv.idx = [0; 4];
                pv.val = [0.0; 4];
                pv.dense.resize(modes.count(), 0.0);
                if slope {
                    modes.slopes_into(x, &mut pv.dense);
                } else {
                    modes.values_into(x, &mut pv.dense);
                }
            }
        }
    }

    /// The FE shape functions (or their slopes) of the element holding x,
    /// on the contact wire's dofs.
    pub(super) fn element_vector(&self, x: f64, slope: bool) -> ([usize; 4], [f64; 4]) {
        self.element_vector_on(&self.dof_of, x, slope)
    }

    /// As [`BeamModel::element_vector`], on the messenger's dofs.
    pub(crate) fn messenger_element_vector(&self, x: f64, slope: bool) -> ([usize; 4], [f64; 4]) {
        self.element_vector_on(&self.messenger_dof_of, x, slope)
    }

    /// True when the model carries a messenger wire (`[messenger]`).
    pub fn has_messenger(&self) -> bool {
        !self.messenger_dof_of.is_empty()
    }

    /// r_m(x): the messenger's displacement v_m(x) = r_m(x)ᵀ d (eq. W1),
    /// on a mesh with a messenger (panics otherwise: a caller asks only when
    /// [`BeamModel::has_messenger`]).
    pub fn messenger_point_vector(&self, x: f64) -> PointVector {
        assert!(self.has_messenger(), "the model has no messenger wire");
        let (idx, val) = self.messenger_element_vector(x, false);
        match &self.basis {
            Basis::Elements => PointVector {
                idx,
                val,
                dense: AlignedLanes::default(),
            },
            // the modes of the two-line model (`BeamModel::modal`): Φᵀ of
            // the messenger's FE point vector, as on the contact wire
            Basis::Modal { shapes, modes } => {
                let mut pv = PointVector::default();
                modal_rows(shapes, *modes, idx, val, &mut pv);
                pv
            }
            Basis::Galerkin(_) => {
                unreachable!("a Galerkin basis with a messenger is refused by resolve::messenger")
            }
        }
    }

    /// The shape functions (or slopes) of the element holding x on the
    /// line whose node-local dofs map through `map`.
    fn element_vector_on(
        &self,
        map: &[Option<usize>],
        x: f64,
        slope: bool,
    ) -> ([usize; 4], [f64; 4]) {
        let (e, s) = self.locate(x);
        let h = self.mesh.element_length(e);
        let (mut idx, mut val) = ([0usize; 4], [0.0; 4]);
        match self.family {
            Family::Hermite => {
                let n = if slope {
                    element::hermite_slope(s, h)
                } else {
                    element::hermite_shape(s, h)
                };
                for k in 0..4 {
                    if let Some(i) = map[2 * e + k] {
                        idx[k] = i;
                        val[k] = n[k];
                    }
                }
            }
            Family::String => {
                let n = if slope {
                    [-1.0 / h, 1.0 / h]
                } else {
                    element::string_shape(s)
                };
                for k in 0..2 {
                    if let Some(i) = map[e + k] {
                        idx[k] = i;
                        val[k] = n[k];
                    }
                }
            }
        }
        (idx, val)
    }

    /// An upper bound of the model's highest natural frequency ω_max, rad/s:
    /// the element-eigenvalue bound at the shortest element on a mesh, the
    /// exact ω_J in a modal basis (K and M diagonal).
    ///
    /// With a `[messenger]` each line is bounded on its own elements and
    /// the larger taken: a tie `k r rᵀ`, `r = r_c − r_m` (a linear
    /// messenger dropper, `docs/lines.md` eq. W4), is at most
    /// `2k (r_c r_cᵀ + r_m r_mᵀ)` in the Loewner order (`(a − b)(a − b)ᵀ ≤
    /// 2(aaᵀ + bbᵀ)`), i.e. a grounded spring of 2k on each line at the
    /// dropper, so the two-line K is below a block-diagonal one whose
    /// lines Irons' bound covers, and the messenger's pinned supports only
    /// lower ω_max (a constraint).
    pub fn omega_bound(&self, props: &BeamProps) -> f64 {
        match self.basis {
            Basis::Elements => {
                let doubled: Vec<(f64, f64, f64)> = props
                    .messenger
                    .iter()
                    .flat_map(|m| m.ties.iter().map(|&(x, k)| (x, 2.0 * k, 0.0)))
                    .collect();
                let contact: Vec<(f64, f64, f64)> = props
                    .attachments
                    .iter()
                    .map(|a| (a.x, a.stiffness, a.mass))
                    .chain(doubled.iter().copied())
                    .collect();
                let line = |rho_a: f64, ei: f64, tension: f64, held: &[(f64, f64, f64)]| {
                    let bare = super::element::omega_max(rho_a, ei, tension, self.h);
                    self.attached_bound((rho_a, ei, tension), held).max(bare)
                };
                let wire = line(props.rho_a, props.ei, props.tension, &contact);
                match &props.messenger {
                    Some(m) => {
                        // its own attachments (elastic supports, clamps)
                        // are grounded springs and masses on its elements
                        let held: Vec<(f64, f64, f64)> = doubled
                            .iter()
                            .copied()
                            .chain(m.attachments.iter().map(|a| (a.x, a.stiffness, a.mass)))
                            .collect();
                        wire.max(line(m.rho_a, m.ei, m.tension, &held))
                    }
                    None => wire,
                }
            }
            _ => (0..self.n)
                .map(|j| (self.stiffness.get(j, j) / self.mass.get(j, j)).sqrt())
                .fold(0.0, f64::max),
        }
    }
}

impl BeamModel {
    /// The element bound of the elements of one line (ρA, EI, T) that hold
    /// point attachments `(x, k, m)` ([`super::element::omega_max_attached`],
    /// each counted in the element [`BeamModel::locate`] puts it in), rad/s;
    /// 0 without any. The other elements are bounded by the shortest one's.
    fn attached_bound(
        &self,
        (rho_a, ei, tension): (f64, f64, f64),
        held: &[(f64, f64, f64)],
    ) -> f64 {
        let mut held: Vec<(usize, (f64, f64, f64))> = held
            .iter()
            .map(|&(x, k, m)| {
                let (e, s) = self.locate(x);
                (e, (s, k, m))
            })
            .collect();
        held.sort_by_key(|(e, _)| *e);
        held.chunk_by(|a, b| a.0 == b.0)
            .map(|group| {
                let at: Vec<(f64, f64, f64)> = group.iter().map(|(_, v)| *v).collect();
                let h = self.mesh.element_length(group[0].0);
                super::element::omega_max_attached(rho_a, ei, tension, h, &at)
            })
            .fold(0.0, f64::max)
    }
}

/// A modal basis's point vector Φᵀr of the FE point vector (`idx`, `val`)
/// into `pv`'s dense weights: the sum of Φ's rows (`shapes`, row-major,
/// `modes` columns) weighted by the element's shape functions.
fn modal_rows(shapes: &[f64], modes: usize, idx: [usize; 4], val: [f64; 4], pv: &mut PointVector) {
    pv.idx = [0; 4];
    pv.val = [0.0; 4];
    pv.dense.clear();
    pv.dense.resize(modes, 0.0);
    for (i, w) in idx.into_iter().zip(val) {
        if w != 0.0 {
            let row = &shapes[i * modes..(i + 1) * modes];
            for (r, phi) in pv.dense.iter_mut().zip(row) {
                *r += w * phi;
            }
        }
    }
}

/// One line's section properties for the element assembly.
struct LineProps {
    /// ρA, kg/m.
    rho_a: f64,
    /// EI, N·m².
    ei: f64,
    /// T, N.
    tension: f64,
    /// Distributed load p, N/m.
    load: f64,
}

/// The node nearest x (a messenger support, checked on a node by
/// `resolve::messenger`).
fn nearest_node(mesh: &Mesh, x: f64) -> usize {
    let (e, s) = mesh.locate(x);
    if s < 0.5 { e } else { e + 1 }
}

/// A diagonal matrix as a band of half-bandwidth 0.
fn diagonal(d: &[f64]) -> SymBand {
    let mut m = SymBand::zeros(d.len(), 0);
    for (i, v) in d.iter().enumerate() {
        m.add_entry(i, i, *v);
    }
    m
}

/// Add one element's matrices and load into the global band.
fn scatter<const D: usize>(
    mass: &mut SymBand,
    stiffness: &mut SymBand,
    load: &mut [f64],
    dofs: &[Option<usize>; D],
    me: &nalgebra::SMatrix<f64, D, D>,
    ke: &nalgebra::SMatrix<f64, D, D>,
    fe: &[f64],
) {
    for a in 0..D {
        let Some(i) = dofs[a] else { continue };
        load[i] += fe[a];
        for b in 0..D {
            let Some(j) = dofs[b] else { continue };
            mass.add_entry(i, j, me[(a, b)]);
            stiffness.add_entry(i, j, ke[(a, b)]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::banded::BandedLdlt;

    fn props(ei: f64, left: Support, right: Support) -> BeamProps {
        BeamProps {
            length: 2.0,
            rho_a: 1.5,
            ei,
            ea: None,
            tension: 10.0,
            left,
            right,
            distributed_load: 0.0,
            attachments: Vec::new(),
            messenger: None,
        }
    }

    #[test]
    fn supports_remove_the_right_dofs() {
        let b = BeamModel::new(&props(1.0, Support::Clamped, Support::Pinned), 4);
        assert_eq!(b.n, 10 - 3);
        let b = BeamModel::new(&props(1.0, Support::Free, Support::Free), 4);
        assert_eq!(b.n, 10);
        let s = BeamModel::new(&props(0.0, Support::Pinned, Support::Pinned), 4);
        assert_eq!(s.n, 3);
        assert_eq!(s.bandwidth(), 1);
    }

    #[test]
    fn global_mass_carries_the_beam_mass() {
        // a free–free beam: 1ᵀ M 1 over the translation dofs = ρA L
        let b = BeamModel::new(&props(1.0, Support::Free, Support::Free), 7);
        let ones: Vec<f64> = (0..b.n)
            .map(|i| if i % 2 == 0 { 1.0 } else { 0.0 })
            .collect();
        let mut y = vec![0.0; b.n];
        b.mass.mul_acc(&ones, 1.0, &mut y);
        let total: f64 = ones.iter().zip(&y).map(|(a, b)| a * b).sum();
        assert!((total - 3.0).abs() < 1e-12);
    }

    #[test]
    fn supported_stiffness_is_positive_definite() {
        for (l, r) in [
            (Support::Clamped, Support::Pinned),
            (Support::Clamped, Support::Free),
            (Support::Pinned, Support::Pinned),
        ] {
            let b = BeamModel::new(&props(1.0, l, r), 6);
            assert!(BandedLdlt::factor(&b.stiffness).is_ok(), "{l:?}-{r:?}");
        }
    }

    #[test]
    fn point_vector_interpolates_nodal_values() {
        let b = BeamModel::new(&props(1.0, Support::Pinned, Support::Pinned), 5);
        // v(x) = x(L − x) has nodal values and slopes; Hermite cubics hold it exactly
        let l = b.length;
        let mut d = vec![0.0; b.n];
        for node in 0..=5 {
            let x = node as f64 * b.h;
            if let Some(i) = b.dof_of[2 * node] {
                d[i] = x * (l - x);
            }
            if let Some(i) = b.dof_of[2 * node + 1] {
                d[i] = l - 2.0 * x;
            }
        }
        for k in 0..=40 {
            let x = k as f64 * l / 40.0;
            assert!((b.point_vector(x).dot(&d) - x * (l - x)).abs() < 1e-13);
        }
    }
}
