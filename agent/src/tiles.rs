//! Tile coding as the authors implemented it: per feature, overlapping
//! intervals; the state key is the whole activation bit vector.

use proto::State;
use serde::{Deserialize, Serialize};

use crate::config::{AgentConfig, TILE_ORIGIN};
use crate::config_error::AgentConfigError;

/// Slack on the tile bounds, so that a feature exactly on a decimal edge
/// (e.g. 0.3, the upper edge of tile 4) is inside the tile although the edge
/// `-1 + 0.2 * 4 + 0.5` rounds to 0.30000000000000004 in binary.
const EDGE_TOLERANCE: f64 = 1e-9;

/// The parameters that give a state key its meaning; stored with saved
/// Q-tables so that a table is never read with another tiling.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TilingParams {
    /// Tiles per feature.
    pub tiles_per_feature: u32,
    /// Width of one tile.
    pub tile_width: f64,
    /// Distance between the lower edges of consecutive tiles.
    pub tile_step: f64,
}

impl TilingParams {
    /// The tiling part of an agent configuration.
    pub fn of(config: &AgentConfig) -> Self {
        Self {
            tiles_per_feature: config.tiles_per_feature,
            tile_width: config.tile_width,
            tile_step: config.tile_step,
        }
    }
}

/// A validated tiling with its tile bounds precomputed.
///
/// Tile `i` of every feature covers `[-1 + step * i, -1 + step * i + width]`,
/// bounds inclusive; bit `feature * tiles_per_feature + i` of the key is set
/// when the feature's value lies in tile `i`.
#[derive(Clone, Debug)]
pub struct Tiling {
    params: TilingParams,
    bounds: Vec<(f64, f64)>,
}

impl Tiling {
    /// Builds the tiling of a configuration (validated first).
    pub fn new(config: &AgentConfig) -> Result<Self, AgentConfigError> {
        config.validate()?;
        let params = TilingParams::of(config);
        let bounds = (0..params.tiles_per_feature)
            .map(|i| {
                let lo = TILE_ORIGIN + params.tile_step * f64::from(i);
                (lo - EDGE_TOLERANCE, lo + params.tile_width + EDGE_TOLERANCE)
            })
            .collect();
        Ok(Self { params, bounds })
    }

    /// The parameters this tiling was built from.
    pub fn params(&self) -> TilingParams {
        self.params
    }

    /// The state key: the activation bits of all features, packed.
    pub fn key(&self, state: &State) -> u64 {
        let tiles = self.bounds.len();
        let mut key = 0u64;
        for (f, &x) in state.iter().enumerate() {
            for (i, &(lo, hi)) in self.bounds.iter().enumerate() {
                if x >= lo && x <= hi {
                    key |= 1 << (f * tiles + i);
                }
            }
        }
        key
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use proto::STATE_FEATURES;

    fn tiling() -> Tiling {
        Tiling::new(&AgentConfig::default()).unwrap()
    }

    /// Active tiles of feature 0 when every feature has value `x`.
    fn active(x: f64) -> Vec<usize> {
        let key = tiling().key(&[x; STATE_FEATURES]);
        (0..10).filter(|i| key & (1 << i) != 0).collect()
    }

    #[test]
    fn activations_at_tile_edges() {
        // Tile i = [-1 + 0.2 i, -0.5 + 0.2 i].
        // -0.5: tile 0 = [-1, -0.5] (upper edge), 1 = [-0.8, -0.3], 2 = [-0.6, -0.1].
        assert_eq!(active(-0.5), vec![0, 1, 2]);
        // 0.3: tile 4 = [-0.2, 0.3] (upper edge), 5 = [0, 0.5], 6 = [0.2, 0.7].
        assert_eq!(active(0.3), vec![4, 5, 6]);
        // 1.0: tile 8 = [0.6, 1.1], 9 = [0.8, 1.3]; tile 7 = [0.4, 0.9] ends below.
        assert_eq!(active(1.0), vec![8, 9]);
        // -1.0: only tile 0 (tile 1 starts at -0.8).
        assert_eq!(active(-1.0), vec![0]);
        // 0.0: tile 3 = [-0.4, 0.1], 4 = [-0.2, 0.3], 5 = [0, 0.5] (lower edge).
        assert_eq!(active(0.0), vec![3, 4, 5]);
        // 0.2 is the lower edge of tile 6 = [0.2, 0.7]: also 4 and 5.
        assert_eq!(active(0.2), vec![4, 5, 6]);
    }

    #[test]
    fn features_own_consecutive_bit_ranges() {
        // Feature f uses bits 10 f .. 10 f + 9; -1 activates only tile 0.
        let mut s = [0.0; STATE_FEATURES];
        s[0] = -1.0; // bit 0
        s[1] = 1.0; // bits 18, 19
        s[2] = -1.0; // bit 20
        s[3] = -1.0; // bit 30
        s[4] = -1.0; // bit 40
        s[5] = 1.0; // bits 58, 59
        let expected = 1 | 1 << 18 | 1 << 19 | 1 << 20 | 1 << 30 | 1 << 40 | 1 << 58 | 1 << 59;
        assert_eq!(tiling().key(&s), expected);
    }

    proptest! {
        #[test]
        fn every_value_in_range_activates_one_to_three_tiles(x in -1.0f64..=1.0) {
            // Width 0.5 over step 0.2 gives 2 or 3 tiles inside, 1 near -1.
            let key = tiling().key(&[x; STATE_FEATURES]);
            let n = (key & 0x3ff).count_ones();
            prop_assert!((1..=3).contains(&n), "x = {x}: {n} tiles");
            prop_assert_eq!(key >> 60, 0);
        }
    }
}
