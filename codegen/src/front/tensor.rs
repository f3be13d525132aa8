//! A vector or matrix value of the model language, and which calls make
//! one: what lowering reads vector expressions into (`vectors.rs` expands
//! them).

use crate::Id;
use syn::Expr;

/// A value of the model language: a scalar (1 × 1), a column vector
/// (n × 1) or a matrix, row-major.
#[derive(Clone, Debug)]
pub(crate) struct Tensor {
    pub rows: usize,
    pub cols: usize,
    pub data: Vec<Id>,
}

impl Tensor {
    pub(crate) fn scalar(id: Id) -> Tensor {
        Tensor { rows: 1, cols: 1, data: vec![id] }
    }

    pub(crate) fn from_vector(data: Vec<Id>) -> Tensor {
        Tensor::vector(data)
    }

    pub(crate) fn vector(data: Vec<Id>) -> Tensor {
        Tensor { rows: data.len(), cols: 1, data }
    }

    pub(crate) fn matrix(rows: usize, cols: usize, data: Vec<Id>) -> Tensor {
        Tensor { rows, cols, data }
    }

    pub(crate) fn as_scalar(&self) -> Option<Id> {
        (self.rows == 1 && self.cols == 1).then(|| self.data[0])
    }

    pub(crate) fn at(&self, r: usize, c: usize) -> Id {
        self.data[r * self.cols + c]
    }

    /// `3-vector`, `3×3 matrix`, for messages.
    pub(crate) fn shape(&self) -> String {
        match (self.rows, self.cols) {
            (1, 1) => "scalar".into(),
            (n, 1) => format!("{n}-vector"),
            (r, c) => format!("{r}×{c} matrix"),
        }
    }
}

/// Functions whose value is a vector or a matrix.
pub(crate) const TENSOR_FUNCTIONS: [&str; 24] = [
    "position",
    "orientation",
    "natural_frame",
    "transform",
    "inverse_transform",
    "homogeneous",
    "planar_frame",
    "rot_seq",
    "inverse_rot_seq",
    "omega_seq",
    "omega_quat",
    "vec3",
    "mat3",
    "identity3",
    "rot_x",
    "rot_y",
    "rot_z",
    "euler_313",
    "bryan_123",
    "axis_angle",
    "quat_to_rot",
    "skew",
    "cross",
    "transpose",
];

/// Whether `e` calls a function of this module (whose value may be a vector
/// or a matrix, or a scalar of vectors).
pub(crate) fn is_tensor_call(e: &Expr) -> bool {
    match e {
        Expr::Call(c) => match &*c.func {
            Expr::Path(p) => p.path.get_ident().is_some_and(|i| {
                let n = i.to_string();
                TENSOR_FUNCTIONS.contains(&n.as_str()) || VECTOR_SCALARS.contains(&n.as_str())
            }),
            _ => false,
        },
        _ => false,
    }
}

/// Functions of vectors whose value is a scalar.
pub(crate) const VECTOR_SCALARS: [&str; 2] = ["dot", "norm"];

pub(crate) fn transposed(t: &Tensor) -> Tensor {
    let mut data = Vec::with_capacity(t.data.len());
    for col in 0..t.cols {
        for row in 0..t.rows {
            data.push(t.at(row, col));
        }
    }
    Tensor::matrix(t.cols, t.rows, data)
}
