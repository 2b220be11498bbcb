//! Field-by-field validation with errors that name the field and the allowed range.

use crate::{format_number, Config, ConfigError};

/// Largest magnitude of a physical parameter (ρ, ρx_c, EI, GJ, I_p, gains, weights): products
/// of a few of them stay far from f64 overflow. SI-scale wings (EI ~ 1e7) are well inside.
pub const MAX_MAGNITUDE: f64 = 1e12;
/// Smallest positive physical parameter (ρ, EI, GJ, I_p).
pub const MIN_POSITIVE: f64 = 1e-12;

fn finite(field: &str, v: f64) -> Result<f64, ConfigError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ConfigError::NotFinite { field: field.to_string(), value: format!("{v}") })
    }
}

fn within(field: &str, v: f64, lo: f64, hi: f64) -> Result<(), ConfigError> {
    let v = finite(field, v)?;
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(range(field, v, &format!("in [{}, {}]", format_number(lo), format_number(hi))))
    }
}

fn range(field: &str, v: impl Into<Shown>, allowed: &str) -> ConfigError {
    ConfigError::OutOfRange { field: field.to_string(), value: v.into().0, allowed: allowed.to_string() }
}

/// A value as shown in messages: floats in [`format_number`]'s short form.
struct Shown(String);

impl From<f64> for Shown {
    fn from(x: f64) -> Self {
        Shown(format_number(x))
    }
}

impl From<usize> for Shown {
    fn from(x: usize) -> Self {
        Shown(x.to_string())
    }
}

impl From<u32> for Shown {
    fn from(x: u32) -> Self {
        Shown(x.to_string())
    }
}

fn exponent_pair(lo_name: &str, hi_name: &str, lo: u32, hi: u32) -> Result<(), ConfigError> {
    for (name, v) in [(lo_name, lo), (hi_name, hi)] {
        if v % 2 == 0 || v > 999 {
            return Err(range(name, v, "an odd integer in [1, 999]"));
        }
    }
    if !(lo < hi && hi < 2 * lo) {
        return Err(ConfigError::Inconsistent {
            fields: format!("{lo_name}, {hi_name}"),
            reason: format!("need {lo_name} < {hi_name} < 2·{lo_name} (paper, after (21)); got {lo} and {hi}"),
        });
    }
    Ok(())
}

fn whole_multiple(ratio: f64) -> bool {
    (ratio - ratio.round()).abs() <= 1e-6 * ratio.max(1.0) && ratio.round() >= 1.0
}

impl Config {
    /// Check every field; the first violation is returned.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let w = &self.wing;
        within("wing.span", w.span, 1e-6, 1e6)?;
        for (name, v) in [("wing.rho", w.rho), ("wing.ei", w.ei), ("wing.gj", w.gj), ("wing.ip", w.ip)] {
            within(name, v, MIN_POSITIVE, MAX_MAGNITUDE)?;
        }
        within("wing.rho_xc", w.rho_xc, -MAX_MAGNITUDE, MAX_MAGNITUDE)?;
        within("wing.x_ac", w.x_ac, -1e6, 1e6)?;
        within("wing.xi", w.xi, 0.0, 1e3)?;
        if w.rho * w.ip <= w.rho_xc * w.rho_xc {
            return Err(ConfigError::Inconsistent {
                fields: "wing.rho, wing.ip, wing.rho_xc".into(),
                reason: format!(
                    "the mass matrix [[ρ, −ρx_c], [−ρx_c, I_p]] must be positive definite: need ρ·I_p > (ρx_c)², got {} <= {}",
                    format_number(w.rho * w.ip),
                    format_number(w.rho_xc * w.rho_xc)
                ),
            });
        }

        let c = &self.control;
        for (name, v) in [("control.k1", c.k1), ("control.k2", c.k2), ("control.a", c.a), ("control.b", c.b)] {
            within(name, v, 0.0, MAX_MAGNITUDE)?;
        }

        let o = &self.observer;
        within("observer.sample_period", o.sample_period, 1e-7, 0.1)?;
        for (name, v) in [
            ("observer.kappa1", o.kappa1),
            ("observer.kappa2", o.kappa2),
            ("observer.kappa3", o.kappa3),
            ("observer.kappa4", o.kappa4),
            ("observer.kappa5", o.kappa5),
            ("observer.kappa6", o.kappa6),
        ] {
            within(name, v, 0.0, 1e6)?;
        }
        // the reaching-time bounds (38), (39) divide by the linear and fractional gains
        for (name, v) in [
            ("observer.kappa1", o.kappa1),
            ("observer.kappa3", o.kappa3),
            ("observer.kappa4", o.kappa4),
            ("observer.kappa6", o.kappa6),
        ] {
            if v <= 0.0 {
                return Err(range(name, v, "> 0 (the reaching-time bound (38)/(39) divides by it) and ≤ 1e6"));
            }
        }
        exponent_pair("observer.a1", "observer.a2", o.a1, o.a2)?;
        exponent_pair("observer.b1", "observer.b2", o.b1, o.b2)?;
        within("observer.nu1_0", o.nu1_0, -MAX_MAGNITUDE, MAX_MAGNITUDE)?;
        within("observer.nu2_0", o.nu2_0, -MAX_MAGNITUDE, MAX_MAGNITUDE)?;

        let d = &self.disturbance;
        let g = &d.distributed;
        for (name, v) in [
            ("disturbance.distributed.mean", g.mean),
            ("disturbance.distributed.cos_amp", g.cos_amp),
            ("disturbance.distributed.cos_freq", g.cos_freq),
            ("disturbance.distributed.sin_amp", g.sin_amp),
            ("disturbance.distributed.sin_freq", g.sin_freq),
            ("disturbance.distributed.slope", g.slope),
            ("disturbance.tip_bending.mean", d.tip_bending.mean),
            ("disturbance.tip_bending.amp", d.tip_bending.amp),
            ("disturbance.tip_bending.freq", d.tip_bending.freq),
            ("disturbance.tip_torsion.mean", d.tip_torsion.mean),
            ("disturbance.tip_torsion.amp", d.tip_torsion.amp),
            ("disturbance.tip_torsion.freq", d.tip_torsion.freq),
        ] {
            within(name, v, -1e6, 1e6)?;
        }

        within("initial.q_tip", self.initial.q_tip, -1e3, 1e3)?;
        within("initial.theta_tip", self.initial.theta_tip, -1e3, 1e3)?;

        let disc = &self.discretisation;
        if !(2..=4000).contains(&disc.elements) {
            return Err(range("discretisation.elements", disc.elements, "an integer in [2, 4000]"));
        }
        within("discretisation.dt", disc.dt, 1e-9, o.sample_period)?;
        within("discretisation.grading", disc.grading, 0.0, 0.9)?;
        if !(2..=4000).contains(&disc.fd_points) {
            return Err(range("discretisation.fd_points", disc.fd_points, "an integer in [2, 4000]"));
        }
        if disc.method == crate::Method::Fd && disc.grading != 0.0 {
            return Err(ConfigError::Inconsistent {
                fields: "discretisation.grading, discretisation.method".into(),
                reason: format!(
                    "discretisation.grading = {} is implemented for method fe only; the fd grid is uniform: set discretisation.grading=0",
                    disc.grading
                ),
            });
        }

        if disc.stepper == crate::TimeScheme::Exponential && disc.basis == crate::StepBasis::Nodal {
            return Err(ConfigError::Inconsistent {
                fields: "discretisation.stepper, discretisation.basis".into(),
                reason: "discretisation.stepper = exponential steps the closed loop in its modal basis: \
                         set discretisation.basis to modal or auto"
                    .into(),
            });
        }
        if !whole_multiple(o.sample_period / disc.dt) {
            return Err(ConfigError::Inconsistent {
                fields: "observer.sample_period, discretisation.dt".into(),
                reason: format!(
                    "the observer sample period must be a whole multiple of the time step; got {} / {} = {}",
                    o.sample_period,
                    disc.dt,
                    o.sample_period / disc.dt
                ),
            });
        }

        let h = &self.horizon;
        within("horizon.t_end", h.t_end, o.sample_period, 1e5)?;
        if !whole_multiple(h.t_end / o.sample_period) {
            return Err(ConfigError::Inconsistent {
                fields: "horizon.t_end, observer.sample_period".into(),
                reason: format!(
                    "t_end must be a whole number of sample periods; got {} / {}",
                    h.t_end, o.sample_period
                ),
            });
        }
        within("horizon.sample_every", h.sample_every, o.sample_period, h.t_end)?;
        let per = h.sample_every / o.sample_period;
        if !whole_multiple(per) {
            let (lo, hi) = (per.floor().max(1.0) * o.sample_period, per.ceil().max(1.0) * o.sample_period);
            return Err(ConfigError::Inconsistent {
                fields: "horizon.sample_every, observer.sample_period".into(),
                reason: format!(
                    "horizon.sample_every = {} is not a whole multiple of observer.sample_period = {} \
                     (outputs are taken at observer samples): allowed k × {}, k = 1, 2, …; the nearest are {} and {}",
                    format_number(h.sample_every),
                    format_number(o.sample_period),
                    format_number(o.sample_period),
                    format_number(lo),
                    format_number(hi)
                ),
            });
        }
        if !(2..=2001).contains(&h.field_points) {
            return Err(range("horizon.field_points", h.field_points, "an integer in [2, 2001]"));
        }
        let steps = h.t_end / disc.dt;
        if steps > 1e9 {
            return Err(range(
                "discretisation.dt",
                disc.dt,
                &format!(">= t_end / 1e9 = {}", format_number(h.t_end / 1e9)),
            ));
        }
        Ok(())
    }
}
