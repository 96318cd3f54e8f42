//! A hand-written SVG of Fig. 4, seen from above (world x up the page, y to the left): (a) the
//! hook picks, (b) the pulls, LQT-CP in blue and the DMP in red, planned paths solid and the
//! simulated TCP dotted, the via-points marked, the block's start and its three goals drawn.

use super::{Fig4, PickRow, PullRow};

const PANEL: f64 = 420.0;
const MARGIN: f64 = 30.0;
const TITLE: f64 = 24.0;
const LQT: &str = "#1f77b4";
const DMP: &str = "#d62728";
const GOALS: [&str; 3] = ["#d62728", "#2ca02c", "#1f77b4"];
/// Half the side of a drawn block (m).
const HALF_BLOCK: f64 = 0.03;

/// Maps world (x, y) into one panel, equal scale on both axes.
struct View {
    left: f64,
    x0: f64,
    y1: f64,
    scale: f64,
}

impl View {
    /// The view of panel `index` fitting `points` (world x, y).
    fn fit(index: usize, points: &[[f64; 2]]) -> View {
        let fold =
            |f: fn(f64, f64) -> f64, i: usize, init: f64| points.iter().map(|p| p[i]).fold(init, f);
        let (x0, x1) = (
            fold(libm::fmin, 0, f64::INFINITY),
            fold(libm::fmax, 0, f64::NEG_INFINITY),
        );
        let (y0, y1) = (
            fold(libm::fmin, 1, f64::INFINITY),
            fold(libm::fmax, 1, f64::NEG_INFINITY),
        );
        let span = libm::fmax(libm::fmax(x1 - x0, y1 - y0), 1e-3) + 2.0 * HALF_BLOCK;
        let scale = (PANEL - 2.0 * MARGIN) / span;
        let cx = 0.5 * (x0 + x1);
        let cy = 0.5 * (y0 + y1);
        let half = 0.5 * span;
        View {
            left: index as f64 * PANEL,
            x0: if x0.is_finite() { cx - half } else { 0.0 },
            y1: if y1.is_finite() { cy + half } else { 0.0 },
            scale,
        }
    }

    /// Screen coordinates of world (x, y).
    fn at(&self, x: f64, y: f64) -> (f64, f64) {
        (
            self.left + MARGIN + (self.y1 - y) * self.scale,
            TITLE + PANEL - MARGIN - (x - self.x0) * self.scale,
        )
    }

    fn polyline(&self, path: &[[f64; 3]], colour: &str, dotted: bool) -> String {
        let pts: Vec<String> = path
            .iter()
            .map(|p| {
                let (u, v) = self.at(p[0], p[1]);
                format!("{u:.1},{v:.1}")
            })
            .collect();
        let (width, dash) = if dotted {
            ("1", " stroke-dasharray=\"2 3\"")
        } else {
            ("2", "")
        };
        format!(
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"{width}\"{dash} points=\"{}\"/>\n",
            pts.join(" ")
        )
    }

    fn square(&self, c: &[f64; 3], fill: &str, stroke: &str) -> String {
        let (u, v) = self.at(c[0] + HALF_BLOCK, c[1] + HALF_BLOCK);
        let side = 2.0 * HALF_BLOCK * self.scale;
        format!(
            "<rect x=\"{u:.1}\" y=\"{v:.1}\" width=\"{side:.1}\" height=\"{side:.1}\" \
             fill=\"{fill}\" fill-opacity=\"0.35\" stroke=\"{stroke}\"/>\n"
        )
    }

    fn cross(&self, p: &[f64; 3]) -> String {
        let (u, v) = self.at(p[0], p[1]);
        format!(
            "<path d=\"M{:.1},{:.1}L{:.1},{:.1}M{:.1},{:.1}L{:.1},{:.1}\" stroke=\"black\" \
             stroke-width=\"1.5\"/>\n",
            u - 4.0,
            v - 4.0,
            u + 4.0,
            v + 4.0,
            u - 4.0,
            v + 4.0,
            u + 4.0,
            v - 4.0
        )
    }
}

fn colour(method: &str) -> &'static str {
    if method == "dmp" {
        DMP
    } else {
        LQT
    }
}

fn xy(paths: impl Iterator<Item = [f64; 3]>) -> Vec<[f64; 2]> {
    paths.map(|p| [p[0], p[1]]).collect()
}

fn picks_panel(rows: &[PickRow]) -> String {
    let view = View::fit(
        0,
        &xy(rows
            .iter()
            .flat_map(|r| r.path.iter().copied().chain([r.hook]))),
    );
    let mut s = String::new();
    for r in rows {
        s += &view.polyline(&r.path, colour(&r.method), false);
    }
    for r in rows.iter().filter(|r| r.method != "dmp") {
        s += &view.square(&r.hook, "#888888", "#444444");
    }
    s
}

fn pulls_panel(rows: &[PullRow], block_start: &[f64; 3]) -> String {
    let view = View::fit(
        1,
        &xy(rows
            .iter()
            .flat_map(|r| r.path.iter().copied().chain([r.block_goal]))
            .chain([*block_start])),
    );
    let mut s = view.square(block_start, "#888888", "#444444");
    for r in rows {
        s += &view.polyline(&r.executed, colour(&r.method), true);
        s += &view.polyline(&r.path, colour(&r.method), false);
    }
    for r in rows.iter().filter(|r| r.method != "dmp") {
        s += &view.square(&r.block_goal, "none", GOALS[r.goal % GOALS.len()]);
        for v in &r.via_points {
            s += &view.cross(v);
        }
    }
    s
}

/// The SVG document of `f`.
pub fn svg(f: &Fig4) -> String {
    let width = 2.0 * PANEL;
    let height = PANEL + TITLE + 40.0;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         font-family=\"sans-serif\" font-size=\"12\">\n\
         <rect width=\"{width}\" height=\"{height}\" fill=\"white\"/>\n\
         <text x=\"{:.0}\" y=\"16\" text-anchor=\"middle\">(a) pick {} at three positions</text>\n\
         <text x=\"{:.0}\" y=\"16\" text-anchor=\"middle\">(b) pull {} to three goals</text>\n",
        0.5 * PANEL,
        f.hook,
        1.5 * PANEL,
        f.block
    );
    s += &picks_panel(&f.pick);
    s += &pulls_panel(&f.pull, &f.block_start);
    let y = PANEL + TITLE + 20.0;
    s += &format!(
        "<line x1=\"20\" y1=\"{y}\" x2=\"45\" y2=\"{y}\" stroke=\"{LQT}\" stroke-width=\"2\"/>\
         <text x=\"50\" y=\"{:.0}\">LQT-CP</text>\n\
         <line x1=\"120\" y1=\"{y}\" x2=\"145\" y2=\"{y}\" stroke=\"{DMP}\" stroke-width=\"2\"/>\
         <text x=\"150\" y=\"{:.0}\">DMP</text>\n\
         <text x=\"220\" y=\"{:.0}\">solid: planned, dotted: simulated TCP; ×: via-points; \
         grey: start, outlined: goals (view from above, x up)</text>\n",
        y + 4.0,
        y + 4.0,
        y + 4.0
    );
    s += "</svg>\n";
    s
}
