#!/usr/bin/env bash
# The main job: regenerates every figure and table under figures/ (issue 13), revdist and the
# real baselines (FCL, libccd, CGAL) and peers (coal, parry3d) measured in the same run.
#
#   bash scripts/main.sh           # default scale: about 7 minutes of runs on 2 cores (15 at most)
#   bash scripts/main.sh --paper   # paper scale (50,000 motion frames, 1,000 poses per pair, ...): hours
#
# Every CSV starts with '# key: value' provenance lines (machine, git commit, parameters).
# Timing steps run one query at a time; steps that only check or sample use all cores.
set -euo pipefail
cd "$(dirname "$0")/.."

paper=()
case "${1:-}" in
    "") ;;
    --paper) paper=(--paper) ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "error: unknown argument '$1' (try --help)" >&2; exit 2 ;;
esac

scripts/deps.sh
cargo build --release --workspace
out=figures
mkdir -p "$out"
bin=target/release
timing="$out/main_timing.txt"
echo "# scripts/main.sh ${paper[*]:-} on $(date -u +%Y-%m-%dT%H:%M:%SZ), commit $(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)" > "$timing"

step() {  # step NAME COMMAND...: run, time, record
    local name=$1; shift
    echo "== $name" >&2
    local t0=$SECONDS
    "$@"
    echo "$name $((SECONDS - t0)) s" | tee -a "$timing" >&2
}

if [ ${#paper[@]} -eq 0 ]; then
    fcl_poses=(--poses 100 --poses-1e-5 50); query_poses=(--poses 100); cross=(--poses 100); occt=(--occt-poses 200)
    toi_motions=(--motions 3)
else
    fcl_poses=(--paper); query_poses=(--poses 1000); cross=(--poses 1000); occt=(--occt-poses 400)
    toi_motions=(--motions 30)
fi

step profiles     $bin/revdist figures --out "$out"                          # model profiles, M_t frames
step convergence  $bin/convergence --out "$out" "${paper[@]}"                 # biarcs n^-3 vs chords n^-2
step bvh_tables   $bin/bvh_tables --out "$out" "${paper[@]}"                  # Tables 1-2, Figure 9
step query_times  $bin/accuracy_time --out "$out" "${query_poses[@]}"         # where a query spends its time
step tails        $bin/tails --out "$out"                                      # tail of single-query times: 2,000 seeded queries, cold
step fcl_bench    $bin/fcl_bench --out "$out" "${fcl_poses[@]}"               # speed ratios vs FCL on close poses
step peers        $bin/peers --out "$out" "${paper[@]}"                       # FCL, coal, parry3d in one run; convex solids vs exact GJK
step toi_bench    $bin/toi_bench --out "$out" "${toi_motions[@]}"           # time of impact vs FCL continuous collision
step motion       $bin/motion --out "$out" "${paper[@]}"                      # Figure 12: 15 pairs in continuous motion
step deforming    $bin/deforming --out "$out" "${paper[@]}"                   # Figure 8: static models vs M_t
step pareto       $bin/pareto --out "$out" "${paper[@]}"                      # accuracy vs time, build, memory
step stability    $bin/stability --out "$out" "${paper[@]}"                   # degenerate families, exact references
step crosscheck   $bin/verify crosscheck --out "$out/crosscheck" "${cross[@]}" --occt-poses 0  # vs FCL, CGAL, libccd
step occt         $bin/verify crosscheck --out "$out/crosscheck-occt" --poses 0 --convex-poses 0 "${occt[@]}"  # vs OpenCASCADE on the true surfaces
step kernels      $bin/patch_kernels --out "$out"                            # leaf kernels near contact
step scenes       bash -c 'for f in experiments/scenes/*.toml; do '"$bin"'/revdist-scene "$f" --out '"$out"'/scenes > /dev/null || exit 1; done'  # example scenes: CSV + cost summaries
echo "total $SECONDS s" | tee -a "$timing" >&2
echo "figures and tables written to $out/ (step times in $timing)"
