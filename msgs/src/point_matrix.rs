//! N×3 point matrices in a `Float32MultiArray`, as the lab's `/ingress/mano` publishes them.

use crate::{Error, Float32MultiArray, MultiArrayDimension, MultiArrayLayout};

impl Float32MultiArray {
    /// An N×3 matrix holding `points` row by row: dims `dim_0` (size N, stride 3N) and `dim_1`
    /// (size 3, stride 3), no data offset.
    ///
    /// # Errors
    /// [`Error::NotPointMatrix`] if 3N does not fit the `u32` of a ROS dimension.
    pub fn from_points(points: &[[f32; 3]]) -> Result<Self, Error> {
        let too_many = || Error::NotPointMatrix {
            reason: format!("{} points do not fit a u32 stride", points.len()),
        };
        let rows = u32::try_from(points.len()).map_err(|_| too_many())?;
        let stride = rows.checked_mul(3).ok_or_else(too_many)?;
        Ok(Float32MultiArray {
            layout: MultiArrayLayout {
                dim: vec![
                    MultiArrayDimension {
                        label: "dim_0".into(),
                        size: rows,
                        stride,
                    },
                    MultiArrayDimension {
                        label: "dim_1".into(),
                        size: 3,
                        stride: 3,
                    },
                ],
                data_offset: 0,
            },
            data: points.iter().flatten().copied().collect(),
        })
    }

    /// The rows of an N×3 matrix as points.
    ///
    /// Checks the layout, not the labels or strides (publishers fill those in differently):
    /// exactly two dims, the inner one of size 3, no data offset, and `rows × 3 == data.len()`.
    ///
    /// # Errors
    /// [`Error::NotPointMatrix`] naming the failed check.
    pub fn points(&self) -> Result<Vec<[f32; 3]>, Error> {
        let fail = |reason: String| Err(Error::NotPointMatrix { reason });
        let [rows, cols] = self.layout.dim.as_slice() else {
            return fail(format!("{} dims, expected 2", self.layout.dim.len()));
        };
        if cols.size != 3 {
            return fail(format!("inner dim has size {}, expected 3", cols.size));
        }
        if self.layout.data_offset != 0 {
            return fail(format!(
                "data_offset {}, expected 0",
                self.layout.data_offset
            ));
        }
        if u64::from(rows.size) * 3 != self.data.len() as u64 {
            return fail(format!(
                "{} rows × 3 != {} data elements",
                rows.size,
                self.data.len()
            ));
        }
        Ok(self
            .data
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn layout_is_dim_0_by_dim_1() {
        let m = Float32MultiArray::from_points(&[[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]).unwrap();
        let dims: Vec<_> = m
            .layout
            .dim
            .iter()
            .map(|d| (d.label.as_str(), d.size, d.stride))
            .collect();
        assert_eq!(dims, [("dim_0", 2, 6), ("dim_1", 3, 3)]);
        assert_eq!(m.data, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    }

    #[test]
    fn inconsistent_layouts_are_rejected() {
        let good = Float32MultiArray::from_points(&[[0.0; 3]; 4]).unwrap();
        assert_eq!(good.points().unwrap().len(), 4);

        let mut short = good.clone();
        short.data.pop();
        let mut wide = good.clone();
        wide.layout.dim[1].size = 4;
        let mut one_dim = good.clone();
        one_dim.layout.dim.pop();
        let mut offset = good.clone();
        offset.layout.data_offset = 3;
        for bad in [short, wide, one_dim, offset, Float32MultiArray::default()] {
            assert!(
                matches!(bad.points(), Err(Error::NotPointMatrix { .. })),
                "{bad:?}"
            );
        }
    }

    #[test]
    fn an_empty_matrix_has_no_points() {
        let m = Float32MultiArray::from_points(&[]).unwrap();
        assert_eq!(m.points().unwrap(), Vec::<[f32; 3]>::new());
    }

    proptest! {
        #[test]
        fn points_round_trip(points in prop::collection::vec(any::<[f32; 3]>(), 0..40)) {
            let m = Float32MultiArray::from_points(&points).unwrap();
            let back = m.points().unwrap();
            // Compare bits so NaN coordinates count as equal.
            let bits = |p: &[[f32; 3]]| -> Vec<u32> { p.iter().flatten().map(|x| x.to_bits()).collect() };
            prop_assert_eq!(bits(&back), bits(&points));
        }
    }
}
