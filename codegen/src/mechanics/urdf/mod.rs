//! Robots from URDF files: `parse` reads a file into its links and joints
//! as written, `tree` turns them into the bodies of a kinematic tree (links
//! welded by fixed joints merged into one body, their inertias combined),
//! `statements` writes the tree as the model language's bodies and joints,
//! and `lowering` is the `urdf("path")` statement that reads the file and
//! lowers them. Conventions are
//! URDF's (and Pinocchio's): `rpy` is roll about x, pitch about y, yaw
//! about z, each about the fixed axes, R = Rz(yaw)·Ry(pitch)·Rx(roll); a
//! joint's origin places the child link's frame in the parent link's, and
//! its axis is in the child link's frame; an inertia tensor is about the
//! centre of mass, in the inertial origin's axes.

mod lowering;
pub mod parse;
pub mod statements;
pub mod tree;

/// A mistake in a URDF file, at its line.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfError {
    /// The line in the file (1-based).
    pub line: u32,
    /// What is wrong and how to fix it.
    pub message: String,
}

/// An `<origin xyz rpy>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Translation.
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw (rad), about the fixed x, y, z axes.
    pub rpy: [f64; 3],
}

impl Pose {
    /// No translation, no rotation.
    pub const IDENTITY: Pose = Pose { xyz: [0.0; 3], rpy: [0.0; 3] };

    /// The frame this pose places.
    pub fn frame(&self) -> Frame {
        let [roll, pitch, yaw] = self.rpy;
        let (sr, cr) = roll.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        let (sy, cy) = yaw.sin_cos();
        // Rz(yaw)·Ry(pitch)·Rx(roll).
        let rotation = [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ];
        Frame { rotation, translation: self.xyz }
    }
}

/// A frame in another: x_outer = rotation·x_inner + translation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The inner frame's axes in the outer one, as columns.
    pub rotation: [[f64; 3]; 3],
    /// The inner frame's origin in the outer one.
    pub translation: [f64; 3],
}

impl Frame {
    /// The frame in itself.
    pub const IDENTITY: Frame = Frame {
        rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        translation: [0.0; 3],
    };

    /// `inner` (given in this frame) in this frame's outer frame.
    pub fn then(&self, inner: &Frame) -> Frame {
        Frame {
            rotation: mat_mul(&self.rotation, &inner.rotation),
            translation: self.apply(&inner.translation),
        }
    }

    /// A point given in this frame, in the outer one.
    pub fn apply(&self, p: &[f64; 3]) -> [f64; 3] {
        add(mat_vec(&self.rotation, p), self.translation)
    }
}

pub(crate) fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

pub(crate) fn mat_vec(a: &[[f64; 3]; 3], v: &[f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

pub(crate) fn transpose(a: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[j][i]))
}

pub(crate) fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
