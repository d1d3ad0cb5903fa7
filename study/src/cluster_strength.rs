//! Kaufman & Rousseeuw's reading of a mean silhouette ("Finding Groups in Data", 1990).

use serde::Serialize;

/// How much cluster structure a mean silhouette shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ClusterStrength {
    /// Above 0.70.
    Strong,
    /// Above 0.50, up to 0.70.
    Reasonable,
    /// Above 0.25, up to 0.50: the structure is weak and could be artificial.
    Weak,
    /// 0.25 or below.
    NoSubstantialStructure,
}

impl ClusterStrength {
    /// The band `mean_silhouette` falls in (NaN falls in the lowest).
    pub fn from_silhouette(mean_silhouette: f64) -> Self {
        if mean_silhouette > 0.70 {
            Self::Strong
        } else if mean_silhouette > 0.50 {
            Self::Reasonable
        } else if mean_silhouette > 0.25 {
            Self::Weak
        } else {
            Self::NoSubstantialStructure
        }
    }

    /// Reasonable or strong: the segments cluster by task.
    pub fn clusters(self) -> bool {
        matches!(self, Self::Strong | Self::Reasonable)
    }

    /// The band's name, e.g. `reasonable structure`.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Strong => "strong structure",
            Self::Reasonable => "reasonable structure",
            Self::Weak => "weak structure",
            Self::NoSubstantialStructure => "no substantial structure",
        }
    }

    /// The band's range, e.g. `0.50–0.70`.
    pub fn range(self) -> &'static str {
        match self {
            Self::Strong => "> 0.70",
            Self::Reasonable => "0.50–0.70",
            Self::Weak => "0.25–0.50",
            Self::NoSubstantialStructure => "≤ 0.25",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_edges_belong_to_the_band_below() {
        assert_eq!(
            ClusterStrength::from_silhouette(0.71),
            ClusterStrength::Strong
        );
        assert_eq!(
            ClusterStrength::from_silhouette(0.70),
            ClusterStrength::Reasonable
        );
        assert_eq!(
            ClusterStrength::from_silhouette(0.50),
            ClusterStrength::Weak
        );
        assert_eq!(
            ClusterStrength::from_silhouette(0.25),
            ClusterStrength::NoSubstantialStructure
        );
        assert_eq!(
            ClusterStrength::from_silhouette(-0.3),
            ClusterStrength::NoSubstantialStructure
        );
        assert_eq!(
            ClusterStrength::from_silhouette(f64::NAN),
            ClusterStrength::NoSubstantialStructure
        );
        assert!(ClusterStrength::Reasonable.clusters() && !ClusterStrength::Weak.clusters());
    }
}
