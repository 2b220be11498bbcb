//! Field-by-field validation with errors that name the field and the allowed range.

use crate::bounds::{DT_MIN, FIELD_BOUNDS, T_END_MAX};
use crate::{format_number, Config, ConfigError};

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

/// The number at `path` of the configuration as JSON.
fn number_at(v: &serde_json::Value, path: &str) -> f64 {
    path.split('.').fold(v, |node, key| &node[key]).as_f64().unwrap_or_else(|| panic!("{path} is not a number"))
}

/// Every key's own range ([`FIELD_BOUNDS`], also stated by the config schema).
fn field_bounds(cfg: &Config) -> Result<(), ConfigError> {
    let v = serde_json::to_value(cfg).expect("config serialises");
    for b in FIELD_BOUNDS {
        let x = number_at(&v, b.path);
        finite(b.path, x)?;
        if !b.admits(x) {
            return Err(range(b.path, x, &b.allowed()));
        }
    }
    Ok(())
}

fn exponent_pair(lo_name: &str, hi_name: &str, lo: u32, hi: u32) -> Result<(), ConfigError> {
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
        field_bounds(self)?;
        let w = &self.wing;
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

        let o = &self.observer;
        exponent_pair("observer.a1", "observer.a2", o.a1, o.a2)?;
        exponent_pair("observer.b1", "observer.b2", o.b1, o.b2)?;
        let disc = &self.discretisation;
        within("discretisation.dt", disc.dt, DT_MIN, o.sample_period)?;
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
        within("horizon.t_end", h.t_end, o.sample_period, T_END_MAX)?;
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
