//! A fast hasher for the mesher's internal tables, whose keys are small integer ids
//! (vertex ids, sorted edge and triangle keys) made by the mesher itself.
//!
//! The standard library's SipHash resists hash flooding, which these tables do not need (no
//! key comes from outside), and it cost a tenth of the 3D refinement time. This is a
//! multiply-rotate hash in the style of FxHash: a few cycles per word, good high bits for
//! hashbrown's tags.

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// A `HashMap` with [`FastHasher`].
pub(crate) type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;

/// A `HashSet` with [`FastHasher`].
pub(crate) type FastSet<K> = HashSet<K, BuildHasherDefault<FastHasher>>;

/// Multiply-rotate hasher for integer keys (not for untrusted input).
#[derive(Default, Clone, Copy)]
pub(crate) struct FastHasher {
    h: u64,
}

/// An odd constant with well-mixed bits (2^64 / golden ratio).
const K: u64 = 0x9E37_79B9_7F4A_7C15;

impl FastHasher {
    #[inline]
    fn add(&mut self, w: u64) {
        self.h = (self.h.rotate_left(5) ^ w).wrapping_mul(K);
    }
}

impl Hasher for FastHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            self.add(u64::from_le_bytes(c.try_into().unwrap_or([0; 8])));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut w = [0u8; 8];
            w[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(w));
        }
    }
    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(i as u64);
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(i as u64);
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }
    #[inline]
    fn finish(&self) -> u64 {
        // hashbrown takes its 7-bit tag from the top bits and the bucket from the low bits;
        // one more multiply-xorshift spreads both.
        let h = self.h ^ (self.h >> 29);
        h.wrapping_mul(K) ^ (h >> 32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_works_and_spreads_keys() {
        let mut m: FastMap<[u32; 3], u32> = FastMap::default();
        for i in 0..10_000u32 {
            m.insert([i, i + 1, i + 2], i);
        }
        assert_eq!(m.len(), 10_000);
        assert_eq!(m.get(&[5, 6, 7]), Some(&5));
        assert_eq!(m.get(&[5, 6, 8]), None);
        // Consecutive keys must not collide in the low bits (bucket index).
        let buckets: FastSet<u64> = (0..4096u64)
            .map(|i| {
                let mut h = FastHasher::default();
                h.write_u64(i << 32 | (i + 1));
                h.finish() & 4095
            })
            .collect();
        assert!(
            buckets.len() > 2000,
            "{} distinct buckets of 4096",
            buckets.len()
        );
    }
}
