//! Kani harnesses for truecost (engine 3; running them with Kani: `docs/guide/kani.md`).
//!
//! One source, two engines: `cargo kani -p truecost-proofs` checks every `#[kani::proof]`
//! symbolically (with the real `kani` crate, which Kani injects); under `cargo test` the
//! stand-in crate `kani-standin` (a dependency only when not compiling under Kani) runs each
//! harness as a test — **sampled** (seeded, boundary values first, a stated number of
//! executions) when a choice is wider than 2^16 values, exhaustively otherwise. Each harness is
//! listed in `truecost::claims::harnesses::HARNESSES`; `truecost`'s `tests/harnesses.rs` checks
//! that registry against these sources (names, unwind bounds, should_panic, sample counts) and
//! against the stand-in's runs (mode, executions, choice bits, failures, covers). [`harnesses`]
//! is the table of every harness as the stand-in runs it: `truecost verify` runs the harnesses
//! of the claims it checks through it, in its own process, and reports what the stand-in found
//! there.
//!
//! The harnesses earn their place by width (every domain but the two `_exhaustive_small`
//! variants is at least 2^32 choices: symbolic successors, `u8`/`u16`/`u32` costs, `i32`
//! values, symbolic update orders, `i16` operands) or by induction (C1-corrected's inductive
//! steps). They call truecost's own code: the derandomized Q-learning update, Dijkstra, value
//! iteration, the exploration, the claims' oracles and certificates, the exact value types.
//! Fixed arrays, loops bounded by constants, `#[kani::unwind]` ≥ iterations + 1.
//!
//! Every harness body calls only `truecost-kernel` (the bignum-free kernel that `truecost`
//! re-exports under its old paths), the very code `truecost` runs: under `--cfg kani` this
//! crate's dependency tree is the kernel alone (checked by `tests/lean_kani_build.rs`).
//! `truecost` depends on this crate (not under Kani) to run the harness bodies in `verify`;
//! this crate depends on `truecost` in no way, not even for its tests.

// Harnesses index small fixed arrays in bounded loops, as Kani prefers.
#![allow(clippy::needless_range_loop)]

pub mod c1;
pub mod c2;
pub mod c3;
pub mod c4;
pub mod contracts;
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

/// The stand-in (`kani-standin`) under the name `truecost` uses to run the harnesses: its
/// [`standin::Harness`], [`standin::Summary`] and [`standin::Mode`].
#[cfg(not(kani))]
pub use kani as standin;

/// Every harness of this crate as the stand-in runs it (name, `should_panic`, the stated
/// sample count, the covers written in the body, the contract it proves, its stubs, the body),
/// in the order of `truecost::claims::harnesses::HARNESSES`: the claim and planner harnesses,
/// then the contract proofs ([`contract_harnesses`]). A harness missing here or there fails the
/// registry cross-check of `truecost`'s `tests/harnesses.rs`.
#[cfg(not(kani))]
pub fn harnesses() -> Vec<kani::Harness> {
    vec![
        c1::c1_as_printed_round_fixed_points_are_optimal::HARNESS,
        c1::c1_corrected_round_lifts_the_exact_level::HARNESS,
        c1::c1_corrected_round_raises_the_floor_by_c::HARNESS,
        c1::c1_corrected_round_is_monotone_below_q_star::HARNESS,
        c2::c2_oracle_argmin_cost_is_argmax_reward::HARNESS,
        c3::c3_certificate_makes_discounting_avoid_the_goal::HARNESS,
        c3::c3_example_sides_of_alpha_star_exhaustive_small::HARNESS,
        c4::c4_as_printed_set_is_the_oracles::HARNESS,
        c4::c4_corrected_set_is_the_oracles::HARNESS,
        solvers::dijkstra_cost_to_go_satisfies_bellman_optimality::HARNESS,
        solvers::dijkstra_equals_value_iteration::HARNESS,
        solvers::dijkstra_equals_value_iteration_exhaustive_small::HARNESS,
        solvers::exploration_discovers_the_reachable_states_exhaustive_small::HARNESS,
        values::units_plus_is_exact_when_it_fits::HARNESS,
        values::units_plus_reports_every_overflow::HARNESS,
        values::rational_add_and_mul_are_exact::HARNESS,
        contracts::gcd_divides_both::HARNESS,
        contracts::lowest_terms_has_a_bezout_witness::HARNESS,
        contracts::checked_add_is_exact::HARNESS,
        contracts::checked_mul_is_exact::HARNESS,
        contracts::units_checked_plus_is_exact::HARNESS,
        contracts::update_is_the_rho_one_rule::HARNESS,
    ]
}

/// The harnesses that prove the kernel's contracts (`#[kani::proof_for_contract]`,
/// [`contracts`]), as the stand-in runs them: the lemmas the claim harnesses use through
/// `#[kani::stub_verified]`. Part of [`harnesses`] (so `verify` runs and reports them too).
#[cfg(not(kani))]
pub fn contract_harnesses() -> Vec<kani::Harness> {
    harnesses()
        .into_iter()
        .filter(|h| h.contract.is_some())
        .collect()
}

/// Whether this build checks integer overflow (`-C overflow-checks`, on in debug and test
/// builds, off in a default release build): without it an overflow in a harness body or in the
/// kernel wraps silently instead of failing the stand-in's run (Kani checks it regardless).
#[cfg(not(kani))]
pub fn overflow_checks() -> bool {
    kani::__panics(|| {
        let _ = std::hint::black_box(std::hint::black_box(u8::MAX) + 1);
    })
}

#[cfg(all(test, not(kani)))]
mod registry {
    /// Every contract harness passes its stand-in run (its function called, its covers
    /// satisfied); every `stub_verified` of any harness names a function whose contract one of
    /// them proves (Kani requires such a harness for each); and every wide C1–C4 harness uses
    /// a verified stub (the update for C1, `lowest_terms` for C2–C4).
    #[test]
    fn contract_harnesses_pass_and_cover_every_verified_stub() {
        let contracts = crate::contract_harnesses();
        assert_eq!(contracts.len(), 6);
        for h in &contracts {
            let s = h.explore();
            assert_eq!(s.verdict(), Ok(()), "{s}");
            assert!(s.contract_calls > 0, "{s}");
        }
        let proved: Vec<&str> = contracts.iter().filter_map(|h| h.contract).collect();
        for h in &crate::harnesses() {
            for &f in h.stub_verified {
                assert!(
                    proved.contains(&f),
                    "{}: no contract harness for {f}",
                    h.name
                );
            }
            let claim = ["c1_", "c2_", "c3_", "c4_"]
                .iter()
                .any(|c| h.name.starts_with(c));
            if claim && !h.name.ends_with("_exhaustive_small") {
                assert!(!h.stub_verified.is_empty(), "{}: no verified stub", h.name);
            }
        }
    }

    /// A harness with covers in the three forms, one in a branch.
    #[kani::proof]
    fn listed_covers() {
        let v: u8 = kani::any();
        if v > 20 {
            kani::cover!(v == 30, "thirty");
        }
        kani::cover!(v == 3);
        kani::cover!();
    }

    /// The same covers with the branch made dead by an assume.
    fn dead_branch() {
        let v: u8 = kani::any();
        kani::assume(v < 10);
        if v > 20 {
            kani::cover!(v == 30, "thirty");
        }
        kani::cover!(v == 3);
        kani::cover!();
    }

    /// `#[kani::proof]` lists the covers written in the body, in Kani's messages; with the
    /// branch dead, its cover is reported as never reached (the run alone could not see it: no
    /// execution calls it), and the harness fails.
    #[test]
    fn the_proof_macro_lists_the_covers_of_the_body() {
        let h = listed_covers::HARNESS;
        assert_eq!(
            h.covers,
            ["thirty", "cover condition: v == 3", "cover location"]
        );
        let s = h.explore();
        assert_eq!((s.verdict(), s.covers_hit()), (Ok(()), 3), "{s}");
        let dead = kani::Harness {
            body: dead_branch,
            ..h
        };
        let s = dead.explore();
        let why = s.verdict().expect_err("a cover is never reached");
        assert!(why.contains("cover \"thirty\" was never reached"), "{why}");
        assert_eq!(s.covers_hit(), 2, "{s}");
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
    /// and reports its width in choice bits; many narrow choices together are sampled too.
    #[test]
    fn wide_domains_are_sampled_boundary_values_first() {
        fn wide() {
            let v: i32 = kani::any();
            kani::cover!(v == i32::MIN, "boundary");
        }
        let s = kani::__run_with("wide", false, 1234, wide);
        assert_eq!(
            (s.mode, s.executions, s.choice_bits),
            (kani::Mode::Sampled, 1234, 32)
        );
        assert_eq!(s.covers_hit(), 1);
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
        assert_eq!((s.mode, s.choice_bits), (kani::Mode::Sampled, 32));
        // An overflow is a failure a should_panic harness accepts (under Kani the overflow
        // check is of class `assertion`), and it fails any other harness (where this build
        // checks overflow at all).
        fn overflows() {
            let v: u8 = kani::any();
            let _ = std::hint::black_box(v) + 255;
        }
        assert!(std::panic::catch_unwind(|| kani::__run("overflows", true, overflows)).is_ok());
        assert_eq!(
            std::panic::catch_unwind(|| kani::__run("overflows", false, overflows)).is_err(),
            crate::overflow_checks()
        );
    }
}
