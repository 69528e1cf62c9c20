//! Summary statistics over samples: the mean and the population standard deviation (`ddof = 0`,
//! as `numpy.std`, which the paper's tables use).

/// Mean and population standard deviation; `None` for no samples.
///
/// ```
/// use truecost::experiments::stats::mean_std;
/// assert_eq!(mean_std(&[1.0, 3.0]), Some((2.0, 1.0)));
/// assert_eq!(mean_std(&[]), None);
/// ```
pub fn mean_std(values: &[f64]) -> Option<(f64, f64)> {
    if values.is_empty() {
        return None;
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    Some((mean, var.sqrt()))
}

/// The mean of the present values (`None` if none is present).
///
/// ```
/// use truecost::experiments::stats::mean_of_present;
/// assert_eq!(mean_of_present(&[Some(2.0), None, Some(4.0)]), Some(3.0));
/// assert_eq!(mean_of_present(&[None]), None);
/// ```
pub fn mean_of_present(values: &[Option<f64>]) -> Option<f64> {
    let present: Vec<f64> = values.iter().flatten().copied().collect();
    mean_std(&present).map(|(m, _)| m)
}
