// Newton's gravitation among N bodies, written once for every model that
// uses it (`include!`d: the benchmark is a separate workspace).

/// `gravitating_bodies! { #[attributes] fn name(planar) { declarations }
/// then { statements } }`: a model whose declarations give `N`, the
/// gravitational constant `g`, the masses `m` and the state arrays `x`, `y`
/// (and `z`) of positions and `u`, `v` (and `w`) of velocities, followed by
/// r_i'' = Σ_{j≠i} g m_j (r_j − r_i)/|r_j − r_i|³ in the plane (`planar`)
/// or in space (`spatial`), then by `statements` (outputs, events).
/// `gravitating_bodies!(@then then { arguments } …)` hands the model to
/// `then!` after its arguments instead (tests/expansion.rs snapshots it).
#[allow(unused_macros)]
macro_rules! gravitating_bodies {
    // Each coordinate as (position, velocity, acceleration, difference).
    (@axes [$(($q:ident, $p:ident, $a:ident, $d:ident)),*] $then:ident { $($arguments:tt)* }
     $(#[$attribute:meta])* fn $name:ident { $($declarations:tt)* }
     $(then { $($statements:tt)* })?) => { $then! { $($arguments)*
        $(#[$attribute])*
        fn $name() {
            $($declarations)*
            for i in 0..N {
                $(der($q[i]) == $p[i];)*
                $(let mut $a = 0.0;)*
                for j in 0..N {
                    if j != i {
                        $(let $d = $q[j] - $q[i];)*
                        let r3 = (0.0 $(+ $d * $d)*).powf(-1.5);
                        $($a += g * m[j] * $d * r3;)*
                    }
                }
                $(der($p[i]) == $a;)*
            }
            $($($statements)*)?
        }
    } };
    (@then $then:ident { $($arguments:tt)* } $(#[$attribute:meta])* fn $name:ident(planar)
     $($rest:tt)*) => {
        gravitating_bodies! { @axes [(x, u, ax, dx), (y, v, ay, dy)] $then { $($arguments)* }
            $(#[$attribute])* fn $name $($rest)* }
    };
    (@then $then:ident { $($arguments:tt)* } $(#[$attribute:meta])* fn $name:ident(spatial)
     $($rest:tt)*) => {
        gravitating_bodies! { @axes [(x, u, ax, dx), (y, v, ay, dy), (z, w, az, dz)]
            $then { $($arguments)* } $(#[$attribute])* fn $name $($rest)* }
    };
    ($($model:tt)*) => {
        gravitating_bodies!(@then just_the_item {} $($model)*);
    };
}

/// `just_the_item!(item)`: the item, unchanged.
#[allow(unused_macros)]
macro_rules! just_the_item {
    ($item:item) => {
        $item
    };
}
