//! The hash of the graph's interning table and of the cache of programs: the multiply-rotate hash of
//! the Rust compiler's own tables (FxHash). Keys are instructions of a few words and programs of
//! such instructions, built by the engine, not by an adversary, and SipHash, the standard library's
//! default, took 40 % of the set-up of a run's derivatives.

use std::hash::{BuildHasherDefault, Hasher};

/// FxHash: per word, rotate, xor the word in, multiply.
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct FxHasher(u64);

/// The multiplier of FxHash (64 bits).
const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl FxHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(SEED);
    }
}

impl Hasher for FxHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(word));
        }
    }

    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(u64::from(i));
    }

    #[inline]
    fn write_u16(&mut self, i: u16) {
        self.add(u64::from(i));
    }

    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
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
        self.0
    }
}

/// A `HashMap` with [`FxHasher`].
pub(crate) type FxHashMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<FxHasher>>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::{BuildHasher, Hash};

    #[test]
    fn equal_keys_hash_alike_and_near_keys_apart() {
        let hash = |x: &dyn Fn(&mut FxHasher)| {
            let mut h = BuildHasherDefault::<FxHasher>::default().build_hasher();
            x(&mut h);
            h.finish()
        };
        let a = hash(&|h| (3u32, 7u64).hash(h));
        assert_eq!(a, hash(&|h| (3u32, 7u64).hash(h)));
        assert_ne!(a, hash(&|h| (3u32, 8u64).hash(h)));
        assert_ne!(a, hash(&|h| (7u64, 3u32).hash(h)));
        let mut map: FxHashMap<u64, usize> = FxHashMap::default();
        for i in 0..1000u64 {
            map.insert(i * 1024, i as usize);
        }
        assert!((0..1000u64).all(|i| map[&(i * 1024)] == i as usize));
    }
}
