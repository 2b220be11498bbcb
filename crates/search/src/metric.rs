//! The search's metrics: one typed column per quantity of a point, with its unit and meaning
//! stated once. Chunks and result files store them as numbers in [`Metric::ALL`] order. A metric
//! has one name everywhere it is written — its column name, the short name with its unit suffix
//! (`rms_q_tip_m`, [`Metric::column`]): results.csv and results.json, `missing_metrics`,
//! best.json, the heatmap files. On input (`--best`) the short name (`rms_q_tip`) is accepted too.

use wingcheck_model::quantity::Unit;

/// One metric column of a search point, in output order ([`Metric::ALL`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Metric {
    /// λ2: min W/κ on the Galerkin space (N = 8), in J s per SI unit of κ (25).
    Lambda2,
    /// λ1: max W/κ on the Galerkin space (N = 8), in J s per SI unit of κ (25).
    Lambda1,
    /// max over the η's of min μ3..μ6 ((32) feasible iff > 0), in J per SI unit of κ (25).
    Lambda3Max,
    /// Decay rate λ = λ3/λ1 (1/s) at the η's minimising ε/λ.
    Lambda,
    /// ε of (32) at the η's minimising ε/λ, in J.
    Epsilon,
    /// Theorem 2's ultimate bound √(s³/λ2 · ε/λ) on |q| (m).
    UubBoundQ,
    /// Bound g_hmax on the distributed load used for ε (N/m).
    GHmax,
    /// ζ3 = sup |g̃1| of the point's FTDO run (N).
    Zeta3,
    /// ζ4 = sup |g̃2| of the point's FTDO run (N m).
    Zeta4,
    /// RMS of q(s,t) over the metric window (m).
    RmsQTip,
    /// max |q(s,t)| over the metric window (m).
    MaxQTip,
    /// RMS of θ(s,t) over the metric window (rad).
    RmsThetaTip,
    /// max |θ(s,t)| over the metric window (rad).
    MaxThetaTip,
    /// Joint 5 % settling time of the tip ([`wingcheck_sim::metrics::joint_tip_settle_time`]) (s).
    SettlingTime,
    /// Full-rate peak |τ1| over [0, t_end] (N).
    Tau1Peak,
    /// Full-rate RMS τ1 over [0, t_end] (N).
    Tau1Rms,
    /// Full-rate peak |τ2| over [0, t_end] (N m).
    Tau2Peak,
    /// Full-rate RMS τ2 over [0, t_end] (N m).
    Tau2Rms,
    /// RMS of g̃1 = g1 − ĝ1 over the metric window (N).
    G1TildeRms,
    /// RMS of g̃2 = g2 − ĝ2 over the metric window (N m).
    G2TildeRms,
    /// The wing's energy E at t_end (J).
    EnergyTEnd,
}

impl Metric {
    /// Every metric, in output order.
    pub const ALL: [Metric; 21] = [
        Metric::Lambda2,
        Metric::Lambda1,
        Metric::Lambda3Max,
        Metric::Lambda,
        Metric::Epsilon,
        Metric::UubBoundQ,
        Metric::GHmax,
        Metric::Zeta3,
        Metric::Zeta4,
        Metric::RmsQTip,
        Metric::MaxQTip,
        Metric::RmsThetaTip,
        Metric::MaxThetaTip,
        Metric::SettlingTime,
        Metric::Tau1Peak,
        Metric::Tau1Rms,
        Metric::Tau2Peak,
        Metric::Tau2Rms,
        Metric::G1TildeRms,
        Metric::G2TildeRms,
        Metric::EnergyTEnd,
    ];

    /// The theory metrics ([`Metric::Lambda2`] ..= [`Metric::Zeta4`]), in order.
    pub const THEORY: std::ops::Range<usize> = 0..9;
    /// The simulation metrics ([`Metric::RmsQTip`] ..= [`Metric::EnergyTEnd`]), in order.
    pub const SIMULATION: std::ops::Range<usize> = 9..21;

    /// Position in [`Metric::ALL`] (the column of a point's metric vector).
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The name without its unit (`rms_q_tip`): accepted on input as an alias of
    /// [`Metric::column`], never written.
    pub const fn short_name(self) -> &'static str {
        match self {
            Metric::Lambda2 => "lambda2",
            Metric::Lambda1 => "lambda1",
            Metric::Lambda3Max => "lambda3_max",
            Metric::Lambda => "lambda",
            Metric::Epsilon => "epsilon",
            Metric::UubBoundQ => "uub_bound_q",
            Metric::GHmax => "g_hmax",
            Metric::Zeta3 => "zeta3",
            Metric::Zeta4 => "zeta4",
            Metric::RmsQTip => "rms_q_tip",
            Metric::MaxQTip => "max_q_tip",
            Metric::RmsThetaTip => "rms_theta_tip",
            Metric::MaxThetaTip => "max_theta_tip",
            Metric::SettlingTime => "settling_time",
            Metric::Tau1Peak => "tau1_peak",
            Metric::Tau1Rms => "tau1_rms",
            Metric::Tau2Peak => "tau2_peak",
            Metric::Tau2Rms => "tau2_rms",
            Metric::G1TildeRms => "g1_tilde_rms",
            Metric::G2TildeRms => "g2_tilde_rms",
            Metric::EnergyTEnd => "energy_t_end",
        }
    }

    /// The metric's unit.
    pub const fn unit(self) -> Unit {
        match self {
            Metric::Lambda2 | Metric::Lambda1 => Unit::JouleSecond,
            Metric::Lambda3Max | Metric::Epsilon => Unit::Joule,
            Metric::Lambda => Unit::PerSecond,
            Metric::UubBoundQ | Metric::RmsQTip | Metric::MaxQTip => Unit::Metre,
            Metric::GHmax => Unit::NewtonPerMetre,
            Metric::Zeta3 | Metric::Tau1Peak | Metric::Tau1Rms | Metric::G1TildeRms => Unit::Newton,
            Metric::Zeta4 | Metric::Tau2Peak | Metric::Tau2Rms | Metric::G2TildeRms => Unit::NewtonMetre,
            Metric::RmsThetaTip | Metric::MaxThetaTip => Unit::Radian,
            Metric::SettlingTime => Unit::Second,
            Metric::EnergyTEnd => Unit::Joule,
        }
    }

    /// The metric's one written name: the short name with the unit's column suffix
    /// (`rms_q_tip_m`, `lambda_per_s`, `settling_time_s`), as results.csv heads its column.
    pub fn column(self) -> &'static str {
        &METRICS[self.index()]
    }

    /// The metric whose column name ([`Metric::column`]) or short name
    /// ([`Metric::short_name`]) is `name`.
    pub fn from_name(name: &str) -> Option<Metric> {
        Metric::ALL.into_iter().find(|m| m.column() == name || m.short_name() == name)
    }
}

impl std::fmt::Display for Metric {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.column())
    }
}

/// How `best.json` ranks the points: by one metric, minimised unless `maximise`. Written
/// `name` or `-name` on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ranking {
    /// The metric ranked by.
    pub metric: Metric,
    /// Largest first (`-name`) instead of smallest first.
    pub maximise: bool,
}

impl Default for Ranking {
    /// Smallest tip displacement RMS first.
    fn default() -> Self {
        Ranking { metric: Metric::RmsQTip, maximise: false }
    }
}

/// A ranking names no metric ([`Ranking`]'s `FromStr`); the message lists the known ones.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown metric `{name}`: use one of {}", METRICS.join(", "))]
pub struct UnknownMetric {
    /// The name given (without its `-`).
    pub name: String,
}

impl std::str::FromStr for Ranking {
    type Err = UnknownMetric;

    /// `name` (minimised) or `-name` (maximised); an unknown name is an error listing the known.
    fn from_str(text: &str) -> Result<Self, UnknownMetric> {
        let (name, maximise) = match text.strip_prefix('-') {
            Some(name) => (name, true),
            None => (text, false),
        };
        let metric = Metric::from_name(name).ok_or_else(|| UnknownMetric { name: name.to_string() })?;
        Ok(Ranking { metric, maximise })
    }
}

impl std::fmt::Display for Ranking {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}{}", if self.maximise { "-" } else { "" }, self.metric)
    }
}

impl serde::Serialize for Ranking {
    /// As written on the command line, by column name (`rms_q_tip_m`, `-lambda_per_s`).
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

impl schemars::JsonSchema for Ranking {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Ranking".into()
    }

    /// A metric's column name, optionally prefixed `-` (maximised).
    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let names: Vec<String> = METRICS.iter().flat_map(|m| [m.clone(), format!("-{m}")]).collect();
        schemars::json_schema!({
            "type": "string",
            "description": "a metric name (minimised) or -name (maximised)",
            "enum": names,
        })
    }
}

impl<'de> serde::Deserialize<'de> for Ranking {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        String::deserialize(deserializer)?.parse().map_err(serde::de::Error::custom)
    }
}

/// The column names, in output order ([`Metric::column`] of [`Metric::ALL`]).
pub static METRICS: std::sync::LazyLock<[String; 21]> = std::sync::LazyLock::new(|| {
    Metric::ALL.map(|m| wingcheck_io::column_name(m.short_name(), m.unit().column_suffix()))
});

/// The unit of each metric, in output order (the units of [`Metric::ALL`]): results.csv suffixes
/// its column with it, results.json lists it under `units`.
pub const METRIC_UNITS: [Unit; 21] = {
    let mut units = [Unit::Dimensionless; 21];
    let mut i = 0;
    while i < units.len() {
        units[i] = Metric::ALL[i].unit();
        i += 1;
    }
    units
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metrics_are_in_order_and_named_once() {
        for (i, m) in Metric::ALL.into_iter().enumerate() {
            assert_eq!(m.index(), i);
            assert_eq!(Metric::from_name(m.column()), Some(m));
            assert_eq!(Metric::from_name(m.short_name()), Some(m));
            assert_eq!(METRICS[i], m.column());
            assert!(wingcheck_io::is_column_name(m.column()), "{}", m.column());
        }
        let mut columns: Vec<&str> = METRICS.iter().map(String::as_str).collect();
        columns.sort_unstable();
        columns.dedup();
        assert_eq!(columns.len(), METRICS.len(), "one column per metric");
        assert_eq!(Metric::RmsQTip.column(), "rms_q_tip_m");
        assert_eq!(Metric::Lambda.column(), "lambda_per_s");
        assert_eq!(Metric::SettlingTime.column(), "settling_time_s");
        assert_eq!(Metric::ALL[Metric::THEORY.end], Metric::RmsQTip);
        assert_eq!(Metric::SIMULATION.end, Metric::ALL.len());
        assert_eq!(Metric::from_name("rms_q"), None);
        assert_eq!("-lambda".parse::<Ranking>(), Ok(Ranking { metric: Metric::Lambda, maximise: true }));
        assert_eq!("rms_q_tip_m".parse::<Ranking>(), Ok(Ranking::default()));
        assert_eq!(Ranking::default().to_string(), "rms_q_tip_m");
        assert_eq!(Ranking::default().to_string().parse::<Ranking>(), Ok(Ranking::default()));
        assert!("-rms_q".parse::<Ranking>().unwrap_err().to_string().contains("unknown metric `rms_q`"));
    }
}
