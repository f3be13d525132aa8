//! The `urdf("path")` statement: a robot's tree written as the model
//! language's own statements, one `spatial_body` per body (its centre of
//! mass and attitude where the zero configuration puts them, its full
//! inertia tensor) and one joint per moving joint (its point in each body
//! and its axis in the parent's), which the scene then lowers as if the
//! user had written them. The URDF's names are the bodies' and joints'
//! (`shoulder_pan_joint.q`, `wrist_3_link.x`). The root link is welded to
//! the ground, its welded mass dropped, or, with `.floating()`, a body of
//! its own on a free joint. A joint's `<dynamics damping>` is a damper
//! across it (`damper` or `translational_damper` of the standard library,
//! on the joint's flange, against a `fixed` support), named
//! `<joint>_damping`. A link welded to a moving body is bound to its
//! origin's position (`position(body, point)`), for the model to read.

use super::parse::JointKind;
use super::tree::{MassProperties, Tree};
use super::{mat_vec, Frame};
use proc_macro2::{Literal, Span, TokenStream};
use quote::quote;

/// `x` with the rounding of a quarter turn undone: within 1e-14 of 0 or ±1
/// it is exact (cos(π/2) is 6e-17 in floating point), so the scene sees a
/// quarter-turned axis or attitude as the zeros it has.
fn exact_where_rounded(x: f64) -> f64 {
    if x.abs() < 1e-14 {
        0.0
    } else if (x.abs() - 1.0).abs() < 1e-14 {
        x.signum()
    } else {
        x
    }
}

/// A number as a token, negative ones in parentheses.
fn number(x: f64) -> TokenStream {
    let lit = Literal::f64_unsuffixed(x.abs());
    if x.is_sign_negative() && x != 0.0 {
        quote!((-#lit))
    } else {
        quote!(#lit)
    }
}

fn vec3(v: [f64; 3]) -> TokenStream {
    let [x, y, z] = v.map(number);
    quote!(vec3(#x, #y, #z))
}

/// A URDF name as an identifier of the model language: characters Rust
/// does not allow become `_`.
pub fn identifier(name: &str) -> syn::Ident {
    let mut text: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if text.is_empty() || text.starts_with(|c: char| c.is_ascii_digit()) {
        text.insert(0, '_');
    }
    if syn::parse_str::<syn::Ident>(&text).is_err() {
        text.push('_');
    }
    syn::Ident::new(&text, Span::call_site())
}

/// The unit quaternion (q0 = cos(θ/2) first) of a rotation matrix
/// (Shepperd's method: the largest of the four squares first).
fn quaternion(r: &[[f64; 3]; 3]) -> [f64; 4] {
    let trace = r[0][0] + r[1][1] + r[2][2];
    let candidates = [trace, r[0][0], r[1][1], r[2][2]];
    let k = (0..4).max_by(|&a, &b| candidates[a].total_cmp(&candidates[b])).unwrap_or(0);
    let q = match k {
        0 => {
            let s = 2.0 * (1.0 + trace).sqrt();
            [s / 4.0, (r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s]
        }
        1 => {
            let s = 2.0 * (1.0 + r[0][0] - r[1][1] - r[2][2]).sqrt();
            [(r[2][1] - r[1][2]) / s, s / 4.0, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s]
        }
        2 => {
            let s = 2.0 * (1.0 - r[0][0] + r[1][1] - r[2][2]).sqrt();
            [(r[0][2] - r[2][0]) / s, (r[0][1] + r[1][0]) / s, s / 4.0, (r[1][2] + r[2][1]) / s]
        }
        _ => {
            let s = 2.0 * (1.0 - r[0][0] - r[1][1] + r[2][2]).sqrt();
            [(r[1][0] - r[0][1]) / s, (r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, s / 4.0]
        }
    };
    if q[0] < 0.0 {
        q.map(|x| -x)
    } else {
        q
    }
}

/// A body statement: `let name = spatial_body(m, mat3(..), [centre], [q]);`
/// for mass properties `mass` in a frame placed at `world`.
fn body(name: &syn::Ident, mass: &MassProperties, world: &Frame) -> TokenStream {
    let m = number(mass.mass);
    let inertia = mass.inertia.concat().into_iter().map(number);
    let centre = world.apply(&mass.com).map(number);
    let q = quaternion(&world.rotation).map(exact_where_rounded).map(number);
    quote! {
        let #name = spatial_body(#m, mat3(#(#inertia),*), [#(#centre),*], [#(#q),*]);
    }
}

/// The statements of `tree`: bodies, then joints, parents first. With
/// `floating`, the root is a body on a free joint; else it is the ground.
/// A URDF `floating` joint below the root is refused (`Err` with its line).
pub fn statements(tree: &Tree, floating: bool) -> Result<Vec<TokenStream>, (u32, String)> {
    let mut out = Vec::new();
    let ground = syn::Ident::new("__urdf_ground", Span::call_site());
    out.push(quote!(let #ground = ground();));
    let root_name = identifier(&tree.root_links[0].0);
    if floating {
        if tree.root_mass.mass <= 0.0 {
            return Err((1, format!("the root link `{}` has no mass, and a floating base needs one: give it an <inertial>", tree.root_links[0].0)));
        }
        out.push(body(&root_name, &tree.root_mass, &Frame::IDENTITY));
    }
    // Each body's link frame in the world at zero motion.
    let mut world: Vec<Frame> = Vec::with_capacity(tree.bodies.len());
    for b in &tree.bodies {
        let parent = b.parent.map_or(Frame::IDENTITY, |p| world[p]);
        world.push(parent.then(&b.joint.placement));
    }
    for (b, w) in tree.bodies.iter().zip(&world) {
        out.push(body(&identifier(&b.link), &b.mass, w));
    }
    // A link welded to a moving body (a tool flange, a sensor's frame) is
    // its origin's position, a 3-vector the model reads as `tool0[0]`.
    let mut welded: Vec<(syn::Ident, syn::Ident, [f64; 3])> = Vec::new();
    for b in &tree.bodies {
        for (link, frame) in &b.links[1..] {
            let t = frame.translation;
            let c = b.mass.com;
            welded.push((
                identifier(link),
                identifier(&b.link),
                [t[0] - c[0], t[1] - c[1], t[2] - c[2]],
            ));
        }
    }
    if floating {
        for (link, frame) in &tree.root_links[1..] {
            let (t, c) = (frame.translation, tree.root_mass.com);
            welded.push((
                identifier(link),
                root_name.clone(),
                [t[0] - c[0], t[1] - c[1], t[2] - c[2]],
            ));
        }
    }
    for b in &tree.bodies {
        let j = &b.joint;
        let (parent, parent_com) = match b.parent {
            Some(p) => (identifier(&tree.bodies[p].link), tree.bodies[p].mass.com),
            None if floating => (root_name.clone(), tree.root_mass.com),
            // The ground's frame is the root link's.
            None => (ground.clone(), [0.0; 3]),
        };
        // The joint at the child's link origin: from each centre of mass.
        let t = j.placement.translation;
        let in_parent = vec3([t[0] - parent_com[0], t[1] - parent_com[1], t[2] - parent_com[2]]);
        let in_child = vec3(b.mass.com.map(|c| -c));
        let axis = vec3(mat_vec(&j.placement.rotation, &j.axis).map(exact_where_rounded));
        let (name, child) = (identifier(&j.name), identifier(&b.link));
        let damped = j.damping > 0.0
            && matches!(j.kind, JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic);
        out.push(match j.kind {
            JointKind::Revolute | JointKind::Continuous => {
                quote!(let #name = revolute(#parent, #in_parent, #child, #in_child, #axis);)
            }
            JointKind::Prismatic => {
                quote!(let #name = prismatic(#parent, #in_parent, #child, #in_child, #axis);)
            }
            JointKind::Planar => {
                quote!(let #name = planar(#parent, #in_parent, #child, #in_child, #axis);)
            }
            JointKind::Floating if b.parent.is_none() && !floating => {
                // The root's only child floats: no joint holds it.
                continue;
            }
            JointKind::Floating | JointKind::Fixed => {
                return Err((j.line, format!("joint `{}` is {} below the root; only the root's joint may float (load the robot with `.floating()` instead)", j.name, j.kind.name())));
            }
        });
        if damped {
            let damper = syn::Ident::new(&format!("{name}_damping"), Span::call_site());
            let support = syn::Ident::new(&format!("{name}_support"), Span::call_site());
            let d = number(j.damping);
            let (part, fixed) = if j.kind == JointKind::Prismatic {
                (quote!(translational_damper), quote!(translational_fixed))
            } else {
                (quote!(damper), quote!(fixed))
            };
            out.push(quote! {
                let #damper = #part(#d);
                let #support = #fixed();
                connect(#support.flange, #damper.flange_a);
                connect(#damper.flange_b, #name.flange);
            });
        }
    }
    // After the joints, so that a name both a joint and a welded link
    // have stays the joint's.
    let taken: std::collections::HashSet<String> = tree
        .bodies
        .iter()
        .flat_map(|b| [identifier(&b.link).to_string(), identifier(&b.joint.name).to_string()])
        .chain([root_name.to_string()])
        .collect();
    for (link, on, point) in welded {
        if taken.contains(&link.to_string()) {
            continue;
        }
        let point = vec3(point);
        out.push(quote!(let #link = position(#on, #point);));
    }
    Ok(out)
}
