#!/usr/bin/env bash
# Copies built programs and the shared libraries they need (all but the C library's own) into one
# folder, to run them on a machine that has a GPU driver but none of the Debian packages:
#   scripts/device_bundle.sh .device build/terracal build/crm_settle_probe
#   (there) LD_LIBRARY_PATH=.device .device/terracal ...
set -euo pipefail
dest=${1:?folder}; shift
mkdir -p "$dest"
for exe in "$@"; do
  cp -f "$exe" "$dest/"
  ldd "$exe" | awk '$3 ~ /^\// { print $3 }' | while read -r lib; do
    case "$(basename "$lib")" in
      libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*) ;;
      *) cp -fL "$lib" "$dest/" ;;
    esac
  done
done
for exe in "$@"; do strip "$dest/$(basename "$exe")"; done  # symbols stay here: the transfer is limited
du -sh "$dest"
