//! Reading back the SMT-LIB files that `verify --smt-out` writes, shared by
//! the SMT tests.

use truecost::claims::smt::{Obligation, Sort};

/// Reads an SMT-LIB file written by `write_files` back into an obligation (one command a line).
pub fn parse_back(text: &str, template: &Obligation) -> (Obligation, Option<String>) {
    let mut o = Obligation::new(
        &template.claim,
        &template.lemma,
        &template.structure,
        template.role.clone(),
        template.logic,
    );
    let mut status = None;
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("(declare-const ") {
            let (name, sort) = rest.trim_end_matches(')').split_once(' ').expect("a sort");
            let sort = match sort {
                "Real" => Sort::Real,
                "Int" => Sort::Int,
                "Bool" => Sort::Bool,
                other => panic!("sort {other}"),
            };
            o.declare(name, sort);
        } else if let Some(rest) = line.strip_prefix("(assert ") {
            o.assert(rest.strip_suffix(')').expect("closing").to_string());
        } else if let Some(rest) = line.strip_prefix("(set-info :status ") {
            status = Some(rest.trim_end_matches(')').to_string());
        }
    }
    (o, status)
}

/// The encoding is refuted by the SMT engine: some proof obligation is satisfiable, and every
/// such model replays as a real failure through the claim's exact oracle.
pub fn assert_refuted(enc: truecost::claims::smt::Encoding) {
    use truecost::claims::smt::{run, Answer, Replay, Role, SmtVerdict, Status, TIMEOUT_MS};
    let (claim, replay) = (enc.claim, enc.replay);
    let out = run(enc, TIMEOUT_MS);
    assert_eq!(out.verdict, SmtVerdict::Refuted, "{claim}: {:?}", out.notes);
    let failing: Vec<_> = out
        .solved
        .iter()
        .filter(|s| s.obligation.role == Role::Proof && s.answer.status() == Some(Status::Sat))
        .collect();
    assert!(!failing.is_empty());
    for s in failing {
        let Answer::Sat(Some(m)) = &s.answer else {
            panic!("no rational model")
        };
        assert!(matches!(replay(&s.obligation, m), Replay::Confirmed(..)));
    }
}

/// `write_files` writes one file per solved obligation, stated in one of `logics`, that reads
/// back to the same assertions and status and re-solves to the same answer.
pub fn assert_files_parse_back(solved: &[truecost::claims::smt::Solved], logics: &[&str]) {
    use truecost::claims::smt::{solve, write_files, TIMEOUT_MS};
    let dir = tempfile::tempdir().expect("a temporary directory");
    write_files(dir.path(), solved).expect("files written");
    let index = std::fs::read_to_string(dir.path().join("index.tsv")).expect("an index");
    assert_eq!(index.lines().count(), solved.len() + 1);
    for (line, s) in index.lines().skip(1).zip(solved) {
        let file = line.split('\t').next().expect("a file name");
        let text = std::fs::read_to_string(dir.path().join(file)).expect("a file");
        assert!(logics
            .iter()
            .any(|l| text.contains(&format!("(set-logic {l})"))));
        let (o, status) = parse_back(&text, &s.obligation);
        assert_eq!(o.asserts, s.obligation.asserts);
        assert_eq!(status.as_deref(), Some(s.answer.name()));
        assert_eq!(solve(&o, TIMEOUT_MS).status(), s.answer.status());
    }
}
