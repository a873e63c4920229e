//! A manufactured solution's smooth source in a discretization's basis
//! (MODEL §11): `p_s(x, t) = Σ_k c_k(t) S_k(x)` projected once per run,
//! `F_k = ∫ N S_k dx` for each separable part, so a step adds
//! `Σ_k c_k(t) F_k` to its load at the time its scheme prescribes in O(n K)
//! work and no allocation.
//!
//! The projection is a Gauss–Legendre quadrature well above any scheme's
//! order: on each element (Hermite or string), `POINTS` points on
//! sub-panels short enough that the source's fastest factor turns by at
//! most `PANEL_TURN` rad over one (so a coarse mesh under a fast shape
//! does not alias; on a resolved mesh one panel per element, exact for
//! polynomial shapes up to degree 12 against cubic shape functions); for a
//! `galerkin` basis, the modes' own composite rule
//! ([`crate::analytic::ModeShapes::quadrature`]) refined to the same panel
//! bound; for a `modal` basis, the FE vectors projected on the modes
//! (`Φᵀ F`).

use super::beam::{Basis, BeamModel, Family};
use super::element;
use crate::manufactured::{Line, Manufactured};
use crate::numeric::quadrature::{composite, gauss_legendre};

/// Gauss points per panel (exact for degree 15).
pub(crate) const POINTS: usize = 8;

/// Largest turn, rad, of the source's fastest factor over one panel.
pub(crate) const PANEL_TURN: f64 = 0.5;

/// Most separable parts a source has (three per term of
/// [`crate::scene::manufactured::MAX_TERMS`] on each of the two lines: T̂'',
/// T̂ and, with dashpots, T̂'; and the droppers' constant part): the
/// per-step coefficients live on the stack.
pub(crate) const MAX_PARTS: usize = 6 * crate::scene::manufactured::MAX_TERMS + 1;

/// The projected source of one run.
#[derive(Debug, Clone)]
pub(crate) struct Source {
    /// F, n × K row-major: row i holds unknown i's share of each part.
    shapes: Vec<f64>,
    parts: usize,
    solution: Manufactured,
}

impl Source {
    /// Project `m`'s smooth source on `beam`'s basis (module docs).
    pub fn new(beam: &BeamModel, m: &Manufactured) -> Self {
        let k = m.source_count();
        assert!(k <= MAX_PARTS, "at most {MAX_PARTS} source parts");
        let max_panel = PANEL_TURN / m.x_rate().max(f64::MIN_POSITIVE);
        let mut shapes = match &beam.basis {
            Basis::Elements => elements(beam, m, max_panel),
            Basis::Modal { shapes, modes } => {
                let fe = elements(beam, m, max_panel);
                let n_fe = fe.len() / k.max(1);
                let mut out = vec![0.0; modes * k];
                for i in 0..n_fe {
                    let phi = &shapes[i * modes..(i + 1) * modes];
                    for (j, p) in phi.iter().enumerate() {
                        for c in 0..k {
                            out[j * k + c] += p * fe[i * k + c];
                        }
                    }
                }
                out
            }
            Basis::Galerkin(modes) => {
                let n = modes.count();
                let mut out = vec![0.0; n * k];
                let mut phi = vec![0.0; n];
                let mut s = vec![0.0; k];
                let panel = max_panel.min(beam.length / 200.0);
                for (x, w) in modes.quadrature(panel) {
                    modes.values_into(x, &mut phi);
                    m.source_shapes(x, &mut s);
                    for (j, p) in phi.iter().enumerate() {
                        for c in 0..k {
                            out[j * k + c] += w * p * s[c];
                        }
                    }
                }
                out
            }
        };
        droppers(beam, m, &mut shapes);
        attachments(beam, m, &mut shapes);
        Source {
            shapes,
            parts: k,
            solution: m.clone(),
        }
    }

    /// The manufactured solution this source makes exact.
    pub fn solution(&self) -> &Manufactured {
        &self.solution
    }

    /// rhs[i·stride + col] += scale · Σ_k c_k(t) F_ik for every unknown i.
    #[inline]
    pub fn add_into(&self, t: f64, scale: f64, rhs: &mut [f64], stride: usize, col: usize) {
        let mut c = [0.0; MAX_PARTS];
        let k = self.parts;
        self.solution.source_coefficients(t, &mut c[..k]);
        for v in c[..k].iter_mut() {
            *v *= scale;
        }
        for (row, f) in self.shapes.chunks_exact(k).enumerate() {
            let mut acc = 0.0;
            for (a, b) in c[..k].iter().zip(f) {
                acc += a * b;
            }
            rhs[row * stride + col] += acc;
        }
    }
}

/// Each dropper's point load −N_d*(t) r_d in the basis (module docs of
/// [`crate::manufactured`]): its weights over the parts times r_d = r_c(x_d)
/// − r_m(x_d) on the messenger, r_c(x_d) on a fixed anchor, added to F.
fn droppers(beam: &BeamModel, m: &Manufactured, shapes: &mut [f64]) {
    let k = m.source_count();
    let mut w = vec![0.0; k];
    for d in 0..m.droppers() {
        let (x, on_messenger) = m.dropper_at(d);
        m.dropper_weights(d, &mut w);
        let rc = beam.point_vector(x);
        let rm = on_messenger.then(|| beam.messenger_point_vector(x));
        for (part, &wk) in w.iter().enumerate() {
            rc.scatter(wk, shapes, k, part);
            if let Some(rm) = &rm {
                rm.scatter(-wk, shapes, k, part);
            }
        }
    }
}

/// Each point attachment's load +(m_a v*_tt + c_a v*_t + k_a v*)(x_a, t) r_a
/// in the basis (`docs/verification.md` M4–M5): its weights over the parts
/// times r_a = r_b(x_a), the interpolation vector the model's attachment is
/// assembled with (`BeamModel::attach`), added to F. The load is exact at
/// x_a; the model's attachment acts on the interpolant r_aᵀd, so between
/// nodes the two differ by the elements' interpolation error.
fn attachments(beam: &BeamModel, m: &Manufactured, shapes: &mut [f64]) {
    let k = m.source_count();
    let mut w = vec![0.0; k];
    for a in 0..m.attachments() {
        m.attachment_weights(a, &mut w);
        let x = m.attachment_at(a);
        let ra = if m.attachment_on_messenger(a) {
            beam.messenger_point_vector(x)
        } else {
            beam.point_vector(x)
        };
        for (part, &wk) in w.iter().enumerate() {
            ra.scatter(wk, shapes, k, part);
        }
    }
}

/// F_k = ∫ N S_k dx on the FE mesh, n_fe × K row-major (module docs): each
/// line's parts on its own dofs.
fn elements(beam: &BeamModel, m: &Manufactured, max_panel: f64) -> Vec<f64> {
    let k = m.source_count();
    let n = match beam.basis {
        Basis::Elements => beam.n,
        // the FE model a modal basis was taken from: both lines' dofs
        _ => beam
            .dof_of
            .iter()
            .chain(&beam.messenger_dof_of)
            .flatten()
            .count(),
    };
    let mut out = vec![0.0; n * k];
    let mut lines = vec![(Line::Contact, &beam.dof_of)];
    if m.loads_messenger() && beam.has_messenger() {
        lines.push((Line::Messenger, &beam.messenger_dof_of));
    }
    for (line, dof_of) in lines {
        line_elements(beam, m, max_panel, line, dof_of, &mut out);
    }
    out
}

/// [`elements`] for one line.
fn line_elements(
    beam: &BeamModel,
    m: &Manufactured,
    max_panel: f64,
    line: Line,
    dof_of: &[Option<usize>],
    out: &mut [f64],
) {
    let k = m.source_count();
    let gl = gauss_legendre(POINTS);
    let mut s = vec![0.0; k];
    for e in 0..beam.mesh.elements() {
        let h = beam.mesh.element_length(e);
        let x0 = beam.mesh.node(e);
        let panels = (h / max_panel).ceil().max(1.0) as usize;
        let cuts: Vec<f64> = (0..=panels).map(|i| i as f64 / panels as f64).collect();
        for (u, w) in composite(&gl, &cuts) {
            m.source_shapes_on(line, x0 + u * h, &mut s);
            let wh = w * h;
            let (shape, dofs): ([f64; 4], usize) = match beam.family {
                Family::Hermite => (element::hermite_shape(u, h), 4),
                Family::String => {
                    let n2 = element::string_shape(u);
                    ([n2[0], n2[1], 0.0, 0.0], 2)
                }
            };
            let per_node = dofs / 2;
            for (a, na) in shape.iter().enumerate().take(dofs) {
                let Some(i) = dof_of[per_node * e + a] else {
                    continue;
                };
                for c in 0..k {
                    out[i * k + c] += wh * na * s[c];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::resolve::resolve_scene;

    /// A pinned–pinned beam with a one-term sine source: the Hermite load
    /// vector against the exact ∫N sin, and the galerkin one against the
    /// closed form of the modal load.
    const SCENE: &str = r#"
[beam]
length = 2.0
mass_per_length = 1.5
bending_stiffness = 4.0
tension = 60.0
left = "pinned"
right = "pinned"
[mesh]
elements = 8
[[carrier]]
force = 0.0
side = "below"
start = 0.0
speed = { profile = "constant", value = 0.0 }
[time]
step = 1e-3
end = 0.1
[[manufactured.term]]
amplitude = 1.0
x = [{ kind = "sine", half_waves = 1 }]
t = [{ kind = "polynomial", coefficients = [0, 0, 1] }]
"#;

    /// Quadrature of smooth integrands at 8 points per element: round-off.
    const QUAD: f64 = 1e-12;

    #[test]
    fn a_sine_source_projects_exactly() {
        use std::f64::consts::PI;
        let sc = resolve_scene(SCENE, &[]).unwrap();
        let m = sc.manufactured.as_ref().unwrap();
        let beam = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
        let src = Source::new(&beam, m);
        // at t: c = [a T̂'' = 2, a T̂ = t²]; check the ρA part alone (t = 0)
        let mut rhs = vec![0.0; beam.n];
        src.add_into(0.0, 1.0, &mut rhs, 1, 0);
        // Σ_i F_i d_i with d the nodal interpolant of sin(πx/L) is ∫ρA·2·sin·v_h:
        // check total against ∫ ρA 2 sin(πx/L) v_h dx where v_h interpolates sin
        let mut d = vec![0.0; beam.n];
        let l = 2.0;
        for node in 0..=8 {
            let x = node as f64 * l / 8.0;
            if let Some(i) = beam.dof_of[2 * node] {
                d[i] = (PI * x / l).sin();
            }
            if let Some(i) = beam.dof_of[2 * node + 1] {
                d[i] = PI / l * (PI * x / l).cos();
            }
        }
        let got: f64 = rhs.iter().zip(&d).map(|(a, b)| a * b).sum();
        // Hermite interpolation of sin is O(h⁴) off; ∫ 3 sin² = 3 L/2 = 3
        assert!((got - 3.0).abs() < 1e-3, "{got}");
        // galerkin: F_1 of ρA·2·sin against φ_1 = sqrt(2/(ρA L)) sin: 2ρA·sqrt(2/(ρA L))·L/2
        let g =
            resolve_scene(SCENE, &["mesh.kind=galerkin".into(), "mesh.modes=3".into()]).unwrap();
        let gb = BeamModel::build(&g.beam, &g.mesh_plan()).unwrap();
        let gs = Source::new(&gb, g.manufactured.as_ref().unwrap());
        let mut rhs = vec![0.0; 3];
        gs.add_into(0.0, 1.0, &mut rhs, 1, 0);
        let exact = 2.0 * 1.5 * (2.0 / (1.5 * l)).sqrt() * l / 2.0;
        assert!((rhs[0] - exact).abs() < QUAD * exact, "{rhs:?} {exact}");
        assert!(rhs[1].abs() < QUAD && rhs[2].abs() < QUAD, "{rhs:?}");
    }
}
