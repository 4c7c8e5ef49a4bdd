#!/usr/bin/env bash
# Installs sorgui's launcher, icons, file types and AppStream metadata for the current user
# (XDG base directories: $XDG_DATA_HOME, by default ~/.local/share), or removes them:
#
#   bash packaging/install-desktop.sh [--exec PATH]   install (PATH: the sorgui executable,
#                                                      default: `sorgui` on PATH, else .venv/bin/sorgui)
#   bash packaging/install-desktop.sh --uninstall     remove what the install put there
#
# sorgui itself is installed with pip (see the README); this only makes the desktop find it.
set -euo pipefail
APP_ID=org.sorgui.Sorgui
HERE="$(cd "$(dirname "$0")/.." && pwd)"
RES="$HERE/resources"
DATA="${XDG_DATA_HOME:-$HOME/.local/share}"
SIZES="16 24 32 48 64 128 256 512"

installed_files() {
  echo "$DATA/applications/$APP_ID.desktop"
  echo "$DATA/metainfo/$APP_ID.metainfo.xml"
  echo "$DATA/mime/packages/$APP_ID.xml"
  echo "$DATA/icons/hicolor/scalable/apps/$APP_ID.svg"
  for size in $SIZES; do echo "$DATA/icons/hicolor/${size}x${size}/apps/$APP_ID.png"; done
}

refresh() {
  # Caches of the desktop, where the tools exist; a missing tool only delays what the desktop sees.
  if command -v update-desktop-database >/dev/null; then update-desktop-database -q "$DATA/applications" || true; fi
  if command -v update-mime-database >/dev/null; then update-mime-database "$DATA/mime" >/dev/null || true; fi
  if command -v gtk-update-icon-cache >/dev/null && [ -f "$DATA/icons/hicolor/index.theme" ]; then
    gtk-update-icon-cache -q -t "$DATA/icons/hicolor" || true
  fi
}

uninstall() {
  local removed=0
  while read -r file; do
    if [ -e "$file" ]; then rm -f "$file"; removed=$((removed + 1)); fi
  done < <(installed_files)
  refresh
  echo "sorgui: removed $removed files from $DATA"
}

install_all() {
  local exec_path="${1:-}"
  if [ -z "$exec_path" ]; then
    exec_path="$(command -v sorgui || true)"
    [ -z "$exec_path" ] && [ -x "$HERE/.venv/bin/sorgui" ] && exec_path="$HERE/.venv/bin/sorgui"
  fi
  if [ -z "$exec_path" ] || [ ! -x "$exec_path" ]; then
    echo "sorgui: no sorgui executable found; install sorgui first (pip install .) or pass --exec PATH" >&2
    exit 1
  fi
  mkdir -p "$DATA/applications" "$DATA/metainfo" "$DATA/mime/packages" "$DATA/icons/hicolor/scalable/apps"
  # The launcher runs the executable by its absolute path: a venv's bin/ is rarely on the desktop's PATH.
  sed -e "s|^Exec=sorgui |Exec=\"$exec_path\" |" -e "s|^TryExec=sorgui$|TryExec=$exec_path|" \
    "$RES/$APP_ID.desktop" > "$DATA/applications/$APP_ID.desktop"
  install -m 644 "$RES/$APP_ID.metainfo.xml" "$DATA/metainfo/$APP_ID.metainfo.xml"
  install -m 644 "$RES/$APP_ID.mime.xml" "$DATA/mime/packages/$APP_ID.xml"
  install -m 644 "$RES/icons/$APP_ID.svg" "$DATA/icons/hicolor/scalable/apps/$APP_ID.svg"
  for size in $SIZES; do
    mkdir -p "$DATA/icons/hicolor/${size}x${size}/apps"
    install -m 644 "$RES/icons/hicolor/${size}x${size}/apps/$APP_ID.png" "$DATA/icons/hicolor/${size}x${size}/apps/$APP_ID.png"
  done
  refresh
  echo "sorgui: installed the launcher for $exec_path into $DATA"
}

case "${1:-}" in
  --uninstall) uninstall ;;
  --exec) install_all "${2:?--exec needs the path of the sorgui executable}" ;;
  "") install_all "" ;;
  -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//' ;;
  *) echo "sorgui: unknown option $1 (use --exec PATH, --uninstall or --help)" >&2; exit 2 ;;
esac
