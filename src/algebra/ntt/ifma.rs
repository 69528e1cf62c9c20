//! Garner's recombination ([`super::Garner::coefficient`]) eight coefficients at a time, on
//! x86-64 processors with AVX-512 and its 52-bit integer multiply-add (`avx512f`,
//! `avx512ifma`; detected when the program runs). The primes are below 2⁵⁰, so every
//! modular product is one of 52-bit numbers: Shoup's multiplication by a constant `w < p`
//! with `w' = ⌊w·2⁵²/p⌋` (the quotient estimate `⌊x·w'/2⁵²⌋` is `⌊x·w/p⌋` or one less for
//! `x < 2⁵²`, so `x·w − q·p < 2p`), and the coefficient `X < 2¹⁵⁰` is assembled in 52-bit
//! limbs and cut into three words. The carries between coefficients are propagated one word
//! at a time, as in the portable loop.

use super::{accumulate, Garner, Shoup, PRIMES};
use std::arch::x86_64::{
    __m512i, _mm512_add_epi64, _mm512_and_si512, _mm512_loadu_si512, _mm512_madd52hi_epu64,
    _mm512_madd52lo_epu64, _mm512_min_epu64, _mm512_or_si512, _mm512_set1_epi64,
    _mm512_setzero_si512, _mm512_slli_epi64, _mm512_srli_epi64, _mm512_storeu_si512,
    _mm512_sub_epi64,
};

/// Whether this processor has the instructions [`recombine`] uses.
pub(super) fn available() -> bool {
    std::arch::is_x86_feature_detected!("avx512f")
        && std::arch::is_x86_feature_detected!("avx512ifma")
}

/// `out[k] ← ` the words of `Σ_k X_k·2^(64k)` for the coefficients `X_k` with residues
/// `residues[i][k]` modulo `PRIMES[i]` (each below its prime), the longest multiple of eight of `out`'s
/// words, `carry` the pending carry in and out (see [`accumulate`]). Returns how many words it
/// wrote. Only called when [`available`].
pub(super) fn recombine(
    garner: &Garner,
    residues: [&[u64]; 3],
    out: &mut [u64],
    carry: &mut [u64; 3],
) -> usize {
    assert!(available());
    let words = out.len() / 8 * 8;
    assert!(residues.iter().all(|r| r.len() >= words));
    // SAFETY: the processor has the target features `recombine_ifma` is compiled for
    // (checked just above), and every slice holds the `words` words it reads or writes.
    unsafe { recombine_ifma(garner, residues, &mut out[..words], carry) };
    words
}

/// Shoup's multiplication by `w` modulo `p < 2⁵⁰` in 52-bit lanes: `w` and `⌊w·2⁵²/p⌋`.
#[derive(Clone, Copy)]
struct Shoup52 {
    w: __m512i,
    w_shoup: __m512i,
    p: __m512i,
}

impl Shoup52 {
    #[target_feature(enable = "avx512f")]
    fn new(s: Shoup, p: u64) -> Self {
        let w_shoup = ((s.w as u128) << 52) / p as u128;
        Shoup52 {
            w: _mm512_set1_epi64(s.w as i64),
            w_shoup: _mm512_set1_epi64(w_shoup as i64),
            p: _mm512_set1_epi64(p as i64),
        }
    }

    /// `x·w mod p` in each lane, for `x < 2⁵²`.
    #[inline]
    #[target_feature(enable = "avx512f,avx512ifma")]
    fn mul(self, x: __m512i) -> __m512i {
        let zero = _mm512_setzero_si512();
        let q = _mm512_madd52hi_epu64(zero, x, self.w_shoup);
        // x·w − q·p < 2p < 2⁵², so its low 52 bits are all of it.
        let r = _mm512_sub_epi64(
            _mm512_madd52lo_epu64(zero, x, self.w),
            _mm512_madd52lo_epu64(zero, q, self.p),
        );
        below(_mm512_and_si512(r, _mm512_set1_epi64(MASK as i64)), self.p)
    }
}

/// `2⁵² − 1`.
const MASK: u64 = (1 << 52) - 1;

/// `x mod p` for `x < 2p` in each lane: `x − p` wraps round above `x` when `x < p`.
#[inline]
#[target_feature(enable = "avx512f")]
fn below(x: __m512i, p: __m512i) -> __m512i {
    _mm512_min_epu64(x, _mm512_sub_epi64(x, p))
}

#[target_feature(enable = "avx512f,avx512ifma")]
unsafe fn recombine_ifma(
    garner: &Garner,
    [r0, r1, r2]: [&[u64]; 3],
    out: &mut [u64],
    carry: &mut [u64; 3],
) {
    let [p0, p1, p2] = PRIMES;
    let inv01 = Shoup52::new(garner.inv01, p1);
    let inv012 = Shoup52::new(garner.inv012, p2);
    let inv12 = Shoup52::new(garner.inv12, p2);
    let p0p1 = p0 as u128 * p1 as u128;
    let limb = |x: u128| _mm512_set1_epi64((x as u64 & MASK) as i64);
    let (vp0, vp1, vp2) = (limb(p0 as u128), limb(p1 as u128), limb(p2 as u128));
    // p₁p₂ < 2¹⁰⁰ in two limbs.
    let (pp0, pp1) = (limb(p0p1), limb(p0p1 >> 52));
    let mask = _mm512_set1_epi64(MASK as i64);
    let zero = _mm512_setzero_si512();
    let mut lanes = [[0u64; 8]; 3];
    for (k, chunk) in out.chunks_exact_mut(8).enumerate() {
        let at = 8 * k;
        // SAFETY: `at + 8 ≤ out.len() ≤` each residue slice's length (checked by `recombine`).
        let (a, b, c) = unsafe {
            (
                _mm512_loadu_si512(r0.as_ptr().add(at).cast()),
                _mm512_loadu_si512(r1.as_ptr().add(at).cast()),
                _mm512_loadu_si512(r2.as_ptr().add(at).cast()),
            )
        };
        let t1 = inv01.mul(_mm512_sub_epi64(_mm512_add_epi64(b, vp1), below(a, vp1)));
        let u = inv012.mul(_mm512_sub_epi64(_mm512_add_epi64(c, vp2), below(a, vp2)));
        let t2 = below(
            _mm512_sub_epi64(_mm512_add_epi64(u, vp2), inv12.mul(t1)),
            vp2,
        );
        // X = a + p₁·t₁ + p₁p₂·t₂ in limbs of 52 bits: l₀ + l₁·2⁵² + l₂·2¹⁰⁴.
        let l0 = _mm512_madd52lo_epu64(_mm512_madd52lo_epu64(a, vp0, t1), pp0, t2);
        let l1 = _mm512_madd52hi_epu64(zero, vp0, t1);
        let l1 = _mm512_madd52lo_epu64(_mm512_madd52hi_epu64(l1, pp0, t2), pp1, t2);
        let l2 = _mm512_madd52hi_epu64(zero, pp1, t2);
        let l1 = _mm512_add_epi64(l1, _mm512_srli_epi64::<52>(l0));
        let l0 = _mm512_and_si512(l0, mask);
        let l2 = _mm512_add_epi64(l2, _mm512_srli_epi64::<52>(l1));
        let l1 = _mm512_and_si512(l1, mask);
        let w0 = _mm512_or_si512(l0, _mm512_slli_epi64::<52>(l1));
        let w1 = _mm512_or_si512(_mm512_srli_epi64::<12>(l1), _mm512_slli_epi64::<40>(l2));
        let w2 = _mm512_srli_epi64::<24>(l2);
        // SAFETY: each lane array holds eight words.
        unsafe {
            _mm512_storeu_si512(lanes[0].as_mut_ptr().cast(), w0);
            _mm512_storeu_si512(lanes[1].as_mut_ptr().cast(), w1);
            _mm512_storeu_si512(lanes[2].as_mut_ptr().cast(), w2);
        }
        for (lane, o) in chunk.iter_mut().enumerate() {
            *o = accumulate(carry, [lanes[0][lane], lanes[1][lane], lanes[2][lane]]);
        }
    }
}
