// Pinocchio's reference for the robots (`bench/peers/robots.py` wrote
// tests/robots/pinocchio.json) and the dense solve that checks a model
// against it: shared by tests/robots.rs and codegen/tests/urdf.rs.

/// The entry of robot `name` in `pinocchio.json`, in `robots_dir`.
fn pinocchio_reference(robots_dir: &std::path::Path, name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(robots_dir.join("pinocchio.json")).unwrap();
    let all: serde_json::Value = serde_json::from_str(&text).unwrap();
    all["robots"].as_array().unwrap().iter().find(|r| r["name"] == name).unwrap().clone()
}

/// A JSON array of numbers.
fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

/// The joints of a reference robot, in Pinocchio's order.
fn reference_joints(robot: &serde_json::Value) -> Vec<String> {
    robot["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["joint"].as_str().unwrap().to_string())
        .collect()
}

/// x = A⁻¹ b by Gaussian elimination with partial pivoting: the reference
/// solve of the robot tests, M⁻¹(τ − nle) from Pinocchio's matrices.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs())).unwrap();
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..n {
            let f = a[i][k] / a[k][k];
            let (above, below) = a.split_at_mut(i);
            for (x, p) in below[0][k..].iter_mut().zip(&above[k][k..]) {
                *x -= f * p;
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    x
}
