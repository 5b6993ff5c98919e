//! Which `Host` header names `vivae view` answers: its defence against DNS
//! rebinding, where a page from another site renames the server's address as
//! its own host and then reads the run (or drives the WebSocket) as if same-origin.
//!
//! Accepted: an IP literal equal to the bound address (any IP literal when
//! bound to all interfaces: `0.0.0.0` or `::`), `localhost`, and the names
//! given with `--allow-host`; each with or without a port (any port, so that
//! a forwarded port still works). Names are compared case-insensitively, one
//! trailing dot ignored. A request without a Host header, or with any other
//! name, is refused.

use std::net::IpAddr;

use vivae_lab::io::bad_input;

/// The Host names a server answers.
#[derive(Debug, Clone)]
pub struct HostPolicy {
    bound: IpAddr,
    names: Vec<String>,
}

impl HostPolicy {
    /// Accepts `bound` (the listening address), `localhost` and `extra`.
    ///
    /// # Errors
    /// A bad-input error for an `extra` that is not a host name (with no port).
    pub fn new(bound: IpAddr, extra: &[String]) -> vivae_lab::Result<HostPolicy> {
        let mut names = vec!["localhost".to_string()];
        for name in extra {
            let valid = !name.is_empty()
                && name.len() <= 253
                && name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '.');
            if !valid {
                return Err(bad_input(format!(
                    "--allow-host {name:?}: not a host name (letters, digits, '-' and '.', no port)"
                )));
            }
            names.push(normal_name(name));
        }
        Ok(HostPolicy {
            bound: bound.to_canonical(),
            names,
        })
    }

    /// Whether a request whose Host header is `host` is answered.
    pub fn allows(&self, host: Option<&str>) -> bool {
        let Some(name) = host.and_then(strip_port) else {
            return false;
        };
        let literal = name
            .strip_prefix('[')
            .and_then(|n| n.strip_suffix(']'))
            .unwrap_or(name);
        if let Ok(ip) = literal.parse::<IpAddr>() {
            // An IPv6 literal must be bracketed, as URLs write it.
            let bracketed = literal.len() != name.len();
            return bracketed == ip.is_ipv6()
                && (self.bound.is_unspecified() || ip.to_canonical() == self.bound);
        }
        let name = normal_name(name);
        self.names.contains(&name)
    }
}

fn normal_name(name: &str) -> String {
    name.strip_suffix('.').unwrap_or(name).to_ascii_lowercase()
}

/// The name part of a Host header value (`name`, `name:port`, `[v6]`,
/// `[v6]:port`); `None` if the port is not a number.
fn strip_port(host: &str) -> Option<&str> {
    let (name, port) = if host.starts_with('[') {
        let end = host.find(']')?;
        let rest = &host[end + 1..];
        let port = if rest.is_empty() {
            None
        } else {
            Some(rest.strip_prefix(':')?)
        };
        (&host[..=end], port)
    } else {
        match host.split_once(':') {
            Some((n, p)) => (n, Some(p)),
            None => (host, None),
        }
    };
    let port_ok = port.is_none_or(|p| {
        !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()) && p.parse::<u16>().is_ok()
    });
    (port_ok && !name.is_empty()).then_some(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn policy(bound: &str, extra: &[&str]) -> HostPolicy {
        let extra: Vec<String> = extra.iter().map(|s| s.to_string()).collect();
        HostPolicy::new(bound.parse().unwrap(), &extra).unwrap()
    }

    #[test]
    fn loopback_answers_its_address_and_localhost_only() {
        let p = policy("127.0.0.1", &[]);
        for ok in [
            "127.0.0.1",
            "127.0.0.1:7878",
            "localhost",
            "LocalHost:7878",
            "localhost.:80",
        ] {
            assert!(p.allows(Some(ok)), "{ok}");
        }
        for bad in [
            "evil.example:7878",
            "evil.example",
            "127.0.0.2:7878",
            "localhost.evil.example",
            "127.0.0.1.evil.example",
            "127.0.0.1:x",
            "127.0.0.1:",
            "",
            "[127.0.0.1]",
            "[::1]:7878",
            "localhost:7878:1",
        ] {
            assert!(!p.allows(Some(bad)), "{bad}");
        }
        assert!(!p.allows(None));
    }

    #[test]
    fn allowed_names_and_ipv6_and_all_interfaces() {
        let p = policy("::1", &["MyBox.lan"]);
        assert!(p.allows(Some("[::1]:7878")));
        assert!(p.allows(Some("[::1]")));
        assert!(!p.allows(Some("::1")));
        assert!(p.allows(Some("mybox.lan:7878")));
        assert!(!p.allows(Some("other.lan")));
        let any = policy("0.0.0.0", &[]);
        assert!(any.allows(Some("192.168.1.20:7878")));
        assert!(!any.allows(Some("evil.example:7878")));
        let mapped = policy("::ffff:127.0.0.1", &[]);
        assert!(mapped.allows(Some("127.0.0.1:7878")));
    }

    #[test]
    fn a_port_or_junk_in_an_allowed_name_is_refused() {
        for bad in ["a.lan:80", "", "a b", "a/b"] {
            assert!(HostPolicy::new("127.0.0.1".parse().unwrap(), &[bad.into()]).is_err());
        }
    }
}
