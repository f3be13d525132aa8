//! With the `serde` feature a solution serializes as its model, a table of
//! every name at the stored times, the statistics and the events.
#![cfg(feature = "serde")]

use daegen::prelude::*;

/// A body dropped from 1 m, stopped at the ground.
#[dae_model]
fn falling() {
    let h = state(1.0);
    der(der(h)) == -9.81;
    /// Height above 0.5 m.
    let above = output(h - 0.5);
    let impact = event(h).falling().terminal();
}

#[test]
fn a_solution_serializes_with_every_name_its_stats_and_events() {
    let opts = Options::new().output_times(vec![0.0, 0.1, 0.2]);
    let sol = Falling::default().simulate(0.0, 1.0, &opts).unwrap();
    let json: serde_json::Value = serde_json::to_value(&sol).unwrap();
    assert_eq!(json["model"], "Falling");
    assert_eq!(json["table"]["names"], serde_json::json!(["h", "der(h)", "above"]));
    assert_eq!(json["table"]["times"], serde_json::json!([0.0, 0.1, 0.2]));
    let h = json["table"]["columns"][0].as_array().unwrap();
    let above = json["table"]["columns"][2].as_array().unwrap();
    for (k, t) in [0.0, 0.1, 0.2].iter().enumerate() {
        let exact = 1.0 - 0.5 * 9.81 * t * t;
        assert!((h[k].as_f64().unwrap() - exact).abs() < 1e-12);
        assert!((above[k].as_f64().unwrap() - (exact - 0.5)).abs() < 1e-12);
    }
    assert_eq!(json["stats"]["steps"], sol.stats().steps);
    assert_eq!(json["events"][0]["name"], "impact");
    let impact = (2.0f64 / 9.81).sqrt();
    assert!((json["events"][0]["t"].as_f64().unwrap() - impact).abs() < 1e-14);
    let table = sol.sample(&["h"], &[0.1]).unwrap();
    let text = serde_json::to_string(&table).unwrap();
    assert!(text.starts_with(r#"{"names":["h"],"times":[0.1],"columns":[["#), "{text}");
}
