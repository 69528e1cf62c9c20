//! Embeds the git commit (for `truecost verify --format latex`); "unknown" without git.
use std::process::Command;

fn main() {
    let commit = Command::new("git")
        .args(["rev-parse", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty() && s.chars().all(|c| c.is_ascii_hexdigit()))
        .unwrap_or_else(|| "unknown".to_string());
    println!("cargo:rustc-env=TRUECOST_GIT_COMMIT={commit}");
    // Re-run when HEAD moves (paths from git itself; worktrees keep them elsewhere).
    for what in ["HEAD", "refs/heads"] {
        if let Some(p) = Command::new("git")
            .args(["rev-parse", "--git-path", what])
            .output()
            .ok()
            .filter(|o| o.status.success())
            .and_then(|o| String::from_utf8(o.stdout).ok())
        {
            println!("cargo:rerun-if-changed={}", p.trim());
        }
    }
    println!("cargo:rerun-if-changed=build.rs");
}
