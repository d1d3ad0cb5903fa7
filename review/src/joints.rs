//! Joint samples in the hand model's order: a `JointState` names its joints as the robot's
//! URDF spells them (or as the model does); the model's forward kinematics wants its own
//! order.

use retarget::HandModel;
use station::joint_names::dof_of_published_name;

/// Where each of the model's degrees of freedom is in a sample's name list.
#[derive(Debug, Clone, PartialEq)]
pub struct JointOrder {
    names: Vec<String>,
    index: Vec<usize>,
}

impl JointOrder {
    /// The order for samples named `names`, each name read as the station reads a published
    /// one ([`station::joint_names::dof_of_published_name`]: the model's name, its URDF name,
    /// or `prefix` + the model's name), or, for a sample without names and with one value per
    /// degree of freedom, the model's own order. `Err` names the first degree of freedom the
    /// sample lacks.
    pub fn new(
        model: &HandModel,
        names: &[String],
        values: usize,
        prefix: Option<&str>,
    ) -> Result<JointOrder, String> {
        if names.is_empty() && values == model.dof() {
            return Ok(JointOrder {
                names: Vec::new(),
                index: (0..model.dof()).collect(),
            });
        }
        let dof_of: Vec<Option<usize>> = names
            .iter()
            .map(|n| dof_of_published_name(model, n, prefix))
            .collect();
        let index = (0..model.dof())
            .map(|dof| {
                dof_of.iter().position(|d| *d == Some(dof)).ok_or_else(|| {
                    format!(
                        "no joint named {} (or {})",
                        model.ros_dof_names()[dof],
                        model.dofs()[dof].name
                    )
                })
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
