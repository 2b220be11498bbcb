//! The one explicit ODE step of the claims: classical fourth-order Runge–Kutta for a scalar
//! y' = f(t, y), used by the Filippov reaching time (in σ and in time) and by Lemma 3's
//! independent check.

/// One RK4 step of y' = f(t, y) from (t, y) with step h, given the first slope k1 = f(t, y)
/// (callers that needed it for their step size pass it in); `None` where f has no value at a
/// stage (a caller's signal that the step leaves its domain).
pub fn rk4_step_with(f: impl Fn(f64, f64) -> Option<f64>, t: f64, y: f64, h: f64, k1: f64) -> Option<f64> {
    let k2 = f(t + 0.5 * h, y + 0.5 * h * k1)?;
    let k3 = f(t + 0.5 * h, y + 0.5 * h * k2)?;
    let k4 = f(t + h, y + h * k3)?;
    Some(y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4))
}

/// One RK4 step of y' = f(t, y) from (t, y) with step h ([`rk4_step_with`] with k1 = f(t, y)).
pub fn rk4_step(f: impl Fn(f64, f64) -> Option<f64>, t: f64, y: f64, h: f64) -> Option<f64> {
    let k1 = f(t, y)?;
    rk4_step_with(f, t, y, h, k1)
}

#[cfg(test)]
mod tests {
    use super::rk4_step;

    /// Fourth order: y' = y from y(0) = 1 to t = 1 (exact e); halving h cuts the error by 2⁴
    /// (between 14 and 18 here), and a stage outside f's domain ends the step with `None`.
    #[test]
    fn rk4_is_fourth_order_and_stops_outside_the_domain() {
        let error = |n: usize| {
            let h = 1.0 / n as f64;
            let y = (0..n).fold(1.0, |y, i| rk4_step(|_, y| Some(y), i as f64 * h, y, h).unwrap());
            (y - 1f64.exp()).abs()
        };
        let ratio = error(8) / error(16);
        assert!((14.0..18.0).contains(&ratio), "{ratio}");
        assert!(rk4_step(|t, _| (t < 0.75).then_some(1.0), 0.0, 0.0, 1.0).is_none());
    }
}
