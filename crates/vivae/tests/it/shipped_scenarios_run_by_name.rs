//! `vivae scenario list` shows the shipped scenarios, and `--scenario NAME`
//! runs each of them with the default experiment's robots.

use crate::common::*;

const SHIPPED: [&str; 5] = ["roads", "oval", "town", "figure8", "obstacles"];

#[test]
fn every_shipped_scenario_is_listed_and_evolves_by_name() {
    let list = ok(vivae().args(["scenario", "list"]));
    for name in SHIPPED {
        assert!(list.lines().any(|l| l.starts_with(name)), "{list}");
        // The file in scenarios/ is what the program ships.
        let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(format!("{name}.svg"));
        assert!(file.exists(), "{}", file.display());
    }
    let dir = scratch("shipped");
    let config = write_small_config(&dir, 1);
    for name in SHIPPED {
        let out = dir.join(name);
        evolve(&config, &out, &["--scenario", name]);
        let info = ok(vivae()
            .args(["scenario", "info"])
            .arg(out.join("scenario.svg")));
        assert!(info.contains("robots: 5"), "{name}: {info}");
    }
    let out = run(vivae().args(["scenario", "info", "no-such-scenario"]));
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("vivae scenario list"));
    std::fs::remove_dir_all(&dir).unwrap();
}
