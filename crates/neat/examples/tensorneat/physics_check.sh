#!/usr/bin/env bash
# Checks bench.py's DoublePoleMarkov against pole.rs's own physics code:
# copies pole.rs's constants, derivatives, rk4, step, failed and observe
# verbatim (sin_cos from std instead of crate::math) into a scratch crate, runs
# three fixed linear controllers from the Markov start state in it and in
# bench.py's environment (JAX float64, then float32), and prints the steps
# balanced, the state after 3 steps and the final state of each.
#   bash physics_check.sh [PYTHON]      (default /work/tnvenv/bin/python)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
py=${1:-/work/tnvenv/bin/python}
P=$here/../../src/benchmarks/pole.rs
tmp=$(mktemp -d)
mkdir -p "$tmp/src"
printf '[package]\nname = "polecheck"\nversion = "0.1.0"\nedition = "2021"\n[workspace]\n' > "$tmp/Cargo.toml"
s=$(grep -n '^const GRAVITY' "$P" | cut -d: -f1)
e=$(grep -n '^/// Balances from' "$P" | cut -d: -f1)
{
  echo '#![allow(dead_code)]'
  echo 'fn sin_cos(x: f64) -> (f64, f64) { x.sin_cos() }'
  sed -n "${s},$((e - 1))p" "$P"
  cat <<'RS'
fn main() {
    // Fixed linear controllers: out = 1/(1+e^(-4.9 w.obs)), as physics_check.py.
    let ws: [[f64; 7]; 3] = [
        [0.5, 0.8, 3.0, 0.6, -2.0, 0.1, 0.0],
        [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        [1.2, 1.5, 6.0, 1.1, -4.0, -0.3, -0.05],
    ];
    for w in ws {
        let mut s: State = [0.0, 0.0, 0.07, 0.0, 0.0, 0.0];
        let mut obs = [0.0; 7];
        let mut t = 0u32;
        let mut at3 = s;
        while t < 100_000 {
            observe(&s, true, &mut obs);
            let z: f64 = w.iter().zip(obs.iter()).map(|(a, b)| a * b).sum();
            step(1.0 / (1.0 + (-4.9 * z).exp()), &mut s);
            if failed(&s) {
                break;
            }
            t += 1;
            if t == 3 {
                at3 = s;
            }
        }
        println!("steps={t} state3={at3:?} final={s:?}");
    }
}
RS
} > "$tmp/src/main.rs"
echo "== pole.rs (Rust, f64)"
cargo run -q --release --manifest-path "$tmp/Cargo.toml"
echo "== bench.py, JAX float64"
"$py" "$here/physics_check.py" x64
echo "== bench.py, JAX float32 (as bench.py runs)"
"$py" "$here/physics_check.py" f32
rm -rf "$tmp"
