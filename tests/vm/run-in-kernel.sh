#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# run-in-kernel.sh: run a command inside Debian's real bookworm kernel under QEMU (TCG), with
# vcan interfaces and a gpio-sim GPIO chip set up, and return the command's exit status.
#
#   tests/vm/run-in-kernel.sh [--] CMD [ARGS...]
#   e.g. tests/vm/run-in-kernel.sh -- ctest --test-dir build -L kernel --output-on-failure
#
# Why: the development and CI machines' kernel has no CAN and no GPIO support; SocketCAN and
# libgpiod code is proven here, on Debian's own kernel (resolved from linux-image-amd64 at run
# time, never a hard-coded ABI). gpio-sim is built out of tree from the matching linux-source
# because Debian's kernel leaves CONFIG_GPIO_SIM off. Facts and timings: shared notes
# real-kernel-vm.md.
#
# The guest mounts the host's / read-only over virtio-9p and chroots into it, so CMD and its
# shared libraries come from the host as they are; the current directory is mounted read-write
# at the same path (build trees, XML reports land on the host). /tmp, /run, /var/tmp and /root
# are fresh tmpfs in the guest.
#
# Inside the guest (root): lo up; $HIL_VM_VCAN interfaces up (default "vcan0 vcan1"); one
# gpio-sim chip with $HIL_VM_GPIO_LINES lines (default 16) labelled hil-bank0, line names from
# $HIL_VM_GPIO_NAMES ("0:step 1:dir"); environment HIL_IN_VM=1, HIL_GPIOCHIP=gpiochipN,
# HIL_GPIOSIM_SYSFS=/sys/devices/platform/gpio-sim.0/gpiochipN (sim_gpioK/value reads an output,
# `echo pull-up > sim_gpioK/pull` drives an input).
#
# Knobs: HIL_VM_TIMEOUT seconds (default 600), HIL_VM_MEM MiB (1024), HIL_VM_SMP (2),
# HIL_VM_CACHE (default /var/cache/hilbridge-vm: kernel, modules and gpio-sim.ko are kept there
# between runs), HIL_VM_LOG (console log; default $HIL_VM_CACHE/console.log).
#
# Exit status: CMD's own status (0..123); 124 = timeout; 125 = the VM ended without reporting a
# result (kernel panic, setup failure: see the console log); 2 = usage or host setup error.
set -euo pipefail

[[ "${1:-}" == "--" ]] && shift
if [[ $# -lt 1 ]]; then
  echo "usage: $0 [--] CMD [ARGS...]" >&2
  exit 2
fi

cache=${HIL_VM_CACHE:-/var/cache/hilbridge-vm}
timeout_s=${HIL_VM_TIMEOUT:-600}
mem=${HIL_VM_MEM:-1024}
smp=${HIL_VM_SMP:-2}
vcans=${HIL_VM_VCAN:-vcan0 vcan1}
gpio_lines=${HIL_VM_GPIO_LINES:-16}
gpio_names=${HIL_VM_GPIO_NAMES:-}
log=${HIL_VM_LOG:-$cache/console.log}
workspace=$(pwd -P)
export DEBIAN_FRONTEND=noninteractive
say() { echo "run-in-kernel [${SECONDS}s]: $*" >&2; }
die() { say "$*"; exit 2; }
[[ $(id -u) -eq 0 ]] || die "needs root (apt-get, module build, QEMU's 9p export of /)"
mkdir -p "$cache"

# 1. Which kernel: Debian's current bookworm kernel, resolved through the metapackage.
resolve_kernel() {
  apt-get update -qq || true
  local pkg ver
  pkg=$(apt-cache depends linux-image-amd64 2>/dev/null | awk '$1=="Depends:" && $2 ~ /^linux-image-[0-9]/ {print $2; exit}')
  ver=$(apt-cache policy "$pkg" 2>/dev/null | awk '$1=="Candidate:" {print $2}')
  [[ -n "$pkg" && -n "$ver" && "$ver" != "(none)" ]] || die "cannot resolve linux-image-amd64 (apt lists?)"
  printf 'kpkg=%s\nkver=%s\nkabi=%s\n' "$pkg" "$ver" "${pkg#linux-image-}" > "$cache/kernel.env"
}
# Re-resolve once a day so a new security ABI is picked up; reuse the cache otherwise.
if [[ ! -s "$cache/kernel.env" ]] || [[ -n $(find "$cache/kernel.env" -mmin +1440 2>/dev/null) ]]; then
  resolve_kernel
fi
# shellcheck disable=SC1091
. "$cache/kernel.env"
kroot=$cache/$kabi

# 2. Host tools.
want=(qemu-system-x86 busybox-static cpio kmod xz-utils)
[[ -s "$kroot/gpio-sim.ko" ]] || want+=(gcc make "linux-headers-$kabi")
missing=()
for p in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'ok installed' || missing+=("$p")
done
if ((${#missing[@]})); then
  say "installing ${missing[*]}"
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null ||
    { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; } ||
    die "cannot install ${missing[*]}"
fi

# 3. Kernel image and modules, unpacked (not installed).
if [[ ! -s "$kroot/vmlinux" ]]; then
  say "fetching $kpkg=$kver"
  rm -rf "$kroot" && mkdir -p "$kroot/dl" && chmod 777 "$kroot/dl"
  (cd "$kroot/dl" && apt-get download -qq "$kpkg=$kver" 2>&1 | grep -v 'unsandboxed' || true)
  ls "$kroot"/dl/linux-image-*.deb >/dev/null 2>&1 || die "download of $kpkg=$kver failed"
  dpkg-deb -x "$kroot"/dl/linux-image-*.deb "$kroot"
  depmod -b "$kroot" "$kabi"
  # QEMU boots an uncompressed ELF vmlinux through PVH: no BIOS and no in-guest decompression.
  vz=$kroot/boot/vmlinuz-$kabi
  off=$(LC_ALL=C grep -abo $'\xfd7zXZ\x00' "$vz" | head -1 | cut -d: -f1 || true)
  if [[ -n "$off" ]]; then
    { tail -c +$((off + 1)) "$vz" | xz -dcq --single-stream > "$kroot/vmlinux.tmp"; } 2>/dev/null || true
  fi
  if [[ -s "$kroot/vmlinux.tmp" && "$(head -c 4 "$kroot/vmlinux.tmp" | tail -c 3)" == ELF ]]; then
    mv "$kroot/vmlinux.tmp" "$kroot/vmlinux"
  else
    rm -f "$kroot/vmlinux.tmp"
    cp "$vz" "$kroot/vmlinux"  # bzImage through SeaBIOS: slower, still works
  fi
  rm -rf "$kroot/dl"
fi

# 4. gpio-sim.ko from the matching kernel source (three files), built against the headers.
if [[ ! -s "$kroot/gpio-sim.ko" ]]; then
  say "building gpio-sim.ko for $kabi"
  b=$kroot/gpio-sim-build
  rm -rf "$b" && mkdir -p "$b/dl" && chmod 777 "$b/dl"
  srcpkg=linux-source-${kabi%%.0-*}  # 6.1.0-56-amd64 -> linux-source-6.1
  (cd "$b/dl" && apt-get download -qq "$srcpkg=$kver" 2>&1 | grep -v 'unsandboxed' || true)
  ls "$b"/dl/"$srcpkg"_*.deb >/dev/null 2>&1 || die "download of $srcpkg=$kver failed"
  dpkg-deb --fsys-tarfile "$b"/dl/"$srcpkg"_*.deb | tar -xO --wildcards './usr/src/linux-source-*.tar.xz' |
    xz -dc | tar -x -C "$b" --strip-components=1 --wildcards \
      '*/drivers/gpio/gpio-sim.c' '*/drivers/gpio/gpiolib.h' '*/kernel/irq/irq_sim.c'
  mv "$b/drivers/gpio/gpio-sim.c" "$b/gpio-sim-core.c"
  mv "$b/drivers/gpio/gpiolib.h" "$b/kernel/irq/irq_sim.c" "$b/"
  # irq_to_desc() is not exported to modules in 6.1: dispatch through generic_handle_irq().
  sed -i 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$b/irq_sim.c"
  ! grep -q 'irq_to_desc' "$b/irq_sim.c" || die "irq_sim.c patch did not apply to $kver"
  printf 'obj-m := gpio-sim.o\ngpio-sim-y := gpio-sim-core.o irq_sim.o\n' > "$b/Kbuild"
  make -s -C "/usr/src/linux-headers-$kabi" M="$b" modules >/dev/null || die "gpio-sim build failed"
  strip --strip-debug -o "$kroot/gpio-sim.ko" "$b/gpio-sim.ko"
  rm -rf "$b"
fi

# 5. initramfs: busybox, the modules in dependency order, and /init.
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
mkdir -p "$root"/{bin,proc,sys,dev,host,etc,lib/modules}
cp /bin/busybox "$root/bin/busybox"
for m in can-raw vcan configfs virtio_pci 9pnet_virtio 9p; do
  modprobe -d "$kroot" -S "$kabi" --show-depends "$m" | awk '$1=="insmod" {print $2}'
done | awk '!seen[$0]++' | while read -r ko; do
  name=$(basename "$ko")
  name=${name%.xz}
  case $ko in *.xz) xz -dc "$ko" ;; *) cat "$ko" ;; esac > "$root/lib/modules/$name"
  echo "/lib/modules/$name"
done > "$root/etc/modules.order"
cp "$kroot/gpio-sim.ko" "$root/lib/modules/"
echo /lib/modules/gpio-sim.ko >> "$root/etc/modules.order"
printf '%q ' "$@" > "$root/etc/cmd"
printf 'WS=%q\nVCANS=%q\nGPIO_LINES=%q\nGPIO_NAMES=%q\n' "$workspace" "$vcans" "$gpio_lines" "$gpio_names" > "$root/etc/vm.env"
cat > "$root/init" <<'INIT'
#!/bin/busybox sh
/bin/busybox --install -s /bin
export PATH=/bin
mount -t proc proc /proc; mount -t sysfs sys /sys; mount -t devtmpfs dev /dev
. /etc/vm.env
report() {  # marker on the console, then the status through isa-debug-exit (QEMU exits (rc<<1)|1)
  rc=$1; [ "$rc" -gt 123 ] && rc=123
  echo "HIL-VM-RESULT rc=$rc"
  printf "\\$(printf %o "$rc")" | dd of=/dev/port bs=1 seek=244 count=1 2>/dev/null
  poweroff -f
}
fail_setup() { echo "HIL-VM-SETUP-FAILED: $*"; poweroff -f; }
for ko in $(cat /etc/modules.order); do insmod "$ko" || fail_setup "insmod $ko"; done
ip link set lo up
for n in $VCANS; do ip link add dev "$n" type vcan && ip link set "$n" up || fail_setup "vcan $n"; done
H=/host
mount -t 9p -o trans=virtio,version=9p2000.L,ro,cache=loose,msize=512000 hostroot $H || fail_setup "9p /"
mount -t proc proc $H/proc; mount -t sysfs sys $H/sys; mount -t devtmpfs dev $H/dev
mkdir -p $H/dev/pts $H/dev/shm; mount -t devpts devpts $H/dev/pts; mount -t tmpfs tmpfs $H/dev/shm
mount -t configfs configfs $H/sys/kernel/config
for d in tmp run var/tmp root; do mount -t tmpfs tmpfs $H/$d; done
mkdir -p "$H$WS"; mount -t 9p -o trans=virtio,version=9p2000.L,rw,msize=512000 workspace "$H$WS" || fail_setup "9p workspace"
C=$H/sys/kernel/config/gpio-sim/hil
mkdir $C $C/bank0 && echo "$GPIO_LINES" > $C/bank0/num_lines && echo hil-bank0 > $C/bank0/label || fail_setup "gpio-sim bank"
for kv in $GPIO_NAMES; do mkdir $C/bank0/line${kv%%:*} && echo "${kv#*:}" > $C/bank0/line${kv%%:*}/name || fail_setup "gpio line $kv"; done
echo 1 > $C/live || fail_setup "gpio-sim live"
CHIP=$(cat $C/bank0/chip_name)
export HIL_IN_VM=1 HIL_GPIOCHIP=$CHIP HIL_GPIOSIM_SYSFS=/sys/devices/platform/$(cat $C/dev_name)/$CHIP
export HOME=/root TMPDIR=/tmp PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
echo "HIL-VM: kernel $(uname -r); $VCANS up; gpio-sim $HIL_GPIOCHIP with $GPIO_LINES lines; running: $(cat /etc/cmd)"
mkdir -p $H/run/hil-vm && cp /etc/cmd $H/run/hil-vm/cmd && [ -s $H/run/hil-vm/cmd ] || fail_setup "command"
# Through a pipe so tools see no tty (no colour codes); pipefail keeps the command's status.
chroot $H /bin/bash -o pipefail -c 'cd "$1" && { . /run/hil-vm/cmd; } 2>&1 | cat' bash "$WS"
report $?
INIT
chmod 755 "$root/init"
initrd=$(mktemp --suffix=.cpio)  # per run: several harness runs may share the cache
trap 'rm -rf "$root" "$initrd"' EXIT
(cd "$root" && find . -print0 | cpio --null -o -H newc --quiet -R 0:0) > "$initrd"

# 6. Boot under TCG (this machine's /dev/kvm is a nested PVM that cannot run a stock kernel usefully).
say "booting $kabi ($kver) under TCG; console log: $log"
set +e
timeout -k 5 "$timeout_s" qemu-system-x86_64 -accel tcg -M pc -m "$mem" -smp "$smp" \
  -nographic -monitor none -no-reboot -nic none \
  -kernel "$kroot/vmlinux" -initrd "$initrd" \
  -append "console=ttyS0 panic=-1 quiet" \
  -device isa-debug-exit,iobase=0xf4,iosize=0x04 \
  -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
  -virtfs "local,path=$workspace,mount_tag=workspace,security_model=none,multidevs=remap" \
  </dev/null 2>&1 | sed -u -e 's/\r$//' -e 's/\x1b\[[0-9;?]*[a-zA-Z]//g' -e 's/\x1bc//g' | tee "$log"
qrc=${PIPESTATUS[0]}
set -e
if [[ $qrc -eq 124 || $qrc -eq 137 ]]; then
  say "TIMEOUT: the VM did not finish within ${timeout_s}s (HIL_VM_TIMEOUT)"
  exit 124
fi
if (((qrc & 1) == 1)) && grep -aq "HIL-VM-RESULT rc=$((qrc >> 1))" "$log"; then
  rc=$((qrc >> 1))
  say "command exited with $rc (in the VM, ${SECONDS}s in all)"
  exit "$rc"
fi
say "the VM ended without reporting a result (qemu exit $qrc); see $log"
exit 125
