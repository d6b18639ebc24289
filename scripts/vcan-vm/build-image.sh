#!/usr/bin/env bash
# Builds (once) the kernel and initramfs of the vcan test VM into a cache directory.
# Usage: scripts/vcan-vm/build-image.sh CACHE_DIR
# Leaves CACHE_DIR/kernel (the vmlinux, or the bzImage) and CACHE_DIR/initramfs.cpio.gz. A second run with the same inputs
# (kernel package, init script, module list, busybox) does nothing: the host kernel has no CAN
# support, so the VM boots Debian's stock kernel, fetched as a .deb with `apt-get download`.
# Environment: WAVEBENCH_VM_KERNEL_DEB=/path/to/linux-image-*.deb uses that package instead.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
cache=${1:?usage: build-image.sh CACHE_DIR}
mkdir -p "$cache"
cache=$(cd "$cache" && pwd)

log() { echo "vcan-vm: $*" >&2; }
die() {
  echo "vcan-vm: ERROR: $*" >&2
  exit 1
}

# Modules the VM needs; their dependencies are resolved from the modules themselves, so a kernel
# that builds one of them in (modules.builtin) or adds a dependency still works.
required_modules=(virtio_pci 9pnet_virtio 9p overlay vcan can-raw)
# Loaded when present: other engineers' tests may use the broadcast manager, ISO-TP or the gateway.
optional_modules=(can-bcm can-isotp can-gw)

for tool in busybox cpio gzip dpkg-deb modinfo sha256sum; do
  command -v "$tool" >/dev/null || die "'$tool' not found; run: scripts/install-deps.sh --with-vm"
done
busybox_bin=$(command -v busybox)
if file -L "$busybox_bin" 2>/dev/null | grep -q 'dynamically linked'; then
  die "$busybox_bin is dynamically linked; the initramfs needs busybox-static"
fi

# --- kernel package -----------------------------------------------------------------------------
deb=${WAVEBENCH_VM_KERNEL_DEB:-}
if [[ -z "$deb" ]]; then
  shopt -s nullglob
  cached_debs=("$cache"/linux-image-*.deb)
  shopt -u nullglob
  if ((${#cached_debs[@]} > 0)); then
    deb=${cached_debs[-1]}
  else
    kernel_package() {
      apt-cache depends linux-image-amd64 2>/dev/null |
        awk '$1 == "Depends:" && $2 ~ /^linux-image-/ { print $2; exit }'
    }
    pkg=$(kernel_package) || true
    if [[ -z "$pkg" && $(id -u) -eq 0 ]]; then
      # Fresh CI images often ship without package lists.
      log "no package lists for linux-image-amd64; running apt-get update"
      apt-get update -qq >&2 || true
      pkg=$(kernel_package) || true
    fi
    [[ -n "$pkg" ]] || die "cannot resolve the kernel package: 'apt-cache depends linux-image-amd64'" \
      "named no linux-image-* dependency (run apt-get update, or set WAVEBENCH_VM_KERNEL_DEB)"
    log "downloading $pkg (once; cached in $cache)"
    (cd "$cache" && apt-get download -q -o APT::Sandbox::User=root "$pkg" >&2) ||
      die "'apt-get download $pkg' failed (needs a Debian mirror; or set WAVEBENCH_VM_KERNEL_DEB)"
    shopt -s nullglob
    cached_debs=("$cache"/linux-image-*.deb)
    shopt -u nullglob
    ((${#cached_debs[@]} > 0)) || die "apt-get download $pkg left no .deb in $cache"
    deb=${cached_debs[-1]}
  fi
fi
[[ -f "$deb" ]] || die "kernel package '$deb' does not exist"

stamp_inputs=$(
  {
    basename "$deb"
    stat -c %s "$deb"
    cat "$here/init.sh" "$here/build-image.sh"
    sha256sum <"$busybox_bin"
  } | sha256sum | cut -d' ' -f1
)
if [[ -f "$cache/kernel" && -f "$cache/initramfs.cpio.gz" && -f "$cache/image.stamp" &&
  "$(cat "$cache/image.stamp")" == "$stamp_inputs" ]]; then
  exit 0
fi

log "building kernel + initramfs from $(basename "$deb")"
# Left over by an interrupted build (the caller holds the cache lock, so none is in use).
find "$cache" -maxdepth 1 -type d -name 'image.*' -exec rm -rf {} +
work=$(mktemp -d "$cache/image.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM

# --- kernel and modules: extract only what is needed, not the whole 400 MB tree ------------------
listing=$(dpkg-deb --fsys-tarfile "$deb" | tar -t) || die "cannot read $deb"
vmlinuz=$(grep -E '^\./boot/vmlinuz-' <<<"$listing" | head -n1)
[[ -n "$vmlinuz" ]] || die "$deb holds no ./boot/vmlinuz-*"
kver=${vmlinuz#./boot/vmlinuz-}
builtin=$(grep -E "^\./lib/modules/$kver/modules\.builtin$" <<<"$listing" || true)
modpaths=$(grep -E "^\./lib/modules/$kver/kernel/.*\.ko(\.xz|\.zst|\.gz)?$" <<<"$listing")

# One pass over the (xz-compressed) package for the kernel and the directories the modules are
# expected in; a dependency elsewhere costs one more pass in extract_module.
members=("$vmlinuz" ${builtin:+"$builtin"})
for dir in drivers/virtio net/9p fs/9p fs/netfs fs/fscache fs/overlayfs net/can drivers/net/can; do
  if grep -q "^\./lib/modules/$kver/kernel/$dir/" <<<"$listing"; then
    members+=("./lib/modules/$kver/kernel/$dir/*")
  fi
done
dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$work" --wildcards "${members[@]}" ||
  die "cannot extract the kernel from $deb"

norm() { echo "${1//-/_}"; }
declare -A module_paths=() # normalised module name -> path in the package
while read -r p; do
  base=${p##*/}
  base=${base%%.ko*}
  module_paths[${base//-/_}]=$p
done <<<"$modpaths"
module_path() { echo "${module_paths[$(norm "$1")]:-}"; }
is_builtin() {
  [[ -n "$builtin" ]] || return 1
  grep -qE "/$(norm "$1" | sed 's/_/[-_]/g')\.ko$" "$work/$builtin"
}

declare -A state=() # module -> visiting|done
order=()
extract_module() { # extracts $2 (package path) as $work/mods/$1.ko, decompressing it
  local name=$1 p=$2
  mkdir -p "$work/mods"
  if [[ ! -f "$work/$p" ]]; then
    dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$work" "$p" || die "cannot extract $p"
  fi
  case "$p" in
    *.ko.xz) xz -dc "$work/$p" >"$work/mods/$name.ko" ;;
    *.ko.zst) zstd -qdc "$work/$p" >"$work/mods/$name.ko" ;;
    *.ko.gz) gzip -dc "$work/$p" >"$work/mods/$name.ko" ;;
    *) cp "$work/$p" "$work/mods/$name.ko" ;;
  esac
}
resolve() { # depth-first: dependencies land in $order before their dependents
  local name
  name=$(norm "$1")
  [[ "${state[$name]:-}" == "done" ]] && return 0
  [[ "${state[$name]:-}" == visiting ]] && die "module dependency cycle at $name"
  if is_builtin "$name"; then
    state[$name]="done"
    return 0
  fi
  local p
  p=$(module_path "$name")
  [[ -n "$p" ]] || return 1
  state[$name]=visiting
  extract_module "$name" "$p"
  local deps dep
  deps=$(modinfo -F depends "$work/mods/$name.ko" | tr , ' ')
  for dep in $deps; do
    resolve "$dep" || die "module $name depends on $dep, which $deb does not provide"
  done
  state[$name]="done"
  order+=("$name")
}
for m in "${required_modules[@]}"; do
  resolve "$m" || die "required module $m is neither built into nor shipped with $kver"
done
for m in "${optional_modules[@]}"; do
  resolve "$m" || log "optional module $m not available in $kver; skipped"
done

# --- boot image -----------------------------------------------------------------------------------
# Under TCG the bzImage's own decompressor costs 10-17 s per boot here. qemu boots the embedded
# ELF vmlinux directly through its PVH entry point, so unpack it once when the kernel has one.
has_pvh_entry() { # XEN_ELFNOTE_PHYS32_ENTRY (18)
  readelf -n "$1" 2>/dev/null | grep -q 'Xen.*(0x00000012)'
}
extract_vmlinux() { # $1: bzImage, $2: output; false when no payload unpacks to a PVH-capable ELF
  command -v readelf >/dev/null || return 1
  local magic tool off
  for magic in 'xz:\xfd7zXZ\x00' 'gzip:\x1f\x8b\x08' 'zstd:\x28\xb5\x2f\xfd'; do
    tool=${magic%%:*}
    command -v "$tool" >/dev/null || continue
    for off in $(LC_ALL=C grep -obUaP "${magic#*:}" "$1" 2>/dev/null | cut -d: -f1 | head -n 4); do
      case "$tool" in
        xz) tail -c +$((off + 1)) "$1" | xz -dc --single-stream >"$2" 2>/dev/null || true ;;
        gzip) tail -c +$((off + 1)) "$1" | gzip -dc >"$2" 2>/dev/null || true ;;
        zstd) tail -c +$((off + 1)) "$1" | zstd -qdc >"$2" 2>/dev/null || true ;;
      esac
      if has_pvh_entry "$2"; then
        return 0
      fi
    done
  done
  rm -f "$2"
  return 1
}
boot_kernel=$work/$vmlinuz
if extract_vmlinux "$work/$vmlinuz" "$work/vmlinux"; then
  boot_kernel=$work/vmlinux
  log "booting the unpacked vmlinux (PVH entry)"
else
  log "no PVH-capable vmlinux inside $(basename "$vmlinuz"); booting the bzImage"
fi

# --- initramfs ------------------------------------------------------------------------------------
root=$work/root
mkdir -p "$root"/{bin,dev,proc,sys,etc,lib/modules,newroot,share,lower,rw}
cp "$busybox_bin" "$root/bin/busybox"
cp "$here/init.sh" "$root/init"
chmod 755 "$root/init" "$root/bin/busybox"
for m in "${order[@]}"; do
  cp "$work/mods/$m.ko" "$root/lib/modules/$m.ko"
done
printf '%s\n' "${order[@]}" >"$root/etc/modules.order"
# The kernel opens /dev/console before running /init; without the node (mknod needs root) init
# reopens the console itself after mounting devtmpfs.
if [[ $(id -u) -eq 0 ]]; then
  mknod -m 600 "$root/dev/console" c 5 1
fi
(cd "$root" && find . -print0 | LC_ALL=C sort -z | cpio --null -o -H newc --quiet | gzip -9) \
  >"$work/initramfs.cpio.gz"

cp "$boot_kernel" "$cache/kernel.tmp"
mv "$work/initramfs.cpio.gz" "$cache/initramfs.cpio.gz"
mv "$cache/kernel.tmp" "$cache/kernel"
rm -f "$cache/vmlinuz" # the name before the unpacked vmlinux
echo "$kver" >"$cache/kernel.version"
echo "$stamp_inputs" >"$cache/image.stamp"
log "image ready: kernel $kver, modules: ${order[*]}"
