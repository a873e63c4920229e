//! A multi-mass pantograph carrier (MODEL §10, docs/lines.md P1–P4): two or
//! three masses in series, the head m₁ in contact with the wire, spring
//! k_i and dashpot c_i between m_i and m_{i+1}, the last pair (k_n, c_n)
//! from the frame m_n to the roof, and the static uplift F₀ on m_n — the
//! lumped pantograph models of this field (EN 50318's reference pantograph
//! is a three-mass model of this shape).
//!
//! Scene keys on `[[carrier]]`: `masses = [m₁, …]` (head first),
//! `stiffnesses = [k₁, …]`, `dampings = [c₁, …]` (default all 0) and
//! `uplift = F₀` (N, default 0). They replace `mass`, `stiffness`,
//! `damping`, `preload` (and `force`): a scene gives one kind or the other.

use super::carrier::CarrierSpec;
use crate::error::{Error, Result};

/// Most masses a chain may have.
pub(crate) const MAX_CHAIN: usize = 3;

/// A resolved chain (`n` of the `MAX_CHAIN` slots used; the rest 0).
/// Plain numbers, `Copy` like the carrier it belongs to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainProps {
    /// Number of masses n (2 or 3).
    pub n: usize,
    /// m₁ (head, in contact) … m_n (frame), kg (> 0).
    pub masses: [f64; MAX_CHAIN],
    /// k₁ … k_n, N/m: k_i between m_i and m_{i+1} (> 0), k_n frame–roof (≥ 0).
    pub stiffnesses: [f64; MAX_CHAIN],
    /// c₁ … c_n, N·s/m (≥ 0), placed like the springs.
    pub dampings: [f64; MAX_CHAIN],
    /// Static uplift F₀ on m_n, N (≥ 0), pushing it toward the wire.
    pub uplift: f64,
}

impl ChainProps {
    /// m₁ … m_n, kg.
    pub fn masses(&self) -> &[f64] {
        &self.masses[..self.n]
    }

    /// k₁ … k_n, N/m.
    pub fn stiffnesses(&self) -> &[f64] {
        &self.stiffnesses[..self.n]
    }

    /// c₁ … c_n, N·s/m.
    pub fn dampings(&self) -> &[f64] {
        &self.dampings[..self.n]
    }

    /// Σ m_i, kg.
    pub fn total_mass(&self) -> f64 {
        self.masses().iter().sum()
    }
}

/// The chain keys of carrier `i` (field names `carrier.{i}.…`), if it has
/// any: `None` when `masses` is absent (and no other chain key is given).
/// The single-mass keys (`mass`, `stiffness`, `damping`, `preload`) and
/// `force` are refused alongside, naming both fields.
pub(crate) fn resolve_chain(i: usize, c: &CarrierSpec) -> Result<Option<ChainProps>> {
    let f = |name: &str| format!("carrier.{i}.{name}");
    let Some(masses) = &c.masses else {
        for (name, given) in [
            ("stiffnesses", c.stiffnesses.is_some()),
            ("dampings", c.dampings.is_some()),
            ("uplift", c.uplift.is_some()),
        ] {
            if given {
                return Err(Error::invalid(
                    f(name),
                    "given",
                    "belongs to a multi-mass carrier: give `masses` too, or remove it",
                ));
            }
        }
        return Ok(None);
    };
    for (name, v) in [
        ("mass", c.mass),
        ("stiffness", c.stiffness),
        ("damping", c.damping),
        ("preload", c.preload),
        ("force", c.force),
    ] {
        if let Some(v) = v {
            return Err(Error::invalid(
                f(name),
                v,
                "a multi-mass carrier (`masses` given) takes `stiffnesses`, `dampings` and \
                 `uplift` instead: remove it or remove `masses`",
            ));
        }
    }
    let n = masses.len();
    if !(2..=MAX_CHAIN).contains(&n) {
        return Err(Error::invalid(
            f("masses"),
            format!("{masses:?}"),
            format!("must list 2 to {MAX_CHAIN} masses, head first (kg); for one mass give `mass`"),
        ));
    }
    let stiffnesses = c.stiffnesses.as_ref().ok_or_else(|| {
        Error::invalid(
            f("stiffnesses"),
            "(missing)",
            format!("a multi-mass carrier needs {n} stiffnesses (N/m), one per mass"),
        )
    })?;
    let zeros = vec![0.0; n];
    let dampings = c.dampings.as_ref().unwrap_or(&zeros);
    for (name, list) in [("stiffnesses", stiffnesses), ("dampings", dampings)] {
        if list.len() != n {
            return Err(Error::invalid(
                f(name),
                format!("{list:?}"),
                format!("must list {n} values, one per mass (as `masses`)"),
            ));
        }
    }
    let mut p = ChainProps {
        n,
        masses: [0.0; MAX_CHAIN],
        stiffnesses: [0.0; MAX_CHAIN],
        dampings: [0.0; MAX_CHAIN],
        uplift: 0.0,
    };
    for j in 0..n {
        let (m, k, c_j) = (masses[j], stiffnesses[j], dampings[j]);
        if !(m.is_finite() && m > 0.0) {
            return Err(Error::invalid(
                f(&format!("masses.{j}")),
                m,
                "must be a finite number > 0 (kg)",
            ));
        }
        // k₁ … k_{n−1} hold the chain together (> 0); the roof spring may be 0
        let k_ok = k.is_finite() && if j + 1 < n { k > 0.0 } else { k >= 0.0 };
        if !k_ok {
            let allowed = if j + 1 < n {
                "must be a finite number > 0 (N/m): it joins mass {j} to the next"
            } else {
                "must be a finite number ≥ 0 (N/m): the frame's spring to the roof"
            };
            return Err(Error::invalid(
                f(&format!("stiffnesses.{j}")),
                k,
                allowed.replace("{j}", &(j + 1).to_string()),
            ));
        }
        if !(c_j.is_finite() && c_j >= 0.0) {
            return Err(Error::invalid(
                f(&format!("dampings.{j}")),
                c_j,
                "must be a finite number ≥ 0 (N·s/m)",
            ));
        }
        p.masses[j] = m;
        p.stiffnesses[j] = k;
        p.dampings[j] = c_j;
    }
    let uplift = c.uplift.unwrap_or(0.0);
    if !(uplift.is_finite() && uplift >= 0.0) {
        return Err(Error::invalid(
            f("uplift"),
            uplift,
            "must be a finite number ≥ 0 (N)",
        ));
    }
    p.uplift = uplift;
    Ok(Some(p))
}
