#!/usr/bin/env bash
# Sweep throughput on 1 and 2 MPI ranks (one thread each) and, for the machine's own ceiling, one
# process of 2 threads, taking turns; and rank 0's cost per
# medium (storing it), from which the ranks rank 0 can serve are estimated. Writes a JSON file.
#   bash bench/mpi_sweep.sh build/softdrop bench/results/mpi-sweep.json [repeats]
set -euo pipefail
bin=$(realpath "$1"); out=$(realpath -m "$2"); repeats=${3:-2}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
sweep=(--porosities 0.6,0.7,0.8,0.9 --media 8 --droplets 32 --width 300 --height 300 --threads 1)
# One run: wall seconds and the "storing took X ms a medium" of its last line.
timed() {
  local name=$1; shift
  rm -f "$name.db"
  local t0 t1
  t0=$(date +%s.%N)
  "$@" --db "$name.db" > /dev/null 2> "$name.err"
  t1=$(date +%s.%N)
  local serve
  serve=$(sed -n 's/.*serving the other ranks \([0-9.e+-]*\) ms.*/\1/p' "$name.err" | tail -1)
  echo "$(awk "BEGIN { print $t1 - $t0 }") $(sed -n 's/.*storing took \([0-9.e+-]*\) ms a medium.*/\1/p' "$name.err" | tail -1) ${serve:-null}"
}
rows=()
for r in $(seq "$repeats"); do
  for ranks in 1 2; do  # in turn, so that both see the same machine
    read -r s ms serve < <(timed "r$ranks" mpirun --oversubscribe -n "$ranks" "$bin" sweep "${sweep[@]}")
    echo "repeat $r, $ranks rank(s): $s s, storing $ms ms a medium, serving $serve ms a remote one" >&2
    rows+=("{\"repeat\": $r, \"ranks\": $ranks, \"seconds\": $s, \"store_ms_per_medium\": $ms, \"serve_ms_per_remote_medium\": $serve}")
  done
  # The machine's own ceiling for two cores: one process, two threads, no MPI.
  read -r s ms serve < <(timed threads2 "$bin" sweep "${sweep[@]}" --threads 2)
  echo "repeat $r, one process of 2 threads: $s s" >&2
  rows+=("{\"repeat\": $r, \"ranks\": 0, \"threads\": 2, \"seconds\": $s, \"store_ms_per_medium\": $ms}")
done
# A paper-size medium (200 droplets, 500 x 500, phi 0.65: among the costliest) on one thread, and
# what storing one costs.
read -r paper_s paper_ms serve < <(timed paper "$bin" sweep --preset paper --porosities 0.65 --media 2 --threads 1)
echo "paper media: $paper_s s for 2, storing $paper_ms ms a medium" >&2
droplets=$((4 * 8 * 32))
/usr/bin/python3 - "$out" "$droplets" "$paper_s" "$paper_ms" "${rows[@]}" <<'PY'
import json, platform, statistics, sys
out, droplets, paper_s, paper_ms = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
rows = [json.loads(r) for r in sys.argv[5:]]
one = statistics.median(r["seconds"] for r in rows if r["ranks"] == 1)
two = statistics.median(r["seconds"] for r in rows if r["ranks"] == 2)
threads = statistics.median(r["seconds"] for r in rows if r["ranks"] == 0)
store_ms = statistics.median(r["store_ms_per_medium"] for r in rows if r["ranks"] == 2)
serve_ms = statistics.median(r["serve_ms_per_remote_medium"] for r in rows if r["ranks"] == 2)
# Serving a paper-size medium: storing it, plus what serving costs beyond storing (the claims and
# the decoding), as measured on the bench media.
paper_serve_ms = paper_ms + max(0.0, serve_ms - store_ms)
unit_s = one / 32  # a bench medium on one rank of one thread
paper_unit_s = paper_s / 2
result = {
    "sweep": "4 porosities (0.6-0.9) x 8 media x 32 droplets, 300 x 300, --threads 1 on each rank",
    "runs": rows,
    "one_rank_droplets_per_s": droplets / one, "two_ranks_droplets_per_s": droplets / two,
    "speedup_two_ranks": one / two, "efficiency_two_ranks": one / two / 2,
    "one_process_two_threads_droplets_per_s": droplets / threads, "efficiency_two_threads": one / threads / 2,
    "store_ms_per_medium": store_ms, "serve_ms_per_remote_medium": serve_ms,
    "bench_medium_s_one_thread": unit_s,
    "paper_medium_s_one_thread": paper_unit_s, "paper_store_ms_per_medium": paper_ms,
    "paper_serve_ms_per_medium": paper_serve_ms,
    # Rank 0 serves one medium at a time: it is the bottleneck once the cores bring more media a
    # second than it can serve. Cores it can keep busy = a medium's seconds on one core / serving.
    "cores_rank0_serves_bench_media": unit_s / (serve_ms / 1e3),
    "cores_rank0_serves_paper_media": paper_unit_s / (paper_serve_ms / 1e3),
    "machine": platform.machine(), "cpus": __import__("os").cpu_count(),
}
with open(out + ".tmp", "w") as f:
    json.dump(result, f, indent=2)
    f.write("\n")
__import__("os").replace(out + ".tmp", out)
print(json.dumps({k: v for k, v in result.items() if k != "runs"}, indent=2))
PY
