//! Small triangles, which the fills set up in `i32` and hand to a surface a run of rows at a time
//! (`Surface::fill_short_rows_in_clip`, `Surface::fill_short_halves_in_clip`,
//! `Surface::shade_short_rows_in_clip`), across the clip area's edges too: every surface gives
//! the same pixels, whether it steps its rows itself (`Framebuffer` of every storage, `Band`,
//! `ClipTo`) or takes the default methods (`AnyTarget`), and a flat fill covers exactly the
//! reference's pixels.

use proptest::prelude::*;
use rasterizer_core::prelude::*;
use rasterizer_core::surface::{Band, ClipTo, Storage};
use std::collections::BTreeSet;

use tests::{reference_triangle, StrictMock};

const W: u32 = 40;
const H: u32 = 30;

/// A triangle within a few pixels of `(cx, cy)` (1/256 pixels), at `B` sub-pixel bits, now and
/// then on a grid of whole or half pixels (vertices on rows, columns and centres, flat tops and
/// bottoms, centres on edges).
fn triangle<const B: u32>(cx: i32, cy: i32, d: [i32; 6], grid: i32) -> [SubPoint<B>; 3] {
    let to = |c: i32, o: i32| {
        let raw = (c + o) >> (8 - B);
        let g = (grid << B) >> 8;
        if g > 1 {
            raw.div_euclid(g) * g
        } else {
            raw
        }
    };
    [
        SubPoint::raw(to(cx, d[0]), to(cy, d[1])),
        SubPoint::raw(to(cx, d[2]), to(cy, d[3])),
        SubPoint::raw(to(cx, d[4]), to(cy, d[5])),
    ]
}

/// A fill: flat in the first colour, or Gouraud.
#[derive(Clone, Copy)]
enum Fill<const B: u32, C> {
    Flat([SubPoint<B>; 3], C),
    Smooth([SubPoint<B>; 3], [C; 3]),
}

impl<const B: u32, C: PixelColor + rasterizer_core::color::Channels> Fill<B, C> {
    /// The fill into `surface`, clipped to `clip`.
    fn draw<S: Surface<Color = C>>(self, surface: &mut S, clip: Rectangle) {
        let mut clipped = ClipTo::new(surface, clip);
        let _ = match self {
            Fill::Flat(v, c) => fill_triangle(&mut clipped, v, c),
            Fill::Smooth(v, c) => fill_triangle_gouraud(&mut clipped, v, c),
        };
    }
}

/// Every pixel of a framebuffer.
fn pixels<C: Storage>(fb: &Framebuffer<'_, C>) -> Vec<C> {
    (0..H as i32)
        .flat_map(|y| (0..W as i32).map(move |x| Point::new(x, y)))
        .map(|p| fb.pixel(p).unwrap())
        .collect()
}

/// The pixels of `fill` through a framebuffer of `C` (blank: all words `blank`), through `Band`s
/// of `rows` rows, and through `AnyTarget` over a mock: all the same.
fn same_everywhere<const B: u32, C>(
    fill: Fill<B, C>,
    blank: C::Word,
    (clip, rows): (Rectangle, u32),
) -> Result<Vec<C>, TestCaseError>
where
    C: Storage + PixelColor + PartialEq + core::fmt::Debug,
{
    let len = Framebuffer::<C>::required_len(W, H).unwrap();
    let mut buf = vec![blank; len];
    let mut fb = Framebuffer::<C>::new(&mut buf, W, H).unwrap();
    let background = fb.pixel(Point::zero()).unwrap();
    fill.draw(&mut fb, clip);
    let want = pixels(&fb);
    // Through the default methods.
    let mut mock = StrictMock::<C>::new(W, H);
    fill.draw(&mut AnyTarget::new(&mut mock), clip);
    let got: Vec<C> = (0..H as i32)
        .flat_map(|y| (0..W as i32).map(move |x| (x, y)))
        .map(|(x, y)| mock.get(x, y).unwrap_or(background))
        .collect();
    prop_assert_eq!(&got, &want, "AnyTarget");
    // In bands of `rows` rows (the last one shorter), each its own framebuffer.
    let mut whole = vec![blank; len];
    for y0 in (0..H).step_by(rows as usize) {
        let h = rows.min(H - y0);
        let n = Framebuffer::<C>::required_len(W, h).unwrap();
        let start = n / h as usize * y0 as usize;
        let fb = Framebuffer::<C>::new(&mut whole[start..start + n], W, h).unwrap();
        fill.draw(&mut Band::new(fb, y0 as i32), clip);
    }
    let fb = Framebuffer::<C>::new(&mut whole, W, H).unwrap();
    prop_assert_eq!(&pixels(&fb), &want, "bands");
    Ok(want)
}

/// Small triangles in Rgb565 (the stepped rows of the framebuffer's own storage) and Gray8 (the
/// `Storage` defaults), flat and Gouraud, at 0, 4 and 8 sub-pixel bits: the same pixels through
/// every surface, and the flat fill's are the reference's.
fn check<const B: u32>(
    (cx, cy): (i32, i32),
    d: [i32; 6],
    grid: i32,
    raw: [u16; 3],
    (clip, rows): (Rectangle, u32),
) -> Result<(), TestCaseError> {
    let v = triangle::<B>(cx, cy, d, grid);
    let c = raw.map(|r| Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(r)));
    let flat = same_everywhere(Fill::Flat(v, c[0]), 0, (clip, rows))?;
    let smooth = same_everywhere(Fill::Smooth(v, c), 0, (clip, rows))?;
    let g = raw.map(|r| Gray8::new(r as u8));
    same_everywhere(Fill::Flat(v, g[0]), 0, (clip, rows))?;
    same_everywhere(Fill::Smooth(v, g), 0, (clip, rows))?;
    let inside = |(x, y): (i32, i32)| clip.contains(Point::new(x, y));
    // Cut by the clip area or not (another set-up when the triangle crosses its edge), the
    // Gouraud fill gives each pixel inside it a colour within a step of the uncut one in every
    // channel, and none outside: both are within half a step of the exact blend (a span's
    // start taken exactly where the planes do not serve; a cut span starts elsewhere).
    let screen = Rectangle::new(Point::zero(), Size::new(W, H));
    let uncut = same_everywhere(Fill::Smooth(v, c), 0, (screen, rows))?;
    let channels = |c: Rgb565| [i32::from(c.r()), i32::from(c.g()), i32::from(c.b())];
    let blank = Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(0));
    for (i, (&got, &all)) in smooth.iter().zip(&uncut).enumerate() {
        let p = (i as i32 % W as i32, i as i32 / W as i32);
        let near = channels(got)
            .iter()
            .zip(channels(all))
            .all(|(a, b)| (a - b).abs() <= 1);
        prop_assert!(
            if inside(p) { near } else { got == blank },
            "{:?}: {:?} {:?}",
            p,
            got,
            all
        );
    }
    // The flat fill's pixels: the reference's inside the clip area.
    let want: BTreeSet<(i32, i32)> = reference_triangle(
        v.map(|p| (i64::from(p.x), i64::from(p.y))),
        B,
        W as i32,
        H as i32,
    )
    .into_iter()
    .filter(|&p| inside(p))
    .collect();
    let lit: BTreeSet<(i32, i32)> = (0..H as i32)
        .flat_map(|y| (0..W as i32).map(move |x| (x, y)))
        .filter(|&(x, y)| flat[(y * W as i32 + x) as usize] == c[0])
        .collect();
    // A colour other than the blank one, which `raw` (never zero) guarantees.
    prop_assert_eq!(&lit, &want);
    Ok(())
}

/// A clip area crossing the target, and the rows of a band.
fn clip_and_rows() -> impl Strategy<Value = (Rectangle, u32)> {
    (0i32..12, 0i32..10, 8u32..40, 6u32..30, 1u32..9)
        .prop_map(|(x, y, w, h, rows)| (Rectangle::new(Point::new(x, y), Size::new(w, h)), rows))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn small_triangles_same_on_every_surface(
        centre in (-4 * 256..44 * 256, -4 * 256..34 * 256),
        d in proptest::array::uniform6(-6 * 256..6 * 256),
        grid in prop_oneof![3 => Just(1), 1 => Just(128), 1 => Just(256)],
        raw in proptest::array::uniform3(1u16..),
        clip in clip_and_rows(),
    ) {
        check::<0>(centre, d, grid, raw, clip)?;
        check::<4>(centre, d, grid, raw, clip)?;
        check::<8>(centre, d, grid, raw, clip)?;
    }

    /// Up to the size limit of the `i32` set-up (64 pixels each way) and a little past it.
    #[test]
    fn larger_triangles_same_on_every_surface(
        centre in (0..40 * 256, 0..30 * 256),
        d in proptest::array::uniform6(-34 * 256..34 * 256),
        raw in proptest::array::uniform3(1u16..),
        clip in clip_and_rows(),
    ) {
        check::<4>(centre, d, 1, raw, clip)?;
        check::<8>(centre, d, 1, raw, clip)?;
    }
}

/// A middle row outside the rows handed to `fill_short_halves_in_clip` is a caller's error the
/// framebuffer checks in a debug build, rather than walking a wrapped-round count of rows.
#[cfg(debug_assertions)]
#[test]
#[should_panic(expected = "rows")]
fn halves_with_the_middle_row_outside_panic_in_a_debug_build() {
    let mut buf = vec![0u16; (W * H) as usize];
    let mut fb = Framebuffer::<Rgb565>::new(&mut buf, W, H).unwrap();
    let _ = fb.fill_short_halves_in_clip(0, (5, 2, 8), Rgb565::RED, (0, 0), |_| (0, 0));
}
