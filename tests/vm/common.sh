# Sourced by the tests/vm scripts (POSIX sh). Picks the guest kernel: the
# newest Debian kernel that has an image in /boot, modules in /lib/modules and
# (preferably) headers in /lib/modules/<ver>/build for the out-of-tree gpio-sim. Deliberately NOT `uname -r`: the
# host kernel is not the one the VM boots. FT_VM_KVER overrides.

ft_vm_die() { echo "tests/vm: ERROR: $*" >&2; exit 1; }

ft_vm_kver() {
  if [ -n "${FT_VM_KVER:-}" ]; then echo "$FT_VM_KVER"; return 0; fi
  best='' with_headers=''
  for d in /lib/modules/*; do
    v=${d##*/}
    [ -f "/boot/vmlinuz-$v" ] && [ -f "$d/modules.dep" ] || continue
    best="$best $v"
    [ -f "$d/build/Makefile" ] && with_headers="$with_headers $v"
  done
  [ -n "$with_headers" ] && best=$with_headers  # gpio-sim needs the headers
  [ -n "$best" ] || return 1
  # shellcheck disable=SC2086
  printf '%s\n' $best | sort -V | tail -n 1
}

# ft_vm_need_kver: set KVER or die with a clear message.
ft_vm_need_kver() {
  KVER=$(ft_vm_kver) || ft_vm_die "no guest kernel: need /boot/vmlinuz-<ver> and /lib/modules/<ver>/modules.dep (install linux-image-amd64: tools/install-deps.sh vm)"
  [ -f "/boot/vmlinuz-$KVER" ] || ft_vm_die "/boot/vmlinuz-$KVER missing (install linux-image-amd64: tools/install-deps.sh vm)"
  [ -f "/lib/modules/$KVER/modules.dep" ] || ft_vm_die "/lib/modules/$KVER missing (install linux-image-amd64: tools/install-deps.sh vm)"
}

ft_vm_need_cmd() {
  for c in "$@"; do
    command -v "$c" >/dev/null 2>&1 || ft_vm_die "'$c' not found (tools/install-deps.sh vm installs it)"
  done
}
