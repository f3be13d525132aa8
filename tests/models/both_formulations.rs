// `in_both_formulations!(global_name, recursive_name, { body })`: a scene
// written once, generated in body coordinates and in joint
// coordinates.

#[allow(unused_macros)]
macro_rules! in_both_formulations {
    ($global:ident, $recursive:ident, { $($body:tt)* }) => {
        #[dae_model]
        fn $global() { $($body)* }
        #[dae_model(scene = recursive)]
        fn $recursive() { $($body)* }
    };
}
