//! `[line] steady_arm`: the steady arm at each interior support of a
//! generated line, as the point spring, mass and dashpot it is at the
//! contact wire (`docs/lines.md` "Steady arm with a pivot", eq. S1–S3).
//!
//! A steady arm is a bar of length ℓ_a hinged at the mast (its pivot) and
//! clamped to the contact wire at its tip. Turned by a small angle φ about
//! the pivot its tip rises v = ℓ_a φ, so its kinetic energy ½ I_a φ̇² (I_a
//! about the pivot, kg·m²) is ½ (I_a/ℓ_a²) v̇², and a rotational spring
//! k_φ at the pivot (N·m/rad) stores ½ k_φ φ² = ½ (k_φ/ℓ_a²) v²:
//!
//! ```text
//!   (S1) m_tip = m_s + I_a / ℓ_a²          (kg: the tip's clamp plus the arm's inertia)
//!   (S2) k_tip = k_s + k_φ / ℓ_a²          (N/m: the registration spring plus the pivot's)
//!   (S3) c_tip = c_s                        (N·s/m)
//! ```
//!
//! a point attachment at the support (A0), exact for the linearized
//! (small-angle) arm. Its weight is not modelled: attachments' masses carry
//! no weight in a run, and a horizontal arm's weight moment is a constant
//! tip force, not a stiffness.

use serde::Deserialize;

use super::range::{non_negative, positive};
use crate::error::{Error, Result};

/// `steady_arm = { … }` as written.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SteadyArmSpec {
    /// k_s, the registration spring at the tip to the rest line, N/m (≥ 0).
    #[serde(default)]
    stiffness: f64,
    /// m_s, a point mass at the tip (the clamp), kg (≥ 0).
    #[serde(default)]
    mass: f64,
    /// c_s to the rest line, N·s/m (≥ 0).
    #[serde(default)]
    damping: f64,
    /// ℓ_a, the arm's length from its pivot to the tip, m (> 0; needed with
    /// `inertia` or `pivot_stiffness`).
    #[serde(default)]
    arm_length: Option<f64>,
    /// I_a, the arm's rotational inertia about its pivot, kg·m² (≥ 0).
    #[serde(default)]
    inertia: f64,
    /// k_φ, a rotational spring at the pivot, N·m/rad (≥ 0).
    #[serde(default)]
    pivot_stiffness: f64,
}

/// The arm as a point attachment at the contact wire (S1–S3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SteadyArm {
    /// k_tip, N/m.
    pub stiffness: f64,
    /// m_tip, kg.
    pub mass: f64,
    /// c_tip, N·s/m.
    pub damping: f64,
}

impl SteadyArmSpec {
    /// Check each value and reduce the arm to its tip (S1–S3).
    pub(crate) fn tip(&self) -> Result<SteadyArm> {
        let f = |k: &str| format!("line.steady_arm.{k}");
        let k = non_negative(&f("stiffness"), self.stiffness, "N/m")?;
        let m = non_negative(&f("mass"), self.mass, "kg")?;
        let c = non_negative(&f("damping"), self.damping, "N·s/m")?;
        let inertia = non_negative(&f("inertia"), self.inertia, "kg·m²")?;
        let k_phi = non_negative(&f("pivot_stiffness"), self.pivot_stiffness, "N·m/rad")?;
        let (m_arm, k_arm) = match self.arm_length {
            Some(l) => {
                let l = positive(&f("arm_length"), l, "m, from the pivot to the tip")?;
                let (m_arm, k_arm) = (inertia / (l * l), k_phi / (l * l));
                // I_a/ℓ_a² and k_φ/ℓ_a² must be numbers the run can use: an
                // arm so short or so long that ℓ_a² is no normal number is
                // no arm (S1, S2)
                if (inertia != 0.0 || k_phi != 0.0) && !(l * l).is_normal() {
                    let big = inertia.max(k_phi);
                    let low = (big / f64::MAX).sqrt().max(f64::MIN_POSITIVE.sqrt());
                    let high = f64::MAX.sqrt();
                    return Err(Error::invalid(
                        f("arm_length"),
                        l,
                        format!(
                            "has a square ℓ_a² that is no normal number, so the tip's I_a/ℓ_a² and k_φ/ℓ_a² (S1, S2) cannot be formed: give a length in [{low:.3e}, {high:.3e}] m (m, from the pivot to the tip)"
                        ),
                    ));
                }
                for (key, given, tip, unit) in [
                    ("inertia", inertia, m_arm, "kg·m²"),
                    ("pivot_stiffness", k_phi, k_arm, "N·m/rad"),
                ] {
                    if given != 0.0 && !tip.is_normal() {
                        return Err(Error::invalid(
                            f(key),
                            given,
                            format!(
                                "over ℓ_a² = {:.3e} m² gives the tip no finite non-zero value (S1, S2): give a value that does ({unit}, ≥ 0)",
                                l * l
                            ),
                        ));
                    }
                }
                (m_arm, k_arm)
            }
            None if inertia != 0.0 || k_phi != 0.0 => {
                return Err(Error::invalid(
                    f("arm_length"),
                    "none",
                    "is required with inertia or pivot_stiffness (m, > 0: the arm's length from its pivot to the tip)",
                ));
            }
            None => (0.0, 0.0),
        };
        let tip = SteadyArm {
            stiffness: k + k_arm,
            mass: m + m_arm,
            damping: c,
        };
        if tip.stiffness == 0.0 && tip.mass == 0.0 && tip.damping == 0.0 {
            return Err(Error::invalid(
                "line.steady_arm",
                "{ stiffness = 0, mass = 0 }",
                "needs stiffness > 0 (N/m), mass > 0 (kg), damping > 0 (N·s/m) or an arm (arm_length with inertia or pivot_stiffness); leave it out for no steady arms",
            ));
        }
        Ok(tip)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arm(text: &str) -> Result<SteadyArm> {
        let t: toml::Table = toml::from_str(&format!("a = {text}")).unwrap();
        let spec: SteadyArmSpec = t["a"].clone().try_into().unwrap();
        spec.tip()
    }

    #[test]
    fn the_arm_reduces_to_its_tip_by_hand() {
        // ℓ_a = 1.2 m, I_a = 2.16 kg·m² (a 4.5 kg bar about its end: m ℓ²/3),
        // k_φ = 720 N·m/rad: m_tip = 0.5 + 2.16/1.44 = 2.0 kg, k_tip = 100 +
        // 720/1.44 = 600 N/m
        let t = arm("{ stiffness = 100.0, mass = 0.5, damping = 3.0, arm_length = 1.2, inertia = 2.16, pivot_stiffness = 720.0 }").unwrap();
        assert!(
            (t.mass - 2.0).abs() < 1e-15 && (t.stiffness - 600.0).abs() < 1e-12,
            "{t:?}"
        );
        assert_eq!(t.damping, 3.0);
        // without an arm: the point spring and mass as written
        let t = arm("{ stiffness = 100.0, mass = 0.5 }").unwrap();
        assert_eq!((t.stiffness, t.mass), (100.0, 0.5));
    }

    #[test]
    fn bad_values_are_named() {
        for (text, want) in [
            (
                "{ inertia = 1.0 }",
                &["line.steady_arm.arm_length", "required"][..],
            ),
            (
                "{ arm_length = 0.0, inertia = 1.0 }",
                &["line.steady_arm.arm_length", "0", "> 0"],
            ),
            (
                "{ arm_length = 1.0, inertia = -1.0 }",
                &["line.steady_arm.inertia", "-1", "≥ 0"],
            ),
            (
                "{ arm_length = 1.0, pivot_stiffness = nan }",
                &["line.steady_arm.pivot_stiffness", "finite"],
            ),
            ("{ arm_length = 1.0 }", &["line.steady_arm", "an arm"]),
            // ℓ_a² underflows to 0 or overflows: the length is named, no NaN
            (
                "{ arm_length = 5e-324, inertia = 2.0 }",
                &["`line.steady_arm.arm_length` = 5e-324", "give a length in"],
            ),
            (
                "{ arm_length = 1e308, inertia = 2.0 }",
                &["`line.steady_arm.arm_length` = 1e308", "give a length in"],
            ),
            // I_a/ℓ_a² lost below the smallest normal number
            (
                "{ arm_length = 1.2, inertia = 5e-324 }",
                &["`line.steady_arm.inertia` = 5e-324"],
            ),
        ] {
            let e = arm(text).unwrap_err().to_string();
            for w in want {
                assert!(e.contains(w), "{text}: {e} (wanted {w})");
            }
        }
    }
}
