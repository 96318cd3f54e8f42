//! `logic-lfd lqt`: the shared example runs with every key, shape and invariant; bad input exits 2
//! with the key and the expected shape.

use nalgebra::DMatrix;

use super::{rel_err, EXAMPLE};
use crate::support::cli::run_cli;

fn as_matrix(v: &serde_json::Value) -> DMatrix<f64> {
    let rows = v.as_array().unwrap();
    let cols = rows[0].as_array().unwrap().len();
    DMatrix::from_fn(rows.len(), cols, |r, c| rows[r][c].as_f64().unwrap())
}

/// The shared example runs through the CLI: every key, every shape, and the invariants.
#[test]
fn cli_runs_shared_example() {
    let (code, out, err) = run_cli(&["lqt", EXAMPLE]);
    assert_eq!(code, 0, "{err}");
    let o: serde_json::Value = serde_json::from_str(&out).unwrap();
    let shape = |k: &serde_json::Value| as_matrix(k).shape();
    assert_eq!(shape(&o["A"]), (4, 4));
    assert_eq!(shape(&o["B"]), (4, 2));
    assert_eq!(shape(&o["phi"]), (59, 8));
    assert_eq!(shape(&o["w"]), (8, 2));
    assert_eq!(shape(&o["u"]), (59, 2));
    assert_eq!(shape(&o["x"]), (60, 4));
    assert_eq!(shape(&o["pos"]), (60, 2));
    assert!(o["cost"].as_f64().unwrap() > 0.0);
    let te = o["target_errors"].as_array().unwrap();
    assert_eq!(te.len(), 2);
    assert_eq!(te[0]["role"], "via");
    assert!(te[0].get("vel_dist").is_none());
    assert!(te[1]["vel_dist"].as_f64().is_some());
    assert!(te[1]["pos_dist"].as_f64().unwrap() < 0.05);
    let fb = &o["feedback"];
    assert_eq!(shape(&fb["F"]), (118, 5));
    let gains = fb["gains"].as_array().unwrap();
    assert_eq!(gains.len(), 59);
    assert_eq!(shape(&gains[0]), (2, 5));
    // x_init == x0 in the example: the nominal rollout is the batch solution
    let x = as_matrix(&o["x"]);
    assert!(rel_err(&as_matrix(&fb["nominal"]["x"]), &x) < 1e-9);
    assert!(rel_err(&as_matrix(&fb["nominal"]["u"]), &as_matrix(&o["u"])) < 1e-9);
    let d_nom = fb["nominal"]["final_goal_pos_dist"].as_f64().unwrap();
    assert!((d_nom - te[1]["pos_dist"].as_f64().unwrap()).abs() < 1e-9);
    let d_pert = fb["perturbed"]["final_goal_pos_dist"].as_f64().unwrap();
    assert!(d_pert < 0.01, "{d_pert}");
    // pos is the first D columns of x; the perturbation hits x_21
    let px = as_matrix(&fb["perturbed"]["x"]);
    assert_eq!(as_matrix(&o["pos"]), x.columns(0, 2).into_owned());
    assert!((px.row(20) - x.row(20)).amax() < 1e-12);
    assert!((px.row(21) - x.row(21)).amax() > 0.09);
    // --pretty prints the same object
    let (code, pretty, _) = run_cli(&["lqt", EXAMPLE, "--pretty"]);
    assert_eq!(code, 0);
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&pretty).unwrap(),
        o
    );
}

/// An edit applied to the example's JSON.
type Edit = Box<dyn Fn(&mut serde_json::Value)>;

fn example_json() -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(EXAMPLE).unwrap()).unwrap()
}

/// Bad input: exit 2, the key and the expected shape on stderr, no panic, nothing on stdout.
#[test]
fn cli_rejects_bad_input_with_key() {
    let dir = std::env::temp_dir().join(format!("lqt-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases: Vec<(&str, Edit, &str)> = vec![
        (
            "missing",
            Box::new(|v| {
                v.as_object_mut().unwrap().remove("dim");
            }),
            "dim: missing key",
        ),
        (
            "k_gt_n",
            Box::new(|v| {
                v["basis"] = serde_json::json!({"type": "bernstein", "n_fct": 60});
            }),
            "basis.n_fct",
        ),
        ("order0", Box::new(|v| v["order"] = 0.into()), "order"),
        ("order7", Box::new(|v| v["order"] = 7.into()), "order"),
        (
            "neg_q",
            Box::new(|v| v["reference"]["q_diag"][3][1] = (-1.0).into()),
            "reference.q_diag[3][1]",
        ),
        (
            "basis",
            Box::new(|v| v["basis"]["type"] = "wavelet".into()),
            "unknown basis",
        ),
        (
            "mu_rows",
            Box::new(|v| {
                v["reference"]["mu"].as_array_mut().unwrap().pop();
            }),
            "reference.mu: expected 60 rows of 4 numbers, got 59 rows",
        ),
        (
            "mu_cols",
            Box::new(|v| {
                v["reference"]["mu"][5].as_array_mut().unwrap().pop();
            }),
            "reference.mu: expected 60 rows of 4 numbers, row 5 has 3 numbers",
        ),
        (
            "x0",
            Box::new(|v| v["x0"] = serde_json::json!([0.0, 0.0])),
            "x0: expected 4 numbers, got 2",
        ),
        (
            "centers",
            Box::new(|v| v["basis"]["centers"] = serde_json::json!([0.0, 1.0])),
            "basis.centers",
        ),
        (
            "pert",
            Box::new(|v| v["feedback"]["perturbation"]["after_step"] = 59.into()),
            "after_step",
        ),
        (
            "string",
            Box::new(|v| v["dt"] = "fast".into()),
            "dt: expected a number",
        ),
        (
            "target",
            Box::new(|v| v["targets"][1]["pos"] = serde_json::json!([1.0])),
            "targets[1].pos",
        ),
    ];
    for (name, edit, needle) in cases {
        let mut v = example_json();
        edit(&mut v);
        let path = dir.join(format!("{name}.json"));
        std::fs::write(&path, v.to_string()).unwrap();
        let (code, out, err) = run_cli(&["lqt", path.to_str().unwrap()]);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(out.is_empty(), "{name}");
        assert!(err.contains(needle), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
    // non-finite numbers and broken JSON
    let path = dir.join("nonfinite.json");
    let text =
        std::fs::read_to_string(EXAMPLE)
            .unwrap()
            .replacen("\"dt\": 0.02", "\"dt\": 1e999", 1);
    std::fs::write(&path, text).unwrap();
    let (code, _, err) = run_cli(&["lqt", path.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    let path = dir.join("broken.json");
    std::fs::write(&path, "{\"dim\": 2,\n \"order\": }").unwrap();
    let (code, _, err) = run_cli(&["lqt", path.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("broken.json:2:"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
