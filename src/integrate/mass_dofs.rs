//! The carriers' mass degrees of freedom during a run (MODEL §2, §10): one
//! body a contact, a single mass–spring or a multi-mass pantograph
//! (`chain.rs`) whose head is the contact's dof, with the forces on them —
//! the constant spring preload and gravity, a manufactured mass source
//! (MODEL §11) and external forces (`external_force.rs`).
//!
//! This is the physics; how a method steps it is `mass_step.rs`, one rule
//! a method for every body. The contact problem sees each body through
//! its head ([`MassDof`]: `m q̈ + c q̇ + k q = f0 − λ` for a single mass; a
//! chain's head with its static contact force as `f0`, its dynamic
//! stiffness through the method's effective matrix). The droppers are not
//! mass dofs: they are the beam's (linear ones springs in K, tension-only
//! ones rows of the contact problem, `dropper.rs`).

use crate::manufactured::Manufactured;
use crate::resolve::Resolved;
use crate::scene::CarrierKind;

use super::carrier::Carrier;
use super::chain::Chain;
use super::chain_load::ChainLoad;
use super::external_force::ExternalForces;

/// A mass–spring carrier's mass dof: `m q̈ + c q̇ + k q = f0 − λ` (MODEL §2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassDof {
    /// Mass m, kg.
    pub m: f64,
    /// Spring stiffness k, N/m.
    pub k: f64,
    /// Dashpot c_s, N·s/m.
    pub c: f64,
    /// Constant force on q: k δ0 − s m g, N (MODEL §2), with the external
    /// force and mass source at the step's load time.
    pub f0: f64,
}

/// The mass dofs of a run's contacts (module docs).
#[derive(Debug, Clone)]
pub(crate) struct MassDofs {
    /// Each contact's dof as the contact problem sees it: a single mass,
    /// or a chain's head (its f0 the chain's static contact force λ₀).
    pub(crate) heads: Vec<MassDof>,
    /// The multi-mass pantograph of each contact (`None`: a single mass).
    pub(crate) chains: Vec<Option<Chain>>,
    /// Each head's constant force without a mass source or external force,
    /// N: k δ0 − s m g, or λ₀ of a chain.
    base: Vec<f64>,
    /// Each contact's side sign s.
    side: Vec<f64>,
    /// Each contact's carrier (its index in the scene).
    carrier: Vec<usize>,
    /// External forces on the heads; `None` costs a branch per step.
    external: Option<ExternalForces>,
    /// The time-dependent forces of the chains that have any
    /// (`chain_load.rs`: an aerodynamic uplift, a series on a mass), with
    /// their contact index; empty for constant-uplift chains.
    chain_loads: Vec<(usize, ChainLoad)>,
}

impl MassDofs {
    /// The mass dofs of `carriers` (their contacts numbered in carrier
    /// order) for the scene `sc`; the heads' f0 at t = 0.
    pub(crate) fn new(sc: &Resolved, carriers: &[Carrier]) -> Self {
        let mut heads = Vec::new();
        let mut chains = Vec::new();
        let mut side = Vec::new();
        let mut carrier = Vec::new();
        let mut chain_loads = Vec::new();
        for (i, c) in carriers.iter().enumerate() {
            let CarrierKind::MassSpring {
                mass,
                stiffness,
                damping,
                preload,
            } = c.props.kind
            else {
                continue;
            };
            debug_assert_eq!(c.contact, Some(heads.len()), "contacts in carrier order");
            // a multi-mass pantograph: its head as the mass dof, with the
            // static contact force as its f0 (chain.rs: the chain starts at
            // rest in its static state, so at t = 0 only the head's balance
            // with λ differs from it)
            // its time-dependent forces (chain_load.rs) enter its static
            // state at their t = 0 values; a chain without any keeps the
            // constant uplift's arithmetic
            let series = sc.external_forces[i].as_ref();
            let chain = c.props.chain.map(|p| {
                match ChainLoad::initial_forces(&p, &c.props.motion, series, c.s) {
                    Some(extra) => {
                        let ch = Chain::loaded(&p, c.s, sc.g, &extra);
                        let load = ChainLoad::new(&ch, &p, &c.props.motion, series, c.s);
                        chain_loads.push((heads.len(), load));
                        ch
                    }
                    None => Chain::new(&p, c.s, sc.g),
                }
            });
            let f0 = match &chain {
                Some(ch) => ch.static_force,
                None => stiffness * preload - c.s * mass * sc.g,
            };
            // a deliberate defect of the test build (`crate::defects`): a
            // single mass's dashpot at half its c_s
            let half = chain.is_none() && crate::defects::on(crate::defects::Defect::HalfDashpot);
            heads.push(MassDof {
                m: mass,
                k: stiffness,
                c: if half { 0.5 * damping } else { damping },
                f0,
            });
            chains.push(chain);
            side.push(c.s);
            carrier.push(i);
        }
        let nc = heads.len();
        let base = heads.iter().map(|m| m.f0).collect();
        let mut dofs = MassDofs {
            heads,
            chains,
            base,
            side,
            carrier,
            external: None,
            chain_loads,
        };
        // a chain's series is its ChainLoad's, the single masses' are here
        let single_series = |j: usize| {
            let i = dofs.carrier[j];
            sc.external_forces[i]
                .as_ref()
                .filter(|_| dofs.chains[j].is_none())
        };
        if (0..nc).any(|j| single_series(j).is_some()) {
            let mut ext = ExternalForces::new(nc);
            for j in 0..nc {
                ext.series[j] = single_series(j).cloned();
            }
            // the initial state's accelerations see the force at t = 0
            for (j, m) in dofs.heads.iter_mut().enumerate() {
                m.f0 = dofs.base[j] + dofs.side[j] * ext.force(j, 0.0);
            }
            dofs.external = Some(ext);
        }
        dofs
    }

    /// Number of contacts.
    pub(crate) fn len(&self) -> usize {
        self.heads.len()
    }

    /// True when some contact is a multi-mass pantograph.
    pub(crate) fn has_chains(&self) -> bool {
        self.chains.iter().any(Option::is_some)
    }

    /// True when the run has external forces (a series, or a held force).
    pub(crate) fn has_external_force(&self) -> bool {
        self.external.is_some()
    }

    /// Each head's f0 at the load time `t` of a step: its constant force,
    /// plus the external force (`external_force.rs`: `s·F_ext(t)`) and a
    /// manufactured mass source (MODEL §11) at `t`; a chain's f₀ with its
    /// time-dependent forces (`chain_load.rs`). Untouched when the run has
    /// none (the constant force stands).
    pub(crate) fn set_load_time(&mut self, t: f64, source: Option<&Manufactured>) {
        for (j, load) in &self.chain_loads {
            if let Some(ch) = &mut self.chains[*j] {
                self.heads[*j].f0 = load.apply(t, ch);
            }
        }
        if let Some(ext) = &self.external {
            for (j, m) in self.heads.iter_mut().enumerate() {
                if self.chains[j].is_some() {
                    continue;
                }
                let s = source.map_or(0.0, |src| src.mass_source(self.carrier[j], t));
                m.f0 = self.base[j] + self.side[j] * ext.force(j, t) + s;
            }
            return;
        }
        let Some(src) = source else { return };
        for (j, m) in self.heads.iter_mut().enumerate() {
            m.f0 = self.base[j] + src.mass_source(self.carrier[j], t);
        }
    }

    /// Hold `newtons` (in +v, MODEL §2) on contact `j`'s mass from the next
    /// step on, until changed, on top of its series if any. Allocates the
    /// first time only.
    pub(crate) fn hold_external_force(&mut self, j: usize, newtons: f64) {
        let nc = self.heads.len();
        self.external
            .get_or_insert_with(|| ExternalForces::new(nc))
            .held[j] = newtons;
    }

    /// The force held on contact `j`'s mass, N in +v; 0 when none.
    pub(crate) fn held_external_force(&self, j: usize) -> f64 {
        self.external.as_ref().map_or(0.0, |e| e.held[j])
    }
}

#[cfg(test)]
impl MassDofs {
    /// One contact, the chain `chain` alone (no external force): for the
    /// checks of its step (`chain_steps.rs`).
    pub(crate) fn of_chain(chain: Chain) -> Self {
        let head = MassDof {
            m: chain.m[0],
            k: chain.k[0][0],
            c: chain.c[0][0],
            f0: chain.f0[0],
        };
        MassDofs {
            heads: vec![head],
            chains: vec![Some(chain)],
            base: vec![head.f0],
            side: vec![1.0],
            carrier: vec![0],
            external: None,
            chain_loads: Vec::new(),
        }
    }
}
