//! The line scanner: reads the OBJ text once, line by line, before tobj sees it.
//!
//! tobj gives no line numbers and lets a lot through silently (see the module doc of
//! [`super`]), so every check that needs a line number happens here. The scanner also hands tobj a
//! cleaned-up copy of the text: byte-order mark removed, every line break a `\n` (so CRLF and bare
//! CR files parse), comments cut off, and every line tobj would misread (`l`, `p`, unknown
//! keywords, texture coordinates, groups, materials) blanked, keeping the line count the same.

use super::{ConvertError, Warning};
use std::collections::HashMap;
use std::path::Path;

/// No corner index (an absent `vt` or `vn`).
pub(super) const NONE: u32 = u32::MAX;

/// The largest coordinate magnitude accepted at all.
pub(super) const ABSURD: f64 = 1e6;

/// Coordinates must stay strictly inside this magnitude when they are not rescaled: the packed
/// format stores the box centre and the decoded positions as 16.16 fixed point.
pub(super) const FX16_LIMIT: f64 = 32767.0;

/// One face corner, as 0-based indices into the file's `v`, `vt` and `vn` lists.
#[derive(Debug, Clone, Copy)]
pub(super) struct Corner {
    /// Position index.
    pub v: u32,
    /// Texture coordinate index, or [`NONE`].
    pub vt: u32,
    /// Normal index, or [`NONE`].
    pub vn: u32,
}

/// One `f` line.
#[derive(Debug, Clone, Copy)]
pub(super) struct Face {
    /// Its line number (1-based).
    pub line: u32,
    /// Index of its first corner in [`Scan::corners`].
    pub first: u32,
    /// Number of corners (at least 3).
    pub len: u32,
}

/// What the scanner learnt.
#[derive(Debug, Default)]
pub(super) struct Scan {
    /// The text to hand to tobj.
    pub text: String,
    /// Every face, in file order.
    pub faces: Vec<Face>,
    /// Every face corner, in file order.
    pub corners: Vec<Corner>,
    /// Number of `v` lines.
    pub v_count: usize,
    /// Line number of each `vn` line (for messages about bad normals).
    pub vn_lines: Vec<u32>,
    /// True when every `v` line has an r g b colour (and there is at least one).
    pub colours: bool,
    /// True when every face corner has a normal index.
    pub all_normals: bool,
}

/// How a line goes on to tobj.
#[derive(Debug, Clone, Copy)]
enum Out {
    /// As an empty line.
    Blank,
    /// Unchanged (minus any comment).
    Keep,
    /// A `v` line with colours: its first four words alone, if colours are dropped.
    VertexWithColour,
}

/// Warnings that may repeat on many lines, reported once with the first line and a count.
#[derive(Default)]
struct Grouped {
    order: Vec<(String, u32, usize)>,
    index: HashMap<String, usize>,
}

impl Grouped {
    fn add(&mut self, message: String, line: u32) {
        if let Some(&i) = self.index.get(&message) {
            self.order[i].2 += 1;
        } else {
            self.index.insert(message.clone(), self.order.len());
            self.order.push((message, line, 1));
        }
    }

    fn flush(self, warnings: &mut Vec<Warning>) {
        for (message, line, count) in self.order {
            let message = if count > 1 {
                format!("{message} ({count} lines, the first here)")
            } else {
                message
            };
            warnings.push(Warning {
                line: Some(line as usize),
                message,
            });
        }
    }
}

/// Keywords of the OBJ format that the converter reads no data from: ignored without a warning.
const IGNORED: &[&str] = &[
    "vp",
    "o",
    "g",
    "s",
    "mg",
    "mtllib",
    "usemtl",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "shadow_obj",
    "trace_obj",
    "ctech",
    "stech",
    "maplib",
    "usemap",
];

/// Scans `bytes` (the whole file). `file` names it in messages; `dir` is where `mtllib` files are
/// looked for (no check without it); `rescaled` says whether `--center-unit-sphere` will rescale
/// the coordinates (then only the absurd-size check applies, not the 16.16 one). `progress` is
/// called now and then with the number of bytes scanned.
pub(super) fn scan(
    file: &str,
    bytes: &[u8],
    dir: Option<&Path>,
    rescaled: bool,
    warnings: &mut Vec<Warning>,
    progress: &dyn Fn(u64),
) -> Result<Scan, ConvertError> {
    let mut found = Vec::new();
    let result = scan_into(file, bytes, dir, rescaled, &mut found, progress);
    // In line order, whether or not the scan succeeded.
    found.sort_by_key(|w| w.line);
    warnings.append(&mut found);
    result
}

fn scan_into(
    file: &str,
    bytes: &[u8],
    dir: Option<&Path>,
    rescaled: bool,
    warnings: &mut Vec<Warning>,
    progress: &dyn Fn(u64),
) -> Result<Scan, ConvertError> {
    let err = |line: usize, message: String| ConvertError {
        file: file.to_owned(),
        line: Some(line),
        message,
    };
    let mut bytes = bytes;
    if let Some(rest) = bytes.strip_prefix(b"\xEF\xBB\xBF") {
        bytes = rest;
        warnings.push(Warning {
            line: Some(1),
            message: "UTF-8 byte-order mark removed (tobj would have dropped the first line)"
                .into(),
        });
    }
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let good = &bytes[..e.valid_up_to()];
            let line = 1 + good.iter().filter(|&&b| b == b'\n').count();
            return Err(err(line, "not UTF-8 text".into()));
        }
    };
    if text.trim().is_empty() {
        return Err(err(1, "empty file: no vertices and no faces".into()));
    }

    let mut out = Scan::default();
    let mut outs: Vec<(&str, Out)> = Vec::new();
    let mut grouped = Grouped::default();
    let (mut vt_count, mut vn_count) = (0usize, 0usize);
    let (mut crlf, mut bare_cr) = (None::<u32>, None::<u32>);
    let mut coloured = 0usize;
    let mut first_uncoloured = None::<u32>;
    let mut first_coloured = None::<u32>;
    // Face corners with and without vt / vn: the first line of each kind.
    let mut vt_kinds = [None::<u32>; 2];
    let mut vn_kinds = [None::<u32>; 2];

    let b = text.as_bytes();
    let (mut start, mut i, mut line_no) = (0usize, 0usize, 0u32);
    while start < b.len() {
        // Find the end of this line: \n, \r\n or a bare \r.
        while i < b.len() && b[i] != b'\n' && b[i] != b'\r' {
            i += 1;
        }
        line_no += 1;
        let raw = &text[start..i];
        if i < b.len() {
            if b[i] == b'\r' {
                if b.get(i + 1) == Some(&b'\n') {
                    crlf.get_or_insert(line_no);
                    i += 1;
                } else {
                    bare_cr.get_or_insert(line_no);
                }
            }
            i += 1;
        }
        start = i;
        if line_no % 8192 == 0 {
            progress(start as u64);
        }

        let content = raw.split('#').next().unwrap_or("").trim();
        let mut words = content.split_whitespace();
        let Some(keyword) = words.next() else {
            outs.push(("", Out::Blank));
            continue;
        };
        let line = line_no as usize;
        let kind = match keyword {
            "v" => {
                let mut nums = [0f64; 7];
                let mut text = [""; 7];
                let mut n = 0;
                for w in words {
                    if n == nums.len() {
                        n += 1;
                        break;
                    }
                    nums[n] = w.parse::<f64>().map_err(|_| {
                        err(line, format!("malformed vertex: `{w}` is not a number"))
                    })?;
                    text[n] = w;
                    n += 1;
                }
                if !matches!(n, 3 | 4 | 6) {
                    return Err(err(
                        line,
                        format!(
                            "malformed vertex: expected x y z, x y z w or x y z r g b, found {n} numbers"
                        ),
                    ));
                }
                if n == 4 {
                    if nums[3] == 0.0 || !nums[3].is_finite() {
                        return Err(err(
                            line,
                            format!("vertex weight w = {} is not usable", nums[3]),
                        ));
                    }
                    for k in 0..3 {
                        nums[k] /= nums[3];
                    }
                }
                for (&c, w) in nums[..3].iter().zip(text) {
                    let shown = if n == 4 {
                        format!("`{w}` / w = {c}")
                    } else {
                        format!("`{w}`")
                    };
                    if !c.is_finite() || c.abs() > ABSURD {
                        return Err(err(
                            line,
                            format!(
                                "coordinate {shown} is not finite or absurdly large (limit ±1e6)"
                            ),
                        ));
                    }
                    if !rescaled && c.abs() >= FX16_LIMIT {
                        return Err(err(
                            line,
                            format!(
                                "coordinate {shown} is outside the 16.16 range (magnitude below \
                                 32767); --center-unit-sphere rescales the model"
                            ),
                        ));
                    }
                }
                out.v_count += 1;
                if n == 6 {
                    if let Some(k) = (3..6).find(|&k| !nums[k].is_finite()) {
                        return Err(err(
                            line,
                            format!("vertex colour component `{}` is not finite", text[k]),
                        ));
                    }
                    coloured += 1;
                    first_coloured.get_or_insert(line_no);
                    Out::VertexWithColour
                } else {
                    first_uncoloured.get_or_insert(line_no);
                    Out::Keep
                }
            }
            "vt" => {
                let mut n = 0;
                for w in words {
                    if w.parse::<f64>().is_err() {
                        return Err(err(
                            line,
                            format!("malformed texture coordinate: `{w}` is not a number"),
                        ));
                    }
                    n += 1;
                }
                if !(1..=3).contains(&n) {
                    return Err(err(
                        line,
                        format!("malformed texture coordinate: expected 1 to 3 numbers, found {n}"),
                    ));
                }
                vt_count += 1;
                // Texture coordinates are not converted: tobj never sees them.
                Out::Blank
            }
            "vn" => {
                let mut n = 0;
                for w in words {
                    let x = w.parse::<f64>().map_err(|_| {
                        err(line, format!("malformed normal: `{w}` is not a number"))
                    })?;
                    if !x.is_finite() {
                        return Err(err(line, format!("normal component {w} is not finite")));
                    }
                    n += 1;
                }
                if n != 3 {
                    return Err(err(
                        line,
                        format!("malformed normal: expected 3 numbers, found {n}"),
                    ));
                }
                vn_count += 1;
                out.vn_lines.push(line_no);
                Out::Keep
            }
            "f" => {
                let first = out.corners.len();
                for w in words {
                    let c = corner(w, out.v_count, vt_count, vn_count).map_err(|m| err(line, m))?;
                    vt_kinds[usize::from(c.vt == NONE)].get_or_insert(line_no);
                    vn_kinds[usize::from(c.vn == NONE)].get_or_insert(line_no);
                    out.corners.push(c);
                }
                let len = out.corners.len() - first;
                if len < 3 {
                    return Err(err(
                        line,
                        format!("malformed face: a face needs at least 3 vertices, found {len}"),
                    ));
                }
                if out.corners.len() > u32::MAX as usize / 2 {
                    return Err(err(line, "too many face corners".into()));
                }
                out.faces.push(Face {
                    line: line_no,
                    first: first as u32,
                    len: len as u32,
                });
                Out::Keep
            }
            "l" => {
                grouped.add(
                    "`l` polyline ignored (tobj would have filled it as a polygon)".into(),
                    line_no,
                );
                Out::Blank
            }
            "p" => {
                grouped.add("`p` points ignored".into(), line_no);
                Out::Blank
            }
            "mtllib" => {
                if let Some(dir) = dir {
                    let name = content["mtllib".len()..].trim();
                    if !name.is_empty() && !dir.join(name).is_file() {
                        warnings.push(Warning {
                            line: Some(line),
                            message: format!(
                                "material library `{name}` not found (materials are not converted)"
                            ),
                        });
                    }
                }
                Out::Blank
            }
            k if IGNORED.contains(&k) => Out::Blank,
            k => {
                let shown: String = k.chars().take(24).collect();
                grouped.add(format!("unknown keyword `{shown}` ignored"), line_no);
                Out::Blank
            }
        };
        outs.push((content, kind));
    }
    progress(b.len() as u64);

    let last_line = line_no.max(1) as usize;
    if out.faces.is_empty() {
        let message = if out.v_count == 0 {
            "no faces and no vertices (nothing to convert)".to_owned()
        } else {
            format!(
                "no faces: the file ends after {} vertices but no `f` line",
                out.v_count
            )
        };
        return Err(err(last_line, message));
    }
    // Positive indices may point forwards (tobj allows it), so they are checked at the end.
    for f in &out.faces {
        let corners = &out.corners[f.first as usize..(f.first + f.len) as usize];
        for c in corners {
            let bad = if c.v as usize >= out.v_count {
                Some(("vertex", c.v, out.v_count))
            } else if c.vt != NONE && c.vt as usize >= vt_count {
                Some(("texture coordinate", c.vt, vt_count))
            } else if c.vn != NONE && c.vn as usize >= vn_count {
                Some(("normal", c.vn, vn_count))
            } else {
                None
            };
            if let Some((what, index, count)) = bad {
                return Err(err(
                    f.line as usize,
                    format!(
                        "face refers to {what} {} but the file has only {count}",
                        u64::from(index) + 1
                    ),
                ));
            }
        }
    }

    if let Some(line) = bare_cr {
        warnings.push(Warning {
            line: Some(line as usize),
            message: "bare CR (classic Mac OS) line endings: each CR read as a line break".into(),
        });
    }
    if let Some(line) = crlf {
        warnings.push(Warning {
            line: Some(line as usize),
            message: "CRLF (Windows) line endings".into(),
        });
    }
    grouped.flush(warnings);
    if let [Some(with), Some(without)] = vt_kinds {
        warnings.push(Warning {
            line: Some(with.max(without) as usize),
            message: "faces mix corners with and without texture coordinates (`v/vt` and `v`); \
                      texture coordinates are not converted anyway"
                .into(),
        });
    }
    out.all_normals = vn_kinds[1].is_none();
    if let [Some(with), Some(without)] = vn_kinds {
        warnings.push(Warning {
            line: Some(with.max(without) as usize),
            message: "faces mix corners with and without normals; the file's normals cannot be \
                      kept"
                .into(),
        });
    }
    out.colours = coloured > 0 && coloured == out.v_count;
    if coloured > 0 && !out.colours {
        let line = first_uncoloured
            .unwrap_or(1)
            .max(first_coloured.unwrap_or(1));
        warnings.push(Warning {
            line: Some(line as usize),
            message: format!(
                "only {coloured} of {} vertices have colours: colours dropped",
                out.v_count
            ),
        });
    }

    let mut text_out = String::with_capacity(text.len());
    for (content, kind) in outs {
        match kind {
            Out::Blank => {}
            Out::Keep => text_out.push_str(content),
            Out::VertexWithColour if out.colours => text_out.push_str(content),
            Out::VertexWithColour => {
                for (k, w) in content.split_whitespace().take(4).enumerate() {
                    if k > 0 {
                        text_out.push(' ');
                    }
                    text_out.push_str(w);
                }
            }
        }
        text_out.push('\n');
    }
    out.text = text_out;
    Ok(out)
}

/// Reads one face corner, `v`, `v/vt`, `v//vn` or `v/vt/vn`, resolving negative (relative)
/// indices against the counts so far. Returns the message for a malformed one.
fn corner(word: &str, v: usize, vt: usize, vn: usize) -> Result<Corner, String> {
    let malformed = || {
        format!(
            "malformed face corner `{word}` (expected v, v/vt, v//vn or v/vt/vn, indices from 1)"
        )
    };
    let mut parts = word.split('/');
    let p = [parts.next(), parts.next(), parts.next()];
    if parts.next().is_some() {
        return Err(malformed());
    }
    let index = |s: &str, count: usize, what: &str| -> Result<u32, String> {
        let x: i64 = s.parse().map_err(|_| malformed())?;
        if x == 0 {
            return Err(format!(
                "face corner `{word}` has {what} index 0 (OBJ indices start at 1)"
            ));
        }
        let resolved = if x < 0 { count as i64 + x } else { x - 1 };
        if resolved < 0 {
            return Err(format!(
                "face corner `{word}`: relative {what} index {x} reaches before the first one \
                 ({count} defined so far)"
            ));
        }
        u32::try_from(resolved)
            .ok()
            .filter(|&r| r != NONE)
            .ok_or_else(|| format!("face corner `{word}`: {what} index {x} is out of range"))
    };
    let v = match p[0] {
        Some(s) if !s.is_empty() => index(s, v, "vertex")?,
        _ => return Err(malformed()),
    };
    let (vt, vn) = match (p[1], p[2]) {
        (None, None) => (NONE, NONE),
        (Some(t), None) if !t.is_empty() => (index(t, vt, "texture coordinate")?, NONE),
        (Some(""), Some(n)) if !n.is_empty() => (NONE, index(n, vn, "normal")?),
        (Some(t), Some(n)) if !t.is_empty() && !n.is_empty() => {
            (index(t, vt, "texture coordinate")?, index(n, vn, "normal")?)
        }
        _ => return Err(malformed()),
    };
    Ok(Corner { v, vt, vn })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(text: &str) -> (Result<Scan, ConvertError>, Vec<Warning>) {
        let mut w = Vec::new();
        let r = scan("t.obj", text.as_bytes(), None, false, &mut w, &|_| {});
        (r, w)
    }

    fn line_of(text: &str) -> usize {
        run(text).0.unwrap_err().line.unwrap()
    }

    #[test]
    fn corners_of_every_form() {
        let c = corner("3", 5, 0, 0).unwrap();
        assert_eq!((c.v, c.vt, c.vn), (2, NONE, NONE));
        let c = corner("-1/2", 5, 4, 0).unwrap();
        assert_eq!((c.v, c.vt, c.vn), (4, 1, NONE));
        let c = corner("1//-2", 5, 0, 2).unwrap();
        assert_eq!((c.v, c.vt, c.vn), (0, NONE, 0));
        let c = corner("1/1/1", 5, 1, 1).unwrap();
        assert_eq!((c.v, c.vt, c.vn), (0, 0, 0));
        for bad in ["", "/1", "1/", "1//", "1/2/3/4", "a", "1.5", "1/x", "-6"] {
            assert!(corner(bad, 5, 5, 5).is_err(), "{bad:?}");
        }
        assert!(corner("0", 5, 0, 0).unwrap_err().contains("index 0"));
    }

    #[test]
    fn line_numbers_count_every_kind_of_break() {
        assert_eq!(line_of("v 0 0 0\r\nv 1 0 0\r\nv nan 0 0\r\n"), 3);
        assert_eq!(line_of("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 4\r"), 4);
        assert_eq!(line_of("# a\n\nv 0 0 0\nf 1 1 x\n"), 4);
    }

    #[test]
    fn comments_are_cut_and_lines_kept() {
        let (s, w) = run("v 0 0 0 # one\nv 1 0 0\nvt 0 0\nv 0 1 0\nl 1 2\nf 1 2 3\n");
        let s = s.unwrap();
        assert_eq!(s.text, "v 0 0 0\nv 1 0 0\n\nv 0 1 0\n\nf 1 2 3\n");
        assert_eq!(w.len(), 1, "{w:?}");
    }

    #[test]
    fn forward_references_are_allowed_but_checked() {
        assert!(run("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").0.is_ok());
        assert_eq!(line_of("f 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"), 1);
    }
}
