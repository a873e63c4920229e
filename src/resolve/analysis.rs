//! `[analysis]` resolved (docs/scene.md#analysis): the filtered force's
//! band and the analysis section as a range of carrier positions, m.

use crate::error::{Error, Result};
use crate::numeric::filter::{FORCE_BAND_HZ, max_band_hz};
use crate::scene::AnalysisSpec;

/// The band and the section a run's standard statistics use.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalysisPlan {
    /// Upper edge of the filtered force's band, Hz.
    pub band_hz: f64,
    /// The section, carrier positions [x_start, x_end], m.
    pub x: [f64; 2],
    /// The spans it was given as (`analysis.spans`), if it was.
    pub spans: Option<[usize; 2]>,
    /// The support zone's width, m, when given (`analysis.support_zone`;
    /// None: each carrier's default, `record::zone`).
    pub support_zone: Option<f64>,
}

impl AnalysisPlan {
    /// True when a carrier at `x` (m) is in the section (ends included).
    pub fn contains(&self, x: f64) -> bool {
        self.x[0] <= x && x <= self.x[1]
    }
}

/// Check `[analysis]` against the beam's `length` (m), the time step `dt`
/// (s) and the line's `supports` (m; empty: none).
pub(crate) fn resolve_analysis(
    spec: &AnalysisSpec,
    length: f64,
    dt: f64,
    supports: &[f64],
) -> Result<AnalysisPlan> {
    let band_hz = spec.band.unwrap_or(FORCE_BAND_HZ);
    let top = max_band_hz(dt);
    // the default band on a step too coarse for it leaves the force as it
    // is (`lowpass_zero_phase`); a band given must fit
    if spec.band.is_some() && !(band_hz > 0.0 && band_hz < top) {
        return Err(Error::invalid(
            "analysis.band",
            band_hz,
            format!(
                "must be > 0 and below {top:.6e} Hz (Hz; the filter needs its design cut-off under 0.9 of the Nyquist frequency 1/(2Δt) at Δt = {dt:e} s); default 20"
            ),
        ));
    }
    let x = match (spec.x, spec.spans) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                "analysis.spans",
                format!("{:?}", spec.spans.unwrap_or_default()),
                "give the section as analysis.x or as analysis.spans, not both",
            ));
        }
        (Some([a, b]), None) => {
            if !(a.is_finite() && b.is_finite() && 0.0 <= a && a < b && b <= length) {
                return Err(Error::invalid(
                    "analysis.x",
                    format!("[{a}, {b}]"),
                    format!("must be [x_start, x_end] with 0 ≤ x_start < x_end ≤ L = {length} (m)"),
                ));
            }
            [a, b]
        }
        (None, Some([first, last])) => {
            let spans = supports.len().saturating_sub(1);
            if spans == 0 {
                return Err(Error::invalid(
                    "analysis.spans",
                    format!("[{first}, {last}]"),
                    "needs the line's supports ([output] supports, a [line] or a [messenger]); or give the section in metres, analysis.x = [x_start, x_end]",
                ));
            }
            if !(first <= last && last < spans) {
                return Err(Error::invalid(
                    "analysis.spans",
                    format!("[{first}, {last}]"),
                    format!(
                        "must be [first, last] with first ≤ last ≤ {} (0-based spans between the {} supports, as in spans.csv)",
                        spans - 1,
                        supports.len()
                    ),
                ));
            }
            [supports[first], supports[last + 1]]
        }
        (None, None) => [0.0, length],
    };
    if let Some(z) = spec.support_zone
        && !(z.is_finite() && z > 0.0 && z <= 0.5 * length)
    {
        return Err(Error::invalid(
            "analysis.support_zone",
            z,
            format!(
                "must be > 0 and at most L/2 = {} (m); default max(4ℓ_b, 4h, 4VΔt)",
                0.5 * length
            ),
        ));
    }
    Ok(AnalysisPlan {
        band_hz,
        x,
        spans: spec.spans,
        support_zone: spec.support_zone,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(text: &str) -> AnalysisSpec {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn default_is_the_whole_beam_at_twenty_hertz() {
        let p = resolve_analysis(&AnalysisSpec::default(), 50.0, 1e-4, &[]).unwrap();
        assert_eq!((p.band_hz, p.x), (20.0, [0.0, 50.0]));
    }

    #[test]
    fn spans_become_positions() {
        let p = resolve_analysis(
            &spec("spans = [1, 2]"),
            40.0,
            1e-4,
            &[0.0, 10.0, 20.0, 30.0, 40.0],
        )
        .unwrap();
        assert_eq!(p.x, [10.0, 30.0]);
    }

    #[test]
    fn bad_sections_and_bands_name_their_key() {
        for (text, supports, key) in [
            ("x = [20.0, 10.0]", &[][..], "analysis.x"),
            ("x = [0.0, 60.0]", &[], "analysis.x"),
            ("spans = [0, 0]", &[], "analysis.spans"),
            ("spans = [0, 4]", &[0.0, 10.0, 20.0][..], "analysis.spans"),
            (
                "x = [0.0, 1.0]\nspans = [0, 0]",
                &[0.0, 10.0][..],
                "analysis.spans",
            ),
            ("band = 0.0", &[], "analysis.band"),
            ("support_zone = 0.0", &[], "analysis.support_zone"),
            ("support_zone = 30.0", &[], "analysis.support_zone"),
            ("band = 4000.0", &[], "analysis.band"),
        ] {
            let e = resolve_analysis(&spec(text), 50.0, 1e-4, supports)
                .unwrap_err()
                .to_string();
            assert!(e.contains(key), "{text}: {e}");
        }
    }
}
