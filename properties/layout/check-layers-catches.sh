#!/usr/bin/env bash
# The layer check must fail on a planted violation: a scratch tree whose core includes a
# model header and <vector>. Without this, a check-layers that never fails would pass.
set -euo pipefail
src=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/core/x" "$tmp/protocol/codec" "$tmp/firmware" "$tmp/ci"
cp "$src/ci/check-layers" "$tmp/ci/"
printf '#include "core/ok.hpp"\n#include <cstdint>\n' > "$tmp/core/x/good.hpp"
"$tmp/ci/check-layers" "$tmp" || { echo "clean tree rejected"; exit 1; }
printf '#include "models/tmc2130/device.hpp"\n' > "$tmp/core/x/bad1.hpp"
if "$tmp/ci/check-layers" "$tmp"; then echo "model include not caught"; exit 1; fi
rm "$tmp/core/x/bad1.hpp"
printf '#include <vector>\n' > "$tmp/core/x/bad2.hpp"
if "$tmp/ci/check-layers" "$tmp"; then echo "<vector> not caught"; exit 1; fi
echo "planted violations caught"
