#!/usr/bin/env bash
# The former name of scripts/update-reference.sh, which regenerates every
# reference page (the config keys' and the command line's).
set -euo pipefail
exec "$(dirname "$0")/update-reference.sh" "$@"
