//! Multibody scenes lowered into equations (course notes §4.2): bodies
//! and joints of a planar scene in body coordinates (`planar`) or in
//! joint coordinates (`planar_recursive`, on the spanning tree of
//! `topology`), spatial scenes in body coordinates (`spatial`) or in joint
//! coordinates (`spatial_recursive`, with `spatial_joint_motion` and
//! `joint_space_dynamics` over the tree of `spatial_tree`, and
//! `spatial_vectors` and `algebra`), robots read from URDF files
//! (`urdf`), and the names a scene answers to (`names`). The lowering hands scene statements over through
//! `front::lower::SceneLanguage`, which `Scene` implements; a scene sees
//! the model being built and the lowering's public operations, nothing of
//! its scopes.

pub mod algebra;
pub mod body_frame_dynamics;
pub mod joint_space_dynamics;
pub mod names;
pub mod planar;
pub mod planar_recursive;
pub mod spatial;
pub mod spatial_joint_motion;
pub mod spatial_joint_rows;
pub mod spatial_recursive;
pub mod spatial_tree;
pub mod spatial_vectors;
pub mod topology;
pub mod tree_factorization;
pub mod urdf;

use crate::front::lower::Lower;
use crate::{Id, SymbolId};
use proc_macro2::TokenStream;

/// A planar rigid body: its coordinates and inertia.
#[derive(Clone)]
pub(crate) struct Body {
    pub name: String,
    pub x: SymbolId,
    pub y: SymbolId,
    pub theta: SymbolId,
    pub mass: Id,
    pub inertia: Id,
}

/// What a scene has collected by the end of the model.
#[derive(Default)]
pub(crate) struct Scene {
    pub bodies: Vec<Body>,
    pub ground: bool,
    pub first_body: Option<TokenStream>,
    /// Joint constraint rows and their multipliers.
    pub rows: Vec<(Id, Id)>,
    /// Applied forces: body, world force (x, y), torque.
    pub loads: Vec<(usize, Id, Id, Id)>,
    pub gravity: Option<(Id, Id)>,
    pub joints: usize,
    /// A line for the generated type's documentation.
    pub summary: String,
    /// `#[dae_model(scene = recursive)]`: relative joint coordinates.
    pub recursive: bool,
    /// Every joint, for joint coordinates.
    pub records: Vec<JointRecord>,
    /// The bodies of a spatial scene (then `bodies` is empty).
    pub spatial: Vec<SpatialBody>,
    /// Applied loads in a spatial scene.
    pub spatial_loads: Vec<SpatialLoad>,
    /// Gravity of a spatial scene.
    pub gravity_vector: Option<[Id; 3]>,
    /// Every joint's name, rows and statement, for reporting redundancy.
    pub joint_rows: Vec<(String, std::ops::Range<usize>, TokenStream)>,
    /// A `spatial_body` was declared (even one with an error).
    pub spatial_declared: bool,
    /// Every spatial joint, for joint coordinates.
    pub spatial_records: Vec<SpatialJointRecord>,
    /// The robot descriptions read (`urdf(..)`), which the build depends on.
    pub robot_files: Vec<std::path::PathBuf>,
    /// `init(j.q, ..)`, `init(der(j.q), ..)`: joint coordinates' starts
    /// (`scene = recursive`).
    pub joint_inits: Vec<JointInit>,
    /// Prismatic joints' flanges in joint coordinates: the joint,
    /// the symbol standing for its displacement until the joint's
    /// coordinate replaces it, and the displacement in body coordinates.
    pub prismatic_flanges: Vec<(String, SymbolId, Id)>,
}

/// A joint coordinate's start given by `init`: the state's name, the
/// order (0: the coordinate, 1: its rate), the value and the statement.
#[derive(Clone)]
pub(crate) struct JointInit {
    pub name: String,
    pub order: usize,
    pub value: Id,
    pub origin: TokenStream,
}

impl Scene {
    /// Whether joints and loads are spatial.
    pub(crate) fn is_spatial(&self) -> bool {
        self.spatial_declared
    }
}

/// The scene library the model language lowers bodies, joints and loads
/// with: each entry hands over to this module's lowering.
impl crate::front::lower::SceneLanguage for Scene {
    fn new(recursive: bool) -> Self {
        Scene { recursive, ..Scene::default() }
    }
    fn is_joint(name: &str) -> bool {
        JOINTS.contains(&name)
    }
    fn is_load(name: &str) -> bool {
        LOADS.contains(&name)
    }
    fn joint_init(
        l: &mut Lower<'_, Self>,
        target: &syn::Expr,
        value: &syn::Expr,
        whole: &syn::Expr,
    ) -> bool {
        l.joint_init(target, value, whole)
    }
    fn files(&self) -> Vec<std::path::PathBuf> {
        self.robot_files.clone()
    }
    fn is_robot(name: &str) -> bool {
        name == "urdf"
    }
    fn robot(l: &mut Lower<'_, Self>, call: &syn::ExprCall, e: &syn::Expr, floating: bool) {
        l.urdf(call, e, floating)
    }
    fn is_spatial(&self) -> bool {
        self.spatial_declared
    }
    fn has_spatial_bodies(&self) -> bool {
        !self.spatial.is_empty()
    }
    fn summary(&self) -> &str {
        &self.summary
    }
    fn body(
        l: &mut Lower<'_, Self>,
        ident: &syn::Ident,
        kind: &str,
        call: &syn::ExprCall,
        local: &syn::Local,
    ) {
        l.scene_declaration(ident, kind, call, local)
    }
    fn spatial_body(
        l: &mut Lower<'_, Self>,
        ident: &syn::Ident,
        call: &syn::ExprCall,
        local: &syn::Local,
    ) {
        l.spatial_declaration(ident, call, local)
    }
    fn joint(
        l: &mut Lower<'_, Self>,
        kind: &str,
        name: Option<&syn::Ident>,
        call: &syn::ExprCall,
        e: &syn::Expr,
    ) {
        l.joint(kind, name, call, e)
    }
    fn load(l: &mut Lower<'_, Self>, kind: &str, call: &syn::ExprCall, e: &syn::Expr) {
        l.load(kind, call, e)
    }
    fn body_coordinate(l: &mut Lower<'_, Self>, f: &syn::ExprField, e: &syn::Expr) -> Option<Id> {
        l.body_coordinate(f, e)
    }
    fn orientation(l: &mut Lower<'_, Self>, c: &syn::ExprCall, e: &syn::Expr) -> Option<[Id; 9]> {
        l.orientation(c, e)
    }
    fn position(l: &mut Lower<'_, Self>, c: &syn::ExprCall, e: &syn::Expr) -> Option<[Id; 2]> {
        l.position(c, e)
    }
    fn spatial_position(
        l: &mut Lower<'_, Self>,
        c: &syn::ExprCall,
        e: &syn::Expr,
    ) -> Option<[Id; 3]> {
        l.spatial_position(c, e)
    }
    fn natural_frame(
        g: &mut crate::Graph,
        p1: [Id; 3],
        p2: [Id; 3],
        p3: [Id; 3],
    ) -> crate::Result<[Id; 9]> {
        spatial::natural_frame(g, p1, p2, p3)
    }
    fn joint_axis(l: &Lower<'_, Self>, name: &str) -> Option<&'static str> {
        l.joint_axis(name)
    }
    fn joint_flange(l: &mut Lower<'_, Self>, name: &str, flow: Id, at: &syn::Expr) -> Option<Id> {
        l.joint_flange(name, flow, at)
    }
    fn equations(l: &mut Lower<'_, Self>, item: &syn::ItemFn) {
        l.scene_equations(item)
    }
}

/// A joint as declared: what joint coordinates need to place the
/// child from the parent, and which equations and multipliers it added.
#[derive(Clone)]
pub(crate) struct JointRecord {
    pub kind: &'static str,
    pub name: String,
    pub a: Frame,
    pub b: Frame,
    pub local_a: [Id; 2],
    pub local_b: [Id; 2],
    pub axis: Option<[Id; 2]>,
    pub equations: std::ops::Range<usize>,
    pub algebraics: std::ops::Range<usize>,
    pub rows: std::ops::Range<usize>,
}

/// A spatial joint as declared: what joint coordinates need to
/// place the child from the parent, and which equations and multipliers
/// it added.
#[derive(Clone)]
pub(crate) struct SpatialJointRecord {
    pub kind: &'static str,
    pub name: String,
    pub a: Frame,
    pub b: Frame,
    pub local_a: [Id; 3],
    pub local_b: [Id; 3],
    /// The axis (or normal, or length) in a's axes.
    pub axis: Option<[Id; 3]>,
    /// The axis's value at the defaults, which picks its normals.
    pub axis_values: Option<[f64; 3]>,
    /// A universal joint's axis in b's axes.
    pub cross_axis: Option<[Id; 3]>,
    pub equations: std::ops::Range<usize>,
    pub algebraics: std::ops::Range<usize>,
    pub rows: std::ops::Range<usize>,
}

/// Joint statements, which may be named by a `let`.
pub(crate) const JOINTS: [&str; 8] = [
    "revolute",
    "distance",
    "prismatic",
    "fixed",
    "spherical",
    "universal",
    "cylindrical",
    "planar",
];
/// What `force` takes, in the plane and in space.
pub(crate) const FORCE_USAGE: &str =
    "a body, the point of application in its coordinates and the force in world axes";

/// Load statements.
pub(crate) const LOADS: [&str; 4] = ["gravity", "force", "torque", "spring"];

/// A body or the ground, as a joint sees it.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Frame {
    Ground,
    Body(usize),
}

/// A load on a spatial body: forces at its centre of mass, one in world
/// axes and one in its own (a joint's force along an axis that keeps its
/// direction in the body), and a torque in its own axes.
#[derive(Clone, Copy)]
pub(crate) struct SpatialLoad {
    pub body: usize,
    pub world_force: [Id; 3],
    pub body_force: [Id; 3],
    pub torque: [Id; 3],
}

impl SpatialLoad {
    /// A world force at the centre with a torque in body axes.
    pub fn world(g: &mut crate::Graph, body: usize, world_force: [Id; 3], torque: [Id; 3]) -> Self {
        let zero = g.zero();
        SpatialLoad { body, world_force, body_force: [zero; 3], torque }
    }

    /// Every entry, for rewriting.
    pub fn entries_mut(&mut self) -> impl Iterator<Item = &mut Id> {
        self.world_force.iter_mut().chain(self.body_force.iter_mut()).chain(self.torque.iter_mut())
    }

    /// Every entry.
    pub fn entries(&self) -> impl Iterator<Item = Id> + '_ {
        self.world_force.iter().chain(&self.body_force).chain(&self.torque).copied()
    }
}

/// A spatial rigid body: its coordinates and inertia.
#[derive(Clone)]
pub(crate) struct SpatialBody {
    /// Centre of mass in world axes.
    pub position: [SymbolId; 3],
    /// Attitude, q0 = cos(θ/2) first; body to world.
    pub quaternion: [SymbolId; 4],
    /// Angular velocity in body axes.
    pub rates: [SymbolId; 3],
    pub mass: Id,
    /// Inertia tensor about the centre of mass in body axes, row-major.
    pub inertia: [Id; 9],
}

/// Pushes onto `terms` the constraint forces −(∂Φ_r/∂c)·λ_r on the
/// coordinate `c` of every row `(Φ_r, λ_r)` whose derivative is not
/// identically zero.
pub(crate) fn push_constraint_forces(
    g: &mut crate::Graph,
    rows: &[(Id, Id)],
    c: SymbolId,
    terms: &mut Vec<Id>,
) -> crate::Result<()> {
    for &(row, lambda) in rows {
        let d = g.partial(row, c)?;
        if g.as_number(d).is_some_and(|v| v.is_zero()) {
            continue;
        }
        let t = g.mul(d, lambda)?;
        terms.push(g.neg(t)?);
    }
    Ok(())
}

/// A spring–damper whose squared length is `d2`: its length d and its
/// tension k (d − l₀) + c ḋ, ḋ along `field`.
pub(crate) fn spring_tension(
    g: &mut crate::Graph,
    d2: Id,
    [k, damping, l0]: [Id; 3],
    field: &mut crate::VectorField,
) -> crate::Result<(Id, Id)> {
    let d = g.sqrt(d2)?;
    let d_dot = g.total_derivative(d, field)?;
    let stretch = g.sub(d, l0)?;
    let elastic = g.mul(k, stretch)?;
    let viscous = g.mul(damping, d_dot)?;
    Ok((d, g.add(elastic, viscous)?))
}

/// Removes the items at the positions `dropped` lists.
pub(crate) fn retain_unlisted<T>(items: &mut Vec<T>, dropped: &std::collections::HashSet<usize>) {
    let mut i = 0;
    items.retain(|_| {
        i += 1;
        !dropped.contains(&(i - 1))
    });
}

/// An error for what the scene's lowering could not build (`what`).
pub(crate) fn unsupported(what: &str) -> crate::Error {
    crate::Error::Unsupported { message: what.to_string() }
}
