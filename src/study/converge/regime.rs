//! What a level's errors say about its ladder: asymptotic, stalled by an
//! unrefined variable, pre-asymptotic, at round-off (the `regime` column).

/// What a study knows beyond its runs: the exact histories of its declared
/// reference (if any), the orders the refined variable should show, and
/// what stays fixed.
pub(super) struct Context<'a> {
    /// w(t) under carrier 0, exact.
    pub(super) w: Option<&'a (dyn Fn(f64) -> f64 + Sync)>,
    /// λ(t) of carrier 0, exact (compared at t − lag·Δt of each run).
    pub(super) force: Option<&'a (dyn Fn(f64) -> f64 + Sync)>,
    /// The declared reference's name, for the `reference` column.
    pub(super) name: &'static str,
    /// What the ladder refines.
    pub(super) refine: super::Refine,
    /// It in words: `mesh`, `J`, `Δt`, `mesh and Δt`, `J and Δt`.
    pub(super) refined: &'static str,
    /// The displacement's formal order in the refined variable, if known.
    pub(super) formal: Option<f64>,
    /// What the ladder does not refine ("the mesh", "Δt", "J", …).
    pub(super) unrefined: &'static str,
    /// ω_max·Δt of each level.
    pub(super) omega_dt: Vec<f64>,
}

/// An error falling by less than this factor per level (order < 0.32 at
/// r = 2) is not falling with the refined variable: a ladder limited by
/// what it does not refine. Chosen between a converging ladder's slowest
/// useful rate (first order: ×2 per halving) and the ±10 % a stalled error
/// wanders by.
pub(crate) const STALL_RATIO: f64 = 1.25;

/// An error (against an exact reference) or a difference between levels
/// at least this fraction of the quantity's own size is no discretization
/// error: the run blew up (a Newmark ladder's force error of 250 N on a
/// 15 N force was once called "limited by the mesh"). The regime is then
/// `diverged`, whatever the error did from level to level.
pub const DIVERGED_RELATIVE: f64 = 1.0;

/// Successive observed orders differing by more than this are not yet in
/// the asymptotic range: the ratio of successive error ratios is outside
/// r^(±0.3) (0.81 … 1.23 at r = 2), where the leading error term does not
/// yet dominate the next one.
pub(crate) const ORDER_DRIFT: f64 = 0.3;

/// An observed order this far from the formal one is pre-asymptotic (or
/// the formal order does not hold for this solution: the regime says which
/// to suspect, the numbers show it). The same ±0.3 the verification
/// harness allows a smooth case.
pub(crate) const FORMAL_GAP: f64 = 0.3;

/// The regime of a level from the errors of its ladder (`e`, against an
/// exact reference, or successive differences when `exact` is false), the
/// orders between levels and the quantity's size at the level (`size`:
/// the exact history's norm, or the level's own for a history without a
/// reference; `None` for a scalar) (module docs, `docs/convergence.md`).
pub(super) fn regime(
    e: &[f64],
    orders: &[f64],
    l: usize,
    ctx: &Context,
    exact: bool,
    size: Option<f64>,
) -> String {
    // with differences, level ℓ's difference is index ℓ − 1
    let cur = match (exact, l) {
        (true, _) => e[l],
        (false, 0) => return String::new(),
        (false, _) => e[l - 1],
    };
    if size.is_some_and(|s| s > 0.0 && cur >= DIVERGED_RELATIVE * s) {
        return format!(
            "diverged: {} as large as the quantity itself ({cur:.3e} against {:.3e})",
            if exact {
                "the error is"
            } else {
                "successive levels differ by"
            },
            size.unwrap_or(f64::NAN)
        );
    }
    let prev = match (exact, l) {
        (true, 0) | (false, 1) => return String::new(),
        (true, _) => e[l - 1],
        (false, _) => e[l - 2],
    };
    if !(prev.is_finite() && cur.is_finite()) || prev == 0.0 {
        return String::new();
    }
    if cur == 0.0 {
        return "exact".into();
    }
    if prev / cur < 1.0 / STALL_RATIO {
        return if exact {
            "growing: round-off or an instability".into()
        } else {
            "not converging".into()
        };
    }
    if prev / cur < STALL_RATIO {
        return if exact {
            format!("limited by {}", ctx.unrefined)
        } else {
            "not converging".into()
        };
    }
    let p = orders[l];
    let drift = l >= 2 && orders[l - 1].is_finite() && (p - orders[l - 1]).abs() > ORDER_DRIFT;
    let off = ctx.formal.is_some_and(|f| (p - f).abs() > FORMAL_GAP);
    if drift || off {
        "pre-asymptotic".into()
    } else if l >= 2 || ctx.formal.is_some() {
        "asymptotic".into()
    } else {
        String::new()
    }
}

/// Ratio of successive error ratios (e_{ℓ−2}/e_{ℓ−1})/(e_{ℓ−1}/e_ℓ): 1 in
/// the asymptotic range ([`ORDER_DRIFT`]).
pub(super) fn ratio_change(a: f64, b: f64, c: f64) -> f64 {
    if a > 0.0 && b > 0.0 && c > 0.0 {
        (a / b) / (b / c)
    } else {
        f64::NAN
    }
}
