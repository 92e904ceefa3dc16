#!/usr/bin/env bash
# ctest's blender.addon (tests/CMakeLists.txt): tests/blender/test_addon.py in Blender, headless.
# Skipped (exit 77) when Blender is not installed: Debian's `blender`, which `scripts/setup --test`
# installs. usage: run_test.sh ADDON.zip WORK_FOLDER
set -euo pipefail
if ! command -v blender > /dev/null 2>&1; then
  echo "blender.addon: SKIPPED: blender is not installed (apt-get install blender, or scripts/setup --test)"
  exit 77
fi
here="$(cd "$(dirname "$0")" && pwd)"
zip="$1" work="$2"
rm -rf "$work" && mkdir -p "$work/scripts" "$work/config"
# The add-on is installed into this folder, not the user's own Blender setup.
export BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_CONFIG="$work/config"
exec blender -b --factory-startup --python-exit-code 1 --python "$here/test_addon.py" -- "$zip"
