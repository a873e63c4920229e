//! `--shard i/n`: the points one shard of a sweep runs.

use crate::error::{Error, Result};
/// Shard selector `i/n`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, 0-based.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// Parse `i/n` with 0 ≤ i < n.
    pub fn parse(s: &str) -> Result<Self> {
        let bad = || Error::invalid("--shard", s, "expected i/n with 0 ≤ i < n (e.g. 0/4)");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// Whether this shard runs point `i`.
    pub fn owns(&self, i: usize) -> bool {
        i % self.count == self.index
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn shards_partition_the_grid() {
        let s: Vec<Shard> = (0..3)
            .map(|i| Shard::parse(&format!("{i}/3")).unwrap())
            .collect();
        for i in 0..20 {
            assert_eq!(s.iter().filter(|sh| sh.owns(i)).count(), 1);
        }
        assert!(Shard::parse("3/3").is_err() && Shard::parse("1").is_err());
    }
}
