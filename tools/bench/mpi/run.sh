#!/usr/bin/env bash
# Memory per rank and wall time of the slepc backend's distributed path against the default
# serial path, on the TET10 plate of tools/bench/reduce (240 x 120 x 30 mm steel with four
# holes, clamped at x = 0, 20 modes unless --modes says), side by side in one run for every size:
#   serial    ffr-reduce with its default backend (block Lanczos, own Cholesky), default threads
#   slepc 1   mpirun -np 1 ffr-reduce (part with backend "slepc") --threads 1
#   slepc 2   mpirun -np 2 ffr-reduce (part with backend "slepc") --threads 1
# The slepc runs use the part's MUMPS settings: --ordering NAME (reduction.mumps_ordering; none:
# the default) and --out-of-core (reduction.out_of_core, files under DIR/ooc).
# Each process runs under /usr/bin/time -v (its own file per rank): wall time and the maximum
# resident set of every rank; the load average of the machine is sampled every 10 s during the
# run (mean and largest of the 1-minute figure); rank 0's log gives MUMPS's factor (ordering,
# entries INFOG(29), MB allocated on the largest rank INFOG(18), MUMPS's estimate for an in-core
# factorization INFOG(16)). The SIDs of the slepc runs are
# compared with the serial one (ffr-diff --rtol 1e-6). The runs are sequential, niced, one at a
# time.
#
#   tools/bench/mpi/run.sh [--sizes "100k 250k 500k"] [--workdir DIR] [--no-build] [--paths "serial 1 2"]
#                          [--ordering pord|amd|amf|qamd|auto] [--out-of-core] [--modes N]
#
# --modes N asks N clamped modes instead of 20: fewer shift-invert solves, for a run out of core
# where each solve reads the factor from disk. SLEPc's basis then holds max(2N, N + 15) vectors
# instead of 40; the results' last column says N and fit.py accounts for the difference.
#
# Results go to DIR/results.tsv (appended: one line a run) and fit.py turns them into the
# tables and the memory model of RESULTS.md. A run is skipped when the memory it is expected to
# need (from the largest run so far of the same path and MUMPS settings, scaled by the growth
# between its two largest sizes), plus 3 GiB kept free for the machine's other work, exceeds
# MemAvailable.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../../.." && pwd)
sizes="100k 250k 500k" build=1 workdir="$root/build/bench-mpi" paths="serial 1 2" ordering="" ooc=0 modes=20
while [ $# -gt 0 ]; do
  case "$1" in
    --sizes) sizes=$2; shift ;;
    --paths) paths=$2; shift ;;
    --no-build) build=0 ;;
    --workdir) workdir=$2; shift ;;
    --ordering) ordering=$2; shift ;;
    --out-of-core) ooc=1 ;;
    --modes) modes=$2; shift ;;
    -h|--help) sed -n '2,28p' "$0"; exit 0 ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
if [ $build = 1 ]; then cmake --build "$root/build" -j 2 --target ffr-reduce ffr-diff; fi
bin="$root/build/bin"
mkdir -p "$workdir"
tsv="$workdir/results.tsv"
[ -f "$tsv" ] || printf 'size\tdof\tpath\tranks\twall_s\tmaxrss_mib_per_rank\tdiff\tmumps\tfactor_entries\tmumps_mb_max\tload_mean_max\tmumps_incore_estimate_mb_max\tmodes\n' > "$tsv"
# The MUMPS settings of the slepc runs, as the results name them.
mumps="${ordering:-default}/$([ $ooc = 1 ] && echo out-of-core || echo in-core)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

geo='SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.24, 0.12, 0.03};
Cylinder(2) = {0.07, 0.06, -0.01, 0, 0, 0.05, 0.025};
Cylinder(3) = {0.15, 0.04, -0.01, 0, 0, 0.05, 0.015};
Cylinder(4) = {0.15, 0.09, -0.01, 0, 0, 0.05, 0.012};
Cylinder(5) = {0.21, 0.06, -0.01, 0, 0, 0.05, 0.01};
BooleanDifference(10) = { Volume{1}; Delete; }{ Volume{2, 3, 4, 5}; Delete; };
Physical Volume("body") = {10};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};'

dof_of() { case "$1" in *k) echo $(( ${1%k} * 1000 ));; *M) echo $(( ${1%M} * 1000000 ));; *) echo "$1";; esac; }
nodes_of() { awk '/^\$Nodes/{getline; print $2; exit}' "$1"; }
elapsed_s() { awk -F': ' '/Elapsed \(wall clock\)/{n=split($2,a,":"); s=0; for(i=1;i<=n;i++) s=s*60+a[i]; print s}' "$1"; }
maxrss_mib() { awk -F': ' '/Maximum resident set size/{printf "%d", $2/1024}' "$1"; }
avail_mib() { awk '/MemAvailable/{printf "%d", $2/1024}' /proc/meminfo; }

# The plate mesh with about the requested DOF: DOF ~ 99e3 (5.8 mm / h)^2.77 on this geometry
# (tools/bench/reduce/meshes.cpp), corrected once from the measured count.
mesh() {
  local tag=$1 target dir h nodes ratio
  target=$(dof_of "$tag") dir="$workdir/$tag"
  mkdir -p "$dir"
  write_part "$dir"
  [ -f "$dir/plate.msh" ] && return
  printf '%s\n' "$geo" > "$dir/plate.geo"
  h=$(python3 -c "print(0.0058 * (99e3 / $target) ** (1 / 2.77))")
  for attempt in 1 2; do
    (cd "$dir" && nice gmsh -3 -order 2 -clmax "$h" -format msh41 plate.geo -o plate.msh > gmsh.log 2>&1)
    nodes=$(nodes_of "$dir/plate.msh")
    ratio=$(python3 -c "print(3 * $nodes / $target)")
    python3 -c "import sys; sys.exit(0 if abs($ratio - 1) < 0.05 else 1)" && break
    h=$(python3 -c "print($h * $ratio ** (1 / 2.77))")
  done
}

write_part() {
  cat > "$1/part.json" <<JSON
{"geometry": "plate.msh",
 "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
 "interfaces": [{"name": "clamp", "group": "clamp"}], "visual": false,
 "reduction": {"method": "clamped", "interface": "clamp", "modes": $modes}}
JSON
}

# The same part for the slepc runs, with the MUMPS settings asked.
slepc_part() {
  local dir=$1 extra=""
  [ -n "$ordering" ] && extra="$extra, \"mumps_ordering\": \"$ordering\""
  if [ $ooc = 1 ]; then
    mkdir -p "$dir/ooc"
    extra="$extra, \"out_of_core\": true, \"out_of_core_dir\": \"ooc\""
  fi
  sed "s|\"modes\": $modes}|\"modes\": $modes, \"backend\": \"slepc\"$extra}|" "$dir/part.json" > "$dir/part.slepc.json"
}

# Memory a run is expected to need (MiB): the largest finished run of this path (and, for the
# slepc ones, these MUMPS settings), scaled by DOF^e, e the growth between its two largest
# sizes (kept within 1.0 to 1.5; 1.3 with one size only).
expected_mib() {
  local path=$1 dof=$2
  awk -F'\t' -v p="$path" -v d="$dof" -v s="$mumps" 'NR>1 && $3==p && (p=="serial" || $8==s) && $6 ~ /^[0-9,]+$/ {
      n=split($6,r,","); m=0; for(i=1;i<=n;i++) m+=r[i]; mem[$2]=m}
    END{k=0; for (x in mem) xs[++k]=x+0; if (k==0) {print 0; exit}
      for (i=1;i<=k;i++) for (j=i+1;j<=k;j++) if (xs[j]>xs[i]) {t=xs[i]; xs[i]=xs[j]; xs[j]=t}
      e=1.3; if (k>1) {e=log(mem[xs[1]]/mem[xs[2]])/log(xs[1]/xs[2]); if (e<1) e=1; if (e>1.5) e=1.5}
      printf "%d", mem[xs[1]] * (d/xs[1])^e}' "$tsv"
}

run_one() {
  local tag=$1 path=$2 dir dof need out ranks rss wall diff config entries mb est sampler load
  dir="$workdir/$tag" dof=$((3 * $(nodes_of "$workdir/$tag/plate.msh")))
  config=$([ "$path" = serial ] && echo - || echo "$mumps")
  need=$(expected_mib "$path" "$dof")
  if [ $((need + 3072)) -gt "$(avail_mib)" ]; then
    echo "run.sh: $tag $path skipped: expected $need MiB (+3072 kept free), $(avail_mib) MiB available" >&2
    printf '%s\t%s\t%s\t-\t-\tskipped (expected %s MiB)\t-\t%s\t-\t-\t-\t-\t%s\n' "$tag" "$dof" "$path" "$need" "$config" "$modes" >> "$tsv"
    return
  fi
  rm -f "$dir/time.$path."* "$dir/$path.sid.h5" "$dir/load.$path"
  out="$dir/$path.sid.h5"
  (while sleep 10; do cut -d' ' -f1 /proc/loadavg; done > "$dir/load.$path") &
  sampler=$!
  if [ "$path" = serial ]; then
    ranks=1
    nice /usr/bin/time -v -o "$dir/time.serial.0" "$bin/ffr-reduce" "$dir/part.json" -o "$out" > "$dir/$path.log" 2>&1 || true
  else
    ranks=$path
    slepc_part "$dir"
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 nice mpirun --oversubscribe -np "$ranks" sh -c \
      "/usr/bin/time -v -o '$dir/time.$path.'\$OMPI_COMM_WORLD_RANK '$bin/ffr-reduce' '$dir/part.slepc.json' -o '$out' --threads 1" \
      > "$dir/$path.log" 2>&1 || true
  fi
  kill "$sampler" 2>/dev/null || true
  wait "$sampler" 2>/dev/null || true
  load=$(awk '{s+=$1; if($1>m)m=$1; n++} END{if(n) printf "%.1f/%.1f", s/n, m; else print "-"}' "$dir/load.$path")
  wall=$(elapsed_s "$dir/time.$path.0")
  rss=$(for r in $(seq 0 $((ranks - 1))); do maxrss_mib "$dir/time.$path.$r"; echo; done | paste -sd, -)
  entries=$(sed -n 's/.*MUMPS: .* ordering, \([0-9]*\) entries.*/\1/p' "$dir/$path.log" | tail -1)
  mb=$(sed -n 's/.*entries in the factor (INFOG(29)), \([0-9]*\) MB allocated.*/\1/p' "$dir/$path.log" | tail -1)
  est=$(sed -n 's/.*in-core estimate \([0-9]*\) MB on the largest rank.*/\1/p' "$dir/$path.log" | tail -1)
  diff=-
  if [ ! -f "$out" ]; then
    diff="FAILED (see $path.log)"
  elif [ "$path" != serial ] && [ -f "$dir/serial.sid.h5" ]; then
    if "$bin/ffr-diff" "$dir/serial.sid.h5" "$out" --rtol 1e-6 > "$dir/diff.$path.txt" 2>&1; then diff=equivalent; else diff=DIFFERENT; fi
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$tag" "$dof" "$path" "$ranks" "$wall" "$rss" "$diff" "$config" \
    "${entries:--}" "${mb:--}" "$load" "${est:--}" "$modes" >> "$tsv"
  echo "run.sh: $tag ($dof DOF) $path [$config]: ${wall} s, max RSS per rank ${rss} MiB, factor ${entries:--} entries, $diff, load $load" >&2
}

echo "# $(date -u +%FT%TZ) $(uname -n) $(nproc) cores, $(awk '/MemTotal/{printf "%.1f GiB", $2/1048576}' /proc/meminfo), commit $(git -C "$root" rev-parse --short HEAD)" >> "$workdir/runs.txt"
for tag in $sizes; do
  mesh "$tag"
  for p in $paths; do run_one "$tag" "$p"; done
done
python3 "$here/fit.py" "$tsv"
