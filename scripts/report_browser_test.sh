#!/usr/bin/env bash
# taut report in a real browser: makes the outputs of the reference run, a
# compare (methods that chatter beside one that does not), a convergence
# ladder, an uncertainty family, a tolerance sweep, a line, a
# form-finding run, a work-precision grid and a sweep run in two shards and
# merged, at small settings (about 20 s of runs on 2 cores),
# writes one report.html of them (taut report), opens it in headless
# Chromium at 1400 px wide (Debian's `chromium` package, installed here
# with apt-get the way scripts/slurm_test.sh installs Slurm) and checks that
#   * every folder has its section, headed by the command that wrote it,
#     after a first section of verdicts with a row per folder,
#   * nothing is wider than the window: no horizontal scrolling
#     (document.documentElement.scrollWidth <= 1400), on screen and with
#     the page's print style at the width of an A4 page,
#   * the page loads with no console error and no failed request,
#   * every figure is an image that decoded, has a non-zero size, and
#     there is one per plot file,
#   * the page fetches nothing (no http(s) URL in it);
# then keeps screenshots, out/report/report.png (the top) and
# out/report/report-full.png (the whole page), one of each plot file,
# out/report/plots/FOLDER-NAME.png, and the page,
# out/report/report.html. Last it makes a report of a tampered folder (a
# plot with a script, an onload handler, a javascript: iframe and images
# on a local HTTP server; a table with markup in a cell), opens that page
# as it is and checks that no script ran (the title is unchanged, nothing
# added to the page) and that no request reached the server.
#
# Usage: scripts/report_browser_test.sh [TAUT_BINARY]   (default target/release/taut)
# Skips (exit 0) with a clear message only where Chromium cannot be had:
# not root or no apt-get, or the package does not install.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
TAUT_BIN="$(realpath "${1:-$ROOT/target/release/taut}")"
OUT="$ROOT/out/report"

skip() {
  echo "report browser test: SKIPPED: $*"
  exit 0
}
fail() {
  echo "report browser test: FAILED: $*" >&2
  exit 1
}
[ -x "$TAUT_BIN" ] || fail "no taut binary at $TAUT_BIN (build it first)"

# --- the browser ------------------------------------------------------------
if ! command -v chromium >/dev/null; then
  [ "$(id -u)" = 0 ] || skip "needs root to install Debian's chromium package"
  command -v apt-get >/dev/null || skip "no apt-get to install Debian's chromium package"
  echo "report browser test: installing chromium (apt-get)"
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
    --no-install-recommends chromium fonts-dejavu-core) >/tmp/taut-chromium-apt.log 2>&1 \
    || skip "the chromium package did not install (log: /tmp/taut-chromium-apt.log)"
fi
CHROMIUM=(chromium --headless --no-sandbox --disable-gpu --disable-extensions
  --no-first-run --disable-background-networking --disable-sync
  --disable-component-update --user-data-dir="$(mktemp -d /tmp/taut-chromium.XXXXXX)")

# --- the outputs ---------------------------------------------------------------
rm -rf "$OUT" && mkdir -p "$OUT"
cd "$ROOT"
t() { "$TAUT_BIN" "$@" --quiet >/dev/null; }
SHORT=(--set time.end=0.3)
t run scenes/reference.toml --out "$OUT/run"
t compare scenes/reference.toml --methods newmark,hht,generalized_alpha \
  --formulations lagrange,penalty "${SHORT[@]}" --out "$OUT/compare"
t converge scenes/moving_force_beam.toml --refine step --levels 3 --out "$OUT/converge"
t uncertainty scenes/reference.toml --levels 3 "${SHORT[@]}" --out "$OUT/uncertainty"
t sweep scenes/reference.toml --vary speed_ratio=0.6:1.2:3 "${SHORT[@]}" \
  --tolerance 0.05 --out "$OUT/tolerance"
t run scenes/line_10_spans.toml --set time.end=1.0 --set output.envelope=true \
  --set 'analysis.spans=[0, 1]' --out "$OUT/line"
t run scenes/catenary_designed.toml --set time.end=0.5 --out "$OUT/form"
t precision scenes/reference.toml --levels 2 --formulations lagrange,penalty "${SHORT[@]}" \
  --out "$OUT/precision"
# a 2-D sweep checked under refinement, run in two shards and merged
for s in 0 1; do
  t sweep scenes/reference.toml --vary speed_ratio=0.6:1.2:3 --vary beam.tension=1.5e4:2.5e4:2 \
    --check-refinement "${SHORT[@]}" --shard "$s/2" --out "$OUT/shards/$s"
done
"$TAUT_BIN" merge "$OUT/shards/0" "$OUT/shards/1" --out "$OUT/merge" >/dev/null
FOLDERS=(run compare converge uncertainty tolerance line form precision merge)
# the command each folder's section names
COMMANDS=("taut run" "taut compare" "taut converge" "taut uncertainty"
  "taut sweep --tolerance" "taut run (line)" "taut run (line, form-finding)"
  "taut precision" "taut merge")
"$TAUT_BIN" report "${FOLDERS[@]/#/$OUT/}" --out "$OUT/report.html" >/dev/null
PAGE="$OUT/report.html"
plots=$(ls "$OUT"/*/*.svg | wc -l)
# every section, with its command, and the verdicts first
grep -q '<section id="verdicts"><h2>Verdicts</h2>' "$PAGE" || fail "no verdicts section"
for k in "${!FOLDERS[@]}"; do
  grep -q "<section id=\"f$k\">" "$PAGE" || fail "no section for ${FOLDERS[$k]}"
  grep -qF "<h3>${COMMANDS[$k]}</h3>" "$PAGE" || fail "the ${FOLDERS[$k]} section does not name ${COMMANDS[$k]}"
done
for f in tolerance.svg uncertainty.csv static_heights.csv droppers_static.csv compare.csv converge.csv; do
  grep -qF "$f" "$PAGE" || fail "$f is not on the page"
done

# --- nothing to fetch ------------------------------------------------------------
if grep -Eq '(src|href)="(https?:)?//' "$PAGE"; then
  fail "the page links something outside itself: $(grep -Eo '(src|href)="(https?:)?//[^"]*' "$PAGE" | head -3)"
fi

# --- in the browser: console errors and figure sizes -----------------------------
# a copy of the page with a checker first in <head>: it records every
# console error, uncaught error and failed resource, and once the page has
# loaded writes what it found into <pre id="taut-check"> (read from the DOM
# Chromium dumps). It comes before the page's Content-Security-Policy
# <meta>, which applies only to what follows it, so the checker runs while
# the page's own content is held to the policy (a plot the policy blocked
# would count as an image that did not decode).
CHECK="$OUT/check.html"
python3 - "$PAGE" "$CHECK" <<'PY'
import sys
page, check = sys.argv[1], sys.argv[2]
html = open(page, encoding="utf-8").read()
probe = """<script>
(function () {
  var errors = [];
  var error = console.error;
  console.error = function () { errors.push(Array.prototype.join.call(arguments, ' ')); error.apply(console, arguments); };
  window.addEventListener('error', function (e) { errors.push('error: ' + (e.message || (e.target && (e.target.src || e.target.href)) || e.type)); }, true);
  window.addEventListener('load', function () {
    var figs = document.querySelectorAll('figure img');
    var zero = 0, sizes = [];
    for (var i = 0; i < figs.length; i++) {
      var r = figs[i].getBoundingClientRect();
      if (!(r.width > 0 && r.height > 0 && figs[i].complete && figs[i].naturalWidth > 0)) zero++;
      sizes.push(Math.round(r.width) + 'x' + Math.round(r.height));
    }
    // anything wider than the window: the page scrolls sideways
    var vw = document.documentElement.clientWidth, wide = [];
    var all = document.body.getElementsByTagName('*');
    for (var j = 0; j < all.length && wide.length < 3; j++) {
      var b = all[j].getBoundingClientRect();
      if (b.right > vw + 0.5) wide.push(all[j].tagName + '(' + Math.round(b.right) + ')');
    }
    var pre = document.createElement('pre');
    pre.id = 'taut-check';
    pre.textContent = 'figures=' + figs.length + ' zero=' + zero + ' errors=' + errors.length +
      ' sections=' + document.querySelectorAll('section').length +
      ' scroll=' + document.documentElement.scrollWidth + ' view=' + vw +
      ' wide=' + (wide.join(',') || 'none') +
      ' sizes=' + sizes.join(',') + (errors.length ? ' first=' + errors[0] : '');
    document.body.appendChild(pre);
  });
})();
</script>"""
open(check, "w", encoding="utf-8").write(html.replace("<head>", "<head>\n" + probe, 1))
# the same with the page's print style applied on screen
printed = html.replace("@media print{", "@media all{", 1)
open(check.replace(".html", ".print.html"), "w", encoding="utf-8").write(printed.replace("<head>", "<head>\n" + probe, 1))
PY
DOM="$OUT/check.dom.html"
"${CHROMIUM[@]}" --enable-logging=stderr --v=0 --virtual-time-budget=10000 \
  --hide-scrollbars --window-size=1400,2000 \
  --dump-dom "file://$CHECK" >"$DOM" 2>"$OUT/chromium.log" \
  || fail "chromium could not load the page (log: $OUT/chromium.log)"
line=$(grep -o 'figures=[0-9][^<]*' "$DOM" | tail -1 || true)
[ -n "$line" ] || fail "the page's checker did not run (DOM: $DOM, log: $OUT/chromium.log)"
echo "report browser test: $line" | cut -c1-300
figures=$(echo "$line" | sed -E 's/.*figures=([0-9]+).*/\1/')
zero=$(echo "$line" | sed -E 's/.*zero=([0-9]+).*/\1/')
errors=$(echo "$line" | sed -E 's/.*errors=([0-9]+).*/\1/')
sections=$(echo "$line" | sed -E 's/.*sections=([0-9]+).*/\1/')
scroll=$(echo "$line" | sed -E 's/.*scroll=([0-9]+).*/\1/')
[ "$sections" = $((${#FOLDERS[@]} + 1)) ] || fail "$sections sections for ${#FOLDERS[@]} folders and the verdicts"
[ "$scroll" -le 1400 ] || fail "the page scrolls sideways at 1400 px: $(echo "$line" | grep -o 'scroll=[^ ]* view=[^ ]* wide=[^ ]*')"
echo "$line" | grep -q 'wide=none' || fail "elements wider than the window: $(echo "$line" | grep -o 'wide=[^ ]*')"
# in print: the print style at an A4 page's width (210 mm at 96 px/in)
PDOM="$OUT/check.print.dom.html"
"${CHROMIUM[@]}" --virtual-time-budget=10000 --hide-scrollbars --window-size=794,1123 \
  --dump-dom "file://${CHECK%.html}.print.html" >"$PDOM" 2>>"$OUT/chromium.log" \
  || fail "chromium could not load the print copy"
pline=$(grep -o 'figures=[0-9][^<]*' "$PDOM" | tail -1 || true)
pscroll=$(echo "$pline" | sed -E 's/.*scroll=([0-9]+).*/\1/')
[ -n "$pline" ] && [ "$pscroll" -le 794 ] \
  || fail "in print the page is wider than A4: $(echo "$pline" | grep -o 'scroll=[^ ]* view=[^ ]* wide=[^ ]*')"
rm -f "$PDOM" "${CHECK%.html}.print.html"
[ "$figures" = "$plots" ] || fail "$figures figures in the page for $plots plot files"
[ "$zero" = 0 ] || fail "$zero figures have no size or did not decode"
[ "$errors" = 0 ] || fail "console errors: $line"
# what Chromium itself logged of the page's console (not its own start-up)
if grep -E 'CONSOLE\(|Uncaught' "$OUT/chromium.log" | grep -qv 'taut-check'; then
  fail "console messages: $(grep -E 'CONSOLE\(|Uncaught' "$OUT/chromium.log" | head -3)"
fi

# --- a picture of it -----------------------------------------------------------------
"${CHROMIUM[@]}" --hide-scrollbars --window-size=1400,2400 \
  --screenshot="$OUT/report.png" "file://$PAGE" >/dev/null 2>>"$OUT/chromium.log" \
  || fail "no screenshot (log: $OUT/chromium.log)"
[ -s "$OUT/report.png" ] || fail "the screenshot is empty"
# the whole page: as tall as its content at 1400 px (from the checker's
# DOM: the page's height is not known before it is laid out), capped
"${CHROMIUM[@]}" --hide-scrollbars --window-size=1400,16000 \
  --screenshot="$OUT/report-full.png" "file://$PAGE" >/dev/null 2>>"$OUT/chromium.log" \
  || fail "no full-page screenshot (log: $OUT/chromium.log)"
rm -f "$CHECK" "$DOM"

# --- a picture of each plot --------------------------------------------------------
# every plot file as the browser draws it, at its own size, kept as
# out/report/plots/FOLDER-NAME.png for a person to look at (that each
# kind's legend lies beside its data, with distinct series, is checked from
# the SVGs by `cargo test -p taut --lib report::legend_check`); a screenshot
# of a few kB is a blank page
mkdir -p "$OUT/plots"
shots=0
for svg in "$OUT"/*/*.svg; do
  size=$(head -c 400 "$svg" | grep -o 'width="[0-9]*" height="[0-9]*"' | head -1 \
    | sed -E 's/width="([0-9]+)" height="([0-9]+)"/\1,\2/')
  [ -n "$size" ] || fail "$svg names no size"
  png="$OUT/plots/$(basename "$(dirname "$svg")")-$(basename "$svg" .svg).png"
  "${CHROMIUM[@]}" --hide-scrollbars --window-size="$size" --screenshot="$png" \
    "file://$svg" >/dev/null 2>>"$OUT/chromium.log" || fail "no screenshot of $svg"
  [ "$(stat -c %s "$png")" -gt 8000 ] || fail "the screenshot of $svg is blank ($png)"
  shots=$((shots + 1))
done
echo "report browser test: $shots plots kept as pictures in $OUT/plots"

# --- a tampered folder -----------------------------------------------------------------
# the run's folder with a hostile plot and table, and a local HTTP server
# that logs every request the page might make
BAD="$OUT/tampered"
cp -r "$OUT/run" "$BAD"
rm -f "$BAD/report.html"
PORT=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
HITS="$OUT/tampered.requests.log"
: >"$HITS"
python3 - "$PORT" "$HITS" <<'PY' &
import http.server, sys
port, log = int(sys.argv[1]), sys.argv[2]
class H(http.server.BaseHTTPRequestHandler):
    def do_GET(self):
        open(log, "a").write(self.path + "\n")
        self.send_response(204)
        self.end_headers()
    def log_message(self, *a):
        pass
http.server.HTTPServer(("127.0.0.1", port), H).serve_forever()
PY
SERVER=$!
trap 'kill "$SERVER" 2>/dev/null || true' EXIT
URL="http://127.0.0.1:$PORT"
sleep 1
# the server answers (else "no request" would prove nothing)
python3 -c "import urllib.request; urllib.request.urlopen('$URL/probe')" \
  || fail "the local HTTP server did not start"
grep -q '^/probe$' "$HITS" || fail "the local HTTP server logs no request"
: >"$HITS"
cat >"$BAD/force.svg" <<SVG
<?xml version="1.0"?>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="960" height="480" viewBox="0 0 960 480" onload="document.title='pwned-onload'">
<script>document.title='pwned-script';new Image().src='$URL/script';</script>
<foreignObject width="960" height="100"><iframe xmlns="http://www.w3.org/1999/xhtml" src="javascript:parent.document.title='pwned-iframe'"></iframe></foreignObject>
<image href="$URL/image" xlink:href="$URL/xlink" width="10" height="10"/>
<rect x="0" y="0" width="960" height="480" fill="#1f77b4"/>
</svg>
SVG
printf 'span,force_mean_N\n0,"<script>document.title=\x27pwned-cell\x27</script>"\n1,<img src=%s/cell>\n' "$URL" >"$BAD/spans.csv"
"$TAUT_BIN" report "$BAD" --out "$OUT/tampered.html" >/dev/null 2>"$OUT/tampered.stderr" \
  || fail "no report of the tampered folder ($OUT/tampered.stderr)"
# the page as written: no markup from the folder in it (its text, escaped,
# may be: `&lt;img src=http…` is a table cell's text)
if sed -E 's|;base64,[A-Za-z0-9+/=]*|;base64,|g' "$OUT/tampered.html" \
  | grep -Eiq '<script|<iframe|<[a-z]+ [^>]*(src|href)="?https?:|javascript:|onload='; then
  fail "the tampered folder's markup reached the page: $OUT/tampered.html"
fi
TDOM="$OUT/tampered.dom.html"
"${CHROMIUM[@]}" --virtual-time-budget=5000 --dump-dom "file://$OUT/tampered.html" >"$TDOM" \
  2>>"$OUT/chromium.log" || fail "chromium could not load the tampered page (log: $OUT/chromium.log)"
grep -q '<title>taut report</title>' "$TDOM" \
  || fail "a script ran in the tampered page: $(grep -o '<title>[^<]*' "$TDOM")"
# every hostile script sets the title to pwned-…; the folder's text may
# hold the word (escaped, in a cell), the DOM no element of its markup
if grep -Eiq '<script|<iframe|<foreignObject' "$TDOM"; then
  fail "the tampered folder's markup is in the page's DOM ($TDOM)"
fi
grep -q 'data:image/svg+xml;base64,' "$TDOM" || fail "the tampered plot is not in the page as an image"
"${CHROMIUM[@]}" --hide-scrollbars --window-size=1280,1600 \
  --screenshot="$OUT/tampered.png" "file://$OUT/tampered.html" >/dev/null 2>>"$OUT/chromium.log" \
  || fail "no screenshot of the tampered page (log: $OUT/chromium.log)"
sleep 1
if [ -s "$HITS" ]; then fail "the tampered page made requests: $(head -3 "$HITS" | tr '\n' ' ')"; fi
kill "$SERVER" 2>/dev/null || true
rm -f "$TDOM"
echo "report browser test: passed: ${#FOLDERS[@]} folders' sections and the verdicts, $figures figures, none empty, no console error, nothing wider than 1400 px (scroll width $scroll) or an A4 page in print ($pscroll); screenshots $OUT/report.png, $OUT/report-full.png; tampered folder: no script ran, no request left the page"
