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
    (@then $then:ident { $($arguments:tt)* }
     $(#[$attribute:meta])* fn $name:ident(planar) { $($declarations:tt)* }
     $(then { $($statements:tt)* })?) => { $then! { $($arguments)*
        $(#[$attribute])*
        fn $name() {
            $($declarations)*
            for i in 0..N {
                der(x[i]) == u[i];
                der(y[i]) == v[i];
                let mut ax = 0.0;
                let mut ay = 0.0;
                for j in 0..N {
                    if j != i {
                        let dx = x[j] - x[i];
                        let dy = y[j] - y[i];
                        let r3 = (dx * dx + dy * dy).powf(-1.5);
                        ax += g * m[j] * dx * r3;
                        ay += g * m[j] * dy * r3;
                    }
                }
                der(u[i]) == ax;
                der(v[i]) == ay;
            }
            $($($statements)*)?
        }
    } };
    (@then $then:ident { $($arguments:tt)* }
     $(#[$attribute:meta])* fn $name:ident(spatial) { $($declarations:tt)* }
     $(then { $($statements:tt)* })?) => { $then! { $($arguments)*
        $(#[$attribute])*
        fn $name() {
            $($declarations)*
            for i in 0..N {
                der(x[i]) == u[i];
                der(y[i]) == v[i];
                der(z[i]) == w[i];
                let mut ax = 0.0;
                let mut ay = 0.0;
                let mut az = 0.0;
                for j in 0..N {
                    if j != i {
                        let dx = x[j] - x[i];
                        let dy = y[j] - y[i];
                        let dz = z[j] - z[i];
                        let r3 = (dx * dx + dy * dy + dz * dz).powf(-1.5);
                        ax += g * m[j] * dx * r3;
                        ay += g * m[j] * dy * r3;
                        az += g * m[j] * dz * r3;
                    }
                }
                der(u[i]) == ax;
                der(v[i]) == ay;
                der(w[i]) == az;
            }
            $($($statements)*)?
        }
    } };
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
