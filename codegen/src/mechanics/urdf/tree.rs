//! A URDF robot as a kinematic tree of bodies: one body per moving joint
//! (its child link's frame is the body's), every link welded to it by
//! fixed joints merged in, their masses, centres and inertias combined
//! (parallel-axis theorem); the links welded to the root link form the
//! root. The checks a tree needs: every link named once, every joint's
//! links present, one parent per link, one root, no loop, and no moving
//! joint that carries no mass at all (its coordinate would have no
//! inertia).

use super::parse::{Inertial, JointKind, Robot};
use super::{mat_mul, transpose, Frame, UrdfError};
use std::collections::HashMap;

/// Mass, centre of mass and inertia about it, in one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass.
    pub com: [f64; 3],
    /// Inertia tensor about the centre of mass.
    pub inertia: [[f64; 3]; 3],
}

impl MassProperties {
    /// Nothing.
    pub const ZERO: MassProperties =
        MassProperties { mass: 0.0, com: [0.0; 3], inertia: [[0.0; 3]; 3] };

    /// A link's inertial expressed in `frame` (the link's frame in the
    /// body's).
    fn of(inertial: &Inertial, frame: &Frame) -> MassProperties {
        let at = frame.then(&inertial.origin.frame());
        let r = at.rotation;
        MassProperties {
            mass: inertial.mass,
            com: at.translation,
            inertia: mat_mul(&mat_mul(&r, &inertial.inertia), &transpose(&r)),
        }
    }

    /// The two together: the combined centre of mass, each inertia moved
    /// to it by the parallel-axis theorem.
    fn plus(&self, other: &MassProperties) -> MassProperties {
        let mass = self.mass + other.mass;
        if mass == 0.0 {
            return MassProperties::ZERO;
        }
        let com = [0, 1, 2].map(|i| (self.mass * self.com[i] + other.mass * other.com[i]) / mass);
        let mut inertia = [[0.0; 3]; 3];
        for part in [self, other] {
            let d = [0, 1, 2].map(|i| part.com[i] - com[i]);
            let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            for i in 0..3 {
                for j in 0..3 {
                    let shift = part.mass * (if i == j { dd } else { 0.0 } - d[i] * d[j]);
                    inertia[i][j] += part.inertia[i][j] + shift;
                }
            }
        }
        MassProperties { mass, com, inertia }
    }
}

/// A moving joint of the tree.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeJoint {
    /// Its name in the file.
    pub name: String,
    /// Its line in the file.
    pub line: u32,
    /// Its type (not `Fixed`).
    pub kind: JointKind,
    /// The body's frame in its parent body's frame at zero motion: the
    /// joint's origin after the fixed joints between the two bodies.
    pub placement: Frame,
    /// The axis in the body's frame (unit length).
    pub axis: [f64; 3],
    /// `<limit lower upper>`.
    pub limits: Option<(f64, f64)>,
    /// Viscous damping.
    pub damping: f64,
    /// Friction (kept as given).
    pub friction: f64,
}

/// A body of the tree: a moving joint's child link and the links welded
/// to it.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeBody {
    /// The child link of its joint, whose frame is the body's.
    pub link: String,
    /// Its parent body (an index into [`Tree::bodies`], before it), or
    /// `None` for the root.
    pub parent: Option<usize>,
    /// The joint that moves it.
    pub joint: TreeJoint,
    /// Its mass properties in its frame, welded links included.
    pub mass: MassProperties,
    /// Each link welded to it, with its frame in the body's (the body's
    /// own link first, at the identity).
    pub links: Vec<(String, Frame)>,
}

/// A URDF robot as a tree of bodies, parents before children.
#[derive(Clone, Debug, PartialEq)]
pub struct Tree {
    /// `<robot name>`.
    pub robot: String,
    /// The root link and the links welded to it, with their frames in the
    /// root link's.
    pub root_links: Vec<(String, Frame)>,
    /// The root's mass properties (what a floating base carries; a fixed
    /// base's is dropped).
    pub root_mass: MassProperties,
    /// The bodies.
    pub bodies: Vec<TreeBody>,
}

/// The kinematic tree of `robot`, or every reason it is not one.
pub fn tree(robot: &Robot) -> Result<Tree, Vec<UrdfError>> {
    let mut errors = Vec::new();
    let mut link_index: HashMap<&str, usize> = HashMap::new();
    for (k, link) in robot.links.iter().enumerate() {
        if let Some(&first) = link_index.get(link.name.as_str()) {
            errors.push(UrdfError {
                line: link.line,
                message: format!(
                    "a second link named `{}` (the first is on line {}): give each link its own name",
                    link.name, robot.links[first].line
                ),
            });
        } else {
            link_index.insert(&link.name, k);
        }
    }
    // The joint that makes each link a child.
    let mut parent_joint: Vec<Option<usize>> = vec![None; robot.links.len()];
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); robot.links.len()];
    for (j, joint) in robot.joints.iter().enumerate() {
        let mut find = |name: &str, role: &str| match link_index.get(name) {
            Some(&k) => Some(k),
            None => {
                errors.push(UrdfError {
                    line: joint.line,
                    message: format!(
                        "joint `{}` names the {role} link `{name}`, which the file does not have",
                        joint.name
                    ),
                });
                None
            }
        };
        let (Some(parent), Some(child)) =
            (find(&joint.parent, "parent"), find(&joint.child, "child"))
        else {
            continue;
        };
        if let Some(other) = parent_joint[child] {
            let first = &robot.joints[other];
            errors.push(UrdfError {
                line: joint.line,
                message: format!(
                    "link `{}` is the child of joint `{}` (line {}) and of joint `{}`: a URDF is a tree, each link with one parent; close a loop with a constraint in the model instead",
                    joint.child, first.name, first.line, joint.name
                ),
            });
            continue;
        }
        parent_joint[child] = Some(j);
        children[parent].push(j);
    }
    // Each link's joints by name, as urdfdom keeps them (a map by name) and
    // so Pinocchio numbers them: the coordinates come in Pinocchio's order.
    for list in &mut children {
        list.sort_by(|&a, &b| robot.joints[a].name.as_bytes().cmp(robot.joints[b].name.as_bytes()));
    }
    let roots: Vec<usize> = (0..robot.links.len()).filter(|&k| parent_joint[k].is_none()).collect();
    match roots.as_slice() {
        [_] => {}
        [] if !robot.links.is_empty() => errors.push(UrdfError {
            line: robot.joints.first().map_or(1, |j| j.line),
            message: "every link has a parent: the joints form a loop, and a URDF is a tree".into(),
        }),
        [] => errors.push(UrdfError { line: 1, message: "the file has no links".into() }),
        many => {
            let names: Vec<String> = many
                .iter()
                .map(|&k| format!("`{}` (line {})", robot.links[k].name, robot.links[k].line))
                .collect();
            errors.push(UrdfError {
                line: robot.links[many[1]].line,
                message: format!(
                    "links {} have no parent joint: a URDF is one tree with one root link",
                    names.join(", ")
                ),
            });
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let root = roots[0];
    let mut walk = Walk {
        robot,
        link_index: &link_index,
        children: &children,
        bodies: Vec::new(),
        root_links: vec![(robot.links[root].name.clone(), Frame::IDENTITY)],
        root_mass: mass_of(robot, root, &Frame::IDENTITY),
    };
    walk.visit(root, None, Frame::IDENTITY);
    let Walk { bodies, root_links, root_mass, .. } = walk;
    // Links the walk never reached hang on a loop of their own.
    let reached: std::collections::HashSet<&str> = root_links
        .iter()
        .chain(bodies.iter().flat_map(|b| b.links.iter()))
        .map(|(name, _)| name.as_str())
        .collect();
    let stranded: Vec<&super::parse::Link> =
        robot.links.iter().filter(|l| !reached.contains(l.name.as_str())).collect();
    if let Some(first) = stranded.first() {
        let names: Vec<String> = stranded.iter().map(|l| format!("`{}`", l.name)).collect();
        return Err(vec![UrdfError {
            line: first.line,
            message: format!(
                "links {} are not reached from the root link `{}`: their joints form a loop, and a URDF is a tree",
                names.join(", "),
                robot.links[root].name
            ),
        }]);
    }
    // A moving joint must carry some mass: its body's or a descendant's.
    let mut carried: Vec<f64> = bodies.iter().map(|b| b.mass.mass).collect();
    for b in (0..bodies.len()).rev() {
        if let Some(p) = bodies[b].parent {
            carried[p] += carried[b];
        }
    }
    for (b, body) in bodies.iter().enumerate() {
        if carried[b] == 0.0 {
            errors.push(UrdfError {
                line: body.joint.line,
                message: format!(
                    "joint `{}` moves link `{}`, and nothing it carries has mass: give the link an <inertial> with a mass, or make the joint fixed",
                    body.joint.name, body.link
                ),
            });
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    Ok(Tree { robot: robot.name.clone(), root_links, root_mass, bodies })
}

/// The bodies made by a walk from the root, depth first, each link's
/// joints by name: the order of the coordinates.
struct Walk<'r> {
    robot: &'r Robot,
    link_index: &'r HashMap<&'r str, usize>,
    children: &'r [Vec<usize>],
    bodies: Vec<TreeBody>,
    root_links: Vec<(String, Frame)>,
    root_mass: MassProperties,
}

impl Walk<'_> {
    /// Visits the joints below `link`, which is at `frame` in `body`'s
    /// frame (`None`: the root's).
    fn visit(&mut self, link: usize, body: Option<usize>, frame: Frame) {
        for &j in &self.children[link] {
            let joint = &self.robot.joints[j];
            let child = self.link_index[joint.child.as_str()];
            let at = frame.then(&joint.origin.frame());
            if joint.kind == JointKind::Fixed {
                let extra = mass_of(self.robot, child, &at);
                let welded = (joint.child.clone(), at);
                match body {
                    None => {
                        self.root_links.push(welded);
                        self.root_mass = self.root_mass.plus(&extra);
                    }
                    Some(b) => {
                        self.bodies[b].links.push(welded);
                        self.bodies[b].mass = self.bodies[b].mass.plus(&extra);
                    }
                }
                self.visit(child, body, at);
            } else {
                self.bodies.push(TreeBody {
                    link: joint.child.clone(),
                    parent: body,
                    joint: TreeJoint {
                        name: joint.name.clone(),
                        line: joint.line,
                        kind: joint.kind,
                        placement: at,
                        axis: joint.axis,
                        limits: joint.limits,
                        damping: joint.damping,
                        friction: joint.friction,
                    },
                    mass: mass_of(self.robot, child, &Frame::IDENTITY),
                    links: vec![(joint.child.clone(), Frame::IDENTITY)],
                });
                let new = self.bodies.len() - 1;
                self.visit(child, Some(new), Frame::IDENTITY);
            }
        }
    }
}

/// Link `k`'s mass properties in the frame `frame` places it in.
fn mass_of(robot: &Robot, k: usize, frame: &Frame) -> MassProperties {
    robot.links[k].inertial.as_ref().map_or(MassProperties::ZERO, |i| MassProperties::of(i, frame))
}

/// A point of link `link`'s frame in its body's frame, and the body
/// (`None`: the root): where a link's pose is read.
pub fn locate<'t>(tree: &'t Tree, link: &str) -> Option<(Option<usize>, &'t Frame)> {
    if let Some((_, f)) = tree.root_links.iter().find(|(n, _)| n == link) {
        return Some((None, f));
    }
    tree.bodies
        .iter()
        .enumerate()
        .find_map(|(b, body)| body.links.iter().find(|(n, _)| n == link).map(|(_, f)| (Some(b), f)))
}
