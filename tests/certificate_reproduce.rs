//! `reproduce stochastic --certificates DIR`: one certificate per problem and γ of the run,
//! named by both, each accepted by `truecost check --problem N`; the directory holds nothing
//! else.

mod common;

use common::cli::{json, stdout};

#[test]
fn reproduce_stochastic_writes_one_checkable_certificate_per_problem_and_gamma() {
    let dir = tempfile::tempdir().unwrap();
    let certs = dir.path().join("certs");
    let c = certs.display().to_string();
    for (noise, tolerance) in [("paper", "relative"), ("reference", "reference")] {
        stdout(&[
            "reproduce",
            "stochastic",
            "--problems",
            "3,10",
            "--gammas",
            "0.9,0.99",
            "--rhos",
            "0.5",
            "--epsilons",
            "0.1",
            "--samples",
            "1",
            "--episodes",
            "1",
            "--max-steps",
            "5",
            "--noise",
            noise,
            "--tolerance",
            tolerance,
            "--quiet",
            "--certificates",
            &c,
        ]);
        let mut names: Vec<String> = std::fs::read_dir(&certs)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "problem-10-gamma-0.9.cert.json",
                "problem-10-gamma-0.99.cert.json",
                "problem-3-gamma-0.9.cert.json",
                "problem-3-gamma-0.99.cert.json",
            ]
        );
        for name in &names {
            let id = name
                .strip_prefix("problem-")
                .unwrap()
                .split('-')
                .next()
                .unwrap();
            let path = certs.join(name).display().to_string();
            let v = json(&["check", "--problem", id, &path, "--format", "json"]);
            assert_eq!(v["accepted"], true, "{name}: {v}");
            assert_eq!(v["objective"], "truecost", "{name}");
            assert_eq!(v["states"], 400, "{name}");
            let cert: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(certs.join(name)).unwrap()).unwrap();
            assert_eq!(cert["problem"]["noise"], noise, "{name}");
            let step = if tolerance == "reference" {
                "euclidean"
            } else {
                "unit"
            };
            assert_eq!(cert["problem"]["step_cost"], step, "{name}");
            let gamma = name
                .trim_end_matches(".cert.json")
                .rsplit("gamma-")
                .next()
                .unwrap();
            assert_eq!(cert["problem"]["gamma"], gamma, "{name}");
        }
        std::fs::remove_dir_all(&certs).unwrap();
    }
}
