//! The vertex scratch: each mesh vertex transformed, projected and shaded at most once a frame.
//!
//! A draw call takes a slice of [`VertexSlot`]s from the caller, one per mesh vertex. When the
//! draw begins, every slot gets its vertex's projected screen position (26.6 by default) and
//! depth; the first visible triangle that uses a vertex adds the shader's values, packed
//! ([`Packed`]: three `u16` channels for the colour shaders, so a Gouraud slot is 16 bytes).
//! Vertices beyond the slice's length are processed again by every triangle that uses them: a
//! short scratch is slower, never wrong.

/// What a [`VertexSlot`] keeps of a vertex's shader values, with a value meaning "not shaded
/// yet".
pub trait Packed: Copy + core::fmt::Debug {
    /// Not shaded yet.
    const EMPTY: Self;
    /// All bits zero: what a `static` scratch starts as (in `.bss`, costing no flash).
    const ZERO: Self;
    /// True for [`Packed::EMPTY`] (a value a shader may also produce is only recomputed).
    fn is_empty(&self) -> bool;
}

/// A packed form of the shader values `V`.
pub trait Stored<V>: Packed {
    /// Packs values.
    fn pack(v: &V) -> Self;
    /// The values back.
    fn unpack(&self) -> V;
}

impl<const N: usize> Packed for [i32; N] {
    const EMPTY: Self = [i32::MIN; N];
    const ZERO: Self = [0; N];
    #[inline(always)]
    fn is_empty(&self) -> bool {
        self.first() == Some(&i32::MIN)
    }
}

/// Any values, kept as they are.
impl<const N: usize> Stored<[i32; N]> for [i32; N] {
    #[inline(always)]
    fn pack(v: &[i32; N]) -> Self {
        *v
    }
    #[inline(always)]
    fn unpack(&self) -> [i32; N] {
        *self
    }
}

impl Packed for [u16; 3] {
    const EMPTY: Self = [u16::MAX; 3];
    const ZERO: Self = [0; 3];
    #[inline(always)]
    fn is_empty(&self) -> bool {
        self[0] == u16::MAX
    }
}

/// Three values in `0 ..= 65534` (the colour shaders' channels), in six bytes.
impl Stored<[i32; 3]> for [u16; 3] {
    #[inline(always)]
    fn pack(v: &[i32; 3]) -> Self {
        v.map(|c| c.clamp(0, 65534) as u16)
    }
    #[inline(always)]
    fn unpack(&self) -> [i32; 3] {
        self.map(i32::from)
    }
}

/// Marks a slot whose vertex lies outside the clip volume's guard band (its outcode is in `y`).
pub(crate) const OUTSIDE: i32 = i32::MIN + 1;
/// The smallest screen x a projected vertex keeps, above the mark (far outside the guard band, so
/// it never draws anyway).
pub(crate) const X_MIN: i32 = i32::MIN + 2;

/// One mesh vertex's work for the frame: its screen position and depth, and its packed shader
/// values. `St` is the shading model's [`crate::pipeline::shading::Shading::Stored`]: `[u16; 3]`
/// (16 bytes a slot) for Gouraud and vertex colours, `[i32; 0]` (12 bytes) for unlit and flat
/// shading, `[i32; 6]` (36 bytes) for Phong.
///
/// Make the scratch with [`VertexSlot::EMPTY`] (`[VertexSlot::EMPTY; 507]`); a draw call fills
/// the slots it uses when it starts, so their contents before it do not matter.
#[derive(Debug, Clone, Copy)]
pub struct VertexSlot<St = [u16; 3]> {
    pub(crate) x: i32,
    pub(crate) y: i32,
    pub(crate) z: u16,
    pub(crate) st: St,
}

impl<St: Packed> VertexSlot<St> {
    /// An unused slot, all bits zero (so a `static` scratch costs no flash).
    pub const EMPTY: Self = Self {
        x: 0,
        y: 0,
        z: 0,
        st: St::ZERO,
    };
}

impl<St: Packed> Default for VertexSlot<St> {
    fn default() -> Self {
        Self::EMPTY
    }
}
