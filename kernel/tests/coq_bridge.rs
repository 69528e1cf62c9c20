//! The bridge between the Coq development (`proofs/coq/`) and the kernel's oracles: the
//! definitions the Coq theorems are about (`Model.v`: `Gstar`, `Qstar`, `hstar`, `R1`,
//! `round_bound`) must be the quantities the kernel computes. Problems of `claims::tiny`'s
//! enumeration are written as Coq terms together with the kernel's exact values — `G*` from
//! `oracle::optimal_cost_to_go` (policy enumeration), `Q*` from `QProblem::optimum`, `h` from
//! `QProblem::optimal_steps` and the round bound of C1-corrected from `QProblem::round_bound`
//! for three initial vectors — and `Bridge.v`'s checker, evaluated by `coqc`, compares them
//! with Model.v's definitions. Coq prints how many problems and values it compared and the list
//! of mismatches; the test requires none, and at least 1,000 problems. A second test plants
//! wrong values (`G*`, `Q*`, `h`, `R1`, a round bound, as a wrong oracle would produce them)
//! and requires Coq to report exactly those.
//!
//! Without `coqc` on `PATH` the test fails with the install line (no silent skip). The Coq
//! development is `../proofs/coq` from this crate, or the directory in `TRUECOST_COQ_DIR`
//! (so that a copy of this crate with a planted oracle can be checked against the tree's
//! proofs).

#[path = "support/coq.rs"]
mod coq_support;

use std::fmt::Write as _;

use std::path::Path;
use std::time::Instant;

use truecost_kernel::claims::oracle::optimal_cost_to_go;
use truecost_kernel::claims::qlearning::{QProblem, Terminal, Values, MAX_PAIRS};
use truecost_kernel::claims::tiny::{Family, FamilySpec, Tiny};

use coq_support::{check_all, list, parse, prepare, Verdict};

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
    vec![
        // 2 states, 1-3 moves, 0-2 at the goal, costs with 0: 2,324 problems, every 6th.
        (spec(2, (1, 3), (0, 2), &[0, 1, 2]), 6),
        // 3 states, 1-2 moves, 0-1 at the goal: 5,103 problems, every 13th.
        (spec(3, (1, 2), (0, 1), &[0, 2]), 13),
        // 4 states, 1-2 moves, positive costs (Part B of the round bound applies).
        (spec(4, (1, 2), (0, 1), &[1, 3]), 2_111),
        // 4 states, one move each, 0-1 at the goal, costs with 0.
        (spec(4, (1, 1), (0, 1), &[0, 1, 3]), 97),
    ]
}

/// One problem and what the kernel computes for it.
#[derive(Clone)]
struct Case {
    tiny: Tiny,
    gstar: Vec<Option<i64>>,
    qstar: Vec<Option<i64>>,
    h: Vec<Option<u32>>,
    r1: Option<u64>,
    /// Initial vectors (one entry per pair, in pair order) and the kernel's round bound.
    rounds: Vec<(Vec<i64>, Option<u64>)>,
}

fn case(t: &Tiny) -> Case {
    let q = QProblem::new(t, Terminal::HeldAtZero);
    let n = t.states();
    let pairs = q.len();
    let vector = |f: &dyn Fn(usize) -> i64| -> (Vec<i64>, Values) {
        let mut v = [0i64; MAX_PAIRS];
        for (p, x) in v.iter_mut().enumerate().take(pairs) {
            *x = f(p);
        }
        (v[..pairs].to_vec(), v)
    };
    // All zero; one above Q* (Q* + 1, 50 where Q* is +oo); one with negative entries.
    let zero = vector(&|_| 0);
    let above = vector(&|p| q.optimum[p].map_or(50, |v| v + 1));
    let negative = vector(&|p| (p % 3) as i64 - 2);
    let rounds: Vec<(Vec<i64>, Option<u64>)> = [zero, above, negative]
        .into_iter()
        .map(|(list, v)| (list, q.round_bound(&v)))
        .collect();
    Case {
        tiny: *t,
        gstar: optimal_cost_to_go(t)[..n].to_vec(),
        qstar: q.optimum.clone(),
        h: q.optimal_steps()[..n].to_vec(),
        // Part A of the round bound: with Q0 above Q* the bound is R1 (None if some h is +oo).
        r1: rounds[1].1,
        rounds,
    }
}

fn q(v: i64) -> String {
    format!("({v} # 1)")
}

fn oq(v: Option<i64>) -> String {
    v.map_or("None".into(), |v| format!("(Some {})", q(v)))
}

fn on(v: Option<u64>) -> String {
    v.map_or("None".into(), |v| format!("(Some {v}%nat)"))
}

/// `(problem, expected)` as a Coq term.
fn coq_term(c: &Case) -> String {
    let t = &c.tiny;
    let moves = list((0..t.states()).map(|x| {
        list(
            t.moves(x)
                .iter()
                .map(|m| format!("({}%nat, {})", m.to, q(m.cost as i64))),
        )
    }));
    let rounds = list(
        c.rounds
            .iter()
            .map(|(v, r)| format!("({}, {})", list(v.iter().map(|&x| q(x))), on(*r))),
    );
    format!(
        "(mk {} {moves}, {{| e_Gstar := {}; e_Qstar := {}; e_h := {}; e_R1 := {}; e_rounds := {rounds} |}})",
        t.states(),
        list(c.gstar.iter().map(|&v| oq(v))),
        list(c.qstar.iter().map(|&v| oq(v))),
        list(c.h.iter().map(|&v| on(v.map(u64::from)))),
        on(c.r1),
    )
}

/// Writes `cases` as a Coq file in `work` and evaluates `check_all` on them with `coqc`.
fn coq_check(dir: &Path, work: &Path, name: &str, cases: &[Case]) -> Verdict {
    let terms: Vec<String> = cases.iter().map(coq_term).collect();
    check_all(dir, work, name, "Bridge", &terms)
}

/// The kernel's value at a mismatch, for the failure message.
fn kernel_value(c: &Case, what: &str, k: usize) -> String {
    let get = |v: Option<String>| v.unwrap_or_else(|| "(no entry)".into());
    match what {
        "Gstar" => get(c.gstar.get(k).map(|v| format!("{v:?}"))),
        "Qstar" => get(c.qstar.get(k).map(|v| format!("{v:?}"))),
        "h" => get(c.h.get(k).map(|v| format!("{v:?}"))),
        "R1" => format!("{:?}", c.r1),
        _ => get(c
            .rounds
            .get(k)
            .map(|(v, r)| format!("{r:?} for q0 = {v:?}"))),
    }
}

#[test]
fn model_definitions_equal_the_kernel_oracles_on_enumerated_problems() {
    let started = Instant::now();
    // Only what the checker needs (Model.v, Bridge.v): the other proofs are built and checked
    // by `make -C proofs/coq` in CI and by the crate `truecost`'s Coq test.
    let (dir, work) = prepare("Bridge.vo", "coq-bridge");
    eprintln!(
        "make -C {}: {:.1} s",
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
        let v = coq_check(&dir, &work, &format!("bridge_{f}"), &cases);
        assert_eq!(v.problems, cases.len() as u64, "{}", spec.describe());
        for (i, what, k) in &v.mismatches {
            mismatches += 1;
            if mismatches > 20 {
                continue;
            }
            let c = &cases[*i];
            writeln!(
                failures,
                "{} | problem {} ({}): Model.v's {what} differs from the kernel at position {k} \
                 (kernel: {})",
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
        "Coq checked {checked} problems ({values} values) against the kernel's oracles in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert!(
        mismatches == 0,
        "{mismatches} mismatches between Model.v and the kernel (the first {}):\n{failures}",
        mismatches.min(20)
    );
    assert_eq!(checked, total as u64);
    assert!(checked >= 1_000, "only {checked} problems checked");

    // The sample mixes problems where every state reaches the goal and problems where some
    // state does not, and round bounds of both parts and none.
    let reach_all = all
        .iter()
        .filter(|c| c.gstar.iter().all(Option::is_some))
        .count();
    assert!(
        reach_all >= 100 && all.len() - reach_all >= 100,
        "{reach_all} of {}",
        all.len()
    );
    let bounds: Vec<Option<u64>> = all
        .iter()
        .flat_map(|c| [c.rounds[0].1, c.rounds[2].1])
        .collect();
    let some = bounds.iter().filter(|b| b.is_some()).count();
    assert!(some >= 100 && bounds.len() - some >= 100, "{some}");
    assert!(all.iter().filter(|c| c.r1.is_some_and(|r| r >= 3)).count() >= 10);
}

/// The checker can fail: planted wrong values (as a wrong oracle would produce them) are
/// reported by Coq at exactly their places.
#[test]
fn planted_wrong_values_are_reported() {
    let (dir, work) = prepare("Bridge.vo", "coq-bridge-planted");
    // 0 -> 1 (cost 1), 0 -> 2 (cost 4), 1 -> 2 (cost 1), the goal 2: G* = (2, 1, 0), the
    // pairs (0,0->1) (0,0->2) (1,1->2) (2,uT), h = (2, 1, 0).
    let t = Tiny::from_lists(&[vec![(1, 1), (2, 4)], vec![(2, 1)], vec![]]);
    let good = case(&t);
    assert_eq!(good.gstar, vec![Some(2), Some(1), Some(0)]);
    assert_eq!(good.h, vec![Some(2), Some(1), Some(0)]);
    let mut planted = Vec::new();
    // G*(x1) off by one.
    let mut c = good.clone();
    c.gstar[0] = Some(3);
    planted.push(c);
    // Q* of the second pair off by one.
    let mut c = good.clone();
    c.qstar[1] = Some(5);
    planted.push(c);
    // h of state 1 wrong.
    let mut c = good.clone();
    c.h[1] = Some(2);
    planted.push(c);
    // R1 wrong.
    let mut c = good.clone();
    c.r1 = c.r1.map(|r| r + 1);
    planted.push(c);
    // The round bound of the third initial vector wrong.
    let mut c = good.clone();
    c.rounds[2].1 = Some(c.rounds[2].1.map_or(0, |r| r + 1));
    planted.push(c);
    planted.push(good);
    let v = coq_check(&dir, &work, "bridge_planted", &planted);
    std::fs::remove_dir_all(&work).ok();
    assert_eq!(v.problems, 6);
    assert_eq!(
        v.mismatches,
        vec![
            (0, "Gstar".into(), 0),
            (1, "Qstar".into(), 1),
            (2, "h".into(), 1),
            (3, "R1".into(), 0),
            (4, "round_bound".into(), 2),
        ]
    );
}

/// The parser reads Coq's printing of `check_all`, with and without mismatches.
#[test]
fn coq_output_is_parsed() {
    let v = parse("     = (388%nat, 9000%nat, [])\n     : nat * nat * list mismatch\n").unwrap();
    assert_eq!((v.problems, v.values, v.mismatches.len()), (388, 9000, 0));
    let v = parse(
        "     = (2%nat, 30%nat,\n        [(0%nat, \"h\"%string, 1%nat);\n         (1%nat, \"round_bound\"%string, 2%nat)])\n     : nat * nat * list mismatch\n",
    )
    .unwrap();
    assert_eq!(
        v.mismatches,
        vec![(0, "h".into(), 1), (1, "round_bound".into(), 2)]
    );
    assert!(parse("Error: something").is_none());
}
