#!/usr/bin/env bash
# Kill during save (issue 17): SIGKILLs `facesketch` at random moments while it writes a dataset
# (synth), a face model (train) and a session (strokes simulate), many times, and checks after
# every kill that the target is byte for byte the complete old version or the complete new one,
# never torn (core/atomic_file.h, dataset/dataset.h writeDataset). A dataset is complete when
# its folder equals a reference folder file for file: manifest.json and every mesh it lists.
# Kill moments are uniform over [0.1, 1] times the writer's run time, so some land in the final
# write and rename. The run time starts as the fastest of three uninterrupted writes and shrinks
# by a quarter after every round whose writer finished before its kill: under a changing load
# (CI runs two tests at a time) the first measure can be several times too long, and the kills
# then miss the writer. The test requires that an eighth of the kills or more interrupt a live
# writer (exit status 137), so that it has tested something.
#   kill_during_save.sh FACESKETCH WORK [ROUNDS]
set -euo pipefail
facesketch=$1
work=$2
rounds=${3:-30}
rm -rf "$work"
mkdir -p "$work"
cd "$work"
RANDOM=17 # deterministic kill moments for a given machine speed

# Each writer execs facesketch, so that in a ( subshell ) the pid killed is facesketch itself.
synth() { exec "$facesketch" synth -o "$1" --identities 12 --seed "$2" --poses --pose-identities 1 --threads 1 >/dev/null; }
train() { exec "$facesketch" train "$1" -o "$2" --restarts 1 --components 1 --latent-dim 2 --cleanup-dim 4 --correlation-dim 4 >/dev/null 2>&1; }
simulate() { exec "$facesketch" strokes simulate ref-old --model ref-old.model --sample face_0011 --view "$1" -o "$2" >/dev/null 2>&1; }

# The two complete versions of each target.
(synth ref-old 1)
(synth ref-new 2)
(train ref-old ref-old.model)
(train ref-new ref-new.model)
(simulate front ref-old.json)
(simulate profile ref-new.json)

same() { # same TARGET REFERENCE: files equal, or folders equal file for file
  if [ -d "$2" ]; then diff -r -q "$1" "$2" >/dev/null 2>&1; else cmp -s "$1" "$2"; fi
}

# hammer NAME SUFFIX WRITE: `WRITE VERSION` writes version old or new of target$SUFFIX, whose
# complete versions are ref-old$SUFFIX and ref-new$SUFFIX.
hammer() {
  local name=$1 suffix=$2 write=$3 target=target$2
  rm -rf "$target"
  cp -r "ref-old$suffix" "$target"
  local current=old start end micros=0
  # The writer's run time: the fastest of three uninterrupted writes (new, old, new).
  for version in new old new; do
    start=$(date +%s%N)
    ("$write" "$version")
    end=$(date +%s%N)
    same "$target" "ref-$version$suffix" || { echo "$name: an uninterrupted write is not the $version version"; exit 1; }
    current=$version
    if [ "$micros" -eq 0 ] || [ $(((end - start) / 1000)) -lt "$micros" ]; then micros=$(((end - start) / 1000)); fi
  done
  local interrupted=0 kept=0 replaced=0 first=$micros
  for ((i = 0; i < rounds; i++)); do
    local next=old
    [ "$current" = old ] && next=new
    local delay=$((micros / 10 + RANDOM * micros * 9 / 10 / 32768))
    ("$write" "$next") &
    local pid=$!
    sleep "$(printf '%d.%06d' $((delay / 1000000)) $((delay % 1000000)))"
    kill -KILL "$pid" 2>/dev/null || true
    local status=0
    wait "$pid" 2>/dev/null || status=$?
    if [ "$status" -eq 137 ]; then
      interrupted=$((interrupted + 1))
    elif [ "$micros" -gt 2000 ]; then
      micros=$((micros * 3 / 4))
    fi
    if same "$target" "ref-$next$suffix"; then
      current=$next
      replaced=$((replaced + 1))
    elif same "$target" "ref-$current$suffix"; then
      kept=$((kept + 1))
    else
      echo "$name: after a kill at ${delay} us (round $i) $target is neither the old nor the new version (torn)"
      ls -la "$target" || true
      exit 1
    fi
    # A kill may leave the writer's temporary beside the target; it is never read.
    rm -rf ".$(basename "$target").tmp-"*
  done
  echo "$name: $rounds kills, $interrupted while writing (write time $first us, at the end $micros us); the target stayed whole ($kept old, $replaced new)"
  if [ "$interrupted" -lt $((rounds / 8)) ]; then
    echo "$name: too few kills interrupted the writer"
    exit 1
  fi
}

write_dataset() { synth target "$([ "$1" = old ] && echo 1 || echo 2)"; }
write_model() { train "ref-$1" target.model; }
write_session() { simulate "$([ "$1" = old ] && echo front || echo profile)" target.json; }

hammer dataset "" write_dataset
hammer model .model write_model
hammer session .json write_session
