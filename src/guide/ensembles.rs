//! # Ensembles: one model, many runs
//!
//! Monte Carlo over uncertain parameters, sweeps and fitting run one model
//! thousands of times. [`crate::Ensemble`] runs member `i` as the model
//! `model_of(i)` (its parameters set for that member), optionally from its
//! own initial state, on every core:
//!
//! | to | write |
//! |---|---|
//! | run every member, keep every solution | `ens.run(t0, t1, &opts)`: a `Vec<Result<Solution, Error>>` in member order |
//! | keep only what you need of each | `ens.map(t0, t1, &opts, \|i, result\| ..)`: each member reduced as it ends |
//! | fold the members in order (a million in little memory) | `ens.fold(t0, t1, &opts, reduce, init, \|acc, i, value\| ..)` |
//! | the final states only | `ens.final_states(t0, t1, &opts)`: a [`crate::FinalStates`] table, CSV in and out |
//! | chosen values (outputs too) at the end | `ens.final_values(t0, t1, &opts, &["x", "energy"])?` |
//! | members from their own initial states | `.initial_states(\|i\| vec![..])` |
//! | on k threads (default: every core) | `.threads(k)` |
//! | one progress bar for the ensemble | `.progress(true)` (the members' own bars stay off) |
//! | one machine's share of many | `.shard(Shard::parse("3/16")?)` |
//! | members stepped L at a time in SIMD lanes | `#[dae_model(batch = L)]`, then `ens.final_states_batched::<MBatch>(..)` |
//!
//! Each member is exactly the run it would be alone, so the answers do not
//! depend on the thread count, and a fold visits the members in order
//! whatever the threads. A member that fails keeps its `Err` (with its
//! partial solution) in its place; the others run on. A callback given by
//! [`crate::Options::on_step`] is shared: every member calls it, one at a
//! time.
//!
//! ```
//! use daegen::prelude::*;
//! use daegen::Ensemble;
//!
//! /// x' = −k x.
//! #[dae_model]
//! fn decay() {
//!     let k = param(1.0);
//!     let x = state(1.0);
//!     der(x) == -k * x;
//! }
//!
//! // A sweep of the rate: member i decays at k = 0.1 (i + 1).
//! let ensemble = Ensemble::new(100, |i| Decay { k: 0.1 * (i + 1) as f64 });
//! let opts = Options::new().tolerance(1e-10);
//! let finals = ensemble.final_states(0.0, 1.0, &opts);
//! for row in &finals.rows {
//!     let x = row.state.as_ref().unwrap()[0];
//!     let k = 0.1 * (row.member + 1) as f64;
//!     assert!((x - (-k).exp()).abs() < 1e-8);
//! }
//!
//! // The mean of x(1) over the members, folded in member order.
//! let final_x = |_: usize, r: Result<Solution, Error>| r.map(|s| s.final_state()[0]);
//! let sum = ensemble.fold(0.0, 1.0, &opts, final_x, 0.0, |sum, _, x| sum + x.unwrap());
//! assert!(sum / 100.0 > 0.0);
//! ```
//!
//! ## Batch lanes
//!
//! `#[dae_model(batch = L)]` (L from 2 to 16) generates beside the model
//! `M` the type `MBatch`: L members' parameters and states side by side,
//! the right-hand side computed for all of them at once on
//! [`crate::runtime::lanes::Lanes`] values, which the compiler turns into
//! SIMD instructions (heyoka's batch mode). A batch takes one step size,
//! the one its most demanding member needs, and measures each lane's error
//! alone, so every member meets the tolerance as it would alone; four
//! identical members take exactly the steps of one. It pays where the
//! members are alike (a sweep over a narrow range) and costs where they
//! are not: the results of `bench --ensemble` are in bench/README.md.
//!
//! ```
//! use daegen::prelude::*;
//! use daegen::{Batch, Ensemble};
//!
//! /// x' = −k x, in batches of four.
//! #[dae_model(batch = 4)]
//! fn decay() {
//!     let k = param(1.0);
//!     let x = state(1.0);
//!     der(x) == -k * x;
//! }
//!
//! let ensemble = Ensemble::new(10, |i| Decay { k: 1.0 + 0.01 * i as f64 });
//! let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
//! let finals = ensemble.final_states_batched::<DecayBatch>(0.0, 1.0, &opts);
//! for row in &finals.rows {
//!     let k = 1.0 + 0.01 * row.member as f64;
//!     assert!((row.state.as_ref().unwrap()[0] - (-k).exp()).abs() < 1e-9);
//! }
//! // A batch is a model too: lane l of `x` is `x[lane l]`.
//! let batch = DecayBatch::from_members(&[Decay { k: 1.0 }, Decay { k: 2.0 }, Decay { k: 3.0 }, Decay { k: 4.0 }]);
//! let sol = batch.simulate(0.0, 1.0, &opts).unwrap();
//! assert!((sol.last("x[lane 1]").unwrap() - (-2.0f64).exp()).abs() < 1e-9);
//! ```
//!
//! Batches run the explicit pairs (DOPRI5, DOP853), the fixed-step
//! methods and `Method::Taylor`, which runs the members' tapes as one tape
//! whose coefficients are lanes: each lane picks the order and the radius
//! of convergence it would alone, and the batch steps by the least radius
//! (the straight-line jets of `unroll` are for members run one by one).
//! The stiff methods refuse a batch: their Newton iteration would couple
//! the members' errors. Only explicit ODEs batch: a DAE, events or
//! derivatives solved at run time are a compile error that says so.
//!
//! ## Past one machine
//!
//! A shard `i/n` is the `i`-th of `n` contiguous blocks of members. Each
//! machine runs its shard and writes its final states; a merge puts the
//! files back in member order, refusing a member missing or given twice,
//! and equals the unsharded run to the bit. The example
//! `examples/ensemble.rs` is such a program:
//!
//! ```text
//! cargo run --release --example ensemble -- --members 100000 --shard 3/16 --out shard3.csv
//! cargo run --release --example ensemble -- merge --members 100000 --out all.csv shard*.csv
//! ```
//!
//! The scheduler that spreads the shards is the cluster's own. With Slurm,
//! an array job runs one task a shard, and the merge is a job that waits
//! for every task to succeed:
//!
//! ```text
//! array=$(sbatch --parsable --array=0-15 --cpus-per-task=8 --wrap \
//!   './ensemble --members 100000 --threads $SLURM_CPUS_PER_TASK --shard $SLURM_ARRAY_TASK_ID/16 --out shard$SLURM_ARRAY_TASK_ID.csv')
//! sbatch --parsable --wait --dependency=afterok:$array --wrap \
//!   './ensemble merge --members 100000 --out all.csv shard*.csv'
//! ```
//!
//! (`sbatch --wait` returns when the merge has run, with its exit code.)
//! CI runs this recipe on a real Slurm: `.ci/slurm-ensemble.sh` installs
//! Debian's `slurm-wlm` and `munge`, starts a one-node cluster on
//! localhost (the `slurm.conf` in the script is the least one that works:
//! `proctrack/linuxproc`, no accounting), submits 2000 members as a 4-task
//! array and the merge as a dependent job, and checks the merged file
//! against the unsharded run byte for byte. On Kubernetes, an indexed
//! Job gives each pod its index:
//!
//! ```text
//! apiVersion: batch/v1
//! kind: Job
//! metadata: {name: kepler-ensemble}
//! spec:
//!   completions: 16
//!   parallelism: 16
//!   completionMode: Indexed
//!   template:
//!     spec:
//!       restartPolicy: Never
//!       containers:
//!       - name: shard
//!         image: registry.example/ensemble:latest
//!         command: ["sh", "-c", "./ensemble --members 100000 --shard $JOB_COMPLETION_INDEX/16 --out /results/shard$JOB_COMPLETION_INDEX.csv"]
//!         volumeMounts: [{name: results, mountPath: /results}]
//!       volumes: [{name: results, persistentVolumeClaim: {claimName: ensemble-results}}]
//! ```
//!
//! with the merge as a second Job over the shared volume.
