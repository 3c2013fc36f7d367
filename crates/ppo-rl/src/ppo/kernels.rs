//! The kernels the updates without tensors share (the private `plain` modules of the
//! discrete agent and the continuous agent): candle's float operations one for one on plain
//! `f32` slices, for networks of `D` inputs (4 for CartPole, 3 for Pendulum) and one hidden
//! layer. Which of gemm's summation orders each one reproduces, and why, is in the discrete
//! `plain` module's doc; its tests and the continuous agent's compare both updates with the
//! tensor code, number for number (and print `SKIPPED` where this CPU cannot run them).
//!
//! They run as [`UpdatePath::Plain`](super::UpdatePath::Plain) only where they reproduce
//! candle; [`update_path`](super::update_path) states the rule once ([`shapes_fit`] and
//! [`isa`] are two of its conditions).

use candle_core::{Device, Tensor};

use crate::ppo::adam::Adam;
use crate::ppo::model::Linear;

/// Batch sizes and hidden widths the kernels handle, inclusive (see [`shapes_fit`]).
pub(crate) const MIN_BATCH: usize = 3;
pub(crate) const MAX_BATCH: usize = 512;
pub(crate) const MIN_HIDDEN: usize = 2;
pub(crate) const MAX_HIDDEN: usize = 512;

/// The instruction set the kernels are compiled for: x86-64-v3 (AVX2 and FMA), where
/// candle's kernels are the ones this module reproduces.
#[cfg(target_arch = "x86_64")]
pub(crate) type Isa = pulp::x86::V3;
/// Elsewhere the tensor version runs ([`isa`] says no), so this is never built.
#[cfg(not(target_arch = "x86_64"))]
pub(crate) type Isa = pulp::Scalar;

/// The instruction set, where this CPU has it.
#[cfg(target_arch = "x86_64")]
pub(crate) fn isa() -> Option<Isa> {
    pulp::x86::V3::try_new()
}

/// Never: the module reproduces candle's x86-64 kernels only.
#[cfg(not(target_arch = "x86_64"))]
pub(crate) fn isa() -> Option<Isa> {
    None
}

/// One network's parameters as plain data, in PyTorch's layouts.
#[derive(Debug, Clone, Default)]
pub(crate) struct Params {
    /// `fc1.weight`, `(hidden, inputs)` row-major.
    pub(crate) w1: Vec<f32>,
    /// `fc1.bias`, `(hidden,)`.
    pub(crate) b1: Vec<f32>,
    /// `fc2.weight`, `(out, hidden)` row-major.
    pub(crate) w2: Vec<f32>,
    /// `fc2.bias`, `(out,)`.
    pub(crate) b2: Vec<f32>,
}

impl Params {
    pub(crate) fn read(fc1: &Linear, fc2: &Linear) -> candle_core::Result<Self> {
        let flat = |t: &Tensor| t.flatten_all()?.to_vec1::<f32>();
        Ok(Self {
            w1: flat(fc1.weight.as_tensor())?,
            b1: flat(fc1.bias.as_tensor())?,
            w2: flat(fc2.weight.as_tensor())?,
            b2: flat(fc2.bias.as_tensor())?,
        })
    }

    pub(crate) fn write(&self, fc1: &Linear, fc2: &Linear) -> candle_core::Result<()> {
        let dev = &Device::Cpu;
        for (var, data) in [
            (&fc1.weight, &self.w1),
            (&fc1.bias, &self.b1),
            (&fc2.weight, &self.w2),
            (&fc2.bias, &self.b2),
        ] {
            var.set(&Tensor::from_vec(data.clone(), var.shape(), dev)?)?;
        }
        Ok(())
    }

    /// `W1ᵀ`, `(D, hidden)` row-major, for the forward pass.
    pub(crate) fn w1_transposed<const D: usize>(&self) -> Vec<f32> {
        let hidden = self.b1.len();
        let mut t = vec![0.0; self.w1.len()];
        for (j, row) in self.w1.chunks_exact(D).enumerate() {
            for (p, &w) in row.iter().enumerate() {
                t[p * hidden + j] = w;
            }
        }
        t
    }

    /// Adam's step on the four tensors, in the optimizer's order.
    pub(crate) fn step(
        &mut self,
        adam: &mut Adam,
        grads: Grads,
        max_grad_norm: Option<f64>,
    ) -> candle_core::Result<()> {
        let mut grads = [
            Some(grads.w1),
            Some(grads.b1),
            Some(grads.w2),
            Some(grads.b2),
        ];
        let mut params = [
            &mut self.w1[..],
            &mut self.b1[..],
            &mut self.w2[..],
            &mut self.b2[..],
        ];
        adam.step_params(&mut grads, &mut params, max_grad_norm)
    }
}

/// The gradients of one network's four tensors, laid out as [`Params`].
pub(crate) struct Grads {
    pub(crate) w1: Vec<f32>,
    pub(crate) b1: Vec<f32>,
    pub(crate) w2: Vec<f32>,
    pub(crate) b2: Vec<f32>,
}

/// A kernel's arguments, run by `pulp` under the instruction set it was given.
macro_rules! kernel {
    ($name:ident { $($field:ident: $ty:ty),* $(,)? } -> $out:ty = $body:expr) => {
        struct $name<'a> {
            $($field: $ty,)*
            _life: std::marker::PhantomData<&'a ()>,
        }
        impl pulp::WithSimd for $name<'_> {
            type Output = $out;
            #[inline(always)]
            fn with_simd<S: pulp::Simd>(self, _: S) -> Self::Output {
                let Self { $($field,)* .. } = self;
                $body($($field),*)
            }
        }
    };
}

pub(crate) use kernel;

/// Whether gemm takes the paths the kernels reproduce for a batch of `n` rows and a hidden
/// layer of `hidden` units: it takes other paths for tiny products (`n · hidden ≤ 256` in
/// fc1, `k ≤ 2` in the weight gradients), for `hidden = 1`, and splits sums longer than 512.
pub(crate) fn shapes_fit(n: usize, hidden: usize) -> bool {
    (MIN_BATCH..=MAX_BATCH).contains(&n)
        && (MIN_HIDDEN..=MAX_HIDDEN).contains(&hidden)
        && n * hidden > 256
}

/// The critic's two kernels (forward and parameter gradients), each run under the [`Isa`]
/// (`pulp` compiles it for the instruction set, so `mul_add` is one FMA instruction): the
/// same value network `D → hidden → 1` in both agents.
#[derive(Clone, Copy)]
pub(crate) struct CriticKernels(pub(crate) Isa);

/// [`critic_values`]' arguments.
struct CriticForward<'a, const D: usize> {
    params: &'a Params,
    states: &'a [[f32; D]],
    xt: &'a [Vec<f32>; D],
    hidden: Option<&'a mut [f32]>,
    scratch: &'a mut Scratch,
}

impl<const D: usize> pulp::WithSimd for CriticForward<'_, D> {
    type Output = Vec<f32>;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> Vec<f32> {
        critic_values(self.params, self.states, self.xt, self.hidden, self.scratch)
    }
}

/// [`critic_backward`]'s arguments.
struct CriticBackward<'a, const D: usize> {
    params: &'a Params,
    states: &'a [[f32; D]],
    hidden: &'a [f32],
    grad_values: &'a [f32],
}

impl<const D: usize> pulp::WithSimd for CriticBackward<'_, D> {
    type Output = Grads;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> Grads {
        critic_backward(self.params, self.states, self.hidden, self.grad_values)
    }
}

impl CriticKernels {
    /// `V(s)` for every row of `states` (`xt` its columns); with `hidden`, the hidden layer
    /// is left there for [`CriticKernels::backward`].
    pub(crate) fn forward<const D: usize>(
        self,
        params: &Params,
        states: &[[f32; D]],
        xt: &[Vec<f32>; D],
        hidden: Option<&mut [f32]>,
        scratch: &mut Scratch,
    ) -> Vec<f32> {
        let args = CriticForward {
            params,
            states,
            xt,
            hidden,
            scratch,
        };
        pulp::Simd::vectorize(self.0, args)
    }

    /// The critic's parameter gradients from `∂loss/∂V(s)`.
    pub(crate) fn backward<const D: usize>(
        self,
        params: &Params,
        states: &[[f32; D]],
        hidden: &[f32],
        grad_values: &[f32],
    ) -> Grads {
        let args = CriticBackward {
            params,
            states,
            hidden,
            grad_values,
        };
        pulp::Simd::vectorize(self.0, args)
    }
}

/// `d.exp()`, without calling `exp` where `d` is zero (`exp(±0) = 1` exactly).
#[inline(always)]
pub(crate) fn exp_exact(d: f32) -> f32 {
    if d == 0.0 { 1.0 } else { d.exp() }
}

/// `relu(x · W1ᵀ + b1)` for every row `x` of `states`, into `hidden` (`(N, hidden)`,
/// row-major, as the backward pass reads it). Each unit is gemm's vertical kernel (an FMA
/// chain from +0 over the inputs in order), then add_bias and relu (`ops`).
#[inline(always)]
pub(crate) fn hidden_layer<const D: usize>(
    params: &Params,
    states: &[[f32; D]],
    hidden: &mut [f32],
) {
    let h = params.b1.len();
    let w1t = params.w1_transposed::<D>();
    let columns: [&[f32]; D] = std::array::from_fn(|p| &w1t[p * h..(p + 1) * h]);
    let b1 = &params.b1[..h];
    for (row, x) in hidden.chunks_exact_mut(h).zip(states) {
        let row = &mut row[..h];
        for j in 0..h {
            let mut acc = 0.0_f32;
            for p in 0..D {
                acc = x[p].mul_add(columns[p][j], acc);
            }
            row[j] = (acc + b1[j]).max(0.0);
        }
    }
}

/// The inputs column by column: `x_p` of every row, for each of the `D` inputs.
pub(crate) fn input_columns<const D: usize>(states: &[[f32; D]]) -> [Vec<f32>; D] {
    std::array::from_fn(|p| states.iter().map(|x| x[p]).collect())
}

/// [`hidden_layer`] column-major (`cols[j * N + i]`), so that the output layer's sums over
/// `j` run on all rows at once.
#[inline(always)]
pub(crate) fn hidden_columns<const D: usize>(
    params: &Params,
    xt: &[Vec<f32>; D],
    cols: &mut [f32],
) {
    let n = xt[0].len();
    let inputs: [&[f32]; D] = std::array::from_fn(|p| &xt[p][..n]);
    for ((col, w), &b) in cols
        .chunks_exact_mut(n)
        .zip(params.w1.chunks_exact(D))
        .zip(&params.b1)
    {
        // hidden_layer's chain, one hidden unit over all rows
        let col = &mut col[..n];
        for i in 0..n {
            let mut acc = 0.0_f32;
            for p in 0..D {
                acc = inputs[p][i].mul_add(w[p], acc);
            }
            col[i] = (acc + b).max(0.0);
        }
    }
}

/// gemm's horizontal kernel over all rows: lane `l` sums the FMAs of `j = 8c + l` (the
/// last block zero-padded), then `((l0 + l4) + (l2 + l6)) + ((l1 + l5) + (l3 + l7))`.
/// `lanes` holds `8 N` values.
#[inline(always)]
pub(crate) fn horizontal_columns(cols: &[f32], w: &[f32], lanes: &mut [f32], out: &mut [f32]) {
    let n = out.len();
    let lanes = &mut lanes[..8 * n];
    lanes.fill(0.0);
    for (j, (col, &wj)) in cols.chunks_exact(n).zip(w).enumerate() {
        let l = j % 8;
        for (a, &h) in lanes[l * n..(l + 1) * n].iter_mut().zip(col) {
            *a = h.mul_add(wj, *a);
        }
    }
    let k = w.len().min(cols.len() / n.max(1));
    if !k.is_multiple_of(8) {
        // the padding of the last block: fma(0, 0, acc)
        for a in &mut lanes[(k % 8) * n..] {
            *a = 0.0_f32.mul_add(0.0, *a);
        }
    }
    let lane = |l: usize| &lanes[l * n..(l + 1) * n];
    let (l0, l1, l2, l3) = (lane(0), lane(1), lane(2), lane(3));
    let (l4, l5, l6, l7) = (lane(4), lane(5), lane(6), lane(7));
    for (i, o) in out.iter_mut().enumerate() {
        *o = ((l0[i] + l4[i]) + (l2[i] + l6[i])) + ((l1[i] + l5[i]) + (l3[i] + l7[i]));
    }
}

/// gemm's row-major gemv over all rows: lane `l` of accumulator `b` sums the FMAs of
/// `j = 64t + 8b + l` over the blocks `t` of 64, the eight accumulators are combined as a
/// tree, blocks of 8 go on into the lane, the lanes are summed in order, then the tail.
/// `lanes` holds `8 N` values and `lane` `N`.
#[inline(always)]
pub(crate) fn gemv_columns(
    cols: &[f32],
    w: &[f32],
    lanes: &mut [f32],
    lane: &mut [f32],
    out: &mut [f32],
) {
    let n = out.len();
    let k = w.len().min(cols.len() / n.max(1));
    let (k64, k8) = (k / 64 * 64, k / 8 * 8);
    let col = |j: usize| &cols[j * n..(j + 1) * n];
    let (acc, lane) = (&mut lanes[..8 * n], &mut lane[..n]);
    for l in 0..8 {
        acc.fill(0.0);
        for t in (0..k64).step_by(64) {
            for (b, acc) in acc.chunks_exact_mut(n).enumerate() {
                let j = t + 8 * b + l;
                for (a, &h) in acc.iter_mut().zip(col(j)) {
                    *a = h.mul_add(w[j], *a);
                }
            }
        }
        {
            let c = |b: usize| &acc[b * n..(b + 1) * n];
            let (c0, c1, c2, c3) = (c(0), c(1), c(2), c(3));
            let (c4, c5, c6, c7) = (c(4), c(5), c(6), c(7));
            for (i, v) in lane.iter_mut().enumerate() {
                *v = ((c0[i] + c1[i]) + (c2[i] + c3[i])) + ((c4[i] + c5[i]) + (c6[i] + c7[i]));
            }
        }
        for j in (k64..k8).step_by(8).map(|t| t + l) {
            for (v, &h) in lane.iter_mut().zip(col(j)) {
                *v = h.mul_add(w[j], *v);
            }
        }
        if l == 0 {
            out.copy_from_slice(lane);
        } else {
            for (o, &v) in out.iter_mut().zip(lane.iter()) {
                *o += v;
            }
        }
    }
    for (j, &wj) in w.iter().enumerate().take(k).skip(k8) {
        for (o, &h) in out.iter_mut().zip(col(j)) {
            *o = h.mul_add(wj, *o);
        }
    }
}

/// Buffers of the forward passes, reused.
#[derive(Clone, Default)]
pub(crate) struct Scratch {
    /// A hidden layer column-major, `hidden · N`.
    pub(crate) cols: Vec<f32>,
    /// Lane sums, `8 N`.
    pub(crate) lanes: Vec<f32>,
    /// One lane, `N`; then outputs.
    pub(crate) lane: Vec<f32>,
    pub(crate) out0: Vec<f32>,
    pub(crate) out1: Vec<f32>,
}

impl Scratch {
    pub(crate) fn fit(&mut self, n: usize, hidden: usize) {
        for (buffer, len) in [
            (&mut self.cols, hidden * n),
            (&mut self.lanes, 8 * n),
            (&mut self.lane, n),
            (&mut self.out0, n),
            (&mut self.out1, n),
        ] {
            buffer.resize(len, 0.0);
        }
    }
}

/// The critic's forward pass `V(s)`; with `hidden`, the hidden layer is left there too.
#[inline(always)]
pub(crate) fn critic_values<const D: usize>(
    params: &Params,
    states: &[[f32; D]],
    xt: &[Vec<f32>; D],
    hidden: Option<&mut [f32]>,
    scratch: &mut Scratch,
) -> Vec<f32> {
    if let Some(hidden) = hidden {
        hidden_layer(params, states, hidden);
    }
    let n = states.len();
    let h = params.b1.len();
    scratch.fit(n, h);
    hidden_columns(params, xt, &mut scratch.cols);
    output_column(&params.w2[..h], params.b2[0], n, scratch)
}

/// One output of a `(hidden → 1)` layer over all rows, `cols · w + b`, from the hidden layer
/// column-major in `scratch.cols`: gemm's horizontal kernel up to 256 rows, its row-major
/// gemv above, then add_bias.
#[inline(always)]
pub(crate) fn output_column(w: &[f32], b: f32, n: usize, scratch: &mut Scratch) -> Vec<f32> {
    let Scratch {
        cols,
        lanes,
        lane,
        out0,
        ..
    } = scratch;
    if n <= 256 {
        horizontal_columns(cols, w, lanes, out0);
    } else {
        gemv_columns(cols, w, lanes, lane, out0);
    }
    out0.iter().map(|&v| v + b).collect() // add_bias
}

/// candle's `vec_sum` (AVX): four 8-lane sums over blocks of 32, reduced as a tree, then the
/// rest added in order.
#[inline(always)]
pub(crate) fn vec_sum(xs: &[f32]) -> f32 {
    let blocks = xs.len() / 32 * 32;
    let mut sum = [[0.0_f32; 8]; 4];
    for chunk in xs[..blocks].chunks_exact(32) {
        for (j, sum) in sum.iter_mut().enumerate() {
            for (l, s) in sum.iter_mut().enumerate() {
                *s += chunk[8 * j + l];
            }
        }
    }
    let mut x = [0.0_f32; 8];
    for (l, x) in x.iter_mut().enumerate() {
        *x = (sum[0][l] + sum[1][l]) + (sum[2][l] + sum[3][l]);
    }
    let t = [x[0] + x[4], x[1] + x[5], x[2] + x[6], x[3] + x[7]];
    let mut total = (t[0] + t[1]) + (t[2] + t[3]);
    for &v in &xs[blocks..] {
        total += v;
    }
    total
}

/// The critic's parameter gradients from `∂loss/∂V(s)` (`grad_values`, one per row).
#[inline(always)]
pub(crate) fn critic_backward<const D: usize>(
    params: &Params,
    states: &[[f32; D]],
    hidden: &[f32],
    grad_values: &[f32],
) -> Grads {
    let h = params.b1.len();
    let mut grads = Grads {
        w1: vec![0.0; D * h],
        b1: vec![0.0; h],
        w2: vec![0.0; h],
        b2: vec![0.0],
    };
    let mut grad_b2 = 0.0_f32;
    for &g in grad_values {
        grad_b2 += g;
    }
    grads.b2 = vec![0.0 + grad_b2];
    let blocks = h / 8 * 8;
    for j in (0..blocks).step_by(8) {
        critic_columns::<D, 8>(params, states, hidden, grad_values, j, &mut grads);
    }
    for j in blocks..h {
        critic_columns::<D, 1>(params, states, hidden, grad_values, j, &mut grads);
    }
    grads
}

/// [`critic_backward`] for the `L` columns from `j0` of the hidden layer.
#[inline(always)]
pub(crate) fn critic_columns<const D: usize, const L: usize>(
    params: &Params,
    states: &[[f32; D]],
    hidden: &[f32],
    grad_values: &[f32],
    j0: usize,
    grads: &mut Grads,
) {
    let h = params.b1.len();
    let w: [f32; L] = take(&params.w2[j0..]);
    let mut gw = [0.0_f32; L];
    let mut gb1 = [0.0_f32; L];
    let mut gw1t = [[0.0_f32; L]; D];
    // Hᵀ · g is gemm's column-major gemv: the first row's product, then FMAs. Starting
    // from fma(h, g, +0) instead differs only in the sign of a zero, and only while every
    // product so far is zero; the `0 +` of the gradient's store makes both +0.
    for ((row, x), &g) in hidden.chunks_exact(h).zip(states).zip(grad_values) {
        let hv: [f32; L] = take(&row[j0..]);
        let g = 0.0 + g; // fc2's input gradient: 0 + g
        let mut grad_h = [0.0_f32; L];
        for l in 0..L {
            gw[l] = hv[l].mul_add(g, gw[l]);
            grad_h[l] = 0.0 + g * w[l]; // g · w2 (gevv, k = 1)
        }
        fc1_backward_row(&hv, x, &grad_h, &mut gb1, &mut gw1t);
    }
    store_columns(grads, j0, gw1t, gb1, &[gw]);
}

/// One row's relu and fc1 part of the backward pass, for `L` hidden units: relu's gradient
/// on `z1 > 0` (the same as `h > 0`), add_bias's sum, and `Xᵀ · G1` (vertical kernel).
/// (The `D` rows of `Xᵀ · G1` are separate arrays so that the compiler vectorises over
/// the units, not over the inputs.)
#[inline(always)]
pub(crate) fn fc1_backward_row<const D: usize, const L: usize>(
    hv: &[f32; L],
    x: &[f32; D],
    grad_h: &[f32; L],
    gb1: &mut [f32; L],
    gw1t: &mut [[f32; L]; D],
) {
    let mut grad_z1 = [0.0_f32; L];
    for ((gz, &h), &gh) in grad_z1.iter_mut().zip(hv).zip(grad_h) {
        *gz = 0.0 + if h > 0.0 { gh } else { 0.0 };
    }
    for (b, &gz) in gb1.iter_mut().zip(&grad_z1) {
        *b += gz;
    }
    for (d, &xp) in gw1t.iter_mut().zip(x) {
        for l in 0..L {
            d[l] = xp.mul_add(grad_z1[l], d[l]);
        }
    }
}

/// Writes `L` columns of gradients from `j0`, each added to zeros as candle's backward
/// adds it (`W1` through its transpose, `W2` row by row).
#[inline(always)]
pub(crate) fn store_columns<const D: usize, const L: usize>(
    grads: &mut Grads,
    j0: usize,
    gw1t: [[f32; L]; D],
    gb1: [f32; L],
    gw2: &[[f32; L]],
) {
    let h = grads.b1.len();
    for l in 0..L {
        let j = j0 + l;
        for (g, column) in grads.w1[j * D..(j + 1) * D].iter_mut().zip(&gw1t) {
            *g = 0.0 + column[l];
        }
        grads.b1[j] = 0.0 + gb1[l];
        for (a, gw) in gw2.iter().enumerate() {
            grads.w2[a * h + j] = 0.0 + gw[l];
        }
    }
}

/// The first `L` values of `xs`.
#[inline(always)]
pub(crate) fn take<const L: usize>(xs: &[f32]) -> [f32; L] {
    std::array::from_fn(|l| xs[l])
}

/// The clipped surrogate of one row from its `log π(a|s)`, as the tensor code computes it:
/// `ratio = exp(log_prob - old)`, `surr1 = ratio · A`, `surr2 = clamp(ratio, 1 - ε, 1 + ε) · A`,
/// `objective = min(surr1, surr2)` (the loss is `mean(-objective)`).
#[derive(Clone, Copy)]
pub(crate) struct Surrogate {
    pub(crate) ratio: f32,
    pub(crate) surr1: f32,
    pub(crate) surr2: f32,
    /// `max(ratio, 1 - ε)`.
    above_lo: f32,
    /// `min(above_lo, 1 + ε)`.
    clamped: f32,
    /// `min(surr1, surr2)`.
    pub(crate) objective: f32,
}

impl Surrogate {
    #[inline(always)]
    pub(crate) fn forward(
        log_prob: f32,
        old_log_prob: f32,
        advantage: f32,
        lo: f32,
        hi: f32,
    ) -> Self {
        let ratio = exp_exact(log_prob - old_log_prob);
        let surr1 = ratio * advantage;
        // clamp = maximum then minimum (candle's binary ops)
        let above_lo = if ratio < lo { lo } else { ratio };
        let clamped = if above_lo > hi { hi } else { above_lo };
        let surr2 = clamped * advantage;
        let objective = if surr1 > surr2 { surr2 } else { surr1 };
        Self {
            ratio,
            surr1,
            surr2,
            above_lo,
            clamped,
            objective,
        }
    }

    /// `∂ actor_loss / ∂ log_prob` for this row, `actor_loss = mean(-min(surr1, surr2))`, in
    /// the order candle's backward pass visits the graph.
    #[inline(always)]
    pub(crate) fn backward(&self, inv_n: f32, advantage: f32, lo: f32, hi: f32) -> f32 {
        let eq = |a: f32, b: f32| f32::from(u8::from(a == b));
        // mean_all: affine(1/N) then the sum's broadcast, each added to zeros
        let grad_neg_objective = 0.0 + (0.0 + (0.0 + (1.0 * inv_n + 0.0)));
        let grad_objective = 0.0 - grad_neg_objective; // neg: zeros - grad
        // minimum(surr1, surr2): a tie splits the gradient in halves
        let (on_surr1, on_surr2) = (
            eq(self.objective, self.surr1),
            eq(self.objective, self.surr2),
        );
        let grad_surr1 = 0.0 + (on_surr1 * grad_objective) / (on_surr2 * 1.0 + 1.0);
        let grad_surr2 = 0.0 + (on_surr2 * grad_objective) / (on_surr1 * 1.0 + 1.0);
        // surr2 = clamped * advantage; clamped = minimum(above_lo, hi); above_lo = maximum(ratio, lo)
        let grad_clamped = 0.0 + grad_surr2 * advantage;
        let grad_above_lo = 0.0
            + (eq(self.clamped, self.above_lo) * grad_clamped) / (eq(self.clamped, hi) * 1.0 + 1.0);
        // the ratio's two uses: the clamp is visited first, then surr1
        let grad_ratio = 0.0
            + (eq(self.above_lo, self.ratio) * grad_above_lo) / (eq(self.above_lo, lo) * 1.0 + 1.0);
        let grad_ratio = grad_ratio + grad_surr1 * advantage;
        // ratio = exp(log_prob - old)
        let grad_log_ratio = 0.0 + grad_ratio * self.ratio;
        0.0 + grad_log_ratio
    }
}

/// The critic's loss `mean((V(s) - td_target)²)` and its gradient with respect to `V(s)`,
/// as the tensor code computes them.
pub(crate) fn critic_loss(values: &[f32], td_target: &[f32], inv_n: f32) -> (f32, Vec<f32>) {
    let grad_square = 0.0 + (0.0 + (0.0 + (1.0 * inv_n + 0.0)));
    let mut squares = Vec::with_capacity(values.len());
    let mut grad_values = Vec::with_capacity(values.len());
    for (&v, &target) in values.iter().zip(td_target) {
        let diff = v - target;
        squares.push(diff * diff);
        // sqr's backward: (diff * grad) * 2 + 0, grad = 0 + 1/N
        let grad_diff = 0.0 + ((diff * grad_square) * 2.0 + 0.0);
        grad_values.push(0.0 + grad_diff);
    }
    (vec_sum(&squares) * inv_n + 0.0, grad_values)
}
