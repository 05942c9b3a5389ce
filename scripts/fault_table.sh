#!/usr/bin/env bash
# The fault table of the README ("Rejected inputs and faults"), measured: every command on
# a full disk, kills while writing, an output that is an input, a device as output, stale
# temporaries. For each it checks the exit code, the message, what is left in the output
# folder and that every input (and an ensemble's journal) is intact, and prints one row.
#
#   bash scripts/fault_table.sh [BUILD_DIR]      (default: build; after scripts/build.sh)
#
# The full disk is a real 2 MB tmpfs when this script may mount one (root, and a kernel
# that lets it), else tests/support/fault_shim.c loaded with LD_PRELOAD (ENOSPC after the
# same byte budget; STENGMC_FAULTS_NO_MOUNT=1 forces it); the table says which. Exits 1 if any
# row is not clean.
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
stengmc=$PWD/$build/src/stengmc
shim=$PWD/$build/tests/libfault_shim.so
python=/usr/bin/python3
[[ -x $stengmc ]] || { echo "fault_table: $stengmc missing: run scripts/build.sh first" >&2; exit 1; }

work=$(mktemp -d /tmp/stengmc-faults.XXXXXX)
disk=$work/disk
mkdir -p "$disk"
mounted=0
cleanup() {
  ((mounted)) && umount "$disk" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

if [[ $(id -u) -eq 0 && -z ${STENGMC_FAULTS_NO_MOUNT:-} ]] && mount -t tmpfs -o size=2m tmpfs "$disk" 2>/dev/null; then
  mounted=1
  how="a 2 MB tmpfs"
elif [[ -f $shim ]]; then
  how="the LD_PRELOAD fault shim (no tmpfs could be mounted)"
else
  echo "fault_table: cannot mount a tmpfs and $shim is missing" >&2
  exit 1
fi

# ---------------------------------------------------------------- inputs
cat > "$work/run.toml" <<'EOF'
duration_s = 200e-6
sample_rate_hz = 20e6
[model]
kind = "model1"
[surface]
[[surface.asperity]]
stiffness_n_per_m = 155
[[surface.asperity]]
stiffness_n_per_m = 75
[spectrum]
high_resolution = false
EOF
cat > "$work/ensemble.toml" <<EOF
seed = 5
duration_s = 20e-6
sample_rate_hz = 50e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
[surface]
file = "$PWD/surfaces/lognormal_count.toml"
[ensemble]
realisations = 6
EOF
$python - "$work" <<'EOF'
import math, sys
work = sys.argv[1]
with open(f"{work}/x.csv", "w") as f:
    f.write("t,x1,x2\n")
    for j in range(2001):
        t = j * 1e-8
        f.write(f"{t!r},{1e-6 * math.sin(2e6 * t)!r},{2e-6 * math.sin(3e6 * t)!r}\n")
with open(f"{work}/v.csv", "w") as f:
    f.write("t,V\n")
    for j in range(4096):
        f.write(f"{j * 1e-7!r},{math.sin(2 * math.pi * 1e5 * j * 1e-7)!r}\n")
EOF
surface=$PWD/surfaces/pet_on_steel_gw.toml
inputs=("$work/run.toml" "$work/ensemble.toml" "$work/x.csv" "$work/v.csv" "$surface")
checksum() { sha256sum "${inputs[@]}" | sha256sum | cut -c1-16; }
before=$(checksum)

failures=0
rows=()
row() {  # fault | command | exit | message | left behind | inputs/journal | verdict
  rows+=("| $1 | \`$2\` | $3 | $4 | $5 | $6 | $7 |")
  [[ $7 == clean ]] || failures=$((failures + 1))
}
excerpt() { grep -m1 -E "stengmc: |work limit" "$1" | sed -e "s#$work/##g" -e "s#$PWD/##g" -e 's/|/\\|/g' | cut -c1-150; }
# "yes" when two ensemble files hold bitwise the same per-realisation and per-asperity data.
same_ensemble() {
  $python - "$1" "$2" <<'EOF'
import sys, h5py, numpy as np
try:
    a, b = (h5py.File(p, "r") for p in sys.argv[1:3])
    names = [f"realisations/{k}" for k in ("voltage_rms_v", "final_charge_c", "asperity_count")] + ["asperities/stiffness_n_per_m"]
    print("yes" if all(np.array_equal(a[n][()], b[n][()]) for n in names) else "NO")
except OSError:
    print("NO (no output)")
EOF
}
leftover() { local l; l=$(ls -A "$disk" | grep -v -E '^fill$' | paste -sd' '); echo "${l:-nothing}"; }

# A full disk: `free` bytes left for the output (0: full before the command starts).
fill_disk() {
  rm -rf "${disk:?}"/*
  if ((mounted)); then
    dd if=/dev/zero of="$disk/fill" bs=1k count=1000000 2>/dev/null  # fills it
    if (($1 > 0)); then truncate -s "-$1" "$disk/fill"; fi
    env_prefix=()
  else
    env_prefix=(env "LD_PRELOAD=$shim" "STENGMC_FAULT_PATH_CONTAINS=$disk/" "STENGMC_FAULT_FREE_BYTES=$1")
  fi
}

full_disk_case() {  # name, free bytes, command line with OUT
  local name=$1 free=$2 args=${3//OUT/$disk\/$1.h5}
  fill_disk "$free"
  "${env_prefix[@]}" "$stengmc" $args > "$work/log" 2>&1
  local rc=$?
  local left; left=$(leftover)
  local intact=yes; [[ $(checksum) == "$before" ]] || intact=NO
  local verdict=clean
  [[ $rc -eq 1 ]] && grep -q "No space left on device" "$work/log" && grep -q "$disk/$name.h5" "$work/log" \
    && [[ $left == nothing && $intact == yes ]] || verdict=FAILED
  local when="full from the start"; ((free > 0)) && when="fills while writing"
  local shown=${3//OUT/out.h5}; shown=${shown//$work\//}; shown=${shown//$PWD\//}
  row "full disk ($when)" "$shown" "$rc" "$(excerpt "$work/log")" "$left" "$intact" "$verdict"
}

for free in 0 8192; do
  full_disk_case run "$free" "run $work/run.toml -o OUT"
  full_disk_case circuit "$free" "circuit $work/x.csv -R 1e6 -o OUT"
  full_disk_case spectrum "$free" "spectrum $work/v.csv -o OUT"
  full_disk_case surface "$free" "surface $surface -k 20 -o OUT"
done

# The ensemble: the disk fills after its journal is written (the journal, a few kB, is
# written first and has room; the output does not); then the same command with space again
# resumes the journal to the uninterrupted result.
"$stengmc" run "$work/ensemble.toml" -j 2 -o "$work/reference.h5" > /dev/null 2>&1
if ((mounted)); then
  fill_disk 65536  # the journal (~30 kB) fits, the output (~1.3 MB) does not
  ens_env=()
else
  ens_env=(env "LD_PRELOAD=$shim" "STENGMC_FAULT_PATH_CONTAINS=$disk/" "STENGMC_FAULT_EXEMPT_CONTAINS=journal"
           "STENGMC_FAULT_FREE_BYTES=2048")
fi
"${ens_env[@]}" "$stengmc" run "$work/ensemble.toml" -j 2 -o "$disk/ensemble.h5" > "$work/log" 2>&1
rc=$?
left=$(leftover)
journal=no; [[ -f $disk/ensemble.h5.journal ]] && journal=yes
rm -f "$disk/fill"
"$stengmc" run "$work/ensemble.toml" -j 2 -o "$disk/ensemble.h5" > "$work/log2" 2>&1
resumed=$(grep -o "[0-9]* resumed" "$work/log2" || echo "0 resumed")
same=$(same_ensemble "$disk/ensemble.h5" "$work/reference.h5")
verdict=clean
[[ $rc -eq 1 && $journal == yes && $left == "ensemble.h5.journal" && $resumed == "6 resumed" && $same == yes ]] \
  && grep -q "No space left on device" "$work/log" || verdict=FAILED
row "full disk (output fails, journal fits)" "run ensemble.toml -o out.h5" "$rc" "$(excerpt "$work/log")" "$left" \
    "journal kept; rerun: $resumed, datasets equal to an uninterrupted run: $same" "$verdict"

# ---------------------------------------------------------------- kills
rm -rf "${disk:?}"/*
if [[ -f $shim ]]; then
  for sig in TERM KILL; do
    rm -f "$work/stalled"
    env "LD_PRELOAD=$shim" "STENGMC_FAULT_PATH_CONTAINS=$disk/" "STENGMC_FAULT_STALL_MARKER=$work/stalled" \
      "$stengmc" run "$work/run.toml" -o "$disk/killed.h5" > "$work/log" 2>&1 &
    pid=$!
    for _ in $(seq 600); do [[ -f $work/stalled ]] && break; sleep 0.05; done
    during=$(ls -A "$disk" | paste -sd' ')
    kill -s "$sig" "$pid"; wait "$pid"; rc=$?
    left=$(leftover)
    if [[ $sig == TERM ]]; then
      verdict=clean; [[ $left == nothing && -n $during ]] || verdict=FAILED
      row "SIGTERM while writing the output" "run run.toml -o out.h5" "$rc (killed)" "(none: killed)" "$left (while writing: $during)" "yes" "$verdict"
    else
      "$stengmc" run "$work/run.toml" -o "$disk/killed.h5" > "$work/log" 2>&1; rc2=$?
      after=$(ls -A "$disk" | paste -sd' ')
      verdict=clean; [[ $left == *.tmp* && $rc2 -eq 0 && $after == "killed.h5" ]] || verdict=FAILED
      row "SIGKILL while writing the output" "run run.toml -o out.h5, then the same again" "$rc (killed), then $rc2" \
          "(none: killed)" "after the kill: $left; after the next run: $after" "yes" "$verdict"
    fi
  done
fi
# An ensemble killed mid-run resumes to the uninterrupted result.
rm -rf "${disk:?}"/*
cp "$work/ensemble.toml" "$work/ensemble_long.toml"
sed -i 's/realisations = 6/realisations = 40/' "$work/ensemble_long.toml"
"$stengmc" run "$work/ensemble_long.toml" -j 2 -o "$work/long_reference.h5" > /dev/null 2>&1
"$stengmc" run "$work/ensemble_long.toml" -j 2 -o "$disk/long.h5" > /dev/null 2>&1 &
pid=$!
for _ in $(seq 600); do [[ -s $disk/long.h5.journal ]] && (( $(stat -c %s "$disk/long.h5.journal") > 20000 )) && break; sleep 0.02; done
kill -KILL "$pid"; wait "$pid"; rc=$?
"$stengmc" run "$work/ensemble_long.toml" -j 2 -o "$disk/long.h5" > "$work/log" 2>&1; rc2=$?
resumed=$(grep -o "[0-9]* resumed" "$work/log" || echo "0 resumed")
same=$(same_ensemble "$disk/long.h5" "$work/long_reference.h5")
verdict=clean; [[ $rc2 -eq 0 && $same == yes && $resumed != "0 resumed" ]] || verdict=FAILED
row "SIGKILL during an ensemble" "run ensemble.toml (40 realisations), then the same again" "$rc (killed), then $rc2" \
    "(none: killed)" "after the rerun: $(leftover)" "rerun: $resumed; datasets equal to an uninterrupted run: $same" "$verdict"

# ---------------------------------------------------------------- output = input, devices
cp "$work/run.toml" "$work/self.toml"
self_before=$(sha256sum < "$work/self.toml")
"$stengmc" run "$work/self.toml" -o "$work/self.toml" > "$work/log" 2>&1; rc=$?
intact=yes; [[ $(sha256sum < "$work/self.toml") == "$self_before" ]] || intact=NO
verdict=clean; [[ $rc -eq 2 && $intact == yes ]] || verdict=FAILED
row "output = input" "run s.toml -o s.toml" "$rc" "$(excerpt "$work/log")" "nothing" "$intact" "$verdict"
ln -s "$work/self.toml" "$work/link.h5"
"$stengmc" run "$work/self.toml" -o "$work/link.h5" > "$work/log" 2>&1; rc=$?
intact=yes; [[ $(sha256sum < "$work/self.toml") == "$self_before" && -L $work/link.h5 ]] || intact=NO
verdict=clean; [[ $rc -eq 2 && $intact == yes ]] || verdict=FAILED
row "output = input through a link" "run s.toml -o link.h5" "$rc" "$(excerpt "$work/log")" "nothing" "$intact" "$verdict"

if mknod "$work/null.h5" c 1 3 2>/dev/null; then
  device=$work/null.h5; kind="a character device (a copy of /dev/null's node)"
else
  mkfifo "$work/null.h5"; device=$work/null.h5; kind="a FIFO (no root: no device node)"
fi
"$stengmc" run "$work/run.toml" -o "$device" > "$work/log" 2>&1; rc=$?
still=NO; { [[ -c $device ]] || [[ -p $device ]]; } && still=yes
verdict=clean; [[ $rc -eq 2 && $still == yes ]] || verdict=FAILED
row "device as output: $kind" "run run.toml -o null.h5" "$rc" "$(excerpt "$work/log")" "nothing" "node kept: $still" "$verdict"

# ---------------------------------------------------------------- stale temporaries
rm -rf "${disk:?}"/*
sleep 0 & dead=$!; wait "$dead"  # a pid that has just ended
host=$(hostname)
touch "$disk/stale.h5.$host.$dead.tmp" "$disk/stale.h5.$host.$$.tmp" "$disk/stale.h5.another-host.$dead.tmp"
"$stengmc" run "$work/run.toml" -o "$disk/stale.h5" > "$work/log" 2>&1; rc=$?
left=$(ls -A "$disk" | sed "s/$host/HOST/g" | paste -sd' ')
verdict=clean
[[ $rc -eq 0 && ! -e $disk/stale.h5.$host.$dead.tmp && -e $disk/stale.h5.$host.$$.tmp && -e $disk/stale.h5.another-host.$dead.tmp ]] \
  || verdict=FAILED
row "stale temporaries (a dead process's, a live one's, another host's)" "run run.toml -o stale.h5" "$rc" \
    "(success)" "$left" "live and other-host temporaries kept" "$verdict"

# ---------------------------------------------------------------- the table
echo "Fault table (full disk: $how; $(date -u +%Y-%m-%d), stengmc $("$stengmc" --version | cut -d' ' -f2-))"
echo
echo "| fault | command | exit | message | left in the output folder | inputs intact | verdict |"
echo "|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
echo
if ((failures)); then echo "fault_table: $failures row(s) NOT clean"; exit 1; fi
echo "fault_table: all ${#rows[@]} rows clean"
