//! The report's fog section: the share of fog `Fog` mixes in against the exact curve, for the
//! linear curve and the exponential one (a 33-entry integer table) at each density. Deterministic
//! and quick (no scenes, no callgrind): every 0.15 step of depth between `start` and `end`.

use rasterizer_core::shade::{FogCurve, FOG_ONE};
use std::fmt::Write as _;

/// The exact share at `t` in `0 ..= 1` for density `k` (0: linear).
fn exact(t: f64, k: f64) -> f64 {
    if k == 0.0 {
        t
    } else {
        (1.0 - (-k * t).exp()) / (1.0 - (-k).exp())
    }
}

/// Max and mean |share - exact| over every step of `t`, in 8-bit colour steps of a full fog
/// contrast (share 1 = 255 steps), for density `k16` sixteenths.
pub fn curve_error(k16: u16) -> (f64, f64) {
    let curve = FogCurve::exponential(k16);
    let k = f64::from(k16) / 16.0;
    let (mut worst, mut sum) = (0.0f64, 0.0f64);
    for t in 0..=FOG_ONE {
        let got = f64::from(curve.share(t)) / f64::from(FOG_ONE);
        let e = (got - exact(f64::from(t) / f64::from(FOG_ONE), k)).abs() * 255.0;
        worst = worst.max(e);
        sum += e;
    }
    (worst, sum / f64::from(FOG_ONE + 1))
}

/// The densities the section lists, in sixteenths.
const DENSITIES: [u16; 7] = [0, 16, 32, 48, 64, 96, 128];

/// Appends the section.
pub fn section(s: &mut String) {
    let _ = writeln!(s, "## Fog curves\n");
    let _ = writeln!(
        s,
        "`Fog` mixes each vertex's colour toward the fog colour by a share of depth between \
         `start` and `end`: `t` itself (linear) or `(1 - e^(-k t)) / (1 - e^(-k))` \
         (`FogCurve::exponential`, a 33-entry integer table interpolated linearly). The share \
         against the exact curve over every 0.15 step of `t`, in 8-bit colour steps of a full \
         contrast between the surface and the fog (the error a pixel's channel can take from \
         the curve, before the colour's own rounding). The knob is the density; the cost per \
         pixel is nothing (the mix is per vertex) and per vertex the same for every curve.\n"
    );
    let _ = writeln!(
        s,
        "| curve | density k | max error (steps) | mean error (steps) |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|");
    for k16 in DENSITIES {
        let (worst, mean) = curve_error(k16);
        let name = if k16 == 0 { "linear" } else { "exponential" };
        let _ = writeln!(
            s,
            "| {name} | {} | {worst:.3} | {mean:.4} |",
            f64::from(k16) / 16.0
        );
    }
    let _ = writeln!(s);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Linear is exact to the 0.15 share; the table stays within about 1 % of full contrast
    /// (2.6 steps) at the largest density, as `FOG_MAX_DENSITY` promises, and tighter below.
    #[test]
    fn curves_are_close_to_exact() {
        assert!(curve_error(0).0 < 0.01);
        let (at8, _) = curve_error(128);
        assert!(at8 < 2.6, "{at8}");
        assert!(curve_error(48).0 < at8);
    }

    /// docs/ACCURACY.md holds the section as this code writes it.
    #[test]
    fn accuracy_md_has_the_current_section() {
        let mut s = String::new();
        section(&mut s);
        crate::accuracy::assert_report_holds(&s);
    }
}
