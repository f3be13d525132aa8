//! Vectors and 3 × 3 matrices in the model language (course notes §4.1),
//! expanded into scalar expressions as they are lowered: `vec3`, `mat3`,
//! `identity3`, `rot_x`/`rot_y`/`rot_z` (eq. 4.9), `euler_313` (eq. 4.10),
//! `bryan_123` (eq. 4.11), `axis_angle` (Rodrigues, eq. 4.18),
//! `quat_to_rot` (eq. 4.19), `skew` (eq. 4.17), `cross`, `dot`, `norm`,
//! `transpose`, any axis sequence `rot_seq("zxz", a, b, c)` and its inverse
//! (eq. 4.12), body angular velocities from angle or quaternion states
//! (`omega_seq`, `omega_quat`, §4.1.4),
//! 4 × 4 transforms `transform(r, p)` (eq. 4.7), `inverse_transform` (4.8)
//! and points `homogeneous(p)`, the planar frame of two points in natural
//! coordinates `planar_frame(p1, p2)` and the spatial frame of three points
//! `natural_frame(p1, p2, p3)` (§4.1.5), a spatial body's `orientation(b)`,
//! `+ − *` (scalar, matrix–vector, matrix–matrix) and `/` by a
//! scalar, indexing `p[0]`, `r[1][2]`; an equation or a constraint between
//! vectors stands for one per component.

use crate::front::lower::{Binding, Lower, SceneLanguage};
use crate::front::tensor::{transposed, Tensor, TENSOR_FUNCTIONS, VECTOR_SCALARS};
use crate::Id;
use quote::ToTokens;
use syn::{BinOp, Expr, UnOp};

impl<S: SceneLanguage> Lower<'_, S> {
    /// Whether `e` involves a vector or a matrix (a tensor function or a
    /// name bound to one): such expressions are lowered by [`Lower::tensor`].
    pub(in crate::front) fn mentions_tensor(&self, e: &Expr) -> bool {
        match e {
            Expr::Paren(p) => self.mentions_tensor(&p.expr),
            Expr::Group(g) => self.mentions_tensor(&g.expr),
            Expr::Unary(u) => self.mentions_tensor(&u.expr),
            Expr::Binary(b) => self.mentions_tensor(&b.left) || self.mentions_tensor(&b.right),
            Expr::Index(ix) => self.mentions_tensor(&ix.expr),
            Expr::MethodCall(m) => self.mentions_tensor(&m.receiver),
            Expr::Path(p) => p
                .path
                .get_ident()
                .and_then(|i| self.lookup(&i.to_string()))
                .is_some_and(|b| matches!(b, Binding::Tensor(_))),
            Expr::Call(c) => {
                let name = match &*c.func {
                    Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                    _ => None,
                };
                name.is_some_and(|n| {
                    TENSOR_FUNCTIONS.contains(&n.as_str()) || VECTOR_SCALARS.contains(&n.as_str())
                }) || c.args.iter().any(|a| self.mentions_tensor(a))
            }
            _ => false,
        }
    }

    /// A value that may be a vector or a matrix; scalars as 1 × 1.
    pub(crate) fn tensor(&mut self, e: &Expr) -> Option<Tensor> {
        match e {
            Expr::Paren(p) => self.tensor(&p.expr),
            Expr::Group(g) => self.tensor(&g.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                let t = self.tensor(&u.expr)?;
                let data = t.data.iter().map(|&x| self.g.neg(x)).collect::<Result<Vec<_>, _>>();
                let data = self.graph_result_all(data, e)?;
                Some(Tensor { data, ..t })
            }
            Expr::Binary(b)
                if matches!(
                    b.op,
                    BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Div(_)
                ) =>
            {
                let (l, r) = (self.tensor(&b.left), self.tensor(&b.right));
                self.combine(&b.op, l?, r?, e)
            }
            Expr::Path(p) => {
                let bound = p.path.get_ident().and_then(|i| self.lookup(&i.to_string()).cloned());
                match bound {
                    Some(Binding::Tensor(t)) => Some(t),
                    _ => self.value(e).map(Tensor::scalar),
                }
            }
            Expr::Index(ix) if self.mentions_tensor(&ix.expr) => {
                let base = self.tensor(&ix.expr)?;
                let i = self.index_constant(&ix.index)?;
                let bound =
                    if base.cols == 1 || base.rows == 1 { base.data.len() } else { base.rows };
                if i >= bound {
                    self.cx.error_at(
                        &ix.index,
                        format!(
                            "index {i} is out of bounds: `{}` is a {}",
                            ix.expr.to_token_stream(),
                            base.shape()
                        ),
                    );
                    return None;
                }
                if base.cols == 1 || base.rows == 1 {
                    Some(Tensor::scalar(base.data[i]))
                } else {
                    let row = base.data[i * base.cols..(i + 1) * base.cols].to_vec();
                    Some(Tensor::vector(row))
                }
            }
            Expr::Call(c) => {
                let name = match &*c.func {
                    Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                    _ => None,
                };
                match name {
                    Some(n)
                        if TENSOR_FUNCTIONS.contains(&n.as_str())
                            || VECTOR_SCALARS.contains(&n.as_str()) =>
                    {
                        self.tensor_call(c, &n, e)
                    }
                    _ => self.value(e).map(Tensor::scalar),
                }
            }
            _ => self.value(e).map(Tensor::scalar),
        }
    }

    /// `e` as a scalar, with a message when it is a vector or a matrix.
    pub(in crate::front) fn scalar_of(&mut self, e: &Expr) -> Option<Id> {
        let t = self.tensor(e)?;
        match t.as_scalar() {
            Some(id) => Some(id),
            None => {
                let shape = t.shape();
                self.cx.error_at(e, format!("`{}` is a {shape} where a number is needed: take a component (`v[0]`, `m[1][2]`) or use `dot`/`norm`", e.to_token_stream()));
                None
            }
        }
    }

    fn graph_result_all(&mut self, r: crate::Result<Vec<Id>>, at: &Expr) -> Option<Vec<Id>> {
        match r {
            Ok(v) => Some(v),
            Err(err) => {
                self.cx.error_at(at, err);
                None
            }
        }
    }

    fn combine(&mut self, op: &BinOp, a: Tensor, b: Tensor, e: &Expr) -> Option<Tensor> {
        if let (Some(x), Some(y)) = (a.as_scalar(), b.as_scalar()) {
            return self.arith(op, x, y, e).map(Tensor::scalar);
        }
        let mismatch = |this: &mut Self, what: &str| {
            this.cx.error_at(e, format!("cannot {what} a {} and a {}", a.shape(), b.shape()));
            None
        };
        match op {
            BinOp::Add(_) | BinOp::Sub(_) => {
                if (a.rows, a.cols) != (b.rows, b.cols) {
                    return mismatch(
                        self,
                        if matches!(op, BinOp::Add(_)) { "add" } else { "subtract" },
                    );
                }
                let mut data = Vec::with_capacity(a.data.len());
                for (&x, &y) in a.data.iter().zip(&b.data) {
                    data.push(self.arith(op, x, y, e)?);
                }
                Some(Tensor { data, ..a })
            }
            BinOp::Mul(_) => match (a.as_scalar(), b.as_scalar()) {
                (Some(s), None) => self.scale(&b, s, e),
                (None, Some(s)) => self.scale(&a, s, e),
                _ if a.cols == b.rows => self.product(&a, &b, e),
                _ if a.cols == 1 && b.cols == 1 => {
                    self.cx.error_at(
                        e,
                        format!(
                            "cannot multiply a {} and a {}: use `dot(a, b)` or `cross(a, b)`",
                            a.shape(),
                            b.shape()
                        ),
                    );
                    None
                }
                _ => mismatch(self, "multiply"),
            },
            BinOp::Div(_) => match b.as_scalar() {
                Some(s) => {
                    let mut data = Vec::with_capacity(a.data.len());
                    for &x in &a.data {
                        data.push(self.arith(op, x, s, e)?);
                    }
                    Some(Tensor { data, ..a })
                }
                None => mismatch(self, "divide"),
            },
            _ => mismatch(self, "combine"),
        }
    }

    fn scale(&mut self, t: &Tensor, s: Id, e: &Expr) -> Option<Tensor> {
        let data = t.data.iter().map(|&x| self.g.mul(s, x)).collect::<Result<Vec<_>, _>>();
        let data = self.graph_result_all(data, e)?;
        Some(Tensor::matrix(t.rows, t.cols, data))
    }

    fn product(&mut self, a: &Tensor, b: &Tensor, e: &Expr) -> Option<Tensor> {
        let mut data = Vec::with_capacity(a.rows * b.cols);
        for r in 0..a.rows {
            for c in 0..b.cols {
                let terms = (0..a.cols)
                    .map(|k| self.g.mul(a.at(r, k), b.at(k, c)))
                    .collect::<Result<Vec<_>, _>>();
                let terms = self.graph_result_all(terms, e)?;
                let sum = self.g.sum(&terms);
                data.push(self.graph_result(sum, e)?);
            }
        }
        Some(Tensor::matrix(a.rows, b.cols, data))
    }

    /// The arguments of a tensor function: `shapes[k]` is 1 for a scalar
    /// argument, 3 for a 3-vector.
    fn tensor_args(
        &mut self,
        c: &syn::ExprCall,
        name: &str,
        shapes: &[usize],
    ) -> Option<Vec<Tensor>> {
        if c.args.len() != shapes.len() {
            let what: Vec<&str> =
                shapes.iter().map(|&s| if s == 1 { "a number" } else { "a 3-vector" }).collect();
            self.cx.error_at(
                c,
                format!("`{name}` takes {} argument(s): {}", shapes.len(), what.join(", ")),
            );
            return None;
        }
        let mut out = Vec::with_capacity(shapes.len());
        for (arg, &n) in c.args.iter().zip(shapes) {
            let t = self.tensor(arg)?;
            if (t.rows, t.cols) != (n, 1) {
                let want = if n == 1 { "a number".to_string() } else { format!("a {n}-vector") };
                self.cx.error_at(arg, format!("`{name}` needs {want} here, not a {}", t.shape()));
                return None;
            }
            out.push(t);
        }
        Some(out)
    }

    fn tensor_call(&mut self, c: &syn::ExprCall, name: &str, e: &Expr) -> Option<Tensor> {
        // One match arm per vector function of the language: long because the language is, each
        // arm short.
        let g = |this: &mut Self, r: crate::Result<Id>| this.graph_result(r, e);
        let zero = self.g.zero();
        let one = self.g.one();
        match name {
            "orientation" => {
                if !self.scene.is_spatial() {
                    self.cx.error_at(c, "`orientation` is the rotation matrix of a `spatial_body`; in a planar scene use `rot_z(body.theta)`");
                    return None;
                }
                let r = S::orientation(self, c, e)?;
                Some(Tensor::matrix(3, 3, r.to_vec()))
            }
            "natural_frame" => {
                let a = self.tensor_args(c, name, &[3, 3, 3])?;
                let p = |k: usize| [a[k].data[0], a[k].data[1], a[k].data[2]];
                let r = S::natural_frame(&mut self.g, p(0), p(1), p(2));
                let r = self.graph_result_all(r.map(|m| m.to_vec()), e)?;
                Some(Tensor::matrix(3, 3, r))
            }
            "position" if self.scene.has_spatial_bodies() && c.args.len() == 2 => {
                let p = S::spatial_position(self, c, e)?;
                Some(Tensor::vector(p.to_vec()))
            }
            "position" => {
                let [x, y] = S::position(self, c, e)?;
                Some(Tensor::vector(vec![x, y, zero]))
            }
            "rot_seq" | "inverse_rot_seq" | "omega_seq" => {
                let (axes, angles) = self.sequence_args(c, name)?;
                let rotations = axes
                    .iter()
                    .zip(&angles)
                    .map(|(&axis, &a)| self.primitive(["rot_x", "rot_y", "rot_z"][axis], a, e))
                    .collect::<Option<Vec<Tensor>>>()?;
                match name {
                    "rot_seq" | "inverse_rot_seq" => {
                        let first = self.product(&rotations[0], &rotations[1], e)?;
                        let r = self.product(&first, &rotations[2], e)?;
                        Some(if name == "rot_seq" { r } else { transposed(&r) })
                    }
                    _ => {
                        // ω = R_kᵀ R_jᵀ e_i ȧ + R_kᵀ e_j ḃ + e_k ċ (body axes).
                        let rates = c
                            .args
                            .iter()
                            .skip(1)
                            .map(|a| self.rate_of(a, name))
                            .collect::<Option<Vec<Id>>>()?;
                        let unit = |axis: usize, rate: Id| {
                            let mut data = vec![zero; 3];
                            data[axis] = rate;
                            Tensor::vector(data)
                        };
                        let (rk, rj) = (transposed(&rotations[2]), transposed(&rotations[1]));
                        let rkj = self.product(&rk, &rj, e)?;
                        let first = self.product(&rkj, &unit(axes[0], rates[0]), e)?;
                        let second = self.product(&rk, &unit(axes[1], rates[1]), e)?;
                        let plus = BinOp::Add(Default::default());
                        let sum = self.combine(&plus, first, second, e)?;
                        self.combine(&plus, sum, unit(axes[2], rates[2]), e)
                    }
                }
            }
            "transform" | "inverse_transform" => {
                if c.args.len() != 2 {
                    self.cx.error_at(
                        c,
                        format!("`{name}` takes a 3×3 rotation and a 3-vector: `{name}(r, p)`"),
                    );
                    return None;
                }
                let r = self.tensor(&c.args[0])?;
                let p = self.tensor(&c.args[1])?;
                if (r.rows, r.cols, p.rows, p.cols) != (3, 3, 3, 1) {
                    self.cx.error_at(
                        c,
                        format!(
                            "`{name}` takes a 3×3 rotation and a 3-vector, not a {} and a {}",
                            r.shape(),
                            p.shape()
                        ),
                    );
                    return None;
                }
                // [R p; 0 1], or its inverse [Rᵀ −Rᵀp; 0 1].
                let (r, p) = if name == "transform" {
                    (r, p)
                } else {
                    let rt = transposed(&r);
                    let rtp = self.product(&rt, &p, e)?;
                    let minus = self.g.int(-1);
                    let neg = self.scale(&rtp, minus, e)?;
                    (rt, neg)
                };
                let mut data = Vec::with_capacity(16);
                for row in 0..3 {
                    data.extend_from_slice(&r.data[row * 3..row * 3 + 3]);
                    data.push(p.data[row]);
                }
                data.extend_from_slice(&[zero, zero, zero, one]);
                Some(Tensor::matrix(4, 4, data))
            }
            "homogeneous" => {
                let a = self.tensor_args(c, name, &[3])?;
                let mut data = a[0].data.clone();
                data.push(one);
                Some(Tensor::vector(data))
            }
            "planar_frame" => {
                // The body frame with origin P1 and x axis along P1P2
                // (natural coordinates, §4.1.5): [d −d⊥ 0; …] / L.
                let a = self.tensor_args(c, name, &[3, 3])?;
                let minus = BinOp::Sub(Default::default());
                let d = self.combine(&minus, a[1].clone(), a[0].clone(), e)?;
                let t = Tensor::matrix(1, 3, d.data.clone());
                let dd = self.product(&t, &d, e)?;
                let len = self.g.sqrt(dd.data[0]);
                let len = g(self, len)?;
                let cos = self.g.div(d.data[0], len);
                let cos = g(self, cos)?;
                let sin = self.g.div(d.data[1], len);
                let sin = g(self, sin)?;
                let msin = self.g.neg(sin);
                let msin = g(self, msin)?;
                Some(Tensor::matrix(3, 3, vec![cos, msin, zero, sin, cos, zero, zero, zero, one]))
            }
            "omega_quat" => {
                // ω = 2 (q0 q̇v − q̇0 qv − qv × q̇v) in body axes.
                let a = self.tensor_args(c, name, &[1, 1, 1, 1])?;
                let q: Vec<Id> = a.iter().map(|t| t.data[0]).collect();
                let rates =
                    c.args.iter().map(|a| self.rate_of(a, name)).collect::<Option<Vec<Id>>>()?;
                let qv = Tensor::vector(q[1..].to_vec());
                let dv = Tensor::vector(rates[1..].to_vec());
                let a1 = self.scale(&dv, q[0], e)?;
                let a2 = self.scale(&qv, rates[0], e)?;
                let s = self.skew(&qv, e)?;
                let a3 = self.product(&s, &dv, e)?;
                let minus = BinOp::Sub(Default::default());
                let d = self.combine(&minus, a1, a2, e)?;
                let d = self.combine(&minus, d, a3, e)?;
                let two = self.g.int(2);
                self.scale(&d, two, e)
            }
            "vec3" => {
                let a = self.tensor_args(c, name, &[1, 1, 1])?;
                Some(Tensor::vector(a.iter().map(|t| t.data[0]).collect()))
            }
            "mat3" => {
                let a = self.tensor_args(c, name, &[1; 9])?;
                Some(Tensor::matrix(3, 3, a.iter().map(|t| t.data[0]).collect()))
            }
            "identity3" => {
                self.tensor_args(c, name, &[])?;
                Some(Tensor::matrix(3, 3, vec![one, zero, zero, zero, one, zero, zero, zero, one]))
            }
            "rot_x" | "rot_y" | "rot_z" => {
                let a = self.tensor_args(c, name, &[1])?;
                self.primitive(name, a[0].data[0], e)
            }
            // R = R_{axis₃}(a₃) R_{axis₂}(a₂) R_{axis₁}(a₁).
            "euler_313" | "bryan_123" => {
                let a = self.tensor_args(c, name, &[1, 1, 1])?;
                let axes = if name == "euler_313" {
                    ["rot_z", "rot_x", "rot_z"]
                } else {
                    ["rot_x", "rot_y", "rot_z"]
                };
                let r = self.primitive(axes[2], a[2].data[0], e)?;
                let m = self.primitive(axes[1], a[1].data[0], e)?;
                let l = self.primitive(axes[0], a[0].data[0], e)?;
                let rm = self.product(&r, &m, e)?;
                self.product(&rm, &l, e)
            }
            "skew" => {
                let a = self.tensor_args(c, name, &[3])?;
                self.skew(&a[0], e)
            }
            "cross" => {
                let a = self.tensor_args(c, name, &[3, 3])?;
                let s = self.skew(&a[0], e)?;
                self.product(&s, &a[1], e)
            }
            "dot" => {
                let a = self.tensor_args(c, name, &[3, 3])?;
                let t = Tensor::matrix(1, 3, a[0].data.clone());
                self.product(&t, &a[1], e)
            }
            "norm" => {
                let a = self.tensor_args(c, name, &[3])?;
                let t = Tensor::matrix(1, 3, a[0].data.clone());
                let d = self.product(&t, &a[0], e)?;
                let r = self.g.sqrt(d.data[0]);
                g(self, r).map(Tensor::scalar)
            }
            "transpose" => {
                if c.args.len() != 1 {
                    self.cx.error_at(c, "`transpose` takes one matrix or vector");
                    return None;
                }
                let t = self.tensor(&c.args[0])?;
                let mut data = Vec::with_capacity(t.data.len());
                for col in 0..t.cols {
                    for row in 0..t.rows {
                        data.push(t.at(row, col));
                    }
                }
                Some(Tensor::matrix(t.cols, t.rows, data))
            }
            "axis_angle" => {
                // Rodrigues (eq. 4.18) with the axis normalised:
                // I + sin θ N + (1 − cos θ) N², N = skew(n / |n|).
                let a = self.tensor_args(c, name, &[3, 1])?;
                let n = &a[0];
                let theta = a[1].data[0];
                let t = Tensor::matrix(1, 3, n.data.clone());
                let nn = self.product(&t, n, e)?;
                let len = self.g.sqrt(nn.data[0]);
                let len = g(self, len)?;
                let unit = {
                    let data =
                        n.data.iter().map(|&x| self.g.div(x, len)).collect::<Result<Vec<_>, _>>();
                    Tensor::vector(self.graph_result_all(data, e)?)
                };
                let big_n = self.skew(&unit, e)?;
                let n2 = self.product(&big_n, &big_n, e)?;
                let sin = self.g.call(crate::Func::Sin, theta);
                let sin = g(self, sin)?;
                let cos = self.g.call(crate::Func::Cos, theta);
                let cos = g(self, cos)?;
                let one_minus = self.g.sub(one, cos);
                let one_minus = g(self, one_minus)?;
                let identity =
                    Tensor::matrix(3, 3, vec![one, zero, zero, zero, one, zero, zero, zero, one]);
                let s_n = self.scale(&big_n, sin, e)?;
                let c_n2 = self.scale(&n2, one_minus, e)?;
                let plus = BinOp::Add(Default::default());
                let first = self.combine(&plus, identity, s_n, e)?;
                self.combine(&plus, first, c_n2, e)
            }
            "quat_to_rot" => {
                // Eq. 4.19 for a unit quaternion (q0 = cos(θ/2)).
                let a = self.tensor_args(c, name, &[1, 1, 1, 1])?;
                let [q0, q1, q2, q3] = [a[0].data[0], a[1].data[0], a[2].data[0], a[3].data[0]];
                let entry =
                    |this: &mut Self, terms: &[(Id, Id, i64)], constant: i64| -> Option<Id> {
                        let mut parts = Vec::new();
                        for &(x, y, sign) in terms {
                            let p = this.g.mul(x, y);
                            let p = this.graph_result(p, e)?;
                            let k = this.g.int(2 * sign);
                            let p = this.g.mul(k, p);
                            parts.push(this.graph_result(p, e)?);
                        }
                        parts.push(this.g.int(constant));
                        let s = this.g.sum(&parts);
                        this.graph_result(s, e)
                    };
                let data = vec![
                    entry(self, &[(q0, q0, 1), (q1, q1, 1)], -1)?,
                    entry(self, &[(q1, q2, 1), (q0, q3, -1)], 0)?,
                    entry(self, &[(q0, q2, 1), (q1, q3, 1)], 0)?,
                    entry(self, &[(q0, q3, 1), (q1, q2, 1)], 0)?,
                    entry(self, &[(q0, q0, 1), (q2, q2, 1)], -1)?,
                    entry(self, &[(q2, q3, 1), (q0, q1, -1)], 0)?,
                    entry(self, &[(q1, q3, 1), (q0, q2, -1)], 0)?,
                    entry(self, &[(q0, q1, 1), (q2, q3, 1)], 0)?,
                    entry(self, &[(q1, q1, -1), (q2, q2, -1)], 1)?,
                ];
                Some(Tensor::matrix(3, 3, data))
            }
            _ => None,
        }
    }

    /// `"zxz", a, b, c`: the axes (0, 1, 2 for x, y, z) and the angles.
    fn sequence_args(&mut self, c: &syn::ExprCall, name: &str) -> Option<(Vec<usize>, Vec<Id>)> {
        let usage = format!("`{name}` takes the axes as a string and three angles: `{name}(\"zxz\", psi, theta, phi)`");
        if c.args.len() != 4 {
            self.cx.error_at(c, usage);
            return None;
        }
        let axes: Option<Vec<usize>> = match &c.args[0] {
            Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }) => {
                let text = s.value();
                let axes: Option<Vec<usize>> = text
                    .chars()
                    .map(|ch| match ch {
                        'x' | 'X' | '1' => Some(0),
                        'y' | 'Y' | '2' => Some(1),
                        'z' | 'Z' | '3' => Some(2),
                        _ => None,
                    })
                    .collect();
                axes.filter(|a| a.len() == 3 && a[0] != a[1] && a[1] != a[2])
            }
            _ => None,
        };
        let Some(axes) = axes else {
            self.cx.error_at(
                &c.args[0],
                format!(
                    "{usage}; the axes are three of x, y, z (or 1, 2, 3), no two consecutive equal"
                ),
            );
            return None;
        };
        let mut angles = Vec::with_capacity(3);
        for arg in c.args.iter().skip(1) {
            angles.push(self.scalar_of(arg)?);
        }
        Some((axes, angles))
    }

    /// `der(a)` of an angle or quaternion component that is a state.
    fn rate_of(&mut self, a: &Expr, name: &str) -> Option<Id> {
        let v = self.value(a)?;
        let symbol = self.g.as_symbol(v).filter(|&s| {
            matches!(
                self.g.symbol(s).kind,
                crate::SymbolKind::State | crate::SymbolKind::Derivative { .. }
            )
        });
        match symbol {
            Some(s) => {
                let r = self.g.derivative(s, 1);
                self.graph_result(r, a)
            }
            None => {
                self.cx.error_at(
                    a,
                    format!(
                        "`{name}` takes states (their rates are their `der`), and `{}` is not one",
                        a.to_token_stream()
                    ),
                );
                None
            }
        }
    }

    /// `R_x`, `R_y`, `R_z` of eq. 4.9.
    fn primitive(&mut self, name: &str, theta: Id, e: &Expr) -> Option<Tensor> {
        let (zero, one) = (self.g.zero(), self.g.one());
        let s = self.g.call(crate::Func::Sin, theta);
        let s = self.graph_result(s, e)?;
        let c = self.g.call(crate::Func::Cos, theta);
        let c = self.graph_result(c, e)?;
        let ms = self.g.neg(s);
        let ms = self.graph_result(ms, e)?;
        let data = match name {
            "rot_x" => vec![one, zero, zero, zero, c, ms, zero, s, c],
            "rot_y" => vec![c, zero, s, zero, one, zero, ms, zero, c],
            _ => vec![c, ms, zero, s, c, zero, zero, zero, one],
        };
        Some(Tensor::matrix(3, 3, data))
    }

    /// The cross-product matrix of eq. 4.17.
    fn skew(&mut self, w: &Tensor, e: &Expr) -> Option<Tensor> {
        let zero = self.g.zero();
        let negs = w.data.iter().map(|&x| self.g.neg(x)).collect::<Result<Vec<_>, _>>();
        let n = self.graph_result_all(negs, e)?;
        let (x, y, z) = (w.data[0], w.data[1], w.data[2]);
        Some(Tensor::matrix(3, 3, vec![zero, n[2], y, z, zero, n[0], n[1], x, zero]))
    }
}
