//! Sizes for large models: the `--max-memory` budget of the exact optimum,
//! parsed exactly, and bytes printed for people.

/// The default memory budget of the exact optimum: 4 GiB.
pub const DEFAULT_MAX_MEMORY: u64 = 4 << 30;

/// Why a size was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("--max-memory must be a size such as 4G, 512M, 1.5G or 1000000 (bytes; K, M, G, T are powers of 1024), at least 1M, got {0}")]
pub struct SizeError(pub String);

/// Parses a memory size: digits with an optional decimal fraction, then an optional unit `K`,
/// `M`, `G` or `T` (powers of 1024; `KB`, `KiB`, … and lower case accepted); a bare number is
/// bytes. Exact: the fraction is read from its text and the result rounded down to a byte.
/// Sizes below 1 MiB or above 2⁶⁴ bytes are refused.
///
/// ```
/// use truecost::stochastic::scale::parse_size;
/// assert_eq!(parse_size("4G").unwrap(), 4 << 30);
/// assert_eq!(parse_size("512M").unwrap(), 512 << 20);
/// assert_eq!(parse_size("1.5GiB").unwrap(), 3 << 29);
/// assert_eq!(parse_size("2000000").unwrap(), 2_000_000);
/// assert!(parse_size("-1G").is_err());
/// assert!(parse_size("10X").is_err());
/// ```
pub fn parse_size(text: &str) -> Result<u64, SizeError> {
    let bad = || SizeError(crate::echo::echo(text));
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let shift = match unit.to_ascii_lowercase().as_str() {
        "" | "b" => 0,
        "k" | "kb" | "kib" => 10,
        "m" | "mb" | "mib" => 20,
        "g" | "gb" | "gib" => 30,
        "t" | "tb" | "tib" => 40,
        _ => return Err(bad()),
    };
    let (int, frac) = number.split_once('.').unwrap_or((number, ""));
    if int.is_empty() || frac.contains('.') || int.len() + frac.len() > 30 {
        return Err(bad());
    }
    if number.ends_with('.') {
        return Err(bad());
    }
    // value = int.frac · 2^shift, exactly, rounded down.
    let digits: u128 = format!("{int}{frac}").parse().map_err(|_| bad())?;
    let scale = 10u128.pow(frac.len() as u32);
    let bytes = digits
        .checked_mul(1u128 << shift)
        .map(|v| v / scale)
        .ok_or_else(bad)?;
    let bytes = u64::try_from(bytes).map_err(|_| bad())?;
    if bytes < 1 << 20 {
        return Err(bad());
    }
    Ok(bytes)
}

/// Bytes for people: `512 MiB`, `1.5 GiB` (one decimal above 1 GiB, rounded up so an estimate
/// is never understated).
///
/// ```
/// use truecost::stochastic::scale::format_bytes;
/// assert_eq!(format_bytes(4 << 30), "4.0 GiB");
/// assert_eq!(format_bytes(512 << 20), "512 MiB");
/// assert_eq!(format_bytes((3 << 29) + 1), "1.6 GiB");
/// ```
pub fn format_bytes(bytes: u64) -> String {
    const MIB: u64 = 1 << 20;
    const GIB: u64 = 1 << 30;
    if bytes >= GIB {
        let tenths = (bytes as u128 * 10).div_ceil(GIB as u128);
        format!("{}.{} GiB", tenths / 10, tenths % 10)
    } else {
        format!("{} MiB", bytes.div_ceil(MIB))
    }
}
