#!/usr/bin/env bash
# `mpirun -n P softdrop sweep` against one process: the same store cell for cell at P = 3 and 4
# (oversubscribed on a small machine), a rank killed mid-sweep and the command run again (nothing
# lost, nothing done twice). `mpirun -n 3 softdrop optimize --islands 3` against the islands on
# threads, and killed and resumed against uninterrupted. One error line for bad options, other
# commands refused across ranks, and the same binary without mpirun as the plain program.
#   bash tests/mpi_test.sh SOFTDROP_BINARY
set -euo pipefail
bin=$(realpath "$1")
balloon_toml=$(realpath "$(dirname "$0")/../results/calibration/balloon.toml")
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
# Test machines run as root, in containers without cross-memory attach.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1
run() { timeout 300 mpirun --oversubscribe -n "$@"; }
fail() { echo "FAIL: $*"; exit 1; }

# Every stored cell but the wall times and dates, in key order.
cells() {
  sqlite3 "$1" "SELECT id, status, params, units FROM sweeps ORDER BY id;
    SELECT sweep_id, porosity_index, medium_index, target_porosity, porosity, grains, medium_seed, droplets,
           passed, stuck, timeout, diverged, mean_t, standard_error, stuck_fraction FROM sweep_media ORDER BY 1, 2, 3;
    SELECT * FROM sweep_droplets ORDER BY 1, 2, 3, 4;"
}

# Once `sql` on `db` gives at least `least`, SIGKILL to rank 1 of the job whose command line has
# `pattern`.
kill_rank_1() {
  local db=$1 sql=$2 least=$3 pattern=$4 n victim=""
  for _ in $(seq 600); do
    n=$(sqlite3 "$db" "$sql" 2>/dev/null || echo 0)
    ((n >= least)) && break
    sleep 0.05
  done
  for p in $(pgrep -f "$pattern" || true); do
    if tr '\0' '\n' < "/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1"; then victim=$p; fi
  done
  [[ -n "$victim" ]] || fail "rank 1 of '$pattern' not found"
  kill -9 "$victim"
}

# The balloon (the earlier defaults) on grains of radii 8 to 16, as the C++ tests run the machinery
# (tests/balloon.hpp): a quick droplet, and many grains in a small box.
balloon=(--config "$balloon_toml")
small=(--porosities 0.7,0.8,0.9 --media 4 --droplets 8 --width 200 --height 200 --threads 1 --quiet "${balloon[@]}")
"$bin" sweep --db one.db "${small[@]}" > one.txt
for p in 3 4; do
  run "$p" "$bin" sweep --db "mpi$p.db" "${small[@]}" > "mpi$p.txt"
  [[ "$(cells one.db)" == "$(cells "mpi$p.db")" ]] || fail "the store of $p ranks differs from one process's"
  cmp -s one.txt "mpi$p.txt" || fail "the table of $p ranks differs from one process's"
  [[ $(sqlite3 "mpi$p.db" "SELECT count(*) FROM sweep_media") == 12 ]] || fail "$p ranks: not 12 media"
done
echo "ok: 3 and 4 ranks store what one process stores"

# Rank 1 killed once rank 0 has committed some media; then the same command again.
long=(--porosities 0.7,0.8,0.9 --media 8 --droplets 48 --width 200 --height 200 --threads 1 "${balloon[@]}")
run 3 "$bin" sweep --db killed.db "${long[@]}" > /dev/null 2> killed.err &
job=$!
kill_rank_1 killed.db "SELECT count(*) FROM sweep_media" 2 "sweep --db killed.db"
wait "$job" && fail "the job went on after a rank was killed" || true
before=$(sqlite3 killed.db "SELECT count(*) FROM sweep_media")
((before >= 2 && before < 24)) || fail "after the kill: $before media stored, expected 2 to 23"
run 3 "$bin" sweep --db killed.db "${long[@]}" > /dev/null 2> again.err
grep -q "this session $((24 - before)) media" again.err || { cat again.err; fail "the second run did not do exactly the $((24 - before)) missing media"; }
"$bin" sweep --db whole.db "${long[@]}" --quiet > /dev/null
[[ "$(cells killed.db)" == "$(cells whole.db)" ]] || fail "killed and run again differs from uninterrupted"
echo "ok: a rank killed after $before media, the command run again did the other $((24 - before))"

# Islands: the same history on threads and on ranks; a rank killed, then resumed. (The robust
# objective: a migration re-runs both arrangements on the generation's starts.)
scene=(--grains 16 --width 160 --height 120 --medium-seed 2 --stuck-window 0.1 --stuck-distance 1 --lambda 2 --quiet
  --objective mean --starts 4 "${balloon[@]}")
history() {
  sqlite3 "$1" "SELECT id, island, archipelago, status, params, seed, generations, evaluations, droplets, best_t, best_generation FROM runs ORDER BY id;
    SELECT run_id, generation, kind, accepted_candidate, best_t, touched, state, parent_t, parent_passed FROM generations ORDER BY 1, 2;
    SELECT run_id, generation, candidate, moved_grain, moved, outcome, reason, tortuosity, steps, touched, droplets, passed FROM candidates ORDER BY 1, 2, 3;
    SELECT * FROM grains ORDER BY 1, 2, 3; SELECT * FROM paths ORDER BY 1, 2, 3;"
}
islands=(--islands 3 --migrate-every 5 --generations 16 --strategy lahc)
"$bin" optimize --db isl-threads.db "${scene[@]}" "${islands[@]}" > /dev/null
run 3 "$bin" optimize --db isl-ranks.db "${scene[@]}" "${islands[@]}" --threads 1 > /dev/null
[[ "$(history isl-threads.db)" == "$(history isl-ranks.db)" ]] || fail "islands on 3 ranks differ from islands on threads"
long_islands=(--islands 3 --migrate-every 5 --generations 80 --strategy lahc)
"$bin" optimize --db isl-whole.db "${scene[@]}" "${long_islands[@]}" > /dev/null
run 3 "$bin" optimize --db isl-killed.db "${scene[@]}" "${long_islands[@]}" --threads 1 > /dev/null 2>&1 &
job=$!
kill_rank_1 isl-killed.db "SELECT coalesce(min(generations), 0) FROM runs" 10 "optimize --db isl-killed.db"
wait "$job" && fail "the islands went on after a rank was killed" || true
at=$(sqlite3 isl-killed.db "SELECT min(generations) FROM runs")
((at >= 10 && at < 80)) || fail "islands: killed at generation $at, expected 10 to 79"
run 3 "$bin" optimize --db isl-killed.db --resume 1 --threads 1 --quiet > /dev/null
[[ "$(history isl-killed.db)" == "$(history isl-whole.db)" ]] || fail "islands killed at generation $at and resumed differ"
echo "ok: islands on 3 ranks equal islands on threads; killed at generation $at and resumed, equal too"
if run 2 "$bin" optimize --db plain.db "${scene[@]}" --generations 2 > /dev/null 2> plain.err; then fail "a plain search ran on 2 ranks"; fi
grep -q "only with --islands" plain.err || { cat plain.err; fail "a plain search on 2 ranks: no refusal"; }
[[ ! -e plain.db ]] || fail "a plain search on 2 ranks left a file"

# Bad options: one line, from rank 0, and every rank exits.
if run 3 "$bin" sweep --db bad.db --porosities 0.5,1.5 > /dev/null 2> bad.err; then fail "bad porosity accepted"; fi
[[ $(grep -c "^softdrop: error: porosities = 1.5" bad.err) == 1 ]] || { cat bad.err; fail "not one error line"; }
[[ ! -e bad.db ]] || fail "bad options left a file"
# Other commands are not spread over ranks.
if run 2 "$bin" simulate --droplets 2 > /dev/null 2> simulate.err; then fail "simulate ran on 2 ranks"; fi
[[ $(grep -c "only sweep and optimize --islands run across MPI ranks" simulate.err) == 1 ]] || { cat simulate.err; fail "simulate: no refusal"; }
echo "ok: bad options and other commands refused with one line"

# One rank, and no mpirun at all: the plain program.
run 1 "$bin" sweep --db single.db "${small[@]}" > single.txt
[[ "$(cells one.db)" == "$(cells single.db)" ]] || fail "one rank's store differs"
env -u OMPI_COMM_WORLD_RANK "$bin" simulate --droplets 2 --quiet > /dev/null || fail "simulate without mpirun"
echo "ok: one rank and no mpirun behave as the plain program"
