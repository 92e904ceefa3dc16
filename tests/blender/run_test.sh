#!/usr/bin/env bash
# ctest's blender.addon (tests/CMakeLists.txt): tests/blender/test_addon.py in Blender, headless.
# Skipped (exit 77) when Blender is not installed: Debian's `blender`, which `scripts/setup --test`
# installs. usage: run_test.sh ADDON.zip WORK_FOLDER [SCRIPT]   (SCRIPT default test_addon.py;
# test_addon_ict.py, ctest's blender.ict, is also skipped without the shared data folder's ict/).
set -euo pipefail
if ! command -v blender > /dev/null 2>&1; then
  echo "blender.addon: SKIPPED: blender is not installed (apt-get install blender, or scripts/setup --test)"
  exit 77
fi
here="$(cd "$(dirname "$0")" && pwd)"
zip="$1" work="$2" script="${3:-test_addon.py}"
if [ "$script" = test_addon_ict.py ]; then
  found=""
  for d in "${MYOSHELL_DATA:-}" "${MYO_SHARED_DIR:+$MYO_SHARED_DIR/data}" "$here/../../../shared/data"; do
    if [ -n "$d" ] && [ -d "$d/ict" ]; then found="$d"; fi
  done
  if [ -z "$found" ]; then
    echo "blender.ict: SKIPPED: the shared data folder (../shared/data with ict/) is absent; set MYOSHELL_DATA"
    exit 77
  fi
fi
rm -rf "$work" && mkdir -p "$work/scripts" "$work/config"
# The add-on is installed into this folder, not the user's own Blender setup.
export BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_CONFIG="$work/config"
exec blender -b --factory-startup --python-exit-code 1 --python "$here/$script" -- "$zip"
