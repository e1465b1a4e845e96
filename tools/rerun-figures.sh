#!/usr/bin/env bash
# Re-runs every figure the docs measure on the built-in synthetic set, for a new generator
# version (issue 16: "every figure ... measured on the synthetic set is re-run on the new set"):
#
#   tools/rerun-figures.sh OUTDIR [REFERENCE]
#
# OUTDIR receives the data (OUTDIR/high: 250 high faces, seed 1, and its model), one text file per
# command (its output; the command is the file's first line) and SUMMARY.txt, the lines the docs
# quote. REFERENCE is an ICT import (`facesketch import ict-facekit ... -o REF`) for `eval
# realism`, also run on seeds 2 and 3; without it those are skipped. FACESKETCH names the binary
# (default build/app/facesketch); do not rebuild it while this runs. About 10 minutes on this
# 2-core machine. Each figure's doc:
#   docs/face-model.md   eval observe (joint, thesis, off; 15% and 2% of the vertices, each region)
#   docs/sketching.md    eval strokes (1 px; --extreme 1.5; per stroke; the true-curve oracle and the
#                        first reading at 0 px)
#   docs/contours.md     eval contours (and --curve from the front)
#   docs/posing.md       eval poses (low and high, 40 identities with poses)
#   docs/realism.md      eval realism (seed 1, 2, 3)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# -ge 1 ] || { echo "usage: tools/rerun-figures.sh OUTDIR [REFERENCE]" >&2; exit 2; }
out=$(realpath -m "$1")
ref=${2:-}
F=${FACESKETCH:-$root/build/app/facesketch}
# A binary copied out of the build finds its assets (the pose recipes) here.
export FACESKETCH_ASSETS=${FACESKETCH_ASSETS:-$root/assets}
[ -x "$F" ] || { echo "rerun-figures: no binary at $F (build first, or set FACESKETCH)" >&2; exit 1; }
[ -z "$ref" ] || [ -f "$ref/manifest.json" ] || { echo "rerun-figures: $ref is not a dataset (no manifest.json)" >&2; exit 1; }
mkdir -p "$out"
H=$out/high

# run NAME COMMAND...: the command's output in $out/NAME.txt, headed by the command, and its time.
run() {
    local name=$1 start
    shift
    start=$(date +%s)
    { echo "\$ $*"; "$@"; } > "$out/$name.txt" 2>&1 || { echo "rerun-figures: $name failed, see $out/$name.txt" >&2; exit 1; }
    echo "$name: $(($(date +%s) - start)) s"
}

rm -rf "$H"
run synth "$F" synth --resolution high -o "$H"
run train "$F" train "$H" -o "$H.model"
run strokes "$F" eval strokes "$H.model" "$H" --mappers nearest,hmm --noise 1 --json "$out/strokes.json" --per-stroke "$out/per-stroke.json"
run extreme "$F" eval strokes "$H.model" "$H" --mappers nearest,hmm --noise 1 --extreme 1.5 --json "$out/extreme.json"
run oracle "$F" eval strokes "$H.model" "$H" --mappers hmm --noise 0 --refine 0 --oracle true-curve
run first-reading "$F" eval strokes "$H.model" "$H" --mappers hmm --noise 0 --refine 0
run contours "$F" eval contours "$H.model" "$H" -o "$out/contour-renders"
run curve "$F" eval contours "$H.model" "$H" --curve --views front
for c in joint thesis off; do
    run "observe-$c-15" "$F" eval observe "$H.model" "$H" --fraction 0.15 --correlation $c
    run "observe-$c-2" "$F" eval observe "$H.model" "$H" --fraction 0.02 --correlation $c
    for r in nose mouth_chin eyes_brows; do
        run "observe-$c-$r" "$F" eval observe "$H.model" "$H" --region $r --correlation $c
    done
done
for res in low high; do
    rm -rf "$out/posed-$res"
    run "posed-$res" "$F" synth -o "$out/posed-$res" --identities 40 --poses --resolution $res
    run "train-poses-$res" "$F" train-poses "$out/posed-$res" -o "$out/$res.poses"
    run "poses-$res" "$F" eval poses "$out/$res.poses" "$out/posed-$res" --json "$out/poses-$res.json"
done
if [ -n "$ref" ]; then
    run realism "$F" eval realism "$H" --reference "$ref" --json "$out/realism.json"
    for s in 2 3; do
        rm -rf "$out/seed$s"
        run "synth-seed$s" "$F" synth --resolution high --seed $s -o "$out/seed$s"
        run "realism-seed$s" "$F" eval realism "$out/seed$s" --reference "$ref"
        rm -rf "$out/seed$s"
    done
fi

# The lines the docs quote: each evaluation's table rows.
{
    for f in strokes extreme oracle first-reading; do
        echo "== $f"
        sed -n '/^view  *mapper/,/^#\|^wrote/p' "$out/$f.txt" | grep -v '^wrote'
    done
    for f in contours curve; do
        echo "== $f"
        grep -v '^# face\|^\$' "$out/$f.txt" | tail -n 12
    done
    for f in "$out"/observe-*.txt; do
        echo "== $(basename "$f" .txt): $(grep -m1 '^reconstruction' "$f" | tr -s ' ') | $(grep -m1 'ratio' "$f")"
    done
    for res in low high; do
        echo "== poses-$res"
        grep -v '^\$' "$out/poses-$res.txt" | tail -n 12
    done
    for f in realism realism-seed2 realism-seed3; do
        [ -f "$out/$f.txt" ] || continue
        echo "== $f"
        grep -v '^\$' "$out/$f.txt"
    done
} > "$out/SUMMARY.txt"
echo "rerun-figures: wrote $out/SUMMARY.txt"
