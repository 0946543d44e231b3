#!/usr/bin/env bash
# Screenshot of a report as a reader sees it on a laptop: headless Chromium, 1366 px wide, the
# whole page long.
#   bash scripts/screenshot.sh REPORT.html OUT.png
# The page's height is measured first (the report loaded in a frame of a small measuring page,
# which prints it); the screenshot is then taken at that height. Exit 1 if Chromium is missing.
set -euo pipefail

report=$(realpath "$1")
out=$2
width=1366
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
  echo "screenshot: Chromium is not installed (apt-get install chromium)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
flags=(--headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --disable-sync
       --disable-background-networking --disable-component-update --user-data-dir="$work/profile")

cat > "$work/measure.html" <<EOF
<!DOCTYPE html><html><body><iframe id="page" src="file://$report" style="width:${width}px;height:600px"></iframe>
<pre id="size"></pre><script>
document.getElementById('page').onload = () => {
  const root = document.getElementById('page').contentDocument.documentElement;
  document.getElementById('size').textContent = 'HEIGHT=' + root.scrollHeight;
};
</script></body></html>
EOF
height=$("$chromium" "${flags[@]}" --allow-file-access-from-files --virtual-time-budget=5000 \
  --dump-dom "file://$work/measure.html" 2>/dev/null | sed -n 's/.*HEIGHT=\([0-9]*\).*/\1/p')
height=${height:-12000}
"$chromium" "${flags[@]}" --window-size="$width,$height" --virtual-time-budget=5000 \
  --screenshot="$out" "file://$report" 2>/dev/null
echo "screenshot: $out (${width}×${height} px)"
