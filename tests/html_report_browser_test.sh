#!/usr/bin/env bash
# Browser test of the HTML report: renders `dpscope report -T html samples/faults.pcap` in
# headless Chromium and measures the layout inside the page (an injected script writes its
# results into <pre id="checks">, read back with --dump-dom), then takes a screenshot.
# Usage: html_report_browser_test.sh DPSCOPE SOURCE_DIR
# Exit code 77 (skipped) when /usr/bin/chromium is missing.
set -euo pipefail

dpscope=${1:?usage: html_report_browser_test.sh DPSCOPE SOURCE_DIR}
source_dir=${2:?usage: html_report_browser_test.sh DPSCOPE SOURCE_DIR}
chromium=/usr/bin/chromium

if [[ ! -x $chromium ]]; then
    echo "SKIP: $chromium is not installed"
    exit 77
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/dpscope-browser.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

browser() {
    timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --user-data-dir="$tmp/profile" --window-size=1200,900 "$@" 2>"$tmp/chromium.log"
}

# ---- the report ------------------------------------------------------------------------------

report=$tmp/report.html
set +e
(cd "$source_dir" && TZ=UTC LANG=C LC_ALL=C "$dpscope" report -T html -w "$report" \
    samples/faults.pcap)
status=$?
set -e
[[ $status -eq 1 ]] || fail "dpscope report exited with $status, expected 1 (errors found)"
[[ -s $report ]] || fail "no report written"
grep -q '</body>' "$report" || fail "the report has no </body>"

# What the file declares, per slave section in order: latency bars and timeline bars.
count_per_svg() {  # $1: svg class, $2: rect class
    awk -v svg="<svg class=\"$1\"" -v rect="<rect class=\"$2\"" '
        index($0, svg) { inside = 1; n = 0; next }
        inside && index($0, rect) { n++ }
        inside && index($0, "</svg>") { printf "%s%d", (out++ ? "," : ""), n; inside = 0 }
    ' "$report"
}
latency_bars=$(count_per_svg latency bar)
timeline_bars=$(count_per_svg timeline tx)
echo "declared latency bars per slave: [$latency_bars], timeline bars: [$timeline_bars]"
[[ $latency_bars =~ ^[0-9]+,[0-9]+,[0-9]+$ ]] || fail "expected three latency histograms"
[[ $timeline_bars =~ ^[0-9]+,[0-9]+,[0-9]+$ ]] || fail "expected three timelines"

# ---- the measuring script --------------------------------------------------------------------

cat >"$tmp/checks.js" <<EOF
(function () {
    var expectedLatencyBars = [$latency_bars];
    var expectedTimelineBars = [$timeline_bars];
    var out = [];
    function check(name, ok, detail) {
        out.push((ok ? 'PASS ' : 'FAIL ') + name + (detail === undefined ? '' : ' [' + detail + ']'));
    }
    function box(el) { return el.getBoundingClientRect(); }
    function inside(inner, outer) {
        return inner.left >= outer.left - 0.5 && inner.right <= outer.right + 0.5 &&
               inner.top >= outer.top - 0.5 && inner.bottom <= outer.bottom + 0.5;
    }
    function overlaps(a, b) {
        return a.left < b.right - 0.5 && b.left < a.right - 0.5 &&
               a.top < b.bottom - 0.5 && b.top < a.bottom - 0.5;
    }
    function visible(el) {
        var r = box(el), style = getComputedStyle(el);
        return r.width > 0 && r.height > 0 && style.visibility !== 'hidden' &&
               style.display !== 'none' && parseFloat(style.opacity) > 0;
    }
    // Bars of a chart: all drawn with a positive size inside the chart; labels inside the chart
    // and clear of the bars.
    function chart(name, svg, barSelector, expected) {
        var r = box(svg);
        check(name + '.width>600', r.width > 600, r.width);
        check(name + '.height>100', r.height > 100, r.height);
        var bars = svg.querySelectorAll(barSelector);
        check(name + '.bars=' + expected, bars.length === expected && expected > 0, bars.length);
        var drawn = 0, within = 0;
        bars.forEach(function (bar) {
            var b = box(bar);
            if (b.width > 0 && b.height > 0) drawn++;
            if (inside(b, r)) within++;
        });
        check(name + '.bars.drawn', drawn === bars.length, drawn);
        check(name + '.bars.inside', within === bars.length, within);
        var labels = svg.querySelectorAll('text'), clipped = [], covered = [];
        var rects = svg.querySelectorAll('rect');
        labels.forEach(function (label, j) {
            var t = box(label);
            if (!inside(t, r)) clipped.push(label.textContent);
            rects.forEach(function (rect) {
                if (overlaps(t, box(rect))) covered.push(label.textContent);
            });
            labels.forEach(function (other, k) {
                if (k > j && overlaps(t, box(other)))
                    covered.push(label.textContent + '/' + other.textContent);
            });
        });
        check(name + '.labels.inside', labels.length > 0 && clipped.length === 0, clipped.join('|'));
        check(name + '.labels.clear', covered.length === 0, covered.join('|'));
    }

    var sections = document.querySelectorAll('section.station');
    check('stations=3', sections.length === 3, sections.length);
    sections.forEach(function (section, i) {
        var name = 'station' + i;
        var r = box(section);
        check(name + '.height>0', r.height > 0, r.height);
        var latency = section.querySelectorAll('svg.latency');
        var timeline = section.querySelectorAll('svg.timeline');
        check(name + '.latency=1', latency.length === 1, latency.length);
        check(name + '.timeline=1', timeline.length === 1, timeline.length);
        if (latency.length === 1)
            chart(name + '.latency', latency[0], 'rect.bar', expectedLatencyBars[i]);
        if (timeline.length === 1)
            chart(name + '.timeline', timeline[0], 'rect.tx', expectedTimelineBars[i]);
        if (latency.length === 1 && timeline.length === 1)
            check(name + '.charts.inside', inside(box(latency[0]), r) && inside(box(timeline[0]), r));
    });

    var tables = document.querySelectorAll('table.findings');
    check('findings.table=1', tables.length === 1, tables.length);
    if (tables.length === 1) {
        var rows = tables[0].querySelectorAll('tr');
        var findings = 0, shown = 0;
        rows.forEach(function (row) {
            if (row.querySelector('td')) {
                findings++;
                if (visible(row)) shown++;
            }
        });
        check('findings.rows=20', findings === 20, findings);
        check('findings.rows.visible', shown === findings, shown);
        var table = box(tables[0]);
        check('findings.table.fits', table.right <= window.innerWidth, table.right);
    }

    var verdict = document.getElementById('verdict');
    check('verdict.exists', verdict !== null);
    if (verdict) {
        check('verdict.visible', visible(verdict));
        check('verdict.FAIL', verdict.textContent.indexOf('FAIL') === 0, verdict.textContent);
        check('verdict.styled', getComputedStyle(verdict).backgroundColor === 'rgb(253, 232, 232)',
              getComputedStyle(verdict).backgroundColor);
    }

    var root = document.documentElement;
    check('no.horizontal.overflow', root.scrollWidth <= window.innerWidth,
          'scrollWidth ' + root.scrollWidth + ', innerWidth ' + window.innerWidth);
    var wide = [];
    document.querySelectorAll('body *').forEach(function (el) {
        var b = box(el);
        if (b.width > 0 && b.right > window.innerWidth + 0.5) wide.push(el.tagName);
    });
    check('no.element.beyond.viewport', wide.length === 0, wide.slice(0, 5).join(','));

    var pre = document.createElement('pre');
    pre.id = 'checks';
    pre.textContent = out.join('\n') + '\nCHECKS DONE';
    document.body.appendChild(pre);
})();
EOF

page=$tmp/measured.html
awk -v script="$tmp/checks.js" '
    !done && index($0, "</body>") {
        print "<script>"
        while ((getline line < script) > 0) print line
        print "</script>"
        done = 1
    }
    { print }
' "$report" >"$page"
grep -q '<script>' "$page" || fail "the script was not injected"

# ---- run it in the browser -------------------------------------------------------------------

browser --dump-dom "file://$page" >"$tmp/dom.html" || {
    cat "$tmp/chromium.log" >&2
    fail "chromium --dump-dom failed"
}
# The checks as the browser left them in <pre id="checks"> (text, so '>' appears as &gt;).
sed -n '/<pre id="checks">/,/CHECKS DONE/p' "$tmp/dom.html" | sed 's/.*<pre id="checks">//' \
    >"$tmp/checks.txt"
cat "$tmp/checks.txt"
grep -q 'CHECKS DONE' "$tmp/checks.txt" || fail "the checks did not run in the page"
if grep -q '^FAIL ' "$tmp/checks.txt"; then
    fail "layout checks failed: $(grep '^FAIL ' "$tmp/checks.txt" | tr '\n' ';')"
fi
for expected in 'stations=3' 'findings.rows=20' 'verdict.FAIL' 'verdict.visible' \
    'no.horizontal.overflow' 'station0.latency.bars=' 'station2.timeline.bars='; do
    grep -q "^PASS $expected" "$tmp/checks.txt" || fail "no passing check $expected"
done
passed=$(grep -c '^PASS ' "$tmp/checks.txt")
[[ $passed -ge 60 ]] || fail "only $passed checks passed"

# ---- a screenshot of the report itself -------------------------------------------------------

shot=$tmp/report.png
(cd "$tmp" && browser --screenshot="$shot" "file://$report") || {
    cat "$tmp/chromium.log" >&2
    fail "chromium --screenshot failed"
}
[[ -f $shot ]] || fail "no screenshot"
[[ $(head -c 8 "$shot" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "not a PNG"
size=$(stat -c %s "$shot")
[[ $size -gt 20000 ]] || fail "screenshot of only $size bytes: an empty page?"

echo "PASS: $passed layout checks, screenshot $size bytes"
