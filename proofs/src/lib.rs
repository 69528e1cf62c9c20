//! Kani harnesses for truecost (engine 3 of issue 5; README "Running the proofs with Kani").
//!
//! One source, two engines: `cargo kani -p truecost-proofs` checks every `#[kani::proof]`
//! symbolically (with the real `kani` crate, which Kani injects); under `cargo test` the
//! stand-in crate `kani-standin` (a dependency only when not compiling under Kani) turns each
//! harness into a test that enumerates every `kani::any()` choice explicitly. Each harness is
//! listed in `truecost::claims::harnesses::HARNESSES` with what it proves and its bounds.
//!
//! Harnesses use fixed arrays, small integers and bounded loops (`#[kani::unwind]`); choices
//! are small enums deriving `kani::Arbitrary`, so the stand-in's enumeration is exact and
//! small.

// Harnesses index small fixed arrays in bounded loops, as Kani prefers.
#![allow(clippy::needless_range_loop)]

pub mod c1;
pub mod c2;
pub mod c3;
pub mod c4;
pub mod solvers;

/// A value in `0..=3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, kani::Arbitrary)]
pub enum Four {
    /// 0.
    Zero,
    /// 1.
    One,
    /// 2.
    Two,
    /// 3.
    Three,
}

impl Four {
    /// As an integer.
    pub fn value(self) -> i64 {
        self as i64
    }
}

/// A value in `0..=2`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, kani::Arbitrary)]
pub enum Three {
    /// 0.
    Zero,
    /// 1.
    One,
    /// 2.
    Two,
}

impl Three {
    /// As an integer.
    pub fn value(self) -> usize {
        self as usize
    }
}

#[cfg(all(test, not(kani)))]
mod registry {
    use truecost::claims::harnesses::HARNESSES;

    /// Every harness of the registry runs under the stand-in with the number of executions the
    /// registry states (hand-derived from the choice domains: products of enum sizes).
    #[test]
    fn registry_counts_match_the_stand_in() {
        let all: Vec<(&str, bool, fn())> = vec![
            (
                "c1_as_printed_fails_at_the_termination_pair",
                true,
                crate::c1::c1_as_printed_fails_at_the_termination_pair,
            ),
            (
                "c1_as_printed_fails_on_a_zero_cost_cycle",
                true,
                crate::c1::c1_as_printed_fails_on_a_zero_cost_cycle,
            ),
            (
                "c1_corrected_converges_within_the_bound",
                false,
                crate::c1::c1_corrected_converges_within_the_bound,
            ),
            (
                "c2_argmin_cost_is_argmax_reward",
                false,
                crate::c2::c2_argmin_cost_is_argmax_reward,
            ),
            (
                "c3_certificate_makes_the_discount_optimal_policy_avoid_the_goal",
                false,
                crate::c3::c3_certificate_makes_the_discount_optimal_policy_avoid_the_goal,
            ),
            (
                "c3_example_sides_of_alpha_star",
                false,
                crate::c3::c3_example_sides_of_alpha_star,
            ),
            (
                "c4_printed_formula_fails",
                true,
                crate::c4::c4_printed_formula_fails,
            ),
            (
                "c4_corrected_threshold_matches_averages",
                false,
                crate::c4::c4_corrected_threshold_matches_averages,
            ),
            (
                "dijkstra_cost_to_go_satisfies_bellman_optimality",
                false,
                crate::solvers::dijkstra_cost_to_go_satisfies_bellman_optimality,
            ),
            (
                "dijkstra_equals_value_iteration",
                false,
                crate::solvers::dijkstra_equals_value_iteration,
            ),
            (
                "exploration_terminates_and_discovers_every_reachable_move",
                false,
                crate::solvers::exploration_terminates_and_discovers_every_reachable_move,
            ),
        ];
        assert_eq!(all.len(), HARNESSES.len());
        assert!(all.len() >= 8);
        for (name, should_panic, body) in all {
            let h = HARNESSES
                .iter()
                .find(|h| h.name == name)
                .expect("registered");
            assert_eq!(h.should_panic, should_panic, "{name}");
            let s = kani::__run(name, should_panic, body);
            assert_eq!(s.mode, kani::Mode::Exhaustive, "{name}");
            assert_eq!(s.executions, h.standin_executions, "{name}: {s}");
            assert_eq!(s.failures, h.failing_executions, "{name}: {s}");
        }
    }

    /// The stand-in really enumerates and really fails: a harness with a false assertion on
    /// one choice of 4 must fail, with its choice sequence.
    #[test]
    fn a_failing_harness_fails_with_its_choices() {
        fn bad() {
            let v: crate::Four = kani::any();
            kani::assert(v != crate::Four::Two, "two is bad");
        }
        let r = std::panic::catch_unwind(|| kani::__run("bad", false, bad));
        let msg = *r.expect_err("must fail").downcast::<String>().unwrap();
        assert!(msg.contains("choice sequence [2]"), "{msg}");
        // And a should_panic harness that never fails is reported.
        fn good() {
            let _: bool = kani::any();
        }
        assert!(std::panic::catch_unwind(|| kani::__run("good", true, good)).is_err());
        // assume prunes: 256 executions, 252 pruned.
        fn pruned() {
            let v: u8 = kani::any();
            kani::assume(v < 4);
        }
        let s = kani::__run("pruned", false, pruned);
        assert_eq!((s.executions, s.pruned), (256, 252));
        // A wide domain switches to sampling.
        fn wide() {
            let _: u32 = kani::any();
        }
        assert_eq!(kani::__run("wide", false, wide).mode, kani::Mode::Sampled);
    }
}
