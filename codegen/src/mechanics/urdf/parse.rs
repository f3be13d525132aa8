//! A URDF file read into its links and joints, as written: each link's
//! inertial (origin, mass, inertia tensor), each joint's type, parent and
//! child, origin, axis, limits and dynamics, with the line each stands on
//! for the errors. Visuals, collisions, meshes, transmissions and
//! simulator tags are skipped.

use super::{Pose, UrdfError};

/// A URDF joint type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A hinge with limits.
    Revolute,
    /// A hinge without limits.
    Continuous,
    /// A slider.
    Prismatic,
    /// A weld.
    Fixed,
    /// Six degrees of freedom.
    Floating,
    /// Motion in the plane normal to the axis.
    Planar,
}

impl JointKind {
    /// The type's name in URDF.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
            JointKind::Floating => "floating",
            JointKind::Planar => "planar",
        }
    }
}

/// A link's `<inertial>`.
#[derive(Clone, Debug, PartialEq)]
pub struct Inertial {
    /// The centre of mass and the axes of the inertia tensor, in the
    /// link's frame.
    pub origin: Pose,
    /// Mass (kg).
    pub mass: f64,
    /// The inertia tensor about the centre of mass in `origin`'s axes,
    /// row-major (ixx ixy ixz / ixy iyy iyz / ixz iyz izz).
    pub inertia: [[f64; 3]; 3],
}

/// A `<link>`.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Its name.
    pub name: String,
    /// The line of its `<link>` tag.
    pub line: u32,
    /// Its inertial, if given.
    pub inertial: Option<Inertial>,
}

/// A `<joint>`.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Its name.
    pub name: String,
    /// The line of its `<joint>` tag.
    pub line: u32,
    /// Its type.
    pub kind: JointKind,
    /// The parent link's name.
    pub parent: String,
    /// The child link's name.
    pub child: String,
    /// The child link's frame in the parent link's at zero motion.
    pub origin: Pose,
    /// The axis in the child link's frame (unit length), (1, 0, 0) if
    /// not given.
    pub axis: [f64; 3],
    /// `<limit lower upper>`, if given.
    pub limits: Option<(f64, f64)>,
    /// `<dynamics damping>` (N m s/rad or N s/m), 0 if not given.
    pub damping: f64,
    /// `<dynamics friction>`, 0 if not given.
    pub friction: f64,
}

/// A URDF file's robot.
#[derive(Clone, Debug, PartialEq)]
pub struct Robot {
    /// `<robot name>`.
    pub name: String,
    /// The links in the file's order.
    pub links: Vec<Link>,
    /// The joints in the file's order.
    pub joints: Vec<Joint>,
}

/// Reads the robot in `text`; every mistake found, each with its line.
pub fn parse(text: &str) -> Result<Robot, Vec<UrdfError>> {
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        vec![UrdfError { line: e.pos().row, message: format!("not well-formed XML: {e}") }]
    })?;
    let root = doc.root_element();
    let line = |node: roxmltree::Node<'_, '_>| doc.text_pos_at(node.range().start).row;
    let mut errors = Vec::new();
    if root.tag_name().name() != "robot" {
        errors.push(UrdfError {
            line: line(root),
            message: format!("the root element is <{}>, not <robot>", root.tag_name().name()),
        });
        return Err(errors);
    }
    let mut robot = Robot {
        name: root.attribute("name").unwrap_or("").to_string(),
        links: Vec::new(),
        joints: Vec::new(),
    };
    for node in root.children().filter(|n| n.is_element()) {
        let mut fail = |message: String| errors.push(UrdfError { line: line(node), message });
        match node.tag_name().name() {
            "link" => match read_link(node) {
                Ok(link) => robot.links.push(Link { line: line(node), ..link }),
                Err(message) => fail(message),
            },
            "joint" => match read_joint(node) {
                Ok(joint) => robot.joints.push(Joint { line: line(node), ..joint }),
                Err(message) => fail(message),
            },
            // Materials, transmissions, simulator plugins: not dynamics.
            _ => {}
        }
    }
    if errors.is_empty() {
        Ok(robot)
    } else {
        Err(errors)
    }
}

fn name_of(node: roxmltree::Node<'_, '_>, what: &str) -> Result<String, String> {
    match node.attribute("name") {
        Some(name) if !name.is_empty() => Ok(name.to_string()),
        _ => Err(format!("a <{what}> without a name")),
    }
}

fn child<'a, 'i>(node: roxmltree::Node<'a, 'i>, tag: &str) -> Option<roxmltree::Node<'a, 'i>> {
    node.children().find(|n| n.is_element() && n.tag_name().name() == tag)
}

/// The numbers of attribute `attribute` of `node` (`xyz="0 0 0.1"`).
fn numbers<const N: usize>(
    node: roxmltree::Node<'_, '_>,
    attribute: &str,
    default: [f64; N],
) -> Result<[f64; N], String> {
    let Some(text) = node.attribute(attribute) else { return Ok(default) };
    let values: Vec<&str> = text.split_whitespace().collect();
    let mut out = [0.0; N];
    if values.len() != N {
        return Err(format!(
            "{attribute}=\"{text}\" of <{}> has {} numbers; it takes {N}",
            node.tag_name().name(),
            values.len()
        ));
    }
    for (o, v) in out.iter_mut().zip(&values) {
        *o = v.parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| {
            format!(
                "{attribute}=\"{text}\" of <{}>: `{v}` is not a finite number",
                node.tag_name().name()
            )
        })?;
    }
    Ok(out)
}

fn number(node: roxmltree::Node<'_, '_>, attribute: &str, default: f64) -> Result<f64, String> {
    numbers::<1>(node, attribute, [default]).map(|[x]| x)
}

fn pose(node: roxmltree::Node<'_, '_>) -> Result<Pose, String> {
    match child(node, "origin") {
        None => Ok(Pose::IDENTITY),
        Some(o) => {
            Ok(Pose { xyz: numbers(o, "xyz", [0.0; 3])?, rpy: numbers(o, "rpy", [0.0; 3])? })
        }
    }
}

fn read_link(node: roxmltree::Node<'_, '_>) -> Result<Link, String> {
    let name = name_of(node, "link")?;
    let inertial = match child(node, "inertial") {
        None => None,
        Some(i) => {
            let origin = pose(i).map_err(|e| format!("link `{name}`: {e}"))?;
            let mass = match child(i, "mass") {
                Some(m) => {
                    number(m, "value", f64::NAN).map_err(|e| format!("link `{name}`: {e}"))?
                }
                None => return Err(format!("link `{name}`: its <inertial> has no <mass>")),
            };
            if mass.is_nan() || mass < 0.0 {
                return Err(format!("link `{name}`: its mass must be a number, zero or more"));
            }
            let t = match child(i, "inertia") {
                Some(t) => t,
                None => return Err(format!("link `{name}`: its <inertial> has no <inertia>")),
            };
            let get = |a: &str| number(t, a, 0.0).map_err(|e| format!("link `{name}`: {e}"));
            let (ixx, ixy, ixz) = (get("ixx")?, get("ixy")?, get("ixz")?);
            let (iyy, iyz, izz) = (get("iyy")?, get("iyz")?, get("izz")?);
            let inertia = [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]];
            Some(Inertial { origin, mass, inertia })
        }
    };
    Ok(Link { name, line: 0, inertial })
}

fn read_joint(node: roxmltree::Node<'_, '_>) -> Result<Joint, String> {
    let name = name_of(node, "joint")?;
    let kind = match node.attribute("type").unwrap_or("") {
        "revolute" => JointKind::Revolute,
        "continuous" => JointKind::Continuous,
        "prismatic" => JointKind::Prismatic,
        "fixed" => JointKind::Fixed,
        "floating" => JointKind::Floating,
        "planar" => JointKind::Planar,
        other => {
            return Err(format!(
                "joint `{name}` has type \"{other}\"; a URDF joint is revolute, continuous, prismatic, fixed, floating or planar"
            ))
        }
    };
    let link = |tag: &str| -> Result<String, String> {
        child(node, tag)
            .and_then(|n| n.attribute("link"))
            .filter(|l| !l.is_empty())
            .map(str::to_string)
            .ok_or_else(|| format!("joint `{name}` has no <{tag} link=\"..\"/>"))
    };
    let (parent, child_link) = (link("parent")?, link("child")?);
    let origin = pose(node).map_err(|e| format!("joint `{name}`: {e}"))?;
    let axis = match child(node, "axis") {
        None => [1.0, 0.0, 0.0],
        Some(a) => {
            numbers(a, "xyz", [1.0, 0.0, 0.0]).map_err(|e| format!("joint `{name}`: {e}"))?
        }
    };
    let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    if kind != JointKind::Fixed && kind != JointKind::Floating && norm == 0.0 {
        return Err(format!("joint `{name}` has a zero axis"));
    }
    let axis = if norm > 0.0 { axis.map(|a| a / norm) } else { axis };
    let limits = match child(node, "limit") {
        None => None,
        Some(l) => {
            let lower = number(l, "lower", 0.0).map_err(|e| format!("joint `{name}`: {e}"))?;
            let upper = number(l, "upper", 0.0).map_err(|e| format!("joint `{name}`: {e}"))?;
            Some((lower, upper))
        }
    };
    let (damping, friction) = match child(node, "dynamics") {
        None => (0.0, 0.0),
        Some(d) => (
            number(d, "damping", 0.0).map_err(|e| format!("joint `{name}`: {e}"))?,
            number(d, "friction", 0.0).map_err(|e| format!("joint `{name}`: {e}"))?,
        ),
    };
    Ok(Joint {
        name,
        line: 0,
        kind,
        parent,
        child: child_link,
        origin,
        axis,
        limits,
        damping,
        friction,
    })
}
