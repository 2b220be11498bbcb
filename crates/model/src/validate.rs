//! Field-by-field validation with errors that name the field and the allowed range.

use crate::{Config, ConfigError};

fn finite(field: &str, v: f64) -> Result<f64, ConfigError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ConfigError::NotFinite { field: field.to_string(), value: v })
    }
}

fn positive(field: &str, v: f64) -> Result<(), ConfigError> {
    if finite(field, v)? > 0.0 {
        Ok(())
    } else {
        Err(range(field, v, "> 0"))
    }
}

fn non_negative(field: &str, v: f64) -> Result<(), ConfigError> {
    if finite(field, v)? >= 0.0 {
        Ok(())
    } else {
        Err(range(field, v, ">= 0"))
    }
}

fn within(field: &str, v: f64, lo: f64, hi: f64) -> Result<(), ConfigError> {
    let v = finite(field, v)?;
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(range(field, v, &format!("in [{lo}, {hi}]")))
    }
}

fn range(field: &str, v: impl ToString, allowed: &str) -> ConfigError {
    ConfigError::OutOfRange { field: field.to_string(), value: v.to_string(), allowed: allowed.to_string() }
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
        positive("wing.rho", w.rho)?;
        finite("wing.rho_xc", w.rho_xc)?;
        positive("wing.ei", w.ei)?;
        positive("wing.gj", w.gj)?;
        positive("wing.ip", w.ip)?;
        finite("wing.x_ac", w.x_ac)?;
        within("wing.xi", w.xi, 0.0, 1e3)?;
        if w.rho * w.ip <= w.rho_xc * w.rho_xc {
            return Err(ConfigError::Inconsistent {
                fields: "wing.rho, wing.ip, wing.rho_xc".into(),
                reason: format!(
                    "the mass matrix [[ρ, −ρx_c], [−ρx_c, I_p]] must be positive definite: need ρ·I_p > (ρx_c)², got {} <= {}",
                    w.rho * w.ip,
                    w.rho_xc * w.rho_xc
                ),
            });
        }

        let c = &self.control;
        non_negative("control.k1", c.k1)?;
        non_negative("control.k2", c.k2)?;
        non_negative("control.a", c.a)?;
        non_negative("control.b", c.b)?;

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
        finite("observer.nu1_0", o.nu1_0)?;
        finite("observer.nu2_0", o.nu2_0)?;

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
        if !(2..=2001).contains(&h.field_points) {
            return Err(range("horizon.field_points", h.field_points, "an integer in [2, 2001]"));
        }
        let steps = h.t_end / disc.dt;
        if steps > 1e9 {
            return Err(range("discretisation.dt", disc.dt, &format!(">= t_end / 1e9 = {}", h.t_end / 1e9)));
        }
        Ok(())
    }
}
