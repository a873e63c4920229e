//! `[messenger]`: a second tensioned line above the contact wire, held at
//! supports and coupled to the wire by droppers with `anchor = "messenger"`
//! (`docs/lines.md` eq. W1–W6). Plain data: the scene's spelling
//! ([`MessengerSpec`]), each value's own range check, and the resolved line
//! ([`Messenger`]) the model is built from. That each support falls on a
//! mesh node is checked where the mesh is known (`resolve::messenger`).
//!
//! Sign convention (MODEL §1: v positive up). The messenger's rest line is
//! the straight line at height h_m above the contact wire's undeformed
//! line; its displacement v_m(x) is measured from that line, positive up.
//! It is held vertically (v_m = 0, pinned) at each support x_s and free to
//! rotate there, or held there by a spring, dashpot and mass
//! (`support`, [`super::messenger_support`], eq. E1); beyond the outermost
//! supports it is free.
//!
//! Both lines use one element family (the contact wire's): Hermite
//! (EI_m > 0) when the contact wire has EI > 0, linear string elements
//! (EI_m = 0) when it is a string. The model interleaves the two lines'
//! unknowns node by node in one band (`model::beam`), which needs the same
//! dofs per node on both lines.

use serde::{Deserialize, Serialize};

use super::attachment::Attachment;
use super::messenger_support::{ElasticSupport, resolve_support};
use super::range::positive;
use crate::error::{Error, Result};

/// `[messenger]` as written in the scene.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MessengerSpec {
    /// Tension T_m, N (> 0).
    pub tension: f64,
    /// Mass per length ρA_m, kg/m (> 0).
    pub mass_per_length: f64,
    /// Bending stiffness EI_m, N·m² (> 0 when the contact wire has EI > 0,
    /// 0 when it is a string: one element family for both lines).
    pub bending_stiffness: f64,
    /// Height h_m of the messenger's rest line above the contact wire's
    /// undeformed line, m (> 0; v axis).
    pub height: f64,
    /// Where the messenger is held vertically (pinned), x in [0, L], m:
    /// strictly increasing, at least two, each on a mesh node.
    pub supports: Vec<f64>,
    /// Elastic supports (`docs/lines.md` eq. E1): `{ stiffness, damping,
    /// mass }` for every support, or a list with one `"pinned"` or `{ … }`
    /// per support; absent: every support pinned
    /// (`scene/messenger_support.rs`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub support: Option<toml::Value>,
}

/// The messenger wire, resolved (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Messenger {
    /// Tension T_m, N.
    pub tension: f64,
    /// Mass per length ρA_m, kg/m.
    pub rho_a: f64,
    /// Bending stiffness EI_m, N·m².
    pub ei: f64,
    /// Height h_m of its rest line above the contact wire's, m.
    pub height: f64,
    /// Supports x_s, m (strictly increasing): pinned, or elastic where
    /// `elastic` says.
    pub supports: Vec<f64>,
    /// Each support's spring, dashpot and mass (`None`: pinned, eq. W3;
    /// `Some`: elastic, eq. E1), one per support.
    pub elastic: Vec<Option<ElasticSupport>>,
    /// Point attachments on the messenger (grounded spring k, dashpot c,
    /// mass m at x; eq. A0 and E1 with r_m(x)): the elastic supports, then
    /// the scene's `[[attachment]] wire = "messenger"` (dropper clamps).
    pub attachments: Vec<Attachment>,
    /// Distributed load p_m, N/m (self-weight −ρA_m g when
    /// `[gravity] beam_self_weight`, else 0).
    pub distributed_load: f64,
    /// The linear messenger droppers' springs (x_d, k_d): k_d r_d r_dᵀ with
    /// r_d = r_c(x_d) − r_m(x_d) enters K (eq. W4); filled by the resolve
    /// layer from the `[[dropper]]` list.
    pub ties: Vec<(f64, f64)>,
    /// The damped linear messenger droppers' dashpots (x_d, c_d), N·s/m:
    /// c_d r_d r_dᵀ enters C (`docs/lines.md` eq. D11); filled by the
    /// resolve layer, empty without dropper damping.
    pub tie_dashpots: Vec<(f64, f64)>,
}

impl MessengerSpec {
    /// Check each value: `is_string` says whether the contact wire is a
    /// string (EI = 0); `l` is the span, m; `g` gravity, m/s²;
    /// `self_weight` whether the lines carry their weight.
    pub fn resolve(&self, is_string: bool, l: f64, g: f64, self_weight: bool) -> Result<Messenger> {
        let tension = positive("messenger.tension", self.tension, "N")?;
        let rho_a = positive("messenger.mass_per_length", self.mass_per_length, "kg/m")?;
        let ei = self.bending_stiffness;
        if is_string {
            if ei != 0.0 {
                return Err(Error::invalid(
                    "messenger.bending_stiffness",
                    ei,
                    "must be 0 (N·m²) when the contact wire is a string (EI = 0): both lines use one element family, interleaved node by node in one band",
                ));
            }
        } else if !(ei.is_finite() && ei > 0.0) {
            return Err(Error::invalid(
                "messenger.bending_stiffness",
                ei,
                "must be > 0 (N·m²) when the contact wire has EI > 0: both lines use one element family (Hermite), interleaved node by node in one band",
            ));
        }
        let height = positive("messenger.height", self.height, "m")?;
        if self.supports.len() < 2 {
            return Err(Error::invalid(
                "messenger.supports",
                format!("{:?}", self.supports),
                "must list at least two x (m) where the messenger is held",
            ));
        }
        for (i, &x) in self.supports.iter().enumerate() {
            let field = format!("messenger.supports.{i}");
            if !(0.0..=l).contains(&x) {
                return Err(Error::invalid(
                    field,
                    x,
                    format!("must be on the span, in [0, {l}] m"),
                ));
            }
            if i > 0 && x <= self.supports[i - 1] {
                return Err(Error::invalid(
                    field,
                    x,
                    format!(
                        "must be greater than support {} ({} m): supports are strictly increasing",
                        i - 1,
                        self.supports[i - 1]
                    ),
                ));
            }
        }
        let elastic = resolve_support(
            "messenger.support",
            self.support.as_ref(),
            self.supports.len(),
        )?;
        let attachments = self
            .supports
            .iter()
            .zip(&elastic)
            .filter_map(|(&x, e)| {
                e.map(|e| Attachment {
                    x,
                    stiffness: e.stiffness,
                    mass: e.mass,
                    damping: e.damping,
                })
            })
            .collect();
        Ok(Messenger {
            tension,
            rho_a,
            ei,
            height,
            supports: self.supports.clone(),
            elastic,
            attachments,
            distributed_load: if self_weight { -rho_a * g } else { 0.0 },
            ties: Vec::new(),
            tie_dashpots: Vec::new(),
        })
    }
}

impl Messenger {
    /// The pinned supports' x, m (those without an elastic support).
    pub fn pinned(&self) -> impl Iterator<Item = f64> + '_ {
        self.supports
            .iter()
            .zip(&self.elastic)
            .filter(|(_, e)| e.is_none())
            .map(|(&x, _)| x)
    }
}
