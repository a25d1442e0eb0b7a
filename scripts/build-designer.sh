#!/usr/bin/env bash
# Refresh the designer's vendored JavaScript (src/curvefold/app/designer/static/vendor/, kept
# in git) from npm: installs frontend/'s packages at the versions frontend/package-lock.json
# pins (npm ci, which also brings the designer's ESLint) and copies each file that the
# "vendor" map of frontend/package.json names. Run after changing the pinned three.js, then
# commit the vendored files; installing curvefold never needs npm.
set -euo pipefail
cd "$(dirname "$0")/.."
npm ci --prefix frontend --no-audit --no-fund --loglevel=error
vendor=src/curvefold/app/designer/static/vendor
rm -rf "$vendor"
node --input-type=module - "$vendor" <<'JS'
import { cpSync, readFileSync } from "node:fs";
import { join } from "node:path";
const vendor = process.argv[2];
const { vendor: files } = JSON.parse(readFileSync("frontend/package.json", "utf8"));
for (const [name, from] of Object.entries(files)) {
  cpSync(join("frontend/node_modules", from), join(vendor, name));
}
JS
echo "vendored $(find "$vendor" -type f | wc -l) files into $vendor"
