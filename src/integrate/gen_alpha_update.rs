//! The generalized-α update pass (MODEL §5, update and predictors): from
//! each row's new acceleration a = a★ + Σ λ_c z_c, the new d and v and the
//! next step's predictor d̃ and residual operands ũ and h
//! (`gen_alpha_kernel.rs`, "the residual in one band product"), in one
//! sweep over memory, for L runs interleaved (`x[i·L + l]`; L = 1 is a run
//! alone).
//!
//! Every element goes through [`UpdateCoefs::row`], or its AVX2
//! transcription operation for operation, so a run's bits do not depend on
//! how many lanes it shares a pass with. The column count K and the lane
//! count L are compile-time constants of the pass: each row's L lanes are
//! one vector operation, and a run alone's rows vectorize.

/// Most right-hand-side columns the update pass has a compiled kernel for
/// (five contacts); a run alone with more takes the scalar pass.
pub(crate) const MAX_COLUMNS: usize = 6;

/// Most runs a batch steps together: the widest update pass compiled here
/// (the kernel and the batch re-export it).
pub(crate) const MAX_LANES: usize = 8;

/// The constants of the update pass (MODEL §5, update and predictors).
#[derive(Debug, Clone, Copy)]
pub(crate) struct UpdateCoefs {
    pub(crate) dt: f64,
    pub(crate) gamma: f64,
    /// βΔt².
    pub(crate) bdt2: f64,
    /// (½ − β)Δt².
    pub(crate) c_pred: f64,
    pub(crate) alpha_f: f64,
    /// α′(1 − α_f)βΔt², the shift of ũ.
    pub(crate) c_shift: f64,
    /// α′ = α_m/(1 − α_m).
    pub(crate) alpha_p: f64,
}

/// One row's state in the update pass: d, v, a, d̃, ũ, h (written).
struct RowState<'a> {
    d: &'a mut f64,
    v: &'a mut f64,
    a: &'a mut f64,
    dp: &'a mut f64,
    u: &'a mut f64,
    h: &'a mut f64,
}

impl UpdateCoefs {
    /// The update of one row from its new acceleration `acc` (every lane
    /// of every pass uses this, so their bits agree):
    /// v += Δt((1−γ)a + γ acc), d = d̃ + βΔt² acc, a = acc, then the next
    /// step's d̃, ũ and h (module docs), from the solve's b₀ and the load f.
    #[inline(always)]
    fn row(&self, acc: f64, r: RowState, b0: f64, f: f64) {
        *r.v += self.dt * ((1.0 - self.gamma) * *r.a + self.gamma * acc);
        *r.d = *r.dp + self.bdt2 * acc;
        *r.a = acc;
        let next = *r.d + self.dt * *r.v + self.c_pred * acc;
        *r.dp = next;
        *r.u = (1.0 - self.alpha_f) * next + self.alpha_f * *r.d - self.c_shift * acc;
        *r.h = f - self.alpha_p * b0;
    }
}

/// The vectors one update pass reads and writes, L lanes interleaved.
pub(crate) struct Pass<'a> {
    pub(crate) n: usize,
    pub(crate) rhs: &'a [f64],
    pub(crate) d: &'a mut [f64],
    pub(crate) v: &'a mut [f64],
    pub(crate) a: &'a mut [f64],
    pub(crate) dp: &'a mut [f64],
    pub(crate) u: &'a mut [f64],
    pub(crate) h: &'a mut [f64],
    pub(crate) b0: &'a [f64],
    /// The distributed load f, one per row (shared by the lanes).
    pub(crate) load: &'a [f64],
}

impl Pass<'_> {
    /// The pass for a run alone of any `k` columns, row by row.
    pub(crate) fn scalar(self, k: usize, lambda: &[f64], c: UpdateCoefs) {
        for (i, row) in self.rhs.chunks_exact(k).enumerate() {
            let mut acc = row[0];
            for (l, z) in lambda.iter().zip(&row[1..]) {
                acc += l * z;
            }
            let r = RowState {
                d: &mut self.d[i],
                v: &mut self.v[i],
                a: &mut self.a[i],
                dp: &mut self.dp[i],
                u: &mut self.u[i],
                h: &mut self.h[i],
            };
            c.row(acc, r, self.b0[i], self.load[i]);
        }
    }

    /// [`Pass::lanes`] with AVX2 where the CPU has it (as the banded
    /// kernel: same operations, same rounding).
    pub(crate) fn dispatch<const K: usize, const L: usize, const KL: usize>(
        self,
        lk: &[[f64; MAX_LANES]; MAX_COLUMNS],
        c: UpdateCoefs,
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            if L >= 4 {
                // SAFETY: the CPU supports AVX2 (checked just above).
                unsafe { self.avx2_x4::<K, L, KL>(lk, c) };
            } else {
                // SAFETY: as above.
                unsafe { self.avx2::<K, L, KL>(lk, c) };
            }
            return;
        }
        self.lanes::<K, L, KL>(lk, c)
    }

    /// [`Pass::lanes`] written in AVX2 vectors of four lanes (L ≥ 4; the
    /// lanes past the last multiple of 4 by the scalar formulas): the
    /// compiler, left to itself, vectorizes across rows and transposes
    /// (measured 3× slower per element than a run alone).
    /// Each vector operation is the scalar code's operation on four lanes,
    /// in the scalar code's order and association, so the bits agree.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn avx2_x4<const K: usize, const L: usize, const KL: usize>(
        self,
        lk: &[[f64; MAX_LANES]; MAX_COLUMNS],
        c: UpdateCoefs,
    ) {
        use std::arch::x86_64::*;
        let n = self.n;
        let s = _mm256_set1_pd;
        let (dt, gamma, one_m_gamma) = (s(c.dt), s(c.gamma), s(1.0 - c.gamma));
        let (bdt2, c_pred, alpha_p) = (s(c.bdt2), s(c.c_pred), s(c.alpha_p));
        let (af, one_m_af, c_shift) = (s(c.alpha_f), s(1.0 - c.alpha_f), s(c.c_shift));
        let Pass {
            rhs,
            d,
            v,
            a,
            dp,
            u,
            h,
            b0,
            load,
            ..
        } = self;
        // sliced to their known lengths, so that the row loop's indices
        // need no bounds checks beyond these
        let rhs = &rhs[..n * KL];
        let (d, v, a) = (&mut d[..n * L], &mut v[..n * L], &mut a[..n * L]);
        let (dp, u) = (&mut dp[..n * L], &mut u[..n * L]);
        let (h, b0, load) = (&mut h[..n * L], &b0[..n * L], &load[..n]);
        for i in 0..n {
            let row = &rhs[i * KL..(i + 1) * KL];
            let f = s(load[i]);
            for l in L - L % 4..L {
                let at = i * L + l;
                let mut acc = row[l];
                for cc in 1..K {
                    acc += lk[cc][l] * row[cc * L + l];
                }
                let r = RowState {
                    d: &mut d[at],
                    v: &mut v[at],
                    a: &mut a[at],
                    dp: &mut dp[at],
                    u: &mut u[at],
                    h: &mut h[at],
                };
                c.row(acc, r, b0[at], load[i]);
            }
            for g in (0..L - L % 4).step_by(4) {
                let at = i * L + g;
                // SAFETY: every slice below has at least four elements from
                // its start (at + 3 < n·L, g + 3 < L, cc·L + g + 3 < KL).
                unsafe {
                    let ld = |x: &[f64]| _mm256_loadu_pd(x.as_ptr());
                    let mut acc = ld(&row[g..]);
                    for cc in 1..K {
                        acc = _mm256_add_pd(
                            acc,
                            _mm256_mul_pd(ld(&lk[cc][g..]), ld(&row[cc * L + g..])),
                        );
                    }
                    let a_old = ld(&a[at..]);
                    // v += dt((1 − γ)a + γ acc)
                    let vv = _mm256_add_pd(
                        ld(&v[at..]),
                        _mm256_mul_pd(
                            dt,
                            _mm256_add_pd(
                                _mm256_mul_pd(one_m_gamma, a_old),
                                _mm256_mul_pd(gamma, acc),
                            ),
                        ),
                    );
                    // d = d̃ + βΔt² acc
                    let dd = _mm256_add_pd(ld(&dp[at..]), _mm256_mul_pd(bdt2, acc));
                    // next = d + Δt v + c_pred acc
                    let next = _mm256_add_pd(
                        _mm256_add_pd(dd, _mm256_mul_pd(dt, vv)),
                        _mm256_mul_pd(c_pred, acc),
                    );
                    // ũ = (1 − α_f) next + α_f d − c_shift acc
                    let uu = _mm256_sub_pd(
                        _mm256_add_pd(_mm256_mul_pd(one_m_af, next), _mm256_mul_pd(af, dd)),
                        _mm256_mul_pd(c_shift, acc),
                    );
                    // h = f − α′ b₀
                    let hh = _mm256_sub_pd(f, _mm256_mul_pd(alpha_p, ld(&b0[at..])));
                    _mm256_storeu_pd(v[at..].as_mut_ptr(), vv);
                    _mm256_storeu_pd(d[at..].as_mut_ptr(), dd);
                    _mm256_storeu_pd(a[at..].as_mut_ptr(), acc);
                    _mm256_storeu_pd(dp[at..].as_mut_ptr(), next);
                    _mm256_storeu_pd(u[at..].as_mut_ptr(), uu);
                    _mm256_storeu_pd(h[at..].as_mut_ptr(), hh);
                }
            }
        }
    }

    /// [`Pass::lanes`] compiled with AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn avx2<const K: usize, const L: usize, const KL: usize>(
        self,
        lk: &[[f64; MAX_LANES]; MAX_COLUMNS],
        c: UpdateCoefs,
    ) {
        self.lanes::<K, L, KL>(lk, c)
    }

    /// The pass of every lane, element by element ([`UpdateCoefs::row`]):
    /// L and the columns are compile-time constants, so each row's L lanes
    /// are one vector operation (and a run alone's rows vectorize).
    #[inline(always)]
    fn lanes<const K: usize, const L: usize, const KL: usize>(
        self,
        lk: &[[f64; MAX_LANES]; MAX_COLUMNS],
        c: UpdateCoefs,
    ) {
        let (rhs, _) = self.rhs.as_chunks::<KL>();
        let (d, _) = self.d.as_chunks_mut::<L>();
        let (v, _) = self.v.as_chunks_mut::<L>();
        let (a, _) = self.a.as_chunks_mut::<L>();
        let (dp, _) = self.dp.as_chunks_mut::<L>();
        let (u, _) = self.u.as_chunks_mut::<L>();
        let (h, _) = self.h.as_chunks_mut::<L>();
        let (b0, _) = self.b0.as_chunks::<L>();
        let state = d.iter_mut().zip(v.iter_mut()).zip(a.iter_mut());
        let pred = dp.iter_mut().zip(u.iter_mut());
        let load = h.iter_mut().zip(b0).zip(self.load);
        for ((row, ((d, v), a)), ((dp, u), ((h, b0), f))) in
            rhs.iter().zip(state).zip(pred.zip(load))
        {
            for l in 0..L {
                let mut acc = row[l];
                for cc in 1..K {
                    acc += lk[cc][l] * row[cc * L + l];
                }
                let r = RowState {
                    d: &mut d[l],
                    v: &mut v[l],
                    a: &mut a[l],
                    dp: &mut dp[l],
                    u: &mut u[l],
                    h: &mut h[l],
                };
                c.row(acc, r, b0[l], *f);
            }
        }
    }
}
