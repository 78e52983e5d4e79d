//! The report's plot, drawn with plotters' SVG backend: error against instructions per frame (both
//! log scale), one numbered point per configuration, the Pareto front drawn as a line through its
//! points.

use plotters::prelude::*;

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

const SIZE: (u32, u32) = (960, 560);
/// The width of the chart; the legend takes the rest.
const CHART: u32 = 720;
const FRONT: RGBColor = RGBColor(0xdd, 0x33, 0x33);
const FRONT_TEXT: RGBColor = RGBColor(0xbb, 0, 0);
const INK: RGBColor = RGBColor(0x22, 0x22, 0x22);

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
    // Drawing into a string fails only on a plotters bug; the document is then cut short.
    let _ = draw(&mut s, points, title, x_name, y_name);
    s
}

fn draw<'a>(
    s: &'a mut String,
    points: &[Point],
    title: &str,
    x_name: &str,
    y_name: &str,
) -> Result<(), Box<dyn std::error::Error + 'a>> {
    let root = SVGBackend::with_string(s, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let (chart_area, legend) = root.split_horizontally(CHART);
    if points.is_empty() {
        let note = "no instruction counts: run without --no-count";
        let chart_area = chart_area.titled(title, ("sans-serif", 16))?;
        chart_area.draw(&Text::new(
            note,
            (CHART as i32 / 3, 240),
            ("sans-serif", 12),
        ))?;
        return Ok(root.present()?);
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
    let mut chart = ChartBuilder::on(&chart_area)
        .caption(title, ("sans-serif", 18))
        .margin(20)
        .margin_bottom(40)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (xlo..xhi).log_scale().with_key_points(log_ticks(xlo, xhi)),
            (ylo..yhi).log_scale().with_key_points(log_ticks(ylo, yhi)),
        )?;
    chart
        .configure_mesh()
        .x_desc(x_name)
        .y_desc(y_name)
        .x_label_formatter(&|v| short(*v))
        .y_label_formatter(&|v| trim_small(*v))
        .bold_line_style(RGBColor(0xdd, 0xdd, 0xdd))
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 14))
        .draw()?;
    // The front as a line, in cost order.
    let mut front: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.front)
        .map(|p| (p.cost, p.error.max(ylo)))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart.draw_series(LineSeries::new(front, FRONT.stroke_width(2)))?;
    // Points, numbered; labels of coinciding points are stacked.
    let at: Vec<(i32, i32)> = points
        .iter()
        .map(|p| chart.backend_coord(&(p.cost, p.error.max(ylo))))
        .collect();
    for (i, p) in points.iter().enumerate() {
        let (x, y) = at[i];
        let stack = at[..i]
            .iter()
            .filter(|q| (q.0 - x).abs() < 14 && (q.1 - y).abs() < 12)
            .count() as i32;
        let (fill, stroke) = if p.front {
            (FRONT, RGBColor(0x80, 0, 0))
        } else {
            (WHITE, INK)
        };
        chart.draw_series([EmptyElement::at((p.cost, p.error.max(ylo)))
            + Circle::new((0, 0), 5, fill.filled())
            + Circle::new((0, 0), 5, stroke.stroke_width(1))
            + Text::new(
                (i + 1).to_string(),
                (8 + 18 * stack, -16),
                ("sans-serif", 13),
            )])?;
    }
    // Legend.
    let bold = ("sans-serif", 14, FontStyle::Bold);
    legend.draw(&Text::new("configurations", (0, 40), bold))?;
    for (i, p) in points.iter().enumerate() {
        let color = if p.front { FRONT_TEXT } else { INK };
        let front = if p.front { "  (front)" } else { "" };
        let line = format!("{:>2}  {}{front}", i + 1, p.label);
        let y = 58 + 17 * i as i32;
        legend.draw(&Text::new(
            line,
            (0, y),
            ("sans-serif", 14).into_font().color(&color),
        ))?;
    }
    let note = "filled red: on the Pareto front (no other configuration is both cheaper and more \
                accurate), joined by the red line";
    root.draw(&Text::new(
        note,
        (80, 542),
        ("sans-serif", 13).into_font().color(&INK),
    ))?;
    Ok(root.present()?)
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
        assert_eq!(s.matches("<circle").count(), 4, "{s}");
        assert!(s.contains("<polyline"));
        assert!(s.contains("b &lt;x&gt;"));
        assert!(s.trim_end().ends_with("</svg>"));
        assert_eq!(short(2.5e6), "2.5M");
        assert_eq!(short(850e3), "850k");
        assert_eq!(trim_small(0.05), "0.05");
        assert!(svg(&[], "t", "x", "y").contains("no instruction counts"));
        assert_eq!(log_ticks(0.95e6, 2.1e6), vec![1e6, 2e6]);
        assert_eq!(log_ticks(5.5e6, 8.5e6), vec![6e6, 7e6, 8e6]);
        assert_eq!(log_ticks(0.01, 100.0).len(), 13);
    }
}
