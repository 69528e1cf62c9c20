//! SHA-256 (FIPS 180-4), so that a certificate names the exact problem it is about without a
//! hashing dependency in the checker's trusted base.
//!
//! [`compress_portable`] is the specification's compression function, line for line. On
//! x86-64 processors with the SHA extensions (`sha`, with `ssse3` and `sse4.1`; detected when
//! the program runs) the blocks go through the processor's SHA-256 round instructions instead
//! ([`x86::compress_blocks`], about fifteen times faster: hashing a problem file of a
//! 10⁴-state grid takes well under a millisecond). The unit tests check both against FIPS
//! 180-4's examples and against each other, and the dispatching hasher against an independent
//! implementation (the `sha2` crate) on random inputs cut at random places.

/// The round constants: the first 32 bits of the fractional parts of the cube roots of the
/// first 64 primes (FIPS 180-4, §4.2.2).
const K: [u32; 64] = [
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2,
];

/// The initial hash value (FIPS 180-4, §5.3.3).
const H0: [u32; 8] = [
    0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19,
];

/// One 64-byte block into the state (FIPS 180-4, §6.2.2).
fn compress_portable(state: &mut [u32; 8], block: &[u8; 64]) {
    let mut w = [0u32; 64];
    for (t, word) in block.chunks_exact(4).enumerate() {
        w[t] = u32::from_be_bytes([word[0], word[1], word[2], word[3]]);
    }
    for t in 16..64 {
        let s0 = w[t - 15].rotate_right(7) ^ w[t - 15].rotate_right(18) ^ (w[t - 15] >> 3);
        let s1 = w[t - 2].rotate_right(17) ^ w[t - 2].rotate_right(19) ^ (w[t - 2] >> 10);
        w[t] = w[t - 16]
            .wrapping_add(s0)
            .wrapping_add(w[t - 7])
            .wrapping_add(s1);
    }
    let [mut a, mut b, mut c, mut d, mut e, mut f, mut g, mut h] = *state;
    for t in 0..64 {
        let s1 = e.rotate_right(6) ^ e.rotate_right(11) ^ e.rotate_right(25);
        let ch = (e & f) ^ (!e & g);
        let t1 = h
            .wrapping_add(s1)
            .wrapping_add(ch)
            .wrapping_add(K[t])
            .wrapping_add(w[t]);
        let s0 = a.rotate_right(2) ^ a.rotate_right(13) ^ a.rotate_right(22);
        let maj = (a & b) ^ (a & c) ^ (b & c);
        let t2 = s0.wrapping_add(maj);
        h = g;
        g = f;
        f = e;
        e = d.wrapping_add(t1);
        d = c;
        c = b;
        b = a;
        a = t1.wrapping_add(t2);
    }
    for (s, v) in state.iter_mut().zip([a, b, c, d, e, f, g, h]) {
        *s = s.wrapping_add(v);
    }
}

/// The blocks of `blocks` (a multiple of 64 bytes) into the state, in order.
fn compress_blocks(state: &mut [u32; 8], blocks: &[u8]) {
    debug_assert_eq!(blocks.len() % 64, 0);
    #[cfg(target_arch = "x86_64")]
    if x86::available() {
        x86::compress_blocks(state, blocks);
        return;
    }
    for block in blocks.chunks_exact(64) {
        compress_portable(state, block.try_into().expect("64 bytes"));
    }
}

/// The compression function on the processor's SHA-256 instructions (Intel's SHA extensions,
/// also on AMD processors since Zen): `sha256rnds2` does two rounds of §6.2.2 step 3 on the
/// working variables held as the pairs `(a, b, e, f)` and `(c, d, g, h)`, `sha256msg1` and
/// `sha256msg2` the message schedule of step 1 four words at a time.
#[cfg(target_arch = "x86_64")]
mod x86 {
    use std::arch::x86_64::{
        __m128i, _mm_add_epi32, _mm_alignr_epi8, _mm_blend_epi16, _mm_loadu_si128, _mm_set_epi64x,
        _mm_sha256msg1_epu32, _mm_sha256msg2_epu32, _mm_sha256rnds2_epu32, _mm_shuffle_epi32,
        _mm_shuffle_epi8, _mm_storeu_si128,
    };

    /// Whether this processor has the instructions [`compress_blocks`] uses.
    pub(super) fn available() -> bool {
        std::arch::is_x86_feature_detected!("sha")
            && std::arch::is_x86_feature_detected!("ssse3")
            && std::arch::is_x86_feature_detected!("sse4.1")
    }

    /// [`super::compress_portable`] on every 64-byte block of `blocks`, in order. Only called
    /// when [`available`].
    pub(super) fn compress_blocks(state: &mut [u32; 8], blocks: &[u8]) {
        assert!(available() && blocks.len().is_multiple_of(64));
        // SAFETY: the processor has the target features `blocks_ni` is compiled for (checked
        // just above).
        unsafe { blocks_ni(state, blocks) }
    }

    /// The message words `w[t..t + 4]` of the schedule (§6.2.2 step 1) from the previous
    /// sixteen, `w0 = w[t − 16..t − 12]` … `w3 = w[t − 4..t]`.
    #[target_feature(enable = "sha,ssse3,sse4.1")]
    fn schedule(w0: __m128i, w1: __m128i, w2: __m128i, w3: __m128i) -> __m128i {
        let t1 = _mm_sha256msg1_epu32(w0, w1);
        let t2 = _mm_alignr_epi8(w3, w2, 4);
        _mm_sha256msg2_epu32(_mm_add_epi32(t1, t2), w3)
    }

    /// Rounds `4i..4i + 4` with the message words `w = w[4i..4i + 4]`.
    #[target_feature(enable = "sha,ssse3,sse4.1")]
    fn rounds4(abef: &mut __m128i, cdgh: &mut __m128i, w: __m128i, i: usize) {
        let k: &[u32; 4] = super::K[4 * i..4 * i + 4]
            .try_into()
            .expect("four constants");
        // SAFETY: an unaligned load of the 16 bytes of `k`.
        let wk = _mm_add_epi32(w, unsafe { _mm_loadu_si128(k.as_ptr().cast()) });
        *cdgh = _mm_sha256rnds2_epu32(*cdgh, *abef, wk);
        *abef = _mm_sha256rnds2_epu32(*abef, *cdgh, _mm_shuffle_epi32(wk, 0x0e));
    }

    #[target_feature(enable = "sha,ssse3,sse4.1")]
    fn blocks_ni(state: &mut [u32; 8], blocks: &[u8]) {
        // Big-endian words: reverse the bytes of each 32-bit lane.
        let swap = _mm_set_epi64x(0x0c0d_0e0f_0809_0a0b, 0x0405_0607_0001_0203);
        // SAFETY: unaligned loads of the two halves of `state` (32 bytes).
        let (dcba, hgfe) = unsafe {
            let p = state.as_ptr().cast::<__m128i>();
            (_mm_loadu_si128(p), _mm_loadu_si128(p.add(1)))
        };
        let cdab = _mm_shuffle_epi32(dcba, 0xb1);
        let efgh = _mm_shuffle_epi32(hgfe, 0x1b);
        let mut abef = _mm_alignr_epi8(cdab, efgh, 8);
        let mut cdgh = _mm_blend_epi16(efgh, cdab, 0xf0);
        for block in blocks.chunks_exact(64) {
            let (abef_in, cdgh_in) = (abef, cdgh);
            // SAFETY: unaligned loads of the block's four 16-byte quarters (64 bytes).
            let mut w: [__m128i; 4] = std::array::from_fn(|j| unsafe {
                _mm_shuffle_epi8(
                    _mm_loadu_si128(block.as_ptr().cast::<__m128i>().add(j)),
                    swap,
                )
            });
            for (i, &wi) in w.iter().enumerate() {
                rounds4(&mut abef, &mut cdgh, wi, i);
            }
            for i in 4..16 {
                let next = schedule(w[i % 4], w[(i + 1) % 4], w[(i + 2) % 4], w[(i + 3) % 4]);
                w[i % 4] = next;
                rounds4(&mut abef, &mut cdgh, next, i);
            }
            abef = _mm_add_epi32(abef, abef_in);
            cdgh = _mm_add_epi32(cdgh, cdgh_in);
        }
        let feba = _mm_shuffle_epi32(abef, 0x1b);
        let dchg = _mm_shuffle_epi32(cdgh, 0xb1);
        // SAFETY: unaligned stores into the two halves of `state` (32 bytes).
        unsafe {
            let p = state.as_mut_ptr().cast::<__m128i>();
            _mm_storeu_si128(p, _mm_blend_epi16(feba, dchg, 0xf0));
            _mm_storeu_si128(p.add(1), _mm_alignr_epi8(dchg, feba, 8));
        }
    }
}

/// SHA-256 of a message given in pieces ([`update`](Self::update) or [`std::io::Write`]): the
/// same digest as [`sha256_hex`] of the pieces joined, without joining them.
#[derive(Clone, Debug)]
pub struct Sha256 {
    state: [u32; 8],
    /// The bytes of the current block not yet compressed (`pending < 64` of them).
    block: [u8; 64],
    pending: usize,
    /// The message length in bytes so far.
    length: u64,
}

impl Default for Sha256 {
    fn default() -> Self {
        Sha256 {
            state: H0,
            block: [0; 64],
            pending: 0,
            length: 0,
        }
    }
}

impl Sha256 {
    /// The hash of the empty message, ready for [`update`](Self::update).
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends `bytes` to the message.
    pub fn update(&mut self, mut bytes: &[u8]) {
        self.length = self.length.wrapping_add(bytes.len() as u64);
        if self.pending > 0 {
            let take = bytes.len().min(64 - self.pending);
            self.block[self.pending..self.pending + take].copy_from_slice(&bytes[..take]);
            self.pending += take;
            bytes = &bytes[take..];
            if self.pending < 64 {
                return;
            }
            let block = self.block;
            compress_blocks(&mut self.state, &block);
            self.pending = 0;
        }
        let whole = bytes.len() - bytes.len() % 64;
        compress_blocks(&mut self.state, &bytes[..whole]);
        let rest = &bytes[whole..];
        self.block[..rest.len()].copy_from_slice(rest);
        self.pending = rest.len();
    }

    /// The digest as 64 lowercase hexadecimal digits, after the padding (§5.1.1): a 1 bit,
    /// zeros, and the message length in bits as 64 bits.
    pub fn finish_hex(mut self) -> String {
        let bits = self.length.wrapping_mul(8);
        let mut tail = [0u8; 128];
        tail[..self.pending].copy_from_slice(&self.block[..self.pending]);
        tail[self.pending] = 0x80;
        let end = if self.pending < 56 { 64 } else { 128 };
        tail[end - 8..end].copy_from_slice(&bits.to_be_bytes());
        compress_blocks(&mut self.state, &tail[..end]);
        self.state
            .iter()
            .map(|word| format!("{word:08x}"))
            .collect()
    }
}

impl std::io::Write for Sha256 {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.update(bytes);
        Ok(bytes.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The SHA-256 digest of `bytes` as 64 lowercase hexadecimal digits.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let mut hash = Sha256::new();
    hash.update(bytes);
    hash.finish_hex()
}

#[cfg(test)]
mod tests {
    use super::{compress_blocks, compress_portable, sha256_hex, Sha256, H0};
    use rand::{Rng, RngExt, SeedableRng};

    // The examples of FIPS 180-4's appendix (NIST's published digests) and the empty message.
    #[test]
    fn nist_examples() {
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            sha256_hex(b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"
        );
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
    }

    // One million 'a's (FIPS 180-2's third example): many blocks, and padding in its own block.
    #[test]
    fn a_million_as() {
        assert_eq!(
            sha256_hex(&vec![b'a'; 1_000_000]),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"
        );
    }

    /// The digest by the portable compression function alone.
    fn portable_hex(bytes: &[u8]) -> String {
        let mut state = H0;
        let mut padded = bytes.to_vec();
        padded.push(0x80);
        while padded.len() % 64 != 56 {
            padded.push(0);
        }
        padded.extend_from_slice(&(bytes.len() as u64 * 8).to_be_bytes());
        for block in padded.chunks_exact(64) {
            compress_portable(&mut state, block.try_into().unwrap());
        }
        state.iter().map(|w| format!("{w:08x}")).collect()
    }

    /// `sha2`'s digest of `bytes`: an implementation written elsewhere.
    fn sha2_hex(bytes: &[u8]) -> String {
        use sha2::Digest;
        sha2::Sha256::digest(bytes)
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect()
    }

    #[test]
    fn the_portable_function_gives_the_nist_digests() {
        assert_eq!(
            portable_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            portable_hex(&vec![b'a'; 1_000_000]),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"
        );
    }

    /// Every length around the block and padding boundaries, then long random messages: the
    /// hasher (processor instructions where there are any), the portable function and `sha2`
    /// agree, whatever pieces the message is handed over in.
    #[test]
    fn pieces_paths_and_sha2_agree_on_random_messages() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(48);
        let mut lengths: Vec<usize> = (0..=200).collect();
        lengths.extend([1000, 4095, 4096, 4097, 65_536 + 7, 1 << 20]);
        for len in lengths {
            let bytes: Vec<u8> = (0..len).map(|_| rng.next_u32() as u8).collect();
            let expected = sha2_hex(&bytes);
            assert_eq!(sha256_hex(&bytes), expected, "length {len}");
            if len <= 4097 {
                assert_eq!(portable_hex(&bytes), expected, "length {len}");
            }
            let mut hash = Sha256::new();
            let mut rest = &bytes[..];
            while !rest.is_empty() {
                let cut = rng.random_range(0..=rest.len().min(150));
                hash.update(&rest[..cut]);
                rest = &rest[cut..];
            }
            assert_eq!(hash.finish_hex(), expected, "length {len} in pieces");
        }
    }

    /// The blocks as the hasher compresses them (on a processor with the SHA extensions, by
    /// its instructions) against the portable function, from random states.
    #[test]
    fn the_dispatched_compression_is_the_portable_one() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        for blocks in [1usize, 2, 3, 17] {
            for _ in 0..50 {
                let start: [u32; 8] = std::array::from_fn(|_| rng.next_u32());
                let bytes: Vec<u8> = (0..64 * blocks).map(|_| rng.next_u32() as u8).collect();
                let mut by_spec = start;
                for block in bytes.chunks_exact(64) {
                    compress_portable(&mut by_spec, block.try_into().unwrap());
                }
                let mut dispatched = start;
                compress_blocks(&mut dispatched, &bytes);
                assert_eq!(dispatched, by_spec);
            }
        }
    }
}
