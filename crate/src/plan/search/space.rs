//! The state registry: every generated state stored once, packed, in one arena, with an
//! open-addressing hash index (`id ↦ words[id·w .. (id+1)·w]`).

/// States packed `w` words each in one `Vec<u64>`, deduplicated by a hash index.
#[derive(Clone, Debug)]
pub(crate) struct StateSpace {
    w: usize,
    data: Vec<u64>,
    /// Open addressing table of state ids (`u32::MAX` = empty), size a power of two.
    table: Vec<u32>,
    len: usize,
}

const EMPTY: u32 = u32::MAX;

#[inline]
fn hash(words: &[u64]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ words.len() as u64;
    for &x in words {
        h = (h.rotate_left(5) ^ x).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    h ^ (h >> 29)
}

impl StateSpace {
    /// An empty registry for states of `w` words.
    pub fn new(w: usize) -> Self {
        StateSpace {
            w,
            data: Vec::new(),
            table: vec![EMPTY; 1024],
            len: 0,
        }
    }

    /// Number of registered states.
    pub fn len(&self) -> usize {
        self.len
    }

    /// The words of state `id`.
    #[inline]
    pub fn get(&self, id: u32) -> &[u64] {
        let i = id as usize * self.w;
        &self.data[i..i + self.w]
    }

    /// Registers `words`; returns its id and whether it is new.
    pub fn insert(&mut self, words: &[u64]) -> (u32, bool) {
        debug_assert_eq!(words.len(), self.w);
        if (self.len + 1) * 4 > self.table.len() * 3 {
            self.grow();
        }
        let mask = self.table.len() - 1;
        let mut i = hash(words) as usize & mask;
        loop {
            let id = self.table[i];
            if id == EMPTY {
                let id = self.len as u32;
                self.table[i] = id;
                self.data.extend_from_slice(words);
                self.len += 1;
                return (id, true);
            }
            if self.get(id) == words {
                return (id, false);
            }
            i = (i + 1) & mask;
        }
    }

    fn grow(&mut self) {
        let size = self.table.len() * 2;
        let mask = size - 1;
        let mut table = vec![EMPTY; size];
        for id in 0..self.len as u32 {
            let mut i = hash(self.get(id)) as usize & mask;
            while table[i] != EMPTY {
                i = (i + 1) & mask;
            }
            table[i] = id;
        }
        self.table = table;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dedups_and_grows() {
        let mut s = StateSpace::new(2);
        for i in 0..5000u64 {
            assert_eq!(s.insert(&[i, i * 7]), (i as u32, true));
        }
        for i in 0..5000u64 {
            assert_eq!(s.insert(&[i, i * 7]), (i as u32, false));
            assert_eq!(s.get(i as u32), &[i, i * 7]);
        }
        assert_eq!(s.len(), 5000);
    }
}
