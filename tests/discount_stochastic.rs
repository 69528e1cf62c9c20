//! Issue 11, item 3: `discount` on stochastic problems.
use truecost::envs::EnvSpec;
use truecost::objectives::{parametric::discount_breakpoints, Model};

#[test]
fn scratch_frozenlake() {
    let spec = std::env::var("SPEC").unwrap_or("frozenlake".into());
    let env = EnvSpec::parse(&spec).unwrap().build().unwrap();
    let m = Model::from_environment(&env).unwrap();
    let t = std::time::Instant::now();
    let d = discount_breakpoints(&m).unwrap();
    eprintln!(
        "{:?} probes {} degree {} bps {}",
        t.elapsed(),
        d.probes,
        d.degree,
        d.breakpoints.len()
    );
    for (i, iv) in d.intervals.iter().enumerate() {
        eprintln!(
            "interval {i}: sample {} success {:?} tc {} {}",
            iv.sample,
            iv.achievement.success,
            iv.achievement.truecost_min,
            iv.achievement.truecost_max
        );
        if i < d.breakpoints.len() {
            let b = &d.breakpoints[i];
            eprintln!(
                "  bp {} touch {} ties {:?}",
                b.at.decimal(8),
                b.touch,
                b.ties
            );
        }
    }
}
