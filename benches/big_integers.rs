//! Benchmarks of the big-integer primitives behind an exact optimum's JSON report, on numbers of
//! the size of its values at 10⁴ states and γ = 0.999 (1,875 words, about 120,000 bits; words
//! drawn by ChaCha8 from seed 0):
//!
//! * `big_integers/product/{dashu,ntt,ntt_transformed}` — a product of two such numbers by
//!   `dashu`'s Toom–Cook multiplication, by `algebra::ntt::mul` (number-theoretic transforms),
//!   and by `algebra::ntt::Transformed::mul` with one factor transformed beforehand (as the
//!   modulus and the reciprocal of a Barrett reduction are).
//! * `big_integers/decimal/{malachite,radix}` — the decimal text of one such number (36,000
//!   digits) by `malachite`'s conversion and by `algebra::radix::DecimalPowers::text` with its
//!   table of powers built beforehand (as it is once for all the values of a report).
//!
//! Run with `cargo bench --bench big_integers`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use dashu_int::UBig;
use num_bigint::BigInt;
use rand::{Rng, SeedableRng};
use truecost::algebra::ntt::{self, Transformed};
use truecost::algebra::radix::DecimalPowers;

const WORDS: usize = 1_875;

fn words(rng: &mut rand_chacha::ChaCha8Rng) -> Vec<u64> {
    (0..WORDS).map(|_| rng.next_u64()).collect()
}

fn bench(c: &mut Criterion) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
    let (a, b) = (
        UBig::from_words(&words(&mut rng)),
        UBig::from_words(&words(&mut rng)),
    );
    let mut group = c.benchmark_group("big_integers");
    group.bench_function("product/dashu", |t| {
        t.iter(|| black_box(&a) * black_box(&b))
    });
    group.bench_function("product/ntt", |t| {
        t.iter(|| ntt::mul(black_box(&a), black_box(&b)))
    });
    let transformed = Transformed::new(&a, WORDS);
    group.bench_function("product/ntt_transformed", |t| {
        t.iter(|| transformed.mul(black_box(&b)))
    });
    let x = BigInt::from_bytes_le(num_bigint::Sign::Plus, &a.to_le_bytes());
    let natural = malachite_nz::natural::Natural::from_limbs_asc(a.as_words());
    group.bench_function("decimal/malachite", |t| {
        t.iter(|| black_box(&natural).to_string())
    });
    let powers = DecimalPowers::new(64 * WORDS as u64);
    group.bench_function("decimal/radix", |t| t.iter(|| powers.text(black_box(&x))));
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
