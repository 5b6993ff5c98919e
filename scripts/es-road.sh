#!/usr/bin/env bash
# ES-HyperNEAT on the road, second round (issue 22 §4; docs/results.md,
# "ES-HyperNEAT with multi-resolution training" and "ES-HyperNEAT on three
# maps at once"). Per seed, evolves one run, replays its champion and prints
# one Markdown row.
#
#   scripts/es-road.sh KIND [SEED ...]          # default seeds 1-5
#
# KIND:
#   es         ES-HyperNEAT at the paper's 3x5 sensors  -> RUNS/es-seed-N
#   es-multires ES-HyperNEAT trained at 3x5 and 3x6 sensors -> RUNS/esmr-seed-N
#   dense      the paper's fixed 3x3 sheet               -> RUNS/dense-seed-N
#   es-leo     ES-HyperNEAT with LEO and its locality seed -> RUNS/esleo-seed-N
#              (config RUNS/es-leo.toml: [substrate.es] leo = true, leo_seed = true)
#   es-leo-noseed ES-HyperNEAT with LEO, minimal CPPNs   -> RUNS/esleo-noseed-seed-N
#              (config RUNS/es-leo-noseed.toml: [substrate.es] leo = true)
#     replayed at 3x5, 3x6 and 32x96 sensors: fitness = share of the 3x5
#     replay's (robot-steps on road)
#   maps-es    ES-HyperNEAT on roads, oval and figure8 at once -> RUNS/maps-es-seed-N
#   maps-dense the fixed sheet on the same three maps          -> RUNS/maps-dense-seed-N
#     replayed on the three training maps and on town, obstacles, traffic
#
# Environment: GENERATIONS (default 400, the paper's), RUNS (default runs).
# ES runs' "hidden" and "links" are the champion's, as figures/network.svg states them.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p vivae
vivae=${CARGO_TARGET_DIR:-target}/release/vivae
kind=${1:?usage: scripts/es-road.sh es|es-multires|dense|es-leo|es-leo-noseed|maps-es|maps-dense [SEED ...]}
shift
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
generations=${GENERATIONS:-400}
runs=$(realpath -m "${RUNS:-runs}") # absolute: a multi-map run given a relative --out fails writing its report
field() { sed -n "s/.*$1=\([^ ]*\).*/\1/p"; }
cell() { # "fitness (on road)" of a replay line; with a reference, also the share of it
  local f o
  f=$(echo "$1" | field fitness)
  o=$(echo "$1" | field on_road)
  if [ -n "${2:-}" ]; then
    awk -v f="$f" -v o="$o" -v r="$2" 'BEGIN{printf "%.3f = %.0f%% (%.1f%%)", f, 100*f/r, 100*o}'
  else
    awk -v f="$f" -v o="$o" 'BEGIN{printf "%.3f (%.1f%%)", f, 100*o}'
  fi
}
hidden() {
  grep -o '[0-9]* hidden neurons found, [0-9]* links' "$1/figures/network.svg" 2>/dev/null |
    sed 's/ hidden neurons found, / | /; s/ links//' || echo "– | –"
}

case $kind in
  es) flags=(--substrate es-hyperneat); name=es ;;
  es-multires) flags=(--substrate es-hyperneat --train-sensors 3x5,3x6); name=esmr ;;
  dense) flags=(); name=dense ;;
  es-leo | es-leo-noseed)
    mkdir -p "$runs"
    leo_config=$runs/$kind.toml
    seed_key=$([ "$kind" = es-leo ] && echo "leo_seed = true" || true)
    printf '[substrate]\nkind = "es-hyperneat"\n\n[substrate.es]\nleo = true\n%s\n' "$seed_key" > "$leo_config"
    flags=(--config "$leo_config")
    name=${kind/es-leo/esleo}
    ;;
  maps-es) flags=(--substrate es-hyperneat); name=maps-es ;;
  maps-dense) flags=(); name=maps-dense ;;
  *) echo "unknown kind $kind" >&2; exit 2 ;;
esac
maps=(roads oval figure8 town obstacles traffic)
if [[ $kind == maps-* ]]; then
  flags+=(--scenario roads --scenario oval --scenario figure8)
  echo "| seed | training fitness (gen) | hidden | links | roads* | oval* | figure8* | town | obstacles | traffic |"
else
  echo "| seed | training fitness (gen) | 3x5 sensors (on road) | hidden | links | 3x6 sensors (on road) | 32x96 sensors (on road) |"
fi
for seed in "${seeds[@]}"; do
  dir=$runs/$name-seed-$seed
  $vivae evolve -q "${flags[@]}" --generations "$generations" --seed "$seed" --out "$dir" --force > /dev/null
  best=$(sed -n 's/.*"fitness": \([^,]*\),*/\1/p' "$dir/champion.json" | head -1)
  gen=$(sed -n 's/.*"generation": \([^,]*\),*/\1/p' "$dir/champion.json" | head -1)
  row=$(printf '| %s | %.3f (%s) |' "$seed" "$best" "$gen")
  if [[ $kind == maps-* ]]; then
    row+=" $(hidden "$dir") |"
    for m in "${maps[@]}"; do
      row+=" $(cell "$($vivae replay "$dir" --scenario "$m" -o "$dir/replay-maps" 2>/dev/null)") |"
    done
  else
    own=$($vivae replay "$dir" --sensors 3x5 -o "$dir/replay" 2>/dev/null)
    ref=$(echo "$own" | field fitness)
    row+=" $(cell "$own") | $(hidden "$dir") |"
    for s in 3x6 32x96; do
      row+=" $(cell "$($vivae replay "$dir" --sensors "$s" -o "$dir/replay" 2>/dev/null)" "$ref") |"
    done
  fi
  echo "$row"
done
