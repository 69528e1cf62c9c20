//! Tiny problems for exhaustive small-scope enumeration (engine 1), with symmetry reduction:
//! the kernel's `truecost_kernel::claims::tiny` (bignum-free), re-exported
//! under this path, and the conversion of a [`Tiny`] into the library's exact model.

use num_bigint::BigInt;

use crate::model::{Move, Problem};
use crate::value::Rational;

pub use truecost_kernel::claims::tiny::*;

/// The problem in the library's model (`x1 = 0`, goal `n − 1`), for problem files
/// (`Tiny::to_problem`).
///
/// ```
/// use truecost::claims::tiny::Tiny;
/// use truecost::model::Problem;
/// let p: Problem = Tiny::from_lists(&[vec![(0, 0), (1, 3)], vec![]]).to_problem();
/// assert_eq!((p.states(), p.goals(), p.moves(0).len()), (2, &[1][..], 2));
/// ```
impl From<Tiny> for Problem {
    fn from(t: Tiny) -> Problem {
        let moves = (0..t.states())
            .map(|x| {
                t.moves(x)
                    .iter()
                    .map(|m| Move {
                        successor: m.to as usize,
                        cost: Rational::from_integer(BigInt::from(m.cost)),
                    })
                    .collect()
            })
            .collect();
        Problem::new(moves, 0, vec![t.goal()]).expect("a tiny problem is well formed")
    }
}
