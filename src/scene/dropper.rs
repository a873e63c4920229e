//! `[[dropper]]`: tension-only links from the beam (the contact wire) to a
//! fixed anchor above it (MODEL §10, `docs/lines.md` eq. D1–D4). Plain data:
//! the scene's spelling ([`DropperSpec`]), each value's own range check,
//! and the resolved link ([`Dropper`]) the run is built from.
//!
//! Sign convention (MODEL §1: v positive up). The anchor sits at height
//! z_a (m, on the v axis: the undeformed beam line is z = 0) above the
//! wire, and the dropper's unstretched length is ℓ_0 (m). With the wire at
//! v(x_d) the dropper spans z_a − v(x_d), so its extension is
//!
//! ```text
//!   e = (z_a − v(x_d)) − ℓ_0          (m; > 0 stretched, ≤ 0 slack)
//! ```
//!
//! and it pulls the wire **up** (+v) with N_d = k_d·max(e, 0) ≥ 0. A wire
//! lifted by a pantograph (v grows) shortens e: the dropper goes slack when
//! v(x_d) ≥ z_a − ℓ_0. `linear = true` drops the max: N_d = k_d e, a
//! two-sided spring k_d to the anchor with a preload k_d (z_a − ℓ_0) (the
//! same as an `[[attachment]]` spring plus that constant force).
//!
//! The anchor is a fixed height or the messenger wire (`[messenger]`,
//! `docs/lines.md` eq. W2): e = (h_m + v_m(x_d) − v_c(x_d)) − ℓ_0, the force
//! pulling the contact wire up and the messenger down.

use serde::{Deserialize, Serialize};

use super::range::{non_negative, positive};
use crate::error::{Error, Result};

/// `[[dropper]]` as written in the scene.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DropperSpec {
    /// Position x_d on the beam, m (0 ≤ x_d ≤ L).
    pub x: f64,
    /// Stiffness k_d in tension, N/m (> 0).
    pub stiffness: f64,
    /// Height z_a of the fixed anchor above the undeformed beam line, m
    /// (finite; the v axis, positive up). Exactly one of this and `anchor`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anchor_height: Option<f64>,
    /// `"messenger"`: the upper end is on the messenger wire
    /// (`[messenger]`, eq. W2) instead of a fixed height.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anchor: Option<AnchorSpec>,
    /// Unstretched length ℓ_0, m (≥ 0). The dropper is stretched at the
    /// start (beam straight) by z_a − ℓ_0.
    pub length: f64,
    /// Dashpot c_d in parallel, N·s/m (finite, ≥ 0; default 0): c_d r_d r_dᵀ
    /// in the damping matrix C (`docs/lines.md` eq. D11), as an
    /// `[[attachment]]` dashpot; on a tension-only dropper a Kelvin–Voigt
    /// link N_d = max(0, k_d e + c_d ė) that slackens with its spring (D12).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// Never slack: a two-sided spring (N_d = k_d e, may push).
    #[serde(default, skip_serializing_if = "is_false")]
    pub linear: bool,
    /// A label for the outputs (`dropper_<name>_force`): letters, digits,
    /// `_` and `-`; default the dropper's index.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The contact wire's design height v_c(x_d) at rest, m (v axis, finite;
    /// default none): form-finding (`docs/lines.md` eq. F1–F5) then finds
    /// the dropper's `length` so that the line's static equilibrium puts the
    /// wire at this height, starting from the `length` given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design_height: Option<f64>,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// `anchor = "..."` as written: the line a dropper hangs from.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum AnchorSpec {
    /// The messenger wire (`[messenger]`).
    Messenger,
}

/// Where a dropper's upper end is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Anchor {
    /// A fixed point at height z_a, m (v axis).
    Fixed {
        /// z_a, m.
        height: f64,
    },
    /// The messenger wire at x_d, whose rest line is at h_m (m, v axis):
    /// e = (h_m + v_m(x_d) − v_c(x_d)) − ℓ_0 (`docs/lines.md` eq. W2).
    Messenger {
        /// h_m, m.
        height: f64,
    },
}

/// A dropper, resolved (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Dropper {
    /// Label for the outputs.
    pub name: String,
    /// Position x_d, m.
    pub x: f64,
    /// Stiffness k_d, N/m.
    pub stiffness: f64,
    /// Upper end.
    pub anchor: Anchor,
    /// Unstretched length ℓ_0, m.
    pub length: f64,
    /// Two-sided (never slack).
    pub linear: bool,
    /// Dashpot c_d in parallel, N·s/m (0: none; D11 linear, D12 tension-only).
    pub damping: f64,
    /// The contact wire's design height v_c(x_d) at rest, m: the length is
    /// form-found to meet it (`docs/lines.md` eq. F1–F5; `None`: the length
    /// as given).
    pub design_height: Option<f64>,
}

impl Dropper {
    /// The extension with both lines straight, e₀ = z_a − ℓ_0 (or
    /// h_m − ℓ_0 on the messenger), m: e = e₀ − r_dᵀd.
    pub fn rest_extension(&self) -> f64 {
        match self.anchor {
            Anchor::Fixed { height } | Anchor::Messenger { height } => height - self.length,
        }
    }

    /// True when the upper end is on the messenger wire.
    pub fn on_messenger(&self) -> bool {
        matches!(self.anchor, Anchor::Messenger { .. })
    }

    /// The dropper's force for a beam displacement v at x_d (m, up), N:
    /// k_d max(e, 0), or k_d e when linear.
    pub fn force_at(&self, v: f64) -> f64 {
        let e = self.rest_extension() - v;
        if self.linear {
            self.stiffness * e
        } else {
            self.stiffness * e.max(0.0)
        }
    }
}

/// Check each `[[dropper]]` on a beam of span `l`, m: x in [0, L],
/// stiffness > 0, exactly one of `anchor_height` (finite) and `anchor =
/// "messenger"` (with a `[messenger]`, whose rest height is `messenger`),
/// length ≥ 0, damping finite and ≥ 0, names valid and distinct.
pub(crate) fn resolve_droppers(
    specs: &[DropperSpec],
    l: f64,
    messenger: Option<f64>,
) -> Result<Vec<Dropper>> {
    let mut out: Vec<Dropper> = Vec::with_capacity(specs.len());
    for (i, d) in specs.iter().enumerate() {
        let field = |k: &str| format!("dropper.{i}.{k}");
        if !(0.0..=l).contains(&d.x) {
            return Err(Error::invalid(
                field("x"),
                d.x,
                format!("must be on the beam, in [0, {l}] m"),
            ));
        }
        let stiffness = positive(&field("stiffness"), d.stiffness, "N/m")?;
        let anchor = match (d.anchor_height, d.anchor) {
            (Some(h), None) => {
                if !h.is_finite() {
                    return Err(Error::invalid(
                        field("anchor_height"),
                        h,
                        "must be a finite height above the undeformed beam line (m, positive up)",
                    ));
                }
                Anchor::Fixed { height: h }
            }
            (None, Some(AnchorSpec::Messenger)) => match messenger {
                Some(height) => Anchor::Messenger { height },
                None => {
                    return Err(Error::invalid(
                        field("anchor"),
                        "\"messenger\"",
                        "needs a [messenger] section (the line the dropper hangs from), or give anchor_height (m) for a fixed anchor",
                    ));
                }
            },
            (Some(h), Some(_)) => {
                return Err(Error::invalid(
                    field("anchor_height"),
                    h,
                    "must be left out when anchor = \"messenger\" (exactly one of anchor_height and anchor)",
                ));
            }
            (None, None) => {
                return Err(Error::invalid(
                    field("anchor_height"),
                    "missing",
                    "exactly one of anchor_height (m, a fixed anchor) and anchor = \"messenger\" is required",
                ));
            }
        };
        let length = non_negative(&field("length"), d.length, "m")?;
        let damping = non_negative(&field("damping"), d.damping.unwrap_or(0.0), "N·s/m")?;
        if let Some(h) = d.design_height
            && !h.is_finite()
        {
            return Err(Error::invalid(
                field("design_height"),
                h,
                "must be a finite height of the contact wire at rest (m, positive up)",
            ));
        }
        let name = match &d.name {
            Some(n) => {
                let ok = !n.is_empty()
                    && n.len() <= 32
                    && n.chars()
                        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
                if !ok {
                    return Err(Error::invalid(
                        field("name"),
                        format!("{n:?}"),
                        "must be 1 to 32 characters among letters, digits, '_' and '-' (it names the output column dropper_<name>_force)",
                    ));
                }
                n.clone()
            }
            None => i.to_string(),
        };
        if let Some(j) = out.iter().position(|o| o.name == name) {
            return Err(Error::invalid(
                field("name"),
                format!("{name:?}"),
                format!("must differ from dropper {j}'s name"),
            ));
        }
        out.push(Dropper {
            name,
            x: d.x,
            stiffness,
            anchor,
            length,
            linear: d.linear,
            damping,
            design_height: d.design_height,
        });
    }
    Ok(out)
}
