#!/usr/bin/env bash
# The generated bash completion completes as a user would type: a command from its first
# letters, an option of that command (and not another command's), a file name after an
# option that takes one. Arguments: the completion file, a scratch folder.
set -euo pipefail
source "$1"
cd "$2"
touch device_study.toml
fail=0
complete_line() {  # complete_line WORD... : COMPREPLY for the last word
  COMP_WORDS=("$@")
  COMP_CWORD=$(($# - 1))
  COMPREPLY=()
  _stengmc
  echo "${COMPREPLY[*]-}"
}
expect() {  # expect WANTED GOT WHAT
  if [[ " $2 " != *" $1 "* ]]; then echo "FAIL: $3: wanted '$1' in '$2'"; fail=1; fi
}
refuse() {
  if [[ " $2 " == *" $1 "* ]]; then echo "FAIL: $3: '$1' should not be offered: '$2'"; fail=1; fi
}
expect invert "$(complete_line stengmc inv)" "a command from its first letters"
expect export-netlist "$(complete_line stengmc exp)" "a command with a hyphen"
expect --shard "$(complete_line stengmc run --sh)" "run's --shard"
refuse --known "$(complete_line stengmc run --kn)" "invert's --known under run"
expect --known "$(complete_line stengmc invert --kn)" "invert's --known"
expect device_study.toml "$(complete_line stengmc invert --known dev)" "a file after --known"
expect --max-memory-gb "$(complete_line stengmc calibrate --max-m)" "calibrate's limits"
exit $fail
