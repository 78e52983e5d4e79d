//! Loading OBJ files into the pipeline's plain slices, for the demo, tests and benchmarks.
//!
//! Positions and normals are rounded to 16.16 fixed point. Faces are triangulated by tobj (a fan:
//! right for the convex faces of the test models; the converter handles concave ones). This is the
//! host's quick path; the compact embedded format comes with the converter.

use rasterizer_core::math::{Fx16, Vec3};
use rasterizer_core::mesh::Mesh;
use std::path::Path;

/// A mesh in memory.
#[derive(Debug, Clone, Default)]
pub struct LoadedMesh {
    /// Positions.
    pub positions: Vec<Vec3<Fx16>>,
    /// Normals, one per position, when the file has them.
    pub normals: Option<Vec<Vec3<Fx16>>>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
}

/// An OBJ file's mesh in `f64`, before any range check: what [`LoadedMesh::load`] rounds to
/// 16.16, and what a scene can rescale first.
#[derive(Debug, Clone, Default)]
pub struct RawMesh {
    /// Positions (finite).
    pub positions: Vec<[f64; 3]>,
    /// Normals, one per position, when the file has them for every model.
    pub normals: Option<Vec<[f64; 3]>>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
}

/// Why a mesh could not be loaded.
#[derive(Debug)]
pub enum LoadError {
    /// The file could not be read.
    Read(std::io::Error),
    /// The file is not UTF-8 text; the 1-based line of the first bad byte.
    NotUtf8 {
        /// The line.
        line: usize,
    },
    /// tobj rejected the file.
    Obj(tobj::LoadError),
    /// A coordinate is not finite.
    NotFinite {
        /// The model's vertex index.
        vertex: usize,
    },
    /// A coordinate does not fit 16.16.
    BadCoordinate {
        /// The model's vertex index.
        vertex: usize,
    },
    /// The file has no triangles.
    Empty,
}

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoadError::Read(e) => write!(f, "cannot read: {e}"),
            // The converter's words for the same problem.
            LoadError::NotUtf8 { line } => write!(f, "line {line}: not UTF-8 text"),
            LoadError::Obj(e) => write!(f, "OBJ parse error: {e}"),
            LoadError::NotFinite { vertex } => {
                write!(f, "vertex {vertex} has a coordinate that is not finite")
            }
            LoadError::BadCoordinate { vertex } => {
                write!(f, "vertex {vertex} is outside the 16.16 range (±32767)")
            }
            LoadError::Empty => write!(f, "no triangles"),
        }
    }
}

impl std::error::Error for LoadError {}

fn fx(v: f32) -> Option<Fx16> {
    fx64(f64::from(v))
}

fn fx64(v: f64) -> Option<Fx16> {
    let bits = (v * 65536.0).round();
    (bits.is_finite() && bits.abs() < 2_147_483_647.0).then(|| Fx16::from_bits(bits as i32))
}

/// `v` on the 16.16 grid when it is in range, else unchanged.
fn on_grid(v: f64) -> f64 {
    fx64(v).map_or(v, |f| f64::from(f.to_bits()) / 65536.0)
}

impl RawMesh {
    /// Loads every model of an OBJ file into one mesh. Materials are not read. Coordinates in
    /// 16.16's range are rounded to it (as the pipeline would); larger ones are kept for a caller
    /// that rescales.
    ///
    /// # Errors
    /// [`LoadError`] for an unreadable or non-UTF-8 file, a non-finite coordinate or no
    /// triangles.
    pub fn load(path: &Path) -> Result<Self, LoadError> {
        // Read here rather than in tobj, whose errors drop the operating system's reason.
        let bytes = std::fs::read(path).map_err(LoadError::Read)?;
        let text = std::str::from_utf8(&bytes).map_err(|e| LoadError::NotUtf8 {
            line: 1 + bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count(),
        })?;
        let opts = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..Default::default()
        };
        let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &opts, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(LoadError::Obj)?;
        let mut out = RawMesh::default();
        let mut normals = Vec::new();
        let mut all_normals = true;
        for m in &models {
            let base = out.positions.len() as u32;
            let mesh = &m.mesh;
            for (i, p) in mesh.positions.chunks_exact(3).enumerate() {
                let p = [0, 1, 2].map(|k| f64::from(p[k]));
                if !p.iter().all(|v| v.is_finite()) {
                    return Err(LoadError::NotFinite { vertex: i });
                }
                out.positions.push(p.map(on_grid));
            }
            if mesh.normals.len() == mesh.positions.len() {
                for n in mesh.normals.chunks_exact(3) {
                    normals.push(
                        [0, 1, 2]
                            .map(|k| fx(n[k]).map_or(0.0, |f| f64::from(f.to_bits()) / 65536.0)),
                    );
                }
            } else {
                all_normals = false;
            }
            for t in mesh.indices.chunks_exact(3) {
                out.triangles.push([base + t[0], base + t[1], base + t[2]]);
            }
        }
        if out.triangles.is_empty() {
            return Err(LoadError::Empty);
        }
        out.normals = all_normals.then_some(normals);
        Ok(out)
    }
}

impl LoadedMesh {
    /// Loads every model of an OBJ file into one mesh.
    ///
    /// # Errors
    /// [`LoadError`] for an unreadable file, a bad coordinate or no triangles.
    pub fn load(path: &Path) -> Result<Self, LoadError> {
        let raw = RawMesh::load(path)?;
        let v3 = |p: &[f64; 3]| {
            let [x, y, z] = p.map(fx64);
            Some(Vec3::new(x?, y?, z?))
        };
        let positions = raw
            .positions
            .iter()
            .enumerate()
            .map(|(i, p)| v3(p).ok_or(LoadError::BadCoordinate { vertex: i }))
            .collect::<Result<Vec<_>, _>>()?;
        let normals = raw.normals.as_ref().map(|n| {
            n.iter()
                .map(|p| v3(p).unwrap_or(Vec3::new(Fx16::ZERO, Fx16::ZERO, Fx16::ZERO)))
                .collect()
        });
        Ok(LoadedMesh {
            positions,
            normals,
            triangles: raw.triangles,
        })
    }

    /// The mesh as the pipeline's slices.
    pub fn mesh(&self) -> Mesh<'_, Fx16, u32> {
        Mesh {
            positions: &self.positions,
            normals: self.normals.as_deref(),
            colors: None,
            triangles: &self.triangles,
        }
    }

    /// Computes smooth vertex normals: the sum of the adjacent faces' cross products (area
    /// weighted), replacing any normals loaded.
    pub fn compute_smooth_normals(&mut self) {
        let mut acc = vec![[0f64; 3]; self.positions.len()];
        let f = |v: Fx16| f64::from(v.to_bits()) / 65536.0;
        for t in &self.triangles {
            let p = t
                .map(|i| self.positions[i as usize])
                .map(|v| [f(v.x), f(v.y), f(v.z)]);
            let (a, b) = (
                [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]],
                [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]],
            );
            let n = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            for &i in t {
                for k in 0..3 {
                    acc[i as usize][k] += n[k];
                }
            }
        }
        self.normals = Some(
            acc.iter()
                .map(|n| {
                    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                    let c = |v: f64| {
                        fx(if len > 0.0 { (v / len) as f32 } else { 0.0 }).unwrap_or(Fx16::ZERO)
                    };
                    Vec3::new(c(n[0]), c(n[1]), c(n[2]))
                })
                .collect(),
        );
    }

    /// Moves the bounding box's centre to the origin and scales the mesh to fit the unit sphere.
    pub fn normalize_to_unit_sphere(&mut self) {
        let f = |v: Fx16| f64::from(v.to_bits()) / 65536.0;
        let mut lo = [f64::MAX; 3];
        let mut hi = [f64::MIN; 3];
        for p in &self.positions {
            for (k, v) in [f(p.x), f(p.y), f(p.z)].into_iter().enumerate() {
                lo[k] = lo[k].min(v);
                hi[k] = hi[k].max(v);
            }
        }
        let c = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
        let r = self
            .positions
            .iter()
            .map(|p| {
                let d = [f(p.x) - c[0], f(p.y) - c[1], f(p.z) - c[2]];
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
            })
            .fold(0.0, f64::max)
            .max(1e-9);
        for p in &mut self.positions {
            let g = |v: Fx16, k: usize| fx(((f(v) - c[k]) / r) as f32).unwrap_or(Fx16::ZERO);
            *p = Vec3::new(g(p.x, 0), g(p.y, 1), g(p.z, 2));
        }
    }
}
