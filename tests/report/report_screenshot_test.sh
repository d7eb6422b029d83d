#!/usr/bin/env bash
# Opens a sample report.html in headless Chromium and checks the screenshot: the page is not blank
# and both charts drew (many pixels of the first two series colours).
#
# Usage: report_screenshot_test.sh REPORT_TESTS [WORK_DIR [MAKER MAKER_TEST]]
#   REPORT_TESTS  the report_tests executable: its SampleReport test writes the report (two SVG
#               charts and a comparison sheet) and its ReportScreenshot test checks the screenshot.
#   WORK_DIR    where report/ and screenshot.png go (default: a new temporary folder, kept).
#   MAKER, MAKER_TEST  another gtest executable and the one test of it that writes the report into
#               $VKSPLAT_SAMPLE_REPORT_DIR instead (e.g. sweep_tests and the sweep's report); its
#               first two series colours must show as well.
#
# Without a Chromium (chromium, chromium-browser, google-chrome) on PATH the test is skipped: it
# prints "SKIPPED: ..." and exits with $VKSPLAT_SKIP_EXIT_CODE, 0 unless set (set it to 77 and give
# the CTest test SKIP_RETURN_CODE 77 to have CTest count it as skipped).
set -euo pipefail

if [[ $# -lt 1 || $# -gt 4 || $# -eq 3 ]]; then
    echo "usage: $0 REPORT_TESTS [WORK_DIR [MAKER MAKER_TEST]]" >&2
    exit 2
fi
report_tests=$1
work=${2:-$(mktemp -d "${TMPDIR:-/tmp}/vksplat_report_screenshot.XXXXXX")}
skip_code=${VKSPLAT_SKIP_EXIT_CODE:-0}
maker=${3:-$report_tests}
maker_test=${4:-SampleReport.WritesAReportWithTwoChartsAndASheet}

browser=""
for candidate in chromium chromium-browser google-chrome google-chrome-stable; do
    if command -v "$candidate" >/dev/null 2>&1; then
        browser=$(command -v "$candidate")
        break
    fi
done
if [[ -z $browser ]]; then
    echo "SKIPPED: no Chromium found (tried chromium, chromium-browser, google-chrome);" \
         "install one (Debian: apt-get install chromium) to run this test"
    exit "$skip_code"
fi
for executable in "$report_tests" "$maker"; do
    if [[ ! -x $executable ]]; then
        echo "FAIL: $executable is not an executable" >&2
        exit 1
    fi
done

mkdir -p "$work"
work=$(cd "$work" && pwd)
rm -rf "$work/report" "$work/screenshot.png"

# Runs one gtest of an executable and insists that it ran and passed (a filter matching nothing passes).
run_gtest() {
    local tests=$1 filter=$2 log=$3
    shift 3
    if ! env "$@" "$tests" --gtest_filter="$filter" >"$log" 2>&1 ||
        ! grep -q '^\[  PASSED  \] 1 test' "$log" || grep -q '^\[  SKIPPED \]' "$log"; then
        cat "$log" >&2
        echo "FAIL: $filter did not pass (log: $log)" >&2
        exit 1
    fi
}

run_gtest "$maker" "$maker_test" "$work/make_report.log" \
    VKSPLAT_SAMPLE_REPORT_DIR="$work/report"

profile=$(mktemp -d "${TMPDIR:-/tmp}/vksplat_chromium_profile.XXXXXX")
trap 'rm -rf "$profile"' EXIT
status=0
timeout 180 "$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --screenshot="$work/screenshot.png" --window-size=1200,1600 \
    "file://$work/report/report.html" >"$work/chromium.log" 2>&1 || status=$?
if [[ ! -s $work/screenshot.png ]]; then
    tail -n 30 "$work/chromium.log" >&2
    echo "FAIL: $browser wrote no screenshot (exit status $status; log: $work/chromium.log)" >&2
    exit 1
fi

run_gtest "$report_tests" 'ReportScreenshot.FindsBothChartColoursOnlyWhenTheyAreThere' "$work/check.log" \
    VKSPLAT_REPORT_SCREENSHOT="$work/screenshot.png"
grep '^screenshot ' "$work/check.log" || true
echo "PASS: $work/screenshot.png shows the report ($maker_test) and its charts"
