//! The `convert` command: OBJ -> packed mesh (or Rust source).
//!
//! The OBJ file is read by `fixtures::obj::read` (the reader every path that loads a model
//! shares: line checks, tobj's numbers, ear clipping). Then: optional welding, dropping
//! triangles with a repeated vertex or no area after quantisation, dropping unused vertices,
//! optional centring, normals, per-axis quantisation over the bounding box, and [`encode()`].
//! Every blob is checked with `PackedMesh::parse` before it is written, and the position error
//! reported is measured on the decoded blob.
//!
//! Texture coordinates are written when every face corner of the file has one (unless
//! `--no-uvs`), a position used with several becoming several vertices. The texture is the PNG of
//! `--texture FILE`, or else the `map_Kd` of the OBJ's material (unless `--no-texture`): converted
//! to Rgb565 (rounded to the nearest step); its sides must be powers of two of at most 1024 texels
//! unless `--texture-size N` resamples it to N x N (a box filter: each texel the average of the
//! area it covers; `fixtures::texture_file`). A blob with neither texture coordinates nor a
//! texture is format version 1, as before; otherwise version 2.
//!
//! `--adjacency` adds edge adjacency (format version 3), which anti-aliased silhouettes read: 6
//! bytes a triangle up to 65,535 triangles, 12 above, so it is off unless asked for. Triangles
//! are neighbours when they share an edge's *positions* (`fixtures::adjacency::
//! adjacency_by_position` on the quanta), so a seam where texture coordinates or flat normals split
//! vertices still joins, as it does on screen.
//!
//! Exit codes of the command: 0 success, 1 conversion error (bad input, unreadable input,
//! unwritable output), 2 usage error. Errors are one line on stderr, `error: <file>:<line>:
//! <message>` (or `error: <file>: <message>` when no single line is to blame), and no output file
//! is written then: the output goes to a temporary file in the same directory, renamed into place
//! on success. Odd but usable input gives `warning: <file>:<line>: <message>` lines and the
//! conversion goes on.

mod encode;
mod rust_source;

pub use encode::{decode_normal, encode, quantise_normal, MeshData, Quantiser, TextureData};
pub use fixtures::obj::{newell_normal, triangulate_polygon, ObjError as ConvertError, Warning};
pub use rust_source::{bytes_from_rust_source, is_rust_identifier, rust_source, static_name_for};

use crate::progress::Progress;
use fixtures::adjacency::adjacency_by_position;
use fixtures::obj::normalize;
use fixtures::vec64::{cross, dot, sub, V3 as P3};
use rasterizer_core::mesh::{MAX_COUNT, NO_NEIGHBOUR};
use rasterizer_core::prelude::*;
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Where vertex normals come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum NormalMode {
    /// No normals in the output.
    None,
    /// The file's normals (normalised; a zero one is replaced by the smooth normal).
    Keep,
    /// One normal per triangle; vertices are split so each triangle has its own.
    Flat,
    /// Angle-weighted average of the adjacent triangles' normals, per position.
    Smooth,
}

impl fmt::Display for NormalMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::None => "no",
            Self::Keep => "kept",
            Self::Flat => "flat",
            Self::Smooth => "smooth",
        })
    }
}

/// Checks a `--name` value: an identifier that is not a keyword.
fn parse_static_name(s: &str) -> Result<String, String> {
    if is_rust_identifier(s) {
        Ok(s.to_owned())
    } else {
        Err(format!("`{s}` is not a Rust identifier"))
    }
}

/// Options of the `convert` command.
#[derive(Debug, clap::Args)]
pub struct ConvertArgs {
    /// The OBJ file to convert.
    pub input: PathBuf,
    /// The output file (replaced only when the conversion succeeds).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
    /// Centre the mesh on its bounding-box centre and scale it to fit the unit sphere.
    #[arg(long)]
    pub center_unit_sphere: bool,
    /// Vertex normals: none, keep (the file's), flat (per face) or smooth (angle-weighted).
    /// Default: keep when every face corner has a normal, else smooth.
    #[arg(long, value_enum, value_name = "MODE")]
    pub normals: Option<NormalMode>,
    /// Merge vertices with identical positions and colours (and equal normals after
    /// conversion).
    #[arg(long)]
    pub weld: bool,
    /// Write Rust source instead of the binary: `pub static NAME: [u8; N] = [...];` with a doc
    /// comment; read it with `PackedMesh::parse(&NAME)`.
    #[arg(long)]
    pub rust: bool,
    /// The static's name for --rust (default: the output file's stem in upper case).
    #[arg(long, requires = "rust", value_parser = parse_static_name)]
    pub name: Option<String>,
    /// The texture, a PNG with power-of-two sides of at most 1024 (any sides with
    /// --texture-size); default: the `map_Kd` of the OBJ's material, if any.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["no_texture", "no_uvs"])]
    pub texture: Option<PathBuf>,
    /// Resample the texture to N x N texels (N a power of two, at most 1024) with a box filter.
    #[arg(long, value_name = "N", conflicts_with_all = ["no_texture", "no_uvs"])]
    pub texture_size: Option<u32>,
    /// Write no texture, even if the OBJ's material names one.
    #[arg(long)]
    pub no_texture: bool,
    /// Write no texture coordinates (and so no texture).
    #[arg(long)]
    pub no_uvs: bool,
    /// Write edge adjacency (format version 3) for anti-aliased silhouettes: 6 more bytes a
    /// triangle (12 above 65,535 triangles).
    #[arg(long)]
    pub adjacency: bool,
}

/// What [`convert_obj`] does, apart from the input.
#[derive(Debug, Clone, Copy, Default)]
pub struct Options {
    /// Centre on the bounding-box centre and scale to fit the unit sphere.
    pub center_unit_sphere: bool,
    /// Where normals come from; `None` for the default (keep if present, else smooth).
    pub normals: Option<NormalMode>,
    /// Merge vertices with identical positions (and colours, and normals after conversion).
    pub weld: bool,
    /// Drop the file's texture coordinates.
    pub no_uvs: bool,
    /// Compute and write edge adjacency (format version 3).
    pub adjacency: bool,
    /// Show a progress bar on stderr (when it is a terminal).
    pub progress: bool,
}

/// The figures of one conversion.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Triangles in the file after triangulation (a face of n corners counts n - 2).
    pub triangles_in: usize,
    /// Triangles written.
    pub triangles_out: usize,
    /// `v` lines in the file.
    pub vertices_in: usize,
    /// Vertices written (can exceed `vertices_in` when normals split vertices).
    pub vertices_out: usize,
    /// Triangles dropped for using one vertex twice.
    pub repeated_index: usize,
    /// Triangles dropped for having no area after quantisation.
    pub zero_area: usize,
    /// File positions no written triangle uses (never referenced, or only by dropped triangles).
    pub unused_vertices: usize,
    /// File positions merged into an identical earlier one by `--weld`.
    pub welded_vertices: usize,
    /// Where the normals came from.
    pub normals: NormalMode,
    /// `(centre, factor)` of `--center-unit-sphere`: output = (input - centre) * factor.
    pub transform: Option<([f64; 3], f64)>,
    /// The box the positions were quantised over (output units).
    pub bounds: ([f64; 3], [f64; 3]),
    /// Largest difference between a decoded position component and the input (output units).
    pub max_error: f64,
    /// `max_error` per axis divided by that axis's extent, the largest over the axes.
    pub max_error_fraction: f64,
    /// Largest difference between a decoded normal component and the unit normal computed.
    pub max_normal_error: Option<f64>,
    /// Whether texture coordinates were written.
    pub uvs: bool,
    /// The texture's width and height, when one was written.
    pub texture: Option<(u32, u32)>,
    /// With adjacency written: the triangle edges without a neighbour (boundary, shared by more
    /// than two triangles, or wound inconsistently); 0 for a closed, consistent mesh.
    pub open_edges: Option<usize>,
    /// Size of the blob in bytes.
    pub bytes: usize,
}

/// A finished conversion.
#[derive(Debug, Clone)]
pub struct Conversion {
    /// The mesh as written.
    pub mesh: MeshData,
    /// The encoded blob (it passed `PackedMesh::parse`).
    pub blob: Vec<u8>,
    /// The figures.
    pub report: Report,
    /// The texture file the OBJ's material names (`map_Kd`), if any; not read by
    /// [`convert_obj`] (see [`Conversion::with_texture`]).
    pub material_texture: Option<PathBuf>,
}

impl Conversion {
    /// The conversion with `texture` added to the blob (which must have texture coordinates).
    ///
    /// # Errors
    /// A message when the mesh has no texture coordinates, or (an internal error) when the blob
    /// does not parse.
    pub fn with_texture(mut self, texture: TextureData) -> Result<Self, String> {
        if self.mesh.uvs.is_none() {
            return Err(
                "a texture needs texture coordinates, and the mesh has none (every face \
                        corner needs a `vt`)"
                    .into(),
            );
        }
        self.report.texture = Some((1 << texture.width_log2, 1 << texture.height_log2));
        self.mesh.texture = Some(texture);
        self.blob = encode(&self.mesh);
        PackedMesh::parse(&self.blob)
            .map_err(|e| format!("internal error: the encoded mesh does not parse: {e}"))?;
        self.report.bytes = self.blob.len();
        Ok(self)
    }
}

/// Texture coordinate bits packed into a key, tagged so it never equals a small index.
fn uv_key(uv: [i32; 2]) -> u64 {
    (1 << 63) | (u64::from(uv[0] as u32 & 0x7fff_ffff) << 32) | u64::from(uv[1] as u32)
}

/// A texture coordinate (u, v as in the file) in 16.16 bits, v counted from the top.
fn uv_bits(uv: [f64; 2]) -> [i32; 2] {
    // In range: the reader refuses texture coordinates beyond 16.16.
    [uv[0], 1.0 - uv[1]].map(|c| (c * 65536.0).round() as i32)
}

/// A normal's quanta packed into a key, tagged so it never equals a small index.
fn normal_key(q: [i16; 3]) -> u64 {
    (1 << 63)
        | (u64::from(q[0] as u16) << 32)
        | (u64::from(q[1] as u16) << 16)
        | u64::from(q[2] as u16)
}

/// Converts the OBJ text `bytes`. `file` names it in messages; `mtl_dir` is where its `mtllib`
/// files are looked for (to warn about missing ones). Warnings are pushed onto `warnings`, also
/// when the conversion then fails.
///
/// # Errors
/// A [`ConvertError`] for input that cannot be converted, with the line to blame when there is
/// one.
pub fn convert_obj(
    file: &str,
    bytes: &[u8],
    mtl_dir: Option<&Path>,
    opts: &Options,
    warnings: &mut Vec<Warning>,
) -> Result<Conversion, ConvertError> {
    let progress = Progress::new(opts.progress);
    let result = convert_inner(file, bytes, mtl_dir, opts, warnings, &progress);
    progress.finish();
    result
}

fn convert_inner(
    file: &str,
    bytes: &[u8],
    mtl_dir: Option<&Path>,
    opts: &Options,
    warnings: &mut Vec<Warning>,
    progress: &Progress,
) -> Result<Conversion, ConvertError> {
    let fail = |message: String| ConvertError {
        file: file.to_owned(),
        line: None,
        message,
    };
    let warn = |warnings: &mut Vec<Warning>, line: Option<usize>, message: String| {
        warnings.push(Warning { line, message });
    };

    let obj = fixtures::obj::read(
        file,
        bytes,
        mtl_dir,
        opts.center_unit_sphere,
        warnings,
        progress,
    )?;
    let (pos, corners, mut tris) = (&obj.positions, &obj.corners, obj.triangles.clone());
    let nv = pos.len();
    let col = obj.colors.as_deref().unwrap_or_default();
    let triangles_in = tris.len();
    let keep_possible = obj.normals.is_some();
    let file_normals = obj.normals.as_deref().unwrap_or_default();
    let pos_of = |c: u32| corners[c as usize].v;
    let file_uvs = obj.uvs.as_deref().filter(|_| !opts.no_uvs);

    // Weld: every position id maps to the first identical one (same position and colour).
    let mut canon: Vec<u32> = (0..nv as u32).collect();
    let mut welded_vertices = 0;
    if opts.weld {
        let mut seen: HashMap<([u64; 3], [u8; 3]), u32> = HashMap::new();
        for v in 0..nv {
            let p = pos[v];
            if p[0].is_nan() {
                continue; // never referenced
            }
            // + 0.0 makes -0.0 equal to 0.0.
            let key = (
                p.map(|c| (c + 0.0).to_bits()),
                col.get(v).copied().unwrap_or_default(),
            );
            let first = *seen.entry(key).or_insert(v as u32);
            if first != v as u32 {
                canon[v] = first;
                welded_vertices += 1;
            }
        }
    }
    let vid = |c: u32| canon[pos_of(c) as usize];

    let before = tris.len();
    tris.retain(|t| {
        let [a, b, c] = t.map(vid);
        a != b && b != c && a != c
    });
    let repeated_index = before - tris.len();

    // Quantise over the box of the used positions; dropping zero-area triangles can shrink that
    // box, so repeat until nothing more is dropped.
    progress.stage("quantising", 1);
    let mut zero_area = 0;
    let mut tpos = vec![[0f64; 3]; nv];
    let mut quanta = vec![[0i16; 3]; nv];
    let mut used = vec![false; nv];
    let (quant, transform, bounds) = loop {
        if tris.is_empty() {
            let hint = if zero_area > 0 {
                "; if the model is tiny, --center-unit-sphere rescales it"
            } else {
                ""
            };
            return Err(fail(format!(
                "no triangles left: all {triangles_in} are degenerate (repeated vertex or no \
                 area){hint}"
            )));
        }
        used.iter_mut().for_each(|u| *u = false);
        for t in &tris {
            for &c in t {
                used[vid(c) as usize] = true;
            }
        }
        let ids = || (0..nv).filter(|&v| used[v]);
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for v in ids() {
            for k in 0..3 {
                lo[k] = lo[k].min(pos[v][k]);
                hi[k] = hi[k].max(pos[v][k]);
            }
        }
        let transform = opts.center_unit_sphere.then(|| {
            let c = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
            let r = ids()
                .map(|v| dot(sub(pos[v], c), sub(pos[v], c)).sqrt())
                .fold(0.0, f64::max);
            (c, if r > 0.0 { 1.0 / r } else { 1.0 })
        });
        let (mut tlo, mut thi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for v in ids() {
            tpos[v] = match transform {
                Some((c, s)) => [0, 1, 2].map(|k| (pos[v][k] - c[k]) * s),
                None => pos[v],
            };
            for k in 0..3 {
                tlo[k] = tlo[k].min(tpos[v][k]);
                thi[k] = thi[k].max(tpos[v][k]);
            }
        }
        let quant = Quantiser::for_box(tlo, thi)
            .ok_or_else(|| fail("positions are outside the 16.16 range".into()))?;
        for v in ids() {
            quanta[v] = quant.quantise(tpos[v]);
        }
        let before = tris.len();
        tris.retain(|t| {
            let [a, b, c] = t.map(|c| quanta[vid(c) as usize].map(i64::from));
            let (e, f) = (
                [0, 1, 2].map(|k| b[k] - a[k]),
                [0, 1, 2].map(|k| c[k] - a[k]),
            );
            e[1] * f[2] - e[2] * f[1] != 0
                || e[2] * f[0] - e[0] * f[2] != 0
                || e[0] * f[1] - e[1] * f[0] != 0
        });
        zero_area += before - tris.len();
        if tris.len() == before {
            break (quant, transform, (tlo, thi));
        }
    };
    let used_positions = used.iter().filter(|&&u| u).count();
    let unused_vertices = nv - welded_vertices - used_positions;

    // Normals.
    progress.stage("normals", 1);
    let mut mode = opts.normals.unwrap_or(if keep_possible {
        NormalMode::Keep
    } else {
        NormalMode::Smooth
    });
    if mode == NormalMode::Keep && !keep_possible {
        let why = if obj.vn_lines.is_empty() {
            "the file has no normals"
        } else {
            "not every face corner has a normal"
        };
        warn(
            warnings,
            None,
            format!("--normals keep: {why}; computing smooth normals instead"),
        );
        mode = NormalMode::Smooth;
    }
    let face_normal = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|c| tpos[vid(c) as usize]);
        normalize(cross(sub(b, a), sub(c, a)))
    };
    let mut smooth = vec![[0f64; 3]; if mode == NormalMode::None { 0 } else { nv }];
    if mode != NormalMode::None {
        for t in &tris {
            let Some(n) = face_normal(t) else { continue };
            let p = t.map(|c| tpos[vid(c) as usize]);
            for i in 0..3 {
                let (e1, e2) = (sub(p[(i + 1) % 3], p[i]), sub(p[(i + 2) % 3], p[i]));
                let angle = dot(cross(e1, e2), cross(e1, e2)).sqrt().atan2(dot(e1, e2));
                let s = &mut smooth[vid(t[i]) as usize];
                for k in 0..3 {
                    s[k] += angle * n[k];
                }
            }
        }
        for s in &mut smooth {
            *s = normalize(*s).unwrap_or([0.0, 0.0, 1.0]);
        }
    }
    let mut bad_normals: Vec<usize> = Vec::new();
    let mut non_unit: Vec<usize> = Vec::new();
    let unit_file_normals: Vec<Option<P3>> = if mode == NormalMode::Keep {
        let mut referenced = vec![false; file_normals.len()];
        for t in &tris {
            for &c in t {
                referenced[corners[c as usize].vn as usize] = true;
            }
        }
        file_normals
            .iter()
            .enumerate()
            .map(|(i, &n)| {
                let unit = normalize(n);
                if referenced[i] {
                    match unit {
                        None => bad_normals.push(i),
                        Some(_) if (dot(n, n).sqrt() - 1.0).abs() > 1e-3 => non_unit.push(i),
                        Some(_) => {}
                    }
                }
                unit
            })
            .collect()
    } else {
        Vec::new()
    };
    if let Some(&first) = bad_normals.first() {
        warn(
            warnings,
            Some(obj.vn_lines[first] as usize),
            format!(
                "normal of zero length: vertices using it get smooth normals ({} such normal{})",
                bad_normals.len(),
                if bad_normals.len() == 1 { "" } else { "s" }
            ),
        );
    }
    if let Some(&first) = non_unit.first() {
        warn(
            warnings,
            Some(obj.vn_lines[first] as usize),
            format!(
                "normal not of unit length: normalised ({} such normal{})",
                non_unit.len(),
                if non_unit.len() == 1 { "" } else { "s" }
            ),
        );
    }

    // Output vertices: one per distinct (position, texture coordinate, normal source), in order
    // of first use.
    progress.stage("writing", tris.len() as u64);
    let mut index: HashMap<(u32, u64, u64), u32> = HashMap::with_capacity(used_positions * 2);
    let mut out_pos: Vec<u32> = Vec::with_capacity(used_positions);
    let mut out_nrm: Vec<P3> = Vec::new();
    let mut out_uv: Vec<[i32; 2]> = Vec::new();
    let mut out_tris: Vec<[u32; 3]> = Vec::with_capacity(tris.len());
    for (ti, t) in tris.iter().enumerate() {
        let flat = if mode == NormalMode::Flat {
            face_normal(t)
        } else {
            None
        };
        let mut tri = [0u32; 3];
        for (slot, &c) in tri.iter_mut().zip(t) {
            let v = vid(c);
            let (uv, uv_id) = match file_uvs {
                None => (None, 0),
                Some(file) => {
                    let vt = corners[c as usize].vt;
                    let uv = uv_bits(file[vt as usize]);
                    (
                        Some(uv),
                        if opts.weld {
                            uv_key(uv)
                        } else {
                            u64::from(vt) + 1
                        },
                    )
                }
            };
            let (normal, key) = match mode {
                NormalMode::None => (None, 0),
                NormalMode::Smooth => (Some(smooth[v as usize]), 0),
                NormalMode::Keep => {
                    let vn = corners[c as usize].vn;
                    let n = unit_file_normals[vn as usize].unwrap_or(smooth[v as usize]);
                    let key = if opts.weld {
                        normal_key(quantise_normal(n))
                    } else {
                        u64::from(vn) + 1
                    };
                    (Some(n), key)
                }
                NormalMode::Flat => {
                    let n = flat.unwrap_or(smooth[v as usize]);
                    let key = if opts.weld {
                        normal_key(quantise_normal(n))
                    } else {
                        ti as u64 + 1
                    };
                    (Some(n), key)
                }
            };
            *slot = *index.entry((v, uv_id, key)).or_insert_with(|| {
                out_pos.push(v);
                if let Some(n) = normal {
                    out_nrm.push(n);
                }
                if let Some(uv) = uv {
                    out_uv.push(uv);
                }
                (out_pos.len() - 1) as u32
            });
        }
        out_tris.push(tri);
        if ti % 65536 == 0 {
            progress.set(ti as u64);
        }
    }
    if out_pos.len() > MAX_COUNT as usize || out_tris.len() > MAX_COUNT as usize {
        return Err(fail(format!(
            "{} vertices and {} triangles: the format allows at most {MAX_COUNT} of each",
            out_pos.len(),
            out_tris.len()
        )));
    }

    let mesh = MeshData {
        offset: quant.offset,
        scale: quant.scale,
        positions: out_pos.iter().map(|&v| quanta[v as usize]).collect(),
        normals: (mode != NormalMode::None)
            .then(|| out_nrm.iter().map(|&n| quantise_normal(n)).collect()),
        colors: obj
            .colors
            .is_some()
            .then(|| out_pos.iter().map(|&v| col[v as usize]).collect()),
        uvs: file_uvs.is_some().then_some(out_uv),
        triangles: out_tris,
        texture: None,
        adjacency: None,
    };
    let mesh = MeshData {
        adjacency: opts
            .adjacency
            .then(|| adjacency_by_position(&mesh.triangles, &mesh.positions)),
        ..mesh
    };
    let blob = encode(&mesh);
    let packed = PackedMesh::parse(&blob).map_err(|e| {
        fail(format!(
            "internal error: the encoded mesh does not parse: {e}"
        ))
    })?;

    // The quanta can all differ while their 16.16 decodings coincide (a model smaller than one
    // 16.16 step): such a mesh would draw nothing.
    let decoded_area = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|v| {
            packed
                .position_bits(v as usize)
                .unwrap_or_default()
                .map(i128::from)
        });
        let (e, f) = (
            [0, 1, 2].map(|k| b[k] - a[k]),
            [0, 1, 2].map(|k| c[k] - a[k]),
        );
        e[1] * f[2] - e[2] * f[1] != 0
            || e[2] * f[0] - e[0] * f[2] != 0
            || e[0] * f[1] - e[1] * f[0] != 0
    };
    if !mesh.triangles.iter().any(decoded_area) {
        let extent = (0..3)
            .map(|k| bounds.1[k] - bounds.0[k])
            .fold(0.0, f64::max);
        return Err(fail(format!(
            "the mesh collapses in 16.16 fixed point: its extent is {extent:.3e} and all {} \
             triangles have no area after quantisation; --center-unit-sphere rescales it",
            mesh.triangles.len()
        )));
    }

    // Measure the errors on the decoded blob.
    let mut err = [0f64; 3];
    let mut nerr = 0f64;
    for (i, &v) in out_pos.iter().enumerate() {
        let bits = packed.position_bits(i).unwrap_or_default();
        for k in 0..3 {
            err[k] = err[k].max((f64::from(bits[k]) / 65536.0 - tpos[v as usize][k]).abs());
        }
        if let (Some(nb), Some(n)) = (packed.normal_bits(i), out_nrm.get(i)) {
            for k in 0..3 {
                nerr = nerr.max((f64::from(nb[k]) / 65536.0 - n[k]).abs());
            }
        }
    }
    let max_error = err.iter().copied().fold(0.0, f64::max);
    let max_error_fraction = (0..3)
        .filter(|&k| bounds.1[k] > bounds.0[k])
        .map(|k| err[k] / (bounds.1[k] - bounds.0[k]))
        .fold(0.0, f64::max);
    if max_error_fraction > 1e-3 {
        warn(
            warnings,
            None,
            format!(
                "the model is small for 16.16 fixed point: positions are off by up to \
                 {max_error_fraction:.1e} of its size; --center-unit-sphere rescales it"
            ),
        );
    }
    let report = Report {
        triangles_in,
        triangles_out: mesh.triangles.len(),
        vertices_in: nv,
        vertices_out: mesh.positions.len(),
        repeated_index,
        zero_area,
        unused_vertices,
        welded_vertices,
        normals: mode,
        transform,
        bounds,
        max_error,
        max_error_fraction,
        max_normal_error: mesh.normals.is_some().then_some(nerr),
        uvs: mesh.uvs.is_some(),
        texture: None,
        open_edges: mesh
            .adjacency
            .as_ref()
            .map(|a| a.iter().flatten().filter(|&&u| u == NO_NEIGHBOUR).count()),
        bytes: blob.len(),
    };
    Ok(Conversion {
        mesh,
        blob,
        report,
        material_texture: obj.texture.clone(),
    })
}

impl Report {
    /// The one-line summary the command prints on stdout (without the file names).
    pub fn summary(&self) -> String {
        let mut s = format!(
            "{} -> {} triangles, {} -> {} vertices; dropped {} degenerate triangles ({} repeated \
             vertex, {} zero area) and {} unused vertices; {} welded; {} normals; {} bytes; max \
             quantisation error {:.3e} ({:.3e} of the extent)",
            self.triangles_in,
            self.triangles_out,
            self.vertices_in,
            self.vertices_out,
            self.repeated_index + self.zero_area,
            self.repeated_index,
            self.zero_area,
            self.unused_vertices,
            self.welded_vertices,
            self.normals,
            self.bytes,
            self.max_error,
            self.max_error_fraction,
        );
        if let Some(e) = self.max_normal_error {
            s += &format!(", normals {e:.3e}");
        }
        if self.uvs {
            s += "; texture coordinates";
        }
        if let Some((w, h)) = self.texture {
            s += &format!("; a {w}x{h} texture");
        }
        if let Some(open) = self.open_edges {
            s += &format!("; adjacency ({open} edges without a neighbour)");
        }
        if let Some((c, f)) = self.transform {
            s += &format!(
                "; centred on ({:.6}, {:.6}, {:.6}) and scaled by {f:.6}",
                c[0], c[1], c[2]
            );
        }
        s
    }
}

/// Runs the command: converts, prints warnings on stderr and the summary on stdout, and writes
/// the output only on success.
///
/// # Errors
/// A [`ConvertError`] (boxed) for the `error:` line.
pub fn run(args: &ConvertArgs) -> Result<(), Box<dyn std::error::Error>> {
    let started = Instant::now();
    let file = args.input.display().to_string();
    let bytes = std::fs::read(&args.input).map_err(|e| ConvertError {
        file: file.clone(),
        line: None,
        message: format!("cannot read: {e}"),
    })?;
    let opts = Options {
        center_unit_sphere: args.center_unit_sphere,
        normals: args.normals,
        weld: args.weld,
        no_uvs: args.no_uvs,
        adjacency: args.adjacency,
        progress: bytes.len() > (1 << 20),
    };
    let mut warnings = Vec::new();
    let result = convert_obj(&file, &bytes, args.input.parent(), &opts, &mut warnings);
    for w in &warnings {
        crate::errln!("warning: {}", w.display(&file));
    }
    let mut conv = result?;
    if let Some(tex) = load_texture(args, &file, conv.material_texture.as_deref())? {
        conv = conv.with_texture(tex).map_err(|message| ConvertError {
            file: file.clone(),
            line: None,
            message: format!("--texture: {message}"),
        })?;
    }
    let out = if args.rust {
        let name = args.name.clone().unwrap_or_else(|| {
            static_name_for(
                &args
                    .output
                    .file_stem()
                    .map(|s| s.to_string_lossy())
                    .unwrap_or_default(),
            )
        });
        let r = &conv.report;
        let source_name = args
            .input
            .file_name()
            .map(|s| s.to_string_lossy())
            .unwrap_or_default();
        let texture = r
            .texture
            .map(|(w, h)| format!("a {w}x{h} texture, "))
            .unwrap_or_default();
        let doc =
            format!(
            "Packed mesh (format v{}) converted from `{source_name}` by `host-tools convert`.\n\n\
             {} triangles, {} vertices, {} normals, {}{}{}{}{}-bit indices; max quantisation \
             error {:.3e}.\n\
             Read it in place with `rasterizer_core::mesh::PackedMesh::parse(&{name})`.",
            conv.mesh.version(),
            r.triangles_out,
            r.vertices_out,
            r.normals,
            if conv.mesh.colors.is_some() { "colours, " } else { "" },
            if r.uvs { "texture coordinates, " } else { "" },
            texture,
            if conv.mesh.adjacency.is_some() { "adjacency, " } else { "" },
            if conv.mesh.wide_indices() { 32 } else { 16 },
            r.max_error,
        );
        rust_source(&name, &conv.blob, &doc).into_bytes()
    } else {
        conv.blob.clone()
    };
    crate::output::write_output(&args.output, &[args.input.as_path()], |w| {
        std::io::Write::write_all(w, &out)
    })?;
    crate::outln!(
        "{file} -> {}: {}; {:.2} s",
        args.output.display(),
        conv.report.summary(),
        started.elapsed().as_secs_f64()
    )?;
    Ok(())
}

/// The texture the command writes: `--texture`, else the material's `map_Kd` (unless
/// `--no-texture` or `--no-uvs`), loaded and converted; `None` without either.
fn load_texture(
    args: &ConvertArgs,
    file: &str,
    material: Option<&Path>,
) -> Result<Option<TextureData>, ConvertError> {
    let (path, origin) = match (&args.texture, material) {
        (Some(p), _) => (p.as_path(), String::new()),
        _ if args.no_texture || args.no_uvs => return Ok(None),
        (None, Some(p)) => (
            p,
            format!(" (named by `map_Kd` in {file}'s material; --no-texture converts without it)"),
        ),
        (None, None) => {
            if args.texture_size.is_some() {
                return Err(ConvertError {
                    file: file.to_owned(),
                    line: None,
                    message: "--texture-size but no texture: give one with --texture FILE".into(),
                });
            }
            return Ok(None);
        }
    };
    let shown = path.display().to_string();
    let fail = |message: String| ConvertError {
        file: shown.clone(),
        line: None,
        message: format!("{message}{origin}"),
    };
    use fixtures::texture_file::{TextureFileError as E, TextureImage, MAX_SIDE};
    let image = TextureImage::load_png(path, args.texture_size).map_err(|e| match e {
        E::Read(e) if e.kind() == std::io::ErrorKind::NotFound => {
            fail("texture file not found".into())
        }
        E::NotPowerOfTwo { .. } | E::TooLarge { .. } => fail(format!(
            "{e}; --texture-size N (a power of two up to {MAX_SIDE}) resamples it"
        )),
        E::BadSize(_) => fail(format!("--texture-size: {e}")),
        e => fail(e.to_string()),
    })?;
    Ok(Some(TextureData {
        width_log2: image.width_log2,
        height_log2: image.height_log2,
        texels: image.texels,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn convert(text: &str, opts: Options) -> (Result<Conversion, ConvertError>, Vec<Warning>) {
        let mut w = Vec::new();
        let r = convert_obj("t.obj", text.as_bytes(), None, &opts, &mut w);
        (r, w)
    }

    #[test]
    fn quad_with_normals_keeps_them() {
        let (r, w) = convert(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 2\nf 1//1 2//1 3//1 4//1\n",
            Options::default(),
        );
        let c = r.unwrap();
        assert_eq!(c.report.normals, NormalMode::Keep);
        assert_eq!(c.report.triangles_out, 2);
        assert_eq!(c.mesh.normals.as_ref().unwrap()[0], [0, 0, 32767]);
        assert_eq!(w.len(), 1, "non-unit normal: {w:?}");
    }

    #[test]
    fn degenerate_and_unused_are_counted() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 5 5 5\n\
                    f 1 2 3\nf 1 1 2\nf 1 2 4\n";
        let (r, _) = convert(text, Options::default());
        let r = r.unwrap().report;
        assert_eq!((r.triangles_in, r.triangles_out), (3, 1));
        assert_eq!((r.repeated_index, r.zero_area), (1, 1));
        // Vertex 4 only in a zero-area triangle, vertex 5 never used.
        assert_eq!(r.unused_vertices, 2);
        assert_eq!(r.vertices_out, 3);
    }

    #[test]
    fn weld_merges_identical_positions() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 4 6 5\n";
        let plain = convert(text, Options::default()).0.unwrap().report;
        assert_eq!(plain.vertices_out, 6);
        let opts = Options {
            weld: true,
            ..Options::default()
        };
        let welded = convert(text, opts).0.unwrap().report;
        assert_eq!((welded.vertices_out, welded.welded_vertices), (4, 2));
    }

    #[test]
    fn flat_normals_split_vertices() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n";
        let opts = |weld| Options {
            normals: Some(NormalMode::Flat),
            weld,
            ..Options::default()
        };
        let c = convert(text, opts(false)).0.unwrap();
        assert_eq!(c.report.vertices_out, 6);
        let n = c.mesh.normals.unwrap();
        assert_eq!(n[0], [0, 0, -32767]);
        assert_eq!(n[3], [0, -32767, 0]);
        assert_eq!(convert(text, opts(true)).0.unwrap().report.vertices_out, 6);
    }

    #[test]
    fn colours_are_written() {
        let text = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
        let c = convert(text, Options::default()).0.unwrap();
        assert_eq!(
            c.mesh.colors.unwrap(),
            vec![[255, 0, 0], [0, 255, 0], [0, 0, 255]]
        );
        let (r, w) = convert(
            "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            Options::default(),
        );
        assert!(r.unwrap().mesh.colors.is_none());
        assert_eq!(w.len(), 1);
    }

    #[test]
    fn errors_name_the_line() {
        let e = convert("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", Options::default())
            .0
            .unwrap_err();
        assert_eq!(e.to_string().split(": ").next(), Some("t.obj:4"));
        let all_degenerate = convert("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", Options::default());
        assert_eq!(all_degenerate.0.unwrap_err().line, None);
    }

    #[test]
    fn random_text_never_panics() {
        const NUMS: &[&str] = &["0", "1", "-1", "0.5", "2", "1e-9", "3", "-0"];
        const CORNERS: &[&str] = &[
            "1", "2", "3", "4", "5", "-1", "-2", "1//1", "2//1", "1/1", "2/2", "3/1/1", "1/-1",
        ];
        const ODD: &[&str] = &["nan", "1e7", "0", "x", "1/", "-9", "40000", "\u{feff}v"];
        const BREAKS: &[&str] = &["\n", "\n", "\r\n", "\r"];
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move |n: usize| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % n as u64) as usize
        };
        let mut converted = 0;
        for _ in 0..2000 {
            let mut text =
                String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nvn 0 0 1\nvt 0 0\nvt 1 0.5\n");
            for _ in 0..next(12) {
                let (key, pool, n) = match next(6) {
                    0 => ("v", NUMS, 3),
                    1 => ("vn", NUMS, 3),
                    2 => ("l", CORNERS, 4),
                    3 => ("o", NUMS, 1),
                    _ => ("f", CORNERS, 3 + next(4)),
                };
                text += key;
                for _ in 0..n {
                    text.push(' ');
                    text += if next(40) == 0 {
                        ODD[next(ODD.len())]
                    } else {
                        pool[next(pool.len())]
                    };
                }
                text += BREAKS[next(BREAKS.len())];
            }
            for normals in [None, Some(NormalMode::Flat), Some(NormalMode::Keep)] {
                let opts = Options {
                    normals,
                    weld: next(2) == 0,
                    center_unit_sphere: next(2) == 0,
                    no_uvs: next(2) == 0,
                    adjacency: next(2) == 0,
                    progress: false,
                };
                if let Ok(c) = convert(&text, opts).0 {
                    PackedMesh::parse(&c.blob).unwrap();
                    converted += 1;
                }
            }
        }
        assert!(converted > 500, "{converted}");
    }

    /// A closed cube, one quad a face, outward winding.
    const CUBE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n\
                        f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";

    #[test]
    fn adjacency_is_opt_in_and_joins_split_vertices() {
        let plain = convert(CUBE, Options::default()).0.unwrap();
        assert!(plain.mesh.adjacency.is_none());
        assert_eq!(plain.blob[4], 1, "version 1 without adjacency");
        assert_eq!(plain.report.open_edges, None);
        // Flat normals split every corner: 36 vertices, yet each edge still has its neighbour.
        let flat = |adjacency| Options {
            normals: Some(NormalMode::Flat),
            adjacency,
            ..Options::default()
        };
        let without = convert(CUBE, flat(false)).0.unwrap();
        let c = convert(CUBE, flat(true)).0.unwrap();
        assert_eq!(c.report.vertices_out, 36);
        assert_eq!(c.report.open_edges, Some(0));
        assert!(c
            .report
            .summary()
            .contains("adjacency (0 edges without a neighbour)"));
        assert_eq!(c.blob[4], 3, "version 3");
        // Six bytes a triangle, and everything before them as without.
        assert_eq!(c.report.bytes, without.report.bytes + 12 * 6);
        assert_eq!(c.blob[8..without.blob.len()], without.blob[8..]);
        let p = PackedMesh::parse(&c.blob).unwrap();
        let a = c.mesh.adjacency.as_ref().unwrap();
        for (t, row) in a.iter().enumerate() {
            assert_eq!(p.neighbour_indices(t), Some(*row));
            for &u in row {
                assert!(a[u as usize].contains(&(t as u32)), "{t} <-> {u}");
            }
        }
        // An open mesh: the missing face leaves its four edges without a neighbour.
        let open = CUBE.rsplit_once("f 2 4 8 6").unwrap().0;
        let opts = Options {
            adjacency: true,
            ..Options::default()
        };
        let c = convert(open, opts).0.unwrap();
        assert_eq!(c.report.open_edges, Some(4));
    }

    #[test]
    fn centring_fits_the_unit_sphere() {
        let text = "v 10 10 10\nv 14 10 10\nv 10 13 10\nf 1 2 3\n";
        let opts = Options {
            center_unit_sphere: true,
            ..Options::default()
        };
        let c = convert(text, opts).0.unwrap();
        let (centre, s) = c.report.transform.unwrap();
        assert_eq!(centre, [12.0, 11.5, 10.0]);
        assert!((s - 1.0 / 2.5).abs() < 1e-12);
        assert!(c.report.max_error <= 1.6e-5, "{}", c.report.max_error);
    }
}
