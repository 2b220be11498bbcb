//! A number with its estimated error, and the Richardson/Romberg extrapolation that produces
//! most of them. One definition, used by the converged modes and the trajectory estimates.

pub use wingcheck_model::Estimate;

/// Romberg table of values u_k on meshes h_k = h_0/2^k (coarse → fine), for an error
/// expansion u_h = u + c_1 h^{p_1} + c_2 h^{p_2} + …, with `exponents` = [p_1, p_2, …].
/// Returns the table rows: row k holds T[k][0..=min(k, exponents.len())].
pub fn romberg_table(values: &[f64], exponents: &[f64]) -> Vec<Vec<f64>> {
    let mut table: Vec<Vec<f64>> = Vec::with_capacity(values.len());
    for (k, &v) in values.iter().enumerate() {
        let mut row = vec![v];
        for j in 1..=k.min(exponents.len()) {
            let f = 2f64.powf(exponents[j - 1]);
            let prev = table[k - 1][j - 1];
            let cur = row[j - 1];
            row.push(cur + (cur - prev) / (f - 1.0));
        }
        table.push(row);
    }
    table
}

/// Observed order log2(|u_0 − u_1| / |u_1 − u_2|) of three values on halved meshes (None if
/// the differences are zero).
pub fn observed_order(u0: f64, u1: f64, u2: f64) -> Option<f64> {
    let (d0, d1) = ((u0 - u1).abs(), (u1 - u2).abs());
    (d0 > 0.0 && d1 > 0.0).then(|| (d0 / d1).log2())
}
