//! Sharding the claims engines over many machines.
//!
//! `truecost verify --shard K/N` runs the same control flow as the whole run, but every
//! expensive *site* does only the K-th part of its work and records what it computed in a
//! `Ledger`:
//!
//! * an exhaustive enumeration ([`super::enumerate`]) visits the labelled indices `i` with
//!   `i mod N = K − 1` and records its partial accumulator — counts, maxima and the
//!   candidate minimal counterexamples *with their minimality keys*;
//! * a unit of work that cannot be split without changing its result (one proptest run:
//!   proptest stops at its first failure and shrinks it; one SMT obligation) is owned by one
//!   shard, the `u`-th unit of the run by shard `u mod N + 1`, and recorded there.
//!
//! `truecost verify merge` replays the same control flow with every site answered from the
//! shards' ledgers: an enumeration gets the merge (the accumulator's own associative and
//! commutative `merge`) of its N partial accumulators, a unit gets the value its owner
//! recorded. The claims are then derived from exactly the values the whole run derives them
//! from, so the merged report is the whole run's, byte for byte (times aside).
//!
//! Shards of different runs are refused (a fingerprint of the scope, the claim filter, the
//! options and the tool), so are a missing, duplicated or foreign shard, a file whose
//! checksum does not match its content, and shards that disagree on the sites they ran.
//!
//! **Engine failures.** An engine that panics (a bug in the code it checks, or in itself) is
//! caught by [`caught`], which `verify` wraps around every engine: the panic becomes that
//! engine's line, `engine failed: <message>`, and the rest of the report is still made. A site
//! whose work panics under `verify --shard` records the failure as its value, and the merge
//! raises it again at the same site, so the merged report has the same engine line.

use std::any::Any;
use std::cell::RefCell;
use std::collections::VecDeque;
use std::fmt;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, Once};

use serde::de::DeserializeOwned;
use serde::Serialize;
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
    // checks those shards' sites as it reads them ([`engine`]).
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

enum Mode {
    Shard {
        part: Part,
        entries: Vec<Entry>,
    },
    /// `next[s]`: the next entry of shard `s` to read.
    Merge {
        shards: Vec<ShardFile>,
        next: Vec<usize>,
    },
}

struct Ledger {
    mode: Mode,
    /// Units met so far (the `u` of "unit `u` is owned by shard `u mod N + 1`").
    units: u64,
    /// The first problem met while merging (reported after the run).
    error: Option<String>,
}

thread_local! {
    static LEDGER: RefCell<Option<Ledger>> = const { RefCell::new(None) };
}

/// Runs `f` as shard `part`: returns its value and the recorded entries. The ledger is bound
/// to the calling thread: the engines consult it from the thread that runs the claims.
pub fn record_shard<T>(part: Part, f: impl FnOnce() -> T) -> (T, Vec<Entry>) {
    let previous = LEDGER.with(|l| {
        l.borrow_mut().replace(Ledger {
            mode: Mode::Shard {
                part,
                entries: Vec::new(),
            },
            units: 0,
            error: None,
        })
    });
    let value = f();
    let ledger = LEDGER.with(|l| std::mem::replace(&mut *l.borrow_mut(), previous));
    match ledger.map(|l| l.mode) {
        Some(Mode::Shard { entries, .. }) => (value, entries),
        _ => unreachable!("the shard ledger was replaced while running"),
    }
}

/// Runs `f` with every site answered from `shards` (a [`complete_set`]). Fails if the run met
/// a site the shards did not record, or left some unread.
pub fn replay<T>(shards: Vec<ShardFile>, f: impl FnOnce() -> T) -> Result<T, String> {
    let expected = shards.first().map_or(0, |s| s.entries.len());
    let previous = LEDGER.with(|l| {
        l.borrow_mut().replace(Ledger {
            mode: Mode::Merge {
                next: vec![0; shards.len()],
                shards,
            },
            units: 0,
            error: None,
        })
    });
    let value = f();
    let ledger = LEDGER
        .with(|l| std::mem::replace(&mut *l.borrow_mut(), previous))
        .expect("the merge ledger");
    if let Some(e) = ledger.error {
        return Err(e);
    }
    match ledger.mode {
        Mode::Merge { shards, next }
            if next.iter().zip(&shards).all(|(&j, s)| j == s.entries.len()) =>
        {
            Ok(value)
        }
        Mode::Merge { next, .. } => Err(format!(
            "the merge read {} of the shards' {expected} sites (shards of a different build?)",
            next[0]
        )),
        Mode::Shard { .. } => unreachable!("the merge ledger was replaced while running"),
    }
}

fn decode<T: DeserializeOwned>(site: &str, text: &str) -> Result<T, String> {
    serde_json::from_str(text).map_err(|e| format!("site '{site}': malformed value ({e})"))
}

fn encode<T: Serialize>(value: &T) -> String {
    serde_json::to_string(value).expect("a site's value is serialisable")
}

/// Takes the next merge entry (all shards' values), checking its site. A shard that stopped
/// at the end of the current engine, which failed in it ([`engine`]), answers with its failure.
fn next_merged(l: &mut Ledger, site: &str) -> Option<Vec<Option<String>>> {
    let Mode::Merge { shards, next } = &mut l.mode else {
        return None;
    };
    let values: Option<Vec<Option<String>>> = shards
        .iter()
        .zip(next.iter_mut())
        .map(|(s, j)| {
            let entry = s.entries.get(*j)?;
            if entry.site == END_OF_ENGINE {
                let failure = entry.value.as_ref()?;
                return Some(Some(format!("{ENGINE_FAILED}{failure}")));
            }
            *j += 1;
            (entry.site == site).then(|| entry.value.clone())
        })
        .collect();
    if values.is_none() && l.error.is_none() {
        l.error = Some(format!(
            "the merge met site '{site}' where the shards recorded another (shards of a different build?)"
        ));
    }
    values
}

/// A splittable site (an enumeration): `compute(part)` does the part of the work `part` owns
/// (`None`: all of it), and `combine` is associative and commutative.
///
/// Whole run: `compute(None)`. Shard: `compute(Some(part))`, recorded. Merge: the `combine` of
/// every shard's recorded value (`compute` is not called); `empty()` if a value is unreadable
/// (the merge then fails with the reason).
pub fn split<T: Serialize + DeserializeOwned>(
    site: &str,
    compute: impl FnOnce(Option<Part>) -> T,
    combine: impl Fn(T, T) -> T,
    empty: impl Fn() -> T,
) -> T {
    enum Plan {
        Whole,
        Shard(Part),
        Merged(Vec<Option<String>>),
        Broken,
    }
    let plan = LEDGER.with(|l| match l.borrow_mut().as_mut() {
        None => Plan::Whole,
        Some(Ledger {
            mode: Mode::Shard { part, .. },
            ..
        }) => Plan::Shard(*part),
        Some(ledger) => next_merged(ledger, site).map_or(Plan::Broken, Plan::Merged),
    });
    match plan {
        Plan::Whole => compute(None),
        Plan::Shard(part) => {
            let v = recorded_failure(site, || compute(Some(part)));
            push(site, Some(encode(&v)));
            v
        }
        Plan::Merged(values) => {
            let mut acc: Option<T> = None;
            if let Some(failure) = values.iter().flatten().find_map(|t| failed_value(t)) {
                raise(failure.to_string());
            }
            for text in values {
                let Some(text) = text else {
                    fail(format!("site '{site}': a shard recorded no value"));
                    return empty();
                };
                match decode::<T>(site, &text) {
                    Ok(v) => {
                        acc = Some(match acc {
                            Some(a) => combine(a, v),
                            None => v,
                        })
                    }
                    Err(e) => {
                        fail(e);
                        return empty();
                    }
                }
            }
            acc.unwrap_or_else(empty)
        }
        Plan::Broken => empty(),
    }
}

/// An indivisible unit of work (one proptest run): owned by one shard.
///
/// Whole run: `compute()`. Shard: `compute()` if this shard owns the unit (recorded), else
/// `placeholder()` (recorded as absent). Merge: the owner's recorded value.
pub fn unit<T: Serialize + DeserializeOwned>(
    site: &str,
    compute: impl FnOnce() -> T,
    placeholder: impl Fn() -> T,
) -> T {
    let mut compute = Some(compute);
    units(
        &[site.to_string()],
        |wanted| {
            wanted
                .iter()
                .map(|&w| if w { compute.take().map(|c| c()) } else { None })
                .collect()
        },
        placeholder,
    )
    .pop()
    .expect("one unit")
}

/// A batch of indivisible units (the SMT obligations of a claim), unit `u` of the run owned by
/// shard `u mod N + 1`. `compute(wanted)` computes the units marked `true` (in parallel if it
/// likes) and returns `Some` for each of them; the batch's value is every unit's value, in
/// order — recorded by the owners under `verify --shard`, read from them under `verify merge`.
pub fn units<T: Serialize + DeserializeOwned>(
    sites: &[String],
    compute: impl FnOnce(&[bool]) -> Vec<Option<T>>,
    placeholder: impl Fn() -> T,
) -> Vec<T> {
    enum Plan {
        Whole,
        Shard(Vec<bool>),
        Merged(Vec<Option<Vec<Option<String>>>>),
    }
    let plan = LEDGER.with(|l| match l.borrow_mut().as_mut() {
        None => Plan::Whole,
        Some(ledger) => {
            let first = ledger.units;
            ledger.units += sites.len() as u64;
            match &ledger.mode {
                Mode::Shard { part, .. } => {
                    let part = *part;
                    Plan::Shard((first..ledger.units).map(|u| part.owns(u)).collect())
                }
                Mode::Merge { .. } => {
                    Plan::Merged(sites.iter().map(|site| next_merged(ledger, site)).collect())
                }
            }
        }
    });
    match plan {
        Plan::Whole => compute(&vec![true; sites.len()])
            .into_iter()
            .map(|v| v.expect("a wanted unit is computed"))
            .collect(),
        Plan::Shard(wanted) => {
            let values = match caught(|| compute(&wanted)) {
                Ok(values) => values,
                Err(failure) => {
                    // Every unit of the batch this shard owns failed with it.
                    for (site, &w) in sites.iter().zip(&wanted) {
                        push(site, w.then(|| format!("{ENGINE_FAILED}{failure}")));
                    }
                    raise(failure);
                }
            };
            sites
                .iter()
                .zip(values)
                .map(|(site, v)| match v {
                    Some(v) => {
                        push(site, Some(encode(&v)));
                        v
                    }
                    None => {
                        push(site, None);
                        placeholder()
                    }
                })
                .collect()
        }
        Plan::Merged(values) => sites
            .iter()
            .zip(values)
            .map(|(site, values)| {
                let Some(values) = values else {
                    return placeholder();
                };
                if let Some(failure) = values.iter().flatten().find_map(|t| failed_value(t)) {
                    raise(failure.to_string());
                }
                let mut present = values.into_iter().flatten();
                match (present.next(), present.next()) {
                    (Some(text), None) => decode::<T>(site, &text).unwrap_or_else(|e| {
                        fail(e);
                        placeholder()
                    }),
                    (None, _) => {
                        fail(format!("site '{site}': no shard ran it"));
                        placeholder()
                    }
                    (Some(_), Some(_)) => {
                        fail(format!("site '{site}': run by two shards"));
                        placeholder()
                    }
                }
            })
            .collect(),
    }
}

/// The prefix of an engine line's mode when the engine panicked (the panic's message follows),
/// and of a shard entry's value when the site's work panicked (never JSON, so never a value).
pub const ENGINE_FAILED: &str = "engine failed: ";

/// A panic already caught and described: raised again through the levels above the one that
/// caught it (a shard's site, a proptest run), which keep its description.
struct Described(String);

/// Engines running under [`caught`] now (the panic hook is silent while there are any).
static CATCHING: AtomicUsize = AtomicUsize::new(0);
/// Whether the stand-in's panic hook was installed before [`caught`]'s (which then passes
/// every panic on to it, since it records where the harness bodies it runs panic).
static OUTERMOST: AtomicBool = AtomicBool::new(false);
/// The latest panics under [`caught`] that reached the hook (at most [`RECENT_PANICS`]): their
/// messages and locations, for [`caught`] to find where the panic it caught happened.
static RECENT: Mutex<VecDeque<(String, String)>> = Mutex::new(VecDeque::new());
const RECENT_PANICS: usize = 256;

/// The payload of the panic that asks whether the stand-in's hook is above [`caught`]'s.
struct Probe;

fn message_of(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".into())
}

fn install_hook() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if info.payload().is::<Probe>() {
                OUTERMOST.store(true, Ordering::SeqCst);
                return;
            }
            if CATCHING.load(Ordering::SeqCst) == 0 {
                return previous(info);
            }
            // A panic of a harness body that the stand-in runs silently (on any thread, during
            // any catch) is the stand-in's to record: recorded here it would crowd out the
            // places of the panics being caught.
            if truecost_proofs::standin::__quiet() {
                if OUTERMOST.load(Ordering::SeqCst) {
                    previous(info);
                }
                return;
            }
            let at = info.location().map_or(String::new(), |l| l.to_string());
            let mut recent = RECENT.lock().unwrap_or_else(|e| e.into_inner());
            if recent.len() == RECENT_PANICS {
                recent.pop_front();
            }
            recent.push_back((message_of(info.payload()), at));
            drop(recent);
            if OUTERMOST.load(Ordering::SeqCst) {
                previous(info);
            }
        }));
        // The stand-in installs its hook over this one unless it did already: a silenced probe
        // panic reaches this hook only in that case.
        truecost_proofs::standin::__panics(|| std::panic::panic_any(Probe));
    });
}

/// Runs `f`, an engine, and catches a panic in it — on this thread or on a rayon worker whose
/// work it waits for (rayon raises a worker's panic again in the caller) — as its description:
/// the panic message and where it panicked, escaped to one line. No panic message reaches
/// stderr meanwhile (unless the stand-in's hook was installed first: it then prints them).
///
/// ```
/// use truecost::claims::shard::caught;
/// assert_eq!(caught(|| 6 * 7), Ok(42));
/// let failure = caught(|| -> u8 { panic!("value out of range\nsecond line") }).unwrap_err();
/// assert!(failure.starts_with("value out of range\\nsecond line (at "), "{failure}");
/// ```
pub fn caught<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    install_hook();
    if CATCHING.fetch_add(1, Ordering::SeqCst) == 0 {
        RECENT.lock().unwrap_or_else(|e| e.into_inner()).clear();
    }
    let result = catch_unwind(AssertUnwindSafe(f));
    // The panic's place is read before this catch ends: a catch that starts once none is
    // running (on another thread) clears the places recorded.
    let result = result.map_err(|payload| {
        if let Some(Described(text)) = payload.downcast_ref::<Described>() {
            return text.clone();
        }
        let message = message_of(&*payload);
        let at = RECENT
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .iter()
            .rev()
            .find(|(m, l)| *m == message && !l.is_empty())
            .map(|(_, l)| format!(" (at {l})"))
            .unwrap_or_default();
        crate::echo::one_line(&format!("{message}{at}"))
    });
    CATCHING.fetch_sub(1, Ordering::SeqCst);
    result
}

/// The site of the entry that ends an engine's entries ([`engine`]).
const END_OF_ENGINE: &str = "end of engine";

/// Runs `f`, one engine of `verify`, with its panics [`caught`]. Under `verify --shard` an
/// entry ends the engine's entries, with its failure if it failed: a shard whose engine failed
/// stops meeting that engine's sites while the other shards go on. The merge raises the
/// failure where the failed shard would have answered (at the failing site, or at any later
/// site of the engine), and leaves what the other shards recorded for the rest of the engine
/// unread: the merged report has the engine's failure line, as the whole run has.
pub fn engine<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    let result = caught(f);
    let failed = LEDGER.with(|l| {
        let mut l = l.borrow_mut();
        let ledger = l.as_mut()?;
        match &mut ledger.mode {
            Mode::Shard { entries, .. } => {
                entries.push(Entry {
                    site: END_OF_ENGINE.into(),
                    value: result.as_ref().err().cloned(),
                });
                None
            }
            Mode::Merge { shards, next } => {
                let mut failed = None;
                for (s, j) in shards.iter().zip(next.iter_mut()) {
                    let Some(k) = s.entries[*j..].iter().position(|e| e.site == END_OF_ENGINE)
                    else {
                        ledger.error.get_or_insert_with(|| {
                            "the merge met the end of an engine the shards did not record (shards of a different build?)".into()
                        });
                        continue;
                    };
                    let end = &s.entries[*j + k];
                    if k > 0 && result.is_ok() && end.value.is_none() {
                        ledger.error.get_or_insert_with(|| {
                            format!("shard {} recorded sites of an engine the merge did not meet (shards of a different build?)", s.part)
                        });
                    }
                    failed = failed.or_else(|| end.value.clone());
                    *j += k + 1;
                }
                failed
            }
        }
    });
    match (result, failed) {
        (Ok(_), Some(failure)) => Err(failure),
        (result, _) => result,
    }
}

/// Raises a failure that [`caught`] described again, to the [`caught`] around the engine (its
/// description kept; no panic message printed).
pub fn raise(failure: String) -> ! {
    resume_unwind(Box::new(Described(failure)))
}

/// A shard's work at `site`: a panic in it is recorded as the site's value, then raised again.
fn recorded_failure<T>(site: &str, compute: impl FnOnce() -> T) -> T {
    caught(compute).unwrap_or_else(|failure| {
        push(site, Some(format!("{ENGINE_FAILED}{failure}")));
        raise(failure)
    })
}

/// The failure a shard recorded as a site's value, if it is one.
fn failed_value(text: &str) -> Option<&str> {
    text.strip_prefix(ENGINE_FAILED)
}

fn push(site: &str, value: Option<String>) {
    LEDGER.with(|l| {
        if let Some(Ledger {
            mode: Mode::Shard { entries, .. },
            ..
        }) = l.borrow_mut().as_mut()
        {
            entries.push(Entry {
                site: site.to_string(),
                value,
            });
        }
    });
}

fn fail(message: String) {
    LEDGER.with(|l| {
        if let Some(ledger) = l.borrow_mut().as_mut() {
            ledger.error.get_or_insert(message);
        }
    });
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

    fn sum_of_owned(part: Option<Part>) -> u64 {
        (0..100u64)
            .filter(|&i| part.is_none_or(|p| p.owns(i)))
            .sum()
    }

    fn run_sites() -> (u64, String, String) {
        let total = split("sum", sum_of_owned, |a, b| a + b, || 0);
        let first = unit("first", || "one".to_string(), String::new);
        let second = unit("second", || "two".to_string(), String::new);
        (total, first, second)
    }

    /// An engine that panics, on the calling thread or on a rayon worker (the panic raised
    /// again in the caller by rayon), is caught as its message and location; one that does
    /// not returns its value; a failure raised again keeps its description through a second
    /// [`caught`].
    #[test]
    fn a_panicking_engine_is_caught_with_its_message_and_location() {
        use rayon::prelude::*;
        assert_eq!(caught(|| 6 * 7), Ok(42));
        let here = caught(|| -> u8 { panic!("planted: {}", 3) }).unwrap_err();
        assert!(
            here.starts_with("planted: 3 (at src/claims/shard.rs:"),
            "{here}"
        );
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let on_worker = caught(|| {
            pool.install(|| {
                (0..10_000u32)
                    .into_par_iter()
                    .map(|i| {
                        assert!(i != 7_777, "planted at {i}");
                        u64::from(i)
                    })
                    .sum::<u64>()
            })
        })
        .unwrap_err();
        assert!(
            on_worker.starts_with("planted at 7777 (at src/claims/shard.rs:"),
            "{on_worker}"
        );
        let again = caught(|| caught(|| -> u8 { panic!("inner") }).unwrap_or_else(|f| raise(f)));
        assert!(again.unwrap_err().starts_with("inner (at "));
    }

    /// A site whose work panics under a shard records the failure as its value and raises it;
    /// the merge raises it again at the same site, with the same description, whichever shard
    /// recorded it.
    #[test]
    fn a_shard_records_a_failing_site_and_the_merge_raises_it_again() {
        fn sites() -> Result<u64, String> {
            caught(|| {
                let total = split("sum", sum_of_owned, |a, b| a + b, || 0);
                let failing = unit("failing", || -> u64 { panic!("planted unit") }, || 0);
                total + failing
            })
        }
        let whole = sites().unwrap_err();
        assert!(whole.starts_with("planted unit (at "), "{whole}");
        let files: Vec<(String, ShardFile)> = (1..=2)
            .map(|k| {
                let part = Part::parse(&format!("{k}/2")).unwrap();
                let (r, entries) = record_shard(part, sites);
                // Unit 0 ("failing") is shard 1's: shard 2 records it as another's.
                assert_eq!(r.is_err(), k == 1, "shard {k}: {r:?}");
                assert_eq!(entries.len(), 2);
                let value = entries[1].value.clone();
                assert_eq!(
                    value.is_some_and(|v| v == format!("{ENGINE_FAILED}{whole}")),
                    k == 1
                );
                let file = ShardFile {
                    part,
                    fingerprint: json!({"run": 2}),
                    entries,
                    seconds: 0.0,
                };
                (format!("shard{k}"), file)
            })
            .collect();
        let merged = replay(complete_set(files).unwrap(), sites).unwrap();
        assert_eq!(merged, Err(whole));
    }

    /// Shards that disagree on an engine's sites because it failed in one of them (here on
    /// shard 1's part only): the merge raises shard 1's failure for the engine, leaves shard
    /// 2's further site of it unread, and reads the sites after the engine.
    #[test]
    fn an_engine_failing_in_one_shard_fails_in_the_merge() {
        fn sites() -> (Result<u64, String>, String) {
            let total = engine(|| {
                let first = split(
                    "first",
                    |part| {
                        assert!(part.is_none_or(|p| p.k() != 1), "planted in shard 1");
                        sum_of_owned(part)
                    },
                    |a, b| a + b,
                    || 0,
                );
                first + split("second", sum_of_owned, |a, b| a + b, || 0)
            });
            let after = unit("after", || "after".to_string(), String::new);
            (total, after)
        }
        assert_eq!(sites(), (Ok(2 * 4950), "after".into()));
        let mut files = Vec::new();
        for k in 1..=2 {
            let part = Part::parse(&format!("{k}/2")).unwrap();
            let (r, entries) = record_shard(part, sites);
            assert_eq!(r.0.is_err(), k == 1, "{r:?}");
            let names: Vec<&str> = entries.iter().map(|e| e.site.as_str()).collect();
            if k == 1 {
                assert_eq!(names, ["first", END_OF_ENGINE, "after"]);
            } else {
                assert_eq!(names, ["first", "second", END_OF_ENGINE, "after"]);
            }
            let text = ShardFile {
                part,
                fingerprint: json!({"run": 3}),
                entries,
                seconds: 0.0,
            }
            .to_json("t/1");
            files.push((format!("shard{k}"), text));
        }
        let merged = replay(read_complete_set(&files, "t/1").unwrap(), sites).unwrap();
        let failure = merged.0.unwrap_err();
        assert!(failure.starts_with("planted in shard 1 (at "), "{failure}");
        assert_eq!(merged.1, "after");
    }

    /// Three shards split the sum 0+…+99 = 4950 and own one unit each at most; the merge
    /// answers every site as the whole run does.
    #[test]
    fn three_shards_merge_to_the_whole_run() {
        let whole = run_sites();
        assert_eq!(whole, (4950, "one".into(), "two".into()));
        let mut files = Vec::new();
        for k in 1..=3 {
            let part = Part::parse(&format!("{k}/3")).unwrap();
            let (partial, entries) = record_shard(part, run_sites);
            assert!(partial.0 < 4950);
            files.push((
                format!("shard{k}"),
                ShardFile {
                    part,
                    fingerprint: json!({"run": 1}),
                    entries,
                    seconds: 0.0,
                },
            ));
        }
        // Unit 0 is shard 1's, unit 1 shard 2's: shard 3 ran neither.
        assert_eq!(files[2].1.entries[1].value, None);
        let text: Vec<String> = files.iter().map(|(_, f)| f.to_json("t/1")).collect();
        let read: Vec<(String, ShardFile)> = text
            .iter()
            .enumerate()
            .map(|(i, t)| {
                (
                    format!("f{i}"),
                    ShardFile::from_json(t, "t/1", "f").unwrap(),
                )
            })
            .collect();
        let merged = replay(complete_set(read).unwrap(), run_sites).unwrap();
        assert_eq!(merged, whole);
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

    /// A merge that reads fewer sites than the shards recorded (a run of a different build
    /// that stops early) is refused, naming how many it read; one that meets a site in another
    /// place is refused too.
    #[test]
    fn a_merge_that_leaves_sites_unread_or_reads_another_is_refused() {
        let part = Part::parse("1/1").unwrap();
        let (_, entries) = record_shard(part, run_sites);
        assert_eq!(entries.len(), 3);
        let shards = || {
            vec![ShardFile {
                part,
                fingerprint: json!({}),
                entries: entries.clone(),
                seconds: 0.0,
            }]
        };
        let first_two = || {
            let total = split("sum", sum_of_owned, |a, b| a + b, || 0);
            let first = unit("first", || "one".to_string(), String::new);
            (total, first)
        };
        let e = replay(shards(), first_two).unwrap_err();
        assert_eq!(
            e,
            "the merge read 2 of the shards' 3 sites (shards of a different build?)"
        );
        let swapped = || {
            let total = split("sum", sum_of_owned, |a, b| a + b, || 0);
            let second = unit("second", || "two".to_string(), String::new);
            (total, second)
        };
        let e = replay(shards(), swapped).unwrap_err();
        assert!(e.contains("met site 'second'"), "{e}");
        assert_eq!(replay(shards(), run_sites).unwrap(), run_sites());
    }

    /// A shard file whose recorded values were tampered with is refused on merge, naming the
    /// site: a split site without a value, a malformed value, a unit no shard ran.
    #[test]
    fn a_merge_of_tampered_values_is_refused_naming_the_site() {
        let part = Part::parse("1/1").unwrap();
        let (_, entries) = record_shard(part, run_sites);
        let merge = |edit: &dyn Fn(&mut Vec<Entry>)| {
            let mut entries = entries.clone();
            edit(&mut entries);
            let file = ShardFile {
                part,
                fingerprint: json!({}),
                entries,
                seconds: 0.0,
            };
            replay(vec![file], run_sites)
        };
        assert_eq!(merge(&|_| {}), Ok(run_sites()));
        assert_eq!(
            merge(&|e| e[0].value = None),
            Err("site 'sum': a shard recorded no value".into())
        );
        let malformed = merge(&|e| e[0].value = Some("not json".into())).unwrap_err();
        assert!(
            malformed.starts_with("site 'sum': malformed value"),
            "{malformed}"
        );
        assert_eq!(
            merge(&|e| e[1].value = None),
            Err("site 'first': no shard ran it".into())
        );
    }
}
