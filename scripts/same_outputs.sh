#!/usr/bin/env bash
# Byte-identity of two `taut` binaries' outputs (for a redesign that
# must not move a bit).
#
#   scripts/same_outputs.sh OLD_BIN NEW_BIN OUT [--quick] [--no-run]
#
# Runs the same commands with both binaries: `taut run` of every bundled
# scene (scenes/*.toml, scenes/verify/*.toml), the golden suite (`taut gate
# golden`) and a set of studies (compare, converge, precision, sweep,
# verify --quick, modes) chosen to step every method, the multi-mass
# pantograph, droppers, external forces, damping, a static start and the
# batched kernels (generalized-α lanes, modal_exact batches). Every file
# each writes, its terminal text and its exit code are compared byte for
# byte, after removing only what measures time:
#   * JSON keys and CSV columns named `wall_seconds`, `*_seconds`, `wall*`,
#     `elapsed*`, `*per_second*`, and `pareto` (a front drawn on wall
#     time): their values are set to "T";
#   * terminal lines that report a wall time (`s wall`, `dof-steps/s`);
#   * the output folder's own path in the terminal text;
#   * a terminal table's column headed `wall s` (and the `*` marking a
#     Pareto front drawn on it), a header's `… s on N threads`;
#   * `time="…"` attributes of junit.xml;
#   * the figures whose axes are wall times (precision.svg, cost-time.svg)
#     and a sweep's lock file (its process id): skipped, and named.
# Anything else that differs is a failure, listed with the first
# differing line.
#
# OLD's outputs are kept in OUT/old and reused when OUT/old/.done exists
# (record them once before a change, then compare each step against
# them): delete OUT/old to record again. --quick runs the cases marked
# quick only (under a minute); --no-run compares the outputs already in
# OUT/new again.
#
# Exit code: 0 when every output is the same, 1 otherwise.
set -u
if [ $# -lt 3 ]; then
    sed -n 2,30p "$0"
    exit 2
fi
OLD=$(realpath "$1")
NEW=$(realpath "$2")
OUT=$(realpath -m "$3")
QUICK=
RUN_NEW=yes
for flag in "${@:4}"; do
    case "$flag" in
    --quick) QUICK=--quick ;;
    --no-run) RUN_NEW=no ;;
    *) echo "unknown flag $flag" && exit 2 ;;
    esac
done
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT" || exit 2

# name | quick? | arguments (OUTDIR is replaced by the case's folder)
cases() {
    for s in scenes/*.toml scenes/verify/*.toml; do
        n=$(basename "$s" .toml)
        q=no
        case "$n" in reference | pantograph_3mass | span_droppers | mms_*) q=yes ;; esac
        echo "run_$n|$q|run $s --out OUTDIR --quiet"
    done
    cat <<'EOF'
run_reference_external_force|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.3' --set 'carrier.0.external_force={time=[0.0,0.1,1.0],force=[0.0,-5.0,3.0]}'
run_reference_damped_bathe|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.2' --set 'beam.damping={mass=0.5,stiffness=1e-5}' --set 'integrator={method="bathe"}'
run_reference_damped_ga|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.2' --set 'beam.damping={mass=0.5,stiffness=1e-5}' --set 'integrator.rho_inf=0.8'
run_reference_damped_mj|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.2' --set 'beam.damping={mass=0.5,stiffness=1e-5}' --set 'integrator={method="moreau_jean",theta=0.6}'
run_reference_modal_exact|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.3' --set 'mesh.kind="galerkin"' --set 'mesh.modes=400' --set 'integrator={method="modal_exact"}'
run_reference_modal_exact_modal|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.1' --set 'mesh={kind="modal",elements=200,modes=120}' --set 'integrator={method="modal_exact"}' --set 'contact.formulation="penalty"'
run_reference_modal_exact_damped_ext|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.1' --set 'mesh.kind="galerkin"' --set 'mesh.modes=200' --set 'integrator={method="modal_exact"}' --set 'beam.damping={mass=0.5,stiffness=1e-5}' --set 'carrier.0.external_force={time=[0.0,0.1,1.0],force=[0.0,-5.0,3.0]}'
run_two_pantographs_modal_exact|yes|run scenes/two_pantographs.toml --out OUTDIR --quiet --set 'time.end=0.1' --set 'mesh.kind="galerkin"' --set 'mesh.modes=200' --set 'integrator={method="modal_exact"}'
run_pantograph_static|yes|run scenes/pantograph_3mass.toml --out OUTDIR --quiet --set 'time.end=0.1' --set 'time.initial="static"'
run_reference_impact_mj|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.2' --set 'integrator={method="moreau_jean"}' --set 'contact.formulation="complementarity"'
run_reference_cd_bad_step|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'integrator={method="central_difference"}'
run_reference_unknown_method|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'integrator.method="magic"'
run_reference_foreign_key|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'integrator.method="bathe"'
run_reference_bad_range|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'integrator={method="hht",alpha=0.5}'
run_reference_alpha_placement|yes|run scenes/reference.toml --out OUTDIR --quiet --set 'time.end=0.1' --set 'contact.placement="alpha"' --set 'integrator.rho_inf=0.8'
run_pantograph_modal_exact|yes|run scenes/pantograph_3mass.toml --out OUTDIR --quiet --set 'mesh.kind="galerkin"' --set 'mesh.modes=100' --set 'integrator={method="modal_exact"}'
compare_reference_methods|yes|compare scenes/reference.toml --methods generalized_alpha,bathe,central_difference,moreau_jean --set 'time.end=0.1' --out OUTDIR --quiet
compare_reference_all_methods|no|compare scenes/reference.toml --methods generalized_alpha,newmark,hht,wbz,bathe,central_difference,moreau_jean,modal_exact --discretizations hermite,galerkin:300,modal:150 --set 'time.end=0.15' --set 'time.step=5e-5' --out OUTDIR --quiet
compare_pantograph_methods|yes|compare scenes/pantograph_3mass.toml --methods generalized_alpha,newmark,hht,wbz,bathe,central_difference,moreau_jean --formulations lagrange,penalty,complementarity --set 'time.end=0.1' --set 'time.step=5e-5' --out OUTDIR --quiet
compare_droppers|no|compare scenes/span_droppers.toml --methods generalized_alpha,hht,bathe --formulations lagrange,penalty --out OUTDIR --quiet
compare_two_pantographs|no|compare scenes/two_pantographs.toml --set 'time.end=0.2' --out OUTDIR --quiet
converge_moving_force|yes|converge scenes/moving_force_beam.toml --levels 3 --methods generalized_alpha,bathe,moreau_jean,central_difference --out OUTDIR --quiet
converge_riding_modal|no|converge scenes/riding_mass_pinned.toml --refine step --levels 3 --methods generalized_alpha,modal_exact --discretizations galerkin:100 --out OUTDIR --quiet
precision_reference|no|precision scenes/reference.toml --levels 2 --set 'time.end=0.1' --out OUTDIR --quiet
sweep_speed|yes|sweep scenes/reference.toml --vary speed_ratio=0.3:0.6:5 --set 'time.end=0.1' --out OUTDIR --quiet
sweep_speed_alone|no|sweep scenes/reference.toml --vary speed_ratio=0.3:0.6:5 --set 'time.end=0.1' --batch 1 --out OUTDIR --quiet
sweep_modal_exact|yes|sweep scenes/reference.toml --vary speed_ratio=0.3:0.6:5 --set 'time.end=0.1' --set 'mesh.kind="galerkin"' --set 'mesh.modes=300' --set 'integrator={method="modal_exact"}' --out OUTDIR --quiet
sweep_two_axes|no|sweep scenes/reference.toml --vary speed_ratio=0.4:0.6:3 --vary mass_ratio=0.5:2:3 --log --set 'time.end=0.1' --check-refinement --out OUTDIR --quiet
gate_golden|yes|gate golden --out OUTDIR --quiet
gate_golden_alone|no|gate golden --batch 1 --out OUTDIR --quiet
verify_quick|no|verify --quick --out OUTDIR --quiet
modes_reference|yes|modes scenes/reference.toml --out OUTDIR
modes_line|no|modes scenes/span_messenger.toml --out OUTDIR
EOF
}

# Remove what measures time from one output file, into stdout.
normalize() {
    python3 - "$1" <<'EOF'
import json, re, sys
path = sys.argv[1]
timing = re.compile(r"(^wall|_seconds$|^seconds$|^elapsed|per_second|^pareto$)")
def scrub(x):
    if isinstance(x, dict):
        return {k: ("T" if timing.search(k) else scrub(v)) for k, v in x.items()}
    if isinstance(x, list):
        return [scrub(v) for v in x]
    return x
data = open(path, "rb").read()
if path.endswith(".json"):
    try:
        text = data.decode()
        obj = json.loads(text)
    except Exception:
        sys.stdout.buffer.write(data)
        sys.exit()
    # keep the bytes when nothing is timing: a re-dump could hide a
    # difference of number formatting
    if json.dumps(scrub(obj)) == json.dumps(obj):
        sys.stdout.buffer.write(data)
    else:
        sys.stdout.write(json.dumps(scrub(obj), indent=1, sort_keys=False))
elif path.endswith(".xml"):
    sys.stdout.write(re.sub(r'time="[0-9.e+-]+"', 'time="T"', data.decode(errors="replace")))
elif path.endswith("stdout") or path.endswith("stderr"):
    # a table with a column headed `wall s` (its values, and the `*` of a
    # Pareto front drawn on them), and a header's study time
    table = None
    for line in data.decode(errors="replace").split("\n"):
        line = re.sub(r"[0-9.]+ s on ([0-9]+ threads?)", r"T s on \1", line)
        head = re.search(r"(?<!\S)wall s(?!\S)", line)
        if head:
            table = head.span()
        elif table is not None and line.strip():
            # the value under the header (aligned either way), and a
            # trailing `*`
            line = re.sub(r"\s\*$", "", line.rstrip())
            cells = list(re.finditer(r"\S+", line))
            overlap = lambda m: min(m.end(), table[1]) - max(m.start(), table[0])
            best = max(cells, key=overlap)
            if overlap(best) > 0:
                line = line[: best.start()] + "T" + line[best.end() :]
        else:
            table = None
        sys.stdout.write(line + "\n")
elif path.endswith(".csv"):
    import csv, io
    rows = list(csv.reader(io.StringIO(data.decode(errors="replace"))))
    if rows:
        # timing columns, and the Pareto front drawn on a wall time
        drop = {i for i, h in enumerate(rows[0]) if timing.search(h)}
        out = csv.writer(sys.stdout, lineterminator="\n")
        for r in rows:
            out.writerow(["T" if i in drop and r is not rows[0] else c for i, c in enumerate(r)])
else:
    sys.stdout.buffer.write(data)
EOF
}

# Files whose content is a wall time drawn, or a lock file's process id
# (skipped, named in the report).
timing_figure() {
    case "$(basename "$1")" in precision.svg | cost-time.svg | *.lock) return 0 ;; esac
    return 1
}

run_all() { # BIN DIR
    local bin=$1 dir=$2
    mkdir -p "$dir"
    cases | while IFS='|' read -r name quick args; do
        [ "$QUICK" = "--quick" ] && [ "$quick" != yes ] && continue
        local o="$dir/$name"
        rm -rf "$o"
        mkdir -p "$o/files"
        # shellcheck disable=SC2086
        eval "set -- ${args//OUTDIR/$o/files}"
        "$bin" "$@" >"$o/stdout" 2>"$o/stderr"
        echo $? >"$o/rc"
        for f in stdout stderr; do
            sed -i -E -e "s#$o/files#OUT#g" -e '/s wall|dof-steps\/s/d' "$o/$f"
        done
        echo "  $name (rc $(cat "$o/rc"))"
    done
}

if [ ! -f "$OUT/old/.done" ]; then
    echo "recording $OLD into $OUT/old"
    rm -rf "$OUT/old"
    run_all "$OLD" "$OUT/old"
    touch "$OUT/old/.done"
fi
if [ $RUN_NEW = yes ]; then
    echo "running $NEW into $OUT/new"
    rm -rf "$OUT/new"
    run_all "$NEW" "$OUT/new"
fi

status=0
same=0
skipped=()
while IFS= read -r -d '' f; do
    rel=${f#"$OUT/old/"}
    g="$OUT/new/$rel"
    [ "$QUICK" = "--quick" ] && [ ! -e "$OUT/new/${rel%%/*}" ] && continue
    if timing_figure "$f"; then
        skipped+=("$rel")
        continue
    fi
    if [ ! -e "$g" ]; then
        echo "MISSING in new: $rel"
        status=1
        continue
    fi
    if cmp -s "$f" "$g" || cmp -s <(normalize "$f") <(normalize "$g"); then
        same=$((same + 1))
    else
        echo "DIFFERS: $rel"
        diff <(normalize "$f" 2>/dev/null) <(normalize "$g" 2>/dev/null) | head -4
        status=1
    fi
done < <(find "$OUT/old" -type f ! -name .done -print0 | sort -z)
while IFS= read -r -d '' g; do
    rel=${g#"$OUT/new/"}
    [ -e "$OUT/old/$rel" ] || {
        echo "EXTRA in new: $rel"
        status=1
    }
done < <(find "$OUT/new" -type f -print0 | sort -z)
echo "same: $same files; skipped (wall times drawn): ${skipped[*]:-none}"
[ $status = 0 ] && echo "ALL SAME" || echo "SOME DIFFER"
exit $status
