#!/usr/bin/env bash
# The ranks sit behind one seam (docs/parallel.md, "The seam"): outside the runtime, the seam and the output
# gather, no code asks how many ranks there are. A stage asks whether its grid is split
# (fluid::Decomposition::splits, host::splitting) and exchanges through the seam; a sum or maximum over ranks
# is the Communicator's, which returns its argument alone. Prints each query found elsewhere and exits 1;
# exits 0 when there is none.
#
#   bash tests/cli/rank_queries.sh SOURCE_DIR
#
# A query is a Communicator's size() (the project names its communicators world or comm) or a comparison of
# a decomposition's ranks().
set -euo pipefail
cd "${1:?usage: rank_queries.sh SOURCE_DIR}"

query='\b(world|comm)[A-Za-z_]*(->|\.)size\(\)|ranks\(\)[[:space:]]*[<>=!]'

# The files that may ask, each with why.
allowed=(
  "host/runtime/"                        # the runtime: the communicator, devices per machine
  "fluid/Decomposition."                 # the grid's blocks, a rank each: splits() is where one asks
  "host/stages/BlockGrid."               # the seam: blocks_over and splitting, the one place stages ask
  "host/stages/RankSeam."                # the seam: the wind grid's exchanges and sums
  "host/stages/HaloExchange."            # the seam: the halo's messages
  "host/stages/PointWindAcrossRanks."    # the seam for points: who holds which point
  "host/app/FrameGather."                # the output gather: every rank's block of a frame
  "host/app/RunCheckpoint."              # the output gather: each rank's part of a checkpoint
  "host/app/CheckpointRedistribution."   # the output gather: parts taken over another split
  "host/cli/RunCommand.cpp"              # hands the rank count to the planner, which makes the decomposition
  "host/cli/main.cpp"                    # names the rank in an error: "rank 1 of 4"
  "host/cli/BenchCommand.cpp"            # the benchmarks measure a split and report its ranks
  "host/bench/"
)

status=0
checked=0
while IFS= read -r file; do
  checked=$((checked + 1))
  for prefix in "${allowed[@]}"; do
    [[ $file == "$prefix"* ]] && continue 2
  done
  while IFS= read -r hit; do
    echo "$file:$hit: asks how many ranks there are outside the seam (ask whether the grid splits)" >&2
    status=1
  done < <(grep -nE "$query" "$file" | cut -d: -f1)
done < <(git ls-files 'base/*' 'fluid/*' 'trees/*' 'host/*' 'io/*' 'viz/*' | grep -E '\.(cpp|hpp|h)$')

echo "rank queries: $checked files checked"
exit $status
