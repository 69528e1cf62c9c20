//! C1 encodings (placeholder while written).
