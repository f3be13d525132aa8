//! What the model language asks of a scene library (bodies, joints,
//! loads): the lowering is generic over it, so the front end names no
//! scene type and the scene library depends on the front end, not the
//! other way round. `mechanics::Scene` is the one the pipeline uses.
//!
//! A scene library's lowering sees a narrow part of the front end: the
//! model being built (graph, diagnostics, parameters, states, algebraic
//! variables, equations, initial values, invariants, outputs, events) and
//! the operations `pub(crate)` in `front::lower` (lower a value or a
//! tensor, look up, bind and rebind names, declare states and algebraic
//! variables, push equations of motion, check an arity, report an unknown
//! name). The scopes, unrolling and integer semantics stay private to the
//! front end (`pub(in crate::front)`).

use super::scopes::Lower;
use crate::{Graph, Id};
use syn::Expr;

/// The statements, declarations and functions of the language that a scene
/// library lowers, each entered with the lowering it extends.
pub(crate) trait SceneLanguage: Sized {
    /// An empty scene; joints in relative coordinates when `recursive`.
    fn new(recursive: bool) -> Self;
    /// Whether `name(..)` is a joint statement.
    fn is_joint(name: &str) -> bool;
    /// Whether `name(..)` is a load statement.
    fn is_load(name: &str) -> bool;
    /// Whether `name(..)` loads a robot from a file (`urdf`).
    fn is_robot(name: &str) -> bool;
    /// `urdf("path")`, or `urdf("path").floating()` (`floating`): a robot's
    /// bodies and joints from its description.
    fn robot(l: &mut Lower<'_, Self>, call: &syn::ExprCall, e: &Expr, floating: bool);
    /// `init(j.q, value)` or `init(der(j.q), value)` on a joint's
    /// coordinate: whether the scene took it (else it is lowered as any
    /// `init`).
    fn joint_init(l: &mut Lower<'_, Self>, target: &Expr, value: &Expr, whole: &Expr) -> bool;
    /// The files the scene read (robot descriptions).
    fn files(&self) -> Vec<std::path::PathBuf>;
    /// Whether the scene is in space (a `spatial_body` was declared).
    fn is_spatial(&self) -> bool;
    /// Whether it has spatial bodies.
    fn has_spatial_bodies(&self) -> bool;
    /// What the scene's coordinates are, for the model's documentation.
    fn summary(&self) -> &str;
    /// `let b = body(..);` or `let ground = ground();` (`kind`).
    fn body(
        l: &mut Lower<'_, Self>,
        ident: &syn::Ident,
        kind: &str,
        call: &syn::ExprCall,
        local: &syn::Local,
    );
    /// `let b = spatial_body(..);`
    fn spatial_body(
        l: &mut Lower<'_, Self>,
        ident: &syn::Ident,
        call: &syn::ExprCall,
        local: &syn::Local,
    );
    /// A joint statement `kind(..)`, named when written as a `let`.
    fn joint(
        l: &mut Lower<'_, Self>,
        kind: &str,
        name: Option<&syn::Ident>,
        call: &syn::ExprCall,
        e: &Expr,
    );
    /// A load statement `kind(..)`.
    fn load(l: &mut Lower<'_, Self>, kind: &str, call: &syn::ExprCall, e: &Expr);
    /// `crank.theta`: a body's coordinate.
    fn body_coordinate(l: &mut Lower<'_, Self>, f: &syn::ExprField, e: &Expr) -> Option<Id>;
    /// `orientation(b)`: a spatial body's rotation matrix, row-major.
    fn orientation(l: &mut Lower<'_, Self>, c: &syn::ExprCall, e: &Expr) -> Option<[Id; 9]>;
    /// `position(b, p)` in a planar scene: the world point, x and y.
    fn position(l: &mut Lower<'_, Self>, c: &syn::ExprCall, e: &Expr) -> Option<[Id; 2]>;
    /// `position(b, p)` in space.
    fn spatial_position(l: &mut Lower<'_, Self>, c: &syn::ExprCall, e: &Expr) -> Option<[Id; 3]>;
    /// `natural_frame(p1, p2, p3)`: the frame of three points, row-major.
    fn natural_frame(
        g: &mut Graph,
        p1: [Id; 3],
        p2: [Id; 3],
        p3: [Id; 3],
    ) -> crate::Result<[Id; 9]>;
    /// The kind of the named joint `name` as its flange sees it:
    /// `"revolute"` (a rotational flange on its angle) or `"prismatic"` (a
    /// translational one along its axis); `None` for another joint or none.
    fn joint_axis(l: &Lower<'_, Self>, name: &str) -> Option<&'static str>;
    /// The named joint's relative coordinate (the angle of the second body
    /// from the first, or the displacement along the axis), with the loads
    /// that make `flow` (a torque or a force) act across the joint: on the
    /// second body, its reaction on the first. `None` once reported.
    fn joint_flange(l: &mut Lower<'_, Self>, name: &str, flow: Id, at: &Expr) -> Option<Id>;
    /// The scene's equations of motion, after the last statement.
    fn equations(l: &mut Lower<'_, Self>, item: &syn::ItemFn);
}
