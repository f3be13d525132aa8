use daegen::prelude::*;

/// A misspelt method in the benchmark problem: the error points at it.
#[dae_model(bench = Bench::until(1.0).methods([Dop854]))]
fn decay() {
    let x = state(1.0);
    der(x) == -x;
}

fn main() {}
