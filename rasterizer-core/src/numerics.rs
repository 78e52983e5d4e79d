//! The accuracy knobs of the 3D path besides the number format ([`crate::math::Scalar`]), the
//! sub-pixel bits and the trigonometry table size: how the perspective divide divides, how
//! precisely colour and depth are interpolated across a triangle, and whether the colour is
//! dithered down to the target's depth.
//!
//! They are compile-time choices, carried by a type implementing [`Numerics`] (the last generic
//! parameter of [`crate::pipeline::Pipeline`]), so a pipeline compiles only the method it uses.
//! [`Standard`] is the default; any type implementing [`Numerics`] picks other knobs. `docs/ACCURACY.md` measures what each
//! choice costs and what it changes.

/// How the perspective divide turns clip coordinates into screen coordinates and depth.
///
/// Every method takes one reciprocal of `w` per vertex and a multiplication per coordinate, with
/// no 64-bit division (a library call on a 32-bit core), for a fixed-point vertex inside the
/// clipper's guard band: every vertex of a mesh drawn within the view, and the corners of clipped
/// polygons. The methods differ in how the reciprocal is found and whether the result is settled
/// on the exactly rounded one. Points beyond the guard band's limits and floating-point formats
/// divide exactly in every method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Divide {
    /// The default: exactly rounded results (the only error is the final rounding), the same as
    /// one correctly rounded division per coordinate. The reciprocal comes from one 32-bit
    /// division (a single instruction on a Cortex-M3/M4) and one Newton-Raphson step; an
    /// estimate whose fraction lies so close below a whole number that it may be one short is
    /// then settled with its remainder (rarely: most estimates prove themselves exact with one
    /// compare).
    Exact,
    /// The reciprocal of [`Divide::Exact`] without the settling: at most one unit below the
    /// exactly rounded result (never above), and cheaper than it.
    Reciprocal,
    /// No division at all (for cores without a divide instruction, such as the Cortex-M0+): the
    /// reciprocal comes from a 64-entry table refined by two Newton-Raphson steps, unsettled: at
    /// most one unit below the exactly rounded result (never above).
    Newton,
}

/// Where each span of a triangle starts its interpolated values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpanStart {
    /// The exactly rounded value of every plane at the first pixel of every span, kept as a
    /// quotient and remainder (no division per span): the value of each pixel is at most half a
    /// step of the last fractional bit from the true plane at the span start.
    Exact,
    /// Each plane's per-pixel and per-row gradients rounded once per triangle to the fractional
    /// bits; a span starts at `v0 + gx dx + gy dy` (two multiplications per plane), so the value
    /// of a pixel is still a function of its position alone (bands match the whole frame), but
    /// carries the gradients' rounding times the distance from the first vertex. Falls back to
    /// [`SpanStart::Exact`] for triangles whose gradients are too large.
    Gradient,
    /// The default: each plane is `K + gx px + gy py` over pixel coordinates in 32-bit wrapping
    /// arithmetic, exact at an anchor pixel of the triangle with the gradients rounded to the
    /// fractional bits (to within one unit toward zero of the exactly rounded ones: a quotient
    /// through the triangle's one reciprocal, without a correction step), so a pixel's value is a
    /// function of its position alone (bands match the whole frame) and a pixel `d` pixels from the
    /// anchor is within `(3 d + 1) / 2` units of the last fractional bit of the exact plane (16
    /// fractional bits whatever [`Numerics::FRAC`] says; depth is rounded down, as
    /// [`SpanStart::Exact`] rounds it). Depth, the values and the colour of each pixel are computed
    /// in one loop, with the rounding folded into the span's start. Perspective-correct
    /// interpolation uses [`SpanStart::Exact`] instead.
    Wrapping,
}

/// Whether the interpolated colour is dithered down to the target's channel depth, with an
/// ordered (Bayer) threshold indexed by screen position.
///
/// Without dithering, each channel is rounded to the nearest step of the target (5 bits for red
/// in [`embedded_graphics_core::pixelcolor::Rgb565`]), which shows as bands across smooth
/// shading. With it, the pixel at `(x, y)` adds a threshold from the matrix at
/// `(x mod n, y mod n)` (a fraction of one step, evenly spread over `0 .. 1`) and truncates, so
/// the mean of every `n x n` tile is the exact colour to within `1 / n^2` of a step. The pattern
/// depends on the screen position alone, so bands match the whole frame.
///
/// Applies to the interpolated colour of the default path ([`SpanStart::Wrapping`], affine):
/// [`crate::shade::GouraudLit`] and [`crate::shade::VertexColors`]; a single colour per
/// triangle has no fraction to dither.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dither {
    /// Round each pixel to the nearest step: the default, and no code for dithering at all.
    None,
    /// A 4 x 4 Bayer matrix: 16 levels between two steps.
    Bayer4,
    /// An 8 x 8 Bayer matrix: 64 levels between two steps, a finer but larger pattern.
    Bayer8,
}

/// The 8 x 8 Bayer matrix; its top-left 4 x 4 quarter divided by 4 is the 4 x 4 matrix.
const BAYER8: [[u8; 8]; 8] = [
    [0, 32, 8, 40, 2, 34, 10, 42],
    [48, 16, 56, 24, 50, 18, 58, 26],
    [12, 44, 4, 36, 14, 46, 6, 38],
    [60, 28, 52, 20, 62, 30, 54, 22],
    [3, 35, 11, 43, 1, 33, 9, 41],
    [51, 19, 59, 27, 49, 17, 57, 25],
    [15, 47, 7, 39, 13, 45, 5, 37],
    [63, 31, 55, 23, 61, 29, 53, 21],
];

impl Dither {
    /// The threshold of pixel `(x, y)` in 256ths of a step: the middle of its matrix cell's
    /// share of the step, `(2 m + 1) / (2 n^2)` for the matrix entry `m`, so the thresholds
    /// average exactly one half (what rounding to nearest adds). Always below 256.
    #[inline(always)]
    pub const fn threshold(self, x: i32, y: i32) -> u32 {
        match self {
            // Half a step: rounding to nearest.
            Dither::None => 128,
            // The 4 x 4 matrix is the 8 x 8 one's top-left quarter divided by 4 (its entries
            // there are multiples of 4).
            Dither::Bayer4 => {
                let m = BAYER8[(y & 3) as usize][(x & 3) as usize] as u32 >> 2;
                (2 * m + 1) << 3
            }
            Dither::Bayer8 => {
                let m = BAYER8[(y & 7) as usize][(x & 7) as usize] as u32;
                (2 * m + 1) << 1
            }
        }
    }
}

/// The numeric knobs of a pipeline, as associated constants: the last generic parameter of
/// [`crate::pipeline::Pipeline`]. Every constant has the library's default, so a type sets only
/// what it changes:
///
/// ```
/// use rasterizer_core::numerics::{Divide, Numerics};
/// /// For a core without a divide instruction.
/// struct NoDivider;
/// impl Numerics for NoDivider {
///     const DIVIDE: Divide = Divide::Newton;
/// }
/// ```
pub trait Numerics {
    /// The divide method of the perspective divide.
    const DIVIDE: Divide = Divide::Exact;
    /// Fractional bits of interpolated values and depth as they step across a triangle
    /// (4 to 16; a value outside is clamped into it) with [`SpanStart::Exact`] and
    /// [`SpanStart::Gradient`]. Depth is a 16-bit integer and Gouraud colours carry 8 fractional
    /// bits, so fewer bits show as steps only across long spans. [`SpanStart::Wrapping`] ignores
    /// it: its 32-bit planes always step the shader's values and depth with 16 fractional bits,
    /// which costs nothing more.
    const FRAC: u32 = 16;
    /// How spans start.
    const SPANS: SpanStart = SpanStart::Wrapping;
    /// Whether the shader's values are interpolated perspective-correctly (with
    /// [`SpanStart::Wrapping`] through the fused span loop: one 32-bit division per pixel drawn
    /// for a colour shader's triangle, two for others; otherwise through the general span
    /// engine); otherwise they are affine in screen space. Depth is
    /// affine in screen space either way, and exact.
    const PERSPECTIVE: bool = false;
    /// How the interpolated colour is brought down to the target's channel depth: rounded to the
    /// nearest step, or dithered ([`Dither`]).
    const DITHER: Dither = Dither::None;
}

/// The library's default: exact division, wrapping span starts, affine values.
#[derive(Debug, Clone, Copy, Default)]
pub struct Standard;

impl Numerics for Standard {}

/// [`Standard`] with perspective-correct values.
#[derive(Debug, Clone, Copy, Default)]
pub struct Perspective;

impl Numerics for Perspective {
    const PERSPECTIVE: bool = true;
}

/// `N::FRAC` clamped into `4..=16`.
pub(crate) const fn frac<N: Numerics>() -> u32 {
    if N::FRAC < 4 {
        4
    } else if N::FRAC > 16 {
        16
    } else {
        N::FRAC
    }
}

/// Table entry i: 2^37 / (64 + i + 0.5), the reciprocal of the middle of the interval, in
/// 1.30 (times 2^30 of 2^62 / m's scale once shifted).
const RECIPROCAL_TABLE: [u32; 64] = {
    let mut t = [0u32; 64];
    let mut i = 0;
    while i < 64 {
        // 2^38 / (2 (64 + i) + 1) = 2^37 / (64 + i + 0.5).
        t[i] = ((1u64 << 38) / (2 * (64 + i as u64) + 1)) as u32;
        i += 1;
    }
    t
};

/// `2^32 / (m >> 16)`, within `2^-15` (relative) of `2^48 / m`, for `m` with its top bit set:
/// one division of `u32`s (bit 15 of the divisor is set, so it is never zero).
#[inline(always)]
pub(crate) fn reciprocal_seed(m: u32) -> u32 {
    u32::MAX / (m >> 16 | 1 << 15)
}

/// The reciprocal `r` and shift `sh` of `d = 2w` with `r <= 2^(32 + sh) / d < r (1 + 2^-27)` for
/// `w` in `[1, 2^29)` (the callers test that range first; `w = 0` would overflow the shift):
/// `r <= 2^31`, `sh` in `0..=28`. No 64-bit division: the seed of [`Divide::Exact`] and
/// [`Divide::Reciprocal`] is one 32-bit division (a single instruction on a Cortex-M3/M4) of 16
/// correct bits, refined by one Newton-Raphson step; [`Divide::Newton`]'s is a 64-entry table
/// of 7 bits, refined by two. A Newton step never overshoots the reciprocal (`r' = r (2 - m r)`
/// is `(1 - e^2) / m` for `r = (1 - e) / m`), and its roundings are down, so `r` is never above
/// it.
///
/// `sh` is `w`'s top bit (that of `d` less one), so `d` has `30 - sh` leading zeros and is
/// normalised to `m = d 2^(30 - sh) = w 2^(31 - sh)` in `[2^31, 2^32)`:
/// `2^62 / m = 2^(32 + sh) / d`. (On x86-64 the top bit is the shift, which takes fewer
/// instructions than counting `d`'s leading zeros.)
#[inline(always)]
pub(crate) fn reciprocal_double(w: u32, method: Divide) -> (u64, u32) {
    #[cfg(target_pointer_width = "64")]
    {
        let sh = 63 - u64::from(w).leading_zeros();
        // w 2^(31 - sh) as (w 2^31) / 2^sh (exact: w < 2^(sh + 1)), so that both shifts are
        // by sh.
        (reciprocal_normal((u64::from(w) << 31) >> sh, method), sh)
    }
    // A 32-bit core counts the leading zeros in one instruction either way, and the bound on
    // them (`min(30)`) tells the compiler that the 64-bit products' shifts are below 32.
    #[cfg(not(target_pointer_width = "64"))]
    reciprocal_u32(2 * w, method)
}

/// [`reciprocal_double`] of any `d` in `[2, 2^30)`, odd ones too, normalised by its leading
/// zeros (bounded by 30, which tells the compiler that `sh` is below 32): the clipper's path
/// and 32-bit cores take it.
pub(crate) fn reciprocal_u32(d: u32, method: Divide) -> (u64, u32) {
    // m = d 2^lz in [2^31, 2^32): 2^62 / m = 2^(62 - lz) / d = 2^(32 + sh) / d.
    let lz = d.leading_zeros().min(30);
    (reciprocal_normal(u64::from(d << lz), method), 30 - lz)
}

/// `r <= 2^62 / m < r (1 + 2^-27)` for `m` in `[2^31, 2^32)` ([`reciprocal_double`]), taken as a
/// `u64` (its callers' shifts leave it one).
#[inline(always)]
fn reciprocal_normal(m: u64, method: Divide) -> u64 {
    // r ≈ 2^62 / m, in [2^30, 2^31].
    let mut r = match method {
        // m >> 16 is in [2^15, 2^16): 2^32 / (m >> 16) ≈ 2^48 / m, within 2^-15.
        // (Bit 15 is set whenever d > 0: the divisor is never zero.)
        Divide::Exact | Divide::Reciprocal => i64::from(reciprocal_seed(m as u32)) << 14,
        Divide::Newton => i64::from(RECIPROCAL_TABLE[((m >> 25) & 63) as usize]),
    };
    let steps = if method == Divide::Newton { 2 } else { 1 };
    for _ in 0..steps {
        // e = 2^62 - m r (|e| < 2^56 from a table seed, 2^48 from the division's), then
        // r += r e / 2^62 in two shifts so that the product stays below 2^63.
        let e = if method == Divide::Newton {
            // -4 m r wrapped to i64 is 4e (|4e| < 2^63): the same bits with no 64-bit constant
            // to hold across the two steps (on x86-64; a 32-bit core spends two instructions
            // more on it, so the one-step methods keep the subtraction).
            (m as i64 * r).wrapping_neg().wrapping_shl(2) >> 2
        } else {
            (1i64 << 62) - m as i64 * r
        };
        r += (r * (e >> 24)) >> 38;
    }
    r as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bayer_thresholds_cover_every_level_once() {
        for (d, n) in [(Dither::Bayer4, 4), (Dither::Bayer8, 8)] {
            let mut seen = [false; 64];
            for y in 0..n {
                for x in 0..n {
                    let t = d.threshold(x, y);
                    let m = (t * n as u32 * n as u32 / 256) as usize;
                    assert!(!seen[m], "{d:?} ({x}, {y})");
                    seen[m] = true;
                    // Tiles repeat, also at negative coordinates.
                    assert_eq!(t, d.threshold(x - 3 * n, y + 5 * n));
                }
            }
        }
    }

    /// `2^(32 + sh) / d` exactly, in u128 (an independent reference).
    fn exact(d: u32, sh: u32) -> u128 {
        (1u128 << (32 + sh)) / u128::from(d)
    }

    /// The largest shortfall of `reciprocal_u32` below the exact reciprocal, relative, in units of
    /// 2^-32, over the given divisors.
    fn worst(method: Divide, ds: impl Iterator<Item = u32>) -> u128 {
        let mut worst = 0;
        for d in ds {
            let (r, sh) = reciprocal_u32(d, method);
            assert!(
                sh <= 28 && r <= 1 << 31,
                "{d} {method:?}: r = {r}, sh = {sh}"
            );
            let e = exact(d, sh);
            // Never above the reciprocal (the floor of 2^(32 + sh) / d is its integer part).
            assert!(u128::from(r) <= e, "{d} {method:?}: {r} > {e}");
            worst = worst.max(((e - u128::from(r)) << 32) / e);
        }
        worst
    }

    /// The Newton-Raphson step as first written, `e = 2^62 - m r`, `r += r (e >> 24) >> 38`: the
    /// wrapped form of `reciprocal_normal` must give the same bits.
    fn plain_reciprocal(m: u32, method: Divide) -> u64 {
        let mut r = match method {
            Divide::Exact | Divide::Reciprocal => i64::from(reciprocal_seed(m)) << 14,
            Divide::Newton => i64::from(RECIPROCAL_TABLE[((m >> 25) & 63) as usize]),
        };
        for _ in 0..if method == Divide::Newton { 2 } else { 1 } {
            let e = (1i64 << 62) - m as i64 * r;
            r += (r * (e >> 24)) >> 38;
        }
        r as u64
    }

    #[test]
    fn newton_step_is_the_plain_one() {
        let mut x = 0x0bad_cafeu32;
        let random = core::iter::from_fn(move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            Some(x | 1 << 31)
        })
        .take(200_000);
        // Each table interval's ends and middle, where the table's seed is furthest off.
        let edges = (0..64u32).flat_map(|i| {
            let lo = (64 + i) << 25;
            [lo, lo + 1, lo + (1 << 24), lo + ((1 << 25) - 1)]
        });
        for m in random.chain(edges).chain([u32::MAX, 1 << 31]) {
            for method in [Divide::Exact, Divide::Reciprocal, Divide::Newton] {
                assert_eq!(
                    reciprocal_normal(u64::from(m), method),
                    plain_reciprocal(m, method),
                    "{m}"
                );
            }
        }
    }

    #[test]
    fn reciprocal_of_a_double_is_the_reciprocal() {
        let mut x = 0x2545_f491u32;
        let random = core::iter::from_fn(move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            Some(x >> (x & 31).min(2))
        })
        .take(100_000);
        let edges = (1..3000u32).chain((0..29).flat_map(|b| [(1 << b) - 1, 1 << b, (1 << b) + 1]));
        for w in random.chain(edges).filter(|w| (1..1 << 29).contains(w)) {
            for method in [Divide::Exact, Divide::Reciprocal, Divide::Newton] {
                assert_eq!(
                    reciprocal_double(w, method),
                    reciprocal_u32(2 * w, method),
                    "{w}"
                );
            }
        }
    }

    #[test]
    fn reciprocals_stay_just_below() {
        let mut x = 0x1234_5678u32;
        let random = core::iter::from_fn(move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            Some(x >> 2)
        })
        .filter(|&d| d >= 2)
        .take(200_000);
        let edges = (2..5000u32).chain((0..=30).flat_map(|b| {
            let p = 1u32 << b;
            [p.saturating_sub(1), p, p + 1].into_iter()
        }));
        let edges = edges.filter(|d| (2..1 << 30).contains(d));
        for method in [Divide::Exact, Divide::Reciprocal, Divide::Newton] {
            let w = worst(method, random.clone().chain(edges.clone()));
            // Measured: 4 (2^-30) from the division's seed, 16 (2^-28) from the table's; the
            // projection needs below 32 (2^-27).
            let bound = if method == Divide::Newton { 31 } else { 8 };
            assert!(w <= bound, "{method:?}: {w} / 2^32");
        }
    }
}
