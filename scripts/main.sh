#!/usr/bin/env bash
# The main job: regenerates every figure and table under figures/, revdist and the
# real baselines (FCL, libccd, CGAL) and peers (coal, parry3d) measured in the same run.
#
#   bash scripts/main.sh           # default scale: each step sized to what its figure needs;
#                                  # about 10 minutes on a fresh 2-core machine, build included
#   bash scripts/main.sh --paper   # paper scale (50,000 motion frames, 1,000 poses per pair, ...): hours
#
# Spread over a job array (README, "Spreading the paper run over a job array"): job I of N runs
#   bash scripts/main.sh --paper --shard I/N   # only the long steps, shard I of N: figures/shards/I-of-N/
# and when all N are done,
#   bash scripts/main.sh --paper --merge N     # the short steps, and the long ones merged from the shards
#
# Every CSV starts with '# key: value' provenance lines (machine, git commit, parameters).
# Timing steps run one query at a time; steps that only check or sample use all cores.
set -euo pipefail
cd "$(dirname "$0")/.."

paper=()
shard=""  # I/N: run only the long steps' shard I of N
merge=""  # N: merge the long steps from N shards
while [ $# -gt 0 ]; do
    case "$1" in
        --paper) paper=(--paper) ;;
        --shard|--merge)
            [ $# -ge 2 ] || { echo "error: $1 needs a value (try --help)" >&2; exit 2; }
            if [ "$1" = --shard ]; then shard=$2; else merge=$2; fi
            shift ;;
        -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
        *) echo "error: unknown argument '$1' (try --help)" >&2; exit 2 ;;
    esac
    shift
done
if [ -n "$shard" ] && [ -n "$merge" ]; then
    echo "error: give --shard I/N (one job) or --merge N (after all jobs), not both" >&2; exit 2
fi
if [ -n "$shard" ] && ! { [[ $shard =~ ^([0-9]+)/([0-9]+)$ ]] && (( 10#${BASH_REMATCH[1]} < 10#${BASH_REMATCH[2]} )); }; then
    echo "error: --shard '$shard': need I/N with whole numbers 0 <= I < N" >&2; exit 2
fi
if [ -n "$merge" ] && ! [[ $merge =~ ^[1-9][0-9]*$ ]]; then
    echo "error: --merge '$merge': need the number of shards N (a positive whole number)" >&2; exit 2
fi

out=figures
bin=${CARGO_TARGET_DIR:-target}/release
shards="$out/shards"  # shard I of N writes its raw rows to $shards/I-of-N/
if [ -n "$shard" ]; then
    here="$shards/${shard%/*}-of-${shard#*/}"
else
    here=$out
fi
mkdir -p "$here"
timing="$here/main_timing.txt"
echo "# scripts/main.sh ${paper[*]:-} ${shard:+--shard $shard}${merge:+--merge $merge} on $(date -u +%Y-%m-%dT%H:%M:%SZ), commit $(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)" > "$timing"

step() {  # step NAME COMMAND...: run, time, record (the time printed as each step ends)
    local name=$1; shift
    echo "== $name (at $SECONDS s)" >&2
    local t0=$SECONDS
    "$@"
    echo "$name $((SECONDS - t0)) s" | tee -a "$timing" >&2
}

step deps  scripts/deps.sh                           # Debian packages, coal (first run: minutes)
step build cargo build --release --workspace

short() {  # short NAME COMMAND...: a step --shard does not split: left to the merge job
    [ -n "$shard" ] || step "$@"
}

long() {  # long NAME SUBDIR COMMAND...: a step --shard splits; its --out is $out[/SUBDIR]
    local name=$1 sub=${2:+/$2}; shift 2
    if [ -n "$shard" ]; then
        step "$name" "$@" --out "$here$sub" --shard "$shard"
    elif [ -n "$merge" ]; then
        local dirs=() i
        for ((i = 0; i < merge; i++)); do dirs+=("$shards/$i-of-$merge$sub"); done
        step "$name" "$@" --out "$out$sub" --merge "$(IFS=,; echo "${dirs[*]}")"
    else
        step "$name" "$@" --out "$out$sub"
    fi
}

# The default run sizes each step to what its figure needs (rows, slopes, medians and the
# pass/fail columns all present; fewer samples per cell), so that the whole job, build
# included, takes about 10 minutes on a fresh 2-core machine; --paper keeps the full sizes.
# The OpenCASCADE sweep keeps all 45 pairs (exact, freeform and M_t frames, every pair kind)
# and both eps, with 20 poses each (two blocks: every pose kind) instead of 200.
if [ ${#paper[@]} -eq 0 ]; then
    fcl_poses=(--poses 40 --poses-1e-5 20); query_poses=(--poses 100); cross=(--poses 100); occt=(--occt-poses 20)
    toi_motions=(--motions 3); tails_poses=(--poses 1000); peers_poses=(--poses 20 --parry-poses 4)
    motion_frames=(--frames 60 --frames-1e-5 30); deforming_frames=(--frames 20 --frames-1e-5 4)
    pareto_poses=(--poses 60); bvh_frames=(--morph-frames 10); stability_seeds=(--seeds 3)
else
    fcl_poses=(--paper); query_poses=(--poses 1000); cross=(--poses 1000); occt=(--occt-poses 400)
    toi_motions=(--motions 30); tails_poses=(--poses 2000); peers_poses=(--paper)
    motion_frames=(--paper); deforming_frames=(--paper); pareto_poses=(--paper); bvh_frames=(--paper)
    stability_seeds=(--paper)
fi

short profiles     $bin/revdist figures --out "$out"                          # model profiles, M_t frames
short convergence  $bin/convergence --out "$out" "${paper[@]}"                 # biarcs n^-3 vs chords n^-2
short bvh_tables   $bin/bvh_tables --out "$out" "${bvh_frames[@]}"                  # Tables 1-2, Figure 9
short query_times  $bin/accuracy_time --out "$out" "${query_poses[@]}"         # where a query spends its time
short tails        $bin/tails --out "$out" "${tails_poses[@]}"                                    # tail of single-query times: 1,000 seeded queries (2,000 with --paper), cold
long fcl_bench   "" $bin/fcl_bench "${fcl_poses[@]}"                           # speed ratios vs FCL on close poses
long peers       "" $bin/peers "${peers_poses[@]}"                                 # FCL, coal, parry3d in one run; convex solids vs exact GJK
short toi_bench    $bin/toi_bench --out "$out" "${toi_motions[@]}"           # time of impact vs FCL continuous collision
short penetration  $bin/penetration --out "$out" "${paper[@]}"                # penetration depth: interval width vs depth and eps, time, coal's EPA
long motion      "" $bin/motion "${motion_frames[@]}"                                # Figure 12: 15 pairs in continuous motion
long deforming   "" $bin/deforming "${deforming_frames[@]}"                             # Figure 8: static models vs M_t
long pareto      "" $bin/pareto "${pareto_poses[@]}"                                # accuracy vs time, build, memory
long stability   "" $bin/stability "${stability_seeds[@]}"                             # degenerate families, exact references
long crosscheck  crosscheck $bin/verify crosscheck "${cross[@]}" --occt-poses 0  # vs FCL, CGAL, libccd
long occt        crosscheck-occt $bin/verify crosscheck --poses 0 --convex-poses 0 "${occt[@]}"  # vs OpenCASCADE on the true surfaces
short kernels      $bin/patch_kernels --out "$out"                            # leaf kernels near contact
short scenes       bash -c 'for f in experiments/scenes/*.toml; do '"$bin"'/revdist-scene "$f" --out '"$out"'/scenes > /dev/null || exit 1; done'  # example scenes: CSV + cost summaries
echo "total $SECONDS s" | tee -a "$timing" >&2
if [ -n "$shard" ]; then
    echo "shard $shard of the long steps written to $here/ (merge with: bash scripts/main.sh ${paper[*]:-}${paper[*]:+ }--merge ${shard#*/})"
else
    echo "figures and tables written to $out/ (step times in $timing)"
fi
