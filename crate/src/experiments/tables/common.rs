//! What both tables share: summary statistics, the paper's numbers and failure counts.

/// Mean, sample standard deviation and median of a sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Summary {
    pub(crate) mean: f64,
    pub(crate) sd: f64,
    pub(crate) median: f64,
}

/// The [`Summary`] of `v` (`None` when empty).
pub(crate) fn summary(v: &[f64]) -> Option<Summary> {
    if v.is_empty() {
        return None;
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = if v.len() > 1 {
        v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
    } else {
        0.0
    };
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.total_cmp(b));
    let median = if s.len() % 2 == 1 {
        s[s.len() / 2]
    } else {
        0.5 * (s[s.len() / 2 - 1] + s[s.len() / 2])
    };
    Some(Summary {
        mean,
        sd: var.sqrt(),
        median,
    })
}

/// Mean ± sd (s); `None` = N/A.
pub type MeanSd = Option<(f64, f64)>;

/// The paper's Table I: (success %, planning time mean, sd in s) per method column and benchmark.
pub const PAPER_TABLE1: [(&str, [(f64, MeanSd); 3]); 3] = [
    ("linear", [(27.0, None), (31.0, None), (24.0, None)]),
    (
        "tamp",
        [
            (100.0, Some((0.53, 0.10))),
            (100.0, Some((0.53, 0.23))),
            (100.0, Some((0.23, 0.09))),
        ],
    ),
    (
        "logic-lfd",
        [
            (100.0, Some((0.16, 0.07))),
            (100.0, Some((0.37, 0.27))),
            (100.0, Some((0.14, 0.06))),
        ],
    ),
];

/// The paper's Table II: execution time mean ± sd (s) per level, method, benchmark; `None` = N/A.
pub const PAPER_TABLE2: [(&str, [[MeanSd; 3]; 4]); 3] = [
    (
        "linear",
        [
            [
                Some((13.23, 0.58)),
                Some((12.50, 0.13)),
                Some((24.63, 0.05)),
            ],
            [None, None, None],
            [None, None, None],
            [None, None, None],
        ],
    ),
    (
        "rlds",
        [
            [
                Some((13.70, 1.23)),
                Some((12.59, 0.19)),
                Some((24.64, 0.04)),
            ],
            [
                Some((18.07, 0.95)),
                Some((19.08, 0.01)),
                Some((30.83, 0.04)),
            ],
            [None, None, None],
            [None, None, None],
        ],
    ),
    (
        "logic-lfd",
        [
            [
                Some((13.23, 0.35)),
                Some((12.50, 0.13)),
                Some((24.62, 0.03)),
            ],
            [
                Some((17.62, 0.67)),
                Some((19.08, 0.01)),
                Some((30.79, 0.02)),
            ],
            [
                Some((23.05, 0.49)),
                Some((26.03, 0.78)),
                Some((30.23, 0.08)),
            ],
            [
                Some((19.00, 1.29)),
                Some((12.60, 0.15)),
                Some((31.57, 0.04)),
            ],
        ],
    ),
];

pub(super) fn reason_kind(r: &crate::lfd::FailReason) -> String {
    serde_json::to_value(r)
        .ok()
        .and_then(|v| v.get("kind").and_then(|k| k.as_str()).map(str::to_string))
        .unwrap_or_else(|| "unknown".into())
}

pub(super) fn count(failures: &mut Vec<(String, usize)>, k: String) {
    match failures.iter_mut().find(|(n, _)| *n == k) {
        Some((_, c)) => *c += 1,
        None => failures.push((k, 1)),
    }
}

/// The group of a failure kind of the tables: `logic` (the task level found no way: no plan, no
/// demonstration step applies, the plan ended short of the goal), `motion` (an action could not
/// be executed, a block out of the robots' reach) or `budget` (replans or simulated time ran out).
pub fn failure_group(kind: &str) -> &'static str {
    match kind {
        "action-failed" | "out-of-reach" => "motion",
        "budget" => "budget",
        _ => "logic",
    }
}

/// The 95 % Wilson score interval of `successes` out of `n` (`(0, 1)` when `n` is 0).
pub fn wilson(successes: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (z, n) = (1.959_963_984_540_054, n as f64);
    let p = successes as f64 / n;
    let denom = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / denom;
    let half = z * libm::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / denom;
    ((centre - half).max(0.0), (centre + half).min(1.0))
}
