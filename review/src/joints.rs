//! Joint samples in the hand model's order: a `JointState` names its joints as the robot's
//! URDF spells them (or as the model does); the model's forward kinematics wants its own
//! order.

use retarget::HandModel;

/// Where each of the model's degrees of freedom is in a sample's name list.
#[derive(Debug, Clone, PartialEq)]
pub struct JointOrder {
    names: Vec<String>,
    index: Vec<usize>,
}

impl JointOrder {
    /// The order for samples named `names`: by the URDF's names or the model's, or, for a
    /// sample without names and with one value per degree of freedom, the model's own order.
    /// `Err` names the first degree of freedom the sample lacks.
    pub fn new(model: &HandModel, names: &[String], values: usize) -> Result<JointOrder, String> {
        if names.is_empty() && values == model.dof() {
            return Ok(JointOrder {
                names: Vec::new(),
                index: (0..model.dof()).collect(),
            });
        }
        let index = model
            .dofs()
            .iter()
            .zip(model.ros_dof_names())
            .map(|(dof, ros)| {
                names
                    .iter()
                    .position(|n| n == ros || names_dof(n, &dof.name))
                    .ok_or_else(|| format!("no joint named {ros} (or {})", dof.name))
            })
            .collect::<Result<Vec<usize>, String>>()?;
        Ok(JointOrder {
            names: names.to_vec(),
            index,
        })
    }

    /// Whether this order is for samples named `names`.
    pub fn fits(&self, names: &[String]) -> bool {
        self.names == names
    }

    /// The sample's values in the model's order (NaN where a value is missing).
    pub fn reorder(&self, values: &[f64]) -> Vec<f64> {
        self.index
            .iter()
            .map(|&i| values.get(i).copied().unwrap_or(f64::NAN))
            .collect()
    }
}

/// Whether `name` is the degree of freedom `dof` under some prefix: `dof` itself, or `dof`
/// after a prefix ending in `_` or `/` (`left_index_mcp`, `orca/index_mcp`).
fn names_dof(name: &str, dof: &str) -> bool {
    name.strip_suffix(dof)
        .is_some_and(|prefix| prefix.is_empty() || prefix.ends_with(['_', '/']))
}
