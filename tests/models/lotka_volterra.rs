// Lotka–Volterra's prey and predators, shared by the expansion snapshots
// and the benchmark of sensitivities.

/// `lotka_volterra!(then! { arguments })`: `then!` called with its
/// arguments followed by the model as a plain item, so that
/// `lotka_volterra!(dae_model_with! { (sensitivities = [a]) })` defines it
/// and tests/expansion.rs snapshots its expansion.
#[allow(unused_macros)]
macro_rules! lotka_volterra {
    ($then:ident ! { $($arguments:tt)* }) => {
        $then! {
            $($arguments)*
            /// Lotka–Volterra, x′ = a·x − b·x·y, y′ = c·x·y − d·y (non-stiff).
            fn lotka_volterra() {
                let a = param(1.5);
                let b = param(1.0);
                let c = param(1.0);
                let d = param(3.0);
                let x = state(10.0);
                let y = state(5.0);
                der(x) == a * x - b * x * y;
                der(y) == c * x * y - d * y;
            }
        }
    };
}
