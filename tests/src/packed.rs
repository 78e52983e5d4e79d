//! A minimal encoder of the packed mesh format, written from the format's documentation, so the
//! reader can be tested without the host converter.

/// One vertex: position quanta, optional normal quanta and colour.
#[derive(Debug, Clone, Copy, Default)]
pub struct Vert {
    /// Position quanta.
    pub q: [i16; 3],
    /// Normal quanta.
    pub n: [i16; 3],
    /// Colour.
    pub c: [u8; 3],
}

/// A texture section: the sides' powers of two and the texel bytes (written as given, so a test
/// can give a wrong length).
#[derive(Debug, Clone, Copy)]
pub struct Tex<'a> {
    /// The width's power of two.
    pub width_log2: u8,
    /// The height's power of two.
    pub height_log2: u8,
    /// The texel bytes.
    pub texels: &'a [u8],
}

/// Encodes a mesh: `offset` and `scale` per axis as the format defines them (version 1).
pub fn encode(
    verts: &[Vert],
    tris: &[[u32; 3]],
    offset: [i32; 3],
    scale: [u32; 3],
    normals: bool,
    colors: bool,
    wide: bool,
) -> Vec<u8> {
    encode_v2(
        verts, tris, offset, scale, normals, colors, wide, None, None,
    )
}

/// Encodes a mesh with texture coordinates (one pair per vertex) and a texture, either optional;
/// version 2 when either is given, else version 1.
#[allow(clippy::too_many_arguments)]
pub fn encode_v2(
    verts: &[Vert],
    tris: &[[u32; 3]],
    offset: [i32; 3],
    scale: [u32; 3],
    normals: bool,
    colors: bool,
    wide: bool,
    uvs: Option<&[[i32; 2]]>,
    texture: Option<Tex<'_>>,
) -> Vec<u8> {
    encode_v3(
        verts, tris, offset, scale, normals, colors, wide, uvs, texture, None,
    )
}

/// [`encode_v2`] with optional adjacency (written as given, so a test can give a wrong length or
/// entry): version 3 when it is given. Entries are `u16` up to 65,535 triangles (`u32::MAX`
/// written as `0xFFFF`, others cut to 16 bits), else `u32`.
#[allow(clippy::too_many_arguments)]
pub fn encode_v3(
    verts: &[Vert],
    tris: &[[u32; 3]],
    offset: [i32; 3],
    scale: [u32; 3],
    normals: bool,
    colors: bool,
    wide: bool,
    uvs: Option<&[[i32; 2]]>,
    texture: Option<Tex<'_>>,
    adjacency: Option<&[[u32; 3]]>,
) -> Vec<u8> {
    let mut b = Vec::new();
    b.extend_from_slice(b"RMSH");
    let version: u16 = if adjacency.is_some() {
        3
    } else if uvs.is_some() || texture.is_some() {
        2
    } else {
        1
    };
    b.extend_from_slice(&version.to_le_bytes());
    let flags = u16::from(normals)
        | u16::from(colors) << 1
        | u16::from(wide) << 2
        | u16::from(uvs.is_some()) << 3
        | u16::from(texture.is_some()) << 4
        | u16::from(adjacency.is_some()) << 5;
    b.extend_from_slice(&flags.to_le_bytes());
    b.extend_from_slice(&(verts.len() as u32).to_le_bytes());
    b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for o in offset {
        b.extend_from_slice(&o.to_le_bytes());
    }
    for s in scale {
        b.extend_from_slice(&s.to_le_bytes());
    }
    let pad = |b: &mut Vec<u8>| {
        while !b.len().is_multiple_of(4) {
            b.push(0);
        }
    };
    for v in verts {
        for q in v.q {
            b.extend_from_slice(&q.to_le_bytes());
        }
    }
    pad(&mut b);
    if normals {
        for v in verts {
            for q in v.n {
                b.extend_from_slice(&q.to_le_bytes());
            }
        }
        pad(&mut b);
    }
    if colors {
        for v in verts {
            b.extend_from_slice(&v.c);
        }
        pad(&mut b);
    }
    if let Some(uvs) = uvs {
        for uv in uvs {
            for c in uv {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
        pad(&mut b);
    }
    for t in tris {
        for i in t {
            if wide {
                b.extend_from_slice(&i.to_le_bytes());
            } else {
                b.extend_from_slice(&(*i as u16).to_le_bytes());
            }
        }
    }
    pad(&mut b);
    if let Some(adjacency) = adjacency {
        for e in adjacency.iter().flatten() {
            if tris.len() <= 0xFFFF {
                let e = if *e == u32::MAX { 0xFFFF } else { *e as u16 };
                b.extend_from_slice(&e.to_le_bytes());
            } else {
                b.extend_from_slice(&e.to_le_bytes());
            }
        }
        pad(&mut b);
    }
    if let Some(t) = texture {
        b.extend_from_slice(&[t.width_log2, t.height_log2, 0, 0]);
        b.extend_from_slice(t.texels);
        pad(&mut b);
    }
    b
}
