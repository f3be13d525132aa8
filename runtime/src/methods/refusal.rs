//! Which models a method does not run, and why: the reasons a run is
//! refused before its first step, each with what to use instead.

use crate::model::{has_mass_matrix, Model};
use crate::options::Method;

impl Method {
    /// Why this method does not run models of type `M`, as the message of
    /// the [`crate::Error::InvalidOptions`] a run returns; `None` where it
    /// runs them. A method refuses a model it would integrate wrongly or
    /// not at all: `TaylorFixed` of an order the model was not expanded
    /// to, `Taylor` without the model's AD tape, a method other than
    /// `Radau5`, `Rodas5P` or `Auto` on a singular mass matrix, `Rodas5P`
    /// on index-2 variables, an implicit method on a batch of members.
    /// Whatever the options, the run is refused where this is `Some`; the
    /// options may refuse it too (a `Formulation` or `LinearSolver` the
    /// method does not support).
    pub fn refusal<M: Model>(self) -> Option<String> {
        if let Method::TaylorFixed { order, .. } = self {
            if order == 0 || order > M::TAYLOR_ORDER {
                return Some(format!(
                    "TaylorFixed of order {order} needs the model expanded with #[dae_model(taylor = {order})] or higher; it has {}",
                    M::TAYLOR_ORDER
                ));
            }
        }
        // A singular mass matrix: RADAU5 integrates it (Auto picks it),
        // RODAS5P too where no variable is of index 2.
        if has_mass_matrix::<M>() && self == Method::Rodas5P && !M::INDEX2_COMPONENTS.is_empty() {
            let index2: Vec<&str> =
                M::INDEX2_COMPONENTS.iter().map(|&i| M::INFO.states[i]).collect();
            return Some(format!(
                "{} has variables of index 2 ({}), which a Rosenbrock method does not converge on: integrate it with Method::Radau5 (or Method::Auto)",
                M::INFO.name,
                index2.join(", ")
            ));
        }
        if has_mass_matrix::<M>()
            && !matches!(self, Method::Radau5 | Method::Rodas5P | Method::Auto)
        {
            let algebraic: Vec<&str> = (0..M::STATES)
                .filter(|&i| M::MASS.is_algebraic(i))
                .map(|i| M::INFO.states[i])
                .collect();
            let which = if algebraic.is_empty() {
                String::new()
            } else {
                format!(" (algebraic components {})", algebraic.join(", "))
            };
            return Some(format!(
                "{} has a singular mass matrix{which}: integrate it with Method::Radau5 (or Method::Auto, or Method::Rodas5P where it is of index 1)",
                M::INFO.name,
            ));
        }
        if M::LANES > 1
            && matches!(
                self,
                Method::Auto | Method::Radau5 | Method::Rodas5P | Method::BackwardEuler
            )
        {
            return Some(format!(
                "{} steps {} members together, and only the explicit pairs and the explicit fixed-step methods keep each member to its own tolerance: use Method::Dopri5 or Method::Dop853 (or Rk4 with a step), or run the members one by one for {:?}",
                M::INFO.name,
                M::LANES,
                self
            ));
        }
        if let (Method::Taylor, Some(reason)) = (self, M::TAYLOR_TAPE.reason()) {
            return Some(taylor_refusal::<M>(reason));
        }
        None
    }
}

/// Why `Method::Taylor` does not run `M`, for `reason`: the tape the
/// macro could not make (`Model::TAYLOR_TAPE`), or a model that
/// hands over none. A batch has no `Auto` to suggest.
pub(crate) fn taylor_refusal<M: Model>(reason: &str) -> String {
    if M::LANES > 1 {
        format!(
            "Method::Taylor is not available for {}: {reason}. Use Method::Dop853 for a non-stiff run at tight tolerances, or Method::Radau5 for a stiff model",
            M::INFO.name
        )
    } else {
        format!(
            "Method::Taylor is not available for {}: {reason}. Use Method::Dop853 for a non-stiff run at tight tolerances (Method::Auto switches to Radau5 where it turns stiff), or Method::Radau5 for a stiff model",
            M::INFO.name
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::info::{EvalError, ModelInfo};
    use crate::model::MassMatrix;

    /// y' = −y and z' = y − z, or, with a singular mass matrix, z
    /// algebraic (0 = y − z): written by hand, its mass matrix the
    /// identity (`KIND` 0), diagonal (1) or a general pattern (2).
    struct Written<const KIND: u8>;

    impl<const KIND: u8> Model for Written<KIND> {
        const STATES: usize = 2;
        type State = [f64; 2];
        const INDEX: usize = 1;
        const INFO: ModelInfo = ModelInfo::bare("Written", &["y", "z"], 2);
        const MASS: MassMatrix = match KIND {
            0 => MassMatrix::Identity,
            1 => MassMatrix::Diagonal(&[1.0, 0.0]),
            _ => MassMatrix::Pattern(&[(0, 0)]),
        };
        fn initial_state(&self, y: &mut [f64]) {
            y.copy_from_slice(&[1.0, 1.0]);
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), EvalError> {
            dy.copy_from_slice(&[-y[0], y[0] - y[1]]);
            Ok(())
        }
    }

    #[test]
    fn a_model_says_what_it_lacks_once_and_the_refusal_reads_it_there() {
        // No tape: the trait's default says so, with the reason Taylor
        // gives before the first step.
        let taylor = Method::Taylor.refusal::<Written<0>>().unwrap();
        assert!(taylor.contains("Written: it has no Taylor tape"), "{taylor}");
        // A diagonal mass matrix names its algebraic components; a general
        // one cannot, and says only that it is singular.
        let diagonal = Method::Dopri5.refusal::<Written<1>>().unwrap();
        assert!(diagonal.contains("singular mass matrix (algebraic components z)"), "{diagonal}");
        let general = Method::Dopri5.refusal::<Written<2>>().unwrap();
        assert!(
            general.contains("singular mass matrix: integrate it with Method::Radau5"),
            "{general}"
        );
        assert_eq!(Method::Dopri5.refusal::<Written<0>>(), None);
        for method in [Method::Radau5, Method::Rodas5P, Method::Auto] {
            assert_eq!(method.refusal::<Written<2>>(), None, "{method:?}");
        }
    }
}
