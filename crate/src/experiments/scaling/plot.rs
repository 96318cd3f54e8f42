//! A hand-written SVG line plot of the scaling study: time against N, log-scale y axis with
//! decade ticks, one coloured line and legend entry per method, axis labels.

/// One line of the plot.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// `(x, y)` points, `y > 0` (others are skipped).
    pub points: Vec<(f64, f64)>,
}

const WIDTH: f64 = 760.0;
const HEIGHT: f64 = 400.0;
const LEFT: f64 = 70.0;
const RIGHT: f64 = 270.0;
const TOP: f64 = 20.0;
const BOTTOM: f64 = 50.0;
/// Colours by method, the same for both searches (`METHODS` lists each search's three).
const COLOURS: [&str; 3] = ["#1f77b4", "#ff7f0e", "#d62728"];

/// The plot's axes: x range and the decades of the y range.
struct Axes {
    x0: f64,
    x1: f64,
    d0: i32,
    d1: i32,
}

impl Axes {
    fn of(series: &[Series]) -> Axes {
        let pts = || {
            series
                .iter()
                .flat_map(|s| s.points.iter())
                .filter(|p| p.1 > 0.0)
        };
        let x0 = pts().map(|p| p.0).fold(f64::INFINITY, libm::fmin);
        let x1 = pts().map(|p| p.0).fold(f64::NEG_INFINITY, libm::fmax);
        let y0 = pts().map(|p| p.1).fold(f64::INFINITY, libm::fmin);
        let y1 = pts().map(|p| p.1).fold(f64::NEG_INFINITY, libm::fmax);
        if !x0.is_finite() {
            return Axes {
                x0: 0.0,
                x1: 1.0,
                d0: 0,
                d1: 1,
            };
        }
        let d0 = libm::floor(libm::log10(y0)) as i32;
        let d1 = (libm::ceil(libm::log10(y1)) as i32).max(d0 + 1);
        Axes {
            x0,
            x1: if x1 > x0 { x1 } else { x0 + 1.0 },
            d0,
            d1,
        }
    }

    fn x(&self, x: f64) -> f64 {
        LEFT + (x - self.x0) / (self.x1 - self.x0) * (WIDTH - LEFT - RIGHT)
    }

    fn y(&self, y: f64) -> f64 {
        let t = (libm::log10(y) - f64::from(self.d0)) / f64::from(self.d1 - self.d0);
        HEIGHT - BOTTOM - t * (HEIGHT - TOP - BOTTOM)
    }
}

/// A decade as a plain number: `0.01`, `0.1`, `1`, `10`, `1000`.
fn decade(d: i32) -> String {
    if d >= 0 {
        format!("1{}", "0".repeat(d as usize))
    } else {
        format!("0.{}1", "0".repeat((-d - 1) as usize))
    }
}

/// The SVG document of `series`: time (ms, log scale) against the number of blocks.
pub fn svg(series: &[Series]) -> String {
    let a = Axes::of(series);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         font-family=\"sans-serif\" font-size=\"12\">\n\
         <rect width=\"{WIDTH}\" height=\"{HEIGHT}\" fill=\"white\"/>\n"
    );
    let (xl, xr, yb, yt) = (LEFT, WIDTH - RIGHT, HEIGHT - BOTTOM, TOP);
    s += &format!("<line x1=\"{xl}\" y1=\"{yb}\" x2=\"{xr}\" y2=\"{yb}\" stroke=\"black\"/>\n");
    s += &format!("<line x1=\"{xl}\" y1=\"{yb}\" x2=\"{xl}\" y2=\"{yt}\" stroke=\"black\"/>\n");
    for d in a.d0..=a.d1 {
        let y = a.y(libm::pow(10.0, f64::from(d)));
        s += &format!(
            "<line x1=\"{}\" y1=\"{y:.1}\" x2=\"{xl}\" y2=\"{y:.1}\" stroke=\"black\"/>\
             <text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>\n",
            xl - 5.0,
            xl - 8.0,
            y + 4.0,
            decade(d)
        );
    }
    let mut xs: Vec<f64> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .collect();
    xs.sort_by(|p, q| p.total_cmp(q));
    xs.dedup();
    for x in xs {
        let px = a.x(x);
        s += &format!(
            "<line x1=\"{px:.1}\" y1=\"{yb}\" x2=\"{px:.1}\" y2=\"{}\" stroke=\"black\"/>\
             <text x=\"{px:.1}\" y=\"{}\" text-anchor=\"middle\">{x}</text>\n",
            yb + 5.0,
            yb + 18.0
        );
    }
    s += &format!(
        "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\">blocks N</text>\n",
        0.5 * (xl + xr),
        HEIGHT - 10.0
    );
    s += &format!(
        "<text x=\"15\" y=\"{:.1}\" text-anchor=\"middle\" transform=\"rotate(-90 15 {:.1})\">\
         first plan time (ms)</text>\n",
        0.5 * (yb + yt),
        0.5 * (yb + yt)
    );
    for (i, line) in series.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        // The second search's lines (lazy GBFS) are dashed.
        let dash = if i >= COLOURS.len() {
            " stroke-dasharray=\"6 4\""
        } else {
            ""
        };
        let pts: Vec<String> = line
            .points
            .iter()
            .filter(|p| p.1 > 0.0)
            .map(|p| format!("{:.1},{:.1}", a.x(p.0), a.y(p.1)))
            .collect();
        s += &format!(
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\"{dash} points=\"{}\"/>\n",
            pts.join(" ")
        );
        // A marker on every point, so a method measured at one N alone still shows.
        for p in line.points.iter().filter(|p| p.1 > 0.0) {
            s += &format!(
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3\" fill=\"{colour}\"/>\n",
                a.x(p.0),
                a.y(p.1)
            );
        }
        let ly = TOP + 20.0 * i as f64 + 10.0;
        s += &format!(
            "<line x1=\"{}\" y1=\"{ly}\" x2=\"{}\" y2=\"{ly}\" stroke=\"{colour}\" stroke-width=\"2\"{dash}/>\
             <text x=\"{}\" y=\"{}\" font-size=\"12\">{}</text>\n",
            xr + 10.0,
            xr + 30.0,
            xr + 35.0,
            ly + 4.0,
            line.label
        );
    }
    s += "</svg>\n";
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn demo() -> Vec<Series> {
        vec![Series {
            label: "m".into(),
            points: vec![(4.0, 0.5), (6.0, 5.0), (8.0, 50.0)],
        }]
    }

    #[test]
    fn the_document_is_balanced() {
        let s = svg(&demo());
        assert!(s.starts_with("<svg") && s.ends_with("</svg>\n"));
        assert_eq!(s.matches("<circle").count(), 3, "one marker per point");
        assert_eq!(s.matches("<text").count(), s.matches("</text>").count());
    }

    #[test]
    fn larger_values_map_higher_and_to_the_right() {
        let a = Axes::of(&demo());
        assert!(a.y(50.0) < a.y(5.0) && a.y(5.0) < a.y(0.5));
        assert!(a.x(8.0) > a.x(6.0) && a.x(6.0) > a.x(4.0));
        assert_eq!((a.d0, a.d1), (-1, 2));
    }
}

#[cfg(test)]
mod decade_tests {
    #[test]
    fn decades_are_plain_numbers() {
        assert_eq!(super::decade(-2), "0.01");
        assert_eq!(super::decade(0), "1");
        assert_eq!(super::decade(3), "1000");
    }
}
