//! Element values recovered at the nodes: each element's value at its node, averaged over the
//! elements sharing the node (the usual unweighted nodal average of a discontinuous field, such
//! as the stress of a displacement-based element).

/// The average at each of `nodes` nodes of the values `samples` (a node and one element's value
/// there); 0 at a node that no sample reaches.
pub fn average<const C: usize>(
    nodes: usize,
    samples: impl IntoIterator<Item = (usize, [f64; C])>,
) -> Vec<[f64; C]> {
    let mut sum = vec![[0.0; C]; nodes];
    let mut count = vec![0u32; nodes];
    for (n, value) in samples {
        (0..C).for_each(|c| sum[n][c] += value[c]);
        count[n] += 1;
    }
    sum.iter()
        .zip(&count)
        .map(|(s, &c)| s.map(|v| v / f64::from(c.max(1))))
        .collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn averages_the_samples_at_each_node() {
        let nodal = super::average(3, [(0, [1.0, 2.0]), (0, [3.0, 4.0]), (2, [5.0, -1.0])]);
        assert_eq!(nodal, vec![[2.0, 3.0], [0.0, 0.0], [5.0, -1.0]]);
    }
}
