#!/usr/bin/env bash
# The fault table of docs/faults.md ("The fault table"), measured: every command on a full
# disk, kills while writing, an output that is an input, a device as output, stale
# temporaries, and for calibrate, invert, merge, export-netlist and plot also a FIFO or a
# device as input. For each it checks the exit code, the message, what is left in the
# output folder and that every input (and a journal) is intact, and prints one row.
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
# calibrate, invert, merge, export-netlist and plot: the inverse tests' known device with its
# quick prior (a bank of 50 records in seconds), a bank and a record of it, two shards of
# the ensemble, a run file to plot.
{ echo "duration_s = 20e-6"; cat tests/support/known_device.toml; echo "[inverse]"
  cat tests/support/known_device_quick_prior.toml; } > "$work/device.toml"
"$stengmc" calibrate "$work/device.toml" -j 2 -o "$work/bank.h5" > /dev/null 2>&1 || { echo "fault_table: calibrate failed" >&2; exit 1; }
"$stengmc" run "$work/device.toml" -o "$work/rec.h5" > /dev/null 2>&1 || { echo "fault_table: the record's run failed" >&2; exit 1; }
for i in 0 1; do
  "$stengmc" run "$work/ensemble.toml" --shard $i/2 -j 2 -o "$work/s$i.shard" > /dev/null 2>&1 \
    || { echo "fault_table: shard $i failed" >&2; exit 1; }
done
"$stengmc" run "$work/run.toml" -o "$work/r.h5" > /dev/null 2>&1 || { echo "fault_table: the run to plot failed" >&2; exit 1; }
inputs=("$work/run.toml" "$work/ensemble.toml" "$work/x.csv" "$work/v.csv" "$surface" "$work/device.toml" "$work/bank.h5"
        "$work/rec.h5" "$work/s0.shard" "$work/s1.shard" "$work/r.h5")
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

# A full disk: `free` bytes left for the output (0: full before the command starts); a
# second argument is a file put on the disk first (plot's input, beside which it writes).
fill_disk() {
  rm -rf "${disk:?}"/*
  if (($# > 1)); then cp "$2" "$disk/"; fi
  if ((mounted)); then
    dd if=/dev/zero of="$disk/fill" bs=1k count=1000000 2>/dev/null  # fills it
    if (($1 > 0)); then truncate -s "-$1" "$disk/fill"; fi
    env_prefix=()
  else
    env_prefix=(env "LD_PRELOAD=$shim" "STENGMC_FAULT_PATH_CONTAINS=$disk/" "STENGMC_FAULT_FREE_BYTES=$1")
  fi
}

full_disk_case() {  # name, free bytes, command line with OUT[, the output's extension]
  local name=$1 free=$2 extension=${4:-.h5}
  local args=${3//OUT/$disk\/$1$extension}
  fill_disk "$free"
  "${env_prefix[@]}" "$stengmc" $args > "$work/log" 2>&1
  local rc=$?
  local left; left=$(leftover)
  local intact=yes; [[ $(checksum) == "$before" ]] || intact=NO
  local verdict=clean
  [[ $rc -eq 1 ]] && grep -q "No space left on device" "$work/log" && grep -q "$disk/$name$extension" "$work/log" \
    && [[ $left == nothing && $intact == yes ]] || verdict=FAILED
  local when="full from the start"; ((free > 0)) && when="fills while writing"
  local shown=${3//OUT/out$extension}; shown=${shown//$work\//}; shown=${shown//$PWD\//}
  row "full disk ($when)" "$shown" "$rc" "$(excerpt "$work/log")" "$left" "$intact" "$verdict"
}

for free in 0 8192; do
  full_disk_case run "$free" "run $work/run.toml -o OUT"
  full_disk_case circuit "$free" "circuit $work/x.csv -R 1e6 -o OUT"
  full_disk_case spectrum "$free" "spectrum $work/v.csv -o OUT"
  full_disk_case surface "$free" "surface $surface -k 20 -o OUT"
  # calibrate's journal comes first: a disk that fills mid-run is the journal's (below).
  ((free == 0)) && full_disk_case calibrate "$free" "calibrate $work/device.toml -j 2 -o OUT"
  full_disk_case invert "$free" "invert $work/rec.h5 --known $work/device.toml --bank $work/bank.h5 -o OUT"
  full_disk_case merge "$free" "merge $work/s0.shard $work/s1.shard -o OUT"
  full_disk_case export-netlist "$free" "export-netlist $work/run.toml -o OUT" .cir
done
# plot writes its figures beside the file it plots, on the full disk with it.
for free in 0 8192; do
  fill_disk "$free" "$work/r.h5"
  "${env_prefix[@]}" "$stengmc" plot "$disk/r.h5" > "$work/log" 2>&1; rc=$?
  left=$(leftover); intact=yes; [[ $(checksum) == "$before" ]] || intact=NO
  verdict=clean
  [[ $rc -eq 1 && $left == r.h5 && $intact == yes ]] && grep -q "r.png: cannot write the figure: No space left on device" "$work/log" \
    || verdict=FAILED
  when="full from the start"; ((free > 0)) && when="fills while writing"
  row "full disk ($when)" "plot r.h5 (on the disk)" "$rc" "$(grep -m1 "cannot write the figure" "$work/log" | sed -e "s#$work/##g")" \
      "$left" "$intact" "$verdict"
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

# The same for calibrate: the disk fills while records are journalled (8 kB left: the
# journal keeps the whole records it holds), or its journal (~100 kB) fits and the bank
# (~1.7 MB) does not; each time the same command with space again resumes the journal.
fill_disk 8192
"${env_prefix[@]}" "$stengmc" calibrate "$work/device.toml" -j 2 -o "$disk/bank.h5" > "$work/log" 2>&1
rc=$?
left=$(leftover)
rm -f "$disk/fill"
"$stengmc" calibrate "$work/device.toml" -j 2 -o "$disk/bank.h5" > "$work/log2" 2>&1; rc2=$?
resumed=$(grep -o "[0-9]* resumed" "$work/log2" || echo "0 resumed")
verdict=clean
[[ $rc -eq 1 && $left == "bank.h5.journal" && $rc2 -eq 0 && $resumed != "0 resumed" && $(leftover) == bank.h5 ]] \
  && grep -q "No space left on device" "$work/log" || verdict=FAILED
row "full disk (fills while the records are journalled)" "calibrate device.toml -o bank.h5" "$rc" "$(excerpt "$work/log")" \
    "$left" "journal kept; rerun: exit $rc2, $resumed, only the bank left" "$verdict"

if ((mounted)); then
  fill_disk 400000
  cal_env=()
else
  cal_env=(env "LD_PRELOAD=$shim" "STENGMC_FAULT_PATH_CONTAINS=$disk/" "STENGMC_FAULT_EXEMPT_CONTAINS=journal"
           "STENGMC_FAULT_FREE_BYTES=2048")
fi
"${cal_env[@]}" "$stengmc" calibrate "$work/device.toml" -j 2 -o "$disk/bank.h5" > "$work/log" 2>&1
rc=$?
left=$(leftover)
rm -f "$disk/fill"
"$stengmc" calibrate "$work/device.toml" -j 2 -o "$disk/bank.h5" > "$work/log2" 2>&1; rc2=$?
resumed=$(grep -o "[0-9]* resumed" "$work/log2" || echo "0 resumed")
verdict=clean
[[ $rc -eq 1 && $left == "bank.h5.journal" && $rc2 -eq 0 && $resumed == "50 resumed" && $(leftover) == bank.h5 ]] \
  && grep -q "No space left on device" "$work/log" || verdict=FAILED
row "full disk (bank fails, journal fits)" "calibrate device.toml -o bank.h5" "$rc" "$(excerpt "$work/log")" "$left" \
    "journal kept; rerun: exit $rc2, $resumed, only the bank left" "$verdict"

# ---------------------------------------------------------------- kills
# The shim stalls the first write of the output (a journal is written as usual), and the
# command is killed there: SIGTERM must remove the temporary (a journal stays: it is what
# the next run resumes), after SIGKILL the next run of the same command must remove it.
kill_case() {  # name, command line with OUT, the output's extension, what SIGTERM leaves ("": nothing)
  local name=$1 extension=$3 kept=${4:-nothing}
  local args=${2//OUT/$disk\/$name$extension}
  local shown=${2//OUT/out$extension}; shown=${shown//$work\//}; shown=${shown//$PWD\//}
  local sig pid rc rc2 during left after verdict
  for sig in TERM KILL; do
    rm -rf "${disk:?}"/* "$work/stalled"
    env "LD_PRELOAD=$shim" "STENGMC_FAULT_PATH_CONTAINS=$disk/" "STENGMC_FAULT_EXEMPT_CONTAINS=journal" \
      "STENGMC_FAULT_STALL_MARKER=$work/stalled" "$stengmc" $args > "$work/log" 2>&1 &
    pid=$!
    for _ in $(seq 1200); do [[ -f $work/stalled ]] && break; sleep 0.05; done
    during=$(ls -A "$disk" | paste -sd' ')
    kill -s "$sig" "$pid"; wait "$pid"; rc=$?
    left=$(leftover)
    if [[ $sig == TERM ]]; then
      verdict=clean; [[ $left == "$kept" && $during == *.tmp* ]] || verdict=FAILED
      row "SIGTERM while writing the output" "$shown" "$rc (killed)" "(none: killed)" "$left (while writing: $during)" "yes" "$verdict"
    else
      "$stengmc" $args > "$work/log" 2>&1; rc2=$?
      after=$(ls -A "$disk" | paste -sd' ')
      verdict=clean; [[ $left == *.tmp* && $rc2 -eq 0 && $after == "$name$extension" ]] || verdict=FAILED
      row "SIGKILL while writing the output" "$shown, then the same again" "$rc (killed), then $rc2" \
          "(none: killed)" "after the kill: $left; after the next run: $after" "yes" "$verdict"
    fi
  done
}
if [[ -f $shim ]]; then
  kill_case killed "run $work/run.toml -o OUT" .h5
  kill_case bank "calibrate $work/device.toml -j 2 -o OUT" .h5 bank.h5.journal
  kill_case inverse "invert $work/rec.h5 --known $work/device.toml --bank $work/bank.h5 -o OUT" .h5
  kill_case merged "merge $work/s0.shard $work/s1.shard -o OUT" .h5
  kill_case netlist "export-netlist $work/run.toml -o OUT" .cir
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

# The same for calibrate, invert, merge, export-netlist and plot: an output that is one of
# the command's inputs, an output that is a device, an input that is a FIFO or a device.
# `timeout` turns a hang (a FIFO read for ever) into exit 124, a failure.
refusal_case() {  # fault, command shown, the file that must stay as it was, arguments...
  local fault=$1 shown=$2 kept=$3; shift 3
  local kind_before; kind_before=$(stat -c %F "$kept"); local sum_before=""
  [[ -f $kept ]] && sum_before=$(sha256sum < "$kept")
  timeout 60 "$stengmc" "$@" > "$work/log" 2>&1; local rc=$?
  local intact=yes
  [[ $(stat -c %F "$kept") == "$kind_before" ]] || intact=NO
  [[ -z $sum_before || $(sha256sum < "$kept") == "$sum_before" ]] || intact=NO
  local verdict=clean; [[ $rc -eq 2 && $intact == yes ]] && grep -q "$(basename "$kept")" "$work/log" || verdict=FAILED
  row "$fault" "$shown" "$rc" "$(excerpt "$work/log")" "nothing" "$(basename "$kept") kept as it was: $intact" "$verdict"
}
cp "$work/device.toml" "$work/dev_self.toml"
refusal_case "output = input" "calibrate d.toml -o d.toml" "$work/dev_self.toml" calibrate "$work/dev_self.toml" -o "$work/dev_self.toml"
refusal_case "output = input" "invert rec.h5 --known d.toml -o rec.h5" "$work/rec.h5" \
  invert "$work/rec.h5" --known "$work/device.toml" -o "$work/rec.h5"
refusal_case "output = input" "invert rec.h5 --known d.toml --bank bank.h5 -o bank.h5" "$work/bank.h5" \
  invert "$work/rec.h5" --known "$work/device.toml" --bank "$work/bank.h5" -o "$work/bank.h5"
refusal_case "output = input" "merge s0 s1 -o s0" "$work/s0.shard" merge "$work/s0.shard" "$work/s1.shard" -o "$work/s0.shard"
refusal_case "output = input" "export-netlist run.toml -o run.toml" "$work/run.toml" \
  export-netlist "$work/run.toml" -o "$work/run.toml"
cp "$work/r.h5" "$work/f.png"  # a run file named like its own figure
refusal_case "output = input" "plot f.png (a run file)" "$work/f.png" plot "$work/f.png"

mkdir -p "$work/dev"
if mknod "$work/dev/null.h5" c 1 3 2>/dev/null && mknod "$work/dev/null.cir" c 1 3 && mknod "$work/dev/r.png" c 1 3; then
  kind="a character device"
else
  mkfifo "$work/dev/null.h5" "$work/dev/null.cir" "$work/dev/r.png"; kind="a FIFO (no root: no device node)"
fi
cp "$work/r.h5" "$work/dev/r.h5"
refusal_case "device as output: $kind" "calibrate d.toml -o null.h5" "$work/dev/null.h5" calibrate "$work/device.toml" -o "$work/dev/null.h5"
refusal_case "device as output: $kind" "invert rec.h5 --known d.toml -o null.h5" "$work/dev/null.h5" \
  invert "$work/rec.h5" --known "$work/device.toml" -o "$work/dev/null.h5"
refusal_case "device as output: $kind" "merge s0 s1 -o null.h5" "$work/dev/null.h5" merge "$work/s0.shard" "$work/s1.shard" -o "$work/dev/null.h5"
refusal_case "device as output: $kind" "export-netlist run.toml -o null.cir" "$work/dev/null.cir" \
  export-netlist "$work/run.toml" -o "$work/dev/null.cir"
refusal_case "device as a figure: $kind at r.png" "plot r.h5" "$work/dev/r.png" plot "$work/dev/r.h5"

mkfifo "$work/fifo.toml" "$work/fifo.h5" "$work/fifo.csv" "$work/fifo.shard"
refusal_case "FIFO as input" "calibrate fifo.toml" "$work/fifo.toml" calibrate "$work/fifo.toml" -o "$work/fifo_bank.h5"
refusal_case "FIFO as input" "invert fifo.csv --known d.toml" "$work/fifo.csv" invert "$work/fifo.csv" --known "$work/device.toml" -o "$work/fifo_inv.h5"
refusal_case "FIFO as input" "invert rec.h5 --known d.toml --bank fifo.h5" "$work/fifo.h5" \
  invert "$work/rec.h5" --known "$work/device.toml" --bank "$work/fifo.h5" -o "$work/fifo_inv.h5"
refusal_case "FIFO as input" "merge s0 fifo.shard" "$work/fifo.shard" merge "$work/s0.shard" "$work/fifo.shard" -o "$work/fifo_merged.h5"
refusal_case "FIFO as input" "export-netlist fifo.toml" "$work/fifo.toml" export-netlist "$work/fifo.toml" -o "$work/fifo.cir"
refusal_case "FIFO as input" "plot fifo.h5" "$work/fifo.h5" plot "$work/fifo.h5"
refusal_case "device as input" "merge s0 /dev/zero" /dev/zero merge "$work/s0.shard" /dev/zero -o "$work/zero_merged.h5"

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
