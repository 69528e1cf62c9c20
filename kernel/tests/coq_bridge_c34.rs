//! The bridge between the Coq proofs of C3 and C4 (`proofs/coq/C3.v`, `C4.v`) and the kernel's
//! oracles: the terms the Coq theorems are about must be the quantities the kernel computes.
//! Problems of `claims::tiny`'s enumeration are written as Coq terms together with the
//! kernel's exact values, and `BridgeC34.v`'s checker, evaluated by `coqc` (`vm_compute`),
//! compares them with the Coq definitions:
//!
//! - C4-corrected: every simple goal path's `(L(u), S(u))` from `c4::Instance::goal_paths`
//!   (in its depth-first order), `Lav(Ĉ)` from `Instance::least_mean_cycle`, and for every
//!   `S*` the bonus sets of `c4::bonus_analysis` (`L*`, `S*`, `Lav(Ĉ)` and the corrected
//!   interval, `M < 0` included: its ends, open or closed, and whether it is empty) against
//!   `G*(x1)`, `goal_paths`, `Lav`, `sstars`, `c_lo`/`c_hi` (`BridgeC34.v` proves these exact
//!   for C4.v's `corrected_interval`, the set of `c4_corrected`).
//! - C3: the goal-avoiding core of `c3::goal_avoiding_core` against C3.v's `in_core`, and the
//!   certificate of `c3::certificate` for three discount factors against the move costs of
//!   C3.v's `engine_certificate` with `lasso_marks` of `core_pi` (the certificate of
//!   `c3_engine`), or neither side building one.
//!
//! Coq prints how many problems and values it compared and the list of mismatches; the test
//! requires none, and at least 1,000 problems. A second run writes a few problems with planted
//! wrong values (a `T(u)` off by one in an interval end, a wrong `S(u)`, a certificate cost)
//! and requires Coq to report exactly those.
//!
//! Without `coqc` on `PATH` the test fails with the install line (no silent skip). The Coq
//! development is `../proofs/coq` from this crate, or the directory in `TRUECOST_COQ_DIR`.

#[path = "support/coq.rs"]
mod coq_support;

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use truecost_kernel::claims::c3::{certificate, goal_avoiding_core};
use truecost_kernel::claims::c4::{bonus_analysis, End, Instance, Interval};
use truecost_kernel::claims::exact::Q;
use truecost_kernel::claims::tiny::{Family, FamilySpec, Tiny};

use coq_support::{check_all, list, parse, prepare, Verdict};

/// The policy bound of the bonus analysis (as `verify` runs it).
const LIMIT: u64 = 1 << 20;

/// The discount factors `alpha0` of the certificates: `claims::c3::alphas()` and one more.
fn alphas() -> Vec<Q> {
    vec![Q::new(1, 2), Q::new(9, 10), Q::new(1, 3)]
}

/// The scopes, and the stride at which each one's labelled problems are sampled (every
/// `stride`-th labelled problem, kept if it is its class's representative).
fn scopes() -> Vec<(FamilySpec, u64)> {
    let spec = |states, degree, goal_degree, costs: &[u8]| FamilySpec {
        states,
        initial_fixed: true,
        degree,
        goal_degree,
        costs: costs.to_vec(),
        distinct_successors: false,
    };
    // C3's quick scope (as `claims::c3` enumerates it for the SMT engine): every structure,
    // distinct successors, the costs replaced by the certificate's.
    let structure = |states, d| FamilySpec {
        states,
        initial_fixed: true,
        degree: (1, d),
        goal_degree: (0, 0),
        costs: vec![0],
        distinct_successors: true,
    };
    vec![
        (structure(2, 2), 1),
        (structure(3, 3), 1),
        (structure(4, 2), 1),
        // C4's verify scopes: no move at the goal, 1-2 moves, costs with 0. 8,100 labelled
        // problems, every 29th.
        (spec(3, (1, 2), (0, 0), &[0, 1, 2, 3]), 29),
        // 729,000 labelled problems (about half representatives), every 1,399th.
        (spec(4, (1, 2), (0, 0), &[0, 1, 3]), 1_399),
        // Parallel moves and moves at the goal (the certificate recosts them too): 39,698,496
        // labelled problems, every 79,999th.
        (spec(4, (1, 3), (0, 1), &[0, 2]), 79_999),
        // 17,850,625 labelled problems (about a sixth representatives), every 11,999th.
        (spec(5, (1, 2), (0, 0), &[0, 1]), 11_999),
    ]
}

/// One problem and what the kernel computes for it.
#[derive(Clone)]
struct Case {
    tiny: Tiny,
    lstar: Option<Q>,
    /// `(L(u), S(u))` of every simple goal path from `x1`.
    paths: Vec<(i64, i64)>,
    lav: Option<Q>,
    /// `(L*, S*, Lav, corrected interval)` for every `S*`.
    sets: Vec<(i64, i64, Option<Q>, Interval)>,
    core: Vec<bool>,
    /// `(alpha0, certificate's costs state by state)`.
    certs: Vec<(Q, Option<Vec<Vec<u8>>>)>,
}

fn case(t: &Tiny) -> Case {
    let inst = Instance::from_tiny(t);
    let n = t.states();
    let sets: Vec<_> = bonus_analysis(&inst, LIMIT)
        .unwrap_or_else(|e| panic!("{}: {e}", t.describe()))
        .unwrap_or_default()
        .into_iter()
        .map(|s| {
            // The exact oracle (every stationary policy's average cost) gives the set the
            // corrected formula gives, which Coq checks against its interval: the exact
            // oracle agrees with C4.v's `corrected_interval` (`c4_corrected`).
            assert!(
                s.exact.same_set(&s.corrected),
                "{}: exact {} vs corrected {}",
                t.describe(),
                s.exact,
                s.corrected
            );
            (
                s.optimal_cost,
                s.optimal_states,
                s.least_mean_cycle,
                s.corrected,
            )
        })
        .collect();
    let certs = alphas()
        .into_iter()
        .map(|a| {
            let costs = certificate(t, a).map(|c| {
                (0..n)
                    .map(|x| c.moves(x).iter().map(|m| m.cost).collect())
                    .collect()
            });
            (a, costs)
        })
        .collect();
    Case {
        tiny: *t,
        lstar: sets.first().map(|s| Q::int(s.0 as i128)),
        paths: inst.goal_paths(LIMIT).unwrap(),
        lav: inst.least_mean_cycle().unwrap(),
        sets,
        core: goal_avoiding_core(t)[..n].to_vec(),
        certs,
    }
}

fn q(v: Q) -> String {
    format!("({} # {})", v.numer(), v.denom())
}

fn qi(v: i64) -> String {
    format!("({v} # 1)")
}

fn oq(v: Option<Q>) -> String {
    v.map_or("None".into(), |v| format!("(Some {})", q(v)))
}

fn end(e: End) -> String {
    match e {
        End::Unbounded => "Unb".into(),
        End::Closed(v) => format!("(Cl {})", q(v)),
        End::Open(v) => format!("(Op {})", q(v)),
    }
}

/// `(problem, expected)` as a Coq term.
fn coq_term(c: &Case) -> String {
    let t = &c.tiny;
    let moves = list((0..t.states()).map(|x| {
        list(
            t.moves(x)
                .iter()
                .map(|m| format!("({}%nat, {})", m.to, qi(m.cost as i64))),
        )
    }));
    let paths = list(
        c.paths
            .iter()
            .map(|&(l, s)| format!("({}, {s}%nat)", qi(l))),
    );
    let sets = list(c.sets.iter().map(|(l, s, lav, iv)| {
        format!(
            "({}, {s}%nat, {}, ({}, {}, {}))",
            qi(*l),
            oq(*lav),
            end(iv.lo),
            end(iv.hi),
            iv.empty
        )
    }));
    let certs = list(c.certs.iter().map(|(a, costs)| {
        let costs = costs.as_ref().map_or("None".into(), |cs| {
            format!(
                "(Some {})",
                list(cs.iter().map(|row| list(row.iter().map(|&k| qi(k as i64)))))
            )
        });
        format!("({}, {costs})", q(*a))
    }));
    format!(
        "(mk {} {moves}, {{| e_Lstar := {}; e_paths := {paths}; e_Lav := {}; e_sets := {sets}; \
         e_core := {}; e_certs := {certs} |}})",
        t.states(),
        oq(c.lstar),
        oq(c.lav),
        list(c.core.iter().map(|b| b.to_string())),
    )
}

/// Writes `cases` as a Coq file in `work`, evaluates `check_all` on them with `coqc`.
fn coq_check(dir: &Path, work: &Path, name: &str, cases: &[Case]) -> Verdict {
    let terms: Vec<String> = cases.iter().map(coq_term).collect();
    check_all(dir, work, name, "BridgeC34", &terms)
}

/// The kernel's value at a mismatch, for the failure message.
fn kernel_value(c: &Case, what: &str, k: usize) -> String {
    let get = |v: Option<String>| v.unwrap_or_else(|| "(no entry)".into());
    match what {
        "Lstar" => format!("{:?}", c.lstar.map(|v| v.to_string())),
        "paths" => get(c.paths.get(k).map(|v| format!("(L, S) = {v:?}"))),
        "Lav" => format!("{:?}", c.lav.map(|v| v.to_string())),
        "sets" => get(c
            .sets
            .get(k)
            .map(|(l, s, lav, iv)| format!("L* = {l}, S* = {s}, Lav = {lav:?}, corrected = {iv}"))),
        "core" => get(c.core.get(k).map(|v| v.to_string())),
        _ => get(c
            .certs
            .get(k)
            .map(|(a, v)| format!("{v:?} for alpha0 = {a}"))),
    }
}

#[test]
fn c3_c4_definitions_equal_the_kernel_oracles_on_enumerated_problems() {
    let started = Instant::now();
    let (dir, work) = prepare("BridgeC34.vo", "coq-bridge-c34");
    eprintln!(
        "make -C {} BridgeC34.vo: {:.1} s",
        dir.display(),
        started.elapsed().as_secs_f64()
    );
    let mut all = Vec::new();
    let (mut total, mut checked, mut values) = (0usize, 0u64, 0u64);
    let (mut failures, mut mismatches) = (String::new(), 0usize);
    for (f, (spec, stride)) in scopes().iter().enumerate() {
        let family = Family::new(spec);
        let cases: Vec<Case> = (0..family.labelled_count())
            .step_by(*stride as usize)
            .map(|i| family.problem(i))
            .filter(|t| family.is_canonical(t))
            .map(|t| case(&t))
            .collect();
        let v = coq_check(&dir, &work, &format!("bridge_c34_{f}"), &cases);
        assert_eq!(v.problems, cases.len() as u64, "{}", spec.describe());
        for (i, what, k) in &v.mismatches {
            mismatches += 1;
            if mismatches > 20 {
                continue;
            }
            let c = &cases[*i];
            writeln!(
                failures,
                "{} | problem {} ({}): the Coq definitions' {what} differ from the kernel at \
                 position {k} (kernel: {})",
                spec.describe(),
                i,
                c.tiny.describe(),
                kernel_value(c, what, *k)
            )
            .unwrap();
        }
        eprintln!(
            "{}: {} problems, {} values, {} mismatches",
            spec.describe(),
            v.problems,
            v.values,
            v.mismatches.len()
        );
        total += cases.len();
        checked += v.problems;
        values += v.values;
        all.extend(cases);
    }
    std::fs::remove_dir_all(&work).ok();
    eprintln!(
        "Coq checked {checked} problems ({values} values) against the kernel's C3 and C4 oracles \
         in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert!(
        mismatches == 0,
        "{mismatches} mismatches between C3.v/C4.v and the kernel (the first {}):\n{failures}",
        mismatches.min(20)
    );
    assert_eq!(checked, total as u64);
    assert!(checked >= 1_000, "only {checked} problems checked");

    // The sample covers every shape of the corrected interval and of the certificate.
    let sets: Vec<&(i64, i64, Option<Q>, Interval)> =
        all.iter().flat_map(|c| c.sets.iter()).collect();
    let count = |p: &dyn Fn(&Interval) -> bool| sets.iter().filter(|s| p(&s.3)).count();
    let closed_lo = count(&|i| matches!(i.lo, End::Closed(_)) && !i.empty);
    let closed_hi = count(&|i| matches!(i.hi, End::Closed(_)) && !i.empty);
    let empty = count(&|i| i.empty);
    let from_cycle = sets
        .iter()
        .filter(|s| {
            s.2.is_some_and(|l| {
                s.3.hi == End::Closed(Q::int(s.1 as i128) * l - Q::int(s.0 as i128))
            })
        })
        .count();
    eprintln!(
        "{} (problem, S*) pairs: {closed_lo} closed lower ends, {closed_hi} closed upper ends \
         ({from_cycle} at S* Lav - L*), {empty} empty",
        sets.len()
    );
    assert!(closed_lo >= 20 && closed_hi >= 20 && empty >= 5 && from_cycle >= 5);
    assert!(all.iter().filter(|c| c.sets.len() >= 2).count() >= 5);
    assert!(all.iter().filter(|c| c.lstar.is_none()).count() >= 5);
    let built = all
        .iter()
        .filter(|c| c.certs.iter().all(|(_, k)| k.is_some()))
        .count();
    assert!(
        built >= 50 && all.len() - built >= 50,
        "{built} of {}",
        all.len()
    );
}

/// The checker can fail: planted wrong values (as a wrong oracle would produce them) are
/// reported by Coq at exactly their places.
#[test]
fn planted_wrong_values_are_reported() {
    let (dir, work) = prepare("BridgeC34.vo", "coq-bridge-c34");
    // 0 -> 1 (cost 1), 0 -> 3 (cost 5), 1 -> 2 (cost 0), 1 -> 3 (cost 1), 2 -> 1 (cost 2):
    // L* = 2 (S* = 3), T(0 -> 3) = (3*5 - 2*2)/(2 - 3) = -11, the cycle 1 -> 2 -> 1 (mean 1).
    let t = Tiny::from_lists(&[
        vec![(1, 1), (3, 5)],
        vec![(2, 0), (3, 1)],
        vec![(1, 2)],
        vec![],
    ]);
    let good = case(&t);
    assert_eq!(good.sets[0].3.lo, End::Closed(Q::int(-11)));
    let mut planted = Vec::new();
    // A T(u) off by one: the corrected interval's lower end.
    let mut c = good.clone();
    c.sets[0].3.lo = End::Closed(Q::int(-10));
    planted.push(c);
    // A simple goal path's S(u) off by one.
    let mut c = good.clone();
    c.paths[1].1 += 1;
    planted.push(c);
    // Lav(C^) wrong.
    let mut c = good.clone();
    c.lav = Some(Q::new(1, 2));
    planted.push(c);
    // A certificate cost wrong (alpha0 = 9/10, state 1's second move).
    let mut c = good.clone();
    c.certs[1].1.as_mut().unwrap()[1][1] += 1;
    planted.push(c);
    // The goal-avoiding core wrong at state 2.
    let mut c = good.clone();
    c.core[2] = !c.core[2];
    planted.push(c);
    planted.push(good);
    let v = coq_check(&dir, &work, "bridge_c34_planted", &planted);
    std::fs::remove_dir_all(&work).ok();
    assert_eq!(v.problems, 6);
    assert_eq!(
        v.mismatches,
        vec![
            (0, "sets".into(), 0),
            (1, "paths".into(), 1),
            (2, "Lav".into(), 0),
            (3, "cert".into(), 1),
            (4, "core".into(), 2),
        ]
    );
}

/// The numbers of `C4.c4_as_printed_refuted_positive_costs` are the kernel's: on `c4pos`
/// (0 -> 1 cost 1, 1 -> 2 cost 1, 0 -> 2 cost 3, goal 2) `L* = 2`, `S* = 3`, no goal-avoiding
/// cycle; the printed lower end is `A(0 -> 2) = (1 - 2/3)(2*2/(3*3) - 1) = -5/27`, the
/// corrected one `T(0 -> 2) = (3*3 - 2*2)/(2 - 3) = -5`, and the exact oracle's set starts at
/// `-5` too (the average `(2 + M)/3` of pi* against `(3 + M)/2` of 0 -> 2 -> reset). Coq's
/// checker finds no mismatch on the problem.
#[test]
fn the_positive_cost_counterexample_of_c4_is_the_kernels() {
    let (dir, work) = prepare("BridgeC34.vo", "coq-bridge-c34");
    let t = Tiny::from_lists(&[vec![(1, 1), (2, 3)], vec![(2, 1)], vec![]]);
    let sets = bonus_analysis(&Instance::from_tiny(&t), LIMIT)
        .unwrap()
        .unwrap();
    assert_eq!(sets.len(), 1);
    let s = &sets[0];
    assert_eq!(
        (s.optimal_cost, s.optimal_states, s.least_mean_cycle),
        (2, 3, None)
    );
    let printed = s.printed.expect("the printed formula applies (L(u) > 0)");
    assert_eq!(printed.lo, End::Closed(Q::new(-5, 27)));
    assert_eq!(s.corrected.lo, End::Closed(Q::int(-5)));
    for m in [Q::int(-5), Q::new(-1, 5)] {
        assert!(s.exact.contains(m) && !printed.contains(m), "{m}");
    }
    assert!(!s.exact.contains(Q::new(-51, 10)));
    // A planted wrong exact set is told apart from the corrected one.
    let mut wrong = s.exact;
    wrong.lo = End::Closed(Q::new(-5, 27));
    assert!(!wrong.same_set(&s.corrected));
    let v = coq_check(&dir, &work, "bridge_c34_c4pos", &[case(&t)]);
    std::fs::remove_dir_all(&work).ok();
    assert_eq!((v.problems, v.mismatches.len()), (1, 0), "{v:?}");
}

/// The parser reads Coq's printing of `check_all`, with and without mismatches.
#[test]
fn coq_output_is_parsed() {
    let v = parse("     = (388%nat, 9000%nat, [])\n     : nat * nat * list mismatch\n").unwrap();
    assert_eq!((v.problems, v.values, v.mismatches.len()), (388, 9000, 0));
    let v = parse(
        "     = (2%nat, 30%nat,\n        [(0%nat, \"sets\"%string, 1%nat);\n         (1%nat, \"cert\"%string, 2%nat)])\n     : nat * nat * list mismatch\n",
    )
    .unwrap();
    assert_eq!(
        v.mismatches,
        vec![(0, "sets".into(), 1), (1, "cert".into(), 2)]
    );
    assert!(parse("Error: something").is_none());
}
