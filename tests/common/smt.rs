//! Reading back the SMT-LIB files that `verify --smt-out` writes (issue 9, item 6), shared by
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
