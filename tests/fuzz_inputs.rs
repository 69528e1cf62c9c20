//! Fuzz targets over the command line's hostile inputs, run on the built binary: `--env` specs,
//! map files, shard files (`reproduce merge`, `verify merge`) and problem files with extreme
//! numbers (huge, tiny, many digits). Every case must end within [`CASE_SECONDS`] without a
//! panic (exit 101, "panicked"), and a refusal is exactly one line on stderr.
//!
//! The cases are drawn from a seeded ChaCha generator, so a run is reproducible:
//! `TRUECOST_FUZZ_SEED` (default 0) and `TRUECOST_FUZZ_CASES` (cases per target, default 12)
//! override them. Each target prints its classes of outcome (ok / clean refusal) with
//! `--nocapture`.
//!
//! `discount` on huge exponents and digits and on long chains must refuse at once or answer
//! within [`CASE_SECONDS`]; `export --out` onto hostile targets (symlinks to a victim file or to
//! a device, devices, directories, missing directories, symlinks planted at process-numbered
//! temporary names) never writes through a link or onto a device.
//!
//! Beside the fuzzers, the bounds checked before work: `--alpha` with too many digits, and
//! `--samples` at its maximum with `--shard` (refused before any run, since a shard lists every
//! site and would exceed what `reproduce merge` reads).

mod common;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The longest a case may run.
const CASE_SECONDS: u64 = 20;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_truecost")
}

fn cases() -> usize {
    std::env::var("TRUECOST_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(12)
}

fn rng(target: u64) -> ChaCha8Rng {
    let seed = std::env::var("TRUECOST_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0u64);
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    r.set_stream(target);
    r
}

/// A scratch directory of its own.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("truecost-fuzz-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// How a case ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Class {
    Ok,
    Refused,
}

/// Runs the binary with `args`, asserting no panic, no timeout and a one-line refusal.
fn run(args: &[String]) -> Class {
    // An argument cannot hold a NUL byte (the operating system's limit, not the tool's).
    let args: Vec<String> = args.iter().map(|a| a.replace('\0', "\\0")).collect();
    let mut child = Command::new(bin())
        .args(&args)
        .env("RAYON_NUM_THREADS", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        stderr.read_to_string(&mut s).ok();
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(CASE_SECONDS) {
            child.kill().ok();
            child.wait().ok();
            panic!("timeout after {CASE_SECONDS} s: truecost {args:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let err = reader.join().unwrap();
    assert_ne!(status.code(), Some(101), "exit 101 on {args:?}: {err}");
    assert!(!err.contains("panicked"), "panic on {args:?}: {err}");
    assert!(
        status.code().is_some(),
        "killed by a signal on {args:?}: {err}"
    );
    if status.success() {
        Class::Ok
    } else {
        let lines: Vec<&str> = err.lines().collect();
        assert_eq!(
            lines.len(),
            1,
            "a refusal of {} lines on {args:?}: {err:?}",
            lines.len()
        );
        assert!(!lines[0].trim().is_empty(), "an empty refusal on {args:?}");
        Class::Refused
    }
}

fn report(target: &str, classes: &[Class]) {
    let ok = classes.iter().filter(|&&c| c == Class::Ok).count();
    println!(
        "{target}: {} cases, {ok} ok, {} clean refusals",
        classes.len(),
        classes.len() - ok
    );
}

fn pick<'a>(r: &mut ChaCha8Rng, items: &[&'a str]) -> &'a str {
    items[r.random_range(0..items.len())]
}

/// Hostile fragments of specs and files.
const HOSTILE: &[&str] = &[
    "",
    "=",
    ":",
    ",",
    "\u{1b}[31m",
    "\n",
    "\u{202e}",
    "-1",
    "0",
    "99999999999999999999",
    "1e308",
    "1e-400",
    "NaN",
    "/dev/zero",
    "\u{0}",
    "é",
];

/// A byte-level mutation of `text`: flips, deletions, insertions of hostile fragments.
fn mutate(r: &mut ChaCha8Rng, text: &str) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for _ in 0..r.random_range(1..4) {
        let at = r.random_range(0..=bytes.len());
        match r.random_range(0..4) {
            0 if at < bytes.len() => bytes[at] ^= 1 << r.random_range(0..8),
            1 if at < bytes.len() => {
                let end = (at + r.random_range(1..8)).min(bytes.len());
                bytes.drain(at..end);
            }
            2 => {
                let piece = pick(r, HOSTILE).as_bytes().to_vec();
                bytes.splice(at..at, piece);
            }
            _ => {
                let piece = pick(r, &["0", "9", "\"", "}", "]", "1/0", "0.5"])
                    .as_bytes()
                    .to_vec();
                bytes.splice(at..at, piece);
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

/// `--env` specs: names, parameters and values combined and mutated, through `solve --env`.
#[test]
fn env_specs() {
    let mut r = rng(1);
    let names = ["frozenlake", "taxi", "cliffwalking", "frozen", ""];
    let keys = [
        "map",
        "slippery",
        "size",
        "seed",
        "p",
        "is_slippery",
        "rows",
    ];
    let values = [
        "4x4",
        "8x8",
        "true",
        "false",
        "0",
        "1",
        "100x100",
        "101x101",
        "1000000x1",
        "0x0",
        "-3",
        "1e9",
        "SFFG",
        "/dev/zero",
    ];
    let mut classes = Vec::new();
    for case in 0..cases() {
        let mut spec = pick(&mut r, &names).to_string();
        for _ in 0..r.random_range(0..3) {
            spec.push(if spec.contains(':') { ',' } else { ':' });
            spec.push_str(pick(&mut r, &keys));
            spec.push('=');
            spec.push_str(pick(&mut r, &values));
        }
        if case % 3 == 2 {
            spec = mutate(&mut r, &spec);
        }
        classes.push(run(&[
            "solve".into(),
            "--algorithm".into(),
            "exact".into(),
            "--env".into(),
            spec,
        ]));
    }
    report("env specs", &classes);
}

/// Map files: random grids of `SFHG` and hostile bytes, of random shapes, through
/// `solve --env frozenlake:map=FILE`.
#[test]
fn map_files() {
    let mut r = rng(2);
    let dir = scratch("maps");
    let mut classes = Vec::new();
    for case in 0..cases() {
        let (w, h) = (r.random_range(0..12), r.random_range(0..12));
        let mut text = String::new();
        for y in 0..h {
            for x in 0..w {
                text.push(match (x, y) {
                    (0, 0) => 'S',
                    _ if x == w - 1 && y == h - 1 => 'G',
                    _ => ['F', 'F', 'F', 'H'][r.random_range(0..4)],
                });
            }
            text.push('\n');
        }
        if case % 2 == 1 {
            text = mutate(&mut r, &text);
        }
        let path = dir.join(format!("map{case}.txt"));
        std::fs::write(&path, &text).unwrap();
        classes.push(run(&[
            "solve".into(),
            "--algorithm".into(),
            "exact".into(),
            "--env".into(),
            format!("frozenlake:map={}", path.display()),
        ]));
    }
    std::fs::remove_dir_all(&dir).ok();
    report("map files", &classes);
}

/// Shard files: a real shard of a tiny run, mutated, through `reproduce merge` and
/// `verify merge`.
#[test]
fn shard_files() {
    let mut r = rng(3);
    let dir = scratch("shards");
    let out = Command::new(bin())
        .args([
            "reproduce",
            "deterministic",
            "--problems",
            "16",
            "--samples",
            "1",
            "--episodes",
            "1",
            "--max-steps",
            "10",
            "--mode",
            "reference",
            "--shard",
            "1/1",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let shard = String::from_utf8(out.stdout).unwrap();
    let whole = dir.join("whole.json");
    std::fs::write(&whole, &shard).unwrap();
    assert_eq!(
        run(&["reproduce".into(), "merge".into(), path(&whole)]),
        Class::Ok
    );
    let mut classes = Vec::new();
    for case in 0..cases() {
        let text = mutate(&mut r, &shard);
        let file = dir.join(format!("shard{case}.json"));
        std::fs::write(&file, &text).unwrap();
        let command = if case % 2 == 0 { "reproduce" } else { "verify" };
        classes.push(run(&[command.into(), "merge".into(), path(&file)]));
    }
    std::fs::remove_dir_all(&dir).ok();
    report("shard files", &classes);
}

fn path(p: &Path) -> String {
    p.display().to_string()
}

/// A number a hostile user would write: huge, tiny, long or odd.
fn extreme_number(r: &mut ChaCha8Rng) -> String {
    match r.random_range(0..8) {
        0 => format!("1e{}", r.random_range(0..400)),
        1 => format!("1e-{}", r.random_range(0..400)),
        2 => format!("0.{}", "9".repeat(r.random_range(1..400))),
        3 => format!("{}/{}", r.random::<u64>(), r.random::<u64>().max(1)),
        4 => "1".repeat(r.random_range(1..300)),
        5 => format!("{}", r.random_range(0..5)),
        6 => pick(r, &["-1", "0", "1/0", "inf", "NaN", "0x10", "+1", " 1"]).to_string(),
        _ => format!("{}.{}", r.random_range(0..100), r.random_range(0..1000)),
    }
}

/// Problem files (deterministic and stochastic) with extreme numbers, through `solve --file`,
/// `discount --file` and `compare --file`.
#[test]
fn extreme_number_files() {
    let mut r = rng(4);
    let dir = scratch("numbers");
    let mut classes = Vec::new();
    for case in 0..cases() {
        let n = r.random_range(2..5);
        let text = if case % 2 == 0 {
            let actions: Vec<String> = (0..n)
                .map(|x| {
                    if x == n - 1 {
                        return "[]".to_string();
                    }
                    let a: Vec<String> = (0..r.random_range(1..3))
                        .map(|_| {
                            format!(
                                "{{\"to\": {}, \"cost\": \"{}\"}}",
                                r.random_range(0..n),
                                extreme_number(&mut r)
                            )
                        })
                        .collect();
                    format!("[{}]", a.join(","))
                })
                .collect();
            format!(
                "{{\"format\": \"truecost-problem/1\", \"states\": {n}, \"initial\": 0, \"goals\": [{}], \"actions\": [{}]}}",
                n - 1,
                actions.join(",")
            )
        } else {
            let actions: Vec<String> = (0..n)
                .map(|x| {
                    if x == n - 1 {
                        return "[]".to_string();
                    }
                    let p = extreme_number(&mut r);
                    format!(
                        "[{{\"cost\": \"{}\", \"outcomes\": [{{\"to\": {}, \"p\": \"{p}\"}}, {{\"to\": {x}, \"p\": \"1 - {p}\"}}]}}, {{\"cost\": \"{}\", \"outcomes\": [{{\"to\": {}, \"p\": \"1\"}}]}}]",
                        extreme_number(&mut r),
                        n - 1,
                        extreme_number(&mut r),
                        x + 1
                    )
                })
                .collect();
            format!(
                "{{\"format\": \"truecost-stochastic/1\", \"initial\": 0, \"goals\": [{}], \"actions\": [{}]}}",
                n - 1,
                actions.join(",")
            )
        };
        let file = dir.join(format!("problem{case}.json"));
        std::fs::write(&file, &text).unwrap();
        let mut args: Vec<String> = match case % 3 {
            0 => vec!["solve".into(), "--algorithm".into(), "exact".into()],
            1 => vec!["discount".into()],
            _ => vec!["compare".into()],
        };
        args.extend(["--file".into(), path(&file)]);
        classes.push(run(&args));
    }
    std::fs::remove_dir_all(&dir).ok();
    report("extreme-number files", &classes);
}

/// `--alpha` with 300 digits is refused in one line that names the bound and shows the value
/// shortened (not "common denominator exceeds 2^62", the solver's words for a state).
#[test]
fn a_long_alpha_is_refused_naming_the_digits() {
    let long = format!("0.{}", "1".repeat(300));
    for args in [
        vec!["compare", "--problem", "1", "--alphas", long.as_str()],
        vec![
            "solve",
            "--env",
            "frozenlake",
            "--algorithm",
            "exact",
            "--objective",
            "discounted",
            "--alpha",
            long.as_str(),
        ],
    ] {
        let out = Command::new(bin()).args(&args).output().unwrap();
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains("62 bits") && err.contains("301 decimal digits"),
            "{err}"
        );
        assert!(err.contains("0.1111") && err.contains('…'), "{err}");
        assert!(!err.contains("common denominator"), "{err}");
    }
    // 18 digits fit (10^18 < 2^62).
    let out = Command::new(bin())
        .args([
            "compare",
            "--problem",
            "1",
            "--alphas",
            "0.999999999999999999",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `--samples` at its maximum with `--shard`: refused before any run (a shard lists every
/// site, far more than `reproduce merge` reads), in well under a second, without building
/// every task first (gigabytes).
#[test]
fn the_largest_sample_count_is_refused_for_shards_before_work() {
    for experiment in ["deterministic", "stochastic"] {
        let start = Instant::now();
        let out = Command::new(bin())
            .args([
                "reproduce",
                experiment,
                "--samples",
                "1048576",
                "--shard",
                "1/2",
                "--quiet",
            ])
            .output()
            .unwrap();
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("64 MiB") && err.contains("--samples"), "{err}");
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "{:?}",
            start.elapsed()
        );
    }
}

/// A number of a huge exponent or many digits, within the readers' limits (4096 characters,
/// exponents within ±10000).
fn huge_number(r: &mut ChaCha8Rng) -> String {
    match r.random_range(0..6) {
        0 => format!("1e{}", r.random_range(0..=10000)),
        1 => format!("1e-{}", r.random_range(0..=10000)),
        2 => "9".repeat(r.random_range(1..=4096)),
        3 => format!("0.{}", "3".repeat(r.random_range(1..=4094))),
        4 => format!("1/{}", "7".repeat(r.random_range(1..=4000))),
        _ => format!("{}/13", r.random_range(1..13)),
    }
}

/// `discount --file` on two- and three-state files of huge numbers (costs or rewards) and on
/// chains of up to 2,500 states in lines of 202 to 259 (refused before any probe) or of 5 to 39
/// (answered; costs `k/13`): each case refused in one
/// line or answered within [`CASE_SECONDS`].
#[test]
fn discount_on_huge_numbers_and_long_chains() {
    let mut r = rng(5);
    let dir = scratch("discount");
    let mut classes = Vec::new();
    for case in 0..cases() {
        let text = if case % 2 == 0 {
            let (a, b) = (huge_number(&mut r), huge_number(&mut r));
            let field = if r.random_range(0..2) == 0 {
                "cost"
            } else {
                "reward"
            };
            let other = if field == "reward" {
                r#", "reward": "-1""#
            } else {
                ""
            };
            format!(
                r#"{{"states": 3, "initial": 0, "goals": [2], "actions": [[{{"to": 2, "cost": "1", "{field}": "{a}"}}, {{"to": 1, "cost": "1"{other}}}], [{{"to": 0, "cost": "1", "{field}": "{b}"}}, {{"to": 2, "cost": "2"{other}}}], []]}}"#
            )
            .replace(r#""cost": "1", "cost""#, r#""cost""#)
        } else {
            // Long lines are refused before any probe (degree); short problems are answered.
            let length = if r.random_range(0..2) == 0 {
                r.random_range(202..260)
            } else {
                r.random_range(5..40)
            };
            let n = if length > 201 {
                r.random_range(length..=2500)
            } else {
                r.random_range(length..=length + 20)
            };
            common::line_chains(n, length, |i, next| {
                format!(
                    r#"[{{"to": {next}, "cost": "{}/13"}}, {{"to": {}, "cost": "{}/13"}}]"#,
                    r.random_range(1..13),
                    i - i % length,
                    r.random_range(1..40)
                )
            })
        };
        let file = dir.join(format!("discount{case}.json"));
        std::fs::write(&file, &text).unwrap();
        classes.push(run(&["discount".into(), "--file".into(), path(&file)]));
    }
    std::fs::remove_dir_all(&dir).ok();
    report("discount on huge numbers and long chains", &classes);
}

/// `export --out` onto hostile targets: a victim file behind a symlink at the target or at
/// process-numbered temporary names is never written, a device is never replaced, a refusal is
/// one line, and a success leaves a regular file at the target.
#[test]
fn export_onto_hostile_targets() {
    let mut r = rng(6);
    let dir = scratch("targets");
    let victim = dir.join("victim.txt");
    let mut classes = Vec::new();
    for case in 0..cases() {
        std::fs::write(&victim, "victim\n").unwrap();
        let out = dir.join(format!("out{case}.json"));
        let target = match r.random_range(0..7) {
            0 => out.clone(),
            1 => {
                std::os::unix::fs::symlink(&victim, &out).unwrap();
                out.clone()
            }
            2 => {
                std::os::unix::fs::symlink("/dev/full", &out).unwrap();
                out.clone()
            }
            3 => PathBuf::from(pick(&mut r, &["/dev/full", "/dev/null", "/dev/zero"])),
            4 => dir.clone(),
            5 => dir.join(format!("missing{case}/out.json")),
            _ => {
                let next: u32 = std::fs::read_to_string("/proc/sys/kernel/ns_last_pid")
                    .ok()
                    .and_then(|s| s.trim().parse().ok())
                    .unwrap_or(0);
                for pid in next..next + 200 {
                    let name = format!(".truecost-{pid}-out{case}.json");
                    std::os::unix::fs::symlink(&victim, dir.join(name)).ok();
                }
                out.clone()
            }
        };
        let class = run(&[
            "export".into(),
            "--grid".into(),
            "3x3".into(),
            "--out".into(),
            path(&target),
        ]);
        assert_eq!(
            std::fs::read_to_string(&victim).unwrap(),
            "victim\n",
            "written through a link: {}",
            target.display()
        );
        if class == Class::Ok {
            let meta = std::fs::symlink_metadata(&target).unwrap();
            assert!(meta.file_type().is_file(), "{}", target.display());
        }
        assert!(!dir.join(format!("missing{case}")).exists());
        classes.push(class);
    }
    std::fs::remove_dir_all(&dir).ok();
    report("export onto hostile targets", &classes);
}

/// A file of the fuzz corpus (`tests/fuzz_corpus`).
fn corpus(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_corpus")
        .join(name)
}

/// The exact `values` of a certificate's JSON text, `None` when it has none that parse.
fn certificate_values(text: &str) -> Option<Vec<Option<truecost::value::Rational>>> {
    let doc: serde_json::Value = serde_json::from_str(text).ok()?;
    let values = doc.get("values")?.as_array()?;
    Some(
        values
            .iter()
            .map(|v| {
                v.as_str()
                    .and_then(|s| truecost::value::parse_rational(s).ok())
            })
            .collect(),
    )
}

/// Certificates of `solve --certificate`, mutated, through `check`: a clean refusal, or an
/// acceptance whose values are the optimum's (the certificate of the unmutated run).
#[test]
fn certificates() {
    let mut r = rng(7);
    let dir = scratch("certificates");
    let mut classes = Vec::new();
    for (name, objective) in [
        ("slippery.json", "truecost"),
        ("line.json", "truecost"),
        ("fractions-and-stay.json", "discounted"),
    ] {
        let problem = corpus(name);
        let cert = dir.join(format!("{name}.cert"));
        let mut args = vec![
            "solve".to_string(),
            "--file".into(),
            path(&problem),
            "--algorithm".into(),
            "exact".into(),
            "--objective".into(),
            objective.into(),
            "--certificate".into(),
            path(&cert),
        ];
        if objective == "discounted" {
            args.extend(["--alpha".into(), "9/10".into()]);
        }
        assert_eq!(run(&args), Class::Ok);
        let original = std::fs::read_to_string(&cert).unwrap();
        let optimum = certificate_values(&original).expect("the certificate's values");
        assert!(optimum.iter().any(Option::is_some), "{original}");
        let check =
            |file: &Path| run(&["check".into(), "--file".into(), path(&problem), path(file)]);
        assert_eq!(check(&cert), Class::Ok);
        for case in 0..cases() {
            let text = mutate(&mut r, &original);
            let file = dir.join(format!("{name}{case}.cert"));
            std::fs::write(&file, &text).unwrap();
            let class = check(&file);
            if class == Class::Ok {
                assert_eq!(
                    certificate_values(&text).as_ref(),
                    Some(&optimum),
                    "check accepted other values: {text}"
                );
            }
            classes.push(class);
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    report("certificates", &classes);
}

/// Storm DRN files written by `export --format drn`, mutated, through `solve`, `compare` and
/// `discount`.
#[test]
fn drn_files() {
    let mut r = rng(8);
    let dir = scratch("drn");
    let mut classes = Vec::new();
    for name in ["slippery.json", "line.json", "fractions-and-stay.json"] {
        let drn = dir.join(format!("{name}.drn"));
        let export = [
            "export".to_string(),
            "--file".into(),
            path(&corpus(name)),
            "--format".into(),
            "drn".into(),
            "--out".into(),
            path(&drn),
        ];
        assert_eq!(run(&export), Class::Ok);
        let original = std::fs::read_to_string(&drn).unwrap();
        for case in 0..cases() {
            let file = dir.join(format!("{name}{case}.drn"));
            std::fs::write(&file, mutate(&mut r, &original)).unwrap();
            let command: &[&str] = match case % 3 {
                0 => &["solve", "--algorithm", "exact"],
                1 => &["compare"],
                _ => &["discount"],
            };
            let mut args: Vec<String> = command.iter().map(|s| s.to_string()).collect();
            args.extend(["--file".into(), path(&file)]);
            classes.push(run(&args));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    report("drn files", &classes);
}
