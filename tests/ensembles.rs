//! Ensembles: members in order with their own parameters and initial
//! states, each member's error kept in its place, answers independent of
//! the thread count, reductions that fold in member order, and shards that
//! merge back into the unsharded answer — checked against the exact
//! solution x(t) = x₀ e^(−k t).

use daegen::prelude::*;
use daegen::{Batch, Ensemble, FinalStates, Shard};

mod support;
use support::harness::{adaptive_methods_for, is_implicit};

/// x' = −k x from x(0) = 1.
#[dae_model]
fn decay() {
    let k = param(1.0);
    let x = state(1.0);
    der(x) == -k * x;
}

/// Member i decays at the rate k = 0.1 (i + 1).
fn rate(i: usize) -> f64 {
    0.1 * (i + 1) as f64
}

fn ensemble(n: usize) -> Ensemble<'static, Decay, impl Fn(usize) -> Decay + Sync> {
    Ensemble::new(n, |i| Decay { k: rate(i) })
}

fn options() -> Options {
    Options::new().method(Method::Dop853).tolerance(1e-12)
}

#[test]
fn members_come_back_in_order_with_their_own_parameters() {
    let results = ensemble(40).run(0.0, 2.0, &options());
    assert_eq!(results.len(), 40);
    for (i, result) in results.iter().enumerate() {
        let x = result.as_ref().unwrap().last("x").unwrap();
        let exact = (-rate(i) * 2.0).exp();
        assert!((x - exact).abs() <= 1e-11, "member {i}: {x} against {exact}");
    }
}

#[test]
fn members_start_from_their_own_initial_states() {
    let finals = ensemble(10).initial_states(|i| vec![i as f64]).final_states(0.0, 1.0, &options());
    assert_eq!(finals.names, ["x"]);
    for row in &finals.rows {
        let x = row.state.as_ref().unwrap()[0];
        let exact = row.member as f64 * (-rate(row.member)).exp();
        assert!((x - exact).abs() <= 1e-11, "member {}: {x} against {exact}", row.member);
    }
}

#[test]
fn a_failing_member_keeps_its_error_and_the_others_run() {
    let results = Ensemble::new(8, |i| Decay { k: if i == 3 { f64::NAN } else { rate(i) } }).run(
        0.0,
        1.0,
        &options(),
    );
    for (i, result) in results.iter().enumerate() {
        match (i, result) {
            (3, Err(Error::NonFiniteParameter { parameter, .. })) => assert_eq!(*parameter, "k"),
            (3, other) => panic!("member 3: expected NonFiniteParameter, got {other:?}"),
            (_, Ok(sol)) => assert!((sol.last("x").unwrap() - (-rate(i)).exp()).abs() <= 1e-11),
            (_, Err(e)) => panic!("member {i}: {e}"),
        }
    }
    let finals = Ensemble::new(8, |i| Decay { k: if i == 3 { f64::NAN } else { rate(i) } })
        .final_states(0.0, 1.0, &options());
    let errors: Vec<_> = finals.errors().collect();
    assert_eq!(errors.len(), 1);
    assert_eq!(errors[0].0, 3);
    assert!(errors[0].1.contains('k'), "{}", errors[0].1);
}

#[test]
fn the_answers_do_not_depend_on_the_thread_count() {
    let runs: Vec<Vec<(Vec<f64>, usize)>> = [1, 2, 0]
        .into_iter()
        .map(|threads| {
            ensemble(64).threads(threads).map(0.0, 3.0, &options(), |_, result| {
                let sol = result.unwrap();
                (sol.final_state().to_vec(), sol.stats().steps)
            })
        })
        .collect();
    assert_eq!(runs[0], runs[1]);
    assert_eq!(runs[0], runs[2]);
}

#[test]
fn a_fold_sums_in_member_order_beyond_one_chunk_of_members() {
    // More members than a fold holds at once (4096), on two threads.
    let n = 5000;
    let ens = Ensemble::new(n, |i| Decay { k: 1e-4 * i as f64 }).threads(2);
    let opts = Options::new().method(Method::Dopri5).tolerance(1e-10);
    let final_x = |_: usize, r: Result<Solution, Error>| r.unwrap().final_state()[0];
    let (count, sum) = ens.fold(0.0, 1.0, &opts, final_x, (0usize, 0.0f64), |(c, s), i, x| {
        assert_eq!(i, c, "members fold in order");
        (c + 1, s + x)
    });
    assert_eq!(count, n);
    // Σ e^(−1e-4 i) over i < n, a geometric series.
    let q = (-1e-4f64).exp();
    let exact = (1.0 - q.powi(n as i32)) / (1.0 - q);
    assert!((sum - exact).abs() <= 1e-9 * exact, "{sum} against {exact}");
    // The same order on one thread: the same bits.
    let again = ens.threads(1).fold(0.0, 1.0, &opts, final_x, 0.0, |s, _, x| s + x);
    assert_eq!(again, sum);
}

#[test]
fn shards_cover_every_member_once_and_merge_into_the_unsharded_table() {
    let n = 23;
    let whole = ensemble(n).final_states(0.0, 2.0, &options());
    let dir = std::env::temp_dir().join(format!("daegen-shards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut parts = Vec::new();
    let mut covered = 0;
    for index in 0..4 {
        let shard = Shard::parse(&format!("{index}/4")).unwrap();
        let part = ensemble(n).shard(shard);
        assert_eq!(part.members().start, covered);
        covered = part.members().end;
        let path = dir.join(format!("shard{index}.csv"));
        part.final_states(0.0, 2.0, &options()).write_csv(&path).unwrap();
        parts.push(FinalStates::read_csv(&path).unwrap());
    }
    assert_eq!(covered, n);
    // Shards given in any order; the numbers read back to the bit.
    parts.reverse();
    let merged = FinalStates::merge(parts.clone(), n).unwrap();
    assert_eq!(merged, whole);
    // A shard left out, or given twice, is an error that says so.
    let missing = FinalStates::merge(parts[..3].to_vec(), n).unwrap_err().to_string();
    assert!(missing.contains("missing"), "{missing}");
    let mut twice = parts.clone();
    twice.push(parts[0].clone());
    let twice = FinalStates::merge(twice, n).unwrap_err().to_string();
    assert!(twice.contains("two shards"), "{twice}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_error_message_crosses_a_csv_file_intact() {
    let finals = Ensemble::new(3, |i| Decay { k: if i == 1 { f64::INFINITY } else { 1.0 } })
        .final_states(0.0, 1.0, &options());
    let path = std::env::temp_dir().join(format!("daegen-errors-{}.csv", std::process::id()));
    finals.write_csv(&path).unwrap();
    let back = FinalStates::read_csv(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(back, finals);
    assert_eq!(back.errors().count(), 1);
}

#[test]
fn bad_shards_are_refused_with_what_to_write() {
    for text in ["4/4", "1/0", "one/4", "3"] {
        let e = Shard::parse(text).unwrap_err().to_string();
        assert!(e.contains("i/n"), "{text}: {e}");
    }
    // Blocks differ in size by one at most.
    let sizes: Vec<usize> = (0..3).map(|i| Shard::new(i, 3).unwrap().members(10).len()).collect();
    assert_eq!(sizes, [3, 3, 4]);
}

include!("models/kepler.rs");

// Kepler's problem, and beside it `KeplerBatch`: four members a run.
kepler_model!(fn kepler(batch = 4) {});

#[test]
fn a_batch_of_equal_steps_gives_each_member_its_scalar_run_to_the_bit() {
    let members: Vec<Kepler> = (0..4).map(|i| Kepler { e: 0.1 + 0.2 * i as f64 }).collect();
    let batch = KeplerBatch::from_members(&members);
    assert_eq!(batch.member(2), members[2]);
    let opts = Options::new().method(Method::Rk4).step(1e-3);
    let together = batch.simulate(0.0, 3.0, &opts).unwrap();
    for (lane, member) in members.iter().enumerate() {
        let alone = member.simulate(0.0, 3.0, &opts).unwrap();
        for (i, name) in ["q1", "q2", "p1", "p2"].iter().enumerate() {
            let lane_value = together.last(&format!("{name}[lane {lane}]")).unwrap();
            assert_eq!(lane_value, alone.final_state()[i], "lane {lane}: {name}");
        }
    }
}

#[test]
fn a_batch_of_identical_members_steps_as_one_member_alone() {
    // Each lane is measured alone: four equal lanes take the scalar run's
    // steps, to the bit.
    // Every adaptive method that runs a batch (the Taylor method's order
    // and tolerances are the next test's).
    for method in adaptive_methods_for::<KeplerBatch>() {
        let opts = Options::new().method(method).tolerance(1e-10);
        let member = Kepler { e: 0.7 };
        let alone = member.simulate(0.0, 10.0, &opts).unwrap();
        let together = KeplerBatch::from_members(&[member; 4]).simulate(0.0, 10.0, &opts).unwrap();
        assert_eq!(together.stats().steps, alone.stats().steps, "{method:?}");
        let lane3: Vec<f64> = together.final_state().iter().skip(3).step_by(4).copied().collect();
        assert_eq!(lane3, alone.final_state(), "{method:?}");
    }
}

#[test]
fn a_taylor_batch_of_identical_members_steps_as_one_member_alone() {
    // The members' tapes on lanes: four equal lanes take the scalar tape's
    // order and steps and end on its state, to the bit.
    for tol in [1e-9, 1e-15] {
        let opts = Options::new().method(Method::Taylor).tolerance(tol);
        let member = Kepler { e: 0.7 };
        let alone = member.simulate(0.0, 10.0, &opts).unwrap();
        let together = KeplerBatch::from_members(&[member; 4]).simulate(0.0, 10.0, &opts).unwrap();
        assert_eq!(together.stats().taylor_order, alone.stats().taylor_order, "tol {tol}");
        assert_eq!(together.stats().steps, alone.stats().steps, "tol {tol}");
        for lane in 0..4 {
            let values: Vec<f64> =
                together.final_state().iter().skip(lane).step_by(4).copied().collect();
            assert_eq!(values, alone.final_state(), "tol {tol}, lane {lane}");
        }
    }
}

#[test]
fn a_taylor_batch_meets_the_tolerance_in_every_lane() {
    // Eccentricities 0 … 0.72 in batches of four (the last of two members,
    // two spare lanes), one period: every member back at its pericentre.
    let ens = Ensemble::new(10, |i| Kepler { e: 0.08 * i as f64 });
    let opts = Options::new().method(Method::Taylor).tolerance(1e-13);
    let batched = ens.final_states_batched::<KeplerBatch>(0.0, 2.0 * std::f64::consts::PI, &opts);
    assert_eq!(batched.rows.len(), 10);
    for row in &batched.rows {
        let y = row.state.as_ref().unwrap();
        let e = 0.08 * row.member as f64;
        let start = [1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt()];
        for k in 0..4 {
            assert!((y[k] - start[k]).abs() <= 1e-10, "member {}: {y:?}", row.member);
        }
    }
}

/// x' = −k x + sin t in batches of three: a width that is not a power of
/// two (the lanes run padded to four).
#[dae_model(batch = 3)]
fn forced_decay() {
    let k = param(1.0);
    let x = state(1.0);
    let t = time();
    der(x) == -k * x + sin(t);
}

/// The exact solution of [`forced_decay`] from x(0) = 1.
fn forced_decay_exact(k: f64, t: f64) -> f64 {
    let particular = |t: f64| (k * t.sin() - t.cos()) / (1.0 + k * k);
    particular(t) + (1.0 - particular(0.0)) * (-k * t).exp()
}

#[test]
fn a_taylor_batch_of_three_follows_each_members_exact_solution_between_steps() {
    let rates = [0.5, 2.0, 7.0];
    let members = rates.map(|k| ForcedDecay { k });
    let batch = ForcedDecayBatch::from_members(&members);
    let opts = Options::new().method(Method::Taylor).tolerance(1e-14).dense_output(true);
    let sol = batch.simulate(0.0, 5.0, &opts).unwrap();
    for (lane, &k) in rates.iter().enumerate() {
        let name = format!("x[lane {lane}]");
        for t in [0.37, 1.9, 3.05, 5.0] {
            let (got, exact) = (sol.at(t, &name).unwrap(), forced_decay_exact(k, t));
            assert!((got - exact).abs() <= 1e-13, "lane {lane}, t = {t}: {got} against {exact}");
        }
    }
}

#[test]
fn a_taylor_batch_names_the_lane_that_went_non_finite() {
    let members = [1.0, f64::NAN, 2.0].map(|k| ForcedDecay { k });
    let err = ForcedDecayBatch::from_members(&members)
        .simulate(0.0, 1.0, &Options::new().method(Method::Taylor))
        .unwrap_err();
    assert!(matches!(err, Error::NonFinite { variable: "x[lane 1]", .. }), "{err}");
}

#[test]
fn batched_ensembles_meet_the_tolerance_in_every_lane() {
    // Eccentricities 0 … 0.8: the lanes need different steps; the batch
    // takes the smallest, and every member stays within the tolerance of
    // its exact orbit (energy −1/2 for a = 1).
    let ens = Ensemble::new(10, |i| Kepler { e: 0.08 * i as f64 });
    let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
    let batched = ens.final_states_batched::<KeplerBatch>(0.0, 2.0 * std::f64::consts::PI, &opts);
    let alone = ens.final_states(0.0, 2.0 * std::f64::consts::PI, &opts);
    assert_eq!(batched.rows.len(), 10, "the last batch's two spare lanes are dropped");
    for (b, a) in batched.rows.iter().zip(&alone.rows) {
        assert_eq!(b.member, a.member);
        let (yb, ya) = (b.state.as_ref().unwrap(), a.state.as_ref().unwrap());
        // After one period the orbit is back at its pericentre.
        let e = 0.08 * b.member as f64;
        let start = [1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt()];
        for k in 0..4 {
            assert!((yb[k] - start[k]).abs() <= 1e-7, "member {}: {yb:?}", b.member);
            assert!((ya[k] - start[k]).abs() <= 1e-7, "member {}: {ya:?}", a.member);
        }
    }
    // Members from their own initial states, in batches too: the orbit of
    // eccentricity 0.05 i (the parameter only sets the initial state), back
    // at its pericentre after one period.
    let pericentre = |e: f64| vec![1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt()];
    let shifted = ens.initial_states(move |i| pericentre(0.05 * i as f64));
    let b = shifted.final_states_batched::<KeplerBatch>(0.0, 2.0 * std::f64::consts::PI, &opts);
    for row in &b.rows {
        let y = row.state.as_ref().unwrap();
        let start = pericentre(0.05 * row.member as f64);
        assert!(y.iter().zip(&start).all(|(a, b)| (a - b).abs() <= 1e-7), "{y:?} {start:?}");
    }
}

#[test]
fn the_contracts_chain_runs_with_a_progress_bar() {
    // `Ensemble::new(n, |i| model_i).threads(k).run(t0, t1, &opts)`, with
    // one bar for the ensemble (drawn on stderr only on a terminal).
    let rates: Vec<f64> = (0..16).map(rate).collect();
    let results = Ensemble::new(rates.len(), |i| Decay { k: rates[i] })
        .threads(2)
        .progress(true)
        .run(0.0, 1.0, &options().progress(true));
    assert_eq!(results.len(), 16);
    for (k, result) in rates.iter().zip(&results) {
        let x = result.as_ref().unwrap().last("x").unwrap();
        assert!((x - (-k).exp()).abs() <= 1e-11);
    }
}

#[test]
fn a_batch_refuses_the_methods_that_would_mix_its_members_errors() {
    let batch = KeplerBatch::from_members(&[Kepler { e: 0.5 }; 4]);
    // The implicit methods: one Newton or Rosenbrock system for all the
    // lanes would mix the members' errors.
    for method in Method::ALL.into_iter().filter(|&m| is_implicit(m)) {
        let err = batch.simulate(0.0, 1.0, &Options::new().method(method)).unwrap_err();
        let message = err.to_string();
        assert!(
            message.contains("Dop853") || message.contains("one by one"),
            "{method:?}: {message}"
        );
    }
}

/// The decay with its rate of change as an output.
#[dae_model]
fn decay_with_rate() {
    let k = param(1.0);
    let x = state(1.0);
    der(x) == -k * x;
    let rate_of_x = output(-k * x);
}

#[test]
fn final_values_read_outputs_by_name_and_refuse_unknown_names() {
    let ens = Ensemble::new(5, |i| DecayWithRate { k: rate(i) });
    let values = ens.final_values(0.0, 1.0, &options(), &["rate_of_x", "x"]).unwrap();
    assert_eq!(values.names, ["rate_of_x", "x"]);
    for row in &values.rows {
        let k = rate(row.member);
        let v = row.state.as_ref().unwrap();
        assert!((v[1] - (-k).exp()).abs() <= 1e-11);
        assert!((v[0] + k * (-k).exp()).abs() <= 1e-11);
    }
    match ens.final_values(0.0, 1.0, &options(), &["energy"]) {
        Err(Error::UnknownName { name, known }) => {
            assert_eq!(name, "energy");
            assert!(known.contains(&"rate_of_x"), "{known:?}");
        }
        other => panic!("expected UnknownName, got {other:?}"),
    }
}

#[test]
fn members_may_borrow_their_initial_states_and_shards_nest() {
    let starts: Vec<Vec<f64>> = (0..12).map(|i| vec![1.0 + i as f64]).collect();
    let ens = ensemble(12).initial_states(|i| starts[i].clone());
    let whole = ens.final_states(0.0, 1.0, &options());
    // Shard 1 of 3 is members 4..8; its shard 1 of 2, members 6..8.
    let inner = ensemble(12).shard(Shard::new(1, 3).unwrap()).shard(Shard::new(1, 2).unwrap());
    assert_eq!(inner.members(), 6..8);
    let part = inner.initial_states(|i| starts[i].clone()).final_states(0.0, 1.0, &options());
    assert_eq!(part.rows[..], whole.rows[6..8]);
}

#[test]
fn an_empty_ensemble_runs_nothing_and_says_nothing_went_wrong() {
    let empty = ensemble(0);
    assert!(empty.run(0.0, 1.0, &options()).is_empty());
    assert!(empty.final_states(0.0, 1.0, &options()).rows.is_empty());
    assert_eq!(empty.fold(0.0, 1.0, &options(), |_, _| 1, 0, |a, _, b| a + b), 0);
    let no_batches = Ensemble::new(0, |_| Kepler { e: 0.5 });
    assert!(no_batches.final_states_batched::<KeplerBatch>(0.0, 1.0, &options()).rows.is_empty());
}
