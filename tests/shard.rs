//! Sharding over many machines: three shards run as separate processes and
//! their merge is compared with the whole run — `verify` byte for byte (text and JSON, times
//! left out), `reproduce deterministic|stochastic` field by field apart from times — and every
//! incomplete or foreign set of shards is refused with one line and exit 1.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn truecost(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_truecost"))
        .args(args)
        .output()
        .expect("the truecost binary runs")
}

fn ok(args: &[&str]) -> String {
    let out = truecost(args);
    assert!(
        out.status.success(),
        "truecost {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8")
}

/// A fresh directory under the target directory.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("shard-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    dir
}

/// Runs `args --shard k/3` for k = 1, 2, 3 as three processes; returns the three files.
fn three_shards(dir: &Path, args: &[&str]) -> Vec<String> {
    (1..=3)
        .map(|k| {
            let part = format!("{k}/3");
            let mut a = args.to_vec();
            a.extend(["--shard", &part]);
            let path = dir.join(format!("shard{k}.json"));
            std::fs::write(&path, ok(&a)).expect("write the shard file");
            path.display().to_string()
        })
        .collect()
}

fn error_line(out: &Output) -> String {
    let e = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(e.lines().count(), 1, "one line: {e}");
    e
}

#[test]
fn verify_merge_of_three_shards_is_the_whole_report_byte_for_byte() {
    let dir = scratch("verify");
    let files = three_shards(&dir, &["verify", "--no-coq", "--scope", "smoke"]);
    // The shards split the work: their enumerations' case counts differ from the whole run's.
    let shard1: Value = serde_json::from_str(&std::fs::read_to_string(&files[0]).unwrap()).unwrap();
    assert_eq!(shard1["shard"], "1/3");
    assert_eq!(shard1["fingerprint"]["scope"], "smoke");
    for format in ["text", "json", "markdown", "latex"] {
        let whole = ok(&[
            "verify",
            "--no-coq",
            "--scope",
            "smoke",
            "--no-times",
            "--format",
            format,
        ]);
        let mut merge = vec!["verify", "merge", "--format", format];
        // Any order of the files.
        merge.extend([files[2].as_str(), files[0].as_str(), files[1].as_str()]);
        let merged = ok(&merge);
        assert_eq!(merged, whole, "format {format}");
    }
    let whole: Value = serde_json::from_str(&ok(&[
        "verify",
        "--no-coq",
        "--scope",
        "smoke",
        "--no-times",
        "--format",
        "json",
    ]))
    .unwrap();
    // Something was refuted with a counterexample, so the merge chose among candidates.
    assert!(whole["claims"]
        .as_array()
        .unwrap()
        .iter()
        .any(|c| c["verdict"] == "refuted" && c["counterexample"].is_object()));
}

#[test]
fn verify_merge_refuses_missing_duplicate_and_foreign_shards() {
    let dir = scratch("verify-refusals");
    let files = three_shards(
        &dir,
        &["verify", "--no-coq", "--scope", "smoke", "--claim", "C2"],
    );
    let other = three_shards(
        &scratch("verify-refusals-other"),
        &["verify", "--no-coq", "--scope", "smoke", "--claim", "C3"],
    );
    let missing = truecost(&["verify", "merge", &files[0], &files[2]]);
    assert_eq!(missing.status.code(), Some(1));
    assert!(error_line(&missing).contains("shard 2/3 is missing"));
    let twice = truecost(&[
        "verify", "merge", &files[0], &files[1], &files[1], &files[2],
    ]);
    assert_eq!(twice.status.code(), Some(1));
    assert!(error_line(&twice).contains("given twice"));
    let foreign = truecost(&["verify", "merge", &files[0], &other[1], &files[2]]);
    assert_eq!(foreign.status.code(), Some(1));
    assert!(error_line(&foreign).contains("different run"));
    // An edited file fails its checksum.
    let text = std::fs::read_to_string(&files[1]).unwrap();
    let edited = dir.join("edited.json");
    let changed = text.replacen("\\\"cases\\\":", "\\\"cases\\\":1", 1);
    assert_ne!(changed, text, "the shard records case counts");
    std::fs::write(&edited, changed).unwrap();
    let out = truecost(&[
        "verify",
        "merge",
        &files[0],
        &edited.display().to_string(),
        &files[2],
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(error_line(&out).contains("checksum"));
    // An endless stream named as a shard is refused at the limit, by both merges.
    for command in ["verify", "reproduce"] {
        let out = truecost(&[command, "merge", "/dev/zero", &files[1]]);
        assert_eq!(out.status.code(), Some(1), "{command}");
        assert!(
            error_line(&out).contains("the limit for shard files"),
            "{command}: {}",
            error_line(&out)
        );
    }
    // K/N is checked before any work.
    for bad in ["0/3", "4/3", "1/0", "1/4097", "x", "1/2/3"] {
        let out = truecost(&["verify", "--no-coq", "--scope", "smoke", "--shard", bad]);
        assert_eq!(out.status.code(), Some(1), "--shard {bad}");
        assert!(error_line(&out).contains("expected K/N"));
    }
    let out = truecost(&["verify", "--shard", "1/2", "--counterexamples", "x"]);
    assert_eq!(out.status.code(), Some(2));
}

/// The report with every time-valued field removed (times are never compared).
fn without_times(v: Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.into_iter()
                .filter(|(k, _)| !(k.contains("time") || k.contains("ns_per_action")))
                .map(|(k, v)| (k, without_times(v)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.into_iter().map(without_times).collect()),
        other => other,
    }
}

fn reproduce_merge_equals_whole(name: &str, args: &[&str]) {
    let dir = scratch(name);
    let files = three_shards(&dir, args);
    let mut whole_args = args.to_vec();
    whole_args.extend(["--format", "json"]);
    let whole: Value = serde_json::from_str(&ok(&whole_args)).unwrap();
    let merged: Value = serde_json::from_str(&ok(&[
        "reproduce",
        "merge",
        "--format",
        "json",
        &files[1],
        &files[2],
        &files[0],
    ]))
    .unwrap();
    let rows = whole.as_array().expect("a JSON array of rows");
    assert!(rows.len() >= 6);
    assert!(rows.iter().any(|r| r["mean_actions"].as_f64() > Some(0.0)));
    assert_eq!(without_times(merged), without_times(whole));
    let missing = truecost(&["reproduce", "merge", &files[0], &files[1]]);
    assert_eq!(missing.status.code(), Some(1));
    assert!(error_line(&missing).contains("shard 3/3 is missing"));
}

#[test]
fn reproduce_deterministic_merge_of_three_shards_is_the_whole_run() {
    reproduce_merge_equals_whole(
        "deterministic",
        &[
            "reproduce",
            "deterministic",
            "--problems",
            "16,6,3",
            "--samples",
            "3",
            "--mode",
            "reference",
            "--episodes",
            "40",
            "--max-steps",
            "300",
            "--quiet",
        ],
    );
}

#[test]
fn reproduce_stochastic_merge_of_three_shards_is_the_whole_run() {
    reproduce_merge_equals_whole(
        "stochastic",
        &[
            "reproduce",
            "stochastic",
            "--problems",
            "16,6",
            "--gammas",
            "0.9,0.99",
            "--rhos",
            "0.5",
            "--epsilons",
            "1,decay",
            "--samples",
            "3",
            "--episodes",
            "20",
            "--max-steps",
            "200",
            "--quiet",
        ],
    );
}

/// A shard whose checksum was recomputed after tampering with a recorded counterexample (a
/// tiny problem claiming 9 moves at a state, more than any tiny problem has) is refused with
/// one line naming the site, not indexed out of bounds.
#[test]
fn a_tampered_counterexample_with_a_valid_checksum_is_refused_cleanly() {
    use truecost::claims::shard::ShardFile;
    let dir = scratch("tampered-tiny");
    let files: Vec<String> = (1..=2)
        .map(|k| {
            let part = format!("{k}/2");
            let path = dir.join(format!("c1-{k}.json"));
            let text = ok(&[
                "verify", "--no-coq", "--scope", "smoke", "--claim", "C1", "--no-smt", "--shard",
                &part,
            ]);
            std::fs::write(&path, text).unwrap();
            path.display().to_string()
        })
        .collect();
    let text = std::fs::read_to_string(&files[0]).unwrap();
    let format = serde_json::from_str::<Value>(&text).unwrap()["format"]
        .as_str()
        .unwrap()
        .to_string();
    let mut shard = ShardFile::from_json(&text, &format, "shard 1").unwrap();
    let entry = shard
        .entries
        .iter_mut()
        .find(|e| {
            e.value
                .as_deref()
                .is_some_and(|v| v.contains("\"deg\":[1,"))
        })
        .expect("a recorded tiny problem with one move at state 0");
    let value = entry.value.take().unwrap();
    entry.value = Some(value.replacen("\"deg\":[1,", "\"deg\":[9,", 1));
    let tampered = dir.join("tampered.json");
    std::fs::write(&tampered, shard.to_json(&format)).unwrap();
    let out = truecost(&[
        "verify",
        "merge",
        &tampered.display().to_string(),
        &files[1],
    ]);
    assert_eq!(out.status.code(), Some(1));
    let line = error_line(&out);
    assert!(!line.contains("internal error"), "{line}");
    assert!(
        line.contains("more moves than a tiny problem allows"),
        "{line}"
    );
}
