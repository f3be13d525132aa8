//! An ensemble's members stepped `L` at a time by a batch model
//! (`#[dae_model(batch = L)]`): one run, one step size, the arithmetic of
//! `L` members side by side in SIMD lanes (heyoka's batch mode).

use super::{progress_bar, Ensemble, FinalState, FinalStates};
use crate::error::Error;
use crate::lanes::{interleave, lane_of};
use crate::model::Model;
use crate::options::Options;
use crate::run::Simulate;
use rayon::prelude::*;

/// A model whose state holds [`Model::LANES`] members of `Member`, stepped
/// together with one step size: what `#[dae_model(batch = L)]` generates
/// beside a model `M` as `MBatch`.
pub trait Batch: Simulate {
    /// The model of one member.
    type Member: Model;
    /// The batch of `members` (exactly `LANES` of them): lane `l` has
    /// member `l`'s parameters and starts from its initial state.
    fn from_members(members: &[Self::Member]) -> Self;
}

impl<M, F> Ensemble<'_, M, F>
where
    M: Simulate,
    F: Fn(usize) -> M + Sync,
{
    /// [`Ensemble::final_states`] with the members stepped `B::LANES` at a
    /// time by the batch model `B`: each batch takes the steps its most
    /// demanding member needs (so it pays where the members are alike),
    /// and each lane meets the tolerance as its member would alone. A
    /// batch that fails fails for each of its members, with its message.
    /// Explicit pairs (DOPRI5, DOP853) and the fixed-step methods run in
    /// batch.
    pub fn final_states_batched<B: Batch<Member = M>>(
        &self,
        t0: f64,
        t1: f64,
        options: &Options,
    ) -> FinalStates {
        let lanes = B::LANES;
        let options = super::final_state_options(options, t1).progress(false);
        let first = self.members.start;
        let batches = self.members.len().div_ceil(lanes);
        let bar = self.progress.then(|| progress_bar(self.members.len()));
        let one = |b: usize| -> Vec<FinalState> {
            let start = first + b * lanes;
            let end = (start + lanes).min(self.members.end);
            // The last batch repeats its last member in the lanes left over.
            let of = |l: usize| (start + l).min(end - 1);
            let members: Vec<M> = (0..lanes).map(|l| (self.model_of)(of(l))).collect();
            let batch = B::from_members(&members);
            let result = match &self.initial_state_of {
                Some(initial) => {
                    let states: Vec<Vec<f64>> = (0..lanes).map(|l| initial(of(l))).collect();
                    batch.simulate_from(t0, &interleave(&states), t1, &options)
                }
                None => batch.simulate(t0, t1, &options),
            };
            if let Some(bar) = &bar {
                bar.inc((end - start) as u64);
            }
            (start..end)
                .map(|member| FinalState {
                    member,
                    state: match &result {
                        Ok(solution) => Ok(lane_of(solution.final_state(), lanes, member - start)),
                        Err(e) => Err(e.to_string()),
                    },
                })
                .collect()
        };
        let rows = self.pool().run(|| (0..batches).into_par_iter().flat_map_iter(one).collect());
        if let Some(bar) = bar {
            bar.finish();
        }
        let names = M::INFO.states.iter().map(|s| s.to_string()).collect();
        let rows = rows.unwrap_or_else(|message| {
            let state = Err(Error::InvalidOptions { message }.to_string());
            self.members.clone().map(|member| FinalState { member, state: state.clone() }).collect()
        });
        FinalStates { names, rows }
    }
}
