//! The report's plot, written as SVG text: error against instructions per frame (log scale), one
//! numbered point per configuration, the Pareto front drawn as a line through its points.

use std::fmt::Write;

/// One point of the plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Its label in the legend.
    pub label: String,
    /// Instructions per frame.
    pub cost: f64,
    /// Error (percent).
    pub error: f64,
    /// On the Pareto front.
    pub front: bool,
}

const W: f64 = 960.0;
const H: f64 = 560.0;
const LEFT: f64 = 80.0;
const RIGHT: f64 = 700.0;
const TOP: f64 = 50.0;
const BOTTOM: f64 = 490.0;

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Ticks for a log axis from `lo` to `hi`: the multiples 1..9 of the powers of ten inside, or
/// only 1, 2 and 5 times them when that gives too many.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let ticks = |ms: &[f64]| {
        let mut out = Vec::new();
        let mut p = 10f64.powf(lo.log10().floor());
        while p <= hi {
            for m in ms {
                let v = p * m;
                if v >= lo && v <= hi {
                    out.push(v);
                }
            }
            p *= 10.0;
        }
        out
    };
    let all = ticks(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    if all.len() > 10 {
        ticks(&[1.0, 2.0, 5.0])
    } else {
        all
    }
}

/// A short form of a count: 6.9M, 850k.
fn short(v: f64) -> String {
    if v >= 1e6 {
        format!("{}M", trim(v / 1e6))
    } else if v >= 1e3 {
        format!("{}k", trim(v / 1e3))
    } else {
        trim(v)
    }
}

/// A tick value below or above 1: 0.05, 2, 30.
fn trim_small(v: f64) -> String {
    if v >= 1.0 {
        trim(v)
    } else {
        let digits = (-v.log10().floor()) as usize;
        format!("{v:.digits$}")
    }
}

fn trim(v: f64) -> String {
    let s = format!("{v:.1}");
    s.strip_suffix(".0").map(str::to_string).unwrap_or(s)
}

/// The SVG document: `title` on top, `x_name` and `y_name` on the axes.
pub fn svg(points: &[Point], title: &str, x_name: &str, y_name: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{W}" height="{H}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="28" font-size="16" text-anchor="middle">{}</text>"#,
        (LEFT + RIGHT) / 2.0,
        esc(title)
    );
    if points.is_empty() {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">no instruction counts: run without --no-count</text></svg>"#,
            (LEFT + RIGHT) / 2.0,
            (TOP + BOTTOM) / 2.0
        );
        return s;
    }
    let (mut xlo, mut xhi) = points.iter().fold((f64::MAX, f64::MIN), |(a, b), p| {
        (a.min(p.cost), b.max(p.cost))
    });
    xlo /= 1.15;
    xhi *= 1.15;
    // Errors span orders of magnitude: log scale too, zero drawn at the bottom edge.
    let positive = points.iter().map(|p| p.error).filter(|&e| e > 0.0);
    let ylo = positive.clone().fold(f64::MAX, f64::min).min(1.0) / 1.5;
    let yhi = positive.fold(0.0, f64::max).max(ylo * 10.0) * 1.5;
    let x = |v: f64| LEFT + (v.ln() - xlo.ln()) / (xhi.ln() - xlo.ln()) * (RIGHT - LEFT);
    let y = |v: f64| BOTTOM - (v.max(ylo).ln() - ylo.ln()) / (yhi.ln() - ylo.ln()) * (BOTTOM - TOP);
    // Axes and grid.
    let _ = writeln!(
        s,
        r##"<rect x="{LEFT}" y="{TOP}" width="{}" height="{}" fill="none" stroke="#444"/>"##,
        RIGHT - LEFT,
        BOTTOM - TOP
    );
    for t in log_ticks(xlo, xhi) {
        let xp = x(t);
        let _ = writeln!(
            s,
            r##"<line x1="{xp:.1}" y1="{TOP}" x2="{xp:.1}" y2="{BOTTOM}" stroke="#ddd"/><text x="{xp:.1}" y="{}" text-anchor="middle">{}</text>"##,
            BOTTOM + 16.0,
            short(t)
        );
    }
    for v in log_ticks(ylo, yhi) {
        let yp = y(v);
        let _ = writeln!(
            s,
            r##"<line x1="{LEFT}" y1="{yp:.1}" x2="{RIGHT}" y2="{yp:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">{}</text>"##,
            LEFT - 6.0,
            yp + 4.0,
            trim_small(v)
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        (LEFT + RIGHT) / 2.0,
        BOTTOM + 40.0,
        esc(x_name)
    );
    let _ = writeln!(
        s,
        r#"<text x="20" y="{}" text-anchor="middle" transform="rotate(-90 20 {})">{}</text>"#,
        (TOP + BOTTOM) / 2.0,
        (TOP + BOTTOM) / 2.0,
        esc(y_name)
    );
    // The front as a line, in cost order.
    let mut front: Vec<&Point> = points.iter().filter(|p| p.front).collect();
    front.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    let path: Vec<String> = front
        .iter()
        .map(|p| format!("{:.1},{:.1}", x(p.cost), y(p.error)))
        .collect();
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#d33" stroke-width="2"/>"##,
        path.join(" ")
    );
    // Points, numbered; labels of coinciding points are stacked.
    let mut placed: Vec<(f64, f64, usize)> = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let (px, py) = (x(p.cost), y(p.error));
        let (fill, stroke) = if p.front {
            ("#d33", "#800")
        } else {
            ("white", "#333")
        };
        let _ = writeln!(
            s,
            r#"<circle cx="{px:.1}" cy="{py:.1}" r="5" fill="{fill}" stroke="{stroke}" stroke-width="1.5"/>"#
        );
        let stack = placed
            .iter()
            .filter(|(qx, qy, _)| (qx - px).abs() < 14.0 && (qy - py).abs() < 12.0)
            .count();
        placed.push((px, py, i));
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" font-size="11">{}</text>"#,
            px + 8.0 + 18.0 * stack as f64,
            py - 6.0,
            i + 1
        );
    }
    // Legend.
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" font-weight="bold">configurations</text>"#,
        RIGHT + 20.0,
        TOP + 4.0
    );
    for (i, p) in points.iter().enumerate() {
        let yp = TOP + 22.0 + 17.0 * i as f64;
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{yp:.1}" fill="{}">{:>2}  {}{}</text>"##,
            RIGHT + 20.0,
            if p.front { "#b00" } else { "#222" },
            i + 1,
            esc(&p.label),
            if p.front { "  (front)" } else { "" }
        );
    }
    let _ = writeln!(
        s,
        r##"<text x="{LEFT}" y="{}" font-size="11" fill="#555">filled red: on the Pareto front (no other configuration is both cheaper and more accurate), joined by the red line</text>"##,
        H - 10.0
    );
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_has_every_point_and_the_front() {
        let pts = vec![
            Point {
                label: "a".into(),
                cost: 1e6,
                error: 2.0,
                front: true,
            },
            Point {
                label: "b <x>".into(),
                cost: 2e6,
                error: 3.0,
                front: false,
            },
        ];
        let s = svg(&pts, "t", "x", "y");
        assert_eq!(s.matches("<circle").count(), 2);
        assert!(s.contains("<polyline"));
        assert!(s.contains("b &lt;x&gt;"));
        assert!(s.ends_with("</svg>\n"));
        assert_eq!(log_ticks(0.95e6, 2.1e6), vec![1e6, 2e6]);
        assert_eq!(log_ticks(5.5e6, 8.5e6), vec![6e6, 7e6, 8e6]);
        assert_eq!(log_ticks(0.01, 100.0).len(), 13);
        assert_eq!(trim_small(0.05), "0.05");
    }
}
