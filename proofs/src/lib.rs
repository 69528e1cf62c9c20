//! Kani harnesses for truecost (engine 3; issue 10; README "Running the proofs with Kani").
//!
//! One source, two engines: `cargo kani -p truecost-proofs` checks every `#[kani::proof]`
//! symbolically (with the real `kani` crate, which Kani injects); under `cargo test` the
//! stand-in crate `kani-standin` (a dependency only when not compiling under Kani) runs each
//! harness as a test — **sampled** (seeded, boundary values first, a stated number of
//! executions) when a choice is wider than 2^16 values, exhaustively otherwise. Each harness is
//! listed in `truecost::claims::harnesses::HARNESSES`; a test checks that registry against these
//! sources (names, unwind bounds, should_panic, sample counts) and against the stand-in's runs
//! (mode, executions, domain size).
//!
//! The harnesses earn their place by width (every domain but the two `_exhaustive_small`
//! variants is at least 2^99 choices: symbolic successors, `u8`/`u16`/`u32` costs, `i32`
//! values, symbolic update orders) or by induction (C1-corrected's inductive steps). They call
//! truecost's own code: the derandomized Q-learning update, Dijkstra, value iteration, the
//! exploration, the claims' oracles and certificates, the exact value types. Fixed arrays,
//! loops bounded by constants, `#[kani::unwind]` ≥ iterations + 1.
//!
//! Every harness body calls only `truecost-kernel` (the bignum-free kernel that `truecost`
//! re-exports under its old paths), the very code `truecost` runs: under `--cfg kani` this
//! crate's dependency tree is the kernel alone (issue 10, item 3; checked by
//! `tests/lean_kani_build.rs`). `truecost` itself is a dev-dependency for the registry
//! cross-check only.

// Harnesses index small fixed arrays in bounded loops, as Kani prefers.
#![allow(clippy::needless_range_loop)]

pub mod c1;
pub mod c2;
pub mod c3;
pub mod c4;
pub mod solvers;
pub mod symbolic;
pub mod values;

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
    use truecost::claims::harnesses::{StandinMode, HARNESSES};

    /// Every harness body, by name (a harness missing here or in the registry fails the test).
    fn bodies() -> Vec<(&'static str, fn())> {
        vec![
            (
                "c1_as_printed_round_fixed_points_are_optimal",
                crate::c1::c1_as_printed_round_fixed_points_are_optimal,
            ),
            (
                "c1_corrected_round_lifts_the_exact_level",
                crate::c1::c1_corrected_round_lifts_the_exact_level,
            ),
            (
                "c1_corrected_round_raises_the_floor_by_c",
                crate::c1::c1_corrected_round_raises_the_floor_by_c,
            ),
            (
                "c1_corrected_round_is_monotone_below_q_star",
                crate::c1::c1_corrected_round_is_monotone_below_q_star,
            ),
            (
                "c2_oracle_argmin_cost_is_argmax_reward",
                crate::c2::c2_oracle_argmin_cost_is_argmax_reward,
            ),
            (
                "c3_certificate_makes_discounting_avoid_the_goal",
                crate::c3::c3_certificate_makes_discounting_avoid_the_goal,
            ),
            (
                "c3_example_sides_of_alpha_star_exhaustive_small",
                crate::c3::c3_example_sides_of_alpha_star_exhaustive_small,
            ),
            (
                "c4_as_printed_set_is_the_oracles",
                crate::c4::c4_as_printed_set_is_the_oracles,
            ),
            (
                "c4_corrected_set_is_the_oracles",
                crate::c4::c4_corrected_set_is_the_oracles,
            ),
            (
                "dijkstra_cost_to_go_satisfies_bellman_optimality",
                crate::solvers::dijkstra_cost_to_go_satisfies_bellman_optimality,
            ),
            (
                "dijkstra_equals_value_iteration",
                crate::solvers::dijkstra_equals_value_iteration,
            ),
            (
                "dijkstra_equals_value_iteration_exhaustive_small",
                crate::solvers::dijkstra_equals_value_iteration_exhaustive_small,
            ),
            (
                "exploration_discovers_the_reachable_states_exhaustive_small",
                crate::solvers::exploration_discovers_the_reachable_states_exhaustive_small,
            ),
            (
                "units_plus_is_exact_when_it_fits",
                crate::values::units_plus_is_exact_when_it_fits,
            ),
            (
                "units_plus_reports_every_overflow",
                crate::values::units_plus_reports_every_overflow,
            ),
            (
                "rational_add_and_mul_are_exact",
                crate::values::rational_add_and_mul_are_exact,
            ),
        ]
    }

    /// The registry's mode, execution count, domain size and failing count of every harness are
    /// what the stand-in measures when it runs the harness (the sample counts and the rest of
    /// each entry are checked against the sources by `tests/harnesses.rs` of `truecost`).
    #[test]
    fn registry_matches_the_stand_in_runs() {
        let all = bodies();
        assert_eq!(all.len(), HARNESSES.len());
        for (name, body) in all {
            let h = HARNESSES
                .iter()
                .find(|h| h.name == name)
                .expect("registered");
            let s = kani::__run_with(name, h.should_panic, h.executions, body);
            let mode = match s.mode {
                kani::Mode::Exhaustive => StandinMode::Exhaustive,
                kani::Mode::Sampled => StandinMode::Sampled,
            };
            assert_eq!(mode, h.mode, "{name}: {s}");
            assert_eq!(s.executions, h.executions, "{name}: {s}");
            assert_eq!(s.domain_bits, h.domain_bits, "{name}: {s}");
            assert_eq!(s.failures, h.failing, "{name}: {s}");
            // Wide domains only, but for the named small variants.
            assert_eq!(
                name.ends_with("_exhaustive_small"),
                h.domain_bits < 32,
                "{name}"
            );
            // A sampled harness is not vacuous: most executions are not pruned.
            assert!(s.executions - s.pruned >= s.executions / 20, "{name}: {s}");
        }
    }

    /// Every finite pair whose sum does not fit is reported: every non-pruned execution of the
    /// overflow harness panics.
    #[test]
    fn every_sampled_overflow_is_reported() {
        let s = kani::__run_with(
            "units_plus_reports_every_overflow",
            true,
            kani::SAMPLES,
            crate::values::units_plus_reports_every_overflow,
        );
        assert_eq!(s.failures, s.executions - s.pruned, "{s}");
    }

    /// The stand-in really enumerates and really fails: a harness with a false assertion on
    /// one choice of 4 must fail, with its choice sequence.
    #[test]
    fn a_failing_harness_fails_with_its_choices() {
        fn bad() {
            let v: crate::Three = kani::any();
            kani::assert(v != crate::Three::Two, "two is bad");
        }
        let r = std::panic::catch_unwind(|| kani::__run("bad", false, bad));
        let msg = *r.expect_err("must fail").downcast::<String>().unwrap();
        assert!(msg.contains("choice sequence [2]"), "{msg}");
        // A should_panic harness that never fails is reported.
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
        assert_eq!(
            (s.executions, s.pruned, s.mode),
            (256, 252, kani::Mode::Exhaustive)
        );
        // Every execution pruned: vacuous, reported.
        fn vacuous() {
            let v: u8 = kani::any();
            kani::assume(v.count_ones() > 8); // never: a u8 has 8 bits
        }
        assert!(std::panic::catch_unwind(|| kani::__run("vacuous", false, vacuous)).is_err());
    }

    /// A wide domain is sampled, with the stated number of executions, boundary values first,
    /// and reports its width; many narrow choices together are sampled too.
    #[test]
    fn wide_domains_are_sampled_boundary_values_first() {
        fn wide() {
            let v: i32 = kani::any();
            kani::cover!(v == i32::MIN, "boundary");
        }
        let s = kani::__run_with("wide", false, 1234, wide);
        assert_eq!(
            (s.mode, s.executions, s.domain_bits),
            (kani::Mode::Sampled, 1234, 32)
        );
        // Boundary values first: some early execution draws i32::MIN, i32::MAX, -1, 0, 1 (an
        // assertion that they never occur must fail).
        for (name, body) in [
            (
                "no_min",
                (|| kani::assert(kani::any::<i32>() != i32::MIN, "min")) as fn(),
            ),
            ("no_max", || {
                kani::assert(kani::any::<i32>() != i32::MAX, "max")
            }),
            ("no_zero", || kani::assert(kani::any::<i32>() != 0, "zero")),
            ("no_minus_one", || {
                kani::assert(kani::any::<i32>() != -1, "-1")
            }),
        ] {
            let s = kani::__run_with(name, true, 50, body);
            assert!(s.failures > 0, "{s}");
        }
        fn many_narrow() {
            let _: [u8; 4] = kani::any();
        }
        let s = kani::__run_with("many_narrow", false, 100, many_narrow);
        assert_eq!((s.mode, s.domain_bits), (kani::Mode::Sampled, 32));
        // An overflow is not the failure a should_panic harness expects.
        fn overflows() {
            let v: u8 = kani::any();
            let _ = std::hint::black_box(v) + 255;
        }
        assert!(std::panic::catch_unwind(|| kani::__run("overflows", true, overflows)).is_err());
    }
}
