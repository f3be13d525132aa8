//! The block-diagonal preconditioner P = I − γ·J_blocks that CVODE's
//! GMRES takes on reaction–diffusion grids, as SUNDIALS' own cvDiurnal_kry
//! example builds it by hand: the Jacobian's entries inside each block of
//! `block` consecutive states (one grid cell's species, with the diagonal
//! of the diffusion), each block inverted once per preconditioner set-up.

/// Diagonal blocks of a Jacobian and the inverses of I − γ·(those blocks).
pub struct BlockJacobi {
    block: usize,
    /// For each pattern entry inside a block: its index in the pattern and
    /// its place in `jacobian` (block k's row-major b × b at k·b²).
    entries: Vec<(usize, usize)>,
    /// The blocks of J at the last evaluation.
    jacobian: Vec<f64>,
    /// The inverses of I − γ·J's blocks, row-major.
    inverse: Vec<f64>,
    /// One block of scratch, for the inversion.
    work: Vec<f64>,
}

impl BlockJacobi {
    /// The preconditioner of `n` states in blocks of `block` for the
    /// Jacobian `pattern`.
    pub fn new(n: usize, block: usize, pattern: &[(usize, usize)]) -> BlockJacobi {
        let b2 = block * block;
        let entries = pattern
            .iter()
            .enumerate()
            .filter(|(_, &(r, c))| r / block == c / block)
            .map(|(k, &(r, c))| (k, (r / block) * b2 + (r % block) * block + c % block))
            .collect();
        BlockJacobi {
            block,
            entries,
            jacobian: vec![0.0; n * block],
            inverse: vec![0.0; n * block],
            work: vec![0.0; 2 * b2],
        }
    }

    /// Keeps the blocks of the Jacobian whose non-zeros are `values`.
    pub fn load(&mut self, values: &[f64]) {
        self.jacobian.fill(0.0);
        for &(k, slot) in &self.entries {
            self.jacobian[slot] += values[k];
        }
    }

    /// Inverts I − γ·J block by block (Gauss–Jordan with partial pivoting);
    /// `false` if a block is singular.
    pub fn factor(&mut self, gamma: f64) -> bool {
        let b = self.block;
        let b2 = b * b;
        for (blk, inv) in self.jacobian.chunks(b2).zip(self.inverse.chunks_mut(b2)) {
            // [A | I] → [I | A⁻¹] in `work`, A = I − γ J_block.
            let (a, e) = self.work.split_at_mut(b2);
            for i in 0..b {
                for j in 0..b {
                    a[i * b + j] = f64::from(u8::from(i == j)) - gamma * blk[i * b + j];
                    e[i * b + j] = f64::from(u8::from(i == j));
                }
            }
            for col in 0..b {
                let pivot = (col..b)
                    .max_by(|&p, &q| a[p * b + col].abs().total_cmp(&a[q * b + col].abs()))
                    .unwrap_or(col);
                if a[pivot * b + col] == 0.0 {
                    return false;
                }
                for j in 0..b {
                    a.swap(col * b + j, pivot * b + j);
                    e.swap(col * b + j, pivot * b + j);
                }
                let p = a[col * b + col];
                for j in 0..b {
                    a[col * b + j] /= p;
                    e[col * b + j] /= p;
                }
                for i in (0..b).filter(|&i| i != col) {
                    let f = a[i * b + col];
                    for j in 0..b {
                        a[i * b + j] -= f * a[col * b + j];
                        e[i * b + j] -= f * e[col * b + j];
                    }
                }
            }
            inv.copy_from_slice(e);
        }
        true
    }

    /// z = P⁻¹ r.
    pub fn solve(&self, r: &[f64], z: &mut [f64]) {
        let b = self.block;
        for ((inv, r), z) in self.inverse.chunks(b * b).zip(r.chunks(b)).zip(z.chunks_mut(b)) {
            for (i, zi) in z.iter_mut().enumerate() {
                *zi = inv[i * b..(i + 1) * b].iter().zip(r).map(|(a, x)| a * x).sum();
            }
        }
    }
}
