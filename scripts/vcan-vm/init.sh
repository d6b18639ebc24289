#!/bin/busybox sh
# /init of the vcan test VM (runs as PID 1 from the initramfs that build-image.sh packs).
# Loads the virtio/9p/overlay/CAN modules, mounts the host's root (share "hostroot", read-only,
# made writable by a throw-away overlay) with the build directory (share "buildshare") writable
# at its own path, creates vcan0/vcan1 and runs the job
# script run-vcan-tests.sh left in BUILD/vcan-vm/run/ inside a chroot of the host root, so the
# tests see the host's compilers, libraries, python3-can and can-utils at their usual paths.
# Results go back through the writable share: console.log is only for humans.
/bin/busybox --install -s /bin
export PATH=/bin

mount -t devtmpfs dev /dev 2>/dev/null
exec </dev/null >/dev/console 2>&1
mount -t proc proc /proc
mount -t sysfs sys /sys

say() { echo "vcan-vm: $*"; }
halt() {
  sync
  poweroff -f
  # Without ACPI power-off a reboot ends qemu too (-no-reboot).
  reboot -f
}
fail() {
  say "ERROR: $*"
  halt
}

for m in $(cat /etc/modules.order); do
  insmod "/lib/modules/$m.ko" || fail "insmod $m failed"
done

new=/newroot
p9opts=trans=virtio,version=9p2000.L,msize=524288
mount -t 9p -o "$p9opts,ro,cache=loose" hostroot /lower || fail "cannot mount the host root (9p)"
# The whole host root becomes writable through an overlay whose upper layer is a tmpfs that
# vanishes with the VM, so /tmp, /root, /var/tmp, /run and even the source tree can be written
# without hiding anything (a checkout or build directory may live under /tmp or /root).
mount -t tmpfs -o mode=0755,size=75% tmpfs /rw || fail "cannot mount the overlay's tmpfs"
mkdir -p /rw/upper /rw/work
mount -t overlay overlay -o lowerdir=/lower,upperdir=/rw/upper,workdir=/rw/work $new ||
  fail "cannot mount the overlay on the host root"
mount -t 9p -o "$p9opts" buildshare /share || fail "cannot mount the build directory (9p)"
run=/share/vcan-vm/run
[ -f $run/build-dir ] || fail "$run/build-dir missing: the host side did not prepare the run"
build=$(cat $run/build-dir)
[ -d "$new$build" ] || fail "build directory $build not visible in the host root"

mount -t proc proc $new/proc
mount -t sysfs sys $new/sys
mount -t devtmpfs dev $new/dev
mkdir -p $new/dev/pts $new/dev/shm
mount -t devpts devpts $new/dev/pts
mount -t tmpfs -o mode=1777 tmpfs $new/dev/shm
# Last, so that nothing is mounted over it: the build directory itself is the host's, writable.
mount -o bind /share "$new$build" || fail "cannot bind the build directory to $build"

in_root() {
  chroot $new /usr/bin/env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    HOME=/root TMPDIR=/tmp LANG=C.UTF-8 TERM=dumb PYTHONDONTWRITEBYTECODE=1 "$@"
}
ip link set lo up
# busybox ip cannot create vcan links; the host's iproute2 in the chroot can. MTU 72 makes
# vcan0 CAN FD capable; classic CAN sockets work on it unchanged.
for dev in vcan0 vcan1; do
  in_root ip link add dev $dev type vcan || fail "ip link add $dev type vcan failed"
  in_root ip link set $dev mtu 72 || fail "ip link set $dev mtu 72 failed"
  in_root ip link set $dev up || fail "ip link set $dev up failed"
done
[ -e /proc/net/can/rcvlist_all ] || fail "/proc/net/can missing after loading can.ko"

read -r up _ </proc/uptime
say "booted in ${up}s (guest clock); running $build/vcan-vm/run/job.sh"
rm -f $run/status
(
  in_root /bin/sh "$build/vcan-vm/run/job.sh"
  echo $? >$run/status
) 2>&1 | tee $run/ctest.log
read -r up _ </proc/uptime
say "job finished at ${up}s (guest clock), status $(cat $run/status 2>/dev/null || echo none)"

umount "$new$build" 2>/dev/null
umount $new/dev/pts $new/dev/shm $new/dev $new/proc $new/sys 2>/dev/null
umount /share 2>/dev/null
halt
