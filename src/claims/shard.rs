//! Sharding `truecost verify` over many machines: which units of the plan a shard runs, the
//! shard file, and the merge of a complete set of shard files.
//!
//! `truecost verify --shard K/N` runs the plan's units that [`select`] gives it ([`super::plan`],
//! [`super::runner`]):
//!
//! * a split unit (a claim checker) does the K-th part of every enumeration it meets — the
//!   labelled indices `i` with `i mod N = K − 1` ([`super::enumerate`]) — and records its
//!   partial accumulator: counts, maxima and the candidate minimal counterexamples *with their
//!   minimality keys*;
//! * an owned unit, one that cannot be split without changing its result (a proptest run stops
//!   at its first failure and shrinks it; one SMT obligation; one harness; the Coq re-check), is
//!   run by one shard, the `u`-th owned unit of the plan by shard `u mod N + 1`, and recorded
//!   there; the other shards list it without a value.
//!
//! The shard file ([`file()`]) lists what the shard recorded, one engine run (a step of the plan)
//! after the other, each closed by an entry that carries the engine's failure if it failed.
//! `truecost verify merge` reads the N files back ([`merge`]), step by step, for the runner to
//! answer every unit from them: the merged report is the whole run's, byte for byte (times
//! aside).
//!
//! Shards of different runs are refused (a fingerprint of the scope, the claim filter, the
//! options and the tool), so are a missing, duplicated or foreign shard, a file whose
//! checksum does not match its content, and shards that disagree on the sites they ran.
//!
//! **Engine failures.** An engine that panics (a bug in the code it checks, or in itself) is
//! caught by [`super::caught::caught`], which the runner wraps around every engine, and by the harness and
//! proptest engines around each case: the panic becomes that engine's line, `engine failed:
//! <message>`, and the rest of the report is still made.

use std::fmt;

use serde::de::DeserializeOwned;
use serde_json::{json, Value};

/// The largest number of shards accepted (`N` of `--shard K/N`).
pub const MAX_SHARDS: u32 = 4096;

/// The format tag of a shard file of `truecost verify`.
pub const VERIFY_FORMAT: &str = "truecost-verify-shard/1";

/// The part of the work a shard does: shard `k` (1-based) of `n`.
///
/// ```
/// use truecost::claims::shard::Part;
/// let p = Part::parse("2/3").unwrap();
/// assert_eq!((p.k(), p.n()), (2, 3));
/// assert!(p.owns(1) && p.owns(4) && !p.owns(0));
/// assert!(Part::parse("0/3").is_err() && Part::parse("4/3").is_err());
/// assert!(Part::parse("1/5000").is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Part {
    k: u32,
    n: u32,
}

impl Part {
    /// Parses `K/N` with `1 ≤ K ≤ N ≤` [`MAX_SHARDS`].
    pub fn parse(text: &str) -> Result<Part, String> {
        let bad = || {
            format!(
                "--shard '{}': expected K/N with 1 <= K <= N <= {MAX_SHARDS} (e.g. 2/8)",
                crate::echo::one_line(text)
            )
        };
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let k: u32 = k.trim().parse().map_err(|_| bad())?;
        let n: u32 = n.trim().parse().map_err(|_| bad())?;
        if k == 0 || k > n || n > MAX_SHARDS {
            return Err(bad());
        }
        Ok(Part { k, n })
    }

    /// `K` (1-based).
    pub fn k(self) -> u32 {
        self.k
    }

    /// `N`.
    pub fn n(self) -> u32 {
        self.n
    }

    /// Whether item `i` of a site belongs to this shard (`i mod N = K − 1`).
    pub fn owns(self, i: u64) -> bool {
        i % u64::from(self.n) == u64::from(self.k - 1)
    }
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

/// One recorded site: its name (what it ran) and its value as JSON text (kept as text so
/// 128-bit integers survive exactly).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    /// `enumerate <family>`, `proptest C1`, `smt C1 obligation 3`, …
    pub site: String,
    /// The recorded value (`None`: a unit another shard owns).
    pub value: Option<String>,
}

/// A shard's partial result: the fingerprint of the run and every site's value.
#[derive(Clone, Debug, PartialEq)]
pub struct ShardFile {
    /// Which shard.
    pub part: Part,
    /// What run this is a shard of (compared on merge).
    pub fingerprint: Value,
    /// The sites, in the order the run met them.
    pub entries: Vec<Entry>,
    /// Wall-clock seconds of the shard (informative; never compared).
    pub seconds: f64,
}

/// The checksum a shard file carries: FNV-1a over everything a merge trusts — the shard
/// (`K/N`), the fingerprint of the run and every site with its value — so that a truncated or
/// edited file is refused. (It detects accidents and casual edits, not a forger who recomputes it.)
fn checksum(part: &str, fingerprint: &Value, entries: &[Entry]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut feed = |bytes: &[u8]| {
        for &b in bytes.iter().chain([0u8].iter()) {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    feed(part.as_bytes());
    feed(fingerprint.to_string().as_bytes());
    for e in entries {
        feed(e.site.as_bytes());
        feed(e.value.as_deref().unwrap_or("\u{1}").as_bytes());
    }
    format!("{h:016x}")
}

impl ShardFile {
    /// The file's JSON text.
    pub fn to_json(&self, format: &str) -> String {
        let entries: Vec<Value> = self
            .entries
            .iter()
            .map(|e| json!({"site": e.site, "value": e.value}))
            .collect();
        let mut s = serde_json::to_string_pretty(&json!({
            "format": format,
            "shard": self.part.to_string(),
            "fingerprint": self.fingerprint,
            "seconds": self.seconds,
            "checksum": checksum(&self.part.to_string(), &self.fingerprint, &self.entries),
            "entries": entries,
        }))
        .expect("serialisable");
        s.push('\n');
        s
    }

    /// Reads a shard file's text (`name` names it in errors).
    pub fn from_json(text: &str, format: &str, name: &str) -> Result<ShardFile, String> {
        let v: Value = serde_json::from_str(text)
            .map_err(|e| format!("{name}: not a shard file (invalid JSON: {e})"))?;
        if v["format"].as_str() != Some(format) {
            return Err(format!(
                "{name}: not a shard file of this command (format is not {format})"
            ));
        }
        let part =
            Part::parse(v["shard"].as_str().unwrap_or("")).map_err(|e| format!("{name}: {e}"))?;
        let mut entries = Vec::new();
        for e in v["entries"]
            .as_array()
            .ok_or_else(|| format!("{name}: no entries"))?
        {
            let site = e["site"]
                .as_str()
                .ok_or_else(|| format!("{name}: an entry without a site"))?;
            let value = match &e["value"] {
                Value::Null => None,
                Value::String(s) => Some(s.clone()),
                _ => return Err(format!("{name}: entry '{site}' has a malformed value")),
            };
            entries.push(Entry {
                site: site.to_string(),
                value,
            });
        }
        let shard_text = v["shard"].as_str().unwrap_or("");
        if v["checksum"].as_str()
            != Some(checksum(shard_text, &v["fingerprint"], &entries).as_str())
        {
            return Err(format!(
                "{name}: the checksum does not match the shard, fingerprint and entries (a truncated or edited file)"
            ));
        }
        Ok(ShardFile {
            part,
            fingerprint: v["fingerprint"].clone(),
            entries,
            seconds: v["seconds"].as_f64().unwrap_or(0.0),
        })
    }
}

/// Checks that `files` are exactly the shards `1/N … N/N` of one run (same fingerprint, each
/// once) and returns them ordered by `K`. `names[i]` names `files[i]` in errors.
pub fn complete_set(mut files: Vec<(String, ShardFile)>) -> Result<Vec<ShardFile>, String> {
    let Some((first_name, first)) = files.first() else {
        return Err("merge needs the shard files (none given)".into());
    };
    let n = first.part.n();
    let fingerprint = first.fingerprint.clone();
    let first_name = first_name.clone();
    for (name, f) in &files {
        if f.part.n() != n {
            return Err(format!(
                "{name} is shard {} but {first_name} is shard {}: shards of different splits",
                f.part, first.part
            ));
        }
        if f.fingerprint != fingerprint {
            return Err(format!(
                "{name} is a shard of a different run than {first_name} (fingerprints differ: {} vs {})",
                f.fingerprint, fingerprint
            ));
        }
    }
    files.sort_by_key(|(_, f)| f.part.k());
    for w in files.windows(2) {
        if w[0].1.part.k() == w[1].1.part.k() {
            return Err(format!(
                "shard {} given twice ({} and {})",
                w[0].1.part, w[0].0, w[1].0
            ));
        }
    }
    let present: Vec<u32> = files.iter().map(|(_, f)| f.part.k()).collect();
    if let Some(missing) = (1..=n).find(|k| !present.contains(k)) {
        return Err(format!(
            "shard {missing}/{n} is missing ({} of {n} given)",
            files.len()
        ));
    }
    // A shard whose engine failed met fewer of that engine's sites than the others: the merge
    // checks those shards' sites as it reads them ([`super::runner`]).
    let failed = files.iter().any(|(_, f)| {
        f.entries
            .iter()
            .any(|e| e.site == END_OF_ENGINE && e.value.is_some())
    });
    let sites: Vec<&str> = files[0].1.entries.iter().map(|e| e.site.as_str()).collect();
    for (name, f) in files[1..].iter().filter(|_| !failed) {
        let other: Vec<&str> = f.entries.iter().map(|e| e.site.as_str()).collect();
        if other != sites {
            return Err(format!(
                "{name} ran different sites than {} (shards of different builds?)",
                files[0].0
            ));
        }
    }
    Ok(files.into_iter().map(|(_, f)| f).collect())
}

/// The largest shard file read, in bytes.
pub const MAX_SHARD_BYTES: u64 = 64 << 20;

/// The largest total size of the shard files of one merge, in bytes.
pub const MAX_MERGE_BYTES: u64 = 1 << 30;

/// Reads the shard files named on a `merge` command line as `(name, text)`, each at most
/// [`MAX_SHARD_BYTES`] and all together at most [`MAX_MERGE_BYTES`] (`/dev/zero` or an endless
/// pipe is refused after the limit, not read until memory runs out).
///
/// ```
/// use truecost::claims::shard::read_files;
/// let err = read_files(&["/dev/zero".into()]).unwrap_err();
/// assert!(err.contains("the limit for shard files"), "{err}");
/// ```
pub fn read_files(paths: &[std::path::PathBuf]) -> Result<Vec<(String, String)>, String> {
    let mut total = 0u64;
    let mut files = Vec::with_capacity(paths.len());
    for p in paths {
        let text = crate::bounded::read_text(p, MAX_SHARD_BYTES, "shard files")
            .map_err(|e| e.to_string())?;
        total += text.len() as u64;
        if total > MAX_MERGE_BYTES {
            return Err(format!(
                "the shard files take more than {MAX_MERGE_BYTES} bytes together, the limit of one merge"
            ));
        }
        files.push((p.display().to_string(), text));
    }
    Ok(files)
}

/// Reads the shard files `(name, text)` of one command (`format`) and checks that they are the
/// complete set of one run ([`complete_set`]): the first step of every `merge`.
pub fn read_complete_set(
    files: &[(String, String)],
    format: &str,
) -> Result<Vec<ShardFile>, String> {
    let read = files
        .iter()
        .map(|(name, text)| ShardFile::from_json(text, format, name).map(|f| (name.clone(), f)))
        .collect::<Result<Vec<_>, _>>()?;
    complete_set(read)
}

/// The fingerprint a set of shards carries, read back on merge: typed fields, each malformed
/// one refused with the same message, and the final check that the settings read back
/// reproduce it (same build, nothing edited).
///
/// ```
/// use truecost::claims::shard::Fingerprint;
/// let v = serde_json::json!({"seed": 7, "tool": "truecost 0.1.0", "commit": "abc"});
/// let fp = Fingerprint(&v);
/// assert_eq!(fp.field::<u64>("seed").unwrap(), 7);
/// assert!(fp.field::<u64>("samples").unwrap_err().contains("samples"));
/// assert!(fp.confirm(&v).is_ok());
/// let other = serde_json::json!({"seed": 8, "tool": "truecost 0.1.0", "commit": "abc"});
/// assert!(fp.confirm(&other).unwrap_err().contains("same build"));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Fingerprint<'a>(pub &'a Value);

impl Fingerprint<'_> {
    /// The refusal of a malformed field `what`.
    pub fn bad(&self, what: &str) -> String {
        format!("the shards' fingerprint has no valid {what}")
    }

    /// Field `key`, deserialised.
    pub fn field<T: DeserializeOwned>(&self, key: &str) -> Result<T, String> {
        serde_json::from_value(self.0[key].clone()).map_err(|_| self.bad(key))
    }

    /// Field `key` as text (`""` when it is not a string; the caller's parse then refuses it).
    pub fn text(&self, key: &str) -> &str {
        self.0[key].as_str().unwrap_or("")
    }

    /// Refuses unless `recomputed` — the fingerprint of the settings read back, made by this
    /// build — equals the shards' own.
    pub fn confirm(&self, recomputed: &Value) -> Result<(), String> {
        if recomputed == self.0 {
            return Ok(());
        }
        Err(format!(
            "the shards were made by {} (commit {}), this is {} (commit {}), or they state other settings than they ran: merge with the same build",
            self.0["tool"], self.0["commit"], recomputed["tool"], recomputed["commit"]
        ))
    }
}

/// What a shard recorded for one step of the plan: the entries of its units (an owned unit's
/// value, or no value where another shard owns it; a split unit's partial accumulators, one per
/// enumeration it met) and the failure of the step's engine in this shard, if it failed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepRecord {
    /// The entries, in the order the step met them.
    pub entries: Vec<Entry>,
    /// The engine's failure (the text after `engine failed: `).
    pub failure: Option<String>,
}

/// The site of the entry that closes a step's entries in a shard file, with the step's failure
/// as its value.
const END_OF_ENGINE: &str = "end of engine";

/// How a unit's work is shared among the shards of `verify --shard K/N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Share {
    /// Every shard does its part: the labelled indices `i ≡ K − 1 (mod N)` of each enumeration
    /// the unit meets; the merge combines the parts.
    Split,
    /// Indivisible (a proptest run stops at its first failure and shrinks it; one SMT
    /// obligation; one harness; the Coq re-check): the `u`-th owned unit of the plan belongs to
    /// shard `u mod N + 1`.
    Owned(u64),
}

/// A unit of work as the shards share it.
pub trait Shared {
    /// How the shards share it.
    fn share(&self) -> Share;
}

/// The units of `units` (a plan's, in plan order) that shard `part` runs (`None`: the whole
/// run, every unit): every split unit, for its part, and the owned units it owns — the `u`-th
/// owned unit when `u mod N = K − 1`.
///
/// ```
/// use truecost::claims::registry::{plan, Options};
/// use truecost::claims::shard::{select, Part};
/// use truecost::claims::Scope;
/// let options = Options { smt: false, ..Options::default() };
/// let plan = plan(Scope::Smoke, Some("C2"), &options).unwrap();
/// let whole = select(plan.units(), None).len();
/// let parts: usize = (1..=3)
///     .map(|k| select(plan.units(), Some(Part::parse(&format!("{k}/3")).unwrap())).len())
///     .sum();
/// // Two split units (the C2 enumeration, and the worked example's exact solve that gives
/// // α*) run in each of the three shards, every other unit in one of them.
/// assert_eq!(parts, whole + 2 * 2);
/// ```
pub fn select<'u, U: Shared>(
    units: impl IntoIterator<Item = &'u U>,
    part: Option<Part>,
) -> Vec<&'u U> {
    units
        .into_iter()
        .filter(|u| match (u.share(), part) {
            (_, None) | (Share::Split, _) => true,
            (Share::Owned(i), Some(p)) => p.owns(i),
        })
        .collect()
}

/// The shard file of shard `part`: its `records`, one per step of the plan, each closed by the
/// entry that ends an engine's entries.
pub fn file(part: Part, fingerprint: Value, records: Vec<StepRecord>, seconds: f64) -> ShardFile {
    let entries = records
        .into_iter()
        .flat_map(|r| {
            let end = Entry {
                site: END_OF_ENGINE.into(),
                value: r.failure,
            };
            r.entries.into_iter().chain([end])
        })
        .collect();
    ShardFile {
        part,
        fingerprint,
        entries,
        seconds,
    }
}

/// A complete set of shard files read back.
#[derive(Clone, Debug, PartialEq)]
pub struct Merged {
    /// The fingerprint of the run they are shards of.
    pub fingerprint: Value,
    /// For each step of the plan, every shard's record of it, in shard order.
    pub steps: Vec<Vec<StepRecord>>,
}

/// `truecost verify merge`: reads the shard files `(name, text)` of one run — every shard
/// present once ([`read_complete_set`]) — and splits every shard's entries into its steps.
pub fn merge(files: &[(String, String)]) -> Result<Merged, String> {
    let shards = read_complete_set(files, VERIFY_FORMAT)?;
    let fingerprint = shards[0].fingerprint.clone();
    let mut per_shard = Vec::with_capacity(shards.len());
    for s in shards {
        let mut steps = Vec::new();
        let mut current = StepRecord::default();
        for e in s.entries {
            if e.site == END_OF_ENGINE {
                current.failure = e.value;
                steps.push(std::mem::take(&mut current));
            } else {
                current.entries.push(e);
            }
        }
        if !current.entries.is_empty() {
            return Err(format!(
                "shard {} recorded sites after its last engine (a truncated file?)",
                s.part
            ));
        }
        per_shard.push(steps);
    }
    let count = per_shard[0].len();
    if per_shard.iter().any(|steps| steps.len() != count) {
        return Err(
            "the shards recorded different numbers of engine runs (shards of different builds?)"
                .into(),
        );
    }
    let mut steps: Vec<Vec<StepRecord>> = (0..count).map(|_| Vec::new()).collect();
    for shard_steps in per_shard {
        for (i, r) in shard_steps.into_iter().enumerate() {
            steps[i].push(r);
        }
    }
    Ok(Merged { fingerprint, steps })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `K/N` at the edges of `1 ≤ K ≤ N ≤ MAX_SHARDS`: each accepted at the edge, refused one
    /// past it.
    #[test]
    fn a_part_is_accepted_up_to_its_bounds() {
        let parse = |k: u32, n: u32| Part::parse(&format!("{k}/{n}")).map(|p| (p.k(), p.n()));
        assert_eq!(parse(1, 1), Ok((1, 1)));
        assert_eq!(parse(3, 3), Ok((3, 3)));
        assert_eq!(parse(MAX_SHARDS, MAX_SHARDS), Ok((MAX_SHARDS, MAX_SHARDS)));
        assert_eq!(parse(1, MAX_SHARDS), Ok((1, MAX_SHARDS)));
        for (k, n) in [
            (0, 3),
            (4, 3),
            (1, MAX_SHARDS + 1),
            (MAX_SHARDS + 1, MAX_SHARDS + 1),
        ] {
            assert!(parse(k, n).is_err(), "{k}/{n}");
        }
    }

    #[test]
    fn missing_duplicate_and_foreign_shards_are_refused() {
        let file = |k: u32, n: u32, run: u32| {
            (
                format!("s{k}-{run}"),
                ShardFile {
                    part: Part { k, n },
                    fingerprint: json!({ "run": run }),
                    entries: vec![],
                    seconds: 0.0,
                },
            )
        };
        let e = complete_set(vec![file(1, 3, 0), file(3, 3, 0)]).unwrap_err();
        assert!(e.contains("shard 2/3 is missing"), "{e}");
        let e = complete_set(vec![file(1, 2, 0), file(1, 2, 0), file(2, 2, 0)]).unwrap_err();
        assert!(e.contains("given twice"), "{e}");
        let e = complete_set(vec![file(1, 2, 0), file(2, 2, 1)]).unwrap_err();
        assert!(e.contains("different run"), "{e}");
        let e = complete_set(vec![file(1, 2, 0), file(2, 3, 0)]).unwrap_err();
        assert!(e.contains("different splits"), "{e}");
    }

    #[test]
    fn an_edited_file_fails_its_checksum() {
        let f = ShardFile {
            part: Part { k: 1, n: 1 },
            fingerprint: json!({}),
            entries: vec![Entry {
                site: "sum".into(),
                value: Some("12".into()),
            }],
            seconds: 0.0,
        };
        let text = f.to_json("t/1").replace("\"12\"", "\"13\"");
        let e = ShardFile::from_json(&text, "t/1", "x.json").unwrap_err();
        assert!(e.contains("checksum"), "{e}");
    }

    /// The checksum covers what a merge trusts besides the entries: the fingerprint (a seed
    /// edited from 0 to 12345 would otherwise be reported as the run's) and the shard `K/N`.
    #[test]
    fn an_edited_fingerprint_or_part_fails_the_checksum() {
        let f = ShardFile {
            part: Part { k: 1, n: 2 },
            fingerprint: json!({"seed": 0}),
            entries: vec![],
            seconds: 0.0,
        };
        let text = f.to_json("t/1");
        assert!(ShardFile::from_json(&text, "t/1", "x.json").is_ok());
        let seed = text.replace("\"seed\": 0", "\"seed\": 12345");
        assert_ne!(seed, text);
        let e = ShardFile::from_json(&seed, "t/1", "x.json").unwrap_err();
        assert!(e.contains("checksum"), "{e}");
        let part = text.replace("\"1/2\"", "\"2/2\"");
        assert_ne!(part, text);
        let e = ShardFile::from_json(&part, "t/1", "x.json").unwrap_err();
        assert!(e.contains("checksum"), "{e}");
    }

    fn record(sites: &[(&str, Option<&str>)], failure: Option<&str>) -> StepRecord {
        StepRecord {
            entries: sites
                .iter()
                .map(|(site, value)| Entry {
                    site: site.to_string(),
                    value: value.map(String::from),
                })
                .collect(),
            failure: failure.map(String::from),
        }
    }

    /// Two shards' records written as files and merged: the merge gives back every shard's
    /// record of every step, in shard order, whatever the order of the files; a step that
    /// failed keeps its failure.
    #[test]
    fn the_merge_gives_back_every_shard_s_records_step_by_step() {
        let records = |k: u32| {
            vec![
                record(&[("enumerate a", Some(&format!("{k}")))], None),
                record(
                    &[("proptest C2", (k == 1).then_some("{}"))],
                    (k == 2).then_some("planted"),
                ),
                record(&[], None),
            ]
        };
        let files: Vec<(String, String)> = [2, 1]
            .into_iter()
            .map(|k| {
                let part = Part::parse(&format!("{k}/2")).unwrap();
                let f = file(part, json!({"run": 7}), records(k), 0.5);
                assert_eq!(f.entries.len(), 4 + 1, "one entry per unit and per step");
                (format!("s{k}"), f.to_json(VERIFY_FORMAT))
            })
            .collect();
        let merged = merge(&files).unwrap();
        assert_eq!(merged.fingerprint, json!({"run": 7}));
        assert_eq!(merged.steps.len(), 3);
        for (i, step) in merged.steps.iter().enumerate() {
            assert_eq!(step, &[records(1)[i].clone(), records(2)[i].clone()]);
        }
    }

    /// A file whose entries do not close their last step, or shards that recorded different
    /// numbers of steps, are refused.
    #[test]
    fn a_merge_of_unclosed_or_unequal_steps_is_refused() {
        let part = |k: u32| Part::parse(&format!("{k}/2")).unwrap();
        let text = |f: ShardFile| f.to_json(VERIFY_FORMAT);
        // A failed step: the shards' sites are then compared step by step by the runner.
        let one = file(
            part(1),
            json!({}),
            vec![record(&[("a", None)], Some("x"))],
            0.0,
        );
        let mut unclosed = file(part(2), json!({}), vec![record(&[("a", None)], None)], 0.0);
        unclosed.entries.push(Entry {
            site: "b".into(),
            value: None,
        });
        let e = merge(&[
            ("1".into(), text(one.clone())),
            ("2".into(), text(unclosed)),
        ])
        .unwrap_err();
        assert!(e.contains("after its last engine"), "{e}");
        let two_steps = file(
            part(2),
            json!({}),
            vec![record(&[("a", None)], None), record(&[], Some("x"))],
            0.0,
        );
        let e = merge(&[("1".into(), text(one)), ("2".into(), text(two_steps))]).unwrap_err();
        assert!(e.contains("different numbers of engine runs"), "{e}");
    }
}
