//! The config parser and validator on arbitrary text.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data)
        && let Ok(config) = vivae_lab::config::Config::from_toml(text)
    {
        // A config that validates round-trips through TOML.
        let again = vivae_lab::config::Config::from_toml(&config.to_toml()).expect("round trip");
        assert_eq!(again, config);
    }
});
