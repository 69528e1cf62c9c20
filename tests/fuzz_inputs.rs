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
    /// Exit 0.
    Ok,
    /// A non-zero exit with one clean line on stderr.
    Refused,
    /// Still running after [`CASE_SECONDS`] (killed).
    Timeout,
    /// A panic (exit 101 or "panicked") or death by a signal.
    Panic,
    /// A refusal of several lines, an empty one or one with a raw control character.
    BadRefusal,
}

/// The processor time (user and system) of a running process, in seconds, read from
/// `/proc/PID/stat` (clock ticks of 1/100 s); `None` where it cannot be read.
fn processor_seconds(pid: u32) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The fields after the command name, which is in parentheses and may hold spaces.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split(' ').collect();
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(ticks as f64 / 100.0)
}

/// Runs the binary with `args`: its class, and what went wrong when it is not `Ok` or
/// `Refused` (with the processor time of a timeout, to tell a slow case from a busy machine).
fn outcome(args: &[String]) -> (Class, String) {
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
            let cpu = processor_seconds(child.id());
            child.kill().ok();
            child.wait().ok();
            return (
                Class::Timeout,
                format!("timeout after {CASE_SECONDS} s ({cpu:?} s of processor time): truecost {args:?}"),
            );
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let err = reader.join().unwrap();
    if status.code() == Some(101) || err.contains("panicked") || status.code().is_none() {
        return (Class::Panic, format!("{status} on {args:?}: {err}"));
    }
    if status.success() {
        return (Class::Ok, String::new());
    }
    let lines: Vec<&str> = err.lines().collect();
    if lines.len() != 1 || lines[0].trim().is_empty() || lines[0].chars().any(char::is_control) {
        return (
            Class::BadRefusal,
            format!("a refusal of {} lines on {args:?}: {err:?}", lines.len()),
        );
    }
    (Class::Refused, String::new())
}

/// Runs the binary with `args`, asserting no panic, no timeout and a one-line refusal.
fn run(args: &[String]) -> Class {
    let (class, why) = outcome(args);
    assert!(matches!(class, Class::Ok | Class::Refused), "{why}");
    class
}

/// The outcomes of one target's cases: every case runs, the failures are listed at the end.
struct Tally {
    target: &'static str,
    classes: Vec<Class>,
    failures: Vec<String>,
}

impl Tally {
    fn new(target: &'static str) -> Self {
        Tally {
            target,
            classes: Vec::new(),
            failures: Vec::new(),
        }
    }

    /// Runs one case; a failure is recorded, not raised (so that a campaign sees them all).
    fn run(&mut self, args: &[String]) -> Class {
        let (class, why) = outcome(args);
        self.classes.push(class);
        if !why.is_empty() {
            eprintln!("{}: {why}", self.target);
            self.failures.push(why);
        }
        class
    }

    /// Records a failed expectation about a case that ended `Ok` or `Refused`.
    fn fail(&mut self, why: String) {
        eprintln!("{}: {why}", self.target);
        self.failures.push(why);
    }

    /// Prints the classes, removes `dir` unless a case failed (its files are then kept for
    /// re-running), and fails the test if any case failed.
    fn finish(self, dir: Option<&Path>) {
        let count = |c: Class| self.classes.iter().filter(|&&k| k == c).count();
        println!(
            "{}: {} cases, {} ok, {} clean refusals, {} timeouts, {} panics, {} bad refusals, {} failed checks",
            self.target,
            self.classes.len(),
            count(Class::Ok),
            count(Class::Refused),
            count(Class::Timeout),
            count(Class::Panic),
            count(Class::BadRefusal),
            self.failures.len()
                - count(Class::Timeout)
                - count(Class::Panic)
                - count(Class::BadRefusal),
        );
        if let Some(dir) = dir.filter(|_| self.failures.is_empty()) {
            std::fs::remove_dir_all(dir).ok();
        }
        assert!(
            self.failures.is_empty(),
            "{}: {} failures (files kept in {:?}): {:#?}",
            self.target,
            self.failures.len(),
            dir,
            self.failures
        );
    }
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
    let mut tally = Tally::new("env specs");
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
        tally.run(&[
            "solve".into(),
            "--algorithm".into(),
            "exact".into(),
            "--env".into(),
            spec,
        ]);
    }
    tally.finish(None);
}

/// Map files: random grids of `SFHG` and hostile bytes, of random shapes, through
/// `solve --env frozenlake:map=FILE`.
#[test]
fn map_files() {
    let mut r = rng(2);
    let dir = scratch("maps");
    let mut tally = Tally::new("map files");
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
        tally.run(&[
            "solve".into(),
            "--algorithm".into(),
            "exact".into(),
            "--env".into(),
            format!("frozenlake:map={}", path.display()),
        ]);
    }
    tally.finish(Some(&dir));
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
    let mut tally = Tally::new("shard files");
    for case in 0..cases() {
        let text = mutate(&mut r, &shard);
        let file = dir.join(format!("shard{case}.json"));
        std::fs::write(&file, &text).unwrap();
        let command = if case % 2 == 0 { "reproduce" } else { "verify" };
        tally.run(&[command.into(), "merge".into(), path(&file)]);
    }
    tally.finish(Some(&dir));
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
    let mut tally = Tally::new("extreme-number files");
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
        tally.run(&args);
    }
    tally.finish(Some(&dir));
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
    let mut tally = Tally::new("discount on huge numbers and long chains");
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
        tally.run(&["discount".into(), "--file".into(), path(&file)]);
    }
    tally.finish(Some(&dir));
}

/// `export --out` onto hostile targets: a victim file behind a symlink at the target or at
/// process-numbered temporary names is never written, a device is never replaced, a refusal is
/// one line, and a success leaves a regular file at the target.
#[test]
fn export_onto_hostile_targets() {
    let mut r = rng(6);
    let dir = scratch("targets");
    let victim = dir.join("victim.txt");
    let mut tally = Tally::new("export onto hostile targets");
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
        let class = tally.run(&[
            "export".into(),
            "--grid".into(),
            "3x3".into(),
            "--out".into(),
            path(&target),
        ]);
        if std::fs::read_to_string(&victim).ok().as_deref() != Some("victim\n") {
            tally.fail(format!("written through a link: {}", target.display()));
        }
        if class == Class::Ok
            && !std::fs::symlink_metadata(&target).is_ok_and(|m| m.file_type().is_file())
        {
            tally.fail(format!(
                "not a regular file after export: {}",
                target.display()
            ));
        }
        if dir.join(format!("missing{case}")).exists() {
            tally.fail(format!("a directory created: missing{case}"));
        }
    }
    tally.finish(Some(&dir));
}

/// A file of the fuzz corpus (`tests/fuzz_corpus`).
fn corpus(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_corpus")
        .join(name)
}

/// How a certificate is made: `solve --algorithm exact` (the deterministic `G*` of a
/// deterministic file, truecost otherwise), with `--objective truecost`, `discounted --alpha A`
/// or `reach`, or `discount`.
fn certify(r: &mut ChaCha8Rng, problem: &Path, cert: &Path) -> Vec<String> {
    let mut args: Vec<String> = match r.random_range(0..5) {
        0 => vec!["solve".into(), "--algorithm".into(), "exact".into()],
        1 => vec![
            "solve".into(),
            "--algorithm".into(),
            "exact".into(),
            "--objective".into(),
            "truecost".into(),
        ],
        2 => {
            let alpha = pick(r, &["1/2", "9/10", "99/100", "1/3", "2/7", "0.95"]);
            vec![
                "solve".into(),
                "--algorithm".into(),
                "exact".into(),
                "--objective".into(),
                "discounted".into(),
                "--alpha".into(),
                alpha.into(),
            ]
        }
        3 => vec![
            "solve".into(),
            "--algorithm".into(),
            "exact".into(),
            "--objective".into(),
            "reach".into(),
        ],
        _ => vec!["discount".into()],
    };
    args.extend([
        "--file".into(),
        path(problem),
        "--certificate".into(),
        path(cert),
    ]);
    args
}

/// Hostile leaves: numbers spelled wrongly, infinities, zero denominators, control
/// characters, the other objectives' names, JSON of the wrong type.
const HOSTILE_LEAVES: &[&str] = &[
    r#""inf""#,
    r#""-inf""#,
    r#""NaN""#,
    r#""-1""#,
    r#""0""#,
    r#""1/0""#,
    r#""0/0""#,
    r#""-0""#,
    r#""+1""#,
    r#"" 1""#,
    r#""1e5""#,
    r#""0x""#,
    r#""0x0""#,
    r#""0x01""#,
    r#""0X1""#,
    r#""0xA""#,
    r#""1/-2""#,
    r#""1//2""#,
    r#""""#,
    r#""１""#,
    r#""\u0000""#,
    r#""\u001b[31m""#,
    r#""\u202e""#,
    r#""truecost""#,
    r#""discount""#,
    r#""reach""#,
    r#""deterministic""#,
    r#""discounted""#,
    r#""0x1f/0xa0""#,
    "0",
    "-1",
    "1.5",
    "1e400",
    "18446744073709551615",
    "18446744073709551616",
    "null",
    "true",
    "[]",
    "{}",
    r#"["0"]"#,
];

/// Every JSON pointer in `v` (containers and leaves).
fn pointers(v: &serde_json::Value, at: String, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                pointers(item, format!("{at}/{i}"), out);
            }
        }
        serde_json::Value::Object(map) => {
            for (k, item) in map {
                pointers(
                    item,
                    format!("{at}/{}", k.replace('~', "~0").replace('/', "~1")),
                    out,
                );
            }
        }
        _ => {}
    }
    out.push(at);
}

/// A huge natural number: `digits` decimal digits or hexadecimal ones (`0x`, first not `0`).
fn huge_integer(r: &mut ChaCha8Rng, digits: usize) -> String {
    if r.random_range(0..2) == 0 {
        format!("9{}", "7".repeat(digits - 1))
    } else {
        format!("0xf{}", "e".repeat(digits - 1))
    }
}

/// `q` spelled as certificates may spell it: over a multiple of its denominator (`k·p/k·q`),
/// or in hexadecimal (`-0x1f/0xa0`).
fn respelled(r: &mut ChaCha8Rng, q: &common::Q) -> String {
    use num_traits::{Signed, Zero};
    let k = common::Q::from_integer(r.random_range(2..1000).into());
    if q.is_zero() || r.random_range(0..2) == 0 {
        return format!("{}/{}", q.numer() * k.numer(), q.denom() * k.numer());
    }
    let sign = if q.is_negative() { "-" } else { "" };
    format!("{sign}0x{:x}/0x{:x}", q.numer().magnitude(), q.denom())
}

/// Whether a mutated certificate must be accepted (a valid re-spelling of the original) or
/// may be accepted only if the independent judge finds it valid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Expect {
    Accept,
    Judge,
}

/// A structural or numerical mutation of a certificate's text: its name, the text, and what
/// `check` may do with it.
fn mutate_certificate(r: &mut ChaCha8Rng, original: &str) -> (&'static str, String, Expect) {
    use serde_json::Value;
    let mut v: Value = serde_json::from_str(original).expect("a certificate is JSON");
    let mut all = Vec::new();
    pointers(&v, String::new(), &mut all);
    let numbers: Vec<&String> = all
        .iter()
        .filter(|p| !p.starts_with("/problem"))
        .filter(|p| {
            v.pointer(p)
                .and_then(Value::as_str)
                .and_then(common::certificate_oracle::exact)
                .is_some()
        })
        .collect();
    let lists: Vec<&String> = all
        .iter()
        .filter(|p| v.pointer(p).is_some_and(Value::is_array))
        .collect();
    let objects: Vec<&String> = all
        .iter()
        .filter(|p| v.pointer(p).is_some_and(Value::is_object))
        .collect();
    let any = all[r.random_range(0..all.len())].clone();
    let placeholder = "\"@@leaf@@\"";
    let with_leaf = |v: &mut Value, at: &str, leaf: String| {
        *v.pointer_mut(at).expect("a pointer of v") = Value::String("@@leaf@@".into());
        serde_json::to_string(v)
            .unwrap()
            .replacen(placeholder, &leaf, 1)
    };
    match r.random_range(0..16) {
        0 => {
            let leaf = pick(r, HOSTILE_LEAVES).to_string();
            ("hostile leaf", with_leaf(&mut v, &any, leaf), Expect::Judge)
        }
        1 if !numbers.is_empty() => {
            let at = numbers[r.random_range(0..numbers.len())].clone();
            let q = common::certificate_oracle::exact(v.pointer(&at).unwrap().as_str().unwrap())
                .unwrap();
            let text = respelled(r, &q);
            (
                "number re-spelled",
                with_leaf(&mut v, &at, format!("\"{text}\"")),
                Expect::Accept,
            )
        }
        2 if !numbers.is_empty() => {
            let at = numbers[r.random_range(0..numbers.len())].clone();
            let q = common::certificate_oracle::exact(v.pointer(&at).unwrap().as_str().unwrap())
                .unwrap();
            let off =
                q + common::Q::new(1.into(), num_traits::pow(num_bigint::BigInt::from(10), 30));
            (
                "number off by 1e-30",
                with_leaf(&mut v, &at, format!("\"{off}\"")),
                Expect::Judge,
            )
        }
        3 => {
            let digits = [300, 1000, 100_000, 1_000_000][r.random_range(0..4)];
            let n = huge_integer(r, digits);
            let leaf = match r.random_range(0..4) {
                0 => format!("\"{n}\""),
                1 => format!("\"-{n}\""),
                2 => format!("\"1/{n}\""),
                _ => format!("\"{n}/{}\"", huge_integer(r, digits)),
            };
            let at = if numbers.is_empty() {
                any
            } else {
                numbers[r.random_range(0..numbers.len())].clone()
            };
            ("huge number", with_leaf(&mut v, &at, leaf), Expect::Judge)
        }
        4 => {
            let at = lists[r.random_range(0..lists.len())].clone();
            let l = v.pointer_mut(&at).unwrap().as_array_mut().unwrap();
            match (l.len(), r.random_range(0..3)) {
                (0, _) | (_, 0) => l.push(Value::String("0".into())),
                (k, 1) => {
                    l.remove(r.random_range(0..k));
                }
                (k, _) => {
                    let item = l[r.random_range(0..k)].clone();
                    l.insert(r.random_range(0..=k), item);
                }
            }
            (
                "list length",
                serde_json::to_string(&v).unwrap(),
                Expect::Judge,
            )
        }
        5 => {
            let at = lists[r.random_range(0..lists.len())].clone();
            let l = v.pointer_mut(&at).unwrap().as_array_mut().unwrap();
            let item = l
                .first()
                .filter(|i| i.to_string().len() < 64)
                .cloned()
                .unwrap_or(Value::String("0".into()));
            *l = vec![item; 1_000_000];
            if r.random_range(0..2) == 0 {
                v["states"] = 1_000_000.into();
            }
            (
                "a 10^6-element list",
                serde_json::to_string(&v).unwrap(),
                Expect::Judge,
            )
        }
        6 => {
            let depth = [64, 200, 10_000, 1_000_000][r.random_range(0..4)];
            let leaf = format!("{}\"0\"{}", "[".repeat(depth), "]".repeat(depth));
            ("deep nesting", with_leaf(&mut v, &any, leaf), Expect::Judge)
        }
        7 => {
            let at = objects[r.random_range(0..objects.len())].clone();
            let key = pick(
                r,
                &["extra", "Values", "values ", "\u{1b}[2J", "states", "alpha"],
            );
            let o = v.pointer_mut(&at).unwrap().as_object_mut().unwrap();
            o.insert(key.into(), Value::String("0".into()));
            (
                "a field added",
                serde_json::to_string(&v).unwrap(),
                Expect::Judge,
            )
        }
        8 => {
            let at = objects[r.random_range(0..objects.len())].clone();
            let o = v.pointer_mut(&at).unwrap().as_object_mut().unwrap();
            if let Some(k) = o.keys().nth(r.random_range(0..o.len().max(1))).cloned() {
                o.remove(&k);
            }
            (
                "a field removed",
                serde_json::to_string(&v).unwrap(),
                Expect::Judge,
            )
        }
        9 => {
            // The same key twice, the bogus value first or last.
            let keys: Vec<String> = v.as_object().unwrap().keys().cloned().collect();
            let key = &keys[r.random_range(0..keys.len())];
            let bogus = pick(r, HOSTILE_LEAVES);
            let text = serde_json::to_string(&v).unwrap();
            let text = if r.random_range(0..2) == 0 {
                format!("{{\"{key}\":{bogus},{}", &text[1..])
            } else {
                format!("{},\"{key}\":{bogus}}}", &text[..text.len() - 1])
            };
            ("a duplicate key", text, Expect::Judge)
        }
        10 => {
            let at = r.random_range(0..original.len());
            ("truncated", original[..at].to_string(), Expect::Judge)
        }
        11 => {
            let mut bytes = original.as_bytes().to_vec();
            bytes.insert(r.random_range(0..=bytes.len()), 0);
            (
                "a NUL byte",
                String::from_utf8(bytes).unwrap(),
                Expect::Judge,
            )
        }
        12 => (
            "pretty-printed",
            serde_json::to_string_pretty(&v).unwrap(),
            Expect::Accept,
        ),
        13 => {
            // A wrong SHA-256: one digit changed, or upper case.
            let sha = v["problem"]["sha256"].as_str().unwrap().to_string();
            let changed = if r.random_range(0..2) == 0 {
                sha.to_uppercase()
            } else {
                let i = r.random_range(0..sha.len());
                let d = if &sha[i..=i] == "0" { "1" } else { "0" };
                format!("{}{d}{}", &sha[..i], &sha[i + 1..])
            };
            v["problem"]["sha256"] = changed.into();
            (
                "a wrong SHA-256",
                serde_json::to_string(&v).unwrap(),
                Expect::Judge,
            )
        }
        14 => {
            let objective = pick(
                r,
                &[
                    "truecost",
                    "deterministic",
                    "reach",
                    "discounted",
                    "discount",
                ],
            );
            v["objective"] = objective.into();
            (
                "another objective",
                serde_json::to_string(&v).unwrap(),
                Expect::Judge,
            )
        }
        _ => ("bytes", mutate(r, original), Expect::Judge),
    }
}

/// Certificates of random tiny problems (deterministic and stochastic files, with and without
/// rewards; `solve --algorithm exact --certificate` for the deterministic, truecost,
/// discounted and reach objectives, `discount --certificate`), each through `check` unmutated
/// (accepted, and valid by the independent judge of `common::certificate_oracle`) and mutated
/// structurally and numerically ([`mutate_certificate`]): a mutated certificate is refused in
/// one line within [`CASE_SECONDS`], or accepted only if the judge finds it valid; a valid
/// re-spelling (hexadecimal or unreduced numbers, pretty-printed) is accepted.
#[test]
fn certificates() {
    use common::certificate_oracle::judge;
    use common::tiny::Tiny;
    const MUTATIONS: usize = 5;
    let mut r = rng(7);
    let dir = scratch("certificates");
    let mut tally = Tally::new("certificates");
    for case in 0..cases() {
        let deterministic = r.random_range(0..2) == 0;
        let rewards = r.random_range(0..3) == 0;
        let model = Tiny::random(&mut |n| r.random_range(0..n), deterministic, rewards);
        let file = model.file();
        let problem = dir.join(format!("problem{case}.json"));
        std::fs::write(&problem, &file).unwrap();
        let cert = dir.join(format!("problem{case}.cert"));
        let args = certify(&mut r, &problem, &cert);
        if tally.run(&args) != Class::Ok {
            tally.fail(format!("no certificate: truecost {args:?}"));
            continue;
        }
        let original = std::fs::read_to_string(&cert).unwrap();
        let check = |tally: &mut Tally, c: &Path| {
            tally.run(&["check".into(), "--file".into(), path(&problem), path(c)])
        };
        if check(&mut tally, &cert) != Class::Ok {
            tally.fail(format!(
                "check refused the certificate of truecost {args:?}"
            ));
        }
        if let Err(why) = judge(&model, file.as_bytes(), &original) {
            tally.fail(format!(
                "the certificate of truecost {args:?} is wrong: {why}"
            ));
        }
        for m in 0..MUTATIONS {
            let (name, text, expect) = mutate_certificate(&mut r, &original);
            let mutated = dir.join(format!("problem{case}-{m}.cert"));
            std::fs::write(&mutated, &text).unwrap();
            match (check(&mut tally, &mutated), expect) {
                (Class::Ok, _) => {
                    if let Err(why) = judge(&model, file.as_bytes(), &text) {
                        tally.fail(format!(
                            "{name}: check accepted {}: {why}",
                            mutated.display()
                        ));
                    }
                }
                (Class::Refused, Expect::Accept) => {
                    tally.fail(format!("{name}: check refused {}", mutated.display()));
                }
                _ => {}
            }
        }
    }
    tally.finish(Some(&dir));
}

/// Storm DRN files written by `export --format drn`, mutated, through `solve`, `compare` and
/// `discount`.
#[test]
fn drn_files() {
    let mut r = rng(8);
    let dir = scratch("drn");
    let mut tally = Tally::new("drn files");
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
            tally.run(&args);
        }
    }
    tally.finish(Some(&dir));
}

/// A case `certificates` found: a value of 10⁶ hexadecimal digits made `check` reduce a
/// fraction of millions of bits (quadratic: 22 s of processor time at 4·10⁶ bits, unbounded
/// below the 1 GiB file limit). An integer of more than 2^20 bits is refused as it is read,
/// naming the bound; one of exactly 2^20 bits is read, and the certificate rejected by its
/// conditions (at the goal, whose value must be 0).
#[test]
fn an_integer_past_2_20_bits_in_a_certificate_is_refused_as_read() {
    let dir = scratch("integer-bound");
    let problem = dir.join("p.json");
    std::fs::write(
        &problem,
        r#"{"format": "truecost-stochastic/1", "states": 2, "initial": 0, "goals": [1],
 "actions": [[{"cost": "2", "outcomes": [{"to": 0, "p": "3/4"}, {"to": 1, "p": "1/4"}]}], []]}"#,
    )
    .unwrap();
    let cert = dir.join("p.cert");
    run(&[
        "solve".into(),
        "--algorithm".into(),
        "exact".into(),
        "--objective".into(),
        "truecost".into(),
        "--file".into(),
        path(&problem),
        "--certificate".into(),
        path(&cert),
    ]);
    // V(0) = 2 + 3/4 V(0) = 8.
    let text = std::fs::read_to_string(&cert).unwrap();
    assert!(text.contains(r#""values":["8","0"]"#), "{text}");
    let check = |digits: usize| {
        let value = format!("0xf{}", "e".repeat(digits - 1));
        let file = dir.join(format!("{digits}.cert"));
        std::fs::write(
            &file,
            text.replace(
                r#""values":["8","0"]"#,
                &format!(r#""values":["8","{value}"]"#),
            ),
        )
        .unwrap();
        let out = Command::new(bin())
            .args(["check", "--file", &path(&problem), &path(&file)])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1));
        String::from_utf8(out.stderr).unwrap()
    };
    // 262 145 hexadecimal digits: more than 2^20 bits.
    let err = check(262_145);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("value of state 1: an integer of 262145 hexadecimal digits")
            && err.contains("2^20"),
        "{err}"
    );
    // 262 144 digits, the first `f`: exactly 2^20 bits, read; the goal's value is not 0.
    let err = check(262_144);
    assert!(err.contains("state 1: condition goal"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
