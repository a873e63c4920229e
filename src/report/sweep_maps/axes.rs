//! Axes of a sweep map: the label of a swept key, tick labels, and the cell
//! edges around grid values.

use crate::study::sweep::Axis;
/// The label of a swept key: the key, its symbol and unit.
pub(crate) fn axis_label(key: &str) -> String {
    let last = key.rsplit('.').next().unwrap_or(key);
    let sym = match (key, last) {
        ("speed_ratio", _) => "V0/c",
        ("tension_ratio", _) => "T/EA",
        ("mass_ratio", _) => "m/M, M = ρAL",
        ("stiffness_ratio", _) => "k/(T/L)",
        (_, "tension") => "T (N)",
        (_, "cruise") | (_, "value") => "V0 (m/s)",
        (_, "mass") => "m (kg)",
        (_, "stiffness") => "k (N/m)",
        (_, "preload") => "δ0 (m)",
        (_, "damping") => "c_s (N·s/m)",
        (_, "start") => "x0 (m)",
        (_, "force") => "F (N)",
        (_, "length") => "L (m)",
        (_, "density") => "ρ (kg/m³)",
        (_, "area") => "A (m²)",
        (_, "youngs_modulus") => "E (Pa)",
        (_, "second_moment") => "I (m⁴)",
        (_, "mass_per_length") => "ρA (kg/m)",
        (_, "bending_stiffness") => "EI (N·m²)",
        (_, "elements") => "N (elements)",
        (_, "step") => "Δt (s)",
        (_, "rho_inf") => "ρ∞",
        (_, "g") => "g (m/s²)",
        _ => "",
    };
    if sym.is_empty() {
        key.to_string()
    } else {
        format!("{sym}   [{key}]")
    }
}

/// A tick label: the value rounded to 9 significant digits, shortest form
/// (so 0.30000000000000004 reads 0.3).
pub fn tick(v: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    let r: f64 = format!("{v:.8e}").parse().unwrap_or(v);
    let a = r.abs();
    if r == 0.0 {
        "0".into()
    } else if (1e-4..1e6).contains(&a) {
        format!("{r}")
    } else {
        let s = format!("{r:e}");
        s.replace("e-", "e−")
    }
}

/// Cell edges around grid values `v` (midpoints; geometric when `log`).
pub(super) fn edges(v: &[f64], log: bool) -> Vec<f64> {
    let t = |x: f64| if log { x.ln() } else { x };
    let u = |x: f64| if log { x.exp() } else { x };
    let n = v.len();
    if n == 1 {
        return if log {
            vec![v[0] / 1.1, v[0] * 1.1]
        } else {
            let h = if v[0] == 0.0 { 0.5 } else { 0.05 * v[0].abs() };
            vec![v[0] - h, v[0] + h]
        };
    }
    let mut e = Vec::with_capacity(n + 1);
    e.push(u(t(v[0]) - 0.5 * (t(v[1]) - t(v[0]))));
    for i in 0..n - 1 {
        e.push(u(0.5 * (t(v[i]) + t(v[i + 1]))));
    }
    e.push(u(t(v[n - 1]) + 0.5 * (t(v[n - 1]) - t(v[n - 2]))));
    e
}

pub(super) fn axis_values(a: &Axis) -> Vec<f64> {
    (0..a.count).map(|i| a.value(i)).collect()
}

/// Lowest and highest of cell edges `e`.
pub(super) fn span(e: &[f64]) -> (f64, f64) {
    let lo = e.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = e.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

/// `v` rounded to `digits` significant digits.
pub(super) fn round_sig(v: f64, digits: i32) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let p = 10f64.powi(digits - 1 - v.abs().log10().floor() as i32);
    (v * p).round() / p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(0.1 + 0.2), "0.3");
        assert_eq!(tick(0.0012000000000000001), "0.0012");
        assert_eq!(tick(20100.000000000004), "20100");
        assert_eq!(tick(0.0), "0");
        assert_eq!(tick(2.5e-5), "2.5e−5");
    }

    #[test]
    fn edges_bracket_values() {
        let e = edges(&[1.0, 2.0, 3.0], false);
        assert_eq!(e, vec![0.5, 1.5, 2.5, 3.5]);
        let l = edges(&[1.0, 100.0], true);
        assert!((l[1] - 10.0).abs() < 1e-9);
    }
}
