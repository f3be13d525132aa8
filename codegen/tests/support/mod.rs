//! What the property tests share: how many cases, and where they come from.

use proptest::test_runner::{Config, FileFailurePersistence, RngSeed};

/// The seed CI runs with: a submission is judged on cases chosen once, never
/// on a draw nobody saw. Locally the draw is random, so new cases keep being
/// tried; a failure found either way is kept (in the file `regressions` names, else
/// proptest's default) and replayed first.
pub const CI_SEED: u64 = 0x6461_6567_656e;

/// `cases` random cases, from [`CI_SEED`] when the environment says `CI=true`.
pub fn config(cases: u32, regressions: Option<&'static str>) -> Config {
    let ci = std::env::var("CI").is_ok_and(|v| v == "true");
    let mut config = Config {
        cases,
        max_global_rejects: 1_000_000,
        rng_seed: if ci { RngSeed::Fixed(CI_SEED) } else { RngSeed::Random },
        ..Config::default()
    };
    if let Some(path) = regressions {
        config.failure_persistence = Some(Box::new(FileFailurePersistence::Direct(path)));
    }
    config
}
